"""The planar engine's modes, one compiled function each: what
:func:`shaketable.models.planar.engine.integrate` does in REST, SLIDE, FLIGHT and in the contact
modes (ROCK, SLIDE_ROCK: entering one, its DOP853 steps, the event that ends them, an impact).

Each takes the engine's state (the time, the mode, its pivot ``side`` and slip direction
``sigma``, the work arrays) and returns what it changed; the counters, the work of the
table and of friction and the impact losses are accumulated in the info array
(:mod:`shaketable.models.planar.layout`). They are inlined into the driver by numba
(``inline="always"``): the driver, compiled without reference counting, runs the same
arithmetic as one function would, and hands them its arrays at no cost. The two rare
phases with the longest code, a flight (:func:`flight_mode`) and an impact
(:func:`corner_impact`), are compiled apart and called (:data:`APART`): numba copies the
code of a function each time it inlines it, at a cost in first-compile time that grows
with the function's size, and these two run once per flight or impact.
"""

from __future__ import annotations

import math
from typing import Any

from numba import njit

from shaketable.core.constants import G
from shaketable.models.planar.layout import (
    EV_CASCADE,
    EV_IMPACT,
    EV_LANDING,
    EV_MODE,
    EV_OVERTURN,
    EV_REVERSAL,
    EV_UNSTABLE,
    I_CAPPED,
    I_CASCADES,
    I_EVALUATIONS,
    I_FAILED_MODE,
    I_IMPACT_LOSS,
    I_N_EVENTS,
    I_N_IMPACTS,
    I_OVERTURN_DIRECTION,
    I_REJECTED,
    I_STEPS,
    I_T_OVERTURN,
    I_T_REST,
    I_T_START,
    I_T_UNSTABLE,
    I_TIME_FLIGHT,
    I_TIME_REST,
    I_TIME_ROCK,
    I_TIME_SLIDE,
    I_TIME_SLIDE_ROCK,
    I_UNSTABLE_DIRECTION,
    I_W_FRICTION,
    I_W_TABLE,
    MAX_IMMEDIATE_IMPACTS,
    MODE_FLIGHT,
    MODE_REST,
    MODE_ROCK,
    MODE_SLIDE,
    MODE_SLIDE_ROCK,
    PEAKS,
    STATUS_COMPLETED,
    STATUS_INCONSISTENT,
    STATUS_OVERTURNED,
    STATUS_PAINLEVE,
    STATUS_STALLED,
)
from shaketable.models.planar.modes import (
    enter_contact,
    first_failure,
    flat,
    q_from_z,
    strike,
    z_from_q,
)
from shaketable.models.planar.physics import (
    FLIGHT,
    HELPER,
    INCONSISTENT,
    PAINLEVE,
    REST,
    ROCK,
    SLIDE,
    SLIDE_ROCK,
    block_angle,
    corner_height,
    corner_height_rate,
    corner_vector,
    kinetic_energy,
    pivot_acceleration,
    rock_forces,
    slide_rock_accelerations,
    start_mode,
)
from shaketable.models.planar.steps import (
    E_FRICTION,
    E_IMPACT,
    E_MASS,
    E_NORMAL,
    E_OVERTURN,
    KIND_ALPHA,
    N_EVENTS,
    N_STATE,
    dop853_step,
    events,
    flight_state,
    ground,
    locate,
    lowest_corner,
    polynomial_work,
    rhs,
    terminal_event,
)
from shaketable.models.planar.track import contact_extrema, flight_extrema, record, track
from shaketable.models.rocking.physics import ASYMMETRIC, COR_MINUS, COR_PLUS, ERROR_MODEL, cascade_rest_time
from shaketable.models.sliding.engine import first_up_crossing, first_velocity_zero

