"""The steppers of the planar engine (:mod:`shaketable.models.planar.engine`), compiled with numba.

* ROCK and SLIDE_ROCK: the state z = [theta, theta', X_s, X_s', W_ground, W_friction]
  (X_s the active corner's horizontal position [m], fixed in ROCK; W the work per unit
  mass of the table's inertial force and of friction [m^2/s^2], integrated with the
  motion) advanced by the explicit Runge-Kutta pair DOP853 of Dormand & Prince (order 8,
  error estimators of orders 5 and 3; Hairer, Norsett & Wanner, Solving ODEs I, Sec. II.10;
  the shared :mod:`shaketable.numerics.dop853`), with the physics of
  :mod:`shaketable.models.planar.physics`. (The Nystrom pair of the
  rocking engine needs theta'' = f(t, theta); SLIDE_ROCK has theta'^2 terms.)
* Events are zeros of event functions of the state, located on the accepted step's
  continuous extension of order 7 (Hairer's contd8: three more stages, built only for a
  step in which an event is looked for) by Newton's step or the Illinois variant of
  regula falsi, safeguarded by bisection, to a bracket of a few ulps.
* REST, SLIDE and FLIGHT are closed forms (the table accelerations are linear between
  samples): the polynomial helpers here.

Every function is compiled with :data:`~shaketable.models.planar.physics.HELPER`'s options,
the error model :data:`~shaketable.models.rocking.physics.ERROR_MODEL` included.
"""

from __future__ import annotations

import math
from typing import Any

from numba import njit

from shaketable.core.constants import G
from shaketable.models.planar.physics import (
    HELPER,
    ROCK,
    block_angle,
    corner_vector,
    pivot_acceleration,
    rock_forces,
    slide_rock_accelerations,
)
from shaketable.models.rocking.physics import HALF_HEIGHT, HALF_WIDTH, HALF_WIDTH_MINUS
from shaketable.numerics import dop853

#: Components of the integrated state.
N_STATE = 6

#: Rows of the stage array: DOP853's 16 (:data:`shaketable.numerics.dop853.N_STAGES_EXTENDED`),
#: then the work arrays of :func:`dense_output` and :func:`locate` (no allocation inside
#: the engine's loop).
W_DENSE, W_TRIAL, W_VALUES = 16, 17, 18
STAGE_ROWS = 19

#: Event-function kinds for :func:`locate`; KIND_RATE + j (j = 0..4): the rate of the
#: slip (j = 0) or of a corner's X (j = 1..4, :func:`horizontal_rate`), for their extrema.
KIND_TERMINAL, KIND_PEAK, KIND_ALPHA, KIND_RATE = 0.0, 1.0, 2.0, 3.0
N_RATES = 5

#: numba options of the helpers called from one place only: inlined there by numba (a
#: function compiled apart costs a first compile of its own).
ONE_CALLER: Any = {"inline": "always", "error_model": HELPER["error_model"]}

#: Terminal events of the contact modes (indices of :func:`events`).
E_IMPACT, E_NORMAL, E_FRICTION, E_OVERTURN, E_MASS = 0, 1, 2, 3, 4
N_EVENTS = 5


@njit(**HELPER)
def ground(segment, time):
    """Horizontal and vertical table acceleration [m/s^2] at ``time`` (linear in the interval).

    ``segment``: start [s], length [s], ug at the start [m/s^2] and its change, vg and its
    change, then (for :func:`slopes_ground`) the slopes of ug and vg [m/s^3]."""
    fraction = (time - segment[0]) / segment[1]
    return segment[2] + segment[3] * fraction, segment[4] + segment[5] * fraction


@njit(**ONE_CALLER)
def slopes_ground(segment, time):
    """:func:`ground` from the slopes ``segment[6:8]`` [m/s^3] (no division: the
    right-hand side's; the rest and start rules keep :func:`ground`, the rocking engine's)."""
    elapsed = time - segment[0]
    return segment[2] + segment[6] * elapsed, segment[4] + segment[7] * elapsed


