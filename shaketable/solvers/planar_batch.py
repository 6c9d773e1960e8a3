"""Many runs of the planar block at once: blocks x frictions x COR on one motion, compiled,
in parallel (Python threads, each calling the compiled engine without the GIL), scalar
results only (no time histories).

The batch of the rocking model is :mod:`shaketable.solvers.batch`; this one calls the
planar engine (:func:`shaketable.solvers.planar.integrate`) with length-0 output arrays,
exactly as :func:`~shaketable.solvers.planar_run.simulate_planar` does with full ones, so
a row equals that run's summary on the columns they share.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable

import numba
import numpy as np

from shaketable.core.dynamics import N_PARAMETERS, block_parameters
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.planar_result import MODES, VERDICTS
from shaketable.core.sliding_result import Friction
from shaketable.solvers import planar
from shaketable.solvers.common import extended
from shaketable.solvers.planar_run import DEFAULT_PLANAR_RTOL, check_planar_inputs, impact_ratios


def _run_cases(arguments: tuple, n_cases: int, threads: int) -> None:
    """Case i of ``arguments`` (per-case arrays, indexed by i) for every i, on ``threads``
    Python threads, each taking the next case when done.

    Each case is one call of the compiled engine :func:`~shaketable.solvers.planar.integrate`
    (compiled without the GIL, so the threads run in parallel) with the very argument types
    :func:`~shaketable.solvers.planar_run.simulate_planar` gives it: the batch compiles
    nothing of its own (a compiled ``prange`` loop around the engine compiled and optimised
    the whole engine a second time, ~4.6 s of CPU on a cold cache). The cases are handed
    out one at a time (run costs differ a lot: a block that overturns early is cheap); the
    results do not depend on the number of threads (each case writes its own rows).
    """
    (t_grid, ug, vg, parameters, rho, cor_cascade, mu_s, mu_d, rtol, rest_tolerance, info,
     final) = arguments
    none = np.empty((0, planar.N_OUT))
    no_events = np.empty((0, planar.EVENT_COLUMNS))

    def run(i):
        planar.integrate(t_grid, ug, vg, parameters[i], rho[i], cor_cascade[i], mu_s[i],
                         mu_d[i], rtol, rest_tolerance, 0.0, 0.0, none, no_events, final[i],
                         info[i])

    if threads <= 1 or n_cases <= 1:
        for i in range(n_cases):
            run(i)
        return
    import threading

    cases = iter(range(n_cases))
    lock = threading.Lock()
    stop = threading.Event()
    errors: list[BaseException] = []

    def work():
        try:
            while not stop.is_set():
                with lock:
                    i = next(cases, None)
                if i is None:
                    return
                run(i)
        except BaseException as error:  # Ctrl-C in the calling thread, too: handed back below
            errors.append(error)
            stop.set()  # the other threads finish their case and take no other

    workers = [threading.Thread(target=work, name=f"shaketable-planar-batch-{k}", daemon=True)
               for k in range(min(threads, n_cases) - 1)]
    for worker in workers:
        worker.start()
    try:
        work()  # the calling thread is one of them
        for worker in workers:
            worker.join()
    finally:
        stop.set()
    if errors:
        raise errors[0]


def simulate_many_planar(blocks: Block | Iterable[Block], motion: Motion,
                         frictions: Friction | Iterable[Friction], cors, *,
                         rtol: float | None = None, duration: float | None = None):
    """Every combination of blocks, frictions and COR on one motion, from rest, in parallel.

    Parameters
    ----------
    blocks : Block or sequence of Block
        No prestress rods.
    motion : Motion
        Table accelerations [m/s^2] (no rotation).
    frictions : Friction or sequence of Friction
    cors : float, "housner" or a sequence of them
    rtol : float, optional
        DOP853 relative tolerance [-] (default 1e-12).
    duration : float, optional
        Length of the runs [s].

    Returns
    -------
    pandas.DataFrame
        One row per run: block height, width [m], mu_s, mu_d, cor, status, verdict,
        max_theta_ratio [-], peak slip [m], residual slip [m], peak corner excursion [m],
        t_overturn [s], n_impacts, time in each mode [s].
    """
    import pandas as pd

    blocks = [blocks] if isinstance(blocks, Block) else list(blocks)
    frictions = [frictions] if isinstance(frictions, Friction) else list(frictions)
    cors = [cors] if isinstance(cors, (int, float, str)) else list(cors)
    if not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable.Motion, got {type(motion).__name__}")
    if motion.rotation is not None and np.any(motion.rotation != 0.0):
        raise ValueError("motion: the coupled model (friction=...) has no table rotation")
    motion = extended(motion, duration)
    cases = list(itertools.product(range(len(blocks)), range(len(frictions)), range(len(cors))))
    m = len(cases)
    parameters = np.zeros((m, N_PARAMETERS))
    rho, cor_cascade = np.zeros(m), np.zeros(m)
    mu_s, mu_d = np.zeros(m), np.zeros(m)
    for i, (b, f, c) in enumerate(cases):
        friction = check_planar_inputs(blocks[b], frictions[f])
        parameters[i] = block_parameters(blocks[b])
        rho[i], cor_cascade[i] = impact_ratios(blocks[b], cors[c])
        mu_s[i], mu_d[i] = friction.static, friction.dynamic
    info = np.zeros((m, planar.N_INFO))
    final = np.zeros((m, planar.N_OUT))
    _run_cases((np.ascontiguousarray(motion.t, dtype=float),
                np.ascontiguousarray(motion.horizontal, dtype=float),
                np.ascontiguousarray(motion.vertical_or_zero, dtype=float),
                parameters, rho, cor_cascade, mu_s, mu_d,
                DEFAULT_PLANAR_RTOL if rtol is None else float(rtol), -1.0, info, final),
               m, numba.get_num_threads())
    rows = []
    for i, (b, f, c) in enumerate(cases):
        row = info[i]
        status = planar.STATUSES[int(row[planar.I_STATUS])]
        visited = int(row[planar.I_VISITED])
        largest = max(code for code in range(len(MODES)) if visited >> code & 1)
        overturned = status == "overturned"
        rows.append({
            "block_height [m]": blocks[b].height, "block_width [m]": blocks[b].width,
            "static friction mu_s [-]": mu_s[i], "dynamic friction mu_d [-]": mu_d[i],
            "cor [-]": cors[c], "status": status,
            "verdict": "overturned" if overturned else VERDICTS[largest],
            "max_theta_ratio [-]": (np.nan if overturned
                                    else row[planar.I_MAX_ABS_THETA] / blocks[b].alpha),
            "peak slip [m]": row[planar.I_PEAK_SLIP],
            "residual slip [m]": final[i, planar.OUT_SLIP],
            "peak corner excursion [m]": row[planar.I_PEAK_EXCURSION],
            "t_overturn [s]": row[planar.I_T_OVERTURN],
            "n_impacts": int(row[planar.I_N_IMPACTS]),
            **{f"time {name} [s]": row[index] for name, index in zip(MODES, (
                planar.I_TIME_REST, planar.I_TIME_SLIDE, planar.I_TIME_ROCK,
                planar.I_TIME_SLIDE_ROCK, planar.I_TIME_FLIGHT))},
        })
    return pd.DataFrame(rows)