#: numba options of the mode functions: inlined into the driver by numba before it is
#: typed (as :func:`~shaketable.models.planar.track.record`). numba inlines a call of at
#: most 30 arguments: Python passes more as a tuple, which its inliner refuses.
INLINED: Any = {"cache": True, "inline": "always", "error_model": ERROR_MODEL}
#: numba options of the rare phases (a flight, an impact): compiled apart and called,
#: without reference counting (they allocate nothing, as the driver; a call hands them
#: the driver's arrays at no cost).
APART: Any = {**HELPER, "_nrt": False}


@njit(**HELPER)
def track_peaks(t, q, info, parameters):
    """The peaks of the state q at t into ``info`` (planar_track's P_* from I_MAX_ABS_THETA)."""
    track(t, q, info, PEAKS, parameters)


@njit(**HELPER)
def record_event(ev, info, t, kind, before, after, omega, q, parameters):
    """One event row (counted in ``info[I_N_EVENTS]``)."""
    record(ev, info, I_N_EVENTS, t, kind, before, after, omega, q, parameters)


@njit(**INLINED)
def rest_mode(t, t_end, side, sigma, entered, rest_until, segment, mu_s, mu_d, q, z, ev, info,
              parameters):
    """REST until the interval's end or the first instant a rest condition fails.

    That instant is found in closed form (:func:`~shaketable.models.planar.modes.first_failure`);
    the start rules choose the mode there. Returns (t, mode, side, sigma, entered, status,
    transition).
    """
    if rest_until >= t_end:
        info[I_TIME_REST] += t_end - t
        return t_end, REST, side, sigma, entered, STATUS_COMPLETED, False
    if rest_until > t:
        info[I_TIME_REST] += rest_until - t
        t = rest_until
    when = first_failure(t, t_end, segment, mu_s, parameters)
    if when == math.inf:
        info[I_TIME_REST] += t_end - t
        return t_end, REST, side, sigma, entered, STATUS_COMPLETED, False
    info[I_TIME_REST] += when - t
    t = when
    u_now, v_now = ground(segment, t)
    new_mode, new_side, new_sigma = start_mode(u_now, v_now, mu_s, mu_d, parameters)
    if new_mode == INCONSISTENT:
        info[I_FAILED_MODE] = REST
        return t, REST, side, sigma, entered, STATUS_INCONSISTENT, False
    if new_mode == REST:
        return t, REST, side, sigma, entered, STATUS_COMPLETED, True
    if math.isnan(info[I_T_START]):
        info[I_T_START] = t
    if new_mode == ROCK or new_mode == SLIDE_ROCK:
        z_from_q(q, new_side, z, parameters)
        entered = True
    record_event(ev, info, t, EV_MODE, MODE_REST, new_mode, 0.0, q, parameters)
    return t, new_mode, new_side, new_sigma, entered, STATUS_COMPLETED, True