@njit(**HELPER)
def rhs(mode, side, sigma, mu_d, t, z, segment, parameters, out):
    """z' of ROCK or SLIDE_ROCK into ``out``."""
    ug, vg = slopes_ground(segment, t)
    theta = z[0]
    omega = z[1]
    velocity = z[3]
    r_x, r_y = corner_vector(theta, side, parameters)
    friction_power = 0.0
    if mode == ROCK:
        acceleration = pivot_acceleration(theta, side, ug, vg, parameters)
        corner_dd = 0.0
    else:
        acceleration, corner_dd, friction, _, _ = slide_rock_accelerations(
            theta, omega, side, sigma, mu_d, ug, vg, parameters)
        friction_power = friction * velocity
    x_dot = velocity + r_y * omega
    y_dot = -r_x * omega
    out[0] = omega
    out[1] = acceleration
    out[2] = velocity
    out[3] = corner_dd
    out[4] = -ug * x_dot - vg * y_dot
    out[5] = friction_power


@njit(inline="always", error_model=HELPER["error_model"])
def contact_rhs(t, z, out, args):
    """:func:`rhs` as :mod:`shaketable.numerics.dop853` calls it: ``args`` = (mode, side,
    sigma, mu_d, segment, parameters)."""
    mode, side, sigma, mu_d, segment, parameters = args
    rhs(mode, side, sigma, mu_d, t, z, segment, parameters, out)


@njit(**HELPER)
def dop853_step(mode, side, sigma, mu_d, t, z, k1, h, segment, parameters, stages, z_new,
                scale_abs, rtol):
    """One DOP853 step (:func:`shaketable.numerics.dop853.step`) of size ``h`` from (t, z)
    with z'(t) = ``k1``; z(t + h) into ``z_new``.

    Returns the error norm (<= 1: accepted) on the mixed absolute (``scale_abs``) /
    relative (``rtol``) scale. ``stages`` (STAGE_ROWS rows) receives the 12 stages; its
    row 15 is the work array (the continuous extension, :func:`dense_output`, fills rows
    12-15 after the step).
    """
    for i in range(N_STATE):
        stages[0, i] = k1[i]
    return dop853.step(contact_rhs, (mode, side, sigma, mu_d, segment, parameters), t, z, h,
                       stages, z_new, stages[15], scale_abs, rtol)


@njit(**HELPER)
def events(mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, out):
    """The terminal event functions of ROCK / SLIDE_ROCK at (t, z) into ``out``; each is
    positive while the mode holds: side theta (impact), N (lift-off), the friction margin
    mu_s N - |F| (ROCK) or the slip speed sigma X_s' (SLIDE_ROCK), pi/2 - side theta
    (overturn), the effective mass D (SLIDE_ROCK; Painleve)."""
    ug, vg = ground(segment, t)
    theta = z[0]
    omega = z[1]
    out[E_IMPACT] = side * theta
    out[E_OVERTURN] = 0.5 * math.pi - side * theta
    if mode == ROCK:
        _, _, _, friction, normal = rock_forces(theta, omega, side, ug, vg, parameters)
        out[E_NORMAL] = normal
        out[E_FRICTION] = min(mu_s * normal - friction, mu_s * normal + friction)
        out[E_MASS] = 1.0
    else:
        _, _, _, normal, d = slide_rock_accelerations(theta, omega, side, sigma, mu_d, ug, vg,
                                                      parameters)
        out[E_NORMAL] = normal if d > 0.0 else 0.0
        out[E_FRICTION] = sigma * z[3]
        out[E_MASS] = d


@njit(**HELPER)
def event_value(kind, mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, armed, sign,
                values):
    """The event function of ``kind`` at (t, z): positive before the event, <= 0 at and after.

    KIND_TERMINAL: the least of the armed terminal events (the first to fire);
    KIND_PEAK: sign * theta' (a turning point); KIND_ALPHA: alpha - |theta|.
    """
    if kind == KIND_PEAK:
        return sign * z[1]
    if kind == KIND_ALPHA:
        return block_angle(side, parameters) - abs(z[0])
    if kind >= KIND_RATE:
        _, r_y = corner_vector(z[0], side, parameters)
        return sign * horizontal_rate(int(kind - KIND_RATE), z[0], z[3] + r_y * z[1], z[1],
                                      parameters)
    events(mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, values)
    least = math.inf
    for i in range(N_EVENTS):
        if armed[i] and values[i] < least:
            least = values[i]
    return least


@njit(**HELPER)
def dense_output(mode, side, sigma, mu_d, t, z, z_end, h, segment, parameters, stages, dense):
    """DOP853's continuous extension of order 7 on the accepted step (t, z) -> (t + h,
    ``z_end``) into ``dense`` (7, N_STATE), for :func:`dense_state`
    (:func:`shaketable.numerics.dop853.dense_output`).

    ``stages`` (STAGE_ROWS rows) holds the step's 12 stages (:func:`dop853_step`); the
    extension adds z'(t + h) and three more stages; row W_DENSE is its work array.
    Returns the right-hand-side evaluations made (4).
    """
    rhs(mode, side, sigma, mu_d, t + h, z_end, segment, parameters, stages[12])
    dop853.dense_output(contact_rhs, (mode, side, sigma, mu_d, segment, parameters), t, z,
                        z_end, h, stages, dense, stages[W_DENSE])
    return 4


