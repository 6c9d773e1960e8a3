"""Benchmarks of the solvers: accuracy against run time (work-precision).

Nothing here is a pass/fail test; the functions measure and return tables
(pandas) that :mod:`shaketable.commands.bench` and ``benchmarks/`` write out.

* :func:`benchmark_cases` -- the cases: the report's free rocking (Fig. 3.4),
  harmonic (Figs. 3.7, 3.8) and Pacoima Dam (Fig. 4.1) runs and the extreme
  cases (tiny and huge, slender and stocky blocks, 50 Hz input, a 100 s record
  at 200 Hz, stiff prestress rods, shaking at 1.0001 and 0.9999 times Eq. (2-1),
  COR 0 and 1, the decaying cascade of impacts, vertical acceleration reaching
  -g).
* :func:`work_precision` -- every method at several settings against a
  ``reference`` run at the tightest tolerance: the error in max |theta| and in
  the event times, and the median run time.
* :func:`convergence_orders` -- slope of log error against log step per method.
* :func:`accuracy_table` -- ``fast`` at its default against ``reference`` at its
  default (the acceptance check: 1e-8 relative).
* :func:`pacoima_timing`, :func:`first_call_seconds`, :func:`batch_throughput`
  -- the speed figures.
* :func:`results_markdown` -- the Markdown snippet (``benchmarks/RESULTS.md``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block, PrestressRods
from shaketable.core.motion import Motion
from shaketable.models.api import simulate
from shaketable.models.rocking.result import RockingResult

#: Relative accuracy the fast engine must reach against ``reference`` (times, max |theta|).
ACCEPT_RELATIVE = 1e-8

#: The speed targets on the Pacoima Dam run: warm ms per run, speed-up over reference.
TARGET_FAST_MS = 2.0

TARGET_SPEED_UP = 300.0

#: Absolute accuracy of max |theta| [rad] for tiny responses.
ACCEPT_ABSOLUTE_THETA = 1e-10

#: Impacts compared: those before this time [s].
IMPACT_WINDOW = 20.0

#: Errors below this are not used to measure orders of convergence: the truth (reference at
#: rtol 2.5e-14) is itself up to 5e-11 off on these cases (stiff rods).
ORDER_ERROR_FLOOR = 1e-10

#: Settings of each method in the work-precision study.
FAST_RTOLS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 5e-12, 1e-12, 1e-13)

PC_SUBDIVISIONS = (1, 2, 4, 8, 16, 32, 64)

REFERENCE_RTOLS = (1e-8, 1e-10, 1e-12)

#: Fewer settings for ``--quick`` iterations.
QUICK_FAST_RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)

QUICK_PC_SUBDIVISIONS = (1, 4, 16, 64)

#: ``--quick`` runs the SciPy reference at its default tolerance only (the point the
#: accuracy table uses): each reference run costs about as much at 1e-8 as at 1e-12 (SciPy's
#: per-interval overhead, not the tolerance, sets it), and a 1e-8 point cost 3.9 s of the
#: quick study's 14 s of reference runs; the full study draws its curve.
QUICK_REFERENCE_RTOLS = (1e-12,)

#: The truth: ``reference`` at the tightest tolerance SciPy accepts (100 eps).
TRUTH_RTOL = 2.5e-14

#: Default tolerance of ``method="reference"`` (:func:`shaketable.models.api`) [-].
REFERENCE_DEFAULT_RTOL = 1e-12


@dataclass(frozen=True)
class Case:
    """One benchmark run: block, motion (None: free rocking) and the rocking options."""

    name: str
    description: str
    block: Block
    motion: Motion | None
    cor: float
    theta0: float = 0.0
    duration: float | None = None
    options: dict[str, Any] = field(default_factory=dict)
    extreme: bool = False
    #: ``reference`` tolerances of the study for this case (None: all of them); a
    #: long record skips the intermediate ones, each a minute of SciPy.
    reference_rtols: tuple[float, ...] | None = None

    def run(self, method: str = "fast", **options: Any) -> RockingResult:
        """``simulate`` this case with ``method`` and extra options (rtol, subdivisions...)."""
        return simulate(self.block, self.motion, cor=self.cor, theta0=self.theta0,
                        duration=self.duration, method=method, **{**self.options, **options})

    @property
    def intervals(self) -> int:
        """Number of input intervals (sample steps) of the run."""
        if self.motion is None:
            if self.duration is None:
                raise ValueError(f"case {self.name!r}: free rocking needs a duration")
            return int(math.ceil(self.duration / 0.005 - 1e-9))
        n = self.motion.t.size - 1
        if self.duration is not None:
            n = int(round(self.duration / self.motion.dt))
        return n


# --------------------------------------------------------------------------- motions
def _harmonic(frequency: float, horizontal_g: float, vertical_g: float = 0.0,
              duration: float = 10.0, dt: float = 0.01) -> Motion:
    from shaketable.ground.generators import harmonic

    return harmonic(frequency, horizontal=horizontal_g * G, vertical=vertical_g * G,
                    duration=duration, dt=dt)


def threshold_harmonic(block: Block, factor: float, frequency: float = 2.0,
                       duration: float = 2.0, dt: float = 0.005) -> Motion:
    """Sine of amplitude ``factor`` times Eq. (2-1)'s level, a sample on every crest.

    The amplitude is ``factor * (B/H) g`` (plus the rods' prestress), so the
    block rocks only if ``factor > 1``; ``dt`` must divide a quarter period so
    that the crest is sampled (the motion is linear between samples).
    """
    level = factor * block.rocking_threshold()
    t = np.arange(0.0, duration + dt / 2, dt)
    quarter = 1.0 / (4.0 * frequency)
    crest = np.isclose(np.mod(t - quarter, 2 * quarter), 0.0, atol=1e-9)
    values = np.sin(2 * np.pi * frequency * t)
    values[crest] = np.sign(values[crest])  # exactly +-1 on the crests
    return Motion(t, level * values, None,
                  name=f"{frequency:g} Hz at {factor:g} x Eq. (2-1)")


def vertical_to_minus_g(duration: float = 2.0, dt: float = 0.01, t_airborne: float = 1.37,
                        horizontal_g: float = 0.3, frequency: float = 2.0) -> Motion:
    """Horizontal sine and a vertical ramp that reaches -g at ``t_airborne`` [s]."""
    t = np.arange(0.0, duration + dt / 2, dt)
    vertical = -G * t / t_airborne
    return Motion(t, horizontal_g * G * np.sin(2 * np.pi * frequency * t), vertical,
                  name=f"vertical reaching -g at {t_airborne:g} s")


def long_record(duration: float = 100.0, dt: float = 0.005, seed: int = 1,
                pga_g: float = 0.3) -> Motion:
    """A 100 s artificial record (A-1 substitute, PGA ``pga_g`` [g]) sampled at 200 Hz.

    At 0.3 g (1.2 times Eq. (2-1) for 16 x 4 ft) the block rocks in short
    episodes that end in a summed cascade, so the run is well conditioned.
    At 0.5 g the same block rocks for tens of seconds and the rocking is
    chaotic: two runs differing by 1e-12 drift apart like e^(0.5 t), and no
    solver (not the reference at rtol 1e-12 against 2.5e-14 either) agrees to
    1e-8 past about 20 s.
    """
    from shaketable.ground.generators import artificial

    return artificial("A-1", seed=seed, duration=duration, dt=dt, pga=pga_g * G)


# --------------------------------------------------------------------------- cases
def benchmark_cases(extreme: bool = True, quick: bool = False,
                    names: Sequence[str] | None = None) -> list[Case]:
    """The benchmark cases: the report's runs, then (``extreme``) the extreme ones.

    Parameters
    ----------
    extreme : bool
        Include the extreme cases (listed in the module docstring).
    quick : bool
        For iterations: without ``names``, the report's four cases only (every
        method of the study runs on each of them, so every method still gets its
        points; the extreme cases, whose SciPy truths cost most of the study's time,
        are in the full run); a named long record is cut to 20 s.
    names : list of str, optional
        Keep only these cases (any of them, also with ``quick``); an unknown name
        raises ``ValueError`` listing the known ones.
    """
    long_duration = 20.0 if quick else 100.0
    from shaketable.ground import records

    block_30x6 = Block.parse("30x6in")
    pacoima = records.load("pacoima-dam-s16e")
    cases = [
        Case("free-rocking", "Fig. 3.4: 30 x 6 in, COR 0.925, released at 0.5 alpha, 8 s",
             block_30x6, None, 0.925, theta0=0.5 * block_30x6.alpha, duration=8.0),
        Case("harmonic-2hz-0.5g", "Fig. 3.7: 30 x 6 in, COR 0.925, 2 Hz 0.5 g (overturns)",
             block_30x6, _harmonic(2.0, 0.5), 0.925),
        Case("harmonic-2hz-vertical", "Fig. 3.8: 30 x 6 in, COR 0.925, 2 Hz 0.38 g H + 0.33 g V",
             block_30x6, _harmonic(2.0, 0.38, 0.33), 0.925),
        Case("pacoima-16x4ft", "Fig. 4.1: 16 x 4 ft, COR 1.0, Pacoima Dam S16E + vertical",
             Block.parse("16x4ft"), pacoima, 1.0),
    ]
    if not extreme or (quick and names is None):
        return _select(cases, names)
    tiny = Block.parse("3x1cm")
    slender = Block.from_slenderness(R=1.0, alpha=0.02)
    stocky = Block.parse("1x1m")
    rods = Block.parse("8x2ft", rods=PrestressRods.from_inches(40, 0.4, 12))
    cases += [
        Case("tiny-3x1cm", f"3 x 1 cm block (p = {tiny.p:.1f} rad/s), COR 0.9, 5 Hz 0.5 g, 3 s",
             tiny, _harmonic(5.0, 0.5, duration=3.0, dt=0.002), 0.9, extreme=True),
        Case("huge-20x5m", "20 x 5 m block, COR 0.95, Pacoima Dam S16E + vertical",
             Block.parse("20x5m"), pacoima, 0.95, extreme=True),
        Case("slender-alpha-0.02", "alpha = 0.02 rad, R = 1 m, COR 0.95, 1 Hz 0.03 g, 10 s",
             slender, _harmonic(1.0, 0.03, duration=10.0), 0.95, extreme=True),
        Case("stocky-1x1m", "H/B = 1 (1 x 1 m), COR 0.9, 3 Hz 1.5 g, 5 s",
             stocky, _harmonic(3.0, 1.5, duration=5.0), 0.9, extreme=True),
        Case("50hz-5g", "30 x 6 in, COR 0.925, 50 Hz 5 g at 1 kHz, 2 s",
             block_30x6, _harmonic(50.0, 5.0, duration=2.0, dt=0.001), 0.925, extreme=True),
        Case("long-100s-200hz", "16 x 4 ft, COR 0.95, 100 s A-1 substitute (0.3 g) at 200 Hz",
             Block.parse("16x4ft"), long_record(duration=long_duration), 0.95, extreme=True,
             reference_rtols=(REFERENCE_DEFAULT_RTOL,)),
        Case("stiff-rods", "8 x 2 ft, rods K = 40 W/in, F0 = 0.4 W at mid-width, COR 0.95, "
             "Pacoima Dam S16E + vertical, 15 s",
             rods, pacoima, 0.95, duration=15.0, extreme=True),
        Case("threshold-1.0001", "30 x 6 in, COR 0.925, 2 Hz at 1.0001 x Eq. (2-1)",
             block_30x6, threshold_harmonic(block_30x6, 1.0001), 0.925, extreme=True),
        Case("threshold-0.9999", "30 x 6 in, COR 0.925, 2 Hz at 0.9999 x Eq. (2-1)",
             block_30x6, threshold_harmonic(block_30x6, 0.9999), 0.925, extreme=True),
        Case("cor-0", "30 x 6 in, COR 0, 2 Hz 0.4 g, 4 s",
             block_30x6, _harmonic(2.0, 0.4, duration=4.0), 0.0, extreme=True),
        Case("cor-1", "30 x 6 in, COR 1, released at 0.6 alpha, 20 s",
             block_30x6, None, 1.0, theta0=0.6 * block_30x6.alpha, duration=20.0, extreme=True),
        Case("cascade", "36 x 9 in, COR 0.7, released at 0.9 alpha: the decaying cascade, 4 s",
             Block.parse("36x9in"), None, 0.7, theta0=0.9 * Block.parse("36x9in").alpha,
             duration=4.0, extreme=True),
        Case("vertical-to-minus-g", "30 x 6 in, COR 0.925, 2 Hz 0.3 g, vertical ramp to -g "
             "at 1.37 s", block_30x6, vertical_to_minus_g(), 0.925, extreme=True),
    ]
    return _select(cases, names)


def _select(cases: list[Case], names: Sequence[str] | None) -> list[Case]:
    if names is None:
        return cases
    known = {case.name: case for case in cases}
    unknown = [name for name in names if name not in known]
    if unknown:
        raise ValueError(f"unknown benchmark case(s) {unknown}; known: {sorted(known)}")
    return [known[name] for name in names]


# --------------------------------------------------------------------------- comparisons
class RockingLike(Protocol):
    """What :func:`compare` reads of a run: a RockingResult, or a planar run in the rocking
    limit (:class:`shaketable.studies.planar_work_precision.RockingView`)."""

    @property
    def max_abs_theta(self) -> float: ...
    @property
    def impact_times(self) -> np.ndarray: ...
    @property
    def t_start(self) -> float: ...
    @property
    def t_unstable(self) -> float: ...
    @property
    def t_overturn(self) -> float: ...
    @property
    def t_rest(self) -> float: ...
    @property
    def t_airborne(self) -> float: ...
    @property
    def overturned(self) -> bool: ...


def _events(result: RockingLike, window: float = IMPACT_WINDOW) -> np.ndarray:
    times = result.impact_times[result.impact_times < window]
    return times


def compare(result: RockingLike, truth: RockingLike,
            window: float = IMPACT_WINDOW) -> dict[str, Any]:
    """Errors of ``result`` against ``truth`` (two RockingResults of one case, or a
    :class:`RockingLike` view of another model's run).

    Returns the relative error of max |theta| (and the absolute one [rad]), the
    largest relative error of the event times (impacts before 20 s, start,
    unstable, overturn and airborne times, and the last rest time when it is
    before 20 s in both), whether the number of impacts before 20 s and the
    overturn verdict agree. A time present in one run and not in the other
    counts as an infinite error.
    """
    theta_abs = abs(result.max_abs_theta - truth.max_abs_theta)
    theta_rel = theta_abs / truth.max_abs_theta if truth.max_abs_theta > 0 else theta_abs
    errors = []
    a, b = _events(result, window), _events(truth, window)
    n = min(a.size, b.size)
    if n:
        errors.append(np.max(np.abs(a[:n] - b[:n]) / np.abs(b[:n])))
    for name in ("t_start", "t_unstable", "t_overturn", "t_rest", "t_airborne"):
        x, y = getattr(result, name), getattr(truth, name)
        if name == "t_rest" and not (x < window and y < window):
            continue  # the last rest time: compared only inside the window, like impacts
        if np.isfinite(x) and np.isfinite(y) and y != 0:
            errors.append(abs(x - y) / abs(y))
        elif np.isfinite(x) != np.isfinite(y):
            errors.append(math.inf)
    return {
        "error max_theta [-]": theta_rel,
        "error max_theta [rad]": theta_abs,
        "error events [-]": max(errors) if errors else 0.0,
        "impacts": int(a.size), "impacts truth": int(b.size),
        "same impacts": bool(a.size == b.size),
        "same verdict": bool(result.overturned == truth.overturned),
    }
