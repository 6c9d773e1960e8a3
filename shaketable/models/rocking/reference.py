"""High-accuracy reference solver: SciPy's DOP853 with event location.

An implementation independent of :mod:`shaketable.models.rocking.engine` (different
integrator, different root finder: SciPy's ``solve_ivp`` events and Brent's
method) used as the yardstick for the other methods and in the tests. It shares
only the physics (:mod:`shaketable.models.rocking.physics`) and the event rules.

It integrates each input interval separately, one corner's equation
continued smoothly past theta = 0 during a flight (like the engine; the
impact is where that solution reaches zero), (the ground acceleration is linear
inside one, so the right-hand side is smooth) with ``rtol`` and an absolute
tolerance scaled by alpha, and is slow: one ``solve_ivp`` call per interval.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from shaketable.core.constants import G
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
    HOLD_DOWN,
    angular_acceleration,
    cascade_rest_time,
    flight_acceleration,
)


def _passed_impact(solution, side, t_segment):
    """The impact a step passed without seeing it, as ``(time, omega)``, else None.

    ``solve_ivp`` tests the sign of an event function at step ends only: a dip of
    theta below zero (on the active corner's side, ``side * theta < 0``) that begins
    and ends inside one step is invisible to the impact event. Its turning point is
    not: theta' changes sign once there, and the peak event finds it. A turning point
    on the wrong side of theta = 0 therefore means the block hit the table before it;
    the impact is the first zero of ``side * theta`` before that turning point, found
    on the step's dense output (Brent's method). Turning points after a terminal
    event (an impact seen, or an overturn) are not considered.
    """
    t_last = float(solution.t[-1])
    for time, y in zip(solution.t_events[2], solution.y_events[2]):
        if time >= t_last and solution.status == 1:
            break
        if side * y[0] >= 0.0:
            continue
        # the last accepted step time before the turning point: theta is on the
        # active side there (else the impact event would have stopped the segment)
        steps = solution.t[solution.t < time]
        low = float(steps[-1]) if steps.size else t_segment
        theta_of = lambda s: side * float(solution.sol(s)[0])  # noqa: E731
        if theta_of(low) <= 0.0:  # the segment began at theta = 0 (a start of rocking)
            low = float(np.nextafter(low, time))
            if theta_of(low) <= 0.0:
                return low, float(solution.sol(low)[1])
        t_impact = brentq(theta_of, low, float(time), xtol=1e-15, rtol=4 * np.finfo(float).eps,
                          maxiter=200)
        return t_impact, float(solution.sol(t_impact)[1])
    return None


def _pivots(parameters, alpha, cor, sides):
    """(parameters, alpha, COR of an impact onto it) of a pivot, as functions of its side.

    ``sides`` None: the symmetric block's one set for both; else ``(rows, cors)``.
    """
    if sides is None:
        return (lambda side: parameters), (lambda side: alpha), (lambda side: cor)
    rows, cors = sides

    def par(side):
        return rows[0] if side > 0 else rows[1]

    return (par, (lambda side: float(par(side)[ALPHA])),
            (lambda side: float(cors[0] if side > 0 else cors[1])))


class ReferenceSolverError(RuntimeError):
    """SciPy's integrator gave up, or the event loop stopped advancing in time.

    The second happens only for degenerate input (an input interval near the
    spacing of floating-point numbers, or an acceleration so large that the
    block starts and impacts again at the same instant); :class:`Motion`
    refuses most such input before it gets here.
    """


#: Consecutive segments (rocking start, flight, impact) that may end at the
#: instant they began before the reference solver gives up: a real start of
#: rocking followed by an immediate impact happens once or twice, not 100 times.
MAX_STALLED_SEGMENTS = 100

#: Segments (solve_ivp calls) allowed inside one input interval.
MAX_SEGMENTS_PER_INTERVAL = 100_000


def _start_of_rocking(t, t_end, ground, par):
    """When a block at rest at ``t`` starts rocking before ``t_end`` [s], and onto which corner.

    The margin s theta''(theta = 0) of Eq. (2-1) is affine in time inside an input interval:
    the first corner s whose margin turns positive, at the first time it is strictly
    positive. ``ground(time)`` gives the ground accelerations, ``par(s)`` the parameters
    of corner s. Returns (time [s], s), or (``t_end``, 0) when the block stays at rest.
    """
    start, start_side = math.inf, 0.0
    for s in (1.0, -1.0):
        margin_a = s * angular_acceleration(0.0, s, *ground(t), par(s))
        margin_b = s * angular_acceleration(0.0, s, *ground(t_end), par(s))
        if margin_a > 0:
            candidate = t
        elif margin_b > 0:
            candidate = t + (t_end - t) * (-margin_a) / (margin_b - margin_a)
        else:
            continue
        if candidate < start:
            start, start_side = candidate, s
    if start_side == 0.0:
        return t_end, 0.0
    # at the interpolated crossing the margin is zero to rounding: begin where it is
    # strictly positive (else the flight "impacts" at once and the block rests and
    # restarts at the same instant forever; engine: same rule)
    low, high = start, t_end
    if start_side * angular_acceleration(0.0, start_side, *ground(start),
                                         par(start_side)) <= 0.0:
        for _ in range(200):
            middle = 0.5 * (low + high)
            if middle <= low or middle >= high:
                break
            if start_side * angular_acceleration(0.0, start_side, *ground(middle),
                                                 par(start_side)) > 0.0:
                high = middle
            else:
                low = middle
        start = high
    return start, start_side


def _flight(ground, t, t_end, theta, omega, side, active, active_alpha, rtol, atol):
    """One flight about the corner ``side`` from ``t`` [s] to at most ``t_end`` [s].

    SciPy's DOP853 from theta [rad], theta' [rad/s] with the events impact and overturn
    (terminal), turning point and instability (``solution.t_events`` in this order);
    ``active`` are the corner's parameters, ``active_alpha`` its angle [rad].
    """
    t_segment = t
    from_zero = theta == 0.0

    def rhs(time, y):
        # the active corner's equation continued past theta = 0 (smooth), as in
        # the engine: Eq. 2-13's switch of corner there is a jump in theta''
        # that made DOP853 give up at the impact
        return [y[1], flight_acceleration(y[0], side, *ground(time), active)]

    def impact(time, y):
        if from_zero:
            elapsed = time - t_segment
            return side * y[1] if elapsed <= 0 else side * y[0] / elapsed
        return side * y[0]
    impact.terminal, impact.direction = True, -1

    def overturn(time, y):
        return 0.5 * math.pi - side * y[0]
    overturn.terminal, overturn.direction = True, -1

    def peak(time, y):
        return y[1]
    peak.terminal, peak.direction = False, 0

    def unstable(time, y):
        return active_alpha - abs(y[0])
    unstable.terminal, unstable.direction = False, -1

    solution = solve_ivp(rhs, (t, t_end), [theta, omega], method="DOP853", rtol=rtol,
                         atol=atol, events=[impact, overturn, peak, unstable],
                         first_step=None, dense_output=True)
    if solution.status == -1:
        raise ReferenceSolverError(
            f"reference solver (DOP853, rtol {rtol:g}) failed at t = {solution.t[-1]!r} s "
            f"(theta = {solution.y[0, -1]!r} rad): {solution.message}")
    return solution


def _record_peaks(solution, t_impact, side, info):
    """Updates ``info`` with a flight's turning points up to ``t_impact`` [s] (the largest
    |theta| so far) and its first instability, if before ``t_impact``."""
    for time, y in zip(solution.t_events[2], solution.y_events[2]):
        if time > t_impact:
            break
        if abs(y[0]) > info[INFO_MAX_ABS_THETA]:
            info[INFO_MAX_ABS_THETA], info[INFO_T_MAX], info[INFO_THETA_AT_MAX] = \
                abs(y[0]), time, y[0]
    if math.isnan(info[INFO_T_UNSTABLE]) and len(solution.t_events[3]) and (
            solution.t_events[3][0] <= t_impact):
        info[INFO_T_UNSTABLE] = solution.t_events[3][0]
        info[INFO_UNSTABLE_DIRECTION] = side


def _rest_after_impact(omega, deceleration, landing, rest_tolerance, velocity_floor):
    """The time a block takes to rest after an impact [s], else -1 (the engine's rule).

    ``omega`` is theta' just after the impact [rad/s], ``deceleration`` the magnitude of
    theta'' at theta = 0 on the new corner [rad/s^2], ``landing`` the impact's COR [-]: the
    cascade of impacts that follows is summed in closed form
    (:func:`~shaketable.models.rocking.physics.cascade_rest_time`).
    """
    remaining = cascade_rest_time(omega, deceleration, landing)
    if (remaining == math.inf and landing >= 1.0 and deceleration > 0.0
            and abs(omega) <= velocity_floor):
        remaining = 0.0  # COR = 1 bounces at the noise level: at rest (engine)
    if omega == 0.0 or remaining <= rest_tolerance or (
            abs(omega) <= velocity_floor and remaining < math.inf):
        return 0.0 if omega == 0.0 else remaining
    return -1.0


def integrate_reference(t_grid, ug, vg, rg, parameters, alpha, p, cor, theta0, omega0, rtol,
                        rest_tolerance, out_theta, out_omega, out_acceleration, impact_times,
                        impact_velocities, info, sides=None):
    """Same contract as :func:`shaketable.models.rocking.engine.integrate` (METHOD_FAST).

    ``sides``: an asymmetric block (:mod:`shaketable.models.rocking.asymmetric`), as
    ``(rows, cors)``: the two rows of :func:`~shaketable.models.rocking.physics.side_parameters`
    (theta > 0, theta < 0) and the CORs of an impact landing on each pivot; ``alpha``
    and ``p`` are then the smaller angle and the larger p (the tolerances), ``cor`` and
    ``parameters`` unused. ``None``: the symmetric block, every number as before.
    """
    par, alpha_of, cor_onto = _pivots(parameters, alpha, cor, sides)
    parameters = par(1.0)
    atol = np.array([rtol * alpha, rtol * alpha * p]) * 1e-2
    if rest_tolerance < 0:
        rest_tolerance = 1e-6 / p
    velocity_floor = 1e3 * atol[1]
    hold_down = parameters[HOLD_DOWN]
    info[:] = math.nan
    info[INFO_MAX_ABS_THETA] = abs(theta0)
    info[INFO_T_MAX] = t_grid[0]
    info[INFO_THETA_AT_MAX] = theta0
    counts = {"steps": 0, "evaluations": 0, "impacts": 0, "cascades": 0}
    status = STATUS_COMPLETED
    theta, omega = float(theta0), float(omega0)
    resting = theta == 0.0 and omega == 0.0
    side = -1.0 if theta < 0.0 or (theta == 0.0 and omega < 0.0) else 1.0
    if not resting:
        info[INFO_T_START] = t_grid[0]
    if abs(theta) > alpha:
        info[INFO_T_UNSTABLE] = t_grid[0]
        info[INFO_UNSTABLE_DIRECTION] = side
    t = float(t_grid[0])
    rest_until = t
    out_theta[0], out_omega[0] = theta, omega
    out_acceleration[0] = 0.0 if resting else angular_acceleration(theta, side, ug[0], vg[0],
                                                                   rg[0], par(side))
    filled = 1
    max_recorded = len(impact_times)

    for k in range(len(t_grid) - 1):
        t0, t1 = float(t_grid[k]), float(t_grid[k + 1])
        u0, u1, v0, v1, r0, r1 = ug[k], ug[k + 1], vg[k], vg[k + 1], rg[k], rg[k + 1]

        def ground(time):
            fraction = (time - t0) / (t1 - t0)
            return (u0 + (u1 - u0) * fraction, v0 + (v1 - v0) * fraction,
                    r0 + (r1 - r0) * fraction)

        support_0, support_1 = G + v0 + hold_down, G + v1 + hold_down
        t_end, airborne = t1, False
        if support_0 <= 0:
            t_end, airborne = t0, True
        elif support_1 <= 0:
            t_end, airborne = t0 + (t1 - t0) * support_0 / (support_0 - support_1), True

        stalled = segments = 0
        while t < t_end:
            segments += 1
            if segments > MAX_SEGMENTS_PER_INTERVAL:
                raise ReferenceSolverError(
                    f"reference solver: more than {MAX_SEGMENTS_PER_INTERVAL} segments in the "
                    f"input interval [{t0!r}, {t1!r}] s (at t = {t!r} s); the input is "
                    "degenerate (interval too short or acceleration too large?)")
            if resting:
                if rest_until >= t_end:
                    t = t_end
                    break
                t, start_side = _start_of_rocking(max(t, rest_until), t_end, ground, par)
                if start_side == 0.0:
                    break
                side, theta, omega, resting = start_side, 0.0, 0.0, False
                if math.isnan(info[INFO_T_START]):
                    info[INFO_T_START] = t
                continue

            active_side = side
            solution = _flight(ground, t, t_end, theta, omega, side, par(side), alpha_of(side),
                               rtol, atol)
            counts["steps"] += len(solution.t) - 1
            counts["evaluations"] += solution.nfev
            passed = _passed_impact(solution, active_side, t)
            if passed is not None:
                # theta dipped past zero and back inside one step: the sign test at step
                # ends cannot see it, but the turning point on the wrong side can
                t_impact, omega_impact = passed
            _record_peaks(solution, t_impact if passed is not None else math.inf, active_side,
                          info)
            end_time = t_impact if passed is not None else float(solution.t[-1])
            stalled = stalled + 1 if end_time <= t else 0
            if stalled > MAX_STALLED_SEGMENTS:
                raise ReferenceSolverError(
                    f"reference solver made no progress at t = {t!r} s in the input interval "
                    f"[{t0!r}, {t1!r}] s ({t1 - t0!r} s long): {MAX_STALLED_SEGMENTS} "
                    "consecutive segments ended where they began; the input is degenerate "
                    "(interval too short or acceleration too large?)")
            if passed is not None:
                t, theta, omega = t_impact, 0.0, omega_impact
            else:
                t = float(solution.t[-1])
                theta, omega = float(solution.y[0, -1]), float(solution.y[1, -1])
            if abs(theta) > info[INFO_MAX_ABS_THETA]:
                info[INFO_MAX_ABS_THETA], info[INFO_T_MAX], info[INFO_THETA_AT_MAX] = \
                    abs(theta), t, theta
            if passed is not None or solution.status == 1:  # an impact or overturn
                if passed is None and len(solution.t_events[1]):
                    status = STATUS_OVERTURNED
                    info[INFO_T_OVERTURN] = t
                    info[INFO_OVERTURN_DIRECTION] = active_side
                    theta = active_side * 0.5 * math.pi
                    break
                if counts["impacts"] < max_recorded:
                    impact_times[counts["impacts"]] = t
                    impact_velocities[counts["impacts"]] = omega
                counts["impacts"] += 1
                side = -active_side
                landing = cor_onto(side)
                omega *= landing
                theta = 0.0
                remaining = _rest_after_impact(
                    omega, -side * angular_acceleration(0.0, side, *ground(t), par(side)),
                    landing, rest_tolerance, velocity_floor)
                if remaining >= 0.0:
                    if omega != 0.0:
                        counts["cascades"] += 1
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
        out_theta[k + 1], out_omega[k + 1] = theta, omega
        out_acceleration[k + 1] = 0.0 if resting else angular_acceleration(
            theta, side, u1, v1, r1, par(side))
        filled = k + 2

    _finish(info, t, theta, omega, counts, status, filled)


def _finish(info, t, theta, omega, counts, status, filled):
    """Writes the final state [s, rad, rad/s], the run's counts and its status into ``info``."""
    info[INFO_T_END], info[INFO_THETA_END], info[INFO_THETA_DOT_END] = t, theta, omega
    info[INFO_STEPS] = counts["steps"]
    info[INFO_EVALUATIONS] = counts["evaluations"]
    info[INFO_REJECTED] = 0
    info[INFO_CASCADES] = counts["cascades"]
    info[INFO_STATUS] = status
    info[INFO_N_IMPACTS] = counts["impacts"]
    info[INFO_N_OUTPUT] = filled
    assert len(info) == N_INFO
