"""A calibrated COR with its uncertainty, carried into prediction.

:class:`CalibratedCor` is what a ``calibration.json`` (written by ``shaketable
calibrate`` / :meth:`Calibration.to_json`) says about a block's COR: the block's
mean COR, its standard error and degrees of freedom, and the impact-to-impact
scatter sigma of the random-effects model (:mod:`~shaketable.calibration.scatter`;
a file without it falls back to the least-squares COR and its standard error, sigma 0).

:func:`calibrated_ensemble` runs the block under a motion once per member with a
COR drawn from that distribution, in parallel (:func:`shaketable.models.rocking.batch.simulate_cases`),
and reports P(overturn) with Wilson's interval and the median and 5-95 % range of
max |theta|/alpha (:func:`shaketable.core.ensemble.verdict_statistics`, the
statistics of every ensemble of the package). Member k's COR is

    cor_k = mean + se t_k + sigma z_k,    t_k ~ Student t (dof),  z_k ~ N(0, 1),

kept in [0.05, 1]; member 0 is the mean. The engine has one COR per run, so the
impact-to-impact scatter is carried as a run-to-run spread of sigma: an upper bound
on its effect (within a run the scatter of the impacts averages out over impacts,
though the first impacts, which decide an overturn, are few); ``scatter=False``
draws the mean's uncertainty alone, the lower bound.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core.ensemble import verdict_statistics
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.rocking.batch import Case, simulate_cases

if TYPE_CHECKING:
    import pandas as pd

#: Smallest COR drawn [-].
COR_FLOOR = 0.05

#: Most members of one calibrated ensemble (each is a run of the block).
MAX_MEMBERS = 1_000_000


class CalibrationMismatchWarning(UserWarning):
    """A calibration applied to a block of another size than the one it was measured on."""


#: Largest degrees of freedom a calibration may state (a t distribution with more is a
#: normal one to 1e-9; a larger value is a tampered or broken file).
MAX_DOF = 10**9


@dataclass(frozen=True)
class CalibratedCor:
    """A block's COR as a calibration measured it.

    Attributes
    ----------
    mean : float
        The block's mean COR [-].
    mean_se : float
        Its standard error [-].
    dof : int
        Degrees of freedom of the mean's t distribution.
    sigma : float
        Impact-to-impact scatter of the COR [-] (0 without a scatter model).
    source : str
        Where it comes from (a file name).
    height, width : float or None
        Size of the calibrated block [m] (None when the calibration does not say):
        :meth:`size_mismatch` compares it with the block a run uses.
    """

    mean: float
    mean_se: float
    dof: int
    sigma: float = 0.0
    source: str = ""
    height: float | None = None
    width: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.source, str):
            raise TypeError(f"CalibratedCor.source must be text (a file name), got "
                            f"{self.source!r}")
        for name in ("mean", "mean_se", "sigma"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ValueError(f"CalibratedCor.{name} must be a finite number, got {value!r}")
        if not 0 < self.mean <= 1:
            raise ValueError(f"CalibratedCor.mean must be in (0, 1], got {self.mean!r}")
        for name in ("mean_se", "sigma"):   # a COR lies in [0, 1]: so do its spreads
            if not 0 <= getattr(self, name) <= 1:
                raise ValueError(f"CalibratedCor.{name} must be from 0 to 1 (a spread of a "
                                 f"COR), got {getattr(self, name)!r}")
        if isinstance(self.dof, bool) or not isinstance(self.dof, (int, np.integer)) \
                or not 1 <= self.dof <= MAX_DOF:
            raise ValueError(f"CalibratedCor.dof must be an integer from 1 to {MAX_DOF:.0e} "
                             f"(degrees of freedom of the mean), got {self.dof!r}")
        for name in ("height", "width"):
            value = getattr(self, name)
            if value is not None and (isinstance(value, bool)
                                      or not isinstance(value, (int, float))
                                      or not 0 < value < math.inf):
                raise ValueError(f"CalibratedCor.{name} must be a positive size [m] or None, "
                                 f"got {value!r}")

    def size_mismatch(self, block: Block, tolerance: float = 0.01) -> str | None:
        """Why this calibration may not fit ``block``, in words, or None.

        A COR is a property of one block: it depends on its shape (Housner's
        1 - 1.5 sin^2 alpha, Eq. 2-12 of [1]_) and on its size and base. A
        calibration measured on a block whose height or width differs by more than
        ``tolerance`` (relative) from ``block``'s is named with both sizes.
        """
        if self.height is None or self.width is None:
            return None
        if (abs(block.height / self.height - 1) <= tolerance
                and abs(block.width / self.width - 1) <= tolerance):
            return None
        measured = Block(height=self.height, width=self.width)
        return (f"the calibration{' ' + self.source if self.source else ''} was measured on a "
                f"{measured.describe(unit='in')} block ({self.height:.4g} x {self.width:.4g} m, "
                f"H/B {self.height / self.width:.3g}), not on this {block.describe()} block "
                f"({block.height:.4g} x {block.width:.4g} m, H/B "
                f"{block.height / block.width:.3g}); a COR belongs to the block it was "
                "measured on (its shape and size): calibrate this block, or take the result "
                "as a what-if")

    @classmethod
    def from_json(cls, path: str | os.PathLike[str]) -> CalibratedCor:
        """Read a ``calibration.json`` (ValueError naming the file and the missing key)."""
        path = Path(path)
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no such calibration file")
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except (json.JSONDecodeError, UnicodeDecodeError) as error:
            raise ValueError(f"{path}: not a calibration JSON file ({error})") from None
        if not isinstance(data, dict):
            raise ValueError(f"{path}: not a calibration JSON file (no object at the top)")
        return cls.from_summary(data, source=str(path))

    @classmethod
    def from_summary(cls, data: dict[str, Any], source: str = "") -> CalibratedCor:
        """From :meth:`Calibration.summary`: its headline COR (``cor [-]``, ``cor_se [-]``,
        ``cor_dof``, ``cor_sigma [-]``, with ``cor_source``); a summary without
        ``cor_source`` (written by earlier versions) gives the scatter model's mean if it is
        there, else the least-squares COR."""
        where = source or "calibration summary"

        def number(key: str) -> float:
            value = data.get(key)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ValueError(f"{where}: {key!r} is missing or not a finite number; is this "
                                 "a calibration.json written by `shaketable calibrate`?")
            return float(value)

        def integer(key: str) -> int:
            value = number(key)
            if value != int(value) or not 1 <= value <= MAX_DOF:
                raise ValueError(f"{where}: {key!r} is {value!r}; it must be a whole number "
                                 f"from 1 to {MAX_DOF:.0e}")
            return int(value)

        def size(key: str) -> float | None:
            if key not in data:
                return None
            value = number(key)
            if not value > 0:
                raise ValueError(f"{where}: {key!r} is {value!r}; a block size is positive")
            return value

        sizes = {"height": size("block_height [m]"), "width": size("block_width [m]")}
        try:
            if "cor_source" in data:   # the headline keys: the COR the calibration leads with
                sigma = number("cor_sigma [-]") if "cor_sigma [-]" in data else 0.0
                return cls(number("cor [-]"), number("cor_se [-]"), integer("cor_dof"), sigma,
                           source, **sizes)
            # files written before the headline keys: the scatter model's mean if it is there
            if "cor_mean [-]" in data:
                return cls(number("cor_mean [-]"), number("cor_mean_se [-]"),
                           integer("cor_mean_dof"), number("cor_scatter_sigma [-]"), source,
                           **sizes)
            samples = integer("fit samples") if "fit samples" in data else 1000
            return cls(number("cor [-]"), number("cor_se [-]"), max(samples - 5, 1), 0.0,
                       source, **sizes)
        except ValueError as error:
            message = str(error)
            raise ValueError(message if message.startswith(where) else
                             f"{where}: {message}") from None

    def draws(self, members: int, seed: int = 0, *, scatter: bool = True) -> np.ndarray:
        """``members`` CORs [-]: member 0 the mean, the others drawn (see the module)."""
        if isinstance(members, bool) or not isinstance(members, (int, np.integer)) \
                or members < 2:
            raise ValueError(f"members must be an integer >= 2, got {members!r}")
        rng = np.random.default_rng(seed)
        values = self.mean + self.mean_se * rng.standard_t(self.dof, members)
        if scatter:
            values = values + self.sigma * rng.standard_normal(members)
        values[0] = self.mean
        return np.clip(values, COR_FLOOR, 1.0)

    def describe(self) -> str:
        """One line: the mean, its interval and the scatter."""
        import scipy.stats

        half = float(scipy.stats.t.ppf(0.975, self.dof)) * self.mean_se
        # one decimal beyond the interval's half-width, at least 4
        digits = max(4, int(math.ceil(-math.log10(half))) + 1) if half > 0 else 6
        return (f"COR {self.mean:.{digits}f} (95 % interval {self.mean - half:.{digits}f} to "
                f"{self.mean + half:.{digits}f}), impact-to-impact scatter sigma "
                f"{self.sigma:.4f}"
                + (f", from {self.source}" if self.source else ""))


@dataclass(frozen=True)
class CalibratedEnsemble:
    """Runs of one block and motion over the calibrated COR distribution.

    Attributes
    ----------
    block : Block
    motion : Motion
    cor : CalibratedCor
    members : pandas.DataFrame
        One row per member: the batch columns and ``cor [-]``.
    summary : dict
        :func:`shaketable.core.ensemble.verdict_statistics` plus the COR's spread.
    scatter : bool
        Whether the scatter sigma was drawn.
    """

    block: Block
    motion: Motion
    cor: CalibratedCor
    members: pd.DataFrame
    summary: dict[str, Any]
    scatter: bool = True

    def to_frame(self) -> pd.DataFrame:
        """One row per member (a copy)."""
        return self.members.copy()

    def describe(self) -> str:
        """P(overturn) with its interval and the peak theta/alpha with its 5-95 % range."""
        s = self.summary
        peaks = ("every member overturns" if not s["standing members"] else
                 f"max θ/α of the {s['standing members']} standing members: median "
                 f"{s['median max theta/alpha [-]']:.3f}, 5-95 % "
                 f"{s['p05 max theta/alpha [-]']:.3f} to {s['p95 max theta/alpha [-]']:.3f}")
        return (f"P(overturn) = {s['P(overturn) [-]']:.3f} (Wilson 95 % {s['P low [-]']:.3f} to "
                f"{s['P high [-]']:.3f}) over {s['members']} members drawn from the calibrated "
                f"COR (5-95 % {s['cor p05 [-]']:.4f} to {s['cor p95 [-]']:.4f}); {peaks}")

    def plot(self, ax: Any = None) -> Any:
        """max theta/alpha (or overturned) against each member's COR."""
        from shaketable.plots.calibration import plot_calibrated_ensemble

        return plot_calibrated_ensemble(self, ax=ax)


