"""The asymmetric block's own compiled solver (numba): Eq. (2-13) with a b, I0 and alpha per pivot.

A block whose centre of mass is not over the middle of its base
(:class:`~shaketable.core.geometry.AsymmetricBlock`) rocks on each pivot with that
pivot's b_s, I0_s and alpha_s; the equation of motion is the package's one statement,
:func:`shaketable.models.rocking.physics.flight_acceleration`, called with the row of
:func:`~shaketable.models.rocking.physics.side_parameters` of the active pivot. The compiled
engine of the symmetric :class:`~shaketable.core.geometry.Block`
(:mod:`shaketable.models.rocking.engine`) is untouched: a symmetric block runs there exactly as
before, and an asymmetric one here.

The scheme: classical fourth-order Runge-Kutta steps of at most ``max_step`` inside each
input interval (the ground acceleration linear there, as in the engine); an impact
(theta reaching 0 on the active side) located by a safeguarded Newton iteration on the
step length, each trial one Runge-Kutta step from the flight's last state; the impact
law theta' -> c_s theta' with the COR of the pivot the block lands on
(:func:`~shaketable.models.rocking.physics.impact_cors`: the report's constant COR, or Housner's
for each pivot); the start of rocking where the uplift margin of either side turns
positive (Eq. 2-1 per side: |ug| h > (g + vg) b_s, linear inside an interval, so its
zero is found exactly); a cascade of impacts summed in closed form
(:func:`~shaketable.models.rocking.physics.cascade_rest_time`); overturned at |theta| = pi/2 as in
the engine. A dip of theta below zero that begins and ends inside one step is not seen
(the steps are short: ``max_step`` defaults to 0.01 / p).

:func:`simulate_asymmetric` runs one block (``method="fast"`` here, ``"reference"`` the
SciPy reference, :mod:`shaketable.models.rocking.reference`); :func:`simulate_many_asymmetric`
runs many (block, motion, COR, scale) cases without the GIL.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numba import njit

from shaketable.core.constants import G
from shaketable.core.geometry import AsymmetricBlock
from shaketable.core.motion import Motion, whole_number
from shaketable.core.validation import in_range
from shaketable.models.rocking.asymmetric_result import AsymmetricResult
from shaketable.models.rocking.layout import (
    INFO_CASCADES,
    INFO_EVALUATIONS,
    INFO_MAX_ABS_THETA,
    INFO_N_IMPACTS,
    INFO_N_OUTPUT,
    INFO_OVERTURN_DIRECTION,
    INFO_REJECTED,
    INFO_STATUS,
    INFO_STEPS,
    INFO_T_AIRBORNE,
    INFO_T_END,
    INFO_T_MAX,
    INFO_T_OVERTURN,
    INFO_T_REST,
    INFO_T_START,
    INFO_T_UNSTABLE,
    INFO_THETA_AT_MAX,
    INFO_THETA_DOT_END,
    INFO_THETA_END,
    INFO_UNSTABLE_DIRECTION,
    N_INFO,
    STATUS_AIRBORNE,
    STATUS_COMPLETED,
    STATUS_OVERTURNED,
)
from shaketable.models.rocking.physics import (
    ALPHA,
    ERROR_MODEL,
    N_PARAMETERS,
    cascade_rest_time,
    flight_acceleration,
    impact_cors,
    side_parameters,
)
from shaketable.models.rocking.run import (
    engine_arrays,
    extended,
    run_in_chunks,
    run_motion,
    thread_count,
)

#: Longest Runge-Kutta step, as a fraction of 1 / p of the quicker side [-]: p h = 0.01
#: makes the classical scheme's error per step ~1e-12 of the motion.
STEP_FRACTION = 0.01


@njit(cache=True, error_model=ERROR_MODEL, nogil=True)
def _acceleration(theta, side, u, v, plus, minus):
    if side > 0.0:
        return flight_acceleration(theta, side, u, v, 0.0, plus)
    return flight_acceleration(theta, side, u, v, 0.0, minus)


@njit(cache=True, error_model=ERROR_MODEL, nogil=True)
def _rk4(theta, omega, side, start, tau, u0, du, v0, dv, plus, minus):
    """One classical Runge-Kutta step of length ``tau`` from ``start`` (time in the interval)."""
    half = start + 0.5 * tau
    end = start + tau
    a1 = _acceleration(theta, side, u0 + du * start, v0 + dv * start, plus, minus)
    w2 = omega + 0.5 * tau * a1
    a2 = _acceleration(theta + 0.5 * tau * omega, side, u0 + du * half, v0 + dv * half,
                       plus, minus)
    w3 = omega + 0.5 * tau * a2
    a3 = _acceleration(theta + 0.5 * tau * w2, side, u0 + du * half, v0 + dv * half,
                       plus, minus)
    w4 = omega + tau * a3
    a4 = _acceleration(theta + tau * w3, side, u0 + du * end, v0 + dv * end, plus, minus)
    theta_new = theta + tau * (omega + 2.0 * w2 + 2.0 * w3 + w4) / 6.0
    omega_new = omega + tau * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0
    return theta_new, omega_new


@njit(cache=True, error_model=ERROR_MODEL, nogil=True)
def _locate(theta, omega, side, start, upper, theta_upper, omega_upper, u0, du, v0, dv,
            plus, minus, scale_t, level, sign):
    """Step length in (0, upper] at which side * theta reaches ``level``, and theta' there.

    g = sign (side * theta - level) is positive at 0 (an impact: level 0, sign +1, just
    after the flight's start; an overturn: level pi/2, sign -1) and <= 0 at ``upper``;
    Newton on the step length (the rate is sign side theta' of the same trial step),
    replaced by bisection outside the bracket.
    """
    a = 0.0
    b = upper
    c = upper
    gc = sign * (side * theta_upper - level)
    dgc = sign * side * omega_upper
    wc = omega_upper
    tolerance = 4e-16 * scale_t + 1e-300
    trials = 0
    for _ in range(200):
        newton = math.inf if dgc == 0.0 else gc / dgc
        candidate = c - newton
        if not (a < candidate < b):
            candidate = 0.5 * (a + b)
        if abs(newton) <= tolerance or b - a <= tolerance:
            break
        x, w = _rk4(theta, omega, side, start, candidate, u0, du, v0, dv, plus, minus)
        trials += 1
        c, gc, dgc, wc = candidate, sign * (side * x - level), sign * side * w, w
        if gc > 0.0:
            a = candidate
        else:
            b = candidate
    return c, wc, trials


@njit(cache=True, error_model=ERROR_MODEL, nogil=True)
def _start_time(t_from, t1, u0, du, v0, dv, t0, plus, minus):
    """(time, side) of the first uplift in [t_from, t1], else (inf, 0): Eq. (2-1) per side."""
    start = math.inf
    start_side = 0.0
    for s in (1.0, -1.0):
        margin_a = s * _acceleration(0.0, s, u0 + du * (t_from - t0), v0 + dv * (t_from - t0),
                                     plus, minus)
        margin_b = s * _acceleration(0.0, s, u0 + du * (t1 - t0), v0 + dv * (t1 - t0),
                                     plus, minus)
        if margin_a > 0.0:
            candidate = t_from
        elif margin_b > 0.0:
            candidate = t_from + (t1 - t_from) * (-margin_a) / (margin_b - margin_a)
        else:
            continue
        if candidate < start:
            start = candidate
            start_side = s
    if start_side != 0.0:
        # where the margin is strictly positive (at the interpolated zero it is zero to
        # rounding, and the flight would end at once): the engine's and reference's rule
        low = start
        high = t1
        if start_side * _acceleration(0.0, start_side, u0 + du * (start - t0),
                                      v0 + dv * (start - t0), plus, minus) <= 0.0:
            for _ in range(200):
                middle = 0.5 * (low + high)
                if middle <= low or middle >= high:
                    break
                if start_side * _acceleration(0.0, start_side, u0 + du * (middle - t0),
                                              v0 + dv * (middle - t0), plus, minus) > 0.0:
                    high = middle
                else:
                    low = middle
            start = high
    return start, start_side


@njit(cache=True, error_model=ERROR_MODEL, nogil=True)
def integrate_asymmetric(t, ug, vg, scale, plus, minus, cor_onto_plus, cor_onto_minus, theta0,
                         omega0, max_step, rest_tolerance, out_theta, out_omega, impact_times, info):
    """Integrate one run; fills ``info`` (the engine's layout) and, when they are long
    enough, ``out_theta`` / ``out_omega`` at the input samples; the first impacts' times in
    ``impact_times`` (as many as it holds).

    ``plus`` and ``minus`` are the two rows of :func:`side_parameters`; ``scale``
    multiplies ``ug``; ``cor_onto_plus`` is the COR of an impact that lands on the pivot of
    theta > 0.
    """
    n = t.shape[0]
    store = out_theta.shape[0] >= n
    for i in range(N_INFO):
        info[i] = math.nan
    theta = theta0
    omega = omega0
    side = 1.0
    if theta < 0.0 or (theta == 0.0 and omega < 0.0):
        side = -1.0
    resting = theta == 0.0 and omega == 0.0
    rest_until = t[0]
    info[INFO_MAX_ABS_THETA] = abs(theta)
    info[INFO_T_MAX] = t[0]
    info[INFO_THETA_AT_MAX] = theta
    if not resting:
        info[INFO_T_START] = t[0]
    steps = 0
    trials = 0
    impacts = 0
    cascades = 0
    status = STATUS_COMPLETED
    # below this theta' an impact is lost in the integration error: sum the cascade
    velocity_floor = 1e-9 * min(plus[ALPHA], minus[ALPHA]) * STEP_FRACTION / max_step
    if store:
        out_theta[0] = theta
        out_omega[0] = omega
    filled = 1
    tt = t[0]
    scale_t = abs(t[-1]) + 1.0
    for k in range(n - 1):
        t0 = t[k]
        t1 = t[k + 1]
        u0 = scale * ug[k]
        du = (scale * ug[k + 1] - u0) / (t1 - t0)
        v0 = vg[k]
        dv = (vg[k + 1] - v0) / (t1 - t0)
        if G + vg[k + 1] <= 0.0 or G + v0 <= 0.0:
            status = STATUS_AIRBORNE
            info[INFO_T_AIRBORNE] = t0
            break
        stalled = 0
        while tt < t1:
            if resting:
                if rest_until >= t1:
                    tt = t1
                    break
                tt = max(tt, rest_until)
                start, start_side = _start_time(tt, t1, u0, du, v0, dv, t0, plus, minus)
                if start_side == 0.0:
                    tt = t1
                    break
                tt = start
                side = start_side
                theta = 0.0
                omega = 0.0
                resting = False
                if math.isnan(info[INFO_T_START]):
                    info[INFO_T_START] = tt
                continue
            tau = min(max_step, t1 - tt)
            x, w = _rk4(theta, omega, side, tt - t0, tau, u0, du, v0, dv, plus, minus)
            steps += 1
            if side * x <= 0.0:
                tau, w, used = _locate(theta, omega, side, tt - t0, tau, x, w, u0, du, v0, dv,
                                       plus, minus, scale_t, 0.0, 1.0)
                trials += used
                stalled = stalled + 1 if tau <= 0.0 else 0
                tt = tt + tau
                if impacts < impact_times.shape[0]:
                    impact_times[impacts] = tt
                impacts += 1
                side = -side
                theta = 0.0
                cor = cor_onto_plus if side > 0.0 else cor_onto_minus
                omega = cor * w
                deceleration = -side * _acceleration(0.0, side, u0 + du * (tt - t0),
                                                     v0 + dv * (tt - t0), plus, minus)
                remaining = cascade_rest_time(omega, deceleration, cor)
                if omega == 0.0 or remaining <= rest_tolerance or stalled > 100 or (
                        abs(omega) <= velocity_floor and remaining < math.inf):
                    if omega != 0.0:
                        cascades += 1
                    resting = True
                    rest_until = tt + (0.0 if omega == 0.0 or remaining == math.inf
                                       else remaining)
                    info[INFO_T_REST] = rest_until
                    omega = 0.0
                continue
            theta_before = theta
            omega_before = omega
            tt = tt + tau
            theta = x
            omega = w
            alpha_side = plus[ALPHA] if side > 0.0 else minus[ALPHA]
            if abs(theta) > info[INFO_MAX_ABS_THETA]:
                info[INFO_MAX_ABS_THETA] = abs(theta)
                info[INFO_T_MAX] = tt
                info[INFO_THETA_AT_MAX] = theta
            if math.isnan(info[INFO_T_UNSTABLE]) and side * theta > alpha_side:
                info[INFO_T_UNSTABLE] = tt
                info[INFO_UNSTABLE_DIRECTION] = side
            if side * theta >= 0.5 * math.pi:
                back, _, used = _locate(theta_before, omega_before, side, tt - tau - t0, tau,
                                        x, w, u0, du, v0, dv, plus, minus, scale_t,
                                        0.5 * math.pi, -1.0)
                trials += used
                tt = tt - tau + back
                status = STATUS_OVERTURNED
                info[INFO_MAX_ABS_THETA] = 0.5 * math.pi  # as the engine: the run stops there
                info[INFO_THETA_AT_MAX] = side * 0.5 * math.pi
                info[INFO_T_OVERTURN] = tt
                info[INFO_OVERTURN_DIRECTION] = side
                theta = side * 0.5 * math.pi
                break
        if status != STATUS_COMPLETED:
            break
        if store:
            out_theta[k + 1] = theta
            out_omega[k + 1] = omega
        filled = k + 2
    info[INFO_T_END] = tt
    info[INFO_THETA_END] = theta
    info[INFO_THETA_DOT_END] = omega
    info[INFO_STEPS] = steps
    info[INFO_EVALUATIONS] = 4 * (steps + trials)
    info[INFO_REJECTED] = 0
    info[INFO_CASCADES] = cascades
    info[INFO_STATUS] = status
    info[INFO_N_IMPACTS] = impacts
    info[INFO_N_OUTPUT] = filled


@njit(cache=True, error_model=ERROR_MODEL, nogil=True)
def _run_cases(t_all, ug_all, vg_all, offsets, parameters, cors, case_block, case_motion,
               case_scale, max_steps, rest_tolerance, info, first, last):
    empty = np.empty(0)
    for i in range(first, last):
        j = case_block[i]
        q = case_motion[i]
        a = offsets[q]
        b = offsets[q + 1]
        integrate_asymmetric(t_all[a:b], ug_all[a:b], vg_all[a:b], case_scale[i],
                             parameters[j, 0], parameters[j, 1], cors[i, 0], cors[i, 1], 0.0,
                             0.0, max_steps[j], rest_tolerance, empty, empty, empty, info[i])


def _check_block(block) -> AsymmetricBlock:
    if not isinstance(block, AsymmetricBlock):
        raise ValueError(f"block must be a shaketable.AsymmetricBlock, got "
                         f"{type(block).__name__}")
    return block


def default_step(block: AsymmetricBlock) -> float:
    """The longest Runge-Kutta step of a block, :data:`STEP_FRACTION` / p [s]."""
    return STEP_FRACTION / block.p


def simulate_asymmetric(block: AsymmetricBlock, motion: Motion | None = None, *,
                        cor: float | str, theta0: float = 0.0, theta_dot0: float = 0.0,
                        duration: float | None = None, method: str = "fast",
                        max_step: float | None = None, rtol: float = 1e-12,
                        output_dt: float = 0.005,
                        max_recorded_impacts: int = 10_000) -> AsymmetricResult:
    """Rocking response of an asymmetric block, Eq. (2-13) on each pivot with its impact law.

    Parameters
    ----------
    block : AsymmetricBlock
    motion : Motion, optional
        Ground accelerations [m/s^2] (horizontal, optional vertical; a pitch is not
        offered); ``None``: free rocking on a table at rest for ``duration``.
    cor : float or "housner"
        The report's constant COR [-] in [0, 1] for both pivots, or ``"housner"``:
        :meth:`AsymmetricBlock.housner_cor` of the pivot the block lands on.
    theta0, theta_dot0 : float
        Initial state [rad], [rad/s].
    duration : float, optional
        Length of the run [s] (the motion cut or padded with the table at rest).
    method : {"fast", "reference"}
        This module's compiled solver, or the SciPy DOP853 reference.
    max_step : float, optional
        Longest Runge-Kutta step [s] (``"fast"``); default :func:`default_step`.
    rtol : float
        Relative tolerance of the reference [-].
    output_dt : float
        Output interval of free rocking [s].
    max_recorded_impacts : int
        Impact times kept (all are counted).

    Returns
    -------
    AsymmetricResult
    """
    block = _check_block(block)
    if method not in ("fast", "reference"):
        raise ValueError(f"method must be 'fast' or 'reference' for an asymmetric block, got "
                         f"{method!r}")
    theta0 = in_range("theta0", theta0, -0.5 * math.pi, 0.5 * math.pi)
    theta_dot0 = in_range("theta_dot0", theta_dot0)
    cors = impact_cors(block, cor)
    motion = run_motion(motion, duration, output_dt)
    if motion.rotation is not None:
        raise ValueError("motion: a table pitch is not offered for an asymmetric block")
    step = default_step(block) if max_step is None else in_range("max_step", max_step, 0.0,
                                                                  low_open=True)
    rows = side_parameters(block)
    t, ug, vg = engine_arrays(motion.t, motion.horizontal, motion.vertical_or_zero)
    n = t.size
    theta, omega = np.zeros(n), np.zeros(n)
    info = np.zeros(N_INFO)
    rest = 1e-6 / block.p
    recorded = max(1, whole_number("max_recorded_impacts", max_recorded_impacts, minimum=0))
    impact_times, impact_velocities = np.zeros(recorded), np.zeros(recorded)
    if method == "fast":
        integrate_asymmetric(t, ug, vg, 1.0, rows[0], rows[1], cors[0], cors[1], theta0,
                             theta_dot0, step, rest, theta, omega, impact_times, info)
    else:
        from shaketable.models.rocking.reference import integrate_reference  # SciPy: loaded on use

        acceleration = np.zeros(n)
        integrate_reference(t, ug, vg, np.zeros(n), rows[0], block.alpha, block.p, 1.0, theta0,
                            theta_dot0, rtol, rest, theta, omega, acceleration, impact_times,
                            impact_velocities, info, sides=(rows, cors))
    filled = int(info[INFO_N_OUTPUT])
    recorded = min(int(info[INFO_N_IMPACTS]), max_recorded_impacts)
    return AsymmetricResult(block=block, motion=motion, cor_onto_plus=float(cors[0]),
                            cor_onto_minus=float(cors[1]), method=method, t=t[:filled].copy(),
                            theta=theta[:filled].copy(), theta_dot=omega[:filled].copy(),
                            impact_times=impact_times[:recorded].copy(), info=info.copy())


def simulate_many_asymmetric(blocks: Sequence[AsymmetricBlock], motions: Sequence[Motion],
                             cases: np.ndarray, cors: Sequence[float | str], *,
                             scales: np.ndarray | None = None, duration: float | None = None,
                             threads: int | None = None) -> np.ndarray:
    """Many runs of asymmetric blocks at once (compiled, without the GIL).

    Parameters
    ----------
    blocks : sequence of AsymmetricBlock
    motions : sequence of Motion
        Horizontal (and optional vertical) accelerations [m/s^2].
    cases : ndarray of int, shape (n, 2)
        Block index and motion index of each run.
    cors : sequence of float or "housner"
        The COR of each run (length n).
    scales : ndarray, optional
        Factor on each run's horizontal acceleration [-] (default 1).
    duration : float, optional
        Every motion cut or padded to this length [s] (the table at rest after the
        record: the end-of-motion fate is simulated, not guessed).
    threads : int, optional
        Python threads (default numba's thread count).

    Returns
    -------
    ndarray, shape (n, N_INFO)
        The engine's info layout (:mod:`shaketable.models.rocking.layout`) per run.
    """
    blocks = [_check_block(block) for block in blocks]
    cases = np.ascontiguousarray(cases, dtype=np.int64)
    if cases.ndim != 2 or cases.shape[1] != 2:
        raise ValueError(f"cases must have shape (n, 2), got {cases.shape}")
    n = cases.shape[0]
    if len(cors) != n:
        raise ValueError(f"cors must have one entry per case ({n}), got {len(cors)}")
    if n and (cases[:, 0].min() < 0 or cases[:, 0].max() >= len(blocks)
              or cases[:, 1].min() < 0 or cases[:, 1].max() >= len(motions)):
        raise ValueError("cases: a block or motion index out of range")
    runs = [extended(motion, duration) for motion in motions]
    offsets = np.zeros(len(runs) + 1, dtype=np.int64)
    offsets[1:] = np.cumsum([motion.t.size for motion in runs])
    # read-only and C-contiguous like simulate_asymmetric's arrays: one compiled signature
    t_all, ug_all, vg_all = engine_arrays(np.concatenate([motion.t for motion in runs]),
                                          np.concatenate([motion.horizontal for motion in runs]),
                                          np.concatenate([motion.vertical_or_zero
                                                          for motion in runs]))
    block_index, motion_index = np.ascontiguousarray(cases.T)
    parameters = np.empty((len(blocks), 2, N_PARAMETERS))
    for j, block in enumerate(blocks):
        parameters[j] = side_parameters(block)
    cor_rows = np.array([impact_cors(blocks[cases[i, 0]], cors[i]) for i in range(n)]
                        ).reshape(n, 2)
    steps = np.array([default_step(block) for block in blocks])
    scale = np.ones(n) if scales is None else np.ascontiguousarray(scales, dtype=float)
    if scale.shape != (n,):
        raise ValueError(f"scales must have one entry per case ({n}), got shape {scale.shape}")
    rest = 1e-6 / max(block.p for block in blocks)
    info = np.full((n, N_INFO), np.nan)

    def run(first: int, last: int) -> None:
        _run_cases(t_all, ug_all, vg_all, offsets, parameters, cor_rows, block_index,
                   motion_index, scale, steps, rest, info, first, last)

    run_in_chunks(run, n, thread_count(threads), chunk=16)
    return info
