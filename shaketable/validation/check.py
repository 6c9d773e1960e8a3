"""How good a calibration is on tests it was not tuned on: k-fold cross-validation with the
baselines, and a bootstrap check of the calibration's intervals.

Both reuse the candidates' verdicts on every test (computed once): a fold's calibration is
:func:`shaketable.validation.fit.fit` on the other folds' tests only, scored on the fold.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from shaketable.validation.fit import AXES, ensemble_probability, fit
from shaketable.validation.model import EquivalentBlock
from shaketable.validation.score import scores, threshold_fit


def folds(outcomes, k: int, seed: int) -> np.ndarray:
    """Fold number (0 to k-1) of each test: stratified by outcome, shuffled with ``seed``."""
    y = np.asarray(outcomes, dtype=int)
    if not 2 <= k <= y.size:
        raise ValueError(f"k must be from 2 to the number of tests ({y.size}), got {k}")
    rng = np.random.default_rng(seed)
    fold = np.empty(y.size, dtype=int)
    offset = 0
    for value in (0, 1):
        members = np.flatnonzero(y == value)
        rng.shuffle(members)
        fold[members] = (np.arange(members.size) + offset) % k
        offset += members.size
    return fold


def cross_validate(overturned: np.ndarray, outcomes, candidates: Sequence[EquivalentBlock],
                   pgv, *, k: int = 5, repeats: int = 5, seed: int = 0):
    """k-fold cross-validated scores of the calibration and of the baselines.

    Parameters
    ----------
    overturned : ndarray of bool, shape (candidates, tests, scales)
    outcomes : array_like of int
    candidates : sequence of EquivalentBlock
    pgv : array_like
        Peak table velocity of each test [m/s] (the PGV-threshold baseline).
    k, repeats, seed : int
        Folds, repetitions with other random folds, and the first repetition's seed.

    Returns
    -------
    pandas.DataFrame
        One row per (repeat, fold, model): ``model`` ("calibrated", "always not overturned",
        "PGV threshold"), ``n``, ``accuracy``, ``log_loss``, ``brier`` and the confusion
        counts.
    """
    import pandas as pd

    y = np.asarray(outcomes, dtype=int)
    pgv = np.asarray(pgv, dtype=float)
    rows = []
    for repeat in range(repeats):
        fold = folds(y, k, seed + repeat)
        for f in range(k):
            train, test = fold != f, fold == f
            calibration = fit(overturned[:, train], y[train], candidates, intervals=False)
            p = ensemble_probability(calibration, candidates, overturned[:, test])
            threshold = threshold_fit(pgv[train], y[train])
            base_rate = float(np.clip(y[train].mean(), 1e-3, 1 - 1e-3))
            for model, probability in (
                    ("calibrated", p),
                    ("always not overturned", np.full(test.sum(), min(base_rate, 0.499))),
                    ("PGV threshold", np.where(pgv[test] >= threshold, 1.0, 0.0))):
                rows.append({"repeat": repeat, "fold": f, "model": model,
                             **scores(probability, y[test])})
    return pd.DataFrame(rows)


def summary(frame) -> "object":
    """Mean and standard deviation over folds of each model's accuracy, log loss, Brier."""
    return (frame.groupby("model")[["accuracy", "log_loss", "brier"]]
            .agg(["mean", "std"]))


def bootstrap_coverage(overturned: np.ndarray, outcomes, candidates: Sequence[EquivalentBlock],
                       intervals: dict, *, resamples: int = 200, seed: int = 0) -> dict:
    """Fraction of bootstrap refits whose best candidate lies in the calibration's sets.

    The tests are resampled with replacement ``resamples`` times; each resample is refitted
    (:func:`fit`) and each axis of its best candidate checked against ``intervals``
    (the profile-likelihood sets of the fit on all tests). A 95 % set should hold about 95 %
    of the refits (more at a coarse grid).

    Returns
    -------
    dict
        Axis -> fraction of refits inside [-].
    """
    y = np.asarray(outcomes, dtype=int)
    rng = np.random.default_rng(seed)
    inside = {axis: 0 for axis in AXES}
    for _ in range(resamples):
        rows = rng.integers(0, y.size, y.size)
        best = fit(overturned[:, rows], y[rows], candidates, intervals=False).best
        for axis in AXES:
            value = best.sigma if axis == "sigma" else getattr(best.block, axis)
            accepted = intervals[axis]
            if axis in ("cor", "sign"):
                inside[axis] += value in accepted
            else:
                inside[axis] += accepted[0] <= value <= accepted[1]
    return {axis: count / resamples for axis, count in inside.items()}