def calibrated_ensemble(block: Block, motion: Motion, cor: CalibratedCor, *,
                        members: int = 200, seed: int = 0, scatter: bool = True,
                        duration: float | None = None, method: str = "fast",
                        threads: int | None = None) -> CalibratedEnsemble:
    """Run ``block`` under ``motion`` with ``members`` CORs drawn from a calibration.

    Parameters
    ----------
    block : Block
    motion : Motion
        Ground accelerations [m/s^2].
    cor : CalibratedCor
        The calibrated COR (:meth:`CalibratedCor.from_json`).
    members : int
        Ensemble size (member 0 runs the mean COR).
    seed : int
        Seed of the draws.
    scatter : bool
        Draw the impact-to-impact scatter too (default) or the mean's
        uncertainty alone.
    duration, method, threads
        As in :func:`shaketable.models.rocking.batch.simulate_cases`.
    """
    if not isinstance(block, Block):
        raise TypeError(f"calibrated_ensemble: block must be a shaketable Block, got "
                        f"{type(block).__name__}")
    if not isinstance(cor, CalibratedCor):
        raise TypeError(f"calibrated_ensemble: cor must be a CalibratedCor (e.g. "
                        f"CalibratedCor.from_json('calibration.json')), got {type(cor).__name__}")
    if not isinstance(motion, Motion):
        raise TypeError(f"calibrated_ensemble: motion must be a shaketable Motion, got "
                        f"{type(motion).__name__}")
    if isinstance(members, bool) or not isinstance(members, (int, np.integer)) \
            or not 2 <= members <= MAX_MEMBERS:
        raise ValueError(f"calibrated_ensemble: members must be an integer from 2 to "
                         f"{MAX_MEMBERS}, got {members!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"calibrated_ensemble: seed must be a non-negative integer, got "
                         f"{seed!r}")
    if not isinstance(scatter, (bool, np.bool_)):
        raise TypeError(f"calibrated_ensemble: scatter must be True or False, got {scatter!r}")
    mismatch = cor.size_mismatch(block)
    if mismatch is not None:
        warnings.warn(mismatch, CalibrationMismatchWarning, stacklevel=2)
    cors = cor.draws(members, seed, scatter=scatter)
    cases = [Case(block, motion, float(value)) for value in cors]
    frame = simulate_cases(cases, threads=threads, method=method, duration=duration)
    frame["member"] = np.arange(members)
    frame["cor [-]"] = cors
    summary = verdict_statistics(frame["overturned"].to_numpy(),
                                 frame["max_theta_ratio [-]"].to_numpy())
    summary.update({"cor mean [-]": cor.mean, "cor mean se [-]": cor.mean_se,
                    "cor scatter sigma [-]": cor.sigma, "scatter drawn": scatter,
                    "cor p05 [-]": float(np.percentile(cors, 5)),
                    "cor p95 [-]": float(np.percentile(cors, 95)),
                    "calibration": cor.source, "seed": seed})
    return CalibratedEnsemble(block, motion, cor, frame, summary, scatter)
