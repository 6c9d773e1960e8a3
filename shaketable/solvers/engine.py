"""Compiled event-driven integration of Eq. (2-13)/(2-14) (numba).

One driver, :func:`integrate`, walks the ground-motion samples interval by
interval (the ground acceleration is linear inside each one, Section 2.8 of the
report, so the right-hand side is smooth there) and hands each piece of free
flight to one of three steppers:

``METHOD_FAST``
    Dormand-Prince 5(4) with step-size control on a mixed absolute/relative
    error, steps ending on every sample of the input. Events (impact at
    theta = 0, |theta| = alpha, |theta| = pi/2 and the turning points
    theta' = 0) are located by a bracketing root finder on the *stepper itself*
    (one step from the step's start to the trial time), so an event time is as
    accurate as the integration.
``METHOD_PREDICTOR_CORRECTOR``
    The report's two-step scheme (Section 2.8): each input interval is divided
    into ``subdivisions`` equal steps; each step predicts with an explicit Euler
    step and corrects with the trapezoidal rule (Heun's method, second order).
``METHOD_LINEAR``
    Housner's slender-block linearisation, Eq. (2-4) extended to ground motion
    and rods: theta'' = mu theta + c0 + c1 tau, solved in closed form on each
    interval (cosh/sinh, or cos/sin when stiff rods make mu negative). The
    vertical acceleration is held at its mid-interval value so that the closed
    form exists.

All three share the event logic: start of rocking at the exact crossing of
Eq. (2-1) inside an interval, the impact map theta' -> cor * theta', the
summation of the endless cascade of impacts of a decaying block
(:func:`shaketable.dynamics.cascade_rest_time`), unstable / overturned, and the
block leaving the ground when g + vg <= 0.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..constants import G
from ..dynamics import (ALPHA, HALF_HEIGHT, HALF_WIDTH, HOLD_DOWN, INERTIA, ROD_ARM_1,
                        ROD_ARM_2, ROD_FORCE, ROD_STIFFNESS, TOP_FORCE, angular_acceleration,
                        cascade_rest_time)

METHOD_FAST = 0
METHOD_PREDICTOR_CORRECTOR = 1
METHOD_LINEAR = 2

STATUS_COMPLETED = 0
STATUS_OVERTURNED = 1
STATUS_AIRBORNE = 2

# Layout of the float summary array returned by ``integrate``.
(INFO_T_START, INFO_T_UNSTABLE, INFO_UNSTABLE_DIRECTION, INFO_T_OVERTURN,
 INFO_OVERTURN_DIRECTION, INFO_T_AIRBORNE, INFO_MAX_ABS_THETA, INFO_T_MAX,
 INFO_THETA_AT_MAX, INFO_T_END, INFO_THETA_END, INFO_THETA_DOT_END, INFO_STEPS,
 INFO_EVALUATIONS, INFO_REJECTED, INFO_CASCADES, INFO_STATUS, INFO_N_IMPACTS,
 INFO_N_OUTPUT, INFO_T_REST) = range(20)
N_INFO = 20

EVENT_IMPACT = 0
EVENT_OVERTURN = 1
EVENT_PEAK = 2
EVENT_UNSTABLE = 3


@njit(cache=True)
def _linear_acceleration(theta, side, ug, vg, rg, parameters):
    """Slender-block linearisation of Eq. (2-13)/(2-14) [rad/s^2] (Eq. 2-4)."""
    b = parameters[HALF_WIDTH]
    h = parameters[HALF_HEIGHT]
    radius = math.sqrt(b * b + h * h)
    inertia = parameters[INERTIA]
    s = side
    if theta > 0.0:
        s = 1.0
    elif theta < 0.0:
        s = -1.0
    arm_1 = parameters[ROD_ARM_1]
    arm_2 = parameters[ROD_ARM_2]
    rods = (parameters[ROD_FORCE] * (arm_1 + arm_2)
            + parameters[ROD_STIFFNESS] * (arm_1 * arm_1 + arm_2 * arm_2) * abs(theta))
    top = parameters[TOP_FORCE] * 2.0 * parameters[HALF_HEIGHT]
    return (radius * (ug - (G + vg) * (s * parameters[ALPHA] - theta)) - s * rods - top) / inertia - rg


@njit(cache=True)
def model_acceleration(method, theta, side, ug, vg, rg, parameters):
    """theta'' of the model a method integrates: exact, or linearised for METHOD_LINEAR."""
    if method == METHOD_LINEAR:
        return _linear_acceleration(theta, side, ug, vg, rg, parameters)
    return angular_acceleration(theta, side, ug, vg, rg, parameters)


@njit(cache=True)
def _ground(segment, time):
    """Horizontal, vertical [m/s^2] and rotational [rad/s^2] table acceleration at ``time``."""
    fraction = (time - segment[0]) / segment[1]
    return (segment[2] + segment[3] * fraction, segment[4] + segment[5] * fraction,
            segment[6] + segment[7] * fraction)


@njit(cache=True)
def _dormand_prince(t, theta, omega, side, h, segment, parameters):
    """One Dormand-Prince 5(4) step; returns theta, omega, error of theta, error of omega."""
    def f(time, y0):
        ug, vg, rg = _ground(segment, time)
        return angular_acceleration(y0, side, ug, vg, rg, parameters)

    k1x = omega
    k1v = f(t, theta)
    x = theta + h * (k1x / 5.0)
    k2x = omega + h * (k1v / 5.0)
    k2v = f(t + h / 5.0, x)
    x = theta + h * (3.0 / 40.0 * k1x + 9.0 / 40.0 * k2x)
    k3x = omega + h * (3.0 / 40.0 * k1v + 9.0 / 40.0 * k2v)
    k3v = f(t + 3.0 * h / 10.0, x)
    x = theta + h * (44.0 / 45.0 * k1x - 56.0 / 15.0 * k2x + 32.0 / 9.0 * k3x)
    k4x = omega + h * (44.0 / 45.0 * k1v - 56.0 / 15.0 * k2v + 32.0 / 9.0 * k3v)
    k4v = f(t + 4.0 * h / 5.0, x)
    x = theta + h * (19372.0 / 6561.0 * k1x - 25360.0 / 2187.0 * k2x
                     + 64448.0 / 6561.0 * k3x - 212.0 / 729.0 * k4x)
    k5x = omega + h * (19372.0 / 6561.0 * k1v - 25360.0 / 2187.0 * k2v
                       + 64448.0 / 6561.0 * k3v - 212.0 / 729.0 * k4v)
    k5v = f(t + 8.0 * h / 9.0, x)
    x = theta + h * (9017.0 / 3168.0 * k1x - 355.0 / 33.0 * k2x + 46732.0 / 5247.0 * k3x
                     + 49.0 / 176.0 * k4x - 5103.0 / 18656.0 * k5x)
    k6x = omega + h * (9017.0 / 3168.0 * k1v - 355.0 / 33.0 * k2v + 46732.0 / 5247.0 * k3v
                       + 49.0 / 176.0 * k4v - 5103.0 / 18656.0 * k5v)
    k6v = f(t + h, x)
    theta_new = theta + h * (35.0 / 384.0 * k1x + 500.0 / 1113.0 * k3x + 125.0 / 192.0 * k4x
                             - 2187.0 / 6784.0 * k5x + 11.0 / 84.0 * k6x)
    omega_new = omega + h * (35.0 / 384.0 * k1v + 500.0 / 1113.0 * k3v + 125.0 / 192.0 * k4v
                             - 2187.0 / 6784.0 * k5v + 11.0 / 84.0 * k6v)
    k7x = omega_new
    k7v = f(t + h, theta_new)
    e1, e3, e4, e5, e6, e7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0,
                              -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0)
    error_theta = h * (e1 * k1x + e3 * k3x + e4 * k4x + e5 * k5x + e6 * k6x + e7 * k7x)
    error_omega = h * (e1 * k1v + e3 * k3v + e4 * k4v + e5 * k5v + e6 * k6v + e7 * k7v)
    return theta_new, omega_new, error_theta, error_omega


@njit(cache=True)
def _heun(t, theta, omega, side, h, segment, parameters):
    """The report's predictor-corrector step (Section 2.8): Euler predictor, trapezoidal corrector."""
    ug, vg, rg = _ground(segment, t)
    acceleration = angular_acceleration(theta, side, ug, vg, rg, parameters)
    theta_predicted = theta + h * omega
    ug, vg, rg = _ground(segment, t + h)
    acceleration_predicted = angular_acceleration(theta_predicted, side, ug, vg, rg, parameters)
    omega_new = omega + 0.5 * h * (acceleration + acceleration_predicted)
    theta_new = theta + 0.5 * h * (omega + omega_new)
    return theta_new, omega_new, 0.0, 0.0


