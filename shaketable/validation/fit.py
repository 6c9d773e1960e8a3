"""Calibrate an equivalent block on measured verdicts by maximum likelihood; its intervals.

The model's probability. A candidate block c is run on each test i at the amplitude factors
e^beta_k (:data:`shaketable.validation.model.LOG_SCALES`); its P(overturn) is the verdict
averaged over beta ~ N(0, sigma^2) on those points, which is a probit link on the logarithm
of the test's margin (the factor by which the motion must be scaled to overturn the block):
sigma is what the deterministic block cannot say (chaotic rocking near the threshold, the
contact, the table's repeatability). sigma = 0 is the verdict at the recorded amplitude.
A floor epsilon (P in [epsilon, 1 - epsilon]) keeps one surprising test from an infinite
log loss:

    P_ci = epsilon + (1 - 2 epsilon) sum_k w_k(sigma) V_cik,
    l(c, sigma, epsilon) = sum_i y_i log P_ci + (1 - y_i) log(1 - P_ci).

The maximum-likelihood block is the candidate, sigma and epsilon (on their grids) of the
largest l (ties: the first of the grid's order). Its 95 % intervals are the profile
likelihood's: on each axis of the grid, the values whose best candidate has
2 (l_max - l) <= 3.84 (chi-square, one degree of freedom), at the grid's resolution.

The prediction is an ensemble over the calibration's uncertainty, the probabilities
averaged; the verdict is P >= 0.5. Two ensembles:

* bagged (``bags > 0``, the default of ``shaketable validate``): the maximum-likelihood
  member of each of ``bags`` refits on bootstrap resamples of the tests, each with its own
  sigma and epsilon, weighted by how many refits chose it. The spread of the members is
  the calibration's sampling uncertainty as the bootstrap measures it, which holds where
  the likelihood is too rough for its curvature to (the block's verdicts jump as a
  parameter crosses a value where the rocking changes course, so the profile sets are too
  narrow: docs/validation.md);
* likelihood-weighted (``bags = 0``): the :data:`ENSEMBLE_SIZE` most likely candidates,
  each with its own sigma and epsilon, weighted by their profile likelihood (a flat prior
  on the grid, Bayes' rule).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from shaketable.validation.model import LOG_SCALES, EquivalentBlock

#: chi-square(1) 95 % quantile: the profile likelihood's cut.
CHI2_95 = 3.841458820694124

#: Candidates kept in a likelihood-weighted ensemble (the heaviest).
ENSEMBLE_SIZE = 24

#: Bootstrap refits of the bagged ensemble of ``shaketable validate`` (see the docstring).
BAGS = 30

#: The axes of the grid whose intervals are reported (``half_width``: h tan(alpha_weak), the
#: effective contact half-width, a function of two axes).
AXES = ("alpha_weak", "alpha_strong", "h", "half_width", "cor", "sign", "sigma")

#: Grids of the link's spread sigma [-] (of ln amplitude) and floor epsilon [-].
SIGMAS = (0.0, 0.1, 0.2, 0.3, 0.4)
EPSILONS = (0.002, 0.01, 0.03, 0.06)


def scale_weights(sigma: float, log_scales=LOG_SCALES) -> np.ndarray:
    """Weights of the amplitude points for a spread ``sigma`` (normal, discretised)."""
    beta = np.asarray(log_scales, dtype=float)
    if sigma == 0.0:
        weights = (beta == 0.0).astype(float)
        if not weights.any():
            raise ValueError("log_scales must hold 0 (the recorded amplitude)")
    else:
        weights = np.exp(-0.5 * (beta / sigma) ** 2)
    return weights / weights.sum()


def candidate_probability(overturned: np.ndarray, sigma: float, epsilon: float) -> np.ndarray:
    """P(overturn) of a candidate from its verdicts (..., scales) at ``sigma``, ``epsilon``."""
    margin = np.asarray(overturned, dtype=float) @ scale_weights(sigma)
    return epsilon + (1.0 - 2.0 * epsilon) * margin


def likelihood_table(overturned: np.ndarray, outcomes) -> np.ndarray:
    """Log likelihood of every candidate, sigma and epsilon: shape (candidates, sigmas, eps)."""
    y = np.asarray(outcomes, dtype=float)
    table = np.empty((overturned.shape[0], len(SIGMAS), len(EPSILONS)))
    verdict = np.asarray(overturned, dtype=float)
    for s, sigma in enumerate(SIGMAS):
        margin = verdict @ scale_weights(sigma)
        for e, epsilon in enumerate(EPSILONS):
            p = epsilon + (1.0 - 2.0 * epsilon) * margin
            table[:, s, e] = np.log(p) @ y + np.log1p(-p) @ (1.0 - y)
    return table


@dataclass(frozen=True)
class Member:
    """One candidate of a calibration's ensemble, with its link's sigma and epsilon."""

    block: EquivalentBlock
    sigma: float
    epsilon: float

    def to_dict(self) -> dict:
        """JSON-ready."""
        return {"block": self.block.to_dict(), "sigma": self.sigma, "epsilon": self.epsilon}


@dataclass(frozen=True, eq=False)
class Calibration:
    """The calibrated equivalent block of one specimen and its ensemble.

    Attributes
    ----------
    specimen : str
    best : Member
        The maximum-likelihood candidate with its sigma and epsilon.
    log_likelihood : float
        Its log likelihood [-].
    n : int
        Tests with an outcome it was calibrated on.
    accuracy : float
        Training accuracy of the ensemble's verdicts [-].
    intervals : dict
        Axis -> 95 % profile-likelihood set: ``[low, high]`` for numbers, the list of
        accepted values for the COR (which may hold "housner") and the sign.
    members : list of Member
        The ensemble (the heaviest candidates), the best first.
    weights : ndarray
        Their weights (summing to 1).
    tests : tuple of str
        The ids of the tests it was calibrated on (a prediction of one of them is
        in-sample); empty when not recorded.
    """

    specimen: str
    best: Member
    log_likelihood: float
    n: int
    accuracy: float
    intervals: dict
    members: list = field(default_factory=list)
    weights: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tests: tuple = ()

    def to_dict(self) -> dict:
        """JSON-ready."""
        return {"specimen": self.specimen, "best": self.best.to_dict(),
                "log_likelihood": self.log_likelihood, "n": self.n, "accuracy": self.accuracy,
                "intervals": self.intervals,
                "members": [member.to_dict() for member in self.members],
                "weights": [float(weight) for weight in self.weights],
                "tests": list(self.tests)}

    @classmethod
    def from_dict(cls, data: dict, where: str = "calibration") -> "Calibration":
        """From :meth:`to_dict`'s dict; ValueError naming ``where`` and the key."""
        def member(item):
            return Member(EquivalentBlock(**item["block"]), float(item["sigma"]),
                          float(item["epsilon"]))
        try:
            return cls(str(data["specimen"]), member(data["best"]),
                       float(data["log_likelihood"]), int(data["n"]), float(data["accuracy"]),
                       dict(data["intervals"]), [member(item) for item in data["members"]],
                       np.asarray(data["weights"], dtype=float),
                       tuple(str(test) for test in data.get("tests", ())))
        except (KeyError, TypeError) as error:
            raise ValueError(f"{where}: not a calibration of shaketable validate ({error!r})") \
                from None

    def blocks(self) -> list[EquivalentBlock]:
        """The members' blocks (the best first), without repeats."""
        return list(dict.fromkeys(member.block for member in self.members))

    def probability(self, overturned: np.ndarray) -> np.ndarray:
        """P(overturn) of tests from the verdicts of :meth:`blocks` (blocks, tests, scales)."""
        row = {block: k for k, block in enumerate(self.blocks())}
        total = np.zeros(np.asarray(overturned).shape[1])
        for weight, member in zip(self.weights, self.members):
            total += weight * candidate_probability(overturned[row[member.block]], member.sigma,
                                                    member.epsilon)
        return total


