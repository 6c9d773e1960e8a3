"""Perturbed copies of one run: the spreads, the draws and the verdict statistics.

The solver-free part of an ensemble, shared by every layer that runs
one: :mod:`shaketable.studies.predictability` (the API, ``simulate --ensemble``,
a scene's ``[ensemble]``, Tables 4.1-4.3) and :mod:`shaketable.sweeps` (a sweep's
``[ensemble]``, one ensemble per cell). Member ``k`` of an ensemble has

* the input amplitude multiplied by ``1 + amplitude * u1``,
* the COR multiplied by ``1 + cor * u2`` (kept in [0, 1]),
* the block height and width multiplied by ``1 + size * u3``, ``1 + size * u4``,
* the record started ``start * u5`` sample intervals later
  (:func:`shifted`: the record re-sampled, linearly, at t + delta),

with u1 ... u5 independent and uniform in [-1, 1], drawn by
:func:`perturbed_members` from a seeded generator; member 0 is the unperturbed
run. :func:`verdict_statistics` gives P(overturn) with Wilson's 95 % score
interval and the median and 5-95 % range of max |theta|/alpha.

The ``[ensemble]`` options of a scene or a sweep spec are read by
:func:`ensemble_options` (one parser for both).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.validation import unknown_keys

__all__ = ["ENSEMBLE_KEYS", "HORIZON_THRESHOLD", "Members", "Perturbation", "TINY",
           "ensemble_options", "perturbed_block", "perturbed_cor", "perturbed_members",
           "shifted", "verdict_statistics", "wilson_interval"]

#: Default relative spread of every input [-]: far below any physical
#: uncertainty, large enough (1e7 machine epsilons) to be a different run.
TINY = 1e-9

#: Default divergence threshold of the predictability horizon [-], in units of alpha.
HORIZON_THRESHOLD = 1e-3

#: Keys of an ``[ensemble]`` section (scene or sweep spec).
#: Most members of one ensemble (each is a run; the draws alone take 40 bytes a member).
MAX_MEMBERS = 1_000_000

ENSEMBLE_KEYS = {"members", "perturb", "perturb_amplitude", "perturb_cor", "perturb_size",
                 "perturb_start", "seed", "horizon_threshold"}


@dataclass(frozen=True)
class Perturbation:
    """Relative spreads [-] of the inputs of an ensemble (uniform in +/- spread).

    Attributes
    ----------
    amplitude : float
        Of the input amplitude (every component of the motion) [-].
    cor : float
        Of the coefficient of restitution [-] (the result kept in [0, 1]).
    size : float
        Of the block height and width, independently [-].
    start : float
        Of the record's start, in sample intervals [-]: the record is read
        from ``t + start * u * dt`` on (linear interpolation).
    """

    amplitude: float = TINY
    cor: float = TINY
    size: float = TINY
    start: float = TINY

    def __post_init__(self):
        for name in ("amplitude", "cor", "size", "start"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value)
                    and 0.0 <= value < 1.0):
                raise ValueError(f"Perturbation.{name} must be a relative spread in [0, 1), "
                                 f"got {value!r}")
            object.__setattr__(self, name, float(value))

    @classmethod
    def uniform(cls, spread: float) -> "Perturbation":
        """Every input perturbed by the same relative ``spread``."""
        return cls(spread, spread, spread, spread)


def wilson_interval(successes: int, trials: int, z: float = 1.959964) -> tuple[float, float]:
    """Wilson's score interval for a binomial proportion (95 % for the default z).

    Wilson, E. B., J. Am. Stat. Assoc. 22(158), 209-212, 1927.
    """
    if trials <= 0:
        raise ValueError(f"trials must be positive, got {trials!r}")
    if not 0 <= successes <= trials:
        raise ValueError(f"successes must be in [0, trials], got {successes!r}")
    p = successes / trials
    denominator = 1.0 + z * z / trials
    centre = (p + z * z / (2 * trials)) / denominator
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / denominator
    return max(0.0, centre - half), min(1.0, centre + half)


def shifted(motion: Motion, delta: float) -> Motion:
    """The record read from ``t + delta`` on [s] (same grid, linear interpolation).

    ``delta = 0`` returns ``motion`` itself (the nominal member shares its object).
    """
    if delta == 0.0:
        return motion
    times = motion.t + delta
    horizontal = np.interp(times, motion.t, motion.horizontal)
    vertical = None if motion.vertical is None else np.interp(times, motion.t, motion.vertical)
    rotation = None if motion.rotation is None else np.interp(times, motion.t, motion.rotation)
    return Motion(motion.t, horizontal, vertical, name=motion.name, rotation=rotation,
                  metadata=motion.metadata)


def _factors(rng, members, spread):
    """``members`` factors 1 + spread * U[-1, 1], the first exactly 1."""
    values = 1.0 + spread * rng.uniform(-1.0, 1.0, members)
    values[0] = 1.0
    return values


@dataclass(frozen=True)
class Members:
    """The perturbed inputs of an ensemble, member 0 the nominal run.

    Attributes
    ----------
    amplitude, cor, height, width : ndarray
        Factors [-] on the input amplitude, the COR, the block height and width.
    start : ndarray
        Shifts of the record's start [sample intervals].
    """

    amplitude: np.ndarray
    cor: np.ndarray
    height: np.ndarray
    width: np.ndarray
    start: np.ndarray


def perturbed_members(members: int, perturbation: Perturbation, seed: int = 0) -> Members:
    """Factors (amplitude, COR, height, width) and start shifts [sample intervals] per member.

    The same ``(members, perturbation, seed)`` always gives the same draws.
    """
    if not (isinstance(members, (int, np.integer)) and not isinstance(members, bool)
            and 2 <= members <= MAX_MEMBERS):
        raise ValueError(f"members must be an integer >= 2 (at most {MAX_MEMBERS:,}), got "
                         f"{members!r}")
    rng = np.random.default_rng(seed)
    start = perturbation.start * rng.uniform(-1.0, 1.0, members)
    start[0] = 0.0
    return Members(_factors(rng, members, perturbation.amplitude),
                   _factors(rng, members, perturbation.cor),
                   _factors(rng, members, perturbation.size),
                   _factors(rng, members, perturbation.size), start)


def perturbed_block(block: Block, drawn: Members, k: int) -> Block:
    """Member ``k``'s block (``block`` itself for the nominal member 0)."""
    if k == 0:
        return block
    return Block(block.height * drawn.height[k], block.width * drawn.width[k], block.rods)


