"""Scores of predicted verdicts against measured ones: accuracy, confusion, log loss, Brier,
reliability and fragility (measured against predicted P(overturn))."""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.ensemble import wilson_interval

#: Probabilities are clipped to [CLIP, 1 - CLIP] in the log loss (a model certain and wrong
#: would score infinity).
CLIP = 1e-6


def _checked(probability, outcomes) -> tuple[np.ndarray, np.ndarray]:
    p = np.asarray(probability, dtype=float)
    y = np.asarray(outcomes, dtype=int)
    if p.shape != y.shape:
        raise ValueError(f"probability has shape {p.shape}, outcomes {y.shape}")
    if p.size and (np.any(p < 0) | np.any(p > 1) | np.any(~np.isfinite(p))):
        raise ValueError("probability must be in [0, 1]")
    if p.size and not np.isin(y, (0, 1)).all():
        raise ValueError("outcomes must be 0 or 1")
    return p, y


def scores(probability, outcomes, predicted=None) -> dict:
    """Accuracy, confusion matrix, log loss and Brier score.

    Parameters
    ----------
    probability : array_like
        Predicted P(overturn) [-].
    outcomes : array_like of int
        Measured verdicts (1 overturned).
    predicted : array_like of bool, optional
        The predicted verdicts (default ``probability >= 0.5``).

    Returns
    -------
    dict
        ``n``, ``accuracy``, ``true_positive`` (predicted and measured overturned),
        ``false_positive``, ``true_negative``, ``false_negative``, ``log_loss`` [nats per
        test], ``brier``.
    """
    p, y = _checked(probability, outcomes)
    verdict = p >= 0.5 if predicted is None else np.asarray(predicted, dtype=bool)
    clipped = np.clip(p, CLIP, 1 - CLIP)
    n = int(y.size)
    return {
        "n": n,
        "accuracy": float(np.mean(verdict == y.astype(bool))) if n else math.nan,
        "true_positive": int(np.sum(verdict & (y == 1))),
        "false_positive": int(np.sum(verdict & (y == 0))),
        "true_negative": int(np.sum(~verdict & (y == 0))),
        "false_negative": int(np.sum(~verdict & (y == 1))),
        "log_loss": float(-np.mean(y * np.log(clipped) + (1 - y) * np.log1p(-clipped)))
        if n else math.nan,
        "brier": float(np.mean((p - y) ** 2)) if n else math.nan,
    }


def reliability(probability, outcomes, edges=(0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0)):
    """Predicted fraction against measured in bins of predicted probability.

    Returns
    -------
    pandas.DataFrame
        One row per non-empty bin: ``low``, ``high``, ``n``, ``predicted`` (mean P),
        ``measured`` (fraction overturned), ``binomial_sd`` (sqrt(P (1 - P) / n) of the mean
        predicted P), ``within_2sd`` (|measured - predicted| <= 2 sd, or <= 1/n).
    """
    import pandas as pd

    p, y = _checked(probability, outcomes)
    edges = np.asarray(edges, dtype=float)
    which = np.clip(np.searchsorted(edges, p, side="right") - 1, 0, edges.size - 2)
    rows = []
    for k in range(edges.size - 1):
        mask = which == k
        count = int(mask.sum())
        if not count:
            continue
        predicted = float(p[mask].mean())
        measured = float(y[mask].mean())
        sd = math.sqrt(predicted * (1 - predicted) / count)
        rows.append({"low": edges[k], "high": edges[k + 1], "n": count,
                     "predicted": predicted, "measured": measured, "binomial_sd": sd,
                     "within_2sd": abs(measured - predicted) <= max(2 * sd, 1.0 / count)})
    return pd.DataFrame(rows)


def fragility(probability, outcomes, measure, edges):
    """Measured and predicted P(overturn) in bins of an intensity measure.

    Parameters
    ----------
    probability, outcomes : array_like
        Predicted P and measured verdicts.
    measure : array_like
        The intensity measure of each test (e.g. PGA [g], PGV/PGA [s]).
    edges : array_like
        Bin edges in the measure's unit.

    Returns
    -------
    pandas.DataFrame
        ``low``, ``high``, ``centre`` (geometric mean of the tests' measure), ``n``,
        ``measured``, ``measured_low``, ``measured_high`` (Wilson 95 %), ``predicted``.
    """
    import pandas as pd

    p, y = _checked(probability, outcomes)
    measure = np.asarray(measure, dtype=float)
    edges = np.asarray(edges, dtype=float)
    rows = []
    for low, high in zip(edges[:-1], edges[1:]):
        mask = (measure >= low) & (measure < high)
        count = int(mask.sum())
        if not count:
            continue
        successes = int(y[mask].sum())
        lower, upper = wilson_interval(successes, count)
        rows.append({"low": low, "high": high,
                     "centre": float(np.exp(np.mean(np.log(measure[mask])))), "n": count,
                     "measured": successes / count, "measured_low": lower,
                     "measured_high": upper, "predicted": float(p[mask].mean())})
    return pd.DataFrame(rows)


def threshold_fit(measure, outcomes) -> float:
    """The threshold on a measure that best separates the verdicts (overturned above it).

    The midpoint between consecutive sorted values with the highest training accuracy (ties:
    the lowest); a baseline against which a model is judged.
    """
    x = np.asarray(measure, dtype=float)
    y = np.asarray(outcomes, dtype=int)
    values = np.unique(x)
    candidates = np.concatenate([[values[0] - 1.0], 0.5 * (values[1:] + values[:-1]),
                                 [values[-1] + 1.0]])
    accuracy = [(np.mean((x >= c) == (y == 1))) for c in candidates]
    return float(candidates[int(np.argmax(accuracy))])
