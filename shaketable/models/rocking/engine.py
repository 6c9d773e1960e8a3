"""Compiled event-driven integration of Eq. (2-13)/(2-14) (numba).

One driver, :func:`integrate`, walks the ground-motion samples interval by
interval (the ground acceleration is linear inside each one, Section 2.8 of the
report, so the right-hand side is smooth there) and hands each piece of free
flight to one of three steppers:

``METHOD_FAST``
    The Runge-Kutta-Nystrom pair RKN6(4)6FM of Dormand, El-Mikkawy and Prince
    (order 6, embedded order 4, first same as last: five new evaluations per
    step), which integrates theta'' = f(t, theta) directly, with a PI
    step-size controller on a mixed absolute/relative error, steps ending on
    every sample of the input. Events (impact at theta = 0, |theta| = alpha,
    |theta| = pi/2 and the turning points theta' = 0) are located by a
    safeguarded Newton iteration on the *stepper itself* (one step from the
    step's start to the trial time), so an event time is as accurate as the
    integration.
``METHOD_PREDICTOR_CORRECTOR``
    The report's two-step scheme (Section 2.8): each input interval is divided
    into ``subdivisions`` equal steps; each step predicts with an explicit Euler
    step and corrects with the trapezoidal rule (Heun's method, second order).
``METHOD_LINEAR``
    Housner's slender-block linearisation, Eq. (2-4) extended to ground motion
    and rods: theta'' = mu theta + c0 + c1 tau, solved in closed form on each
    interval (cosh/sinh, or cos/sin when stiff rods make mu negative). The
    vertical acceleration is held at its value at the middle of each step so
    that the closed form exists.

During one flight (between two impacts) the block pivots on one corner,
``side``; the steppers integrate that corner's equation, which is analytic in
theta (:func:`flight_acceleration`). Eq. (2-13)/(2-14) switches corner where
theta changes sign, a jump of 2 g b / I0 in theta'' that an explicit step
straddling theta = 0 (or a stage of it) would see as an error of order one:
the step-size controller then rejected steps over and over while it crept up
on every impact. The analytic continuation past theta = 0 makes every step
smooth, and the impact is where the continued solution reaches zero.

An impact can hide inside one step: theta dips below 0 and comes back before
the step ends. With one turning point in the step, theta' changes sign and the
driver locates the turning point and, when it lies past 0, the impact before
it. With two (theta' of one sign at both ends, the ground acceleration ramping
fast), :func:`~shaketable.models.rocking.events.dip_on_stepper` searches the cubic
Hermite interpolant of theta, theta' at the step ends and confirms the dip on
the stepper itself; the same check makes a step that ends past 0 after three
crossings stop at the first.
Steps without such a dip are not changed.

All three share the event logic: start of rocking at the exact crossing of
Eq. (2-1) inside an interval, the impact map theta' -> cor * theta', the
summation of the endless cascade of impacts of a decaying block
(:func:`shaketable.models.rocking.physics.cascade_rest_time`), unstable / overturned, and the
block leaving the ground when g + vg <= 0.

First compile: each method has its own compiled integrator, the driver's code
with the method a compile-time constant and the method's functions bound to the names it
calls (:func:`_integrator`), so the default method's first compile types and optimises
only its own code, with no compiled layer that chooses a method's function. numba's first
compile costs about 1 ms of CPU per float operation, 4 ms per branch, 3.5 ms per call of
a helper returning a tuple and 25 ms per compiled function (``benchmarks/cold_start.py
--constructs``): hence the events of a step
(:func:`~shaketable.models.rocking.events.step_events`, which LLVM still inlines) and the rest
after an impact (:func:`_rest_after_impact`) are compiled apart from the driver (splitting
further did not pay: each split links and optimises the event location once more), the
driver's phases (:data:`_PHASES`) are inlined into it before typing, an impact is located
from one call site, and conditions of several comparisons are combined with ``&`` and
``|`` (no short-circuit branches).
``--breakdown`` shows where the rest goes.
"""

from __future__ import annotations

import math
import types

from numba import boolean, int64, njit

