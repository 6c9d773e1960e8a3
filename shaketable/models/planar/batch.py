"""Many runs of the planar block at once: blocks x frictions x COR on one motion, compiled,
in parallel, scalar results only (no time histories).

The batch of the rocking model is :mod:`shaketable.models.rocking.batch`; this one calls the
planar engine (:func:`shaketable.models.planar.engine.integrate`, compiled without the GIL) with
length-0 output arrays, exactly as :func:`~shaketable.models.planar.run.simulate_planar`
does with full ones, so a row equals that run's summary on the columns they share; the
cases are shared among Python threads as the rocking batch's
(:func:`~shaketable.models.rocking.run.run_in_chunks`). The batch therefore compiles nothing
of its own.
"""

from __future__ import annotations

import itertools
import threading
from collections.abc import Iterable

import numpy as np

from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.core.motion import Motion
from shaketable.core.validation import in_range
from shaketable.models.planar import engine as planar
from shaketable.models.planar.result import MODES, VERDICTS
from shaketable.models.planar.run import DEFAULT_PLANAR_RTOL, check_planar_inputs, impact_ratios
from shaketable.models.rocking.physics import N_PARAMETERS, block_parameters
from shaketable.models.rocking.run import (
    MIN_RTOL,
    engine_arrays,
    extended,
    run_in_chunks,
    thread_count,
)
from shaketable.models.sliding.result import Friction


def _one_or_many(value, kinds: tuple, name: str, what: str) -> list:
    """``value`` as a non-empty list of ``kinds``: one item, or a sequence of them; a
    TypeError or ValueError naming the parameter ``name`` otherwise."""
    if isinstance(value, kinds):
        return [value]
    if value is None or isinstance(value, (bytes, dict)) or not hasattr(value, "__iter__"):
        raise TypeError(f"simulate_many_planar: {name} must be {what} or a sequence of them, "
                        f"got {type(value).__name__}")
    items = list(value)
    if not items:
        raise ValueError(f"simulate_many_planar: {name} is empty; give {what} or more")
    wrong = [item for item in items if not isinstance(item, kinds) or isinstance(item, bool)]
    if wrong:
        raise TypeError(f"simulate_many_planar: {name} must hold {what} each, got "
                        f"{type(wrong[0]).__name__} ({wrong[0]!r})")
    return items


def simulate_many_planar(blocks: Block | Iterable[Block], motion: Motion,
                         frictions: Friction | Iterable[Friction], cors, *,
                         rtol: float | None = None, duration: float | None = None,
                         threads: int | None = None):
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
    threads : int, optional
        Number of threads, at most :data:`numba.config.NUMBA_NUM_THREADS` (default
        ``numba.get_num_threads()``: all cores unless set lower); one runs the cases in the
        calling thread. The results do not depend on it.

    Returns
    -------
    pandas.DataFrame
        One row per run: block height, width [m], mu_s, mu_d, cor, status, verdict,
        max_theta_ratio [-], peak slip [m], residual slip [m], peak corner excursion [m],
        t_overturn [s], n_impacts, time in each mode [s].
    """
    import pandas as pd

    blocks = _one_or_many(blocks, (Block, AsymmetricBlock), "blocks", "a Block")
    if any(isinstance(block, AsymmetricBlock) for block in blocks):
        raise ValueError("block: the planar batch takes Blocks; run an AsymmetricBlock one at a "
                         "time (simulate(..., friction=...))")
    frictions = _one_or_many(frictions, (Friction,), "frictions", "a Friction")
    cors = _one_or_many(cors, (int, float, str, np.floating, np.integer), "cors",
                        "a COR (a number in [0, 1] or 'housner')")
    if not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable.Motion, got {type(motion).__name__}")
    if motion.rotation is not None and np.any(motion.rotation != 0.0):
        raise ValueError("motion: the coupled model (friction=...) has no table rotation")
    threads = thread_count(threads)
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
    t_grid, ug, vg = engine_arrays(motion.t, motion.horizontal, motion.vertical_or_zero)
    rtol = DEFAULT_PLANAR_RTOL if rtol is None else in_range("rtol", rtol, MIN_RTOL, 1.0)
    none, no_events = np.empty((0, planar.N_OUT)), np.empty((0, planar.EVENT_COLUMNS))

    per_thread = threading.local()

    def run(start: int, stop: int) -> None:
        # the engine's own compiled entry point, with simulate_planar's argument types
        # (floats, not NumPy scalars): one compiled signature for both; one set of work
        # arrays per thread
        work = getattr(per_thread, "work", None)
        if work is None:
            work = per_thread.work = planar.work_arrays()
        for i in range(start, stop):
            planar.integrate(t_grid, ug, vg, parameters[i], float(rho[i]),
                             float(cor_cascade[i]), float(mu_s[i]), float(mu_d[i]), rtol, -1.0,
                             0.0, 0.0, none, no_events, final[i], info[i], *work)

    # one case at a time: run costs differ a lot (a block that overturns early is cheap),
    # and a call costs microseconds against the milliseconds of a run
    run_in_chunks(run, m, threads, 1)
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
            "peak base slip [m]": row[planar.I_PEAK_BASE_SLIP],
            "residual slip [m]": final[i, planar.OUT_SLIP],
            "peak corner excursion [m]": row[planar.I_PEAK_EXCURSION],
            "t_overturn [s]": row[planar.I_T_OVERTURN],
            "n_impacts": int(row[planar.I_N_IMPACTS]),
            **{f"time {name} [s]": row[index] for name, index in zip(MODES, (
                planar.I_TIME_REST, planar.I_TIME_SLIDE, planar.I_TIME_ROCK,
                planar.I_TIME_SLIDE_ROCK, planar.I_TIME_FLIGHT))},
        })
    return pd.DataFrame(rows)
