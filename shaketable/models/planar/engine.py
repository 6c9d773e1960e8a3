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

One compiled driver (as the rocking engine) that walks the samples and hands each mode to
its own function (:mod:`~shaketable.models.planar.phases`: ``rest_mode``, ``slide_mode``,
``flight_mode``, and for the contact modes ``contact_entry``, ``contact_steps``,
``contact_event``, ``corner_impact``), inlined into it by numba, except the two rare
ones with the longest code (``flight_mode``, ``corner_impact``: a flight, an impact),
which are called (numba copies the code of each function it inlines, and copying those two
cost more first-compile time than their calls cost at run time); the driver allocates
nothing (its caller passes the work arrays of :func:`work_arrays`), so that it is compiled
without reference counting. Its steppers and event location are in
:mod:`~shaketable.models.planar.steps` (on :mod:`shaketable.numerics.dop853`), its helpers in
:mod:`~shaketable.models.planar.modes` and :mod:`~shaketable.models.planar.track`, the
layout of its arrays in :mod:`~shaketable.models.planar.layout`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from shaketable.core.constants import G
from shaketable.models.planar.layout import (  # the layout, re-exported: planar.<NAME>
    EV_CASCADE,  # noqa: F401
    EV_IMPACT,  # noqa: F401
    EV_LANDING,  # noqa: F401
    EV_MODE,  # noqa: F401
    EV_OVERTURN,  # noqa: F401
    EV_REVERSAL,  # noqa: F401
    EV_UNSTABLE,  # noqa: F401
    EVENT_COLUMNS,  # noqa: F401
    EVENT_KINDS,  # noqa: F401
    EVENTS,
    I_CAPPED,  # noqa: F401
    I_CASCADES,  # noqa: F401
    I_E0,
    I_E_END,
    I_EVALUATIONS,  # noqa: F401
    I_FAILED_MODE,
    I_IMPACT_LOSS,  # noqa: F401
    I_MAX_ABS_THETA,  # noqa: F401
    I_N_EVENTS,  # noqa: F401
    I_N_IMPACTS,  # noqa: F401
    I_N_OUTPUT,
    I_OVERTURN_DIRECTION,  # noqa: F401
    I_PEAK_BASE_SLIP,  # noqa: F401
    I_PEAK_EXCURSION,  # noqa: F401
    I_PEAK_SLIP,  # noqa: F401
    I_REJECTED,  # noqa: F401
    I_STATUS,
    I_STEPS,  # noqa: F401
    I_T_END,
    I_T_MAX,  # noqa: F401
    I_T_OVERTURN,
    I_T_PEAK_BASE_SLIP,  # noqa: F401
    I_T_PEAK_SLIP,  # noqa: F401
    I_T_REST,
    I_T_START,
    I_T_UNSTABLE,
    I_TIME_FLIGHT,  # noqa: F401
    I_TIME_REST,  # noqa: F401
    I_TIME_ROCK,  # noqa: F401
    I_TIME_SLIDE,  # noqa: F401
    I_TIME_SLIDE_ROCK,  # noqa: F401
    I_UNSTABLE_DIRECTION,
    I_VISITED,
    I_W_FRICTION,  # noqa: F401
    I_W_TABLE,  # noqa: F401
    MAX_IMMEDIATE_IMPACTS,  # noqa: F401
    MAX_TRANSITIONS_AT_ONE_TIME,
    MAX_TRANSITIONS_PER_INTERVAL,
    N_INFO,
    ONE,
    SIX,
    STATE,
    STATUS_CHATTER,
    STATUS_COMPLETED,
    STATUS_INCONSISTENT,  # noqa: F401
    STATUS_OVERTURNED,  # noqa: F401
    STATUS_PAINLEVE,  # noqa: F401
    STATUS_STALLED,  # noqa: F401
    STATUSES,  # noqa: F401
)
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
    measures,
    q_from_z,
    store,
    z_from_q,
)
from shaketable.models.planar.phases import (
    INLINED,
    contact_entry,
    contact_event,
    contact_steps,
    corner_impact,
    flight_mode,
    rest_mode,
    slide_mode,
    track_peaks,
)
from shaketable.models.planar.physics import (
    FLIGHT,
    REST,
    ROCK,
    SLIDE,
    SLIDE_ROCK,
    block_angle,
    corner_vector,
    half_width,
    kinetic_energy,
)
from shaketable.models.planar.steps import E_IMPACT, N_STATE, STAGE_ROWS
from shaketable.models.rocking.physics import ALPHA, ERROR_MODEL, HALF_HEIGHT, HALF_WIDTH

#: numba options of :func:`integrate`: no reference counting (it allocates nothing).
ENTRY: Any = {"cache": True, "nogil": True, "error_model": ERROR_MODEL, "_nrt": False}