def profile_intervals(candidates: Sequence[EquivalentBlock], table: np.ndarray) -> dict:
    """95 % profile-likelihood set of each axis (see the module docstring)."""
    best = float(table.max())
    per_candidate = table.max(axis=(1, 2))
    intervals: dict = {}
    for axis in AXES:
        if axis == "sigma":
            profile = table.max(axis=(0, 2))
            accepted = [sigma for sigma, value in zip(SIGMAS, profile)
                        if 2.0 * (best - value) <= CHI2_95]
            intervals[axis] = [float(min(accepted)), float(max(accepted))]
            continue
        values = [getattr(candidate, axis) for candidate in candidates]
        accepted = []
        for value in dict.fromkeys(values):
            mask = np.array([item == value for item in values])
            if 2.0 * (best - float(per_candidate[mask].max())) <= CHI2_95:
                accepted.append(value)
        if axis in ("cor", "sign"):
            intervals[axis] = accepted
        else:
            intervals[axis] = [float(min(accepted)), float(max(accepted))]
    return intervals


def fit(overturned: np.ndarray, outcomes, candidates: Sequence[EquivalentBlock],
        specimen: str = "", *, intervals: bool = True, bags: int = 0,
        seed: int = 0) -> Calibration:
    """Maximum-likelihood equivalent block from the candidates' verdicts.

    Parameters
    ----------
    overturned : ndarray of bool, shape (candidates, tests, scales)
        :func:`shaketable.validation.model.verdicts`.
    outcomes : array_like of int, shape (tests,)
        Measured verdicts (1 overturned).
    candidates : sequence of EquivalentBlock
    specimen : str
    intervals : bool
        Compute the profile-likelihood sets (skipped inside cross-validation).
    bags : int
        Bootstrap refits of the bagged ensemble (see the module docstring); 0: the
        likelihood-weighted ensemble.
    seed : int
        Seed of the bootstrap resamples.
    """
    overturned = np.asarray(overturned, dtype=bool)
    y = np.asarray(outcomes, dtype=int)
    if overturned.shape[:2] != (len(candidates), y.size) or overturned.ndim != 3:
        raise ValueError(f"overturned has shape {overturned.shape}, expected "
                         f"({len(candidates)}, {y.size}, scales)")
    if y.size == 0:
        raise ValueError("outcomes: no test to calibrate on")
    table = likelihood_table(overturned, y)
    flat = table.reshape(len(candidates), -1)
    per_candidate = flat.max(axis=1)
    choice = flat.argmax(axis=1)
    order = np.argsort(-per_candidate, kind="stable")[:ENSEMBLE_SIZE]
    weights = np.exp(per_candidate[order] - per_candidate[order[0]])
    weights /= weights.sum()
    members = []
    for k in order:
        s, e = np.unravel_index(choice[k], (len(SIGMAS), len(EPSILONS)))
        members.append(Member(candidates[k], SIGMAS[s], EPSILONS[e]))
    sets = profile_intervals(candidates, table) if intervals else {}
    if bags:
        members, weights = _bagged(overturned, y, candidates, members[0], bags, seed)
    calibration = Calibration(specimen, members[0], float(per_candidate[order[0]]), int(y.size),
                              0.0, sets, members, weights)
    rows = [list(candidates).index(block) for block in calibration.blocks()]
    accuracy = float(np.mean((calibration.probability(overturned[rows]) >= 0.5) == (y == 1)))
    return Calibration(specimen, members[0], calibration.log_likelihood, int(y.size), accuracy,
                       sets, members, weights)