from shaketable.core.constants import G
from shaketable.models.rocking import events
from shaketable.models.rocking.events import bound_per_method, step_events
from shaketable.models.rocking.layout import (
    EVENT_IMPACT,
    EVENT_OVERTURN,
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
    METHOD_FAST,
    METHOD_LINEAR,
    METHOD_PREDICTOR_CORRECTOR,
    N_INFO,
    STATUS_AIRBORNE,
    STATUS_COMPLETED,
    STATUS_OVERTURNED,
)
from shaketable.models.rocking.physics import (
    ALPHA,
    ERROR_MODEL,
    HALF_HEIGHT,
    HALF_WIDTH,
    HOLD_DOWN,
    cascade_rest_time,
)
from shaketable.models.rocking.steppers import (
    HELPER_OPTIONS,
    METHOD_FUNCTIONS,
    ground,
    helper,
)

# Eq. (2-13)/(2-14)'s cascade sum as a compiled helper (shaketable.models.rocking.physics' keeps its
# Python entry; see shaketable.models.rocking.steppers).
_cascade_rest_time = helper(cascade_rest_time.py_func)


# placeholders: each integrator binds the method's functions to these names (_integrator)
model_acceleration = flight_model = advance = bound_per_method

# Right-hand-side evaluations per trial step (the Nystrom pair reuses its last stage).
_EVALUATIONS_FAST, _EVALUATIONS_PREDICTOR_CORRECTOR, _EVALUATIONS_LINEAR = 5, 2, 1


def _first_positive_margin(start, t_end, side, segment, parameters):
    """The first time in [start, t_end] at which rocking onto ``side`` really begins [s].

    ``start`` is the crossing of Eq. (2-1) located by linear interpolation of
    the margin s theta''(theta = 0), which is affine in time inside an input
    interval; there the margin is zero to rounding and may be a few ulps
    negative. A flight begun with s theta'' <= 0 "impacts" at once with zero
    velocity, the block rests at the same instant and the crossing is found
    again: an endless loop. The margin is positive at ``t_end`` (that is how
    the crossing was found), so bisection gives the first representable time
    with a positive margin, a few ulps after ``start``.
    """
    ua, va, ra = ground(segment, start)
    if side * model_acceleration(0.0, side, ua, va, ra, parameters) > 0.0:
        return start
    low = start
    high = t_end
    for _ in range(200):
        middle = 0.5 * (low + high)
        if middle <= low or middle >= high:
            break
        um, vm, rm = ground(segment, middle)
        if side * model_acceleration(0.0, side, um, vm, rm, parameters) > 0.0:
            high = middle
        else:
            low = middle
    return high


def _rest_after_impact(t, omega, side, segment, parameters, cor, rest_tolerance,
                       velocity_floor):
    """Whether the block rests after an impact at ``t``: the time it takes to [s], else -1.

    ``omega`` is theta' just after the impact [rad/s] and ``side`` the corner the block now
    turns about. The endless cascade of impacts that follows is summed in closed form
    (Eq. 2-13/2-14 near theta = 0, :func:`shaketable.models.rocking.physics.cascade_rest_time`)
    and the block put to rest at its end when it is shorter than ``rest_tolerance`` [s],
    or when the impact velocity is below ``velocity_floor`` [rad/s]; without an impact
    velocity it rests at once (0). (-1 is free: the cascade's duration is >= 0 or inf.)
    """
    ux, vx, rx = ground(segment, t)
    deceleration = -side * model_acceleration(0.0, side, ux, vx, rx, parameters)
    remaining = _cascade_rest_time(omega, deceleration, cor)
    if ((remaining == math.inf) & (cor >= 1.0) & (deceleration > 0.0)
            & (abs(omega) <= velocity_floor)):
        # COR = 1 never ends a cascade by itself: bounces of the same tiny velocity,
        # 2|w|/a0 long each, would go on forever (millions per second). Below the velocity
        # floor a bounce rises w^2/(2 a0), far below the integration error: the block is
        # at rest.
        remaining = 0.0
    if ((omega == 0.0) | (remaining <= rest_tolerance)
            | ((abs(omega) <= velocity_floor) & (remaining < math.inf))):
        return 0.0 if omega == 0.0 else remaining
    return -1.0


