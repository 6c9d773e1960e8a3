"""Events inside one step of the rocking engine, located on the stepper itself.

An impact (theta = 0), an overturn (|theta| = pi/2), the turning points (theta' = 0) and the
first instability (|theta| = alpha) of a step of free flight from ``t`` to ``t + h``
(:func:`step_events`), each located by a safeguarded Newton iteration whose trials are
steps of the method's stepper from ``t`` (:func:`locate`), so that an event time is as
accurate as the integration; an impact hidden inside a step, theta dipping below 0 between
two turning points, is found by :func:`dip_on_stepper`.

``advance`` is the method's stepper: :func:`shaketable.models.rocking.engine._integrator` compiles
a copy of :func:`locate`, :func:`dip_on_stepper` and :func:`step_events` for each method,
with the method's function bound to that name (:data:`METHOD_HELPERS`).
"""

from __future__ import annotations

import math

from numba import int64

from shaketable.models.rocking.layout import (
    EVENT_IMPACT,
    EVENT_OVERTURN,
    EVENT_PEAK,
    EVENT_UNSTABLE,
    INFO_MAX_ABS_THETA,
    INFO_T_MAX,
    INFO_T_UNSTABLE,
    INFO_THETA_AT_MAX,
    INFO_UNSTABLE_DIRECTION,
)
from shaketable.models.rocking.physics import ALPHA
from shaketable.models.rocking.steppers import helper


def bound_per_method(*arguments):
    """Stands for the method's function each integrator binds to this name
    (:func:`shaketable.models.rocking.engine._integrator`).

    Not compiled: a helper that calls one of these names without being compiled for a
    method fails numba's typing instead of calling another method's one.
    """
    raise NotImplementedError("bound to the method's function by engine._integrator")


advance = bound_per_method

#: The functions of this module that call the method's stepper: each integrator compiles
#: its own copies.
METHOD_HELPERS = ("locate", "dip_on_stepper", "step_events")


@helper
def event(kind, x, v, a, side, sign, alpha):
    """Event function (positive before the event, <= 0 at and after it) and its rate."""
    if kind == EVENT_IMPACT:
        return side * x, side * v
    if kind == EVENT_OVERTURN:
        return 0.5 * math.pi - side * x, -side * v
    if kind == EVENT_PEAK:
        return sign * v, sign * a
    if x >= 0.0:
        return alpha - x, -v
    return alpha + x, v


def locate(kind, t, theta, omega, acceleration, side, upper, x_upper, v_upper,
            a_upper, segment, parameters, sign):
    """First root of an event function on (0, upper], by a safeguarded Newton iteration.

    The event function is positive at 0 (by construction: for an impact from
    theta = 0 it is positive just after 0) and ``<= 0`` at ``upper``, where the
    state (``x_upper``, ``v_upper``, ``a_upper``) is known. Each trial is one
    step of the stepper from ``t`` to ``t + tau``; the event function's rate
    comes from the same step (theta' for theta events, theta'' for theta'), so
    Newton converges in a few trials; a trial outside the bracket, or one that
    does not halve the step, is replaced by bisection.

    Returns tau, theta, theta', theta'' there and the number of trial steps.
    """
    alpha = parameters[ALPHA]
    a = 0.0
    b = upper
    c = upper
    xc, vc, ac = x_upper, v_upper, a_upper
    xb, vb, ab = x_upper, v_upper, a_upper
    gc, dgc = event(kind, xc, vc, ac, side, sign, alpha)
    if gc > 0.0:
        return upper, xc, vc, ac, 0
    tolerance = 2e-16 * (abs(t) + upper) + 1e-300
    previous = math.inf
    trials = int64(0)  # not a literal 0: see _drive
    for _ in range(100):
        newton = math.inf if dgc == 0.0 else gc / dgc
        candidate = c - newton
        if not (a < candidate < b) or abs(2.0 * newton) > previous:
            candidate = 0.5 * (a + b)
        change = abs(candidate - c)
        if abs(newton) <= tolerance:
            break  # c is the root to within rounding
        previous = change
        x, v, acc, _, _ = advance(t, theta, omega, acceleration, side, candidate, segment,
                                  parameters)
        trials += 1
        g, dg = event(kind, x, v, acc, side, sign, alpha)
        c, xc, vc, ac, gc, dgc = candidate, x, v, acc, g, dg
        if g > 0.0:
            a = candidate
        else:
            b, xb, vb, ab = candidate, x, v, acc
        if b - a <= tolerance:
            c, xc, vc, ac = b, xb, vb, ab
            break
    return c, xc, vc, ac, trials