@njit(**INLINED)
def slide_mode(t, t_end, side, sigma, entered, segment, mu_s, mu_d, q, z, ev, info, parameters):
    """SLIDE: the cubic pieces of :func:`shaketable.models.sliding.engine.slide`, to the end of
    the interval, the return of x' to 0 (rest, reversal or a rocking mode by the start
    rules) or the instant N reaches 0 (flight). Returns (t, mode, side, sigma, entered,
    status, transition).
    """
    length = t_end - t
    ka = segment[6]
    kv = segment[7]
    ua, va = ground(segment, t)
    na = G + va
    v = q[3]
    t_air = first_up_crossing(-na, -kv, length)
    end = length if t_air < 0.0 else t_air
    c0 = -ua - sigma * mu_d * na
    c1 = -ka - sigma * mu_d * kv
    tr = first_velocity_zero(sigma * v, sigma * c0, 0.5 * sigma * c1, end)
    span = end if tr < 0.0 else tr
    info[I_W_TABLE] -= polynomial_work(ua, ka, v, c0, 0.5 * c1, span)
    info[I_W_FRICTION] -= sigma * mu_d * polynomial_work(na, kv, v, c0, 0.5 * c1, span)
    q[0] += v * span + 0.5 * c0 * span * span + c1 * span * span * span / 6.0
    q[3] = v + c0 * span + 0.5 * c1 * span * span
    info[I_TIME_SLIDE] += span
    if tr < 0.0 and t_air < 0.0:
        t = t_end
    else:
        t = t + span
    track_peaks(t, q, info, parameters)
    if tr >= 0.0:
        q[3] = 0.0
        u_now, v_now = ground(segment, t)
        new_mode, new_side, new_sigma = start_mode(u_now, v_now, mu_s, mu_d, parameters)
        if new_mode == INCONSISTENT:
            info[I_FAILED_MODE] = SLIDE
            return t, SLIDE, side, sigma, entered, STATUS_INCONSISTENT, True
        if new_mode == SLIDE:
            kind = EV_REVERSAL if new_sigma != sigma else EV_MODE
            record_event(ev, info, t, kind, MODE_SLIDE, MODE_SLIDE, 0.0, q, parameters)
            return t, SLIDE, side, new_sigma, entered, STATUS_COMPLETED, True
        # a slide an impact left (-inf: pending) ends the rocking's rest
        if new_mode == REST and info[I_T_REST] == -math.inf:
            info[I_T_REST] = t
        if new_mode == ROCK or new_mode == SLIDE_ROCK:
            z_from_q(q, new_side, z, parameters)
            entered = True
        record_event(ev, info, t, EV_MODE, MODE_SLIDE, new_mode, 0.0, q, parameters)
        return t, new_mode, new_side, new_sigma, entered, STATUS_COMPLETED, True
    if t_air >= 0.0:
        record_event(ev, info, t, EV_MODE, MODE_SLIDE, MODE_FLIGHT, 0.0, q, parameters)
        return t, FLIGHT, side, sigma, entered, STATUS_COMPLETED, True
    return t, SLIDE, side, sigma, entered, STATUS_COMPLETED, False


@njit(**INLINED)
def flight_end(length, pieces, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv, parameters):
    """Where a flight of ``length`` [s] ends: (landing, overturn) times from its start [s],
    -1 for none.

    Searched on ``pieces`` pieces by the sign of the lowest corner's height and of each
    corner's height rate (a touch-down between two piece ends shows as a minimum), then
    bisected to the ulp.
    """
    lowest0, _ = lowest_corner(y0, th0, parameters)
    positive_at_start = lowest0 > 0.0
    tau_a = 0.0
    landing = -1.0
    overturn = -1.0
    for j in range(1, pieces + 1):
        tau_b = length if j == pieces else length * j / pieces
        _, yb, thb, _, ydb, _ = flight_state(tau_b, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv)
        if abs(thb) >= 0.5 * math.pi:
            overturn = (math.copysign(0.5 * math.pi, thb) - th0) / om0
        low_b, _ = lowest_corner(yb, thb, parameters)
        upper = -1.0
        # strictly below: a gap of exactly 0 (the rise of a block just lifted off, below
        # half an ulp of y) is no landing (docs/planar.md, lift-off)
        if low_b < 0.0:
            upper = tau_b
        elif positive_at_start or tau_a > 0.0:
            # a touch-down hidden between the piece ends: a minimum of a corner's height
            # below 0 (not looked for in the first piece of a flight that leaves the
            # table: the corner just released starts at zero height with zero rate and
            # rises)
            _, ya, tha, _, yda, _ = flight_state(tau_a, x0, y0, th0, xd0, yd0, om0, ua, ka,
                                                 va, kv)
            for s in (1.0, -1.0):
                rate_a = corner_height_rate(yda, tha, om0, s, parameters)
                rate_b = corner_height_rate(ydb, thb, om0, s, parameters)
                if rate_a < 0.0 and rate_b > 0.0:
                    low = tau_a
                    high = tau_b
                    for _ in range(200):
                        middle = 0.5 * (low + high)
                        if middle <= low or middle >= high:
                            break
                        _, ym, thm, _, ydm, _ = flight_state(middle, x0, y0, th0, xd0, yd0,
                                                             om0, ua, ka, va, kv)
                        if corner_height_rate(ydm, thm, om0, s, parameters) < 0.0:
                            low = middle
                        else:
                            high = middle
                    _, ym, thm, _, _, _ = flight_state(high, x0, y0, th0, xd0, yd0, om0, ua,
                                                       ka, va, kv)
                    if corner_height(ym, thm, s, parameters) <= 0.0 and (
                            upper < 0.0 or high < upper):
                        upper = high
        if upper >= 0.0:
            low = tau_a
            high = upper
            for _ in range(400):
                middle = 0.5 * (low + high)
                if middle <= low or middle >= high:
                    break
                _, ym, thm, _, _, _ = flight_state(middle, x0, y0, th0, xd0, yd0, om0, ua, ka,
                                                   va, kv)
                lm, _ = lowest_corner(ym, thm, parameters)
                if lm > 0.0:
                    low = middle
                else:
                    high = middle
            landing = high
        if landing >= 0.0 or overturn >= 0.0:
            break
        tau_a = tau_b
    return landing, overturn