def integrate(method, t_grid, ug, vg, rg, scale, parameters, cor, theta0, omega0, rtol,
              subdivisions, rest_tolerance, out_theta, out_omega, out_acceleration, impact_times,
              impact_velocities, info):
    """Integrate one run; fill the output arrays and ``info`` (see module constants).

    Each method has its own compiled integrator (:data:`INTEGRATORS`:
    :func:`integrate_fast`, :func:`integrate_predictor_corrector`,
    :func:`integrate_linear`), compiled and cached on its first use: the default
    method's first compile does not include the other two. This calls the method's
    integrator; compiled code (the batch) calls the integrator itself.

    Parameters
    ----------
    method : int
        METHOD_FAST, METHOD_PREDICTOR_CORRECTOR or METHOD_LINEAR.
    t_grid, ug, vg, rg : ndarray
        Sample times [s], ground accelerations [m/s^2] (vertical upward) and
        table angular acceleration [rad/s^2].
    scale : float
        Factor [-] applied to every ground acceleration as it is read (the batch's
        scale factors, without a scaled copy of the record per run; 1 for
        ``simulate``: x * 1.0 is x, bit for bit).
    parameters : ndarray
        From :func:`shaketable.models.rocking.physics.block_parameters`.
    cor : float
        Coefficient of restitution [-].
    theta0, omega0 : float
        Initial rotation [rad] and angular velocity [rad/s].
    rtol : float
        Relative tolerance of METHOD_FAST [-]; absolute tolerances are
        ``rtol * alpha`` [rad] and ``rtol * alpha * p`` [rad/s].
    subdivisions : int
        Steps per input interval for METHOD_PREDICTOR_CORRECTOR.
    rest_tolerance : float
        A cascade of impacts whose summed remaining duration is below this
        [s] is summed in closed form and the block put to rest at its limit;
        negative means the default 1e-6 / p. The cascade is also summed once
        the impact velocity is within 1000 times the velocity tolerance, where
        the integration error would otherwise feed it forever.
    out_theta, out_omega, out_acceleration : ndarray
        Filled with the state at every sample time reached (length 0 arrays:
        nothing is stored, for sweeps that only want the scalar results).
    impact_times, impact_velocities : ndarray
        Filled with the first ``len(impact_times)`` impacts (time [s],
        velocity before impact [rad/s]); ``info[INFO_N_IMPACTS]`` counts all.
    info : ndarray, shape (N_INFO,)
        Filled with the scalar results. ``INFO_EVALUATIONS`` counts every
        right-hand-side evaluation, those of event location included.
    """
    return INTEGRATORS[method](t_grid, ug, vg, rg, scale, parameters, cor, theta0, omega0,
                               rtol, subdivisions, rest_tolerance, out_theta, out_omega,
                               out_acceleration, impact_times, impact_velocities, info)


_METHOD = METHOD_FAST  # each integrator's own value: see _integrator


def _settings(block, rtol, rest_tolerance):
    """The run's constants for the method ``_METHOD``.

    Returns alpha [rad], p [1/s], the absolute tolerances of theta [rad] and theta'
    [rad/s], the rest tolerance [s] (1e-6 / p when ``rest_tolerance`` is negative), the
    impact velocity below which a cascade is summed [rad/s] and the right-hand-side
    evaluations per trial step.
    """
    method = _METHOD
    alpha = block[ALPHA]
    # x * x, not x ** 2: the same number (numba's power by a constant 2 is 1.0 * (x * x)),
    # without compiling numba's integer-power routine on a first run
    radius = math.sqrt(block[HALF_WIDTH] * block[HALF_WIDTH]
                       + block[HALF_HEIGHT] * block[HALF_HEIGHT])
    p = math.sqrt(3.0 * G / (4.0 * radius))
    atol_theta = rtol * alpha
    atol_omega = rtol * alpha * p
    if rest_tolerance < 0.0:
        rest_tolerance = 1e-6 / p
    # Below this velocity an impact is lost in the integration error: sum the cascade.
    velocity_floor = 1e-13 * alpha * p
    if method == METHOD_FAST:
        velocity_floor = max(velocity_floor, 1e3 * atol_omega)
    per_step = _EVALUATIONS_LINEAR
    if method == METHOD_FAST:
        per_step = _EVALUATIONS_FAST
    elif method == METHOD_PREDICTOR_CORRECTOR:
        per_step = _EVALUATIONS_PREDICTOR_CORRECTOR
    return alpha, p, atol_theta, atol_omega, rest_tolerance, velocity_floor, per_step


