"""The peaks and the event record of a run of the planar engine
(:mod:`shaketable.models.planar.engine`), compiled with numba: the largest |theta|, slip and
corner excursion and when they are reached, tracked at every state the engine visits and
located inside a contact step (on the step's continuous extension,
:func:`~shaketable.models.planar.steps.locate`) and inside a flight (on the closed form);
:func:`record` writes the rows of the engine's event array.

They are kept in the engine's info array from slot ``first`` on (layout P_*, relative to
``first``: the engine's I_MAX_ABS_THETA, I_T_MAX, I_PEAK_SLIP, I_T_PEAK_SLIP,
I_PEAK_EXCURSION in this order).
"""

from __future__ import annotations

import math

from numba import njit

from shaketable.models.planar.modes import hermite_peak, measures, q_from_z, quantity
from shaketable.models.planar.physics import HELPER, half_width
from shaketable.models.planar.steps import (
    KIND_PEAK,
    KIND_RATE,
    N_RATES,
    flight_state,
    horizontal_rate,
    horizontal_rate_at,
    locate,
)
from shaketable.models.rocking.physics import ERROR_MODEL, HALF_HEIGHT

#: Layout of the peaks (from ``first``): largest |theta| [rad] and its time [s], peak
#: |slip| [m] and its time [s], peak corner excursion [m].
P_MAX_ABS_THETA, P_T_MAX, P_PEAK_SLIP, P_T_PEAK_SLIP, P_PEAK_EXCURSION = range(5)
N_PEAKS = 5

#: Where the peak base slip [m] and its time [s] are, from ``first`` (the engine's
#: I_PEAK_BASE_SLIP - I_MAX_ABS_THETA: slots appended to its info array).
P_PEAK_BASE_SLIP, P_T_PEAK_BASE_SLIP = 23, 24


# one compiled function (not inlined: a copy of it in each of its four callers cost more
# to compile); the callers pass ``first`` as an int64 so that it is compiled once
@njit(**HELPER)
def track(t, q, info, first, parameters):
    """Update the peaks in ``info`` with the state q = (x, y, theta, x', y', theta') at t."""
    slip, excursion, base = measures(q, parameters)
    base = abs(base)
    if base > info[first + P_PEAK_BASE_SLIP]:
        info[first + P_PEAK_BASE_SLIP] = base
        info[first + P_T_PEAK_BASE_SLIP] = t
    if abs(slip) > info[first + P_PEAK_SLIP]:
        info[first + P_PEAK_SLIP] = abs(slip)
        info[first + P_T_PEAK_SLIP] = t
    if excursion > info[first + P_PEAK_EXCURSION]:
        info[first + P_PEAK_EXCURSION] = excursion
    if abs(q[2]) > info[first + P_MAX_ABS_THETA]:
        info[first + P_MAX_ABS_THETA] = abs(q[2])
        info[first + P_T_MAX] = t


@njit(cache=True, inline="always", error_model=ERROR_MODEL)
def record(ev, info, slot, t, kind, before, after, omega, q, parameters):
    """An event (time [s], kind, mode before and after, theta' [rad/s], slip of the state
    q [m]) into row ``info[slot]`` of ``ev`` if it has room; count it in ``info[slot]``."""
    index = int(info[slot])
    if index < ev.shape[0]:
        slip, _, _ = measures(q, parameters)
        ev[index, 0] = t
        ev[index, 1] = kind
        ev[index, 2] = before
        ev[index, 3] = after
        ev[index, 4] = omega
        ev[index, 5] = slip
    info[slot] = index + 1


