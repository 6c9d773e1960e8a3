"""``shaketable.assess``: assess an object and write its report (Markdown, figures, JSON).

The work is :func:`shaketable.studies.assess.run_assessment`; this module reads the object
file (:func:`shaketable.scenes.assess.load_assessment`) and writes ``report.md``,
``summary.json``, ``runs.csv`` and the figures of :mod:`shaketable.plots.assess`.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

from shaketable.core.constants import G
from shaketable.core.files import json_ready, prepare_output_folder, write_csv, write_text
from shaketable.studies.assess import (
    ASSUMPTIONS,
    Assessment,
    AssessmentResult,
    format_slip_mm,
    run_assessment,
    same_friction_note,
)

#: Figures written, in the report's order: (name, file, caption).
FIGURES = (
    ("mode-map", "mode-map.png", "The mode of the planar block per record and level over "
     "friction, beside Section 2.1's rule mu = B/H."),
    ("demands", "demands.png", "Free-standing: P(overturn), corner excursion and slip per "
     "level."),
    ("anchored", "anchored.png", "Anchored: base shear and uplift from the dynamics beside "
     "ASCE 7-16 Fp."),
    ("floor-spectra", "spectra.png", "The 10 %-damped spectrum where the object stands and "
     "ASCE 43-05's sliding coefficient c_s."),
)


def assess(spec: Assessment | str | os.PathLike, out: str | os.PathLike | None = None, *,
           figures: bool = True) -> AssessmentResult:
    """Assess an object: rock, slide or anchor.

    Parameters
    ----------
    spec : Assessment, or a path to an object file, or the name of a bundled object
        (``"lab-cabinet"``: ``experiments/assess/lab-cabinet.toml``), as ``shaketable assess``
        takes them.
    out : path, optional
        Folder for ``report.md``, ``summary.json``, ``runs.csv`` and the figures; nothing
        is written when omitted.
    figures : bool
        Draw the figures (with ``out``).

    Returns
    -------
    AssessmentResult
    """
    if not isinstance(spec, Assessment):
        from shaketable.scenes.assess import load_assessment
        from shaketable.scenes.catalog import resolve_object_path

        spec = load_assessment(resolve_object_path(spec))
    folder = None if out is None else prepare_output_folder(out)
    result = run_assessment(spec)
    if folder is not None:
        write_report(result, folder, figures=figures)
    return result


def summary(result: AssessmentResult) -> dict:
    """The JSON summary: the object, where, the demand, every part's numbers and the choice."""
    spec = result.spec
    fragility = {case: {key: value for key, value in entry.items() if key != "fit"}
                 for case, entry in result.fragility.items()}
    data = {
        "name": spec.name, "description": spec.description, "where": spec.where,
        "object": {"height [m]": spec.obj.block.height, "width [m]": spec.obj.block.width,
                   "B/H [-]": spec.obj.block.width / spec.obj.block.height,
                   "mass [kg]": spec.obj.mass, "friction [-]": list(spec.obj.frictions),
                   "cor [-]": spec.obj.cor, "cor source": spec.obj.cor_source},
        "demand": {"records": sorted(result.runs["record"].unique()),
                   "levels [g]": [v / G for v in spec.demand.levels],
                   "level names": list(spec.demand.level_names), "S_DS [g]": spec.demand.s_ds},
        "clearance [m]": spec.criteria.clearance, "acceptable P(overturn)":
            spec.criteria.acceptable, "let-it-slide friction [-]": spec.slide_friction,
        "free-standing": result.free.to_dict(orient="records"),
        "fragility": fragility, "risk": result.risk,
        "anchored": result.anchored.to_dict(orient="records"),
        "codes": result.codes, "recommendation": result.recommendation,
        "assumptions": list(ASSUMPTIONS),
    }
    return _clean(data)


def _clean(value):
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    return json_ready(value)


def _level(name: str, pga: float) -> str:
    value = f"{pga / G:.3g} g"
    return value if name == value else f"{name} = {value}"


def _mm(value: float) -> str:
    return "-" if math.isnan(value) else f"{value * 1000:.0f}"