def _initial_state(info, t_start, theta0, omega0, alpha):
    """Fills ``info`` for the state at ``t_start`` [s] (NaN for what has not happened yet).

    Returns whether the block rests and the corner it turns about (+1 or -1).
    """
    for i in range(N_INFO):
        info[i] = math.nan
    info[INFO_MAX_ABS_THETA] = abs(theta0)
    info[INFO_T_MAX] = t_start
    info[INFO_THETA_AT_MAX] = theta0
    resting = theta0 == 0.0 and omega0 == 0.0
    side = 1.0
    if theta0 < 0.0 or (theta0 == 0.0 and omega0 < 0.0):
        side = -1.0
    if not resting:
        info[INFO_T_START] = t_start
    if abs(theta0) > alpha:
        info[INFO_T_UNSTABLE] = t_start
        info[INFO_UNSTABLE_DIRECTION] = side
    return resting, side


def _contact_end(t0, t1, v0, v1, hold_down):
    """The end of contact in the interval [t0, t1] [s] and whether the block leaves the
    ground there: the model needs g + vg (+ the rods' hold-down) to stay positive."""
    support_0 = G + v0 + hold_down
    support_1 = G + v1 + hold_down
    if support_0 <= 0.0:
        return t0, True
    if support_1 <= 0.0:
        return t0 + (t1 - t0) * support_0 / (support_0 - support_1), True
    return t1, False


def _start_of_rocking(t, t_end, segment, block):
    """When a block at rest at ``t`` starts rocking before ``t_end``, and onto which corner.

    The margin s theta''(theta = 0) of Eq. (2-1) is affine in time inside an input interval:
    the first corner s whose margin turns positive, at the crossing made exact by
    :func:`_first_positive_margin`. Returns (time [s], s), or (``t_end``, 0) when the block
    stays at rest.
    """
    ua, va, ra = ground(segment, t)
    ub, vb, rb = ground(segment, t_end)
    start = math.inf
    start_side = 0.0
    for s in (1.0, -1.0):
        margin_a = s * model_acceleration(0.0, s, ua, va, ra, block)
        margin_b = s * model_acceleration(0.0, s, ub, vb, rb, block)
        if margin_a > 0.0:
            candidate = t
        elif margin_b > 0.0:
            candidate = t + (t_end - t) * (-margin_a) / (margin_b - margin_a)
        else:
            continue
        if candidate < start:
            start = candidate
            start_side = s
    if start_side == 0.0:
        return t_end, 0.0
    return _first_positive_margin(start, t_end, start_side, segment, block), start_side


def _step_length(t, t0, t_end, substep, step_size):
    """The next trial step from ``t`` [s] for the method ``_METHOD``, never past ``t_end``.

    METHOD_FAST: the controller's ``step_size``; METHOD_PREDICTOR_CORRECTOR: up to the next
    of the interval's equal steps of ``substep`` from ``t0``; METHOD_LINEAR: the rest of
    the interval.
    """
    method = _METHOD
    if method == METHOD_FAST:
        h = min(step_size, t_end - t)
    elif method == METHOD_PREDICTOR_CORRECTOR:
        index = math.floor((t - t0) / substep * (1.0 + 1e-12) + 1e-9) + 1.0
        h = min(t0 + index * substep, t_end) - t
        if h <= 1e-12 * substep:
            h = min(substep, t_end - t)
    else:
        h = t_end - t
    return h