@njit(**APART)
def flight_mode(t, t_end, side, sigma, entered, rho, mu_s, mu_d, segment, q, z, ev, info,
                parameters):
    """FLIGHT: the exact ballistic path to the interval's end, a landing (struck:
    :func:`~shaketable.models.planar.modes.strike`) or an overturn in the air, on pieces
    of at most 0.02 rad of rotation (at least 8 per interval). Returns (t, mode, side,
    sigma, entered, status, transition).
    """
    length = t_end - t
    ka = segment[6]
    kv = segment[7]
    ua, va = ground(segment, t)
    x0, y0, th0, xd0, yd0, om0 = q[0], q[1], q[2], q[3], q[4], q[5]
    pieces = int(min(1e6, max(8.0, math.ceil(abs(om0) * length / 0.02))))
    landing, overturn = flight_end(length, pieces, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv,
                                   parameters)
    span = length
    terminal = 0
    if overturn >= 0.0 and (landing < 0.0 or overturn <= landing):
        span = overturn
        terminal = 2
    elif landing >= 0.0:
        span = landing
        terminal = 1
    flight_extrema(t, span, pieces, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv, q, info,
                   PEAKS, parameters)
    xs, ys, ths, xds, yds, oms = flight_state(span, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv)
    info[I_W_TABLE] -= polynomial_work(ua, ka, xd0, -ua, -0.5 * ka, span)
    info[I_W_TABLE] -= polynomial_work(va, kv, yd0, -(G + va), -0.5 * kv, span)
    alpha = block_angle(1.0 if ths > 0.0 else -1.0, parameters)
    if math.isnan(info[I_T_UNSTABLE]) and abs(ths) > alpha:
        info[I_T_UNSTABLE] = t + (math.copysign(alpha, ths) - th0) / om0
        info[I_UNSTABLE_DIRECTION] = 1.0 if ths > 0.0 else -1.0
        record_event(ev, info, info[I_T_UNSTABLE], EV_UNSTABLE, MODE_FLIGHT, MODE_FLIGHT, om0,
                     q, parameters)
    q[0], q[1], q[2], q[3], q[4], q[5] = xs, ys, ths, xds, yds, oms
    info[I_TIME_FLIGHT] += span
    t = t_end if terminal == 0 else t + span
    track_peaks(t, q, info, parameters)
    if terminal == 2:
        q[2] = math.copysign(0.5 * math.pi, ths)
        info[I_T_OVERTURN] = t
        info[I_OVERTURN_DIRECTION] = 1.0 if ths > 0.0 else -1.0
        record_event(ev, info, t, EV_OVERTURN, MODE_FLIGHT, MODE_FLIGHT, oms, q, parameters)
        return t, FLIGHT, side, sigma, entered, STATUS_OVERTURNED, False
    if terminal == 0:
        return t, FLIGHT, side, sigma, entered, STATUS_COMPLETED, False
    # the landing: the lowest corner strikes (both at once: a flat landing)
    _, corner_side = lowest_corner(q[1], q[2], parameters)
    landed_flat = q[2] == 0.0 and q[5] == 0.0
    omega_before = q[5]
    kind, new_side, sigma, lost, cap = strike(q, corner_side, rho, mu_s, mu_d, parameters)
    info[I_N_IMPACTS] += 0 if landed_flat else 1
    info[I_CAPPED] += int(cap)
    if kind == PAINLEVE:
        info[I_FAILED_MODE] = FLIGHT
        return t, FLIGHT, side, sigma, entered, STATUS_PAINLEVE, True
    info[I_IMPACT_LOSS] += lost
    mode = int(kind)
    info[I_T_REST] = t if mode == REST else info[I_T_REST]
    if mode == ROCK or mode == SLIDE_ROCK:
        side = new_side
        z_from_q(q, side, z, parameters)
        entered = True
    record_event(ev, info, t, EV_LANDING if landed_flat else EV_IMPACT, MODE_FLIGHT, mode,
                 omega_before, q, parameters)
    return t, mode, side, sigma, entered, STATUS_COMPLETED, True