def work_arrays() -> tuple:
    """The work arrays of one run of :func:`integrate` (its arguments after ``info``), to
    be reused from run to run (integrate clears them): scale_abs (the absolute
    tolerances), segment (:func:`~shaketable.models.planar.steps.ground`'s layout, then the
    interval's end [s]), stages (STAGE_ROWS rows), dense (the continuous extension), ready,
    z, z_new, z_event, z_turn, k1 (contact states), q, q_start, q_end (body states),
    g_start, g_end (event functions), armed, fresh, no_events (event flags)."""
    return (np.empty(6), np.empty(9), np.empty((STAGE_ROWS, N_STATE)),
            np.empty((7, N_STATE)), np.empty(ONE, dtype=np.bool_),
            *(np.empty(STATE) for _ in range(5)), *(np.empty(SIX) for _ in range(3)),
            np.empty(EVENTS), np.empty(EVENTS),
            *(np.empty(EVENTS, dtype=np.bool_) for _ in range(3)))


@njit(**ENTRY)
def integrate(t_grid, ug, vg, parameters, rho, cor_cascade, mu_s, mu_d, rtol, rest_tolerance,
              theta0, omega0, out, ev, final, info, scale_abs, segment, stages, dense, ready,
              z, z_new, z_event, z_turn, k1, q, q_start, q_end, g_start, g_end, armed, fresh,
              no_events):
    """Integrate one run of the planar block; fill ``out``, ``ev``, ``final`` and ``info``.

    Compiled without numba's reference counting: it allocates nothing (the work arrays
    are the caller's, :func:`work_arrays`), and the mode functions, inlined into it or
    called (compiled without reference counting too), take its arrays at no cost.

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
    scale_abs, ..., no_events : ndarray
        The work arrays (:func:`work_arrays`), cleared here.
    """
    clear(ready, z, z_new, z_event, z_turn, k1, q, q_start, q_end, g_start, g_end, armed,
          fresh, no_events)
    n = t_grid.shape[0]
    b = parameters[HALF_WIDTH]
    hh = parameters[HALF_HEIGHT]
    alpha = parameters[ALPHA]
    radius = math.sqrt(b * b + hh * hh)
    p = math.sqrt(3.0 * G / (4.0 * radius))
    if rest_tolerance < 0.0:
        rest_tolerance = 1e-6 / p
    velocity_floor = 1e-8 * alpha * p
    scale_abs[0], scale_abs[1], scale_abs[2] = rtol * alpha, rtol * alpha * p, rtol * radius
    scale_abs[3], scale_abs[4], scale_abs[5] = rtol * radius * p, rtol * G * radius, \
        rtol * G * radius
    t = t_grid[0]
    mode, side = start(t, theta0, omega0, q, z, info, parameters)
    status = STATUS_COMPLETED
    sigma = 0.0
    entered = np.bool_(True)   # not the literal True: flight_mode compiled once
    visited = 1 << mode
    rest_until = t
    step_size = 0.1 / p
    just_rejected = np.bool_(False)   # not the literal False: contact_steps compiled once
    last_impact, last_transition, transitions = t, t, 0
    track_peaks(t, q, info, parameters)
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
        segment[6] = segment[3] / segment[1]
        segment[7] = segment[5] / segment[1]
        t_end = t1
        segment[8] = t_end
        interval_transitions = 0
        while t < t_end and status == STATUS_COMPLETED:
            previous_mode = mode
            transition = False
            if mode == REST:
                t, mode, side, sigma, entered, status, transition = rest_mode(
                    t, t_end, side, sigma, entered, rest_until, segment, mu_s, mu_d, q, z, ev,
                    info, parameters)
            elif mode == SLIDE:
                t, mode, side, sigma, entered, status, transition = slide_mode(
                    t, t_end, side, sigma, entered, segment, mu_s, mu_d, q, z, ev, info,
                    parameters)
            elif mode == FLIGHT:
                t, mode, side, sigma, entered, status, transition = flight_mode(
                    t, t_end, side, sigma, entered, rho, mu_s, mu_d, segment, q, z, ev, info,
                    parameters)
            elif entered:   # ROCK or SLIDE_ROCK, just entered
                mode, sigma, entered, rest_until, status, transition = contact_entry(
                    t, mode, side, sigma, rest_until, segment, mu_s, mu_d, q, z, k1, g_start,
                    fresh, ev, info, parameters)
            else:   # ROCK or SLIDE_ROCK: steps to the interval's end or an event
                t, step_size, just_rejected, status, terminal = contact_steps(
                    t, mode, side, sigma, step_size, just_rejected, rtol, mu_s, mu_d,
                    segment, scale_abs, z, z_new, z_event, z_turn, k1, stages, dense, ready,
                    g_start, g_end, armed, fresh, no_events, q, q_start, q_end, ev, info,
                    parameters)
                if terminal >= 0 and status == STATUS_COMPLETED:
                    transition = True
                    if terminal != E_IMPACT:
                        mode, sigma, entered, status = contact_event(
                            t, terminal, mode, side, sigma, entered, segment, mu_s, mu_d, z, q,
                            ev, info, parameters)
                    else:
                        z[0] = 0.0
                        q_from_z(z, side, q, parameters)
                        step_size = min(step_size, max(t - last_impact, 1e-3 * step_size))
                        last_impact = t
                        mode, side, sigma, rest_until, visited, status = corner_impact(
                            t, mode, side, sigma, rest_until, visited, rho, cor_cascade, mu_s,
                            mu_d, rest_tolerance, velocity_floor, segment, q, ev, info,
                            parameters)
                        if status == STATUS_COMPLETED and (mode == ROCK or mode == SLIDE_ROCK):
                            z_from_q(q, side, z, parameters)
                            entered = True
            if status != STATUS_COMPLETED:
                break
            if mode != previous_mode:
                visited |= 1 << mode
            if transition:
                status, interval_transitions, transitions, last_transition = counted(
                    t, mode, interval_transitions, transitions, last_transition, info)
                if status != STATUS_COMPLETED:
                    break
        if status != STATUS_COMPLETED:
            break
        track_peaks(t, q, info, parameters)
        if keep_rows:
            slip, _, _ = measures(q, parameters)
            store(out, k + 1, q, slip, mode)
        filled = k + 2

    finish(t, q, mode, status, filled, visited, final, info, parameters)