def _control(h, theta, omega, theta_new, omega_new, error_theta, error_omega, rtol,
             atol_theta, atol_omega, step_size, previous_error, just_rejected):
    """Step-size control of METHOD_FAST after a trial step of ``h`` [s].

    The error is mixed absolute/relative; the controller is PI (Gustafsson; Hairer &
    Wanner's DOPRI5 constants). Returns whether the step is accepted, the next step
    size [s], the controller's memory (the last accepted error) and whether the step was
    rejected.
    """
    error = max(abs(error_theta) / (atol_theta + rtol * max(abs(theta), abs(theta_new))),
                abs(error_omega) / (atol_omega + rtol * max(abs(omega), abs(omega_new))))
    if not error <= 1.0:  # also NaN
        if error != error:
            error = 1e10
        return False, h * max(0.2, 0.9 * error ** -0.2), previous_error, True
    error = max(error, 1e-10)
    growth = min(5.0, max(0.2, 0.9 * error ** -0.17 * previous_error ** 0.04))
    if just_rejected:
        growth = min(growth, 1.0)
    if h < step_size:
        # a step cut short by the end of the interval says nothing against the step
        # size that was planned
        step_size = max(step_size, h * growth)
    else:
        step_size = h * growth
    return True, step_size, error, False


#: The single block's step-size control under a public name: the stack's one-DOF patterns,
#: integrated with this engine's stepper, take their steps with it
#: (:mod:`shaketable.models.stack.compiled_one`).
step_size_control = _control

def _store(out_theta, out_omega, out_acceleration, index, theta, omega, resting, side, u, v,
           r, block):
    """Stores theta [rad], theta' [rad/s] and theta'' [rad/s^2] (0 at rest) at sample
    ``index``, where the ground accelerations are ``u``, ``v``, ``r``."""
    out_theta[index] = theta
    out_omega[index] = omega
    if resting:
        out_acceleration[index] = 0.0
    else:
        out_acceleration[index] = model_acceleration(theta, side, u, v, r, block)


def _finish(info, t, theta, omega, steps, evaluations, rejected, cascades, status, n_impacts,
            filled):
    """Writes the final state and the run's counts into ``info``."""
    info[INFO_T_END] = t
    info[INFO_THETA_END] = theta
    info[INFO_THETA_DOT_END] = omega
    info[INFO_STEPS] = steps
    info[INFO_EVALUATIONS] = evaluations
    info[INFO_REJECTED] = rejected
    info[INFO_CASCADES] = cascades
    info[INFO_STATUS] = status
    info[INFO_N_IMPACTS] = n_impacts
    info[INFO_N_OUTPUT] = filled


