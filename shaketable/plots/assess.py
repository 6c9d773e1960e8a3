"""Figures of an assessment (:mod:`shaketable.studies.assess`)."""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G
from shaketable.plots.base import place_legend, pyplot
from shaketable.plots.mode_map import VERDICT_COLOURS
from shaketable.studies.mode_map import VERDICT_ORDER

#: The figures :func:`assessment_figure` draws.
FIGURES = ("mode-map", "demands", "anchored", "floor-spectra")

_CASE_COLOURS = {"low": "tab:blue", "high": "tab:red", "let it slide": "tab:green"}


def assessment_figure(result, which: str = "mode-map", fig=None):
    """One figure of an :class:`~shaketable.studies.assess.AssessmentResult`.

    Parameters
    ----------
    result : AssessmentResult
    which : {"mode-map", "demands", "anchored", "floor-spectra"}
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    drawers = {"mode-map": _mode_map, "demands": _demands, "anchored": _anchored,
               "floor-spectra": _spectra}
    if which not in drawers:
        raise ValueError(f"which must be one of {', '.join(FIGURES)}, got {which!r}")
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(10.0, 4.6), layout="constrained")
    drawers[which](result, fig)
    return fig


def _mode_map(result, fig):
    """Verdict per (level, record) row and friction column; the rule mu = B/H."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    runs = result.runs
    spec = result.spec
    mus = np.sort(runs["mu [-]"].unique())
    order = list(dict.fromkeys(runs["record"]))
    rows = sorted(dict.fromkeys(zip(runs["level"], runs["record"])),
                  key=lambda row: (row[0], order.index(row[1])))
    codes = np.full((len(rows), len(mus)), np.nan)
    for row in runs.itertuples(index=False):
        r = rows.index((row.level, row.record))
        codes[r, np.searchsorted(mus, row[runs.columns.get_loc("mu [-]")])] = \
            VERDICT_ORDER.index(row.verdict)
    axis = fig.subplots()
    cmap = ListedColormap([VERDICT_COLOURS[name] for name in VERDICT_ORDER])
    edges = np.concatenate([[mus[0] - 0.025], 0.5 * (mus[1:] + mus[:-1]), [mus[-1] + 0.025]])
    axis.pcolormesh(edges, np.arange(len(rows) + 1), codes, cmap=cmap, vmin=-0.5,
                    vmax=len(VERDICT_ORDER) - 0.5, edgecolors="white", linewidth=0.4)
    ratio = spec.obj.block.width / spec.obj.block.height
    axis.axvline(ratio, color="black", linestyle="--", linewidth=1.3)
    for mu in spec.obj.frictions:
        axis.axvline(mu, color="black", linewidth=1.3, linestyle=":")
    axis.axvline(spec.slide_friction, color="tab:green", linewidth=1.6)
    labels = [f"{spec.demand.level_names[k]}: {name}" for k, name in rows]
    axis.set_yticks(np.arange(len(rows)) + 0.5, labels, fontsize=7)
    for k in range(1, len(spec.demand.levels)):
        axis.axhline(sum(1 for level, _ in rows if level < k), color="black", linewidth=0.8)
    axis.invert_yaxis()
    axis.set_xlabel("friction μs = μd [-]")
    axis.set_title(f"{spec.name} {spec.where}\nthe planar block's mode; dashed: Section "
                   f"2.1's μ = B/H = {ratio:.3g}; dotted: the object's friction range; "
                   f"green: let it slide", fontsize=9)
    handles = [Patch(facecolor=VERDICT_COLOURS[name], edgecolor="grey", label=name)
               for name in VERDICT_ORDER if name in set(runs["verdict"])]
    fig.legend(handles=handles, loc="outside right center", fontsize=8)


