"""Many runs at once: (block, motion, COR) combinations in one compiled loop.

:func:`simulate_many` runs the Cartesian product of blocks, motions and
coefficients of restitution; :func:`simulate_cases` runs an explicit list of
:class:`Case`. Both hand every run to the compiled engine
(:func:`shaketable.models.rocking.engine.integrate`) from one compiled loop run without the
GIL on several Python threads, with length-0 output arrays so that no time history is
stored: there is no Python work per run, only per batch. Each run gives
exactly the scalar results of :func:`shaketable.models.api` with the same
arguments (the same compiled code on the same numbers; ``tests/test_batch.py``
checks this bit for bit).

The result is a :class:`pandas.DataFrame`, one row per run, with the inputs
and every scalar output. Its column names are those of
:meth:`shaketable.models.rocking.result.RockingResult.summary` (units in square brackets),
plus the inputs a batch adds (labels, indices, scale factor). A run whose
vertical table acceleration reaches -g stops there (the block would leave the
ground, outside the model): its ``status`` is ``"airborne"``, ``airborne`` is
True and ``t_airborne [s]`` says when; its other results are those up to that
time, never a silent NaN.

NaN in a result column means "never happened" (no uplift, never unstable,
did not overturn, never came to rest), as in :class:`RockingResult`; and
``max_theta_ratio [-]`` is NaN for an overturned run, as
:attr:`RockingResult.max_theta_ratio` (the report's F). The columns a batch row
shares with :meth:`RockingResult.summary` hold the same values, bit for bit;
``max_theta_ratio_before_instability [-]`` and ``verdict`` need the time history or
are text, and are left to :func:`shaketable.models.api.simulate`.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from itertools import product
from typing import TYPE_CHECKING, Any

import numba
import numpy as np
from numba import njit

from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.validation import in_range
from shaketable.models.rocking import engine
from shaketable.models.rocking.layout import METHOD_FAST, METHOD_LINEAR, METHOD_PREDICTOR_CORRECTOR
from shaketable.models.rocking.physics import ERROR_MODEL, N_PARAMETERS, block_parameters
from shaketable.models.rocking.result import STATUSES
from shaketable.models.rocking.run import (
    COMPILED_METHODS,
    check_fixed_steps,
    engine_arrays,
    extended,
    labelled,
    run_in_chunks,
    run_options,
    thread_count,
)

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["Case", "METHODS", "simulate_cases", "simulate_many"]

#: Methods the batch runs (the compiled ones; ``reference`` is SciPy, one run at a time).
METHODS = tuple(COMPILED_METHODS)


@dataclass(frozen=True)
class Case:
    """One run of a batch.

    Parameters
    ----------
    block : Block
        The block.
    motion : Motion
        Ground accelerations [m/s^2] (vertical positive up).
    cor : float
        Coefficient of restitution [-] in [0, 1].
    scale : float
        Factor [-] applied to every component of the motion (as
        :meth:`Motion.scaled`), positive; 1 leaves it unchanged.
    block_label, motion_label : str
        Labels written in the result table (default: ``Block.describe()``
        and ``Motion.name``).
    """

    block: Block
    motion: Motion
    cor: float
    scale: float = 1.0
    block_label: str = ""
    motion_label: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.block, Block):
            raise ValueError(f"Case.block must be a shaketable.Block, got "
                             f"{type(self.block).__name__}")
        if not isinstance(self.motion, Motion):
            raise ValueError(f"Case.motion must be a shaketable.Motion, got "
                             f"{type(self.motion).__name__}")
        object.__setattr__(self, "cor", in_range("Case.cor", self.cor, 0.0, 1.0))
        object.__setattr__(self, "scale", in_range("Case.scale", self.scale, 0.0,
                                                        low_open=True))


@njit(inline="always", error_model=ERROR_MODEL)
def _cases(method, t_all, ug_all, vg_all, rg_all, offsets, parameters, case_block,
           case_motion, case_cor, case_scale, theta0, omega0, rtol, subdivisions,
           rest_tolerance, info, first_case, last_case):
    """Integrate cases ``first_case`` to ``last_case - 1``; ``info[i]`` gets case i's results.

    The motions are stored end to end in ``t_all`` ... ``rg_all``; motion m
    occupies ``offsets[m]:offsets[m + 1]``. ``parameters[j]`` is block j's
    :func:`~shaketable.models.rocking.physics.block_parameters`. ``method`` is a constant (one
    compiled loop per method, :data:`_RUN_CASES`), so each loop calls that method's
    compiled integrator, the one :func:`~shaketable.models.api.simulate` uses: inlined
    into the loop, the comparisons below are of two constants, and numba drops the
    other branches before typing.
    """
    if method == METHOD_FAST:
        integrator = engine.integrate_fast
    elif method == METHOD_PREDICTOR_CORRECTOR:
        integrator = engine.integrate_predictor_corrector
    else:
        integrator = engine.integrate_linear
    for i in range(first_case, last_case):
        m = case_motion[i]
        first = offsets[m]
        last = offsets[m + 1]
        none = np.empty(0)
        integrator(t_all[first:last], ug_all[first:last], vg_all[first:last],
                   rg_all[first:last], case_scale[i], parameters[case_block[i]], case_cor[i],
                   theta0, omega0, rtol, subdivisions, rest_tolerance, none, none, none, none,
                   none, info[i])


# Compiled without the GIL: _run_all calls them from several Python threads at once, on
# separate ranges of cases (so do Dask workers, one batch each).
@njit(cache=True, nogil=True, error_model=ERROR_MODEL)
def _run_cases_fast(t_all, ug_all, vg_all, rg_all, offsets, parameters, case_block, case_motion,
                    case_cor, case_scale, theta0, omega0, rtol, subdivisions, rest_tolerance,
                    info, first_case, last_case):
    """:func:`_cases` with METHOD_FAST."""
    _cases(METHOD_FAST, t_all, ug_all, vg_all, rg_all, offsets, parameters, case_block,
           case_motion, case_cor, case_scale, theta0, omega0, rtol, subdivisions,
           rest_tolerance, info, first_case, last_case)


@njit(cache=True, nogil=True, error_model=ERROR_MODEL)
def _run_cases_predictor_corrector(t_all, ug_all, vg_all, rg_all, offsets, parameters,
                                   case_block, case_motion, case_cor, case_scale, theta0, omega0,
                                   rtol, subdivisions, rest_tolerance, info, first_case,
                                   last_case):
    """:func:`_cases` with METHOD_PREDICTOR_CORRECTOR."""
    _cases(METHOD_PREDICTOR_CORRECTOR, t_all, ug_all, vg_all, rg_all, offsets,
           parameters, case_block, case_motion, case_cor, case_scale, theta0, omega0, rtol,
           subdivisions, rest_tolerance, info, first_case, last_case)


@njit(cache=True, nogil=True, error_model=ERROR_MODEL)
def _run_cases_linear(t_all, ug_all, vg_all, rg_all, offsets, parameters, case_block,
                      case_motion, case_cor, case_scale, theta0, omega0, rtol, subdivisions,
                      rest_tolerance, info, first_case, last_case):
    """:func:`_cases` with METHOD_LINEAR."""
    _cases(METHOD_LINEAR, t_all, ug_all, vg_all, rg_all, offsets, parameters,
           case_block, case_motion, case_cor, case_scale, theta0, omega0, rtol, subdivisions,
           rest_tolerance, info, first_case, last_case)


#: The compiled loop of each method code.
_RUN_CASES = {METHOD_FAST: _run_cases_fast,
              METHOD_PREDICTOR_CORRECTOR: _run_cases_predictor_corrector,
              METHOD_LINEAR: _run_cases_linear}


def _run_cases(method: int, *arguments: Any) -> None:
    """Cases ``arguments[-2]`` to ``arguments[-1] - 1`` in the compiled loop of ``method``."""
    loop: Any = _RUN_CASES[method]  # a numba dispatcher: its arguments are typed when called
    loop(*arguments)


def set_default_threads(threads: int) -> None:
    """Threads a batch uses when it is not told (``threads=None``), in this process.

    Parameters
    ----------
    threads : int
        From 1 to :data:`numba.config.NUMBA_NUM_THREADS` (the cores numba found).
    """
    numba.set_num_threads(thread_count(threads))


def _run_all(arguments: tuple, n_cases: int, threads: int) -> None:
    """Every case on ``threads`` threads (:func:`~shaketable.models.rocking.run.run_in_chunks`),
    in chunks of at most 64 cases, 16 per thread or more. The results do not depend on the
    number of threads: each case writes its own row of ``info``."""
    chunk = max(1, min(64, n_cases // (16 * threads)))
    run_in_chunks(lambda start, stop: _run_cases(*arguments, start, stop), n_cases, threads,
                  chunk)


# --------------------------------------------------------------------------- public API
def simulate_many(blocks: Block | Iterable[Block] | Mapping[str, Block],
                  motions: Motion | Iterable[Motion] | Mapping[str, Motion],
                  cors: float | Iterable[float], *, scales: Iterable[float] = (1.0,),
                  threads: int | None = None, method: str = "fast", rtol: float | None = None,
                  duration: float | None = None, **options: Any) -> pd.DataFrame:
    """Every combination of blocks, motions, COR (and scale factors), in parallel.

    Parameters
    ----------
    blocks : Block, sequence of Block or dict
        The blocks; a dict maps a label to each block (default label:
        ``Block.describe()``).
    motions : Motion, sequence of Motion or dict
        The ground motions [m/s^2]; a dict maps a label to each (default
        label: ``Motion.name``).
    cors : float or sequence of float
        Coefficients of restitution [-] in [0, 1].
    scales : sequence of float
        Factors [-] multiplying every component of each motion (default 1).
    threads : int, optional
        Number of threads, at most :data:`numba.config.NUMBA_NUM_THREADS`
        (default ``numba.get_num_threads()``: all cores unless set lower).
    method : str
        ``"fast"`` (default), ``"predictor-corrector"`` or ``"linear"``
        (:data:`METHODS`).
    rtol : float, optional
        Relative tolerance [-] (default as :func:`shaketable.models.api`).
    duration : float, optional
        Length of every run [s]: motions are cut to it or continued with the
        table at rest, as in :func:`shaketable.models.api`.
    **options
        ``theta0`` [rad], ``theta_dot0`` [rad/s], ``subdivisions``,
        ``rest_tolerance`` [s], ``top_force`` [m/s^2], as in
        :func:`shaketable.models.api`.

    Returns
    -------
    pandas.DataFrame
        One row per run, in the order ``product(blocks, motions, scales,
        cors)`` (the last varies fastest); the columns are listed in the
        module docstring.

    Raises
    ------
    ValueError
        An invalid argument; the message names it. The options are checked by
        :func:`shaketable.models.rocking.run.run_options`, as for
        :func:`shaketable.models.api.simulate`.
    """
    block_labels, block_list = labelled("blocks", blocks, Block, Block.describe)
    motion_labels, motion_list = labelled("motions", motions, Motion, lambda m: m.name)
    cor_list = [in_range(f"cors[{k}]", c, 0.0, 1.0) for k, c in
                enumerate(_as_list(cors))]
    scale_list = [in_range(f"scales[{k}]", s, 0.0, low_open=True) for k, s in
                  enumerate(_as_list(scales))]
    if not cor_list or not scale_list:
        raise ValueError("cors and scales must not be empty")
    index = np.array(list(product(range(len(block_list)), range(len(motion_list)),
                                  range(len(scale_list)), range(len(cor_list)))),
                     dtype=np.int64).reshape(-1, 4)
    return _batch(block_list, block_labels, motion_list, motion_labels, index[:, 0],
                  index[:, 1], np.array(cor_list)[index[:, 3]],
                  np.array(scale_list)[index[:, 2]], threads=threads, method=method,
                  rtol=rtol, duration=duration, **options)


def simulate_cases(cases: Iterable[Case], *, threads: int | None = None, method: str = "fast",
                   rtol: float | None = None, duration: float | None = None,
                   **options: Any) -> pd.DataFrame:
    """An explicit list of runs, in parallel; one row per :class:`Case`, in order.

    Parameters
    ----------
    cases : sequence of Case
        The runs. Blocks and motions shared between cases (the same object)
        are packed once.
    threads, method, rtol, duration, **options
        As in :func:`simulate_many`.

    Returns
    -------
    pandas.DataFrame
        As :func:`simulate_many`, row i for ``cases[i]``.
    """
    cases = list(cases)
    if not cases:
        raise ValueError("cases must not be empty")
    blocks: list[Block] = []
    block_labels: list[str] = []
    block_of: dict[tuple[int, str], int] = {}
    motions: list[Motion] = []
    motion_labels: list[str] = []
    motion_of: dict[tuple[int, str], int] = {}
    block_index = np.empty(len(cases), dtype=np.int64)
    motion_index = np.empty(len(cases), dtype=np.int64)
    for k, case in enumerate(cases):
        if not isinstance(case, Case):
            raise ValueError(f"cases[{k}] must be a shaketable.models.rocking.batch.Case, got "
                             f"{type(case).__name__}")
        key = (id(case.block), case.block_label)
        if key not in block_of:
            block_of[key] = len(blocks)
            blocks.append(case.block)
            block_labels.append(case.block_label or case.block.describe())
        key = (id(case.motion), case.motion_label)
        if key not in motion_of:
            motion_of[key] = len(motions)
            motions.append(case.motion)
            motion_labels.append(case.motion_label or case.motion.name)
        block_index[k] = block_of[(id(case.block), case.block_label)]
        motion_index[k] = motion_of[(id(case.motion), case.motion_label)]
    return _batch(blocks, block_labels, motions, motion_labels, block_index, motion_index,
                  np.array([case.cor for case in cases]),
                  np.array([case.scale for case in cases]), threads=threads, method=method,
                  rtol=rtol, duration=duration, **options)


# --------------------------------------------------------------------------- internals
_OPTIONS = {"theta0", "theta_dot0", "subdivisions", "rest_tolerance", "top_force"}


def _as_list(values):
    if isinstance(values, (int, float, np.integer, np.floating)):
        return [values]
    return list(values)


def _batch(blocks, block_labels, motions, motion_labels, block_index, motion_index, cors,
           scales, *, threads, method, rtol, duration, **options):
    """Pack, run the compiled loop, and build the table."""

    unknown = sorted(set(options) - _OPTIONS)
    if unknown:
        raise ValueError(f"unknown option {unknown[0]!r}; expected one of "
                         f"{', '.join(sorted(_OPTIONS))}")
    checked = run_options(method, methods=METHODS, rtol=rtol, duration=duration, **options)
    method, rtol, duration = checked.method, checked.rtol, checked.duration
    theta0, theta_dot0 = checked.theta0, checked.theta_dot0
    subdivisions, rest, top_force = (checked.subdivisions, checked.rest_tolerance,
                                     checked.top_force)
    threads = thread_count(threads)

    # motions end to end (each cut or padded to `duration` exactly as simulate does)
    runs = [extended(motion, duration) for motion in motions]
    check_fixed_steps(method, max(motion.t.size for motion in runs), subdivisions)
    offsets = np.zeros(len(runs) + 1, dtype=np.int64)
    offsets[1:] = np.cumsum([motion.t.size for motion in runs])
    # read-only, as simulate's: one compiled signature of the engine (common.engine_arrays)
    t_all, ug_all, vg_all, rg_all = engine_arrays(
        np.concatenate([motion.t for motion in runs]),
        np.concatenate([motion.horizontal for motion in runs]),
        np.concatenate([motion.vertical_or_zero for motion in runs]),
        np.concatenate([motion.rotation_or_zero for motion in runs]))
    parameters = np.empty((len(blocks), N_PARAMETERS))
    for j, block in enumerate(blocks):
        parameters[j] = block_parameters(block, top_force)
    n = len(block_index)
    info = np.full((n, engine.N_INFO), np.nan)

    block_index = np.ascontiguousarray(block_index, dtype=np.int64)
    motion_index = np.ascontiguousarray(motion_index, dtype=np.int64)
    cors = np.ascontiguousarray(cors, dtype=float)
    scales = np.ascontiguousarray(scales, dtype=float)
    pitched = np.array([motion.pitched for motion in runs])
    scaled_pitch = pitched[motion_index] & (scales != 1.0)
    if scaled_pitch.any():
        first = int(np.flatnonzero(scaled_pitch)[0])
        raise ValueError(
            f"case {first}: scale {scales[first]:g} of a motion that carries the table's pitch "
            f"({runs[motion_index[first]].name!r}): the pitch is a disturbance of the table, not "
            "part of the record; scale the record first, then add the pitch "
            "(shaketable.lab.pitch.motion_at_block), as Motion.scaled does")
    arguments = (COMPILED_METHODS[method], t_all, ug_all, vg_all, rg_all, offsets, parameters,
                 block_index, motion_index, cors, scales, theta0, theta_dot0, rtol,
                 subdivisions, rest, info)
    _run_all(arguments, n, threads)

    return _frame(blocks, block_labels, runs, motion_labels, block_index, motion_index, cors,
                  scales, info, method, rtol, duration)


def _frame(blocks, block_labels, motions, motion_labels, block_index, motion_index, cors,
           scales, info, method, rtol, duration):
    import pandas as pd

    heights = np.array([block.height for block in blocks])
    widths = np.array([block.width for block in blocks])
    alphas = np.array([block.alpha for block in blocks])
    ps = np.array([block.p for block in blocks])
    rods = np.array([block.rods is not None for block in blocks])
    pgas = np.array([motion.pga for motion in motions])
    durations = np.array([motion.duration for motion in motions])
    has_vertical = np.array([motion.vertical is not None for motion in motions])
    status_code = info[:, engine.INFO_STATUS].astype(np.int64)
    status = np.array(STATUSES, dtype=object)[status_code]
    max_abs = info[:, engine.INFO_MAX_ABS_THETA]
    alpha = alphas[block_index]

    def direction(column):
        values = info[:, column]
        return np.where(np.isfinite(values), values, 0.0).astype(np.int64)

    frame = pd.DataFrame({
        "block": np.array(block_labels, dtype=object)[block_index],
        "block_height [m]": heights[block_index],
        "block_width [m]": widths[block_index],
        "aspect_ratio [-]": heights[block_index] / widths[block_index],
        "alpha [rad]": alpha,
        "p [rad/s]": ps[block_index],
        "rods": rods[block_index],
        "motion": np.array(motion_labels, dtype=object)[motion_index],
        "scale [-]": np.asarray(scales, dtype=float),
        "pga [m/s^2]": pgas[motion_index] * np.asarray(scales, dtype=float),
        "motion_vertical": has_vertical[motion_index],
        "duration [s]": durations[motion_index],
        "cor [-]": np.asarray(cors, dtype=float),
        "method": method,
        "rtol [-]": rtol,
        "status": status,
        "overturned": status_code == engine.STATUS_OVERTURNED,
        "airborne": status_code == engine.STATUS_AIRBORNE,
        "unstable": np.isfinite(info[:, engine.INFO_T_UNSTABLE]),
        # as RockingResult.max_theta_ratio: NaN for an overturned run (the report's F;
        # (pi/2)/alpha is where the run stopped, not a peak: max_abs_theta keeps it)
        "max_theta_ratio [-]": np.where(status_code == engine.STATUS_OVERTURNED, np.nan,
                                        max_abs / alpha),
        "max_abs_theta [rad]": max_abs,
        "t_max [s]": info[:, engine.INFO_T_MAX],
        "t_start [s]": info[:, engine.INFO_T_START],
        "t_unstable [s]": info[:, engine.INFO_T_UNSTABLE],
        "unstable_direction": direction(engine.INFO_UNSTABLE_DIRECTION),
        "t_overturn [s]": info[:, engine.INFO_T_OVERTURN],
        "overturn_direction": direction(engine.INFO_OVERTURN_DIRECTION),
        "t_airborne [s]": info[:, engine.INFO_T_AIRBORNE],
        "t_rest [s]": info[:, engine.INFO_T_REST],
        "t_end [s]": info[:, engine.INFO_T_END],
        "theta_end [rad]": info[:, engine.INFO_THETA_END],
        "theta_dot_end [rad/s]": info[:, engine.INFO_THETA_DOT_END],
        "n_impacts": info[:, engine.INFO_N_IMPACTS].astype(np.int64),
        "cascades": info[:, engine.INFO_CASCADES].astype(np.int64),
        "solver steps": info[:, engine.INFO_STEPS].astype(np.int64),
        "solver rejected": info[:, engine.INFO_REJECTED].astype(np.int64),
        "solver evaluations": info[:, engine.INFO_EVALUATIONS].astype(np.int64),
        "block_index": np.asarray(block_index, dtype=np.int64),
        "motion_index": np.asarray(motion_index, dtype=np.int64),
    })
    bad = ~np.isfinite(frame["max_abs_theta [rad]"].to_numpy())
    if bad.any():  # the engine always sets it; say so loudly if it ever does not
        raise RuntimeError(f"{int(bad.sum())} run(s) returned no max |theta|, first row "
                           f"{int(np.flatnonzero(bad)[0])}")
    return frame