def _bagged(overturned: np.ndarray, y: np.ndarray, candidates: Sequence[EquivalentBlock],
            best: Member, bags: int, seed: int) -> tuple[list, np.ndarray]:
    """The bagged ensemble: the best members of ``bags`` bootstrap refits, weighted by how
    often each was chosen; the full data's best member first (weight 0 if never chosen)."""
    if bags < 0:
        raise ValueError(f"bags must be >= 0, got {bags}")
    rng = np.random.default_rng(seed)
    counts: dict = {best: 0}
    for _ in range(bags):
        rows = rng.integers(0, y.size, y.size)
        member = fit(overturned[:, rows], y[rows], candidates, intervals=False).best
        counts[member] = counts.get(member, 0) + 1
    members = [best] + sorted((member for member in counts if member != best),
                              key=lambda member: -counts[member])
    return members, np.array([counts[member] / bags for member in members])


def ensemble_probability(calibration: Calibration, candidates: Sequence[EquivalentBlock],
                         overturned: np.ndarray) -> np.ndarray:
    """P(overturn) of tests from the verdicts of ``candidates`` (which hold the members)."""
    position = {candidate: k for k, candidate in enumerate(candidates)}
    rows = [position[block] for block in calibration.blocks()]
    return calibration.probability(np.asarray(overturned)[rows])