@njit(cache=True)
def _closed_form(t, theta, omega, side, h, segment, parameters):
    """Exact solution of the linearised equation over a time ``h`` (METHOD_LINEAR)."""
    t0, span, du, v0, dv, dr = segment[0], segment[1], segment[3], segment[4], segment[5], segment[7]
    b = parameters[HALF_WIDTH]
    hh = parameters[HALF_HEIGHT]
    radius = math.sqrt(b * b + hh * hh)
    inertia = parameters[INERTIA]
    q = radius / inertia  # = 3 / (4 R)
    s = side
    if theta > 0.0:
        s = 1.0
    elif theta < 0.0:
        s = -1.0
    arm_1 = parameters[ROD_ARM_1]
    arm_2 = parameters[ROD_ARM_2]
    vertical = v0 + 0.5 * dv  # held at mid-interval
    mu = q * (G + vertical) - parameters[ROD_STIFFNESS] * (arm_1 * arm_1 + arm_2 * arm_2) / inertia
    ug_here, _, rg_here = _ground(segment, t)
    c0 = (q * ug_here - q * (G + vertical) * s * parameters[ALPHA]
          - s * parameters[ROD_FORCE] * (arm_1 + arm_2) / inertia
          - parameters[TOP_FORCE] * 2.0 * hh / inertia - rg_here)
    c1 = q * du / span - dr / span
    if abs(mu) * h * h < 1e-12:
        theta_new = theta + omega * h + c0 * h * h / 2.0 + c1 * h * h * h / 6.0 + mu * theta * h * h / 2.0
        omega_new = omega + c0 * h + c1 * h * h / 2.0 + mu * theta * h
        return theta_new, omega_new, 0.0, 0.0
    particular = -c0 / mu
    particular_rate = -c1 / mu
    a = theta - particular
    if mu > 0.0:
        lam = math.sqrt(mu)
        bb = (omega - particular_rate) / lam
        ch = math.cosh(lam * h)
        sh = math.sinh(lam * h)
        theta_new = a * ch + bb * sh + particular + particular_rate * h
        omega_new = lam * (a * sh + bb * ch) + particular_rate
    else:
        lam = math.sqrt(-mu)
        bb = (omega - particular_rate) / lam
        co = math.cos(lam * h)
        si = math.sin(lam * h)
        theta_new = a * co + bb * si + particular + particular_rate * h
        omega_new = lam * (-a * si + bb * co) + particular_rate
    return theta_new, omega_new, 0.0, 0.0


