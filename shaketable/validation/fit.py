"""Calibrate an equivalent block on measured verdicts by maximum likelihood; its intervals.

The likelihood. A candidate block c predicts a verdict V_ci (overturned or not) of test i;
the measured verdict y_i agrees with it except with a probability epsilon (what the
deterministic model cannot say: chaotic rocking near the threshold, details of the contact,
the table's repeatability), so

    L(c, epsilon) = (1 - epsilon)^(n - e_c) epsilon^(e_c),   e_c = #{i : V_ci != y_i},

maximised over epsilon at epsilon_c = e_c / n. The maximum-likelihood block is the candidate
with the fewest errors (ties: the first of the grid's order). Its 95 % intervals are the
profile likelihood's: on each axis of the grid, the values whose best candidate has
2 (l_max - l) <= 3.84 (chi-square, one degree of freedom), at the grid's resolution.

The probabilities. A prediction is an ensemble over the calibration's uncertainty: every
candidate weighted by its likelihood at the best epsilon (a flat prior on the grid,
Bayes' rule), each giving P = epsilon + (1 - 2 epsilon) V_ci, averaged. The verdict is
P >= 0.5.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from shaketable.validation.model import EquivalentBlock

#: chi-square(1) 95 % quantile: the profile likelihood's cut.
CHI2_95 = 3.841458820694124

#: Candidates kept in a calibration's ensemble (the heaviest; the rest weigh less).
ENSEMBLE_SIZE = 48

#: The axes of the grid whose intervals are reported.
AXES = ("alpha_weak", "alpha_strong", "h", "cor", "sign")


def log_likelihood(errors, n: int) -> np.ndarray:
    """Profile log likelihood of candidates with ``errors`` disagreements in ``n`` tests [-]."""
    errors = np.asarray(errors, dtype=float)
    rate = errors / n
    with np.errstate(divide="ignore", invalid="ignore"):
        value = (np.where(errors > 0, errors * np.log(rate), 0.0)
                 + np.where(errors < n, (n - errors) * np.log1p(-rate), 0.0))
    return value


def _epsilon(errors: int, n: int) -> float:
    # at least half an error: a perfect fit on n tests does not prove epsilon = 0
    return max(errors, 0.5) / n


def ensemble_weights(errors, n: int, epsilon: float) -> np.ndarray:
    """Likelihood weights of the candidates at ``epsilon`` (flat prior), summing to 1."""
    errors = np.asarray(errors, dtype=float)
    log_weight = errors * math.log(epsilon) + (n - errors) * math.log1p(-epsilon)
    weight = np.exp(log_weight - log_weight.max())
    return weight / weight.sum()


def probability(overturned: np.ndarray, weights: np.ndarray, epsilon: float) -> np.ndarray:
    """P(overturn) of each test: the weighted ensemble of candidates' verdicts.

    ``overturned`` has shape (candidates, tests).
    """
    verdict = np.asarray(overturned, dtype=float)
    return epsilon + (1.0 - 2.0 * epsilon) * (np.asarray(weights) @ verdict)


@dataclass(frozen=True)
class Calibration:
    """The calibrated equivalent block of one specimen and its ensemble.

    Attributes
    ----------
    specimen : str
    best : EquivalentBlock
        The maximum-likelihood candidate.
    errors : int
        Its disagreements with the measured verdicts.
    n : int
        Tests with an outcome it was calibrated on.
    epsilon : float
        The disagreement probability at the best candidate [-].
    intervals : dict
        Axis -> 95 % profile-likelihood set: ``[low, high]`` for numbers, the list of
        accepted values for the COR (which may hold "housner") and the sign.
    members : list of EquivalentBlock
        The ensemble (the heaviest candidates).
    weights : ndarray
        Their weights (summing to 1).
    """

    specimen: str
    best: EquivalentBlock
    errors: int
    n: int
    epsilon: float
    intervals: dict
    members: list = field(default_factory=list)
    weights: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Calibration) and self.to_dict() == other.to_dict())

    __hash__ = None  # type: ignore[assignment]

    @property
    def accuracy(self) -> float:
        """Training accuracy of the best candidate [-]."""
        return 1.0 - self.errors / self.n

    def to_dict(self) -> dict:
        """JSON-ready."""
        return {"specimen": self.specimen, "best": self.best.to_dict(), "errors": self.errors,
                "n": self.n, "epsilon": self.epsilon, "intervals": self.intervals,
                "members": [member.to_dict() for member in self.members],
                "weights": [float(weight) for weight in self.weights]}

    @classmethod
    def from_dict(cls, data: dict, where: str = "calibration") -> "Calibration":
        """From :meth:`to_dict`'s dict; ValueError naming ``where`` and the key."""
        try:
            return cls(str(data["specimen"]), EquivalentBlock(**data["best"]),
                       int(data["errors"]), int(data["n"]), float(data["epsilon"]),
                       dict(data["intervals"]),
                       [EquivalentBlock(**member) for member in data["members"]],
                       np.asarray(data["weights"], dtype=float))
        except (KeyError, TypeError) as error:
            raise ValueError(f"{where}: not a calibration of shaketable validate ({error!r})") \
                from None