def perturbed_cor(cor: float, drawn: Members, k: int) -> float:
    """Member ``k``'s coefficient of restitution [-], kept in [0, 1]."""
    return min(1.0, max(0.0, cor * drawn.cor[k]))


def verdict_statistics(overturned, max_theta_ratio) -> dict:
    """P(overturn), its Wilson interval, and max |theta|/alpha statistics of one ensemble.

    Parameters
    ----------
    overturned : array_like of bool
        Verdict of each member, member 0 the nominal run.
    max_theta_ratio : array_like of float
        max |theta|/alpha [-] of each member.

    Returns
    -------
    dict
        ``members``, ``overturned`` (count), ``P(overturn) [-]``, ``P low [-]``,
        ``P high [-]`` (Wilson 95 %), ``nominal overturned``, ``robust`` (every
        member agrees), ``standing members`` and the median, 5 % and 95 %
        percentiles of max theta/alpha over the members that stand (an
        overturned member has no peak: (pi/2)/alpha is where its run stopped;
        NaN when none stands).
    """
    overturned = np.asarray(overturned, dtype=bool)
    ratio = np.asarray(max_theta_ratio, dtype=float)
    n, k = int(overturned.size), int(overturned.sum())
    low, high = wilson_interval(k, n)
    standing = ratio[~overturned]

    def statistic(function):
        return float(function(standing)) if standing.size else math.nan

    return {"members": n, "overturned": k, "P(overturn) [-]": k / n,
            "P low [-]": low, "P high [-]": high,
            "nominal overturned": bool(overturned[0]),
            "robust": k in (0, n),
            "standing members": int(standing.size),
            "median max theta/alpha [-]": statistic(np.median),
            "p05 max theta/alpha [-]": statistic(lambda x: np.percentile(x, 5)),
            "p95 max theta/alpha [-]": statistic(lambda x: np.percentile(x, 95))}


def ensemble_options(section: dict, where: str, *, horizon: bool = True) -> dict:
    """Validated ``[ensemble]`` options of a scene or a sweep spec (ValueError naming the key).

    Keys (all optional): ``members`` (default 200), ``perturb`` (relative spread of
    every input, default :data:`TINY`), ``perturb_amplitude``, ``perturb_cor``,
    ``perturb_size``, ``perturb_start`` (override it per input), ``seed`` (0) and,
    when ``horizon`` is true, ``horizon_threshold`` (in units of alpha, default
    :data:`HORIZON_THRESHOLD`).

    Parameters
    ----------
    section : dict
        The parsed ``[ensemble]`` table.
    where : str
        The file, for the messages.
    horizon : bool
        Whether the caller computes a predictability horizon (a sweep does not:
        ``horizon_threshold`` is then an error, not a key silently ignored).

    Returns
    -------
    dict
        ``members`` (int), ``seed`` (int), ``spreads`` (the keyword arguments of
        :class:`Perturbation`) and ``threshold`` [-].
    """
    allowed = ENSEMBLE_KEYS if horizon else ENSEMBLE_KEYS - {"horizon_threshold"}
    unknown = unknown_keys(section, allowed)
    if unknown:
        extra = ("; a sweep computes no predictability horizon (run one cell with "
                 "`shaketable simulate --ensemble`)" if unknown[0] == "horizon_threshold"
                 else "")
        raise ValueError(f"{where}: unknown key ensemble.{unknown[0]}; expected one of "
                         f"{', '.join(sorted(allowed))}{extra}")
    members = section.get("members", 200)
    if isinstance(members, bool) or not isinstance(members, int) \
            or not 2 <= members <= MAX_MEMBERS:
        raise ValueError(f"{where}: ensemble.members must be an integer >= 2 (at most "
                         f"{MAX_MEMBERS:,}), got {members!r}")
    seed = section.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"{where}: ensemble.seed must be a non-negative integer, got {seed!r}")
    spread = section.get("perturb", TINY)
    spreads = {}
    for name in ("amplitude", "cor", "size", "start"):
        value = section.get(f"perturb_{name}", spread)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                0 <= value < 1):
            raise ValueError(f"{where}: ensemble.perturb_{name} (or perturb) must be a "
                             f"relative spread in [0, 1), got {value!r}")
        spreads[name] = float(value)
    threshold = section.get("horizon_threshold", HORIZON_THRESHOLD)
    if isinstance(threshold, bool) or not isinstance(threshold, (int, float)) or not (
            0 < threshold < math.inf):
        raise ValueError(f"{where}: ensemble.horizon_threshold must be positive, got "
                         f"{threshold!r}")
    return {"members": members, "seed": seed, "spreads": spreads,
            "threshold": float(threshold)}
