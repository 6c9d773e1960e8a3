"""The "validation" section of ``shaketable reproduce --all``: the measured granite-rock tests.

A cheap version of ``docs/validation.md``'s calibration, run when the folder of measured
tests is present (it is GPL-3.0 and never copied into the project) and skipped with one
line saying why and how to give it otherwise. The folder is the one named by the caller,
else the ``SHAKETABLE_PBR`` environment variable, else, when the package runs from a source
checkout (not an installed copy), ``../shared/data/pbr`` beside that checkout.

What it runs: the scan-based block (the rocks' geometry as measured), and a coarse
calibration (symmetric blocks, :data:`SECTION_GRID`: 13 block angles at one height and one
COR) scored by 5-fold cross-validation beside the baselines (always "not overturned", a
PGV threshold fitted on the training folds), with the out-of-fold reliability and
fragility figures. The full calibration (asymmetric blocks, heights, CORs, the sign of
the table axis, bootstrap intervals) is ``shaketable validate calibrate``'s.
"""

from __future__ import annotations

import os
from pathlib import Path

from shaketable.validation.model import CandidateGrid

#: The coarse grid of the section: symmetric blocks at the scan's centroid height.
SECTION_GRID = CandidateGrid(alphas=(0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1, 0.11, 0.12,
                                     0.13, 0.14, 0.16, 0.19),
                             ratios=(1.0,), heights=(0.3,), cors=(0.9,))

#: Cross-validation of the section: folds and repetitions.
SECTION_FOLDS, SECTION_REPEATS = 5, 3


def source_checkout(package: str | os.PathLike[str] | None = None) -> Path | None:
    """The source checkout the package runs from (the folder holding ``pyproject.toml``
    beside the ``shaketable`` package folder ``package``); None for an installed copy
    (in site-packages nothing beside the package is the project's)."""
    folder = Path(package) if package is not None else Path(__file__).resolve().parents[1]
    root = folder.parent
    return root if (root / "pyproject.toml").is_file() else None


def data_folder(data: str | os.PathLike[str] | None = None, *,
                package: str | os.PathLike[str] | None = None) -> Path | None:
    """The folder of measured tests: ``data``, else ``$SHAKETABLE_PBR``, else
    ``<checkout>/../shared/data/pbr`` when the package (folder ``package``, by default
    this one) runs from a source checkout (:func:`source_checkout`); else None."""
    if data is not None:
        return Path(data)
    if os.environ.get("SHAKETABLE_PBR"):
        return Path(os.environ["SHAKETABLE_PBR"])
    checkout = source_checkout(package)
    return None if checkout is None else checkout.parent / "shared" / "data" / "pbr"


#: How the section is given its folder, said when it is skipped.
HOW_TO_GIVE = ("give the folder holding metadata.csv with `shaketable reproduce --all "
               "--validation-data DIR`, or set the environment variable SHAKETABLE_PBR=DIR; "
               "see docs/validation.md")


def reproduce_section(out: str | os.PathLike[str], data: str | os.PathLike[str] | None = None,
                      *, threads: int | None = None) -> str:
    """Run the section into ``out`` (its figures); its Markdown.

    Parameters
    ----------
    out : path
        The section's folder (``<reproduce out>/validation``); created if absent.
    data : path, optional
        The folder of measured tests (:func:`data_folder`).
    threads : int, optional
        Threads of the simulations.

    Returns
    -------
    str
        The section (a heading and one line saying why when the folder is absent).
    """
    folder_path = data_folder(data)
    heading = "## Validation against measured shake-table tests — `validation`"
    if folder_path is None:
        return (f"{heading}\n\nSkipped: no folder of measured tests given (none was named, "
                f"SHAKETABLE_PBR is not set, and an installed package has no project folder "
                f"beside it): {HOW_TO_GIVE}.\n")
    if not (folder_path / "metadata.csv").is_file():
        return (f"{heading}\n\nSkipped: no folder of measured tests at {folder_path} (no "
                f"metadata.csv there): {HOW_TO_GIVE}.\n")
    return heading + "\n\n" + _run(folder_path, Path(out), threads)


