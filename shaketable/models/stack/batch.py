"""Many stack runs at once: one summary row per run, as the single-block batch gives.

:func:`simulate_many` runs the Cartesian product of stacks, motions, scale factors and
impact laws; :func:`simulate_cases` runs an explicit list of :class:`Case`. Each run is the
compiled stack engine's (:func:`shaketable.models.stack.compiled.integrate`, the engine
:func:`~shaketable.models.stack.simulate_stack` uses, with the same arguments), and its row
is computed straight from the engine's arrays: no :class:`StackResult`, no event dicts, no
frames. The engine releases the GIL, so the runs share ``threads`` Python threads
(:func:`shaketable.models.rocking.run.run_in_chunks`); the rows do not depend on the number of
threads.

Run i equals ``simulate_stack(stack, extended(motion.scaled(scale), duration),
impact=..., cor=..., rtol=rtol, rest_tolerance=...)`` (``extended``:
:func:`shaketable.models.rocking.run.extended`, which cuts or pads a motion to ``duration``
and starts it at t = 0; the scale is skipped when it is 1). Every result column holds the
value that run's :class:`StackResult` gives, bit for bit (``tests/models/stack/test_batch.py``
checks it against the result object, which computes them by its own path). The model's
assumption warnings (tensile force, friction above :data:`PLAUSIBLE_FRICTION`) are not
raised: the ``tension``, ``t_tension [s]`` and ``t_friction_exceeded [s]`` columns carry
them. A run made again at a tighter tolerance after a chatter stall raises a
:class:`~shaketable.models.stack.model.StackRetryWarning` naming the run (``run k``, its
stack, motion, scale and law; its ``rtol [-]`` says it too). A run the engine cannot
continue at any tolerance tried (:class:`~shaketable.models.stack.engine.StackStalled`)
does not stop the batch: its row has the status ``"stalled"``, the engine's message in
``verdict`` (``"stalled: ..."``), the last tolerance tried in ``rtol [-]``, NaN in every
result column (False in the flags, -1 in the counts and in ``overturned block``), and a
:class:`~shaketable.models.stack.model.StackStalledWarning` names the run.

Columns (units in square brackets; NaN in a time column: never happened)
-------------------------------------------------------------------------
Inputs: ``stack`` (the label), ``blocks``, ``stack height [m]``, ``base width [m]``,
``alpha_min [rad]``, ``motion``, ``scale [-]``, ``pga [m/s^2]`` (the motion's PGA times the
scale), ``motion_vertical``, ``duration [s]`` (of the run's motion), ``impact``
(``"plastic"`` or ``"cor"``), ``cor [-]`` (NaN with the plastic law), ``method``
(``"compiled"``), ``rtol [-]`` (the run's: a tighter one after a chatter stall,
:func:`~shaketable.models.stack.model.integrate_retrying`), ``mu [-]`` (the friction coefficient of
``t_friction_exceeded [s]``).

Results, as :class:`StackResult` names them:

- ``status`` (``"completed"``, ``"overturned"``, ``"airborne"``, ``"stalled"``), ``overturned``,
  ``airborne``, ``overturned block`` (numbered from 0 at the bottom; -1 if none),
  ``verdict`` (:meth:`StackResult.verdict`), ``t_overturn [s]``, ``t_airborne [s]``;
- ``max_theta_ratio [-]``: the largest max |theta_i| / alpha_i over the blocks (NaN when
  overturned, as the single block's); ``max |theta| bottom [rad]``, ``max |theta| top
  [rad]``, and for each block i up to the tallest stack's ``max |theta| block i [rad]`` and
  ``max |theta|/alpha block i [-]`` (NaN past a stack's own blocks); the peaks are read at
  the output times (the motion's samples), as the result's;
- ``t_start [s]`` (the first uplift) and ``first pattern`` (the pattern it entered,
  :func:`pattern_name`; "" if none), ``n_impacts`` (impacts among the recorded events),
  ``n_events`` (all events counted), ``events not unique`` (uplifts and impacts whose
  complementarity had not exactly one solution);
- ``peak top-corner excursion [m]`` (:attr:`StackResult.peak_excursion`), ``max F/N [-]``
  (the largest friction demand where the normal force is positive; NaN if none),
  ``t_friction_exceeded [s]`` (:meth:`StackResult.t_friction_exceeded` of ``mu``),
  ``tension`` and ``t_tension [s]`` (:attr:`StackResult.t_tension`);
- ``t_past_alpha [s]``, ``max F/N before past alpha [-]``, ``peak top-corner excursion
  before past alpha [m]`` (:meth:`StackResult.peak_before_past_alpha`), ``still moving``
  (:attr:`StackResult.still_moving`), ``t_end [s]`` (the last output time);
- ``solver steps``, ``solver evaluations``, ``stack_index``, ``motion_index``.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from itertools import product
from typing import TYPE_CHECKING, Any

import numpy as np
from numba import njit

from shaketable.core.motion import Motion
from shaketable.core.validation import count, in_range, positive
from shaketable.models.rocking.physics import ERROR_MODEL
from shaketable.models.rocking.run import extended, labelled, run_in_chunks, thread_count
from shaketable.models.stack.geometry import Stack
from shaketable.models.stack.result import (
    PLAUSIBLE_FRICTION,
    pattern_name,
    verdict_text,
)

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["Case", "simulate_cases", "simulate_many"]

@dataclass(frozen=True)
class Case:
    """One run of a stack batch.

    Parameters
    ----------
    stack : Stack
        The column of blocks.
    motion : Motion
        The table's accelerations [m/s^2] (vertical positive up).
    cor : float, optional
        The constant COR [-] in [0, 1] (the ``"cor"`` impact law); None (default) or NaN:
        the plastic multi-contact law.
    scale : float
        Factor [-] applied to every component of the motion (:meth:`Motion.scaled`),
        positive; 1 leaves it unchanged.
    stack_label, motion_label : str
        Labels written in the table (default: :meth:`Stack.describe` and ``Motion.name``).
    """

    stack: Stack
    motion: Motion
    cor: float | None = None
    scale: float = 1.0
    stack_label: str = ""
    motion_label: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.stack, Stack):
            raise TypeError(f"Case.stack must be a shaketable.models.stack.Stack, got "
                            f"{type(self.stack).__name__}")
        if not isinstance(self.motion, Motion):
            raise TypeError(f"Case.motion must be a shaketable.Motion, got "
                            f"{type(self.motion).__name__}")
        object.__setattr__(self, "cor", _law("Case.cor", self.cor))
        object.__setattr__(self, "scale", in_range("Case.scale", self.scale, 0.0,
                                                   low_open=True))


# --------------------------------------------------------------------------- public API
def simulate_many(stacks: Stack | Iterable[Stack] | Mapping[str, Stack],
                  motions: Motion | Iterable[Motion] | Mapping[str, Motion],
                  cors: float | str | None | Iterable[float | str | None] = "plastic", *,
                  scales: Iterable[float] = (1.0,), threads: int | None = None,
                  rtol: float = 1e-12, duration: float | None = None,
                  mu: float = PLAUSIBLE_FRICTION, **options: Any) -> pd.DataFrame:
    """Every combination of stacks, motions, scale factors and impact laws, in parallel.

    Parameters
    ----------
    stacks : Stack, sequence of Stack or dict
        The stacks; a dict maps a label to each (default label: :meth:`Stack.describe`).
    motions : Motion, sequence of Motion or dict
        The table's accelerations [m/s^2]; a dict maps a label to each (default label:
        ``Motion.name``).
    cors : "plastic", float or a sequence of them
        The impact laws: ``"plastic"`` (or None: the plastic multi-contact law, default)
        or a constant COR [-] in [0, 1] (``impact="cor"`` of
        :func:`~shaketable.models.stack.simulate_stack`).
    scales : sequence of float
        Factors [-] multiplying every component of each motion (default 1).
    threads : int, optional
        Number of threads, at most :data:`numba.config.NUMBA_NUM_THREADS` (default
        ``numba.get_num_threads()``).
    rtol : float
        The engine's relative tolerance [-] in [1e-14, 1e-3] (default 1e-12, as
        :func:`~shaketable.models.stack.simulate_stack`).
    duration : float, optional
        Length of every run [s]: motions are cut to it or continued with the table at rest
        (:func:`shaketable.models.rocking.run.extended`).
    mu : float
        Friction coefficient [-] of the ``t_friction_exceeded [s]`` column (default
        :data:`PLAUSIBLE_FRICTION`).
    **options
        ``rest_tolerance`` [s] and ``max_recorded_events``, as in
        :func:`~shaketable.models.stack.simulate_stack`. Every run starts from rest.

    Returns
    -------
    pandas.DataFrame
        One row per run, in the order ``product(stacks, motions, scales, cors)`` (the last
        varies fastest); the columns are listed in the module docstring.

    Raises
    ------
    ValueError
        An invalid argument (empty stacks, motions, cors or scales; threads out of range;
        an unknown option); the message names it.
    TypeError
        A stack or motion of the wrong type, naming its index.
    """
    stack_labels, stack_list = labelled("stacks", stacks, Stack, Stack.describe,
                                        wrong_type=TypeError, qualifier="")
    motion_labels, motion_list = labelled("motions", motions, Motion, lambda m: m.name,
                                          wrong_type=TypeError, qualifier="")
    cor_list = [_law(f"cors[{k}]", cor) for k, cor in enumerate(_as_list(cors))]
    scale_list = [in_range(f"scales[{k}]", s, 0.0, low_open=True)
                  for k, s in enumerate(_as_list(scales))]
    for name, values in (("cors", cor_list), ("scales", scale_list)):
        if not values:
            raise ValueError(f"{name} must not be empty")
    cases = [Case(stack_list[i], motion_list[m], cor_list[c], scale_list[s],
                  stack_labels[i], motion_labels[m])
             for i, m, s, c in product(range(len(stack_list)), range(len(motion_list)),
                                       range(len(scale_list)), range(len(cor_list)))]
    return _batch(cases, threads=threads, rtol=rtol, duration=duration, mu=mu, **options)


def simulate_cases(cases: Iterable[Case], *, threads: int | None = None, rtol: float = 1e-12,
                   duration: float | None = None, mu: float = PLAUSIBLE_FRICTION,
                   **options: Any) -> pd.DataFrame:
    """An explicit list of runs, in parallel; one row per :class:`Case`, in order.

    Parameters
    ----------
    cases : sequence of Case
        The runs. A motion shared between cases (the same object, the same scale) is
        scaled and extended once.
    threads, rtol, duration, mu, **options
        As in :func:`simulate_many`.

    Returns
    -------
    pandas.DataFrame
        As :func:`simulate_many`, row i for ``cases[i]``.
    """
    cases = list(cases)
    for k, case in enumerate(cases):
        if not isinstance(case, Case):
            raise TypeError(f"cases[{k}] must be a shaketable.models.stack.batch.Case, got "
                            f"{type(case).__name__}")
    return _batch(cases, threads=threads, rtol=rtol, duration=duration, mu=mu, **options)


# --------------------------------------------------------------------------- internals
_OPTIONS = {"rest_tolerance", "max_recorded_events"}


def _law(name: str, cor) -> float | None:
    """None for the plastic law (``"plastic"``, None or NaN), else the COR in [0, 1]."""
    if cor is None or (isinstance(cor, str) and cor == "plastic"):
        return None
    if isinstance(cor, str):
        raise ValueError(f"{name} must be \"plastic\" or a COR in [0, 1], got {cor!r}")
    if isinstance(cor, (float, np.floating)) and math.isnan(cor):
        return None
    return in_range(name, cor, 0.0, 1.0)


def _as_list(values) -> list:
    if values is None or isinstance(values, (str, int, float, np.integer, np.floating)):
        return [values]
    return list(values)


def _batch(cases: list, *, threads, rtol, duration, mu, **options) -> pd.DataFrame:
    """Check, prepare each run's motion, run the cases on ``threads`` threads, build the
    table."""
    from shaketable.models.stack.engine import StackStalled
    from shaketable.models.stack.model import (
        StackRetryWarning,
        StackStalledWarning,
        user_location,
    )

    if not cases:
        raise ValueError("cases must not be empty")
    unknown = sorted(set(options) - _OPTIONS)
    if unknown:
        raise ValueError(f"unknown option {unknown[0]!r}; expected one of "
                         f"{', '.join(sorted(_OPTIONS))}")
    threads = thread_count(threads)
    rtol = in_range("rtol", rtol, 1e-14, 1e-3)
    if duration is not None:
        duration = positive("duration", duration, " [s]")
    mu = in_range("mu", mu, 0.0)
    rest = options.get("rest_tolerance")
    if rest is not None:
        rest = positive("rest_tolerance", rest, " [s]")
    recorded = count("max_recorded_events", options.get("max_recorded_events", 100_000), 1)

    # each (motion, scale) once: scaled, then cut or padded (as a stack sweep does)
    motions: dict[tuple[int, float], tuple[Motion, int]] = {}
    runs: list[tuple[Motion, int]] = []
    for case in cases:
        key = (id(case.motion), case.scale)
        if key not in motions:
            scaled = case.motion if case.scale == 1.0 else case.motion.scaled(case.scale)
            motions[key] = (extended(scaled, duration), len(motions))
        runs.append(motions[key])
    rows: list[Any] = [None] * len(cases)
    rtols = [rtol] * len(cases)   # each run's, after a chatter stall a tighter one
    constants = {id(case.stack): _constants(case.stack) for case in cases}
    caller = user_location()   # where a retry's warning points, from any thread

    def run(start: int, stop: int) -> None:
        for k in range(start, stop):
            case = cases[k]
            filename, lineno, module_globals = caller
            try:
                rows[k], rtols[k], retried = _row(case, runs[k][0], constants[id(case.stack)],
                                                  rtol, rest, recorded, mu)
            except StackStalled as error:
                # a row of its own; the other runs go on
                rows[k], rtols[k] = _stalled_row(case.stack.n, str(error)), getattr(
                    error, "rtol", rtol)
                warnings.warn_explicit(f"{_run_words(k, case)}: stalled, no results (the "
                                       f"row's status): {error}", StackStalledWarning,
                                       filename, lineno, module_globals=module_globals)
                continue
            if retried:
                warnings.warn_explicit(f"{_run_words(k, case)}: {retried}", StackRetryWarning,
                                       filename, lineno, module_globals=module_globals)

    run_in_chunks(run, len(cases), threads, 1)
    return _frame(cases, [motion for motion, _ in runs], [index for _, index in runs], rows,
                  rtols, mu)


def _run_words(k: int, case: Case) -> str:
    """How a message names run ``k``: ``"run 3 (2 blocks: ..., el-centro, scale 0.5,
    plastic impacts)"`` (runs that share the stack and the motion differ in the scale or
    the law)."""
    law = "plastic impacts" if case.cor is None else f"COR {case.cor:g}"
    return (f"run {k} ({case.stack_label or case.stack.describe()}, "
            f"{case.motion_label or case.motion.name}, scale {case.scale:g}, {law})")


def _row(case: Case, motion: Motion, constants: tuple, rtol: float, rest: float | None,
         recorded: int, mu: float) -> tuple[tuple, float, str]:
    """One run: the engine, then its results from the engine's arrays (:data:`_RESULTS`),
    the tolerance they were computed at (``rtol``, or a tighter one after a chatter stall,
    as :func:`~shaketable.models.stack.model.simulate_stack`) and the retry's note ("" when
    none); ``constants``: the stack's :func:`_constants`."""
    from shaketable.models.stack.compiled import IMPACT, UPLIFT, integrate
    from shaketable.models.stack.model import integrate_retrying

    stack = case.stack
    n = stack.n
    zeros, b, h, alphas, scale, limit, margin, bottom_rest = constants
    out, rtol, retried = integrate_retrying(
        integrate, stack, motion, law="plastic" if case.cor is None else "cor",
        cor=1.0 if case.cor is None else case.cor, theta0=zeros, theta_dot0=zeros, rtol=rtol,
        rest_tolerance=bottom_rest if rest is None else rest, max_recorded_events=recorded)
    compiled_run = out["run"]
    theta, patterns = out["theta"], out["patterns"]
    t = motion.t[:out["filled"]]
    status = compiled_run.status
    overturned = status == "overturned"
    peaks, floats, ints = np.zeros(n), np.empty(_N_FLOATS), np.empty(_N_INTS, dtype=np.int64)
    candidates = np.empty(t.size, dtype=np.int64)
    _scan(t, theta, patterns, out["forces"], b, h, stack.e, alphas, scale, mu, limit, margin,
          peaks, floats, ints, candidates)
    past, end, exceeded, tension = (int(value) for value in ints[:4])
    # the excursion at the candidates, as the result computes it
    chosen = candidates[:ints[_I_CANDIDATES]]
    excursion = np.abs(top_corner_excursion(stack, theta[chosen], patterns[chosen]))
    peak_excursion = float(excursion.max()) if t.size else 0.0
    standing = ((0.0, 0.0) if end == 0 else
                (floats[_F_DEMAND_BEFORE], float(excursion[chosen < end].max())))
    ratios = peaks / alphas
    ratio = max(peak / block.alpha for peak, block in zip(peaks, stack.blocks))

    # the recorded events as the engine's arrays (the result's dicts are built from them):
    # times, kinds, solutions, patterns after (compiled.record)
    reals, integers, _, after = compiled_run._recorded
    kinds = integers[:, 0]
    uplifts = np.flatnonzero(kinds == UPLIFT)
    first_uplift = int(uplifts[0]) if uplifts.size else -1
    choices = (kinds == UPLIFT) | (kinds == IMPACT)

    still = bool(status == "completed" and t.size
                 and (np.any(theta[-1]) or np.any(out["rate"][-1])))
    past_at_end = (tuple(int(i) for i in np.flatnonzero(np.abs(theta[-1]) > alphas))
                   if status == "completed" and t.size else ())
    t_end = float(t[-1]) if t.size else math.nan
    verdict = verdict_text(n, status, compiled_run.overturned_block, compiled_run.t_overturn,
                           compiled_run.t_airborne, peaks, alphas, still, t_end, past_at_end)
    return (status, overturned, status == "airborne", compiled_run.overturned_block, verdict,
            compiled_run.t_overturn, compiled_run.t_airborne,
            math.nan if overturned else float(ratio), float(peaks[0]), float(peaks[-1]),
            peaks, ratios,
            float(reals[first_uplift, 0]) if first_uplift >= 0 else math.nan,
            pattern_name(after[first_uplift]) if first_uplift >= 0 else "",
            int(np.count_nonzero(kinds == IMPACT)), compiled_run.n_events,
            int(np.count_nonzero(integers[choices, 2] != 1)),
            peak_excursion, float(floats[_F_DEMAND]),
            float(t[exceeded]) if exceeded >= 0 else math.nan,
            tension >= 0, float(t[tension]) if tension >= 0 else math.nan,
            float(t[past]) if past >= 0 else math.nan, float(standing[0]), standing[1], still,
            t_end, compiled_run.steps, compiled_run.evaluations), rtol, retried


