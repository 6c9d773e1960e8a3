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
                   pgv, *, k: int = 5, repeats: int = 5, seed: int = 0, bags: int = 0,
                   progress=None):
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
    bags : int
        The calibration's ensemble (:func:`~shaketable.validation.fit.fit`), made in each
        fold from its training tests only.
    progress : callable, optional
        Called as ``progress(done, total)`` (folds) after each fold.

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
            calibration = fit(overturned[:, train], y[train], candidates, intervals=False,
                              bags=bags, seed=seed)
            p = ensemble_probability(calibration, candidates, overturned[:, test])
            threshold = threshold_fit(pgv[train], y[train])
            base_rate = float(np.clip(y[train].mean(), 1e-3, 1 - 1e-3))
            for model, probability in (
                    ("calibrated", p),
                    ("always not overturned", np.full(test.sum(), min(base_rate, 0.499))),
                    ("PGV threshold", np.where(pgv[test] >= threshold, 1.0, 0.0))):
                rows.append({"repeat": repeat, "fold": f, "model": model,
                             **scores(probability, y[test])})
            if progress is not None:
                progress(repeat * k + f + 1, repeats * k)
    return pd.DataFrame(rows)


def summary(frame) -> "object":
    """Mean and standard deviation over folds of each model's accuracy, log loss, Brier."""
    return (frame.groupby("model")[["accuracy", "log_loss", "brier"]]
            .agg(["mean", "std"]))


def bootstrap_refits(overturned: np.ndarray, outcomes, candidates: Sequence[EquivalentBlock],
                     *, resamples: int = 200, seed: int = 0, progress=None) -> list:
    """The best member of refits on ``resamples`` bootstrap resamples of the tests.

    The tests are drawn with replacement; each resample is refitted (:func:`fit`).
    ``progress(done, total)`` is called after each refit.

    Returns
    -------
    list of Member
    """
    y = np.asarray(outcomes, dtype=int)
    rng = np.random.default_rng(seed)
    refits = []
    for done in range(resamples):
        rows = rng.integers(0, y.size, y.size)
        refits.append(fit(overturned[:, rows], y[rows], candidates, intervals=False).best)
        if progress is not None:
            progress(done + 1, resamples)
    return refits


def _value(member, axis: str):
    return member.sigma if axis == "sigma" else getattr(member.block, axis)


def bootstrap_sets(refits: list, level: float = 0.95) -> dict:
    """Percentile sets of the refits: ``[low, high]`` holding ``level`` of them for numbers,
    the values at least (1 - level) / 2 of them chose for the COR and the sign."""
    tail = 0.5 * (1.0 - level)
    sets: dict = {}
    for axis in AXES:
        values = [_value(member, axis) for member in refits]
        if axis in ("cor", "sign"):
            counts = {value: values.count(value) for value in dict.fromkeys(values)}
            sets[axis] = [value for value, count in counts.items()
                          if count >= tail * len(values)]
        else:
            numbers = np.asarray(values, dtype=float)
            sets[axis] = [float(np.quantile(numbers, tail, method="inverted_cdf")),
                          float(np.quantile(numbers, 1.0 - tail, method="inverted_cdf"))]
    return sets


def coverage(refits: list, sets: dict) -> dict:
    """Fraction of the refits whose value lies in ``sets``, per axis [-].

    A 95 % set should hold about 95 % of independent refits (more at a coarse grid).
    """
    inside = {axis: 0 for axis in AXES}
    for member in refits:
        for axis in AXES:
            value = _value(member, axis)
            accepted = sets[axis]
            if axis in ("cor", "sign"):
                inside[axis] += value in accepted
            else:
                inside[axis] += accepted[0] <= value <= accepted[1]
    return {axis: count / len(refits) for axis, count in inside.items()}


def bootstrap_coverage(overturned: np.ndarray, outcomes, candidates: Sequence[EquivalentBlock],
                       intervals: dict, *, resamples: int = 200, seed: int = 0) -> dict:
    """Fraction of bootstrap refits whose best candidate lies in ``intervals``, per axis."""
    return coverage(bootstrap_refits(overturned, outcomes, candidates, resamples=resamples,
                                     seed=seed), intervals)


def out_of_fold(overturned: np.ndarray, outcomes, candidates: Sequence[EquivalentBlock], *,
                k: int = 5, seed: int = 0, bags: int = 0) -> np.ndarray:
    """P(overturn) of every test from the calibration on the other folds (never its own).

    The honest counterpart of a calibration's in-sample predictions: score it with
    :func:`shaketable.validation.score.scores`, or draw its reliability and fragility.
    """
    y = np.asarray(outcomes, dtype=int)
    fold = folds(y, k, seed)
    p = np.empty(y.size)
    for f in range(k):
        train, test = fold != f, fold == f
        calibration = fit(overturned[:, train], y[train], candidates, intervals=False,
                          bags=bags, seed=seed)
        p[test] = ensemble_probability(calibration, candidates, overturned[:, test])
    return p
