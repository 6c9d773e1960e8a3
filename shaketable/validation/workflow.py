"""The three steps on folders: calibrate, predict, score (what ``shaketable validate`` runs)."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np

from shaketable.validation.fit import BAGS, Calibration, fit
from shaketable.validation.folder import TestFolder
from shaketable.validation.model import LOG_SCALES, CandidateGrid, verdicts
from shaketable.validation.score import fragility, reliability, scores

#: Format tag of a calibration file.
FORMAT = "shaketable-validation-calibration/1"


def calibrate_folder(folder: TestFolder, grid: CandidateGrid | None = None, *,
                     threads: int | None = None, cache=None, progress=None,
                     bags: int = BAGS, seed: int = 0) -> tuple[dict, np.ndarray, list]:
    """Calibrate an equivalent block for every specimen with outcomes in ``folder``.

    ``cache``: an ``.npz`` file of the candidates' verdicts: read when it holds the same
    candidates, tests and amplitude factors, else computed and written there (the
    simulations are the expensive part; the fits, cross-validation and bootstrap reuse them).
    ``progress``: called as ``progress(done, total)`` while the runs are simulated
    (:func:`~shaketable.validation.model.verdicts`). ``bags``, ``seed``: the ensemble
    (:func:`~shaketable.validation.fit.fit`; 0 bags: the likelihood-weighted one). Each
    calibration records the ids of the tests it was fitted on (:attr:`Calibration.tests`).

    Returns
    -------
    calibrations : dict
        Specimen -> :class:`Calibration`.
    overturned : ndarray of bool, shape (candidates, tests, scales)
        The candidates' verdicts (for cross-validation and the bootstrap).
    candidates : list of EquivalentBlock
    """
    grid = grid or CandidateGrid()
    candidates = grid.candidates()
    specimens = [name for name in folder.specimens if folder.has_outcomes(name)]
    if not specimens:
        raise ValueError(f"{folder.path / 'metadata.csv'}: no outcome column "
                         "('<specimen>_overturned'): nothing to calibrate on")
    overturned = _cached_verdicts(cache, candidates, folder, threads, progress)
    ids = tuple(str(test) for test in folder.tests)
    calibrations = {name: replace(fit(overturned, folder.outcomes(name), candidates, name,
                                      bags=bags, seed=seed), tests=ids)
                    for name in specimens}
    return calibrations, overturned, candidates


def _cached_verdicts(cache, candidates, folder: TestFolder, threads, progress) -> np.ndarray:
    from pathlib import Path

    key = json.dumps({"candidates": [candidate.to_dict() for candidate in candidates],
                      "tests": folder.tests, "log_scales": list(LOG_SCALES)})
    if cache is not None and Path(cache).is_file():
        with np.load(cache) as data:
            if str(data["key"]) == key:
                return data["overturned"]
    overturned, _ = verdicts(candidates, folder.motions(), threads=threads, progress=progress)
    if cache is not None:
        from shaketable.core.files import atomic_write

        def write(temporary):
            with open(temporary, "wb") as handle:
                np.savez_compressed(handle, overturned=overturned, key=np.array(key))

        atomic_write(cache, write)
    return overturned


def calibration_json(calibrations: dict, extra: dict | None = None) -> str:
    """The calibrations as the JSON text of a calibration file."""
    data = {"format": FORMAT,
            "specimens": {name: calibration.to_dict()
                          for name, calibration in calibrations.items()}}
    data.update(extra or {})
    return json.dumps(data, indent=2, default=_json_default)


def _json_default(value):
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, np.bool_):
        return bool(value)
    raise TypeError(f"not JSON-serialisable: {value!r}")


def read_calibration(path) -> dict:
    """Specimen -> :class:`Calibration` from a calibration file; ValueError naming the file."""
    from shaketable.core.files import read_utf8

    text = read_utf8(path, "calibration file")
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise ValueError(f"{path}, line {error.lineno}: not JSON ({error.msg})") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise ValueError(f"{path}: not a calibration file of shaketable validate (format "
                         f"{FORMAT!r} expected)")
    return {name: Calibration.from_dict(item, f"{path}: specimen {name!r}")
            for name, item in data["specimens"].items()}


def predict_folder(folder: TestFolder, calibrations: dict, *, threads: int | None = None):
    """Predicted verdicts of every test and specimen of ``folder`` (outcomes not needed).

    Returns
    -------
    pandas.DataFrame
        One row per test and specimen: ``test``, ``specimen``, ``p_overturn`` (the
        calibration's ensemble), ``predicted_overturned`` (P >= 0.5), ``best_overturned``
        (the maximum-likelihood block alone), ``fate`` of the best block ("overturns during
        the motion", "overturns after the motion", "stands"), ``t_overturn [s]`` and
        ``in_training`` (1 when the calibration was fitted on that test: an in-sample
        prediction; 0 when not; -1 when the calibration file does not record its tests).
    """
    import pandas as pd

    missing = [name for name in folder.specimens if name not in calibrations]
    specimens = [name for name in folder.specimens if name in calibrations]
    if not specimens:
        raise ValueError(f"the calibration has none of the folder's specimens "
                         f"({', '.join(folder.specimens)}); it has "
                         f"{', '.join(calibrations) or 'none'}")
    motions = folder.motions()
    durations = np.array([motion.duration for motion in motions])
    frames = []
    for name in specimens:
        calibration = calibrations[name]
        overturned, t_overturn = verdicts(calibration.blocks(), motions, threads=threads)
        p = calibration.probability(overturned)
        recorded = LOG_SCALES.index(0.0)
        best = overturned[0, :, recorded]
        best_time = t_overturn[0, :, recorded]
        fate = np.where(~best, "stands",
                        np.where(best_time <= durations + 1e-9, "overturns during the motion",
                                 "overturns after the motion"))
        frames.append(pd.DataFrame({
            "test": folder.metadata["test"].to_numpy(),  # type: ignore[index]
            "specimen": name, "p_overturn": p, "predicted_overturned": (p >= 0.5).astype(int),
            "best_overturned": best.astype(int), "fate": fate,
            "t_overturn [s]": best_time,
            "in_training": (np.isin(folder.tests, calibration.tests).astype(int)
                            if calibration.tests else -1)}))
    frame = pd.concat(frames, ignore_index=True)
    frame.attrs["missing"] = missing
    return frame


def read_predictions(path):
    """A predictions CSV (:func:`predict_folder`'s columns); ValueError naming the file."""
    import pandas as pd

    try:
        frame = pd.read_csv(path)
    except (OSError, pd.errors.ParserError, UnicodeDecodeError) as error:
        raise ValueError(f"{path}: cannot read the predictions ({error})") from None
    for column in ("test", "specimen", "p_overturn"):
        if column not in frame.columns:
            raise ValueError(f"{path}: no column {column!r}")
    p = frame["p_overturn"].to_numpy(dtype=float)
    bad = ~((p >= 0) & (p <= 1))
    if bad.any():
        row = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{path}, line {row + 2}: p_overturn must be in [0, 1], got {p[row]!r}")
    return frame


def score_folder(predictions, folder: TestFolder, *, pga_edges=None, ratio_edges=None) -> dict:
    """Scores of a predictions frame against the folder's measured outcomes.

    Returns
    -------
    dict
        ``specimens``: specimen -> :func:`scores`; ``all``: over both; ``in_sample`` and
        ``out_of_sample``: the same over the rows whose ``in_training`` is 1 (tests the
        calibration was fitted on) and 0 (absent when the predictions have no such column,
        or when a part is empty); ``reliability``,
        ``fragility_pga``, ``fragility_pgv_over_pga``: frames over all specimens (PGA in g,
        PGV/PGA in s); ``joined``: the predictions with the outcome, PGA and PGV.
    """
    import pandas as pd

    from shaketable.core.constants import G

    meta = folder.metadata
    table = pd.DataFrame({"test": meta["test"].astype(str),  # type: ignore[index]
                          "pga [g]": meta["pga [m/s^2]"].to_numpy() / G,  # type: ignore[index]
                          "pgv [m/s]": meta["pgv [m/s]"].to_numpy()})  # type: ignore[index]
    rows = []
    for name in folder.specimens:
        if not folder.has_outcomes(name):
            continue
        part = table.copy()
        part["specimen"] = name
        part["overturned"] = folder.outcomes(name)
        rows.append(part)
    if not rows:
        raise ValueError(f"{folder.path / 'metadata.csv'}: no outcome column to score against")
    measured = pd.concat(rows, ignore_index=True)
    predictions = predictions.assign(test=predictions["test"].astype(str))
    joined = predictions.merge(measured, on=["test", "specimen"], how="inner")
    if joined.empty:
        raise ValueError("no (test, specimen) of the predictions is in the folder")
    joined["pgv/pga [s]"] = joined["pgv [m/s]"] / (joined["pga [g]"] * G)
    result: dict = {"specimens": {}, "joined": joined}
    for name, part in joined.groupby("specimen"):
        result["specimens"][name] = scores(part["p_overturn"], part["overturned"],
                                           part.get("predicted_overturned"))
    result["all"] = scores(joined["p_overturn"], joined["overturned"],
                           joined.get("predicted_overturned"))
    if "in_training" in joined.columns:
        for key, flag in (("in_sample", 1), ("out_of_sample", 0)):
            part = joined[joined["in_training"].astype(int) == flag]
            if len(part):
                result[key] = {"specimens": {
                    name: scores(rows["p_overturn"], rows["overturned"],
                                 rows.get("predicted_overturned"))
                    for name, rows in part.groupby("specimen")},
                    "all": scores(part["p_overturn"], part["overturned"],
                                  part.get("predicted_overturned"))}
    result["unmatched"] = int(len(predictions) - len(joined))
    pga_edges = pga_edges if pga_edges is not None else np.geomspace(0.02, 6.0, 12)
    ratio_edges = ratio_edges if ratio_edges is not None else np.geomspace(0.02, 0.4, 8)
    result["reliability"] = reliability(joined["p_overturn"], joined["overturned"])
    result["fragility_pga"] = fragility(joined["p_overturn"], joined["overturned"],
                                        joined["pga [g]"], pga_edges)
    result["fragility_pgv_over_pga"] = fragility(joined["p_overturn"], joined["overturned"],
                                                 joined["pgv/pga [s]"], ratio_edges)
    return result


#: The unit of each axis of a calibration's intervals (:data:`~shaketable.validation.fit.AXES`).
AXIS_UNITS = {"alpha_weak": "rad", "alpha_strong": "rad", "h": "m", "half_width": "m",
              "cor": "-", "sign": "-", "sigma": "-"}


def axis_with_unit(axis: str) -> str:
    """``"half_width [m]"``: an interval's axis named with its unit."""
    unit = AXIS_UNITS.get(axis)
    return f"{axis} [{unit}]" if unit else axis


def describe_calibration(calibration: Calibration, label: str | None = None) -> str:
    """A few lines: the best block, its training accuracy and the 95 % sets (each axis with
    its unit); the specimen named ``label`` (by default the calibration's name)."""
    best = calibration.best
    lines = [f"{label or calibration.specimen}: {best.block.describe()}",
             f"  link: sigma {best.sigma:g} (of ln amplitude), epsilon {best.epsilon:g}; "
             f"log likelihood {calibration.log_likelihood:.2f} on {calibration.n} tests",
             f"  training accuracy of the ensemble ({len(calibration.members)} members, "
             f"in-sample) {calibration.accuracy:.3f}"]
    for axis, accepted in calibration.intervals.items():
        lines.append(f"  95 % profile-likelihood set of {axis_with_unit(axis)}: "
                     f"{format_set(accepted)}")
    return "\n".join(lines)


def format_set(values) -> str:
    """A set of an axis as text: numbers to 4 significant digits, names as they are."""
    return "[" + ", ".join(f"{value:.4g}" if isinstance(value, float) else str(value)
                           for value in values) + "]"


__all__ = ["calibrate_folder", "calibration_json", "describe_calibration", "format_set",
           "predict_folder", "read_calibration", "read_predictions", "score_folder"]


def predict_from_geometry(folder: TestFolder, geometry, *, sign: int = 1,
                          cor: float | str = "housner", threads: int | None = None):
    """Verdicts of every test and specimen from each specimen's measured geometry (its scan).

    ``geometry`` is the table of :func:`shaketable.validation.model.scan_block`; the block's
    +x side is tipped by a positive recorded acceleration when ``sign`` is +1 (by a negative
    one when -1: the orientation of a specimen on the table is often unknown, so try both).
    A deterministic model: ``p_overturn`` is its verdict, 0 or 1.

    Returns
    -------
    pandas.DataFrame
        :func:`predict_folder`'s columns.
    """
    import pandas as pd

    from shaketable.models.rocking.asymmetric import simulate_many_asymmetric
    from shaketable.models.rocking.layout import INFO_STATUS, INFO_T_OVERTURN, STATUS_OVERTURNED
    from shaketable.models.rocking.run import extended
    from shaketable.validation.model import FATE_PADDING, scan_block

    if sign not in (1, -1):
        raise ValueError(f"sign must be +1 or -1, got {sign!r}")
    motions = [extended(motion, motion.duration + FATE_PADDING) for motion in folder.motions()]
    durations = np.array([motion.duration for motion in folder.motions()])
    frames = []
    for name in folder.specimens:
        block = scan_block(geometry, name)
        cases = np.column_stack([np.zeros(len(motions), dtype=np.int64),
                                 np.arange(len(motions))])
        info = simulate_many_asymmetric([block], motions, cases, [cor] * len(motions),
                                        scales=np.full(len(motions), float(sign)),
                                        threads=threads)
        overturned = info[:, INFO_STATUS] == STATUS_OVERTURNED
        when = info[:, INFO_T_OVERTURN]
        fate = np.where(~overturned, "stands",
                        np.where(when <= durations + 1e-9, "overturns during the motion",
                                 "overturns after the motion"))
        frames.append(pd.DataFrame({
            "test": folder.metadata["test"].to_numpy(),  # type: ignore[index]
            "specimen": name, "p_overturn": overturned.astype(float),
            "predicted_overturned": overturned.astype(int),
            "best_overturned": overturned.astype(int), "fate": fate, "t_overturn [s]": when,
            "in_training": 0}))
    return pd.concat(frames, ignore_index=True)