def dip_on_stepper(t, theta, omega, acceleration, side, h, theta_new, omega_new,
                    threshold, first_only, segment, parameters):
    """A time in (0, h) at which the stepper's own solution is at or past theta = 0.

    Called for a step whose ends have theta on the active side and theta' of
    one sign, which no sign test flags (with ``first_only``: a step that ends
    past 0, whose theta' kept one sign). First, where the step may hide a dip:
    the cubic Hermite interpolant of theta, theta' at both ends (exact when
    theta'' is linear in time, as the ground acceleration is inside an input
    interval, up to the p^2 theta term) is searched for two interior turning
    points, and its minimum of side * theta counts when it is at or below
    ``threshold`` (checked next on the stepper itself, so a generous margin
    costs only evaluations). With ``first_only`` (the end is already below 0),
    only a minimum before the maximum counts: a crossing earlier than the one
    seen. Then, from the interpolant's minimum, Newton's iteration on
    theta' = 0 (one step of the stepper from ``t`` per trial, as
    :func:`locate`) goes towards the stepper's turning point.

    Returns that time (0 when none is found), theta, theta', theta'' there and
    the number of trials.
    """
    x = v = acc = 0.0
    trials = int64(0)  # not a literal 0: see _drive
    # where the cubic Hermite interpolant may hide a dip
    x0 = side * theta
    x1 = side * theta_new
    v0 = side * omega * h
    v1 = side * omega_new * h
    c2 = 3.0 * (x1 - x0) - 2.0 * v0 - v1
    c3 = 2.0 * (x0 - x1) + v0 + v1
    if c3 == 0.0:
        # H' linear: no two interior roots with ends of one sign
        return 0.0, x, v, acc, trials
    discriminant = c2 * c2 - 3.0 * c3 * v0
    if discriminant <= 0.0:
        return 0.0, x, v, acc, trials
    root = math.sqrt(discriminant)
    s1 = (-c2 - root) / (3.0 * c3)
    s2 = (-c2 + root) / (3.0 * c3)
    if not ((0.0 < s1) & (s1 < 1.0) & (0.0 < s2) & (s2 < 1.0)):
        return 0.0, x, v, acc, trials
    s = s1 if 2.0 * c2 + 6.0 * c3 * s1 > 0.0 else s2  # the minimum of side * theta
    # s > min(s1, s2), as numba's min() computes it: min() here would be compiled once more
    if first_only > 0.0 and s > (s2 if s2 < s1 else s1):
        # theta_new < 0: only a minimum before the maximum hides a crossing
        return 0.0, x, v, acc, trials
    lowest = x0 + s * (v0 + s * (c2 + s * c3))
    if lowest > threshold:
        return 0.0, x, v, acc, trials
    tau = s * h
    if tau <= 0.0:
        return 0.0, x, v, acc, trials
    for _ in range(12):
        x, v, acc, _, _ = advance(t, theta, omega, acceleration, side, tau, segment,
                                  parameters)
        trials += 1
        if side * x <= 0.0:
            return tau, x, v, acc, trials
        if side * acc <= 0.0:
            break  # not near a minimum of side * theta
        following = tau - v / acc
        if not (0.0 < following < h) or abs(following - tau) <= 1e-14 * h:
            break
        tau = following
    return 0.0, x, v, acc, trials