@njit(**INLINED)
def contact_entry(t, mode, side, sigma, rest_until, segment, mu_s, mu_d, q, z, k1, g_start,
                  fresh, ev, info, parameters):
    """Entering ROCK or SLIDE_ROCK (from a start rule, an impact or a landing): the mode
    the contact problem of the instant allows
    (:func:`~shaketable.models.planar.modes.enter_contact`); if it is the mode entered,
    its event functions and first slope. Returns (mode, sigma, entered, rest_until,
    status, transition).
    """
    if mode == ROCK:
        z[3] = 0.0   # the pivot sticks (a sticking impact leaves rounding)
    q_from_z(z, side, q, parameters)
    new_mode, new_sigma = enter_contact(mode, side, sigma, t, q, segment, mu_s, mu_d,
                                        parameters)
    if new_mode == PAINLEVE or new_mode == INCONSISTENT:
        info[I_FAILED_MODE] = mode
        status = STATUS_PAINLEVE if new_mode == PAINLEVE else STATUS_INCONSISTENT
        return mode, sigma, True, rest_until, status, False
    if new_mode != mode or new_sigma != sigma:
        record_event(ev, info, t, EV_REVERSAL if new_mode == mode else EV_MODE, mode,
                     new_mode, q[5], q, parameters)
        if new_mode == REST or new_mode == SLIDE:
            flat(q, q[3] if new_mode == SLIDE else 0.0, parameters)
            rest_until = t
        return new_mode, new_sigma, True, rest_until, STATUS_COMPLETED, True
    events(mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, g_start)
    for i in range(N_EVENTS):
        fresh[i] = (i == E_IMPACT or i == E_FRICTION) and g_start[i] <= 0.0
    rhs(mode, side, sigma, mu_d, t, z, segment, parameters, k1)
    info[I_EVALUATIONS] += 1
    return mode, sigma, False, rest_until, STATUS_COMPLETED, False