@njit(**HELPER)
def contact_extrema(mode, side, sigma, mu_s, mu_d, t, z, step, stages, dense, ready, tau, z_new,
                    segment, parameters, info, first, q, q_start, q_end, z_turn, no_events):
    """Track the turning point of theta and the extrema of the slip and of the corners' X
    inside the accepted contact step (t, z) -> (t + tau, ``z_new``) of a step of size
    ``step`` (the arguments of :func:`~shaketable.models.planar.steps.locate`).

    An extremum is located (on the step's continuous extension) only where the cubic
    Hermite interpolant of the step's ends says it may come within 10 % of the peak so far
    (the interpolant's error is far smaller: the peaks stay exact). ``q``, ``q_start``,
    ``q_end`` and ``z_turn`` are work arrays; ``no_events`` all False. Returns the
    right-hand-side evaluations made.
    """
    evaluations = 0
    if z[1] * z_new[1] < 0.0 and hermite_peak(
            z[0], z_new[0], z[1], z_new[1], tau) >= 0.9 * info[first + P_MAX_ABS_THETA]:
        tau_peak, used = locate(KIND_PEAK, mode, side, sigma, mu_s, mu_d, t, z,
                                step, z_new, stages, dense, ready, tau, z_new,
                                no_events, 1.0 if z[1] > 0.0 else -1.0, segment,
                                parameters, z_turn)
        evaluations += used
        q_from_z(z_turn, side, q, parameters)
        track(t + tau_peak, q, info, first, parameters)
    # extrema of the slip and of the corners' X (peak slip, excursion)
    # (cos and sin of theta at both ends once: corner_vector's r_y and the rates)
    b = half_width(side, parameters)
    h = parameters[HALF_HEIGHT]
    cos0, sin0 = math.cos(z[0]), math.sin(z[0])
    cos1, sin1 = math.cos(z_new[0]), math.sin(z_new[0])
    x_dot0 = z[3] + (-side * b * sin0 - h * cos0) * z[1]
    x_dot1 = z_new[3] + (-side * b * sin1 - h * cos1) * z_new[1]
    have_states = False
    for j in range(N_RATES):
        rate0 = horizontal_rate_at(j, cos0, sin0, x_dot0, z[1], parameters)
        rate1 = horizontal_rate_at(j, cos1, sin1, x_dot1, z_new[1], parameters)
        peak = info[first + P_PEAK_SLIP] if j == 0 else info[first + P_PEAK_EXCURSION]
        if not rate0 * rate1 < 0.0:
            continue
        if not have_states:   # the full states at the step's ends, once
            q_from_z(z, side, q_start, parameters)
            q_from_z(z_new, side, q_end, parameters)
            have_states = True
        if hermite_peak(quantity(j, q_start, parameters), quantity(j, q_end, parameters),
                        rate0, rate1, tau) >= 0.9 * peak:
            tau_rate, used = locate(KIND_RATE + j, mode, side, sigma, mu_s,
                                    mu_d, t, z, step, z_new, stages, dense, ready,
                                    tau, z_new, no_events,
                                    1.0 if rate0 > 0.0 else -1.0, segment,
                                    parameters, z_turn)
            evaluations += used
            q_from_z(z_turn, side, q, parameters)
            track(t + tau_rate, q, info, first, parameters)
    return evaluations


@njit(**HELPER)
def flight_extrema(t, span, pieces, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv, q, info,
                   first, parameters):
    """Track the extrema of the slip and of the corners' X inside a flight of ``span`` [s]
    from (x0, y0, th0, xd0, yd0, om0) at ``t`` (the table accelerations ua + ka tau,
    va + kv tau): bisection on the closed form's rates, piece by piece (``pieces``). The
    last extremum found is left in ``q`` (its theta' is not set)."""
    for j in range(N_RATES):
        tau_a = 0.0
        _, _, tha, xda, _, _ = flight_state(0.0, x0, y0, th0, xd0, yd0, om0, ua, ka,
                                            va, kv)
        rate_a = horizontal_rate(j, tha, xda, om0, parameters)
        for piece in range(1, pieces + 1):
            tau_b = span * piece / pieces
            _, _, thb, xdb, _, _ = flight_state(tau_b, x0, y0, th0, xd0, yd0, om0,
                                                ua, ka, va, kv)
            rate_b = horizontal_rate(j, thb, xdb, om0, parameters)
            if rate_a * rate_b < 0.0:
                low = tau_a
                high = tau_b
                for _ in range(200):
                    middle = 0.5 * (low + high)
                    if middle <= low or middle >= high:
                        break
                    _, _, thm, xdm, _, _ = flight_state(middle, x0, y0, th0, xd0,
                                                        yd0, om0, ua, ka, va, kv)
                    if horizontal_rate(j, thm, xdm, om0, parameters) * rate_a > 0.0:
                        low = middle
                    else:
                        high = middle
                xm, ym, thm, xdm, ydm, _ = flight_state(low, x0, y0, th0, xd0, yd0,
                                                        om0, ua, ka, va, kv)
                q[0], q[1], q[2], q[3], q[4] = xm, ym, thm, xdm, ydm
                track(t + low, q, info, first, parameters)
            tau_a = tau_b
            rate_a = rate_b
