"""The compiled event-driven engine of the planar block: rest, slide, rock, slide-rock, flight.

:func:`integrate` walks the table's samples interval by interval (the accelerations are
linear inside one, Section 2.8 of the report) and advances the block in its current
mode (:mod:`shaketable.models.planar.physics` states the physics once):

* REST: nothing moves; the first instant a rest condition fails (N > 0, Eq. (2-2)'s
  |ug| <= mu_s N, Eq. (2-1)'s |ug| h <= b N; each affine in time) is found in closed form
  and, as in the rocking engine, moved to the first representable time at which it fails
  strictly; the start rules (:func:`~shaketable.models.planar.physics.start_mode`) choose
  the next mode there.
* SLIDE: the cubic pieces of :func:`shaketable.models.sliding.engine.slide` (its root
  finders), ending where x' returns to 0 (rest, reversal or a rocking mode by the start
  rules) or N reaches 0 (flight).
* ROCK, SLIDE_ROCK: DOP853 steps (:mod:`shaketable.models.planar.steps`) with error
  control, each step ending inside the interval; the terminal events (impact at theta = 0,
  N = 0, the friction limit |F| = mu_s N or the slip speed's return to 0, overturn at
  pi/2, Painleve's D = 0; a turning point on the far side of theta = 0 is an impact passed
  inside the step) and the peaks (:mod:`~shaketable.models.planar.track`) are located on
  the step's continuous extension of order 7.
* FLIGHT: the exact ballistic path; landing where the lower bottom corner reaches the
  table, searched on pieces of at most 0.02 rad of rotation (at least 8 per interval) by
  the sign of the corner's height and of its rate (a touch-down between two pieces
  shows as a minimum), then bisected to the ulp.

Impacts use :func:`~shaketable.models.planar.physics.impact`; after a sticking impact at
theta = 0 the endless cascade of a decaying block is summed in closed form as the rocking
engine does (:func:`~shaketable.models.rocking.physics.cascade_rest_time`, the same rest tolerance
and velocity floor); after a slipping one, once summable by the same rule, it ends in SLIDE
with the corner's slip velocity (docs/planar.md, "Impacts").

The engine never produces NaN: a run that cannot go on stops with a status (overturned,
painleve, inconsistent, chatter, stalled: :data:`STATUSES`) and the state before it. The
work of the table's inertial force and of friction and the impact losses are accumulated
(closed forms in REST, SLIDE and FLIGHT; integrated with the state in the contact
modes), so that E_end - E_0 = W_table + W_friction - losses.

One compiled driver (as the rocking engine); its steppers and event location are in
:mod:`~shaketable.models.planar.steps`, its helpers in :mod:`~shaketable.models.planar.modes`
and :mod:`~shaketable.models.planar.track`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from shaketable.core.constants import G
from shaketable.models.planar.modes import (  # N_OUT: the output layout, re-exported
    N_OUT,  # noqa: F401
    OUT_MODE,
    OUT_OMEGA,
    OUT_SLIP,
    OUT_THETA,
    OUT_X,
    OUT_X_DOT,
    OUT_Y,
    OUT_Y_DOT,
    enter_contact,
    first_failure,
    flat,
    measures,
    q_from_z,
    store,
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
    corner_height,
    corner_height_rate,
    corner_vector,
    kinetic_energy,
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
    falses,
    flight_state,
    ground,
    locate,
    lowest_corner,
    polynomial_work,
    rhs,
    terminal_event,
    zeros,
)
from shaketable.models.planar.track import (
    P_PEAK_BASE_SLIP,
    contact_extrema,
    flight_extrema,
    record,
    track,
)
from shaketable.models.rocking.physics import (
    ALPHA,
    ERROR_MODEL,
    HALF_HEIGHT,
    HALF_WIDTH,
    cascade_rest_time,
    flight_acceleration,
)
from shaketable.models.sliding.engine import first_up_crossing, first_velocity_zero

#: Why a run stopped (index = status code).
STATUSES = ("completed", "overturned", "painleve", "inconsistent", "chatter", "stalled")
STATUS_COMPLETED, STATUS_OVERTURNED, STATUS_PAINLEVE, STATUS_INCONSISTENT, STATUS_CHATTER, \
    STATUS_STALLED = range(6)

#: Event kinds (index = code): a mode change that is not an impact, a corner impact,
#: a reversal of the slip, the end of a summed cascade of impacts, |theta| first
#: exceeding alpha, overturning, a flat landing of the whole base.
EVENT_KINDS = ("mode change", "impact", "slip reverses", "cascade summed", "unstable",
               "overturned", "flat landing")
# int64 values, not Python ints: numba types a module's int constants as literals and
# compiles a helper once for every distinct literal it is called with (_record was
# compiled 16 times on a cold cache); so are the mode codes _record is given below
EV_MODE, EV_IMPACT, EV_REVERSAL, EV_CASCADE, EV_UNSTABLE, EV_OVERTURN, EV_LANDING = (
    np.int64(code) for code in range(7))
_REST, _SLIDE, _ROCK, _SLIDE_ROCK, _FLIGHT = (
    np.int64(code) for code in (REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT))

#: Columns of the event array: time [s], kind, mode before, mode after, theta' [rad/s]
#: (before an impact; else at the event), slip of the base midpoint [m].
EVENT_COLUMNS = 6

#: Layout of the info array.
(I_STATUS, I_T_END, I_N_IMPACTS, I_CAPPED, I_CASCADES, I_T_START, I_T_UNSTABLE,
 I_UNSTABLE_DIRECTION, I_T_OVERTURN, I_OVERTURN_DIRECTION, I_MAX_ABS_THETA, I_T_MAX,
 I_PEAK_SLIP, I_T_PEAK_SLIP, I_PEAK_EXCURSION, I_W_TABLE, I_W_FRICTION, I_IMPACT_LOSS,
 I_STEPS, I_REJECTED, I_EVALUATIONS, I_N_EVENTS, I_N_OUTPUT, I_TIME_REST, I_TIME_SLIDE,
 I_TIME_ROCK, I_TIME_SLIDE_ROCK, I_TIME_FLIGHT, I_VISITED, I_T_REST, I_E0, I_E_END,
 I_FAILED_MODE, I_PEAK_BASE_SLIP, I_T_PEAK_BASE_SLIP) = range(35)
N_INFO = 35
assert I_PEAK_BASE_SLIP - I_MAX_ABS_THETA == P_PEAK_BASE_SLIP   # planar_track's layout

#: Where planar_track's peaks start in info, as an int64 (track is compiled for the type
#: its callers give ``first``: a literal would compile it once more).
_PEAKS = np.int64(I_MAX_ABS_THETA)

#: The sizes of the engine's work arrays, as int64 for the same reason (zeros, falses).
_ONE, _SIX, _STATE, _EVENTS = np.int64(1), np.int64(6), np.int64(N_STATE), np.int64(N_EVENTS)

#: Transitions allowed at one instant before the run stops with status "chatter".
MAX_TRANSITIONS_AT_ONE_TIME = 200

#: Impacts at one instant (each turning the block onto the other corner) before the run
#: stops with status "inconsistent": a safeguard (the two-corner problem of
#: :func:`~shaketable.models.planar.modes.strike` ends every such sequence at once).
MAX_IMMEDIATE_IMPACTS = 1000

#: Transitions allowed in one sample interval before the run stops with status "chatter"
#: (a safeguard against a Zeno sequence the cascade rule does not sum; never reached in
#: the tests).
MAX_TRANSITIONS_PER_INTERVAL = 100_000


@njit(**HELPER)
def _track(t, q, info, parameters):
    track(t, q, info, _PEAKS, parameters)   # planar_track's P_* from I_MAX_ABS_THETA


@njit(**HELPER)
def _record(ev, info, t, kind, before, after, omega, q, parameters):
    record(ev, info, I_N_EVENTS, t, kind, before, after, omega, q, parameters)


@njit(cache=True, nogil=True, error_model=ERROR_MODEL)
def integrate(t_grid, ug, vg, parameters, rho, cor_cascade, mu_s, mu_d, rtol, rest_tolerance,
              theta0, omega0, out, ev, final, info):
    """Integrate one run of the planar block; fill ``out``, ``ev``, ``final`` and ``info``.

    Parameters
    ----------
    t_grid, ug, vg : ndarray
        Sample times [s], horizontal (+x) and vertical (up) table accelerations [m/s^2].
    parameters : ndarray
        :func:`shaketable.models.rocking.physics.block_parameters` of a block without rods.
    rho : float
        Impact couple ratio [-]: cor / c_H, or 1 for Housner's law.
    cor_cascade : float
        theta' ratio of a rock-to-rock impact [-] (cor, or c_H for Housner), used to sum
        the cascade.
    mu_s, mu_d : float
        Static and dynamic friction [-].
    rtol : float
        Relative tolerance of DOP853 [-]; absolute ones rtol alpha [rad], rtol alpha p
        [rad/s], rtol R [m], rtol R p [m/s], rtol g R [m^2/s^2].
    rest_tolerance : float
        Summed cascade duration below which a cascade is summed [s]; < 0: 1e-6 / p.
    theta0, omega0 : float
        Initial rotation [rad] and rate [rad/s]; both zero: the block stands at rest.
        Otherwise it rocks about the lower corner, which stands at its rest position.
    out : ndarray, shape (n, N_OUT)
        State at the samples (columns OUT_*); 0 rows: not stored (a batch).
    ev : ndarray, shape (capacity, EVENT_COLUMNS)
        The first events (all are counted in ``info[I_N_EVENTS]``).
    final : ndarray, shape (N_OUT,)
        The state where the run ended.
    info : ndarray, shape (N_INFO,)
        Scalar results (I_* layout).
    """
    n = t_grid.shape[0]
    b = parameters[HALF_WIDTH]
    hh = parameters[HALF_HEIGHT]
    alpha = parameters[ALPHA]
    radius = math.sqrt(b * b + hh * hh)
    p = math.sqrt(3.0 * G / (4.0 * radius))
    if rest_tolerance < 0.0:
        rest_tolerance = 1e-6 / p
    velocity_floor = 1e-8 * alpha * p
    scale_abs = np.empty(6)   # (np.empty, not np.array or np.zeros: one numpy routine less
    # to compile on a cold cache; the work arrays below are zeroed by zeros and falses)
    scale_abs[0] = rtol * alpha
    scale_abs[1] = rtol * alpha * p
    scale_abs[2] = rtol * radius
    scale_abs[3] = rtol * radius * p
    scale_abs[4] = rtol * G * radius
    scale_abs[5] = rtol * G * radius
    segment = np.empty(8)
    stages = np.empty((16, N_STATE))
    dense = np.empty((7, N_STATE))
    ready = falses(_ONE)
    z = zeros(_STATE)
    z_new = zeros(_STATE)
    z_event = zeros(_STATE)
    z_turn = zeros(_STATE)
    k1 = zeros(_STATE)
    q = zeros(_SIX)
    q_start = zeros(_SIX)
    q_end = zeros(_SIX)
    g_start = zeros(_EVENTS)
    g_end = zeros(_EVENTS)
    armed = falses(_EVENTS)
    fresh = falses(_EVENTS)
    no_events = falses(_EVENTS)

    for i in range(N_INFO):
        info[i] = 0.0
    for i in (I_T_START, I_T_UNSTABLE, I_T_OVERTURN, I_T_REST):
        info[i] = math.nan
    status = STATUS_COMPLETED
    t = t_grid[0]
    side = 1.0
    sigma = 0.0
    if theta0 == 0.0 and omega0 == 0.0:
        mode = REST
        q[1] = hh
    else:
        mode = ROCK
        if theta0 < 0.0 or (theta0 == 0.0 and omega0 < 0.0):
            side = -1.0
        r_x, r_y = corner_vector(theta0, side, parameters)
        q[0] = -side * b - r_x
        q[1] = -r_y
        q[2] = theta0
        q[3] = r_y * omega0
        q[4] = -r_x * omega0
        q[5] = omega0
        z_from_q(q, side, z, parameters)
        info[I_T_START] = t
        if abs(theta0) > alpha:
            info[I_T_UNSTABLE] = t
            info[I_UNSTABLE_DIRECTION] = side
    entered = True
    visited = 1 << mode
    rest_until = t
    info[I_E0] = kinetic_energy(q[3], q[4], q[5], parameters) + G * q[1]
    w_table = 0.0
    w_friction = 0.0
    loss = 0.0
    step_size = 0.1 / p
    just_rejected = False
    last_impact = t
    last_transition = t
    transitions = 0
    n_impacts = 0
    capped = 0
    cascades = 0
    steps = 0
    rejected = 0
    evaluations = 0
    _track(t, q, info, parameters)
    slip, _, _ = measures(q, parameters)
    keep_rows = out.shape[0] >= n   # a batch passes 0 rows: scalar results only
    filled = 1
    if keep_rows:
        store(out, filled - 1, q, slip, mode)   # row 0 as an int64, not a literal 0: store
        # is compiled once for both its calls

    for k in range(n - 1):
        t0 = t_grid[k]
        t1 = t_grid[k + 1]
        segment[0] = t0
        segment[1] = t1 - t0
        segment[2] = ug[k]
        segment[3] = ug[k + 1] - ug[k]
        segment[4] = vg[k]
        segment[5] = vg[k + 1] - vg[k]
        ka = segment[3] / segment[1]
        kv = segment[5] / segment[1]
        segment[6] = ka
        segment[7] = kv
        t_end = t1
        interval_transitions = 0
        while t < t_end and status == STATUS_COMPLETED:
            previous_mode = mode
            transition = False
            if mode == REST:
                if rest_until >= t_end:
                    info[I_TIME_REST] += t_end - t
                    t = t_end
                    break
                if rest_until > t:
                    info[I_TIME_REST] += rest_until - t
                    t = rest_until
                when = first_failure(t, t_end, segment, mu_s, parameters)
                if when == math.inf:
                    info[I_TIME_REST] += t_end - t
                    t = t_end
                    break
                info[I_TIME_REST] += when - t
                t = when
                u_now, v_now = ground(segment, t)
                new_mode, new_side, new_sigma = start_mode(u_now, v_now, mu_s, mu_d, parameters)
                if new_mode == INCONSISTENT:
                    status = STATUS_INCONSISTENT
                    info[I_FAILED_MODE] = REST
                    break
                transition = True
                if new_mode != REST:
                    mode = new_mode
                    side = new_side
                    sigma = new_sigma
                    if math.isnan(info[I_T_START]):
                        info[I_T_START] = t
                    if mode == ROCK or mode == SLIDE_ROCK:
                        z_from_q(q, side, z, parameters)
                        entered = True
                    _record(ev, info, t, EV_MODE, _REST, mode, 0.0, q, parameters)
            elif mode == SLIDE:
                length = t_end - t
                ua, va = ground(segment, t)
                na = G + va
                v = q[3]
                t_air = first_up_crossing(-na, -kv, length)
                end = length if t_air < 0.0 else t_air
                c0 = -ua - sigma * mu_d * na
                c1 = -ka - sigma * mu_d * kv
                tr = first_velocity_zero(sigma * v, sigma * c0, 0.5 * sigma * c1, end)
                span = end if tr < 0.0 else tr
                w_table -= polynomial_work(ua, ka, v, c0, 0.5 * c1, span)
                w_friction -= sigma * mu_d * polynomial_work(na, kv, v, c0, 0.5 * c1, span)
                q[0] += v * span + 0.5 * c0 * span * span + c1 * span * span * span / 6.0
                q[3] = v + c0 * span + 0.5 * c1 * span * span
                info[I_TIME_SLIDE] += span
                if tr < 0.0 and t_air < 0.0:
                    t = t_end
                else:
                    t = t + span
                _track(t, q, info, parameters)
                if tr >= 0.0:
                    q[3] = 0.0
                    transition = True
                    u_now, v_now = ground(segment, t)
                    new_mode, new_side, new_sigma = start_mode(u_now, v_now, mu_s, mu_d,
                                                               parameters)
                    if new_mode == INCONSISTENT:
                        status = STATUS_INCONSISTENT
                        info[I_FAILED_MODE] = SLIDE
                        break
                    if new_mode == SLIDE:
                        kind = EV_REVERSAL if new_sigma != sigma else EV_MODE
                        sigma = new_sigma
                        _record(ev, info, t, kind, _SLIDE, _SLIDE, 0.0, q, parameters)
                    else:
                        mode = new_mode
                        # a slide an impact left (-inf: pending) ends the rocking's rest
                        if mode == REST and info[I_T_REST] == -math.inf:
                            info[I_T_REST] = t
                        side = new_side
                        sigma = new_sigma
                        if mode == ROCK or mode == SLIDE_ROCK:
                            z_from_q(q, side, z, parameters)
                            entered = True
                        _record(ev, info, t, EV_MODE, _SLIDE, mode, 0.0, q, parameters)
                elif t_air >= 0.0:
                    transition = True
                    mode = FLIGHT
                    _record(ev, info, t, EV_MODE, _SLIDE, _FLIGHT, 0.0, q, parameters)
            elif mode == FLIGHT:
                length = t_end - t
                ua, va = ground(segment, t)
                x0, y0, th0, xd0, yd0, om0 = q[0], q[1], q[2], q[3], q[4], q[5]
                pieces = int(min(1e6, max(8.0, math.ceil(abs(om0) * length / 0.02))))
                lowest0, _ = lowest_corner(y0, th0, parameters)
                positive_at_start = lowest0 > 0.0
                tau_a = 0.0
                landing = -1.0
                overturn = -1.0
                for j in range(1, pieces + 1):
                    tau_b = length if j == pieces else length * j / pieces
                    _, yb, thb, _, ydb, _ = flight_state(tau_b, x0, y0, th0, xd0, yd0, om0, ua,
                                                         ka, va, kv)
                    if abs(thb) >= 0.5 * math.pi:
                        overturn = (math.copysign(0.5 * math.pi, thb) - th0) / om0
                    low_b, _ = lowest_corner(yb, thb, parameters)
                    upper = -1.0
                    # strictly below: a gap of exactly 0 (the rise of a block just lifted
                    # off, below half an ulp of y) is no landing (docs/planar.md, lift-off)
                    if low_b < 0.0:
                        upper = tau_b
                    elif positive_at_start or tau_a > 0.0:
                        # a touch-down hidden between the piece ends: a minimum of a
                        # corner's height below 0 (not looked for in the first piece of a
                        # flight that leaves the table: the corner just released starts at
                        # zero height with zero rate and rises)
                        _, ya, tha, _, yda, _ = flight_state(tau_a, x0, y0, th0, xd0, yd0,
                                                             om0, ua, ka, va, kv)
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
                                    _, ym, thm, _, ydm, _ = flight_state(
                                        middle, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv)
                                    if corner_height_rate(ydm, thm, om0, s, parameters) < 0.0:
                                        low = middle
                                    else:
                                        high = middle
                                _, ym, thm, _, _, _ = flight_state(high, x0, y0, th0, xd0, yd0,
                                                                   om0, ua, ka, va, kv)
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
                            _, ym, thm, _, _, _ = flight_state(middle, x0, y0, th0, xd0, yd0,
                                                               om0, ua, ka, va, kv)
                            lm, _ = lowest_corner(ym, thm, parameters)
                            if lm > 0.0:
                                low = middle
                            else:
                                high = middle
                        landing = high
                    if landing >= 0.0 or overturn >= 0.0:
                        break
                    tau_a = tau_b
                span = length
                terminal = 0
                if overturn >= 0.0 and (landing < 0.0 or overturn <= landing):
                    span = overturn
                    terminal = 2
                elif landing >= 0.0:
                    span = landing
                    terminal = 1
                flight_extrema(t, span, pieces, x0, y0, th0, xd0, yd0, om0, ua, ka, va, kv, q, info,
                               _PEAKS, parameters)
                xs, ys, ths, xds, yds, oms = flight_state(span, x0, y0, th0, xd0, yd0, om0, ua,
                                                          ka, va, kv)
                w_table -= polynomial_work(ua, ka, xd0, -ua, -0.5 * ka, span)
                w_table -= polynomial_work(va, kv, yd0, -(G + va), -0.5 * kv, span)
                if math.isnan(info[I_T_UNSTABLE]) and abs(ths) > alpha:
                    info[I_T_UNSTABLE] = t + (math.copysign(alpha, ths) - th0) / om0
                    info[I_UNSTABLE_DIRECTION] = 1.0 if ths > 0.0 else -1.0
                    _record(ev, info, info[I_T_UNSTABLE], EV_UNSTABLE, _FLIGHT, _FLIGHT, om0, q,
                            parameters)
                q[0], q[1], q[2], q[3], q[4], q[5] = xs, ys, ths, xds, yds, oms
                info[I_TIME_FLIGHT] += span
                t = t_end if terminal == 0 else t + span
                _track(t, q, info, parameters)
                if terminal == 2:
                    status = STATUS_OVERTURNED
                    q[2] = math.copysign(0.5 * math.pi, ths)
                    info[I_T_OVERTURN] = t
                    info[I_OVERTURN_DIRECTION] = 1.0 if ths > 0.0 else -1.0
                    _record(ev, info, t, EV_OVERTURN, _FLIGHT, _FLIGHT, oms, q, parameters)
                    break
                if terminal == 1:
                    transition = True
                    _, corner_side = lowest_corner(q[1], q[2], parameters)
                    landed_flat = q[2] == 0.0 and q[5] == 0.0
                    omega_before = q[5]
                    kind, new_side, sigma, lost, cap = strike(q, corner_side, rho, mu_s, mu_d,
                                                              parameters)
                    n_impacts += 0 if landed_flat else 1
                    capped += int(cap)
                    if kind == PAINLEVE:
                        status = STATUS_PAINLEVE
                        info[I_FAILED_MODE] = FLIGHT
                        break
                    loss += lost
                    mode = int(kind)
                    info[I_T_REST] = t if mode == REST else info[I_T_REST]
                    if mode == ROCK or mode == SLIDE_ROCK:
                        side = new_side
                        z_from_q(q, side, z, parameters)
                        entered = True
                    _record(ev, info, t, EV_LANDING if landed_flat else EV_IMPACT, _FLIGHT, mode,
                            omega_before, q, parameters)
            else:
                # ---------------------------------------------------------------- contact
                if entered:
                    if mode == ROCK:
                        z[3] = 0.0   # the pivot sticks (a sticking impact leaves rounding)
                    q_from_z(z, side, q, parameters)
                    new_mode, new_sigma = enter_contact(mode, side, sigma, t, q, segment, mu_s, mu_d,
                                                 parameters)
                    if new_mode == PAINLEVE or new_mode == INCONSISTENT:
                        status = STATUS_PAINLEVE if new_mode == PAINLEVE \
                            else STATUS_INCONSISTENT
                        info[I_FAILED_MODE] = mode
                        break
                    if new_mode != mode or new_sigma != sigma:
                        transition = True
                        _record(ev, info, t, EV_REVERSAL if new_mode == mode else EV_MODE, mode,
                                new_mode, q[5], q, parameters)
                        if new_mode == REST or new_mode == SLIDE:
                            flat(q, q[3] if new_mode == SLIDE else 0.0, parameters)
                            rest_until = t
                        mode = new_mode
                        sigma = new_sigma
                    else:
                        events(mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, g_start)
                        for i in range(N_EVENTS):
                            fresh[i] = (i == E_IMPACT or i == E_FRICTION) and g_start[i] <= 0.0
                        entered = False
                        rhs(mode, side, sigma, mu_d, t, z, segment, parameters, k1)
                        evaluations += 1
                else:
                    step = min(step_size, t_end - t)
                    if step < 1e-14 * (abs(t) + 1.0) and step < t_end - t:
                        status = STATUS_STALLED
                        info[I_FAILED_MODE] = mode
                        break
                    error = dop853_step(mode, side, sigma, mu_d, t, z, k1, step, segment,
                                        parameters, stages, z_new, scale_abs, rtol)
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
                        mode, side, sigma, mu_s, mu_d, t, z, step, z_new, stages, dense, ready,
                        segment, parameters, armed, g_end, z_event, z_turn, no_events)
                    evaluations += used
                    # non-terminal: the turning point (largest |theta|), the extrema of the slip
                    # and of the corners' X (planar_track), and instability
                    evaluations += contact_extrema(
                        mode, side, sigma, mu_s, mu_d, t, z, step, stages, dense, ready, tau,
                        z_new, segment, parameters, info, _PEAKS, q, q_start, q_end,
                        z_turn, no_events)
                    if math.isnan(info[I_T_UNSTABLE]) and abs(z_new[0]) > alpha \
                            and abs(z[0]) <= alpha:
                        tau_unstable, used = locate(KIND_ALPHA, mode, side, sigma, mu_s, mu_d,
                                                    t, z, step, z_new, stages, dense, ready, tau,
                                                    z_new, no_events, 0.0, segment, parameters,
                                                    z_turn)
                        evaluations += used
                        info[I_T_UNSTABLE] = t + tau_unstable
                        info[I_UNSTABLE_DIRECTION] = 1.0 if z_new[0] > 0.0 else -1.0
                        q_from_z(z_turn, side, q, parameters)
                        _record(ev, info, t + tau_unstable, EV_UNSTABLE, mode, mode, z_turn[1],
                                q, parameters)
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
                    _track(t, q, info, parameters)
                    if terminal < 0:
                        for i in range(N_EVENTS):
                            g_start[i] = g_end[i]
                            fresh[i] = fresh[i] and g_end[i] <= 0.0
                        rhs(mode, side, sigma, mu_d, t, z, segment, parameters, k1)
                        evaluations += 1
                        continue
                    transition = True
                    u_now, v_now = ground(segment, t)
                    if terminal == E_OVERTURN:
                        status = STATUS_OVERTURNED
                        z[0] = side * 0.5 * math.pi
                        q_from_z(z, side, q, parameters)
                        info[I_T_OVERTURN] = t
                        info[I_OVERTURN_DIRECTION] = side
                        _record(ev, info, t, EV_OVERTURN, mode, mode, z[1], q, parameters)
                        break
                    if terminal == E_MASS:
                        status = STATUS_PAINLEVE
                        info[I_FAILED_MODE] = mode
                        break
                    if terminal == E_NORMAL:
                        mode = FLIGHT
                        _record(ev, info, t, EV_MODE, previous_mode, _FLIGHT, z[1], q,
                                parameters)
                    elif terminal == E_FRICTION and mode == ROCK:
                        _, _, _, friction, _ = rock_forces(z[0], z[1], side, u_now, v_now,
                                                           parameters)
                        sigma = -1.0 if friction > 0.0 else 1.0
                        mode = SLIDE_ROCK
                        entered = True
                        _record(ev, info, t, EV_MODE, _ROCK, _SLIDE_ROCK, z[1], q, parameters)
                    elif terminal == E_FRICTION:
                        # the slip speed is zero to the located root: the (rounding-level)
                        # kinetic energy taken out by zeroing it is counted as a loss
                        before = kinetic_energy(q[3], q[4], q[5], parameters)
                        z[3] = 0.0
                        q_from_z(z, side, q, parameters)
                        loss += before - kinetic_energy(q[3], q[4], q[5], parameters)
                        _, _, _, friction, normal = rock_forces(z[0], z[1], side, u_now, v_now,
                                                                parameters)
                        entered = True
                        if abs(friction) <= mu_s * normal:
                            mode = ROCK
                            _record(ev, info, t, EV_MODE, _SLIDE_ROCK, _ROCK, z[1], q,
                                    parameters)
                        else:
                            sigma = -1.0 if friction > 0.0 else 1.0
                            _record(ev, info, t, EV_REVERSAL, _SLIDE_ROCK, _SLIDE_ROCK, z[1], q,
                                    parameters)
                    else:
                        # ---- impact of the other corner at theta = 0 (strike resolves a
                        # block turned back onto the corner on the table with the
                        # two-corner problem; the loop bound is a safeguard)
                        z[0] = 0.0
                        q_from_z(z, side, q, parameters)
                        step_size = min(step_size, max(t - last_impact, 1e-3 * step_size))
                        last_impact = t
                        for repeat in range(MAX_IMMEDIATE_IMPACTS + 1):
                            if repeat == MAX_IMMEDIATE_IMPACTS:
                                status = STATUS_INCONSISTENT
                                info[I_FAILED_MODE] = mode
                                break
                            before_mode = mode
                            omega_before = q[5]
                            striking = -side
                            kind, side, new_sigma, lost, cap = strike(q, striking, rho, mu_s,
                                                                      mu_d, parameters)
                            n_impacts += 1
                            capped += int(cap)
                            if kind == PAINLEVE:
                                status = STATUS_PAINLEVE
                                info[I_FAILED_MODE] = mode
                                break
                            loss += lost
                            omega = q[5]
                            sticking = kind == ROCK and side == striking
                            mode, sigma = enter_contact(int(kind), side, new_sigma, t, q, segment,
                                                 mu_s, mu_d, parameters)
                            if mode >= 0:
                                visited |= 1 << mode
                            if mode == PAINLEVE or mode == INCONSISTENT:
                                status = STATUS_PAINLEVE if mode == PAINLEVE \
                                    else STATUS_INCONSISTENT
                                info[I_FAILED_MODE] = before_mode
                                mode = before_mode
                                break
                            if mode == REST or mode == SLIDE:
                                flat(q, q[3] if mode == SLIDE else 0.0, parameters)
                                rest_until = t
                                info[I_T_REST] = t if mode == REST else -math.inf
                            _record(ev, info, t, EV_IMPACT, before_mode, mode, omega_before, q,
                                    parameters)
                            if mode != ROCK and mode != SLIDE_ROCK:
                                break
                            # the cascade rule of the rocking engine: a sticking rock-to-rock
                            # impact's ratio is cor; a slipping one's is its own |w+/w-|; the
                            # deceleration is that of the mode entered, at theta = theta' = 0
                            ratio = cor_cascade if (sticking and mode == ROCK) \
                                else abs(omega / omega_before)
                            if mode == ROCK:
                                deceleration = -side * flight_acceleration(
                                    0.0, side, u_now, v_now, 0.0, parameters)
                            else:
                                acceleration, _, _, _, _ = slide_rock_accelerations(
                                    0.0, 0.0, side, sigma, mu_d, u_now, v_now, parameters)
                                deceleration = -side * acceleration
                                if not deceleration > 0.0:
                                    # slide-rock at rest tips away: its slip stops within
                                    # microseconds and the block falls back rocking (a
                                    # slender block whose every impact slips); without
                                    # this the Zeno sequence is never summed
                                    deceleration = -side * flight_acceleration(
                                        0.0, side, u_now, v_now, 0.0, parameters)
                            remaining = cascade_rest_time(omega, deceleration, ratio)
                            if remaining == math.inf and ratio >= 1.0 and deceleration > 0.0 \
                                    and abs(omega) <= max(velocity_floor, 0.5 * deceleration
                                                          * rest_tolerance):
                                remaining = 0.0   # no decay, impacts < rest_tolerance apart
                            if omega == 0.0 or remaining <= rest_tolerance or (
                                    abs(omega) <= velocity_floor and remaining < math.inf):
                                # settles flat: sliding at the corner's slip speed (REST if 0)
                                base = 0.0
                                if mode == SLIDE_ROCK:
                                    _, r_y = corner_vector(0.0, side, parameters)
                                    base = q[3] - r_y * q[5]
                                loss += kinetic_energy(q[3], q[4], q[5], parameters) \
                                    - 0.5 * base * base
                                if omega != 0.0:
                                    cascades += 1
                                flat(q, base, parameters)
                                if base == 0.0:
                                    mode = REST
                                    # a plastic impact (omega = 0) rests at once, as the
                                    # rocking engine's: its cascade time is inf when the
                                    # table tips the block onto the striking corner
                                    rest_until = t + (0.0 if omega == 0.0 else remaining)
                                    info[I_T_REST] = rest_until
                                else:
                                    mode = SLIDE
                                    sigma = 1.0 if base > 0.0 else -1.0
                                    info[I_T_REST] = -math.inf
                                _record(ev, info, t, EV_CASCADE, _SLIDE_ROCK if base != 0.0
                                        else _ROCK, mode, omega, q, parameters)
                                break
                            if side * q[5] >= 0.0:
                                break
                        if status != STATUS_COMPLETED:
                            break
                        if mode == ROCK or mode == SLIDE_ROCK:
                            z_from_q(q, side, z, parameters)
                            entered = True
            if mode != previous_mode:
                visited |= 1 << mode
            if transition:
                interval_transitions += 1
                if interval_transitions > MAX_TRANSITIONS_PER_INTERVAL:
                    status = STATUS_CHATTER
                    info[I_FAILED_MODE] = mode
                    break
                if t == last_transition:
                    transitions += 1
                    if transitions > MAX_TRANSITIONS_AT_ONE_TIME:
                        status = STATUS_CHATTER
                        info[I_FAILED_MODE] = mode
                        break
                else:
                    transitions = 0
                    last_transition = t
        if status != STATUS_COMPLETED:
            break
        _track(t, q, info, parameters)
        if keep_rows:
            slip, _, _ = measures(q, parameters)
            store(out, k + 1, q, slip, mode)
        filled = k + 2

    slip, _, _ = measures(q, parameters)
    final[OUT_X] = q[0]
    final[OUT_Y] = q[1]
    final[OUT_THETA] = q[2]
    final[OUT_X_DOT] = q[3]
    final[OUT_Y_DOT] = q[4]
    final[OUT_OMEGA] = q[5]
    final[OUT_SLIP] = slip
    final[OUT_MODE] = mode
    info[I_STATUS] = status
    info[I_T_END] = t
    info[I_N_IMPACTS] = n_impacts
    info[I_CAPPED] = capped
    info[I_CASCADES] = cascades
    info[I_W_TABLE] = w_table
    info[I_W_FRICTION] = w_friction
    info[I_IMPACT_LOSS] = loss
    info[I_STEPS] = steps
    info[I_REJECTED] = rejected
    info[I_EVALUATIONS] = evaluations
    info[I_N_OUTPUT] = filled
    info[I_VISITED] = visited
    info[I_E_END] = kinetic_energy(q[3], q[4], q[5], parameters) + G * q[1]
    if info[I_T_REST] == -math.inf:   # still sliding from an impact
        info[I_T_REST] = math.nan