def _run(path: Path, out: Path, threads: int | None) -> str:
    import pandas as pd

    from shaketable.core.files import prepare_output_folder
    from shaketable.plots.base import save
    from shaketable.plots.validation import fragility_figure, reliability_figure
    from shaketable.validation.check import cross_validate, out_of_fold
    from shaketable.validation.fit import BAGS
    from shaketable.validation.folder import read_folder, specimen_labels
    from shaketable.validation.workflow import (
        calibrate_folder,
        predict_from_geometry,
        score_folder,
    )

    out = prepare_output_folder(out, "out")
    folder = read_folder(path)
    labels = specimen_labels(folder)
    lines = [f"Measured tests read from `{path}` ({len(folder.tests)} tests, specimens "
             f"{', '.join(labels.values())}; GPL-3.0, read in place). A coarse version of "
             "docs/validation.md: symmetric blocks only (13 block angles, h 0.3 m, COR 0.9).",
             ""]
    geometry = path / "geometry.csv"
    if geometry.is_file():
        scan = score_folder(predict_from_geometry(folder, pd.read_csv(geometry),
                                                  threads=threads), folder)
        lines.append("* The block of the scans (Housner's COR per pivot, sign +1): accuracy "
                     + ", ".join(f"{labels.get(name, name)} {values['accuracy']:.3f}"
                                 for name, values in scan["specimens"].items())
                     + " (always 'not overturned': "
                     + ", ".join(f"{labels.get(name, name)} "
                                 f"{1 - folder.outcomes(name).mean():.3f}"
                                 for name in scan["specimens"]) + ").")
    calibrations, overturned, candidates = calibrate_folder(folder, SECTION_GRID,
                                                            threads=threads)
    pgv = folder.metadata["pgv [m/s]"].to_numpy()  # type: ignore[index]
    rows = []
    held_out = []
    for name, calibration in calibrations.items():
        block = calibration.best.block
        lines.append(f"* {labels.get(name, name)}, the most likely block: alpha {block.alpha_weak:g} rad "
                     f"(effective half-width h tan(alpha) "
                     f"{1000 * block.effective_half_width():.0f} mm), link sigma "
                     f"{calibration.best.sigma:g}; training accuracy {calibration.accuracy:.3f}.")
        outcomes = folder.outcomes(name)
        frame = cross_validate(overturned, outcomes, candidates, pgv, k=SECTION_FOLDS,
                               repeats=SECTION_REPEATS, bags=BAGS)
        for model, part in frame.groupby("model"):
            rows.append(f"| {labels.get(name, name)} | {model} | {part['accuracy'].mean():.3f} ± "
                        f"{part['accuracy'].std(ddof=1):.3f} | {part['log_loss'].mean():.3f} |")
        p = out_of_fold(overturned, outcomes, candidates, k=SECTION_FOLDS, bags=BAGS)
        held_out.append(pd.DataFrame({"test": folder.tests, "specimen": name,
                                      "p_overturn": p}))
    lines += ["", f"{SECTION_FOLDS}-fold cross-validation ({SECTION_REPEATS} repetitions; "
              "mean ± standard deviation over the folds; a fold's calibration never sees "
              "its tests):", "", "| specimen | model | accuracy | log loss |", "|---|---|---|---|",
              *rows]
    scored = score_folder(pd.concat(held_out, ignore_index=True), folder)
    save(reliability_figure(scored["reliability"], title="out-of-fold reliability"),
         out / "reliability.png")
    save(fragility_figure(scored["fragility_pga"], "PGA [g]", log=True,
                          title="out-of-fold fragility"), out / "fragility_pga.png")
    within = int(scored["reliability"]["within_2sd"].sum())
    lines += ["", f"Out-of-fold accuracy over both specimens {scored['all']['accuracy']:.3f}; "
              f"reliability: {within} of {len(scored['reliability'])} probability bins hold "
              "the measured fraction within two binomial standard deviations of the predicted "
              "(or 1/n).",
              "", "![reliability](validation/reliability.png)",
              "![fragility](validation/fragility_pga.png)"]
    return "\n".join(lines) + "\n"