def report_markdown(result: AssessmentResult, figure_files=()) -> str:
    """The report as Markdown (figures linked when their files are given)."""
    spec = result.spec
    block = spec.obj.block
    lines = [f"# Assessment: {spec.name}", ""]
    if spec.description:
        lines += [spec.description, ""]
    lines += [
        f"**Recommendation: {result.recommendation['choice']}.** Judged at the "
        f"{result.recommendation['level']} level:", ""]
    lines += [f"* {reason}" for reason in result.recommendation["reasons"]]
    lines += ["", "## The object and the demand", "",
              f"* {block.height:g} m high, {block.width:g} m wide in the direction of shaking "
              f"(B/H = {block.width / block.height:.3g}), {spec.obj.mass:.4g} kg; friction "
              f"{spec.obj.frictions[0]:g} to {spec.obj.frictions[1]:g}; COR "
              f"{spec.obj.cor:g} ({spec.obj.cor_source}).",
              f"* Where: {spec.where}.",
              f"* Records: {', '.join(sorted(result.runs['record'].unique()))}; levels (ground "
              "PGA): " + ", ".join(_level(n, v) for n, v in
                                   zip(spec.demand.level_names, spec.demand.levels)) + ".",
              ""]
    lines += ["## 1. Mode map", "",
              f"Section 2.1's rule: the object rocks if mu > B/H = "
              f"{block.width / block.height:.3g}, else slides.", "",
              "| level | mu [-] | rule | verdicts over the records |", "|---|---|---|---|"]
    for (level, mu), cells in result.runs.groupby(["level name", "mu [-]"], sort=False):
        if mu in spec.obj.frictions or mu == spec.slide_friction:
            counts = ", ".join(f"{v} {c}" for v, c in cells["verdict"].value_counts().items())
            lines.append(f"| {level} | {mu:.3g} | {cells['rule'].iloc[0]} | {counts} |")
    lines += ["", "## 2-3. Free-standing and let it slide", "",
              "| level | case | mu | P(overturn) [95 % interval] | excursion median / 84th "
              "[mm] | slip median / 84th [mm] |", "|---|---|---|---|---|---|"]
    for row in result.free.to_dict(orient="records"):
        lines.append(
            f"| {row['level name']} | {row['case']} | {row['mu [-]']:.3g} | "
            f"{row['overturned']}/{row['records']} = {row['P(overturn) [-]']:.2f} "
            f"[{row['P low [-]']:.2f}, {row['P high [-]']:.2f}] | "
            f"{_mm(row['excursion median [m]'])} / {_mm(row['excursion p84 [m]'])} | "
            f"{format_slip_mm(row['slip median [m]'])} / {format_slip_mm(row['slip p84 [m]'])} |")
    lines += ["", "Excursion and slip are over the records that did not overturn the object."]
    for k, name in enumerate(spec.demand.level_names):
        note = same_friction_note(result.free, k, block.width / block.height)
        if note:
            lines += ["", f"At the {name} level low and high friction agree: {note}."]
    if spec.criteria.clearance is not None:
        lines += ["", f"Clearance available: {_mm(spec.criteria.clearance)} mm."]
    lines += ["", "Fragility (lognormal in ground PGA, maximum likelihood):", ""]
    for case, entry in result.fragility.items():
        if entry.get("fit") is None:
            lines.append(f"* {case} friction: no fit ({entry['why not']}).")
        else:
            low, high = entry["median interval [g]"]
            interval = ("interval not identified" if math.isnan(low) or math.isnan(high)
                        else f"95 % {low:.3g}-{high:.3g} g")
            lines.append(f"* {case} friction: median {entry['median pga [g]']:.3g} g "
                         f"({interval}), beta {entry['beta [-]']:.3g}.")
    for case, entry in result.risk.items():
        span = entry["lambda over the median's interval [1/yr]"]
        spread = ("" if span is None else
                  f"; {span[0]:.3g} to {span[1]:.3g} /yr over the median's 95 % interval")
        lines.append(f"* {case} friction, site hazard: lambda = {entry['lambda [1/yr]']:.3g}"
                     f" /yr (with the tails at most {entry['lambda upper [1/yr]']:.3g}"
                     f"{spread}); P(overturn in {entry['years']:g} yr) = "
                     f"{entry['P(overturn in life) [-]']:.3g}.")
    lines += ["", "## 4. Anchored", "",
              "The dynamics' forces are elastic (a rigid object fixed to its floor, m a(t)); "
              "ASCE 7-16's Fp includes the reduction R_p / I_p (and anchors in concrete are "
              "designed with the further rules of Section 13.4.2).", "",
              "| level | PFA median / 84th [g] | base shear median / 84th [kN] | uplift median"
              " / 84th [kN] | ASCE 7-16 Fp [kN] | Fp uplift [kN] |",
              "|---|---|---|---|---|---|"]
    for row in result.anchored.to_dict(orient="records"):
        lines.append(
            f"| {row['level name']} | {row['pfa median [g]']:.3g} / {row['pfa p84 [g]']:.3g} |"
            f" {row['base shear median [N]'] / 1000:.3g} / {row['base shear p84 [N]'] / 1000:.3g}"
            f" | {row['uplift median [N]'] / 1000:.3g} / {row['uplift p84 [N]'] / 1000:.3g} | "
            f"{row['Fp [N]'] / 1000:.3g} ({row['Fp governs']}) | "
            f"{row['Fp uplift [N]'] / 1000:.3g} |")
    lines += ["", "## 5. The codes' checks", ""]
    for level, checks in result.codes.items():
        lines.append(f"**{level}**")
        lines.append("")
        for code, values in checks.items():
            text = "; ".join(f"{k} {_format(v)}" for k, v in values.items())
            lines.append(f"* {code}: {text}")
        lines.append("")
    lines += ["Not computed: the Circolare's demand side (the behaviour factor q, the floor "
              "spectrum with psi(Z) and gamma) and its displacement-based check; ASCE 43-05's "
              "sliding distance (Eq. A-3) and rocking procedure (Section A.2); ASCE 7-16's "
              "anchorage rules (Section 13.4). Each formula's source: docs/assess.md.", "",
              "## Figures", ""]
    for (name, file, caption) in FIGURES:
        if file in figure_files:
            lines += [f"![{name}]({file})", "", f"*{caption}*", ""]
    lines += ["## Assumptions and limits", ""]
    lines += [f"* {text}" for text in ASSUMPTIONS]
    lines += ["* few records give wide intervals on P(overturn): the 95 % intervals above say "
              "how wide", ""]
    return "\n".join(lines)


def _format(value) -> str:
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return "n/a" if math.isnan(value) else f"{value:.4g}"
    return str(value)


def write_report(result: AssessmentResult, folder: Path, *, figures: bool = True) -> list:
    """Write report.md, summary.json, runs.csv (and the figures) into ``folder``."""
    folder = Path(folder)
    written = []
    if figures:
        from shaketable.plots.base import save

        for name, file, _ in FIGURES:
            save(result.plot(name), folder / file)
            written.append(file)
    write_text(folder / "summary.json", json.dumps(summary(result), indent=1) + "\n")
    write_csv(folder / "runs.csv", result.runs)
    write_text(folder / "report.md", report_markdown(result, written))
    return written + ["summary.json", "runs.csv", "report.md"]