def _drive(t_grid, ug, vg, rg, scale, parameters, cor, theta0, omega0, rtol, subdivisions,
           rest_tolerance, out_theta, out_omega, out_acceleration, impact_times,
           impact_velocities, info):
    """:func:`integrate` for the method ``_METHOD`` (a compile-time constant, see
    :func:`_integrator`).

    Interval by interval of the record: a block at rest waits for the start of rocking
    (:func:`_start_of_rocking`); in flight, a step (:func:`_step_length`, ``advance``,
    :func:`_control`), its events (``step_events``) and at an impact Section 2.7's map
    and the rest that may follow (:func:`_rest_after_impact`).
    """
    method = _METHOD
    n = t_grid.shape[0]
    store = out_theta.shape[0] >= n
    # The block's parameters as a tuple of floats: every helper below takes them by value
    # (an array argument costs an atomic reference-count increment and decrement per call,
    # which were a third of the run time); the arithmetic is the same, bit for bit.
    block = (parameters[0], parameters[1], parameters[2], parameters[3], parameters[4],
             parameters[5], parameters[6], parameters[7], parameters[8], parameters[9])
    alpha, p, atol_theta, atol_omega, rest_tolerance, velocity_floor, per_step = _settings(
        block, rtol, rest_tolerance)
    hold_down = block[HOLD_DOWN]
    max_recorded = impact_times.shape[0]
    # Loop-carried counters and flags start as int64(0) and boolean(False), not 0 and False:
    # a literal, widened later in the loop, cost the first compile two more typing passes.
    n_impacts = int64(0)
    steps = int64(0)
    evaluations = int64(0)
    rejected = int64(0)
    cascades = int64(0)
    status = int64(STATUS_COMPLETED)

    theta, omega = theta0, omega0
    resting, side = _initial_state(info, t_grid[0], theta0, omega0, alpha)
    t = rest_until = last_impact = t_grid[0]
    step_size = 0.1 / p
    previous_error = 1e-4  # PI controller memory
    acceleration = 0.0     # theta'' of the flight model at (t, theta), when known
    known = boolean(False)
    just_rejected = boolean(False)

    if store:
        _store(out_theta, out_omega, out_acceleration, 0, theta, omega, resting, side,
               ug[0] * scale, vg[0] * scale, rg[0] * scale, block)
    filled = int64(1)

    for k in range(n - 1):
        t0 = t_grid[k]
        t1 = t_grid[k + 1]
        # a tuple, not an array: passed by value, with no reference counting per call
        u0, u1 = ug[k] * scale, ug[k + 1] * scale
        v0, v1 = vg[k] * scale, vg[k + 1] * scale
        r0, r1 = rg[k] * scale, rg[k + 1] * scale
        segment = (t0, t1 - t0, u0, u1 - u0, v0, v1 - v0, r0, r1 - r0)
        t_end, airborne = _contact_end(t0, t1, v0, v1, hold_down)
        substep = (t1 - t0) / subdivisions

        while t < t_end:
            if resting:
                if rest_until >= t_end:
                    t = t_end
                    break
                if rest_until > t:
                    t = rest_until
                t, start_side = _start_of_rocking(t, t_end, segment, block)
                if start_side == 0.0:
                    break
                side = start_side
                theta = 0.0
                omega = 0.0
                known = False
                resting = False
                if math.isnan(info[INFO_T_START]):
                    info[INFO_T_START] = t
                continue

            if not known:
                if method != METHOD_LINEAR:  # the closed form does not need it
                    ua, va, ra = ground(segment, t)
                    acceleration = flight_model(theta, side, ua, va, ra, block)
                    evaluations += 1
                known = True

            # ---- one step of free flight about the active corner
            h = _step_length(t, t0, t_end, substep, step_size)
            theta_new, omega_new, acceleration_new, error_theta, error_omega = advance(
                t, theta, omega, acceleration, side, h, segment, block)
            evaluations += per_step
            if method == METHOD_FAST:
                accepted, step_size, previous_error, just_rejected = _control(
                    h, theta, omega, theta_new, omega_new, error_theta, error_omega, rtol,
                    atol_theta, atol_omega, step_size, previous_error, just_rejected)
                if not accepted:
                    rejected += 1
                    continue

            # ---- events inside the step: impact, overturn (terminal), peak, instability
            tau, kind, theta_new, omega_new, acceleration_new, located = step_events(
                t, theta, omega, acceleration, side, h, theta_new, omega_new,
                acceleration_new, segment, block, info)
            evaluations += located * per_step

            t = t + tau
            theta = theta_new
            omega = omega_new
            acceleration = acceleration_new
            steps += 1

            if kind == EVENT_OVERTURN:
                status = STATUS_OVERTURNED
                info[INFO_T_OVERTURN] = t
                info[INFO_OVERTURN_DIRECTION] = side
                break
            if kind == EVENT_IMPACT:
                # the next flight is shorter than the last one: do not try a longer step
                step_size = min(step_size, max(t - last_impact, 1e-3 * step_size))
                last_impact = t
                if n_impacts < max_recorded:
                    impact_times[n_impacts] = t
                    impact_velocities[n_impacts] = omega
                n_impacts += 1
                omega = cor * omega           # Section 2.7 (5), one signed theta
                side = -side
                theta = 0.0
                known = False
                remaining = _rest_after_impact(t, omega, side, segment, block, cor,
                                               rest_tolerance, velocity_floor)
                if remaining >= 0.0:
                    if omega != 0.0:
                        cascades += 1
                    resting = True
                    rest_until = t + remaining
                    info[INFO_T_REST] = rest_until
                    omega = 0.0

        if status != STATUS_COMPLETED:
            break
        if airborne:
            status = STATUS_AIRBORNE
            info[INFO_T_AIRBORNE] = t_end
            break
        if store:
            _store(out_theta, out_omega, out_acceleration, k + 1, theta, omega, resting, side,
                   u1, v1, r1, block)
        filled = k + 2

    _finish(info, t, theta, omega, steps, evaluations, rejected, cascades, status, n_impacts,
            filled)


