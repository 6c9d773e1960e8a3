"""The equivalent block of a specimen, the grid of candidates, and their verdicts on a folder.

A specimen (a rock, a cabinet) is modelled as an :class:`~shaketable.core.geometry.AsymmetricBlock`
rocking without sliding: its two block angles (the weak side's and the strong side's), the
centroid height h (R and p follow), the COR (a number, or Housner's per pivot) and the sign
of the table axis (which way the recorded acceleration is positive relative to the
specimen's weak side: the orientation of a specimen on the table is often not recorded).
Flipping the sign is the same as mirroring the block, so a symmetric candidate has one sign.

Each candidate's verdict on each test is simulated (:func:`verdicts`), the motion padded
with the table at rest so that the end-of-motion fate is simulated, not guessed.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass

import numpy as np

from shaketable.core.geometry import AsymmetricBlock
from shaketable.core.validation import in_range, positive
from shaketable.models.rocking.asymmetric import simulate_many_asymmetric
from shaketable.models.rocking.layout import INFO_STATUS, INFO_T_OVERTURN, STATUS_OVERTURNED

#: Seconds of table at rest appended to every motion: the block's free rocking after the
#: record decides its fate (a block with p ~ 5 rad/s rocks out in a few seconds).
FATE_PADDING = 8.0

#: Natural logarithms of the amplitude factors each candidate runs at [-]: the verdict at
#: e^beta times the recorded motion. P(overturn) of a candidate is the verdict averaged over
#: beta ~ N(0, sigma^2) (discretised on these points): a probit link on the logarithm of the
#: factor by which the motion must be scaled to overturn the block (its margin), sigma
#: calibrated with the block.
LOG_SCALES = (-0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6)


@dataclass(frozen=True)
class EquivalentBlock:
    """One candidate model of a specimen.

    Parameters
    ----------
    alpha_weak : float
        Block angle of the weaker (more slender) side [rad].
    alpha_strong : float
        Block angle of the other side [rad], >= ``alpha_weak``.
    h : float
        Centroid height over the base [m].
    cor : float or "housner"
        Coefficient of restitution [-] (both pivots), or Housner's per pivot.
    sign : int
        +1: a positive recorded table acceleration tips the block over its weak side;
        -1: over its strong side. A symmetric block has +1.
    """

    alpha_weak: float
    alpha_strong: float
    h: float
    cor: float | str
    sign: int = 1

    def __post_init__(self):
        weak = in_range("alpha_weak", self.alpha_weak, 0.0, math.pi / 2, low_open=True)
        strong = in_range("alpha_strong", self.alpha_strong, weak, math.pi / 2)
        object.__setattr__(self, "alpha_weak", weak)
        object.__setattr__(self, "alpha_strong", strong)
        object.__setattr__(self, "h", positive("h", self.h, " [m]"))
        if isinstance(self.cor, str):
            if self.cor != "housner":
                raise ValueError(f"cor must be a number in [0, 1] or 'housner', got {self.cor!r}")
        else:
            object.__setattr__(self, "cor", in_range("cor", self.cor, 0.0, 1.0))
        if self.sign not in (1, -1):
            raise ValueError(f"sign must be +1 or -1, got {self.sign!r}")

    @property
    def symmetric(self) -> bool:
        """True when both sides have the same angle."""
        return self.alpha_weak == self.alpha_strong

    def block(self) -> AsymmetricBlock:
        """The block: theta > 0 (driven by a positive table acceleration) on the weak side.

        The sign is applied to the motion (:func:`verdicts`), not to the block.
        """
        return AsymmetricBlock.from_angles(self.alpha_weak, self.alpha_strong, self.h)

    @property
    def R_weak(self) -> float:
        """Pivot-to-centroid distance of the weak side [m]."""
        return self.h / math.cos(self.alpha_weak)

    @property
    def p_weak(self) -> float:
        """Frequency parameter of the weak side [rad/s]."""
        return self.block().p_of(1.0)

    @property
    def half_width(self) -> float:
        """The weak side's effective contact half-width h tan(alpha_weak) [m]: the distance
        from the centroid to the pivot the block tips over first."""
        return self.effective_half_width("weak")

    def effective_half_width(self, side: str = "weak") -> float:
        """Horizontal distance from the centroid to the pivot, h tan(alpha) [m]."""
        return self.h * math.tan(self.alpha_weak if side == "weak" else self.alpha_strong)

    def to_dict(self) -> dict:
        """JSON-ready fields."""
        return asdict(self)

    def describe(self) -> str:
        """One line: angles, h, COR, sign."""
        cor = self.cor if isinstance(self.cor, str) else f"{self.cor:g}"
        return (f"alpha weak {self.alpha_weak:.4g} rad, strong {self.alpha_strong:.4g} rad, "
                f"h {self.h:.3g} m, COR {cor}, sign {self.sign:+d}")


@dataclass(frozen=True)
class CandidateGrid:
    """The candidates a calibration chooses among (a grid: profile likelihood per axis).

    Parameters
    ----------
    alphas : sequence of float
        Weak-side block angles [rad].
    ratios : sequence of float
        alpha_strong / alpha_weak [-] (1: symmetric); a strong angle past 1.5 rad is left out.
    heights : sequence of float
        Centroid heights [m].
    cors : sequence of float or "housner"
        Coefficients of restitution.
    """

    alphas: tuple[float, ...] = (0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1, 0.11, 0.12, 0.13,
                                 0.14, 0.16, 0.19)
    ratios: tuple[float, ...] = (1.0, 1.5, 2.0)
    heights: tuple[float, ...] = (0.3,)
    cors: tuple[float | str, ...] = ("housner", 0.9, 0.8)

    def candidates(self) -> list[EquivalentBlock]:
        """Every candidate, in a fixed order (the calibration's tie-break)."""
        found = []
        for alpha, ratio, h, cor in itertools.product(self.alphas, self.ratios, self.heights,
                                                      self.cors):
            strong = alpha * in_range("ratio", ratio, 1.0)
            if strong >= 1.5:
                continue
            for sign in ((1,) if ratio == 1.0 else (1, -1)):
                found.append(EquivalentBlock(alpha, strong, h, cor, sign))
        if not found:
            raise ValueError("the candidate grid is empty")
        return found


def verdicts(candidates: Sequence[EquivalentBlock], motions, *, threads: int | None = None,
             padding: float = FATE_PADDING, log_scales=LOG_SCALES,
             progress: Callable[[int, int], None] | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """Simulated verdict of every candidate on every motion, at each amplitude scale.

    Parameters
    ----------
    candidates : sequence of EquivalentBlock
    motions : sequence of Motion
        The recorded table accelerations [m/s^2], as recorded (the sign is the candidate's).
    threads : int, optional
        Threads of the batch.
    padding : float
        Table at rest appended to each motion [s] (the fate after the record).
    log_scales : sequence of float
        Natural logarithms of the factors on the motion's amplitude [-]
        (:data:`LOG_SCALES`; the likelihood's probit link on the log margin).
    progress : callable, optional
        Called as ``progress(done, total)`` (runs: candidate x motion x scale) after each
        group of motions (about 20 groups, every candidate in each: the same runs and
        verdicts as one batch).

    Returns
    -------
    overturned : ndarray of bool, shape (candidates, motions, scales)
    t_overturn : ndarray, shape (candidates, motions, scales)
        When it overturned [s] from the motion's start; NaN if it did not.
    """
    motions = list(motions)
    # each motion padded on its own (the batch pads all to one duration)
    from shaketable.models.rocking.run import extended

    runs = []
    for motion in motions:
        padded = extended(motion, motion.duration + padding)
        runs.append(padded)
    factors = np.exp(np.asarray(log_scales, dtype=float))
    n_c, n_m, n_s = len(candidates), len(runs), factors.size
    overturned = np.empty((n_c, n_m, n_s), dtype=bool)
    t_overturn = np.empty((n_c, n_m, n_s))
    group = max(1, -(-n_m // 20))
    for first in range(0, n_m, group):
        last = min(first + group, n_m)
        overturned[:, first:last], t_overturn[:, first:last] = \
            _group_verdicts(list(candidates), runs[first:last], factors, threads)
        if progress is not None:
            progress(n_c * last * n_s, n_c * n_m * n_s)
    return overturned, t_overturn


def _group_verdicts(candidates: list, runs: list, factors: np.ndarray,
                    threads: int | None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`verdicts` of the candidates on a few padded motions, in one batch."""
    blocks: list[AsymmetricBlock] = []
    index: dict[tuple, int] = {}
    block_of = np.empty(len(candidates), dtype=np.int64)
    for k, candidate in enumerate(candidates):
        key = (candidate.alpha_weak, candidate.alpha_strong, candidate.h)
        if key not in index:
            index[key] = len(blocks)
            blocks.append(candidate.block())
        block_of[k] = index[key]
    n_c, n_m, n_s = len(candidates), len(runs), factors.size
    cases = np.empty((n_c * n_m * n_s, 2), dtype=np.int64)
    cases[:, 0] = np.repeat(block_of, n_m * n_s)
    cases[:, 1] = np.tile(np.repeat(np.arange(n_m), n_s), n_c)
    cors = [candidate.cor for candidate in candidates for _ in range(n_m * n_s)]
    scales = (np.repeat([float(candidate.sign) for candidate in candidates], n_m * n_s)
              * np.tile(factors, n_c * n_m))
    info = simulate_many_asymmetric(blocks, runs, cases, cors, scales=scales, threads=threads)
    overturned = (info[:, INFO_STATUS] == STATUS_OVERTURNED).reshape(n_c, n_m, n_s)
    return overturned, info[:, INFO_T_OVERTURN].reshape(n_c, n_m, n_s)


def scan_block(geometry, specimen: str, direction: str = "x") -> AsymmetricBlock:
    """The block of a specimen straight from its scan (``geometry.csv`` of a test folder).

    ``geometry`` is the table (pandas) with columns ``specimen``, ``direction``, ``side``
    (``+x``, ``-x``), ``b_m``, ``h_m``, ``R_m`` and ``I_O_over_mR2``; the block's theta > 0
    pivot is the ``+x`` side's, its inertia from that side's I_O / (m R^2)
    (k^2 = (I_O/(m R^2) - 1) R^2).
    """
    rows = geometry[(geometry["specimen"].str.lower() == specimen.lower())
                    & (geometry["direction"] == direction)]
    if len(rows) != 2:
        raise ValueError(f"geometry: expected two sides of {specimen!r} in direction "
                         f"{direction!r}, found {len(rows)}")
    plus = rows[rows["side"] == f"+{direction}"].iloc[0]
    minus = rows[rows["side"] == f"-{direction}"].iloc[0]
    k2 = (float(plus["I_O_over_mR2"]) - 1.0) * float(plus["R_m"]) ** 2
    return AsymmetricBlock(float(plus["h_m"]), float(plus["b_m"]), float(minus["b_m"]),
                           gyration=math.sqrt(k2), label=f"{specimen} scan")