def _stalled_row(n: int, message: str) -> tuple:
    """The results (:data:`_RESULTS`) of a run of ``n`` blocks that stalled: its status,
    the message in the verdict, NaN (False in the flags, -1 in the counts)."""
    nan, none = math.nan, np.full(n, math.nan)
    return ("stalled", False, False, -1, f"stalled: {message}", nan, nan, nan, nan, nan,
            none, none, nan, "", -1, -1, -1, nan, nan, nan, False, nan, nan, nan, nan, False,
            nan, -1, -1)


def _constants(stack: Stack) -> tuple:
    """What every run of ``stack`` uses: zeros (its initial state), b, h [m], the blocks'
    alphas [rad], its mass scale, the tensile force a contact may carry [N] (as
    :attr:`StackResult.t_tension`), the excursion's margin [m] and the default rest tolerance
    [s] (:func:`~shaketable.models.stack.simulate_stack`'s)."""
    b, h = stack.b, stack.h
    # the excursion's candidates for its peaks: within far more than its rounding (~1e-15
    # of the stack's size) of the largest value computed without the matmul
    margin = 1e-12 * float(2.0 * (b.sum() + h.sum()))
    return (np.zeros(stack.n), b, h, np.array([block.alpha for block in stack.blocks]),
            stack.mass_scale, -1e-9 * stack.weight, margin, 1e-6 / stack.blocks[0].p)