@njit(**INLINED)
def contact_steps(t, mode, side, sigma, step_size, just_rejected, rtol, mu_s, mu_d,
                  segment, scale_abs, z, z_new, z_event, z_turn, k1, stages, dense, ready,
                  g_start, g_end, armed, fresh, no_events, q, q_start, q_end, ev, info,
                  parameters):
    """ROCK or SLIDE_ROCK to the interval's end or the first terminal event: DOP853 steps
    with error control, each ending inside the interval, the terminal events and the
    peaks located on the step's continuous extension.

    Returns (t, step_size, just_rejected, status, terminal): terminal is the event that
    ended the last step (E_*), -1 for none (the interval's end).
    """
    t_end = segment[8]
    # the work and the counters in registers while stepping (their slots of info are
    # read once and written back at the end: the same sums)
    w_table = info[I_W_TABLE]
    w_friction = info[I_W_FRICTION]
    steps = 0
    rejected = 0
    evaluations = 0
    status = STATUS_COMPLETED
    terminal = -1
    alpha = block_angle(side, parameters)
    while t < t_end:
        step = min(step_size, t_end - t)
        if step < 1e-14 * (abs(t) + 1.0) and step < t_end - t:
            info[I_FAILED_MODE] = mode
            status = STATUS_STALLED
            break
        error = dop853_step(mode, side, sigma, mu_d, t, z, k1, step, segment, parameters,
                            stages, z_new, scale_abs, rtol)
        evaluations += 11
        if not error <= 1.0:
            if error != error:
                error = 1e10
            step_size = step * max(0.2, 0.9 * error ** -0.125)
            rejected += 1
            just_rejected = True
            continue
        growth = min(10.0, max(0.2, 0.9 * max(error, 1e-10) ** -0.125))
        if just_rejected:
            growth = min(growth, 1.0)
            just_rejected = False
        if step < step_size:
            step_size = max(step_size, step * growth)
        else:
            step_size = step * growth
        steps += 1
        ready[0] = False
        for i in range(N_EVENTS):
            armed[i] = g_start[i] > 0.0 or fresh[i]
        terminal, tau, used = terminal_event(
            mode, side, sigma, mu_s, mu_d, t, z, step, z_new, stages, dense, ready, segment,
            parameters, armed, g_end, z_event, z_turn, no_events)
        evaluations += used
        # non-terminal: the turning point (largest |theta|), the extrema of the slip and
        # of the corners' X (planar_track), and instability
        evaluations += contact_extrema(
            mode, side, sigma, mu_s, mu_d, t, z, step, stages, dense, ready, tau, z_new,
            segment, parameters, info, PEAKS, q, q_start, q_end, z_turn, no_events)
        if math.isnan(info[I_T_UNSTABLE]) and abs(z_new[0]) > alpha and abs(z[0]) <= alpha:
            tau_unstable, used = locate(KIND_ALPHA, mode, side, sigma, mu_s, mu_d, t, z, step,
                                        z_new, stages, dense, ready, tau, z_new, no_events,
                                        0.0, segment, parameters, z_turn)
            evaluations += used
            info[I_T_UNSTABLE] = t + tau_unstable
            info[I_UNSTABLE_DIRECTION] = 1.0 if z_new[0] > 0.0 else -1.0
            q_from_z(z_turn, side, q, parameters)
            record_event(ev, info, t + tau_unstable, EV_UNSTABLE, mode, mode, z_turn[1], q,
                         parameters)
        w_table += z_new[4] - z[4]
        w_friction += z_new[5] - z[5]
        if mode == ROCK:
            info[I_TIME_ROCK] += tau
        else:
            info[I_TIME_SLIDE_ROCK] += tau
        t = t_end if (terminal < 0 and tau == t_end - t) else t + tau
        for i in range(N_STATE):
            z[i] = z_new[i]
        q_from_z(z, side, q, parameters)
        track_peaks(t, q, info, parameters)
        if terminal >= 0:
            break
        for i in range(N_EVENTS):
            g_start[i] = g_end[i]
            fresh[i] = fresh[i] and g_end[i] <= 0.0
        rhs(mode, side, sigma, mu_d, t, z, segment, parameters, k1)
        evaluations += 1
    info[I_W_TABLE] = w_table
    info[I_W_FRICTION] = w_friction
    info[I_STEPS] += steps
    info[I_REJECTED] += rejected
    info[I_EVALUATIONS] += evaluations
    return t, step_size, just_rejected, status, terminal