@njit(cache=True)
def _advance(method, t, theta, omega, side, h, segment, parameters):
    if method == METHOD_FAST:
        return _dormand_prince(t, theta, omega, side, h, segment, parameters)
    if method == METHOD_PREDICTOR_CORRECTOR:
        return _heun(t, theta, omega, side, h, segment, parameters)
    return _closed_form(t, theta, omega, side, h, segment, parameters)


@njit(cache=True)
def _event_value(kind, method, t, theta, omega, side, tau, segment, parameters, sign, from_zero):
    """Event function at ``t + tau``: positive before the event, <= 0 at and after it."""
    if tau == 0.0:
        x, v = theta, omega
    else:
        x, v, _, _ = _advance(method, t, theta, omega, side, tau, segment, parameters)
    if kind == EVENT_IMPACT:
        if from_zero:
            if tau == 0.0:
                return side * omega
            return side * x / tau
        return side * x
    if kind == EVENT_OVERTURN:
        return 0.5 * math.pi - side * x
    if kind == EVENT_PEAK:
        return sign * v
    return parameters[ALPHA] - abs(x)


@njit(cache=True)
def _locate(kind, method, t, theta, omega, side, upper, segment, parameters, sign, from_zero):
    """Root of an event function on (0, upper] by the Illinois variant of regula falsi."""
    a = 0.0
    b = upper
    fa = _event_value(kind, method, t, theta, omega, side, a, segment, parameters, sign, from_zero)
    fb = _event_value(kind, method, t, theta, omega, side, b, segment, parameters, sign, from_zero)
    if fb > 0.0:
        return upper
    if fa <= 0.0:
        return 0.0
    tolerance = 4e-16 * (abs(t) + upper) + 1e-300
    side_kept = 0
    for _ in range(200):
        if b - a <= tolerance:
            break
        c = (a * fb - b * fa) / (fb - fa)
        if not (a < c < b):
            c = 0.5 * (a + b)
        fc = _event_value(kind, method, t, theta, omega, side, c, segment, parameters, sign,
                          from_zero)
        if fc > 0.0:
            a, fa = c, fc
            if side_kept == -1:
                fb *= 0.5
            side_kept = -1
        else:
            b, fb = c, fc
            if side_kept == 1:
                fa *= 0.5
            side_kept = 1
    return b