def _demands(result, fig):
    """P(overturn), corner excursion and slip per level for the three frictions."""
    free = result.free
    spec = result.spec
    axes = fig.subplots(1, 3)
    levels = free["ground pga [g]"].to_numpy()
    shift = 0.012 * max(levels.max() - levels.min(), 0.1 * levels.max())
    for index, (case, cells) in enumerate(free.groupby("case", sort=False)):
        colour = _CASE_COLOURS[case]
        x = cells["ground pga [g]"].to_numpy()
        label = f"{case} (μ = {cells['mu [-]'].iloc[0]:.3g})"
        p = cells["P(overturn) [-]"].to_numpy()
        # the three cases side by side (a small shift in x) so that none hides another
        axes[0].errorbar(x + (index - 1) * shift, p,
                         yerr=[p - cells["P low [-]"], cells["P high [-]"] - p],
                         color=colour, marker="o", linestyle="none", capsize=3, label=label)
        for axis, what in ((axes[1], "excursion"), (axes[2], "slip")):
            axis.plot(x, cells[f"{what} median [m]"] * 1000, "o-", color=colour, label=label)
            axis.plot(x, cells[f"{what} p84 [m]"] * 1000, "s--", color=colour,
                      markerfacecolor="none")
            # the range over records as a bar at each level (shifted as on the left): a
            # band between levels drew a range nobody computed (a wedge from a record that
            # stayed at one level to the next level's)
            axis.vlines(x + 2.5 * (index - 1) * shift, cells[f"{what} min [m]"] * 1000,
                        cells[f"{what} max [m]"] * 1000, color=colour, alpha=0.3,
                        linewidth=4)
        fit = result.fragility.get(case, {}).get("fit")
        if fit is not None:
            grid = np.linspace(0.0, x.max() * 1.1, 100)[1:]
            axes[0].plot(grid, fit.probability(grid * G), color=colour, linewidth=0.8,
                         alpha=0.7)
    axes[0].axhline(spec.criteria.acceptable, color="grey", linestyle=":")
    axes[0].set_ylim(-0.03, 1.03)
    fitted = any(entry.get("fit") is not None for entry in result.fragility.values())
    axes[0].set_ylabel("P(overturn) [-] (Wilson 95 %" + ("; line: lognormal fit)" if fitted
                                                          else ")"))
    axes[1].set_ylabel("peak corner excursion [mm]\n(o median, □ 84th, bar: range over records)")
    axes[2].set_ylabel("peak slip [mm] (bar: range over records)")
    if spec.criteria.clearance is not None:
        axes[1].axhline(spec.criteria.clearance * 1000, color="black", linestyle=":",
                        label="clearance")
    for axis in axes:
        axis.set_xlabel("ground PGA [g]")
    for axis in axes[1:]:   # linear: a record the object rides out without moving is a 0
        axis.set_ylim(bottom=0.0)
    place_legend(axes[1], outside="below", fontsize=7)
    # two lines: on one the title ran from edge to edge of the figure
    fig.suptitle(f"{spec.name} {spec.where}:\nfree-standing demands "
                 f"({len(result.runs['record'].unique())} records; excursion and slip of "
                 f"the records it survives)", fontsize=9)


def _anchored(result, fig):
    """Base shear and uplift of the anchored object beside ASCE 7-16 Fp."""
    frame = result.anchored
    x = frame["ground pga [g]"]
    axes = fig.subplots(1, 2)
    axes[0].plot(x, frame["base shear median [N]"] / 1000, "o-", label="dynamics, median")
    axes[0].plot(x, frame["base shear p84 [N]"] / 1000, "s--", label="dynamics, 84th")
    axes[0].plot(x, frame["Fp [N]"] / 1000, "k^-", label="ASCE 7-16 Fp")
    axes[0].set_ylabel("base shear [kN]")
    axes[1].plot(x, frame["uplift median [N]"] / 1000, "o-", label="dynamics, median")
    axes[1].plot(x, frame["uplift p84 [N]"] / 1000, "s--", label="dynamics, 84th")
    axes[1].plot(x, frame["Fp uplift [N]"] / 1000, "k^-",
                 label="Fp with (0.9 - 0.2 S_DS) D")
    axes[1].set_ylabel("uplift on one side [kN]")
    for axis in axes:
        axis.set_xlabel("ground PGA [g]")
        axis.set_ylim(bottom=0.0)
        axis.legend(fontsize=8)
    fig.suptitle(f"{result.spec.name} anchored (rigid, fixed) {result.spec.where}", fontsize=10)


def _spectra(result, fig):
    """The median 10 %-damped spectrum where the object stands, and ASCE 43's c_s."""
    axis = fig.subplots()
    levels = []
    for k, (frequencies, spectrum) in result.spectra.items():
        name = result.spec.demand.level_names[k]
        line, = axis.plot(frequencies, spectrum / G, label=f"{name}: median spectrum")
        code = result.codes[name]["ASCE 43-05 A.1 (sliding)"]
        levels.append((name, line.get_color(), code["c_s [g]"], code["mu_e [-]"],
                       float(np.nanmax(spectrum / G))))
    values = [c_s for _, _, c_s, _, _ in levels]
    if max(values) - min(values) <= 0.03 * max(top for *_, top in levels):
        # lines closer than a line's width: one black line, one entry naming every level
        for index, c_s in enumerate(values):
            axis.axhline(c_s, color="black", linestyle=":", label=None if index else
                         "c_s = 2 μe g: " + ", ".join(f"{name} {c_s:.2f} g (μe {mu_e:.3g})"
                                                      for name, _, c_s, mu_e, _ in levels))
    else:
        for name, colour, c_s, mu_e, _ in levels:
            axis.axhline(c_s, color=colour, linestyle=":",
                         label=f"{name}: c_s = 2 μe g = {c_s:.2f} g (μe {mu_e:.3g})")
    axis.set_xscale("log")
    axis.set_xlabel("frequency [Hz]")
    axis.set_ylabel("spectral acceleration, 10 % damping [g]")
    mu = result.codes[result.spec.demand.level_names[0]]["ASCE 43-05 A.1 (sliding)"]["mu [-]"]
    axis.legend(fontsize=8, title=f"ASCE 43-05 Eq. A-1: μe = μ (1 − 0.4 A_v/g), μ = {mu:.3g} "
                "(the low friction),\nA_v the median peak vertical acceleration",
                title_fontsize=7.5)
    axis.set_title(f"{result.spec.name} {result.spec.where}: where the object stands",
                   fontsize=10)