@njit(**ONE_CALLER)
def dense_state(dense, z, fraction, out):
    """The state at ``fraction`` (0..1) of the step from z on the continuous extension."""
    dop853.dense_state(dense, z, fraction, out)


@njit(**HELPER)
def locate(kind, mode, side, sigma, mu_s, mu_d, t, z, step, z_step, stages, dense, ready,
           upper, z_upper, armed, sign, segment, parameters, z_out):
    """First zero of an event function on (0, upper] of the accepted step (t, z) ->
    (t + ``step``, ``z_step``), on the step's continuous extension of order 7.

    The extension is built on the first call for the step (``ready[0]`` False; ``z_step``
    is read before ``z_out`` is written, so they may be the same array). The function is
    taken as positive at tau = 0 (an event armed at the step start, or one zero there by
    construction, e.g. theta = 0 when rocking begins) and is <= 0 at ``upper`` (state
    ``z_upper``). Trials on the extension: Newton's step where the impact event decides
    (its rate is side theta'), else Illinois regula falsi, and bisection when two trials
    did not halve the bracket, until the bracket is a few ulps of t wide. The state at
    the right end of the bracket (the event has happened) goes into ``z_out``.

    Returns tau and the right-hand-side evaluations made (4 if the extension was built).
    """
    evaluations = 0
    if not ready[0]:
        evaluations = dense_output(mode, side, sigma, mu_d, t, z, z_step, step, segment,
                                   parameters, stages, dense)
        ready[0] = True
    values = stages[W_VALUES]   # N_EVENTS <= N_STATE
    trial = stages[W_TRIAL]
    for i in range(N_STATE):
        z_out[i] = z_upper[i]
    a = 0.0
    b = upper
    gb = event_value(kind, mode, side, sigma, mu_s, mu_d, t + upper, z_upper, segment,
                     parameters, armed, sign, values)
    ga = event_value(kind, mode, side, sigma, mu_s, mu_d, t, z, segment, parameters, armed,
                     sign, values)
    known = ga > 0.0
    tolerance = 4e-16 * (abs(t) + upper) + 1e-300
    kept = 0
    # Newton on the impact event (its rate side * theta' is known) from the last trial,
    # else Illinois regula falsi; bisection whenever two trials did not halve the bracket
    newton = math.nan
    if kind == KIND_TERMINAL and gb == side * z_upper[0] and z_upper[1] != 0.0:
        newton = upper - gb / (side * z_upper[1])
    width_before = math.inf
    width_last = math.inf
    for _ in range(300):
        if b - a <= tolerance or gb == 0.0:
            break
        candidate = math.nan
        if newton == newton and a < newton < b:
            candidate = newton
        elif known and ga != gb:
            candidate = b - gb * (b - a) / (gb - ga)
        if not (a < candidate < b) or (b - a) > 0.5 * width_before:
            candidate = 0.5 * (a + b)
        width_before = width_last
        width_last = b - a
        dense_state(dense, z, candidate / step, trial)
        g = event_value(kind, mode, side, sigma, mu_s, mu_d, t + candidate, trial, segment,
                        parameters, armed, sign, values)
        newton = math.nan
        if kind == KIND_TERMINAL and g == side * trial[0] and trial[1] != 0.0:
            newton = candidate - g / (side * trial[1])
        if g > 0.0:
            a = candidate
            ga = g
            known = True
            if kept == 1:
                gb *= 0.5
            kept = 1
        else:
            b = candidate
            gb = g
            for i in range(N_STATE):
                z_out[i] = trial[i]
            if kept == -1:
                ga *= 0.5
            kept = -1
    return b, evaluations