@njit(**INLINED)
def clear(ready, z, z_new, z_event, z_turn, k1, q, q_start, q_end, g_start, g_end, armed, fresh,
          no_events):
    """The work arrays that are read before written: zeros and False."""
    ready[0] = False
    for i in range(STATE):
        z[i], z_new[i], z_event[i], z_turn[i], k1[i] = 0.0, 0.0, 0.0, 0.0, 0.0
    for i in range(SIX):
        q[i], q_start[i], q_end[i] = 0.0, 0.0, 0.0
    for i in range(EVENTS):
        g_start[i], g_end[i] = 0.0, 0.0
        armed[i], fresh[i], no_events[i] = False, False, False


@njit(**INLINED)
def start(t, theta0, omega0, q, z, info, parameters):
    """The start of a run: info cleared (the counters, the work of the table and of friction
    and the impact losses are accumulated there from 0), the block at rest (REST) or
    released at theta0, omega0 about its lower corner, which stands at its rest position
    (ROCK). Returns (mode, side)."""
    for i in range(N_INFO):
        info[i] = 0.0
    for i in (I_T_START, I_T_UNSTABLE, I_T_OVERTURN, I_T_REST):
        info[i] = math.nan
    for i in range(6):
        q[i] = 0.0
    side = 1.0
    if theta0 == 0.0 and omega0 == 0.0:
        q[1] = parameters[HALF_HEIGHT]
        info[I_E0] = kinetic_energy(q[3], q[4], q[5], parameters) + G * q[1]
        return REST, side
    if theta0 < 0.0 or (theta0 == 0.0 and omega0 < 0.0):
        side = -1.0
    r_x, r_y = corner_vector(theta0, side, parameters)
    q[0] = -side * half_width(side, parameters) - r_x
    q[1] = -r_y
    q[2] = theta0
    q[3] = r_y * omega0
    q[4] = -r_x * omega0
    q[5] = omega0
    z_from_q(q, side, z, parameters)
    info[I_T_START] = t
    if abs(theta0) > block_angle(side, parameters):
        info[I_T_UNSTABLE] = t
        info[I_UNSTABLE_DIRECTION] = side
    info[I_E0] = kinetic_energy(q[3], q[4], q[5], parameters) + G * q[1]
    return ROCK, side


@njit(**INLINED)
def counted(t, mode, interval_transitions, transitions, last_transition, info):
    """A transition counted against the safeguards (status "chatter" beyond
    MAX_TRANSITIONS_PER_INTERVAL in one sample interval or MAX_TRANSITIONS_AT_ONE_TIME at
    one instant). Returns (status, interval_transitions, transitions, last_transition)."""
    interval_transitions += 1
    if interval_transitions > MAX_TRANSITIONS_PER_INTERVAL:
        info[I_FAILED_MODE] = mode
        return STATUS_CHATTER, interval_transitions, transitions, last_transition
    if t == last_transition:
        transitions += 1
        if transitions > MAX_TRANSITIONS_AT_ONE_TIME:
            info[I_FAILED_MODE] = mode
            return STATUS_CHATTER, interval_transitions, transitions, last_transition
    else:
        transitions = 0
        last_transition = t
    return STATUS_COMPLETED, interval_transitions, transitions, last_transition


@njit(**INLINED)
def finish(t, q, mode, status, filled, visited, final, info, parameters):
    """The end of a run: the final state and the scalars of info."""
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
    info[I_N_OUTPUT] = filled
    info[I_VISITED] = visited
    info[I_E_END] = kinetic_energy(q[3], q[4], q[5], parameters) + G * q[1]
    if info[I_T_REST] == -math.inf:   # still sliding from an impact
        info[I_T_REST] = math.nan