def _axis_value(candidate: EquivalentBlock, axis: str):
    return getattr(candidate, axis)


def profile_intervals(candidates: Sequence[EquivalentBlock], errors, n: int) -> dict:
    """95 % profile-likelihood set of each axis (see the module docstring)."""
    loglik = log_likelihood(errors, n)
    best = float(loglik.max())
    intervals: dict = {}
    for axis in AXES:
        values = [_axis_value(candidate, axis) for candidate in candidates]
        accepted = []
        for value in dict.fromkeys(values):
            mask = np.array([item == value for item in values])
            if 2.0 * (best - float(loglik[mask].max())) <= CHI2_95:
                accepted.append(value)
        if axis in ("cor", "sign"):
            intervals[axis] = accepted
        else:
            intervals[axis] = [float(min(accepted)), float(max(accepted))]
    return intervals


def fit(overturned: np.ndarray, outcomes: np.ndarray, candidates: Sequence[EquivalentBlock],
        specimen: str = "", *, intervals: bool = True) -> Calibration:
    """Maximum-likelihood equivalent block from the candidates' verdicts.

    Parameters
    ----------
    overturned : ndarray of bool, shape (candidates, tests)
        :func:`shaketable.validation.model.verdicts`.
    outcomes : ndarray of int, shape (tests,)
        Measured verdicts (1 overturned).
    candidates : sequence of EquivalentBlock
    specimen : str
    intervals : bool
        Compute the profile-likelihood sets (skipped inside cross-validation).
    """
    overturned = np.asarray(overturned, dtype=bool)
    outcomes = np.asarray(outcomes, dtype=int)
    if overturned.shape != (len(candidates), outcomes.size):
        raise ValueError(f"overturned has shape {overturned.shape}, expected "
                         f"({len(candidates)}, {outcomes.size})")
    if outcomes.size == 0:
        raise ValueError("outcomes: no test to calibrate on")
    n = outcomes.size
    errors = (overturned != outcomes.astype(bool)).sum(axis=1)
    best = int(np.argmin(errors))
    epsilon = _epsilon(int(errors[best]), n)
    weights = ensemble_weights(errors, n, epsilon)
    order = np.argsort(-weights, kind="stable")[:ENSEMBLE_SIZE]
    kept = weights[order] / weights[order].sum()
    sets = profile_intervals(candidates, errors, n) if intervals else {}
    return Calibration(specimen, candidates[best], int(errors[best]), n, epsilon, sets,
                       [candidates[k] for k in order], kept)


def ensemble_probability(calibration: Calibration, candidates: Sequence[EquivalentBlock],
                         overturned: np.ndarray) -> np.ndarray:
    """P(overturn) of tests from the verdicts of ``candidates`` (which include the members)."""
    position = {candidate: k for k, candidate in enumerate(candidates)}
    rows = [position[member] for member in calibration.members]
    return probability(np.asarray(overturned)[rows], calibration.weights, calibration.epsilon)