# The helpers that call the method's functions: each integrator compiles its own copies
# (those of shaketable.models.rocking.events first, in a copy of that module's namespace).
_METHOD_HELPERS = events.METHOD_HELPERS + (
    "_first_positive_margin", "_rest_after_impact", "_settings", "_initial_state",
    "_contact_end", "_start_of_rocking", "_step_length", "_control", "_store", "_finish")
# Those that LLVM inlines into the driver (forceinline: LLVM's alwaysinline): part of its
# body, called at every step, compiled apart only to keep numba's first compile short;
# inlined because a call at every step makes the batch slower (benchmarks/batch_rate.py).
_INLINED_HELPERS = ("step_events",)
_INLINED_HELPER = njit(**{**HELPER_OPTIONS, "forceinline": True})
# The driver's phases: numba inlines them into the driver before typing (inline="always"),
# so that the driver compiles and runs as one function, as when they were written in it.
_PHASES = ("_settings", "_initial_state", "_contact_end", "_start_of_rocking",
           "_step_length", "_control", "_store", "_finish")
_PHASE = njit(inline="always", error_model=ERROR_MODEL)


def _integrator(method, name):
    """:func:`_drive` compiled for ``method`` (cached): one compiled integrator per method.

    The same Python code, in a copy of this module's namespace in which ``_METHOD`` is
    ``method`` and ``model_acceleration``, ``flight_model`` and ``advance`` are the
    method's functions (:data:`~shaketable.models.rocking.steppers.METHOD_FUNCTIONS`); the helpers
    that call those (:data:`_METHOD_HELPERS`) are compiled from it too (those of
    :mod:`shaketable.models.rocking.events` from a copy of that module's namespace, bound the
    same way), each under a name of its own. numba reads ``method == METHOD_...`` as a
    comparison of two constants and drops the other methods' branches before typing. The namespace is copied at import:
    replacing a helper in the module afterwards does not change the integrators.

    The integrator allocates no array: it is compiled without numba's reference counting
    (``_nrt=False``). nogil: a long run can go on in a thread (Ctrl-C,
    models.rocking.run.call_interruptibly), and the batch runs them on several threads.
    """
    namespace = dict(_drive.__globals__, _METHOD=method, **METHOD_FUNCTIONS[method])
    events_namespace = dict(vars(events), **METHOD_FUNCTIONS[method])
    for helper_name in _METHOD_HELPERS:
        own = events_namespace if helper_name in events.METHOD_HELPERS else namespace
        code = own[helper_name]
        copy = types.FunctionType(code.__code__, own, helper_name)
        # a name of its own: numba names the compiled symbol after the qualified name and the
        # argument types, and the integrators link their helpers in as weak symbols, so
        # that two integrators loaded from the cache into one process would otherwise share
        # one method's copy
        copy.__qualname__ = f"{name}.{helper_name}"
        compile_as = (_INLINED_HELPER if helper_name in _INLINED_HELPERS
                      else _PHASE if helper_name in _PHASES else helper)
        own[helper_name] = namespace[helper_name] = compile_as(copy)
    function = types.FunctionType(_drive.__code__, namespace, name)
    function.__qualname__ = name
    function.__doc__ = f":func:`integrate` with method code {method}."
    return njit(cache=True, nogil=True, _nrt=False, no_cfunc_wrapper=True,
                error_model=ERROR_MODEL)(function)


integrate_fast = _integrator(METHOD_FAST, "integrate_fast")
integrate_predictor_corrector = _integrator(METHOD_PREDICTOR_CORRECTOR,
                                            "integrate_predictor_corrector")
integrate_linear = _integrator(METHOD_LINEAR, "integrate_linear")

#: The compiled integrator of each method code.
INTEGRATORS = {METHOD_FAST: integrate_fast,
               METHOD_PREDICTOR_CORRECTOR: integrate_predictor_corrector,
               METHOD_LINEAR: integrate_linear}