@njit(cache=True)
def integrate(method, t_grid, ug, vg, rg, parameters, cor, theta0, omega0, rtol, subdivisions,
              rest_tolerance, out_theta, out_omega, out_acceleration, impact_times,
              impact_velocities, info):
    """Integrate one run; fill the output arrays and ``info`` (see module constants).

    Parameters
    ----------
    method : int
        METHOD_FAST, METHOD_PREDICTOR_CORRECTOR or METHOD_LINEAR.
    t_grid, ug, vg, rg : ndarray
        Sample times [s], ground accelerations [m/s^2] (vertical upward) and
        table angular acceleration [rad/s^2].
    parameters : ndarray
        From :func:`shaketable.dynamics.block_parameters`.
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
        Filled with the state at every sample time reached.
    impact_times, impact_velocities : ndarray
        Filled with the first ``len(impact_times)`` impacts (time [s],
        velocity before impact [rad/s]); ``info[INFO_N_IMPACTS]`` counts all.
    info : ndarray, shape (N_INFO,)
        Filled with the scalar results.
    """
    n = t_grid.shape[0]
    alpha = parameters[ALPHA]
    radius = math.sqrt(parameters[HALF_WIDTH] ** 2 + parameters[HALF_HEIGHT] ** 2)
    p = math.sqrt(3.0 * G / (4.0 * radius))
    atol_theta = rtol * alpha
    atol_omega = rtol * alpha * p
    if rest_tolerance < 0.0:
        rest_tolerance = 1e-6 / p
    # Below this velocity an impact is lost in the integration error: sum the cascade.
    velocity_floor = 1e-13 * alpha * p
    if method == METHOD_FAST:
        velocity_floor = max(velocity_floor, 1e3 * atol_omega)
    hold_down = parameters[HOLD_DOWN]
    max_recorded = impact_times.shape[0]
    segment = np.empty(8)

    for i in range(N_INFO):
        info[i] = math.nan
    info[INFO_MAX_ABS_THETA] = abs(theta0)
    info[INFO_T_MAX] = t_grid[0]
    info[INFO_THETA_AT_MAX] = theta0
    n_impacts = 0
    steps = 0
    evaluations = 0
    rejected = 0
    cascades = 0
    status = STATUS_COMPLETED

    theta = theta0
    omega = omega0
    resting = theta == 0.0 and omega == 0.0
    side = 1.0
    if theta < 0.0 or (theta == 0.0 and omega < 0.0):
        side = -1.0
    if not resting:
        info[INFO_T_START] = t_grid[0]
    if abs(theta) > alpha:
        info[INFO_T_UNSTABLE] = t_grid[0]
        info[INFO_UNSTABLE_DIRECTION] = side
    rest_until = t_grid[0]
    t = t_grid[0]
    last_impact = t
    step_size = 0.1 / p
    from_zero = theta == 0.0

    out_theta[0] = theta
    out_omega[0] = omega
    if resting:
        out_acceleration[0] = 0.0
    else:
        out_acceleration[0] = model_acceleration(method, theta, side, ug[0], vg[0], rg[0],
                                                 parameters)
    filled = 1

    for k in range(n - 1):
        t0 = t_grid[k]
        t1 = t_grid[k + 1]
        segment[0] = t0
        segment[1] = t1 - t0
        segment[2] = ug[k]
        segment[3] = ug[k + 1] - ug[k]
        segment[4] = vg[k]
        segment[5] = vg[k + 1] - vg[k]
        segment[6] = rg[k]
        segment[7] = rg[k + 1] - rg[k]
        # The model needs contact: g + vg (+ rods' hold-down) must stay positive.
        support_0 = G + vg[k] + hold_down
        support_1 = G + vg[k + 1] + hold_down
        t_end = t1
        airborne = False
        if support_0 <= 0.0:
            t_end = t0
            airborne = True
        elif support_1 <= 0.0:
            t_end = t0 + (t1 - t0) * support_0 / (support_0 - support_1)
            airborne = True
        substep = (t1 - t0) / subdivisions

        while t < t_end:
            if resting:
                if rest_until >= t_end:
                    t = t_end
                    break
                if rest_until > t:
                    t = rest_until
                ua, va, ra = _ground(segment, t)
                ub, vb, rb = _ground(segment, t_end)
                start = math.inf
                start_side = 0.0
                for s in (1.0, -1.0):
                    margin_a = s * model_acceleration(method, 0.0, s, ua, va, ra, parameters)
                    margin_b = s * model_acceleration(method, 0.0, s, ub, vb, rb, parameters)
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
                    t = t_end
                    break
                t = start
                side = start_side
                theta = 0.0
                omega = 0.0
                from_zero = True
                resting = False
                if math.isnan(info[INFO_T_START]):
                    info[INFO_T_START] = t
                continue

            # ---- one step of free flight about the active corner
            if method == METHOD_FAST:
                h = min(step_size, t_end - t)
            elif method == METHOD_PREDICTOR_CORRECTOR:
                index = math.floor((t - t0) / substep * (1.0 + 1e-12) + 1e-9) + 1.0
                h = min(t0 + index * substep, t_end) - t
                if h <= 1e-12 * substep:
                    h = min(substep, t_end - t)
            else:
                h = t_end - t
            theta_new, omega_new, error_theta, error_omega = _advance(
                method, t, theta, omega, side, h, segment, parameters)
            evaluations += 7 if method == METHOD_FAST else 2
            if method == METHOD_FAST:
                error = max(abs(error_theta) / (atol_theta + rtol * max(abs(theta), abs(theta_new))),
                            abs(error_omega) / (atol_omega + rtol * max(abs(omega), abs(omega_new))))
                if error > 1.0:
                    step_size = h * max(0.2, 0.9 * error ** -0.2)
                    rejected += 1
                    continue
                growth = 5.0 if error == 0.0 else min(5.0, 0.9 * error ** -0.2)
                if h < step_size:
                    # a step cut short by the end of the interval says nothing against
                    # the step size that was planned
                    step_size = max(step_size, h * growth)
                else:
                    step_size = h * growth

            # ---- terminal events inside the step
            tau = h
            kind = -1
            if side * theta_new < 0.0 or (side * theta_new == 0.0 and side * omega_new < 0.0):
                tau = _locate(EVENT_IMPACT, method, t, theta, omega, side, h, segment,
                              parameters, 0.0, from_zero)
                kind = EVENT_IMPACT
            if side * theta_new >= 0.5 * math.pi:
                tau_overturn = _locate(EVENT_OVERTURN, method, t, theta, omega, side, h,
                                       segment, parameters, 0.0, from_zero)
                if kind < 0 or tau_overturn < tau:
                    tau = tau_overturn
                    kind = EVENT_OVERTURN
            if kind >= 0:
                theta_new, omega_new, _, _ = _advance(method, t, theta, omega, side, tau,
                                                      segment, parameters)
                evaluations += 20
                if kind == EVENT_IMPACT:
                    theta_new = 0.0
                else:
                    theta_new = side * 0.5 * math.pi

            # ---- non-terminal events: turning point (max |theta|) and instability
            if omega * omega_new < 0.0:
                sign = 1.0 if omega > 0.0 else -1.0
                tau_peak = _locate(EVENT_PEAK, method, t, theta, omega, side, tau, segment,
                                   parameters, sign, from_zero)
                theta_peak, _, _, _ = _advance(method, t, theta, omega, side, tau_peak, segment,
                                               parameters)
                if abs(theta_peak) > info[INFO_MAX_ABS_THETA]:
                    info[INFO_MAX_ABS_THETA] = abs(theta_peak)
                    info[INFO_T_MAX] = t + tau_peak
                    info[INFO_THETA_AT_MAX] = theta_peak
            else:
                tau_peak = tau
                theta_peak = theta_new
            if abs(theta_new) > info[INFO_MAX_ABS_THETA]:
                info[INFO_MAX_ABS_THETA] = abs(theta_new)
                info[INFO_T_MAX] = t + tau
                info[INFO_THETA_AT_MAX] = theta_new
            if math.isnan(info[INFO_T_UNSTABLE]):
                if abs(theta_peak) > alpha or abs(theta_new) > alpha:
                    upper = tau_peak if abs(theta_peak) > alpha else tau
                    tau_unstable = _locate(EVENT_UNSTABLE, method, t, theta, omega, side, upper,
                                           segment, parameters, 0.0, from_zero)
                    info[INFO_T_UNSTABLE] = t + tau_unstable
                    info[INFO_UNSTABLE_DIRECTION] = side

            t = t + tau
            theta = theta_new
            omega = omega_new
            from_zero = False
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
                from_zero = True
                ux, vx, rx = _ground(segment, t)
                deceleration = -side * model_acceleration(method, 0.0, side, ux, vx, rx,
                                                          parameters)
                remaining = cascade_rest_time(omega, deceleration, cor)
                if omega == 0.0 or remaining <= rest_tolerance or (
                        abs(omega) <= velocity_floor and remaining < math.inf):
                    if omega != 0.0:
                        cascades += 1
                    resting = True
                    rest_until = t + (0.0 if omega == 0.0 else remaining)
                    info[INFO_T_REST] = rest_until
                    omega = 0.0

        if status != STATUS_COMPLETED:
            break
        if airborne:
            status = STATUS_AIRBORNE
            info[INFO_T_AIRBORNE] = t_end
            break
        out_theta[k + 1] = theta
        out_omega[k + 1] = omega
        if resting:
            out_acceleration[k + 1] = 0.0
        else:
            out_acceleration[k + 1] = model_acceleration(method, theta, side, ug[k + 1],
                                                         vg[k + 1], rg[k + 1], parameters)
        filled = k + 2

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