# slots of _scan's outputs: the largest finite F/N over the run and before the first
# sample past alpha (NaN: none); the first sample past alpha, the end of the samples before
# it, the first sample whose F/N exceeds mu and whose corner force is tensile (-1: none), the
# number of the excursion's candidates
_F_DEMAND, _F_DEMAND_BEFORE = range(2)
_N_FLOATS = 2
_I_PAST, _I_END, _I_EXCEEDED, _I_TENSION, _I_CANDIDATES = range(5)
_N_INTS = 5


@njit(cache=True, nogil=True, error_model=ERROR_MODEL)
def _scan(t, theta, patterns, forces, b, h, e, alphas, scale, mu, tension_limit, margin,
          peaks, floats, ints, candidates):
    """One pass over a run's samples for the values of :class:`StackResult` that read its
    histories (the same operations on the same numbers: equal bit for bit): each block's
    peak |theta| (``peaks``), the first sample past alpha, the friction demand |F| / N
    (infinite where N <= 0) of the forces times ``scale`` (the stack's mass scale), its
    largest finite value over the run and before that sample, the first sample above ``mu``,
    the first tensile corner force (below ``tension_limit`` [N]).

    The top corners' excursion is computed here without the result's matrix product (whose
    last bit may differ: BLAS may fuse a multiply and an add), only to find the samples that
    may hold its peak (over the run, and before the sample past alpha): those within
    ``margin`` [m] of the largest, one of each run of identical states; ``candidates`` gets
    them, and :func:`top_corner_excursion` computes them as the result does.
    """
    k, n = theta.shape
    top = n - 1
    rest = 0.0   # the top block's centre at rest [m] (Stack.centres[top])
    for j in range(n):
        rest += e[j]
    past = -1
    for i in range(k):
        for j in range(n):
            value = abs(theta[i, j])
            if value > peaks[j]:
                peaks[j] = value
            if past < 0 and value > alphas[j]:
                past = i
    end = k if past < 0 else np.searchsorted(t, t[past])
    largest, before = -math.inf, -math.inf
    exceeded, tension = -1, -1
    approximate = np.empty(k)
    high, high_before = 0.0, 0.0
    for i in range(k):
        for j in range(n):
            normal = forces[i, j, 0] * scale
            tangential = abs(forces[i, j, 1] * scale)
            demand = tangential / normal if normal > 0.0 else math.inf
            if math.isfinite(demand):
                largest = max(largest, demand)
                if i < end:
                    before = max(before, demand)
            if exceeded < 0 and demand > mu:
                exceeded = i
            if tension < 0 and (forces[i, j, 2] * scale < tension_limit
                                or forces[i, j, 3] * scale < tension_limit):
                tension = i
        # the top corners' displacement (top_corner_excursion's sums, a plain product)
        x = -(1.0 if patterns[i, 0] == 0 else float(patterns[i, 0])) * b[0]
        for j in range(top):
            lower = (1.0 if patterns[i, j] == 0 else float(patterns[i, j])) * b[j]
            upper = (1.0 if patterns[i, j + 1] == 0 else float(patterns[i, j + 1])) * b[j + 1]
            x += math.cos(theta[i, j]) * (lower - upper + e[j + 1]) \
                - math.sin(theta[i, j]) * (2.0 * h[j])
        cosine, sine = math.cos(theta[i, top]), math.sin(theta[i, top])
        reach = (1.0 if patterns[i, top] == 0 else float(patterns[i, top])) * b[top]
        x += cosine * reach - sine * h[top]
        value = 0.0
        for side in (-1.0, 1.0):
            value = max(value, abs(x + cosine * side * b[top] - sine * h[top] - side * b[top]
                                   - rest))
        approximate[i] = value
        high = max(high, value)
        if i < end:
            high_before = max(high_before, value)
    count = 0
    for i in range(k):
        if approximate[i] >= high - margin or (i < end and approximate[i] >= high_before - margin):
            same = count > 0
            if same:
                previous = candidates[count - 1]
                for j in range(n):
                    if theta[i, j] != theta[previous, j] or patterns[i, j] != patterns[previous, j]:
                        same = False
            if not same:
                candidates[count] = i
                count += 1
    floats[0] = largest if largest > -math.inf else math.nan
    floats[1] = before if before > -math.inf else math.nan
    ints[0], ints[1], ints[2], ints[3], ints[4] = past, end, exceeded, tension, count