@njit(**INLINED)
def contact_event(t, terminal, mode, side, sigma, entered, segment, mu_s, mu_d, z, q, ev, info,
                  parameters):
    """The event that ended a contact step other than an impact: overturn, Painleve's
    D = 0, lift-off (N = 0), the friction limit of ROCK or the end of SLIDE_ROCK's slip.
    Returns (mode, sigma, entered, status).
    """
    u_now, v_now = ground(segment, t)
    if terminal == E_OVERTURN:
        z[0] = side * 0.5 * math.pi
        q_from_z(z, side, q, parameters)
        info[I_T_OVERTURN] = t
        info[I_OVERTURN_DIRECTION] = side
        record_event(ev, info, t, EV_OVERTURN, mode, mode, z[1], q, parameters)
        return mode, sigma, entered, STATUS_OVERTURNED
    if terminal == E_MASS:
        info[I_FAILED_MODE] = mode
        return mode, sigma, entered, STATUS_PAINLEVE
    if terminal == E_NORMAL:
        record_event(ev, info, t, EV_MODE, mode, MODE_FLIGHT, z[1], q, parameters)
        return FLIGHT, sigma, entered, STATUS_COMPLETED
    if mode == ROCK:   # the friction limit: the pivot slips the way the force held it
        _, _, _, friction, _ = rock_forces(z[0], z[1], side, u_now, v_now, parameters)
        sigma = -1.0 if friction > 0.0 else 1.0
        record_event(ev, info, t, EV_MODE, MODE_ROCK, MODE_SLIDE_ROCK, z[1], q, parameters)
        return SLIDE_ROCK, sigma, True, STATUS_COMPLETED
    # the slip speed is zero to the located root: the (rounding-level) kinetic energy
    # taken out by zeroing it is counted as a loss
    before = kinetic_energy(q[3], q[4], q[5], parameters)
    z[3] = 0.0
    q_from_z(z, side, q, parameters)
    info[I_IMPACT_LOSS] += before - kinetic_energy(q[3], q[4], q[5], parameters)
    _, _, _, friction, normal = rock_forces(z[0], z[1], side, u_now, v_now, parameters)
    if abs(friction) <= mu_s * normal:
        record_event(ev, info, t, EV_MODE, MODE_SLIDE_ROCK, MODE_ROCK, z[1], q, parameters)
        return ROCK, sigma, True, STATUS_COMPLETED
    sigma = -1.0 if friction > 0.0 else 1.0
    record_event(ev, info, t, EV_REVERSAL, MODE_SLIDE_ROCK, MODE_SLIDE_ROCK, z[1], q, parameters)
    return mode, sigma, True, STATUS_COMPLETED


@njit(**INLINED)
def cascade_end(t, mode, side, sigma, rest_until, sticking, omega, omega_before, u_now, v_now,
                cor_cascade, mu_d, rest_tolerance, velocity_floor, q, ev, info, parameters):
    """After an impact into ROCK or SLIDE_ROCK: whether the cascade of impacts it starts is
    summed (the rocking engine's rule: a sticking rock-to-rock impact's ratio is cor, a
    slipping one's its own |w+/w-|; the deceleration is that of the mode entered, at
    theta = theta' = 0); a summed cascade settles flat, sliding at the corner's slip
    speed (REST if 0). Returns (settled, mode, sigma, rest_until).
    """
    if parameters[ASYMMETRIC] != 0.0:   # the ratio of an impact onto this pivot
        cor_cascade = parameters[COR_PLUS] if side > 0.0 else parameters[COR_MINUS]
    ratio = cor_cascade if (sticking and mode == ROCK) else abs(omega / omega_before)
    if mode == ROCK:
        deceleration = -side * pivot_acceleration(0.0, side, u_now, v_now, parameters)
    else:
        acceleration, _, _, _, _ = slide_rock_accelerations(0.0, 0.0, side, sigma, mu_d, u_now,
                                                            v_now, parameters)
        deceleration = -side * acceleration
        if not deceleration > 0.0:
            # slide-rock at rest tips away: its slip stops within microseconds and the
            # block falls back rocking (a slender block whose every impact slips); without
            # this the Zeno sequence is never summed
            deceleration = -side * pivot_acceleration(0.0, side, u_now, v_now, parameters)
    remaining = cascade_rest_time(omega, deceleration, ratio)
    if remaining == math.inf and ratio >= 1.0 and deceleration > 0.0 \
            and abs(omega) <= max(velocity_floor, 0.5 * deceleration * rest_tolerance):
        remaining = 0.0   # no decay, impacts < rest_tolerance apart
    if not (omega == 0.0 or remaining <= rest_tolerance or (
            abs(omega) <= velocity_floor and remaining < math.inf)):
        return False, mode, sigma, rest_until
    base = 0.0
    if mode == SLIDE_ROCK:
        _, r_y = corner_vector(0.0, side, parameters)
        base = q[3] - r_y * q[5]
    info[I_IMPACT_LOSS] += kinetic_energy(q[3], q[4], q[5], parameters) - 0.5 * base * base
    if omega != 0.0:
        info[I_CASCADES] += 1
    flat(q, base, parameters)
    if base == 0.0:
        mode = REST
        # a plastic impact (omega = 0) rests at once, as the rocking engine's: its
        # cascade time is inf when the table tips the block onto the striking corner
        rest_until = t + (0.0 if omega == 0.0 else remaining)
        info[I_T_REST] = rest_until
    else:
        mode = SLIDE
        sigma = 1.0 if base > 0.0 else -1.0
        info[I_T_REST] = -math.inf
    record_event(ev, info, t, EV_CASCADE, MODE_SLIDE_ROCK if base != 0.0 else MODE_ROCK, mode,
                 omega, q, parameters)
    return True, mode, sigma, rest_until