@njit(**HELPER)
def terminal_event(mode, side, sigma, mu_s, mu_d, t, z, step, z_new, stages, dense, ready,
                   segment, parameters, armed, g_end, z_event, z_turn, no_events):
    """The first of the ``armed`` terminal events in the accepted contact step (t, z) ->
    (t + ``step``, ``z_new``), or an impact passed inside it (theta turned back away from 0
    on the far side of 0), located by :func:`locate`.

    Returns (the event's index, -1 if none; tau [s]; right-hand-side evaluations made). On
    an event, ``z_new`` becomes the state at t + tau; ``g_end`` holds the event functions
    at t + tau; ``z_event`` and ``z_turn`` are work arrays, ``no_events`` all False.
    """
    evaluations = 0
    events(mode, side, sigma, mu_s, mu_d, t + step, z_new, segment, parameters,
           g_end)
    tau = step
    upper = step
    for i in range(N_STATE):
        z_event[i] = z_new[i]
    fire = False
    for i in range(N_EVENTS):
        if armed[i] and g_end[i] <= 0.0:
            fire = True
    if not fire and side * z[1] < 0.0 and side * z_new[1] > 0.0:
        # theta turned back away from 0 inside the step: did it pass 0?
        tau_turn, used = locate(KIND_PEAK, mode, side, sigma, mu_s, mu_d, t, z,
                                step, z_new, stages, dense, ready, step, z_new,
                                no_events, -side, segment, parameters, z_turn)
        evaluations += used
        if side * z_turn[0] <= 0.0:
            fire = True
            upper = tau_turn
            for i in range(N_STATE):
                z_event[i] = z_turn[i]
    terminal = -1
    if fire:
        armed[E_IMPACT] = True
        tau, used = locate(KIND_TERMINAL, mode, side, sigma, mu_s, mu_d, t, z,
                           step, z_new, stages, dense, ready, upper, z_event,
                           armed, 0.0, segment, parameters, z_new)
        evaluations += used
        events(mode, side, sigma, mu_s, mu_d, t + tau, z_new, segment,
               parameters, g_end)
        least = math.inf
        for i in range(N_EVENTS):
            if armed[i] and g_end[i] < least:
                least = g_end[i]
                terminal = i
    return terminal, tau, evaluations


@njit(**HELPER)
def polynomial_work(p0, p1, q0, q1, q2, span):
    """Integral over [0, span] of (p0 + p1 tau)(q0 + q1 tau + q2 tau^2)."""
    return (p0 * q0 * span + (p0 * q1 + p1 * q0) * span ** 2 / 2.0
            + (p0 * q2 + p1 * q1) * span ** 3 / 3.0 + p1 * q2 * span ** 4 / 4.0)


@njit(**HELPER)
def flight_state(tau, x, y, theta, x_dot, y_dot, omega, ua, ka, va, kv):
    """Ballistic state after ``tau`` [s] (x'' = -ug, y'' = -(g + vg), theta'' = 0, the table
    accelerations ua + ka tau, va + kv tau)."""
    gravity = G + va
    return (x + x_dot * tau - ua * tau * tau / 2.0 - ka * tau ** 3 / 6.0,
            y + y_dot * tau - gravity * tau * tau / 2.0 - kv * tau ** 3 / 6.0,
            theta + omega * tau,
            x_dot - ua * tau - ka * tau * tau / 2.0,
            y_dot - gravity * tau - kv * tau * tau / 2.0,
            omega)


@njit(**HELPER)
def lowest_corner(y, theta, parameters):
    """Height of the lower bottom corner [m] and its side."""
    h = parameters[HALF_HEIGHT]
    sine = math.sin(theta)
    cosine = math.cos(theta)
    plus = y - parameters[HALF_WIDTH] * sine - h * cosine
    minus = y + parameters[HALF_WIDTH_MINUS] * sine - h * cosine
    if plus <= minus:
        return plus, 1.0
    return minus, -1.0


@njit(**HELPER)
def horizontal_rate(which, theta, x_dot, omega, parameters):
    """d/dt of the slip of the base's midpoint (``which`` 0) or of the X of a corner
    (1..4: body points (-b, -h), (b, -h), (-b, h), (b, h)) [m/s]: zero at their extrema."""
    return horizontal_rate_at(which, math.cos(theta), math.sin(theta), x_dot, omega,
                              parameters)


@njit(**HELPER)
def horizontal_rate_at(which, cosine, sine, x_dot, omega, parameters):
    """:func:`horizontal_rate` with cos(theta) and sin(theta) given."""
    h = parameters[HALF_HEIGHT]
    if which == 0:
        return x_dot + h * cosine * omega
    u = -parameters[HALF_WIDTH] if which == 1 or which == 3 else parameters[HALF_WIDTH_MINUS]
    w = -h if which <= 2 else h
    return x_dot - omega * (u * sine + w * cosine)