#: The columns of :func:`_row`'s tuple (``None``: the per-block peaks, spread over columns).
_RESULTS = ("status", "overturned", "airborne", "overturned block", "verdict",
            "t_overturn [s]", "t_airborne [s]", "max_theta_ratio [-]",
            "max |theta| bottom [rad]", "max |theta| top [rad]", None, None, "t_start [s]",
            "first pattern", "n_impacts", "n_events", "events not unique",
            "peak top-corner excursion [m]", "max F/N [-]", "t_friction_exceeded [s]",
            "tension", "t_tension [s]", "t_past_alpha [s]", "max F/N before past alpha [-]",
            "peak top-corner excursion before past alpha [m]", "still moving", "t_end [s]",
            "solver steps", "solver evaluations")
#: Where the per-block peaks and peak ratios stand in :func:`_row`'s tuple.
_PEAKS = _RESULTS.index(None)
#: Integer columns (object arrays of Python ints would not be int64 otherwise).
_INTEGERS = {"overturned block", "n_impacts", "n_events", "events not unique",
             "solver steps", "solver evaluations"}


def top_corner_excursion(stack: Stack, theta: np.ndarray, patterns: np.ndarray) -> np.ndarray:
    """Horizontal displacement of the top block's two top corners from rest [m], shape
    (k, 2) (-x corner, +x corner), at the k output times: :attr:`StackResult.top_corner_excursion`
    for all the times at once.

    The centroid of the top block is ``G = P_0 + sum_{k<top} R(theta_k) D_k + R(theta_top)
    C_top`` (:func:`shaketable.models.stack.physics.kinematics`, its x component with the
    pivots of each sample's pattern), its corner ``G + R(theta_top) (+-b, h)``, less its
    place at rest ``(X_top +- b, .)`` (``X_top`` the top block's centre, the sum of the
    offsets, :attr:`Stack.centres`); the sums are taken in the same order as there.
    """
    b, h, e = stack.b, stack.h, stack.e
    rest = float(stack.centres[-1])
    top = stack.n - 1
    sigma = np.where(patterns == 0, 1.0, patterns.astype(float))   # physics.pivots
    cosine, sine = np.cos(theta), np.sin(theta)
    reach = sigma * b
    x = -sigma[:, 0] * b[0]                                          # P_0
    if top > 0:
        dx = reach[:, :top] - reach[:, 1:top + 1] + e[1:top + 1]   # D_k, k < top
        rotated = cosine[:, :top] * dx - sine[:, :top] * (2.0 * h[:top])
        x = x + np.cumsum(rotated, axis=1)[:, -1]
    else:
        x = x + 0.0
    x = x + (cosine[:, top] * reach[:, top] - sine[:, top] * h[top])   # R C_top
    # R(theta_top) (+-b, h) as the result's ``rotation(theta) @ corner``: one matrix-vector
    # product per sample, by the same matmul (BLAS, which may fuse a multiply and an add)
    rotations = np.empty((theta.shape[0], 2, 2))
    rotations[:, 0, 0] = cosine[:, top]
    rotations[:, 0, 1] = -sine[:, top]
    rotations[:, 1, 0] = sine[:, top]
    rotations[:, 1, 1] = cosine[:, top]
    out = np.empty((theta.shape[0], 2))
    for c, side in enumerate((-1.0, 1.0)):
        corner = x + np.matmul(rotations, np.array([side * b[top], h[top]]))[:, 0]
        out[:, c] = corner - side * b[top] - rest
    return out