@njit(**APART)
def corner_impact(t, mode, side, sigma, rest_until, visited, rho, cor_cascade, mu_s, mu_d,
                  rest_tolerance, velocity_floor, segment, q, ev, info, parameters):
    """The other corner strikes at theta = 0: the impact
    (:func:`~shaketable.models.planar.modes.strike`, whose two-corner problem resolves a
    block turned back onto the corner on the table), the contact it leaves the block in
    and the cascade it starts (:func:`cascade_end`); a turn back onto the other corner
    strikes again at once (the loop bound is a safeguard).

    Returns (mode, side, sigma, rest_until, visited, status).
    """
    u_now, v_now = ground(segment, t)
    for repeat in range(MAX_IMMEDIATE_IMPACTS + 1):
        if repeat == MAX_IMMEDIATE_IMPACTS:
            info[I_FAILED_MODE] = mode
            return mode, side, sigma, rest_until, visited, STATUS_INCONSISTENT
        before_mode = mode
        omega_before = q[5]
        striking = -side
        kind, side, new_sigma, lost, cap = strike(q, striking, rho, mu_s, mu_d, parameters)
        info[I_N_IMPACTS] += 1
        info[I_CAPPED] += int(cap)
        if kind == PAINLEVE:
            info[I_FAILED_MODE] = mode
            return mode, side, sigma, rest_until, visited, STATUS_PAINLEVE
        info[I_IMPACT_LOSS] += lost
        omega = q[5]
        sticking = kind == ROCK and side == striking
        mode, sigma = enter_contact(int(kind), side, new_sigma, t, q, segment, mu_s, mu_d,
                                    parameters)
        if mode >= 0:
            visited |= 1 << mode
        if mode == PAINLEVE or mode == INCONSISTENT:
            info[I_FAILED_MODE] = before_mode
            status = STATUS_PAINLEVE if mode == PAINLEVE else STATUS_INCONSISTENT
            return before_mode, side, sigma, rest_until, visited, status
        if mode == REST or mode == SLIDE:
            flat(q, q[3] if mode == SLIDE else 0.0, parameters)
            rest_until = t
            info[I_T_REST] = t if mode == REST else -math.inf
        record_event(ev, info, t, EV_IMPACT, before_mode, mode, omega_before, q, parameters)
        if mode != ROCK and mode != SLIDE_ROCK:
            break
        settled, mode, sigma, rest_until = cascade_end(
            t, mode, side, sigma, rest_until, sticking, omega, omega_before, u_now, v_now,
            cor_cascade, mu_d, rest_tolerance, velocity_floor, q, ev, info, parameters)
        if settled or side * q[5] >= 0.0:
            break
    return mode, side, sigma, rest_until, visited, STATUS_COMPLETED