def step_events(t, theta, omega, acceleration, side, h, theta_new, omega_new,
                 acceleration_new, segment, parameters, info):
    """The events inside a step of free flight from ``t`` to ``t + h``.

    The step's end (``theta_new``, ``omega_new``, ``acceleration_new``) is known.

    - Terminal events, where the step ends early: an impact where theta reached 0 (also
      inside the step: a turning point past 0 after touching it, or a dip between two
      turning points, :func:`dip_on_stepper`), and an overturn where |theta| reached
      pi/2.
    - Non-terminal events, recorded in ``info``: the turning point (theta' changes sign
      away from 0), which with the step's end updates the largest |theta| so far
      (``INFO_MAX_ABS_THETA``, ``INFO_T_MAX``, ``INFO_THETA_AT_MAX``), and the first
      time |theta| passes alpha (``INFO_T_UNSTABLE``, ``INFO_UNSTABLE_DIRECTION``).

    Each is located on the stepper (:func:`locate`).

    Returns
    -------
    tau : float
        Where the step ends [s after ``t``]: ``h``, or the terminal event.
    kind : float
        EVENT_IMPACT, EVENT_OVERTURN, or -1 (no terminal event).
    theta, omega, acceleration : float
        The state there [rad, rad/s, rad/s^2]: theta is exactly 0 at an impact and
        side * pi / 2 at an overturn.
    located : int
        Trial steps made to locate the events.
    """
    tau = h
    kind = -1.0
    located = int64(0)  # trial steps of event location (not a literal 0: see engine._drive)
    # an impact is located (once, below) in (0, upper], with the state there x, v, acc
    impact = False
    upper, x, v, acc = h, theta_new, omega_new, acceleration_new
    if (side * omega < 0.0) & (side * omega_new > 0.0) & (side * theta_new > 0.0):
        # theta turned back away from 0 inside the step: did it touch 0 first?
        sign = 1.0 if omega > 0.0 else -1.0
        upper, x, v, acc, trials = locate(
            EVENT_PEAK, t, theta, omega, acceleration, side, h, theta_new,
            omega_new, acceleration_new, segment, parameters, sign)
        located += trials
        impact = side * x <= 0.0
    elif (side * theta_new < 0.0) | ((side * theta_new == 0.0) & (side * omega_new < 0.0)):
        impact = True
        if (side * omega < 0.0) & (side * omega_new < 0.0):
            # theta may have crossed 0 three times (down, up at a turning point
            # below 0, down again): bracket the first crossing
            found, xd, vd, ad, trials = dip_on_stepper(
                t, theta, omega, acceleration, side, h, theta_new, omega_new,
                0.5 * side * theta, 1.0, segment, parameters)
            located += trials
            if found > 0.0:
                upper, x, v, acc = found, xd, vd, ad
    elif (omega * omega_new > 0.0) & (side * theta_new > 0.0):
        # theta' has the same sign at both ends, but it may have changed sign
        # twice inside the step (the ground acceleration ramps fast enough):
        # a dip below 0 between two turning points that no sign test sees
        lower = side * theta_new if side * theta_new < side * theta else side * theta  # min()
        found, xd, vd, ad, trials = dip_on_stepper(
            t, theta, omega, acceleration, side, h, theta_new, omega_new, 0.5 * lower, 0.0,
            segment, parameters)
        located += trials
        if found > 0.0:
            impact = True
            upper, x, v, acc = found, xd, vd, ad
    if impact:
        tau, theta_new, omega_new, acceleration_new, trials = locate(
            EVENT_IMPACT, t, theta, omega, acceleration, side, upper, x, v, acc, segment,
            parameters, 0.0)
        located += trials
        kind = EVENT_IMPACT
    if side * theta_new >= 0.5 * math.pi:
        tau, theta_new, omega_new, acceleration_new, trials = locate(
            EVENT_OVERTURN, t, theta, omega, acceleration, side, tau, theta_new,
            omega_new, acceleration_new, segment, parameters, 0.0)
        located += trials
        kind = EVENT_OVERTURN
    if kind == EVENT_IMPACT:
        theta_new = 0.0
    elif kind == EVENT_OVERTURN:
        theta_new = side * 0.5 * math.pi

    # non-terminal events: the turning point (max |theta|) and the first instability
    alpha = parameters[ALPHA]
    tau_peak = tau
    theta_peak = theta_new
    v_peak = omega_new
    acceleration_peak = acceleration_new
    if (omega * omega_new < 0.0) & (side * omega > 0.0):
        sign = 1.0 if omega > 0.0 else -1.0
        tau_peak, theta_peak, v_peak, acceleration_peak, trials = locate(
            EVENT_PEAK, t, theta, omega, acceleration, side, tau, theta_new,
            omega_new, acceleration_new, segment, parameters, sign)
        located += trials
        if abs(theta_peak) > info[INFO_MAX_ABS_THETA]:
            info[INFO_MAX_ABS_THETA] = abs(theta_peak)
            info[INFO_T_MAX] = t + tau_peak
            info[INFO_THETA_AT_MAX] = theta_peak
    if abs(theta_new) > info[INFO_MAX_ABS_THETA]:
        info[INFO_MAX_ABS_THETA] = abs(theta_new)
        info[INFO_T_MAX] = t + tau
        info[INFO_THETA_AT_MAX] = theta_new
    if math.isnan(info[INFO_T_UNSTABLE]):
        if (abs(theta_peak) > alpha) | (abs(theta_new) > alpha):
            if abs(theta_peak) > alpha:
                upper, x, v, acc = tau_peak, theta_peak, v_peak, acceleration_peak
            else:
                upper, x, v, acc = tau, theta_new, omega_new, acceleration_new
            tau_unstable, x, v, acc, trials = locate(
                EVENT_UNSTABLE, t, theta, omega, acceleration, side, upper, x, v,
                acc, segment, parameters, 0.0)
            located += trials
            info[INFO_T_UNSTABLE] = t + tau_unstable
            info[INFO_UNSTABLE_DIRECTION] = side
    return tau, kind, theta_new, omega_new, acceleration_new, located