def _frame(cases, motions, motion_index, rows, rtols, mu):
    import pandas as pd

    stacks = [case.stack for case in cases]
    widest = max(stack.n for stack in stacks)
    columns: dict[str, Any] = {
        "stack": [case.stack_label or case.stack.describe() for case in cases],
        "blocks": np.array([stack.n for stack in stacks], dtype=np.int64),
        "stack height [m]": np.array([float(sum(block.height for block in stack.blocks))
                                      for stack in stacks]),
        "base width [m]": np.array([float(stack.blocks[0].width) for stack in stacks]),
        "alpha_min [rad]": np.array([stack.alpha_min for stack in stacks]),
        "motion": [case.motion_label or case.motion.name for case in cases],
        "scale [-]": np.array([case.scale for case in cases]),
        "pga [m/s^2]": np.array([case.motion.pga * case.scale for case in cases]),
        "motion_vertical": np.array([case.motion.vertical is not None for case in cases]),
        "duration [s]": np.array([motion.duration for motion in motions]),
        "impact": ["plastic" if case.cor is None else "cor" for case in cases],
        "cor [-]": np.array([math.nan if case.cor is None else case.cor for case in cases]),
        "method": "compiled", "rtol [-]": np.array(rtols, dtype=float), "mu [-]": float(mu),
    }
    values = list(zip(*rows))
    for name, column in zip(_RESULTS, values):
        if name is not None:
            columns[name] = np.array(column, dtype=np.int64 if name in _INTEGERS else None)
        elif column is values[_PEAKS]:
            # each block's peaks, after the bottom's and the top's
            peaks, ratios = column, values[_PEAKS + 1]
            for i in range(widest):
                columns[f"max |theta| block {i} [rad]"] = np.array(
                    [float(p[i]) if i < p.size else math.nan for p in peaks])
                columns[f"max |theta|/alpha block {i} [-]"] = np.array(
                    [float(r[i]) if i < r.size else math.nan for r in ratios])
    columns["stack_index"] = np.array(_indices([id(stack) for stack in stacks]),
                                      dtype=np.int64)
    columns["motion_index"] = np.array(motion_index, dtype=np.int64)
    return pd.DataFrame(columns)


def _indices(keys: list) -> list[int]:
    """Each key's index in the order keys first appear."""
    seen: dict = {}
    return [seen.setdefault(key, len(seen)) for key in keys]
