"""The peaks and the event record of a run of the planar engine
(:mod:`shaketable.solvers.planar`), compiled with numba: the largest |theta|, slip and
corner excursion and when they are reached, tracked at every state the engine visits and
located inside a contact step (on the step's continuous extension,
:func:`~shaketable.solvers.planar_steps.locate`) and inside a flight (on the closed form);
:func:`record` writes the rows of the engine's event array.

They are kept in ``peaks``, a view of the engine's info array (layout P_*: its slots
I_MAX_ABS_THETA, I_T_MAX, I_PEAK_SLIP, I_T_PEAK_SLIP, I_PEAK_EXCURSION in this order).
"""

from __future__ import annotations

from numba import njit

from shaketable.core.planar_dynamics import corner_vector
from shaketable.solvers.planar_modes import hermite_peak, measures, q_from_z, quantity
from shaketable.solvers.planar_steps import (
    KIND_PEAK,
    KIND_RATE,
    N_RATES,
    flight_state,
    horizontal_rate,
    locate,
)

#: Layout of ``peaks``: largest |theta| [rad] and its time [s], peak |slip| [m] and its
#: time [s], peak corner excursion [m].
P_MAX_ABS_THETA, P_T_MAX, P_PEAK_SLIP, P_T_PEAK_SLIP, P_PEAK_EXCURSION = range(5)
N_PEAKS = 5


@njit(cache=True)
def track(t, q, peaks, parameters):
    """Update ``peaks`` with the full state q = (x, y, theta, x', y', theta') at ``t``."""
    slip, excursion = measures(q, parameters)
    if abs(slip) > peaks[P_PEAK_SLIP]:
        peaks[P_PEAK_SLIP] = abs(slip)
        peaks[P_T_PEAK_SLIP] = t
    if excursion > peaks[P_PEAK_EXCURSION]:
        peaks[P_PEAK_EXCURSION] = excursion
    if abs(q[2]) > peaks[P_MAX_ABS_THETA]:
        peaks[P_MAX_ABS_THETA] = abs(q[2])
        peaks[P_T_MAX] = t


@njit(cache=True)
def record(ev, count, t, kind, before, after, omega, q, parameters):
    """Event ``count[0]`` (time [s], kind, mode before and after, theta' [rad/s], slip of
    the state q [m]) into row ``count[0]`` of ``ev`` if it has room; count it."""
    index = int(count[0])
    if index < ev.shape[0]:
        slip, _ = measures(q, parameters)
        ev[index, 0] = t
        ev[index, 1] = kind
        ev[index, 2] = before
        ev[index, 3] = after
        ev[index, 4] = omega
        ev[index, 5] = slip
    count[0] = index + 1


@njit(cache=True)
def contact_extrema(mode, side, sigma, mu_s, mu_d, t, z, step, stages, dense, ready, tau, z_new,
                    segment, parameters, peaks, q, q_start, q_end, z_turn, no_events):
    """Track the turning point of theta and the extrema of the slip and of the corners' X
    inside the accepted contact step (t, z) -> (t + tau, ``z_new``) of a step of size
    ``step`` (the arguments of :func:`~shaketable.solvers.planar_steps.locate`).

    An extremum is located (on the step's continuous extension) only where the cubic
    Hermite interpolant of the step's ends says it may come within 10 % of the peak so far
    (the interpolant's error is far smaller: the peaks stay exact). ``q``, ``q_start``,
    ``q_end`` and ``z_turn`` are work arrays; ``no_events`` all False. Returns the
    right-hand-side evaluations made.
    """
    evaluations = 0
    q_from_z(z, side, q_start, parameters)
    q_from_z(z_new, side, q_end, parameters)
    if z[1] * z_new[1] < 0.0 and hermite_peak(
            z[0], z_new[0], z[1], z_new[1], tau) >= 0.9 * peaks[P_MAX_ABS_THETA]:
        tau_peak, used = locate(KIND_PEAK, mode, side, sigma, mu_s, mu_d, t, z,
                                step, z_new, stages, dense, ready, tau, z_new,
                                no_events, 1.0 if z[1] > 0.0 else -1.0, segment,
                                parameters, z_turn)
        evaluations += used
        q_from_z(z_turn, side, q, parameters)
        track(t + tau_peak, q, peaks, parameters)
    # extrema of the slip and of the corners' X (peak slip, excursion)
    _, ry0 = corner_vector(z[0], side, parameters)
    _, ry1 = corner_vector(z_new[0], side, parameters)
    for j in range(N_RATES):
        rate0 = horizontal_rate(j, z[0], z[3] + ry0 * z[1], z[1], parameters)
        rate1 = horizontal_rate(j, z_new[0], z_new[3] + ry1 * z_new[1],
                                z_new[1], parameters)
        peak = peaks[P_PEAK_SLIP] if j == 0 else peaks[P_PEAK_EXCURSION]
        if rate0 * rate1 < 0.0 and hermite_peak(
                quantity(j, q_start, parameters), quantity(j, q_end, parameters),
                rate0, rate1, tau) >= 0.9 * peak:
            tau_rate, used = locate(KIND_RATE + j, mode, side, sigma, mu_s,
                                    mu_d, t, z, step, z_new, stages, dense, ready,
                                    tau, z_new, no_events,
                                    1.0 if rate0 > 0.0 else -1.0, segment,
                                    parameters, z_turn)
            evaluations += used
            q_from_z(z_turn, side, q, parameters)
            track(t + tau_rate, q, peaks, parameters)
    return evaluations


@njit(cache=True)
def flight_extrema(t, span, pieces, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv, q, peaks,
                   parameters):
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
                track(t + low, q, peaks, parameters)
            tau_a = tau_b
            rate_a = rate_b
