"""Work-precision of the coupled planar block: error against run time.

Two kinds of rows, both drawn by ``shaketable bench`` beside the rocking methods:

* :func:`rocking_limit_rows` -- the rocking limit. With friction that cannot be exceeded
  (:data:`AMPLE_FRICTION`) the planar block is the report's rocking block, so the compiled
  planar engine (method ``"planar"``) and the SciPy planar reference
  (``"planar-reference"``) are measured on a rocking benchmark case against *that case's
  rocking truth* (the rocking ``reference`` at rtol 2.5e-14,
  :func:`shaketable.studies.work_precision.truth_run`) with the rocking study's own
  :func:`~shaketable.studies.benchmark_cases.compare`: the rows join the rocking study's
  frame and its panel, the same columns.
* :func:`planar_work_precision` -- the coupled cases of :func:`planar_cases` (rock and
  slide-rock with impacts), where no rocking method applies: the planar engine and the
  planar reference at several rtol, each against the planar reference at
  :data:`PLANAR_TRUTH_RTOL` (the tightest tolerance it is run at; the code under test at
  the same setting is never its own truth). Errors (:func:`compare_planar`): max |theta|,
  the times of the mode changes and impacts, the peak slip.
* :func:`moreau_jean_rows` -- the independent Moreau-Jean time stepping
  (:mod:`shaketable.models.planar.moreau`, method ``"moreau-jean"``) at several steps h
  on the first seconds (:data:`MOREAU_WINDOW`) of the coupled cases with the plastic Newton
  law it converges to (``cor="housner"``), against the planar reference at
  :data:`PLANAR_TRUTH_RTOL` on the same window and law: the errors of max |theta| and of
  the peak slip (no event times: a time stepper has none). First order in h.

Nothing here is a pass/fail test; the functions measure and return pandas frames.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.planar.result import EVENT_KINDS
from shaketable.models.sliding.result import Friction
from shaketable.studies.benchmark_cases import Case, compare

if TYPE_CHECKING:
    import pandas as pd

#: Called with each case's name as the study reaches it.
Progress = Callable[[str], object]

#: Methods of this study, as written in the frames' ``method`` column.
PLANAR_METHODS = ("planar", "planar-reference")

#: Tolerances of the compiled planar engine (``simulate(..., friction=..., rtol=...)``).
PLANAR_RTOLS = (1e-6, 1e-8, 1e-10, 1e-11, 1e-12, 1e-13)

#: Tolerances of the SciPy planar reference (``models.planar.reference``).
PLANAR_REFERENCE_RTOLS = (1e-6, 1e-8, 1e-10, 1e-11, 1e-12)

#: Fewer settings for ``--quick``.
QUICK_PLANAR_RTOLS = (1e-6, 1e-10, 1e-12, 1e-13)

#: The planar reference at its default tolerance only (as the rocking ``reference``
#: under ``--quick``, :data:`~shaketable.studies.benchmark_cases.QUICK_REFERENCE_RTOLS`).
QUICK_PLANAR_REFERENCE_RTOLS = (1e-12,)

#: Steps of the Moreau-Jean rows [s] (each a quarter of the last: first order divides the
#: error by about 4 per step).
MOREAU_STEPS = (1e-3, 2.5e-4, 6.25e-5)

QUICK_MOREAU_STEPS = (1e-3, 2.5e-4)

#: The coupled cases that get Moreau-Jean rows and the window they are run on [s]: the
#: first 1.2 s of the 3 Hz case (rest, rock, slide-rock and 4 impacts) and the first 3.5 s
#: of Pacoima Dam (rock with 110 impacts, most in a cascade). Past a few impacts of the 3 Hz
#: case the errors of a first-order scheme stop falling monotonically at affordable steps
#: (its whole 3 s: 1-5e-2 at h = 1e-3 ... 6.25e-5), and the whole 40 s record costs
#: seconds per run.
MOREAU_WINDOW = {"slide-rock-3hz": 1.2, "pacoima-16x4ft-mu0.3": 3.5}

#: The cases of :data:`MOREAU_WINDOW` that ``--quick`` runs.
QUICK_MOREAU_CASES = ("slide-rock-3hz",)

#: The coupled cases ``--quick`` runs (the planar engine and reference still get their
#: points on both kinds of panel: this case's and the rocking limit's); Pacoima's two
#: SciPy runs of 40 s cost a second, half the quick study's planar part.
QUICK_PLANAR_CASES = ("slide-rock-3hz",)

#: Method name of the Moreau-Jean rows.
MOREAU_METHOD = "moreau-jean"

#: The coupled cases' truth: the planar reference at the tightest tolerance it is run at
#: (it accepts 1e-14, where DOP853's rtol/100 absolute tolerances are at rounding).
PLANAR_TRUTH_RTOL = 1e-13

#: Friction that cannot be exceeded on the rocking-limit case: mu_s = mu_d = 10 (the
#: friction a rocking block needs stays below B/H-like ratios, far under 10).
AMPLE_FRICTION = Friction(10.0)

#: The rocking benchmark case that gets the planar rows (Fig. 3.4, free rocking of the
#: 30 x 6 in block: 218 impacts and a summed cascade, no slip, no overturn; an overturning
#: case would not do, see docs/planar.md check 1: the planar block slips before it falls).
ROCKING_LIMIT_CASE = "free-rocking"

#: Event kind of the compiled result that marks |theta| = alpha: not a mode change and not
#: an event of the reference (which gives ``t_unstable``).
_UNSTABLE = EVENT_KINDS.index("unstable")


@dataclass(frozen=True)
class PlanarCase:
    """One coupled benchmark run: block, motion, COR and friction (no rocking method)."""

    name: str
    description: str
    block: Block
    motion: Motion | None
    cor: float | str
    friction: Friction
    theta0: float = 0.0
    duration: float | None = None

    def run(self, method: str = "planar", rtol: float | None = None):
        """Run this case with ``"planar"`` (compiled) or ``"planar-reference"`` (SciPy)."""
        return run_planar(method, self.block, self.motion, cor=self.cor,
                          friction=self.friction, theta0=self.theta0,
                          duration=self.duration, rtol=rtol)


def run_planar(method: str, block: Block, motion: Motion | None, *, cor, friction: Friction,
               theta0: float = 0.0, duration: float | None = None,
               rtol: float | None = None):
    """One run of the planar block by ``method`` (one of :data:`PLANAR_METHODS`).

    Returns a :class:`~shaketable.models.planar.result.PlanarResult` (``"planar"``) or a
    :class:`~shaketable.models.planar.reference_result.PlanarReferenceResult`.
    """
    if method == "planar":
        from shaketable.models.planar.run import simulate_planar

        return simulate_planar(block, motion, cor=cor, friction=friction, theta0=theta0,
                               duration=duration, rtol=rtol)
    if method == "planar-reference":
        from shaketable.models.planar.reference import simulate_reference

        options = {} if rtol is None else {"rtol": float(rtol)}
        return simulate_reference(block, motion, cor=cor, friction=friction, theta0=theta0,
                                  duration=duration, **options)
    raise ValueError(f"method must be one of {PLANAR_METHODS}, got {method!r}")


def planar_cases(names: Sequence[str] | None = None, quick: bool = False) -> list[PlanarCase]:
    """The coupled cases (each visits rock and slide-rock with impacts).

    * ``slide-rock-3hz`` -- the 30 x 6 in block (B/H = 0.2), mu_s 0.25, mu_d 0.22, COR 0.9,
      3 Hz 0.6 g for 3 s with a half-cycle ramp, sampled every 0.05 s: it rocks,
      slide-rocks and impacts 16 times. The coarse samples let DOP853 take steps its
      tolerance sets (at 5 ms one step per sample is exact to rounding at any rtol, which
      measures nothing).
    * ``pacoima-16x4ft-mu0.3`` -- Pacoima Dam S16E + vertical (100 samples/s), 16 x 4 ft,
      COR 0.95, mu = 0.3: rock, slide-rock, overturn at 9.98 s; the report's block and
      record, where the input's samples bound the steps of both solvers.

    ``names`` keeps only those (an unknown name raises ``ValueError`` listing the known);
    ``quick`` without ``names`` keeps :data:`QUICK_PLANAR_CASES`.
    """
    from shaketable.ground import records
    from shaketable.ground.generators import harmonic

    cases = [
        PlanarCase("slide-rock-3hz", "30 x 6 in, mu_s 0.25, mu_d 0.22, COR 0.9, 3 Hz 0.6 g "
                   "(ramped), 3 s at 0.05 s: rock, slide-rock, 16 impacts",
                   Block.from_inches(30, 6),
                   harmonic(3.0, horizontal=0.6 * G, duration=3.0, dt=0.05, ramp=0.25),
                   0.9, Friction(0.25, 0.22)),
        PlanarCase("pacoima-16x4ft-mu0.3", "16 x 4 ft, mu 0.3, COR 0.95, Pacoima Dam S16E + "
                   "vertical: rock, slide-rock, overturns", Block.parse("16x4ft"),
                   records.load("pacoima-dam-s16e"), 0.95, Friction(0.3)),
    ]
    if names is None and quick:
        names = QUICK_PLANAR_CASES
    if names is None:
        return cases
    known = {case.name: case for case in cases}
    unknown = [name for name in names if name not in known]
    if unknown:
        raise ValueError(f"unknown planar benchmark case(s) {unknown}; known: {sorted(known)}")
    return [known[name] for name in names]


def planar_case_names() -> tuple[str, ...]:
    """Names of :func:`planar_cases` (without loading their records)."""
    return ("slide-rock-3hz", "pacoima-16x4ft-mu0.3")


# --------------------------------------------------------------------------- comparisons
def _merged(times, before, after) -> tuple[np.ndarray, np.ndarray]:
    """Mode changes at one instant merged into one, as ``tests/models/planar/test_planar_agreement``.

    The two implementations write some instants differently with the same physics (a
    summed cascade is ``impact rock->rock`` + ``cascade rock->rest`` in the reference and
    one ``impact rock->rest`` in the compiled result): events within 1e-12 s are one.
    Returns the times [s] and an (n, 2) array of (mode before, mode after).
    """
    merged: list[list[float]] = []
    for time_, first, last in zip(times, before, after):
        if merged and abs(time_ - merged[-1][0]) <= 1e-12:
            merged[-1][2] = int(last)
        else:
            merged.append([float(time_), int(first), int(last)])
    found = np.array(merged, dtype=float).reshape(-1, 3)
    return found[:, 0], found[:, 1:].astype(int)


def transitions(result) -> tuple[np.ndarray, np.ndarray]:
    """The events of either planar result as merged (times [s], (mode before, after)).

    Impacts, mode changes, slip reversals, cascades, overturn; the compiled result's
    "unstable" (|theta| = alpha) is left out (the reference has no such event).
    """
    if hasattr(result, "events"):  # PlanarResult: (time, kind, before, after, ...)
        events = np.asarray(result.events).reshape(-1, 6)
        events = events[events[:, 1] != _UNSTABLE]
        return _merged(events[:, 0], events[:, 2], events[:, 3])
    return _merged(result.event_times, result.event_mode_before, result.event_mode_after)


def _relative(value: float, truth: float) -> float:
    if not (math.isfinite(value) and math.isfinite(truth)):
        return 0.0 if math.isfinite(value) == math.isfinite(truth) else math.inf
    return abs(value - truth) / abs(truth) if truth != 0 else abs(value - truth)


def compare_planar(result, truth) -> dict[str, Any]:
    """Errors of a planar run (either result type) against a planar truth of the same case.

    Returns the relative error of max |theta| and of the peak slip, the largest relative
    error of the event times (:func:`transitions`; compared up to the first event whose
    modes differ, a missing or extra event counting as an infinite error), the overturn
    time's relative error joined to the event error, the event counts and whether the
    sequences and verdicts agree (the same columns as the rocking study's
    :func:`~shaketable.studies.benchmark_cases.compare` where they mean the same).
    """
    times, modes = transitions(result)
    truth_times, truth_modes = transitions(truth)
    n = min(times.size, truth_times.size)
    differ = np.flatnonzero(np.any(modes[:n] != truth_modes[:n], axis=1))
    matched = int(differ[0]) if differ.size else n
    same = bool(matched == times.size == truth_times.size)
    errors = [0.0]
    if matched:
        errors.append(float(np.max(np.abs(times[:matched] - truth_times[:matched])
                                   / np.maximum(np.abs(truth_times[:matched]), 1e-300))))
    if not same:
        errors.append(math.inf)
    errors.append(_relative(result.t_overturn, truth.t_overturn))
    theta_abs = abs(result.max_abs_theta - truth.max_abs_theta)
    return {
        "error max_theta [-]": _relative(result.max_abs_theta, truth.max_abs_theta),
        "error max_theta [rad]": theta_abs,
        "error events [-]": max(errors),
        "error peak slip [-]": _relative(result.peak_slip, truth.peak_slip),
        "error peak slip [m]": abs(result.peak_slip - truth.peak_slip),
        "impacts": int(len(result.impact_times)), "impacts truth": int(len(truth.impact_times)),
        "events": int(times.size), "events truth": int(truth_times.size),
        "same impacts": bool(len(result.impact_times) == len(truth.impact_times)),
        "same events": same,
        "same verdict": bool(result.overturned == truth.overturned),
    }


@dataclass(frozen=True)
class RockingView:
    """The quantities :func:`~shaketable.studies.benchmark_cases.compare` reads, from a
    planar run in the rocking limit (no slip, no flight: ``t_airborne`` is NaN)."""

    max_abs_theta: float
    impact_times: np.ndarray
    t_start: float
    t_unstable: float
    t_overturn: float
    t_rest: float
    overturned: bool
    t_airborne: float = math.nan


def rocking_view(result, theta0: float = 0.0) -> RockingView:
    """A planar result (either type) as a :class:`RockingView`.

    ``t_start`` is the first departure from rest (the compiled result's ``t_start``; the
    reference's first "start" event); a block released tilted (``theta0 != 0``) starts
    at 0, as the rocking engine reports.
    """
    if hasattr(result, "t_start"):
        start = result.t_start
    else:
        starts = result.events_of("start")
        start = float(starts[0]) if starts.size else math.nan
    if theta0 != 0.0 and not math.isfinite(start):
        start = 0.0
    return RockingView(max_abs_theta=float(result.max_abs_theta),
                       impact_times=np.asarray(result.impact_times, dtype=float),
                       t_start=float(start), t_unstable=float(result.t_unstable),
                       t_overturn=float(result.t_overturn), t_rest=float(result.t_rest),
                       overturned=bool(result.overturned))


# --------------------------------------------------------------------------- the study
def method_settings(quick: bool = False) -> list[tuple[str, str, dict[str, Any]]]:
    """(method, label, options) of the planar rows: the engine's and the reference's rtol."""
    engine = QUICK_PLANAR_RTOLS if quick else PLANAR_RTOLS
    reference = QUICK_PLANAR_REFERENCE_RTOLS if quick else PLANAR_REFERENCE_RTOLS
    return ([("planar", f"rtol={r:g}", {"rtol": r}) for r in engine]
            + [("planar-reference", f"rtol={r:g}", {"rtol": r}) for r in reference])


def timed(run: Callable[[], Any], compiled: bool, repeats: int) -> tuple[Any, float]:
    """The result of ``run`` and its median wall time [s]; a compiled engine gets an
    untimed first call (numba cache load) and ``repeats`` timed ones, a SciPy engine one
    (each call is a tenth of a second or more; the rocking study's ``reference`` too)."""
    if compiled:
        run()
    count = max(1, repeats) if compiled else 1
    times, result = [], None
    for _ in range(count):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return result, float(np.median(times))


def _row(case_name: str, method: str, label: str, options: dict[str, Any], seconds: float,
         errors: dict[str, Any], result, truth, truth_label: str,
         truth_rtol: float) -> dict[str, Any]:
    return {"case": case_name, "method": method, "setting": label,
            "rtol": options.get("rtol", math.nan), "subdivisions": math.nan,
            "time [s]": seconds, **errors,
            "steps": getattr(result, "statistics", {}).get("steps", 0),
            "rejected": getattr(result, "statistics", {}).get("rejected", 0),
            "evaluations": getattr(result, "statistics", {}).get("evaluations", 0),
            "status": result.status, "status truth": truth.status, "truth": truth_label,
            "truth rtol": truth_rtol}


def rocking_limit_rows(case: Case, truth, settings=None, repeats: int = 5,
                       friction: Friction = AMPLE_FRICTION) -> list[dict[str, Any]]:
    """Rows of the planar engine and reference on a rocking case with ample friction.

    Each run (``case``'s block, motion, COR, theta0 and duration with ``friction``) is
    compared by :func:`~shaketable.studies.benchmark_cases.compare` with ``truth``, the
    rocking case's truth (:func:`shaketable.studies.work_precision.truth_run`): the rows
    have the rocking study's columns and join its frame (``mean step [s]`` is NaN).
    """
    if case.options:
        raise ValueError(f"case {case.name!r}: the planar rows take a case without rocking "
                         f"options (got {sorted(case.options)})")
    settings = method_settings() if settings is None else settings
    truth_rtol = truth.statistics.get("truth rtol", math.nan)
    rows = []
    for method, label, options in settings:
        def run(method=method, options=options):
            return run_planar(method, case.block, case.motion, cor=case.cor,
                              friction=friction, theta0=case.theta0,
                              duration=case.duration, rtol=options.get("rtol"))
        result, seconds = timed(run, method == "planar", repeats)
        errors = compare(rocking_view(result, case.theta0), truth)
        row = _row(case.name, method, label, options, seconds, errors, result, truth,
                   "reference", truth_rtol)
        del row["truth"]  # the case's own truth, as every row of the rocking frame
        row["mean step [s]"] = math.nan
        rows.append(row)
    return rows


def planar_truth(case: PlanarCase, cache: dict | None = None):
    """The truth of a coupled case: the planar reference at :data:`PLANAR_TRUTH_RTOL`
    (memoised in ``cache`` by (case name, "planar truth"))."""
    key = (case.name, "planar truth")
    if cache is not None and key in cache:
        return cache[key]
    truth = case.run("planar-reference", rtol=PLANAR_TRUTH_RTOL)
    if cache is not None:
        cache[key] = truth
    return truth


def planar_work_precision(cases: Sequence[PlanarCase] | None = None,
                          settings: Sequence[tuple[str, str, dict[str, Any]]] | None = None,
                          repeats: int = 5, progress: Progress | None = None,
                          cache: dict | None = None, moreau: Sequence[float] = (),
                          moreau_cases: Sequence[str] | None = None) -> pd.DataFrame:
    """Error against run time on the coupled cases, one row per (case, method, setting).

    Parameters
    ----------
    cases : list of PlanarCase, optional
        Default :func:`planar_cases`.
    settings : list, optional
        Default :func:`method_settings`.
    repeats : int
        Timed repetitions of the compiled engine (median reported) [-]; the reference
        runs once.
    progress : callable, optional
        Called with each case's name.
    cache : dict, optional
        Memo of the truths (:func:`planar_truth`).
    moreau : sequence of float
        Steps h [s] of the Moreau-Jean rows (:func:`moreau_jean_rows`) added after the
        rows of each case of ``moreau_cases``; empty: none.
    moreau_cases : sequence of str, optional
        The cases that get them (default: those of :data:`MOREAU_WINDOW`).

    Returns
    -------
    pandas.DataFrame
        Columns: case, method, setting, rtol, subdivisions (NaN), time [s], the errors of
        :func:`compare_planar`, steps, rejected, evaluations (the compiled engine's),
        status, status truth, truth ("planar-reference"), truth rtol.
    """
    import pandas as pd

    cases = planar_cases() if cases is None else cases
    settings = method_settings() if settings is None else settings
    rows = []
    for case in cases:
        if progress:
            progress(case.name)
        truth = planar_truth(case, cache)
        for method, label, options in settings:
            def run(case=case, method=method, options=options):
                return case.run(method, rtol=options.get("rtol"))
            result, seconds = timed(run, method == "planar", repeats)
            rows.append(_row(case.name, method, label, options, seconds,
                             compare_planar(result, truth), result, truth,
                             "planar-reference", PLANAR_TRUTH_RTOL))
        if moreau and case.name in (MOREAU_WINDOW if moreau_cases is None
                                    else moreau_cases):
            rows += moreau_jean_rows(case, moreau, cache=cache)
    return pd.DataFrame(rows)


# --------------------------------------------------------------------------- Moreau-Jean
def moreau_steps(quick: bool = False) -> tuple[float, ...]:
    """Steps h [s] of the Moreau-Jean rows (fewer for ``--quick``)."""
    return QUICK_MOREAU_STEPS if quick else MOREAU_STEPS


def moreau_case_names(quick: bool = False) -> tuple[str, ...]:
    """The coupled cases that get Moreau-Jean rows (fewer for ``--quick``)."""
    return QUICK_MOREAU_CASES if quick else tuple(MOREAU_WINDOW)


def _window(motion: Motion, end: float) -> Motion:
    """``motion`` up to ``end`` [s] (its samples at or before it)."""
    keep = np.asarray(motion.t) <= end + 1e-12
    return Motion(np.asarray(motion.t)[keep], np.asarray(motion.horizontal)[keep],
                  motion.vertical_or_zero[keep])


def compare_moreau(result, truth) -> dict[str, Any]:
    """Errors of a Moreau-Jean run against a planar truth: max |theta| and peak slip (the
    columns of :func:`compare_planar`); the event error is the overturn time's relative
    error when either overturns, NaN otherwise (a time stepper has no event times)."""
    either = result.overturned or truth.overturned
    return {
        "error max_theta [-]": _relative(result.max_abs_theta, truth.max_abs_theta),
        "error max_theta [rad]": abs(result.max_abs_theta - truth.max_abs_theta),
        "error events [-]": (_relative(result.t_overturn, truth.t_overturn) if either
                             else math.nan),
        "error peak slip [-]": _relative(result.peak_slip, truth.peak_slip),
        "error peak slip [m]": abs(result.peak_slip - truth.peak_slip),
        "impacts": math.nan, "impacts truth": int(len(truth.impact_times)),
        "events": math.nan, "events truth": math.nan,
        "same impacts": math.nan, "same events": math.nan,
        "same verdict": bool(result.overturned == truth.overturned),
    }


def moreau_jean_rows(case: PlanarCase, steps: Sequence[float] = MOREAU_STEPS,
                     window: float | None = None,
                     cache: dict | None = None) -> list[dict[str, Any]]:
    """Rows of the Moreau-Jean check on ``case`` (module docstring), one per step h.

    Parameters
    ----------
    case : PlanarCase
        A coupled case with a motion.
    steps : sequence of float
        Steps h [s].
    window : float, optional
        Run the first ``window`` seconds [s] (default :data:`MOREAU_WINDOW` of the case,
        else the whole motion).
    cache : dict, optional
        Memo of the truth, by (case name, "moreau truth").

    Returns
    -------
    list of dict
        The columns of :func:`planar_work_precision` (setting ``h=...``, rtol NaN, steps
        the number of steps, time [s] one run's wall time, truth
        ``"planar-reference cor=housner"``).
    """
    from shaketable.models.planar.moreau import simulate_moreau_jean

    if case.motion is None:
        raise ValueError(f"case {case.name!r}: the Moreau-Jean rows need a motion")
    end = MOREAU_WINDOW.get(case.name) if window is None else window
    motion = case.motion if end is None else _window(case.motion, float(end))
    key = (case.name, "moreau truth")
    truth = None if cache is None else cache.get(key)
    if truth is None:
        truth = run_planar("planar-reference", case.block, motion, cor="housner",
                           friction=case.friction, theta0=case.theta0,
                           rtol=PLANAR_TRUTH_RTOL)
        if cache is not None:
            cache[key] = truth
    state = (0.0, case.block.h, case.theta0, 0.0, 0.0, 0.0)
    rows = []
    for step in steps:
        start = time.perf_counter()
        result = simulate_moreau_jean(case.block, motion, friction=case.friction,
                                      step=step, state=state)
        seconds = time.perf_counter() - start
        row = _row(case.name, MOREAU_METHOD, f"h={step:g}", {}, seconds,
                   compare_moreau(result, truth), result, truth,
                   "planar-reference cor=housner", PLANAR_TRUTH_RTOL)
        rows.append(row)
    return rows
