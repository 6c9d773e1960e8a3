"""The stack's one-DOF patterns integrated as a single rocking block (numba).

A pattern with one open interface is one rigid body rocking about a corner on a base that
moves with the table (:mod:`shaketable.models.stack.compiled_rigid`): the single-block
engine's method integrates it (:mod:`shaketable.models.rocking.engine`: the
Runge-Kutta-Nystrom pair RKN6(4) of :func:`~shaketable.models.rocking.steppers.nystrom_step`,
one step per input interval while its error allows, the engine's PI step-size control, and
its event location on the stepper, :func:`~shaketable.models.rocking.events.step_events`,
for the landing and the overturn). The stack's own event, the normal force at a seated
corner reaching zero (the uplift that starts the next pattern), is found at the ends of the
accepted steps, as the DOP853 path finds it, and located on the stepper by a bracketed
secant iteration (Illinois). The table's work over a segment is the rocking body's energy
change (no impact inside a segment: the work of the table's inertial forces is the change of
kinetic plus potential energy, Eq. (2-13)'s first integral).
"""

from __future__ import annotations

import math
import types

import numpy as np

from shaketable.core.constants import G
from shaketable.models.rocking import engine as rocking_engine
from shaketable.models.rocking import events as rocking_events
from shaketable.models.rocking.engine import step_size_control
from shaketable.models.rocking.layout import (
    INFO_MAX_ABS_THETA,
    INFO_T_UNSTABLE,
    METHOD_FAST,
    N_INFO,
)
from shaketable.models.rocking.steppers import (
    METHOD_FUNCTIONS,
    flight_acceleration,
    helper,
    nystrom_step,
)
from shaketable.models.rocking.steppers import ground as table_ground
from shaketable.models.stack.compiled_events import record
from shaketable.models.stack.compiled_physics import energy, inlined, kernel
from shaketable.models.stack.compiled_rigid import (
    B_ALPHA,
    B_HALF_WIDTH,
    B_HEIGHT,
    B_INERTIA_PER_MASS,
    N_BODY,
    N_COLUMNS,
    rigid_acceleration,
    rigid_coefficients,
    rigid_energy,
    rigid_forces,
)
from shaketable.models.stack.compiled_steps import EPS, ground
from shaketable.models.stack.layout import (
    ENDS_IMPACT,
    ENDS_LIFT,
    ENDS_NONE,
    ENDS_OVERTURN,
    F_ENERGY,
    F_ENERGY_OMEGA,
    F_ENERGY_SIDE,
    F_ENERGY_THETA,
    F_LAST_IMPACT,
    F_ONE_ACCELERATION,
    F_PREVIOUS_ERROR,
    F_REST_UNTIL,
    F_SAMPLE_ACCELERATION,
    F_STEP,
    F_WORK,
    I_ERROR,
    I_EVALUATIONS,
    I_RIGID_J,
    I_RIGID_S,
    I_STEPS,
    IMPACT,
    NONE,
    P_BLOCK,
    P_COR,
    P_HOUSNER,
    P_LAW,
    P_REST,
    P_RTOL,
    P_TOL_FORCE,
    R_UPLIFT,
    REST,
    STEP_FAILED,
    UPLIFT,
    ZERO,
)


def _with_nystrom(name, namespace):
    """A copy of the rocking engine's event helper ``name`` bound to its RKN6(4) stepper
    (as :func:`shaketable.models.rocking.engine._integrator` binds each method's), compiled
    under a name of its own."""
    function = getattr(rocking_events, name)
    copy = types.FunctionType(function.__code__, namespace, name)
    copy.__qualname__ = f"stack_one_dof.{name}"
    return helper(copy)


_NAMESPACE = dict(vars(rocking_events), advance=nystrom_step)
for _name in rocking_events.METHOD_HELPERS:
    _NAMESPACE[_name] = _with_nystrom(_name, _NAMESPACE)
step_events = _NAMESPACE["step_events"]
control = inlined(step_size_control)

# A stack of one block is the single-block engine's run (its default method, "fast"): its
# own settings (tolerances, first step, rest tolerance, velocity floor), start of rocking
# (Eq. 2-1's margin crossed, made exact) and rest after an impact (the cascade summed),
# compiled from that engine's code with its RKN6(4) functions bound, as its integrator
# binds them (shaketable.models.rocking.engine._integrator).
_ENGINE_NAMESPACE = dict(vars(rocking_engine), _METHOD=METHOD_FAST,
                         **METHOD_FUNCTIONS[METHOD_FAST])
for _name in ("_settings", "_first_positive_margin", "_start_of_rocking",
              "_rest_after_impact"):
    _copy = types.FunctionType(getattr(rocking_engine, _name).__code__, _ENGINE_NAMESPACE,
                               _name)
    _copy.__qualname__ = f"stack_one_block.{_name}"
    _ENGINE_NAMESPACE[_name] = helper(_copy)
one_block_settings_of = _ENGINE_NAMESPACE["_settings"]
start_of_rocking = _ENGINE_NAMESPACE["_start_of_rocking"]
rest_after_impact = _ENGINE_NAMESPACE["_rest_after_impact"]

ONE = np.int64(1)

#: The stepper's evaluations of theta'' per trial step.
PER_STEP = 5
# the stepper's event kinds (shaketable.models.rocking.layout)
_IMPACT, _OVERTURN = float(rocking_events.EVENT_IMPACT), float(rocking_events.EVENT_OVERTURN)


def rigid_workspace_size(n):
    """The float elements of the closed forms' arrays of ``n`` blocks
    (:func:`rigid_workspace`)."""
    return n * (N_COLUMNS + 8) + N_BODY + N_INFO + 3


@inlined
def rigid_workspace(reals, f, n):
    """The arrays of the closed forms for a chain of ``n`` blocks: coefficients, the
    rocking body, forces, the seated corners' margins at a step's two ends, and the single
    block engine's run information that its event location fills (with the instability's
    time set, so that it is not located) and the last angle's cosine and sine
    (:func:`trig`): views of the zeroed pool ``reals`` from ``f`` (as
    :func:`~shaketable.models.stack.compiled_physics.workspace`'s), and the offset past
    them."""
    r0, f = reals[f:f + n * N_COLUMNS].reshape((n, N_COLUMNS)), f + n * N_COLUMNS
    r1, r2, f = reals[f:f + N_BODY], reals[f + N_BODY:f + N_BODY + 4 * n].reshape((n, 4)), \
        f + N_BODY + 4 * n
    r3, r4, f = reals[f:f + 2 * n].reshape((n, 2)), \
        reals[f + 2 * n:f + 4 * n].reshape((n, 2)), f + 4 * n
    info, last = reals[f:f + N_INFO], reals[f + N_INFO:f + N_INFO + 3]
    info[:] = math.nan
    info[INFO_T_UNSTABLE] = 0.0
    info[INFO_MAX_ABS_THETA] = 0.0
    last[:] = math.nan
    return (r0, r1, r2, r3, r4, info, last), f + N_INFO + 3


@inlined
def trig(last, x):
    """cos(x), sin(x), kept in ``last`` (x, cos, sin): a step's end, the segment's energy
    there and the next sample are at the same angle (zero recomputed: its sign is sin's)."""
    if last[0] != x or x == 0.0:
        last[0], last[1], last[2] = x, math.cos(x), math.sin(x)
    return last[1], last[2]


@inlined
def body_parameters(body):
    """The rocking body as the single block's parameters (b, h, I0 / M, no rods, alpha)."""
    return (body[B_HALF_WIDTH], body[B_HEIGHT], body[B_INERTIA_PER_MASS], 0.0, 0.0, 0.0, 0.0,
            body[B_ALPHA], 0.0, 0.0)


@inlined
def one_block_parameters(par):
    """A stack of one block: the block's parameters as the single-block engine takes them
    (a tuple, from ``par[P_BLOCK:]``)."""
    return (par[P_BLOCK], par[P_BLOCK + 1], par[P_BLOCK + 2], par[P_BLOCK + 3],
            par[P_BLOCK + 4], par[P_BLOCK + 5], par[P_BLOCK + 6], par[P_BLOCK + 7],
            par[P_BLOCK + 8], par[P_BLOCK + 9])


@inlined
def one_block_settings(par):
    """A stack of one block: the single-block engine's settings of its run
    (:func:`shaketable.models.rocking.engine._settings`: alpha [rad], p [1/s], the absolute
    tolerances [rad, rad/s], the rest tolerance [s], the velocity floor [rad/s], evaluations
    per step) at the stack's rtol and rest tolerance."""
    return one_block_settings_of(one_block_parameters(par), par[P_RTOL], par[P_REST])


@inlined
def one_block_start(fs, params, seg8, t, theta, omega, side, code):
    """A stack of one block: theta'' [rad/s^2] at the start of a segment, as the
    single-block engine has it: the stepper's own where the last segment reached the end of
    its input interval in this state (``code`` = 2 j + s), else Eq. (2-13) evaluated
    there."""
    carried = fs[F_ONE_ACCELERATION]
    if carried == carried and fs[F_ENERGY_THETA] == theta and fs[F_ENERGY_OMEGA] == omega \
            and fs[F_ENERGY_SIDE] == code:
        return carried
    ug, vg, rg = table_ground(seg8, t)
    return flight_acceleration(theta, side, ug, vg, rg, params)


@inlined
def table_segment(seg):
    """The stack's input interval as the single block's (no table rotation)."""
    return (seg[0], seg[1], seg[2], seg[3], seg[4], seg[5], 0.0, 0.0)


@inlined
def ensure_coefficients(chain, rigid, ist, j, s):
    """Compute the closed forms of the pattern (``j`` open on ``s``; -1 rest) unless the
    run's int state says they are current."""
    if ist[I_RIGID_J] != j or ist[I_RIGID_S] != s:
        rigid_coefficients(chain, j, s, rigid[0], rigid[1])
        ist[I_RIGID_J] = j
        ist[I_RIGID_S] = s


@inlined
def seated_margin(forces, pattern, tol, g):
    """The seated corners' normal forces plus ``tol`` [N] into ``g`` (n, 2); +inf at the
    open interface."""
    for k in range(pattern.size):
        for corner in range(2):
            g[k, corner] = math.inf if pattern[k] != 0 else forces[k, 2 + corner] + tol


@kernel
def force_at(rigid, j, s, t, theta, omega, acceleration, side, tau, seg, seg8, params, k,
             corner, tol):
    """A seated corner's normal force plus ``tol`` [N] ``tau`` after ``t`` on the stepper,
    and the state there."""
    x, v, a, _, _ = nystrom_step(t, theta, omega, acceleration, side, tau, seg8, params)
    ug, vg = ground(seg, t + tau)
    cosine, sine = trig(rigid[6], x)
    rigid_forces(rigid[0], j, s, cosine, sine, v, a, ug, vg, rigid[2])
    return rigid[2][k, 2 + corner] + tol, x, v, a


@inlined
def locate_uplift(rigid, j, s, t, theta, omega, acceleration, side, upper, g_upper, seg,
                  seg8, params, k, corner, tol, g_start):
    """The first zero in (0, ``upper``] of a seated corner's force margin, positive at 0
    (``g_start``) and at most 0 at ``upper`` (``g_upper``), by the Illinois method on the
    stepper's solution; returns it [s after ``t``] and the number of trial steps."""
    low, high = 0.0, upper
    g_low, g_high = g_start, g_upper
    tolerance = 4.0 * EPS * (abs(t) + upper) + 1e-300
    trials = np.int64(0)
    side_kept = 0
    for _ in range(100):
        if high - low <= tolerance or g_high == 0.0:
            break
        trial = high - g_high * (high - low) / (g_high - g_low)
        if not (low < trial < high):
            trial = 0.5 * (low + high)
        g, _, _, _ = force_at(rigid, j, s, t, theta, omega, acceleration, side, trial, seg,
                              seg8, params, k, corner, tol)
        trials += 1
        if g > 0.0:
            low, g_low = trial, g
            if side_kept == 1:
                g_high *= 0.5
            side_kept = 1
        else:
            high, g_high = trial, g
            if side_kept == -1:
                g_low *= 0.5
            side_kept = -1
    return high, trials


@inlined
def open_interface(pattern):
    """The one open interface of a one-DOF pattern."""
    for j in range(pattern.size):
        if pattern[j] != 0:
            return j
    return -1


@inlined
def one_dof_state(chain, run, rigid, ug, vg, forces):
    """The closed forms of the current pattern (rest or one-DOF) made current, and its
    phi'' [rad/s^2] (0 at rest) and contact forces (into ``forces``, (n, 4) [N]) at the
    table's u'', v'' [m/s^2]; returns (interface, side, phi, phi', phi'')."""
    phi, phi_dot, pattern, ist = run[0], run[1], run[2], run[4]
    j = open_interface(pattern)
    s = pattern[j] if j >= 0 else np.int64(0)
    ensure_coefficients(chain, rigid, ist, j, s)
    x, v, a, cosine, sine = 0.0, 0.0, 0.0, 1.0, 0.0
    if j >= 0:
        x, v = phi[j], phi_dot[j]
        cosine, sine = trig(rigid[6], x)
        a = rigid_acceleration(rigid[1], float(s), cosine, sine, ug, vg)
    rigid_forces(rigid[0], j, s, cosine, sine, v, a, ug, vg, forces)
    return j, s, x, v, a


@kernel
def one_dof_segment(chain, run, t, t_end, seg, rigid, fresh):
    """Integrate a one-DOF pattern from ``t`` to its first event or ``t_end`` with the single
    block's stepper (as :func:`shaketable.models.stack.compiled.segment` with DOP853):
    returns (time, what, interface), ``what`` one of ENDS_*. ``fresh``: the state at ``t``
    is the last sample's (its phi'' and forces kept, ``I_SAMPLED``), not evaluated again.
    Compiled apart (once per interval its call passes the run's arrays by value, 0.1 ms per
    two-block run): inlined into the loop over the samples it made the engine's first
    compile about 4 s of CPU longer."""
    phi, phi_dot, pattern, fs, ist, par, atol = run[0], run[1], run[2], run[3], run[4], \
        run[5], run[6]
    n = pattern.size
    j = open_interface(pattern)
    if pattern[j] * phi[j] < 0.0 or (phi[j] == 0.0 and pattern[j] * phi_dot[j] < 0.0):
        phi[j] = 0.0   # on the wrong side of its pivot, or leaving it the wrong way
        return t, ENDS_IMPACT, j
    if fresh:
        s = pattern[j]
        theta, omega, acceleration = phi[j], phi_dot[j], fs[F_SAMPLE_ACCELERATION]
    else:
        ug, vg = ground(seg, t)
        j, s, theta, omega, acceleration = one_dof_state(chain, run, rigid, ug, vg, rigid[2])
    side = float(s)
    params = body_parameters(rigid[1])
    seg8 = table_segment(seg)
    tol = par[P_TOL_FORCE]
    g_old, g_new = rigid[3], rigid[4]
    seated_margin(rigid[2], pattern, tol, g_old)
    work_start = fs[F_WORK]
    if fs[F_ENERGY_THETA] == theta and fs[F_ENERGY_OMEGA] == omega and \
            fs[F_ENERGY_SIDE] == 2 * j + s:
        energy_start = fs[F_ENERGY]   # where the last segment of this pattern ended
    else:
        cosine, sine = trig(rigid[6], theta)
        energy_start = rigid_energy(rigid[1], cosine, sine, omega)
    rtol, atol_theta, atol_omega = par[P_RTOL], atol[j], atol[n + j]
    if n == 1:
        # one block: the single-block engine's run, bit for bit (its parameters, tolerances
        # and theta'' at the start)
        params = one_block_parameters(par)
        _, _, atol_theta, atol_omega, _, _, _ = one_block_settings(par)
        acceleration = one_block_start(fs, params, seg8, t, theta, omega, side, 2 * j + s)
    step_size, previous_error = fs[F_STEP], fs[F_PREVIOUS_ERROR]
    just_rejected = False
    what, where = ENDS_NONE, NONE
    while t < t_end:
        h = min(step_size, t_end - t)
        if h < 10.0 * abs(np.nextafter(t, np.inf) - t) and h < t_end - t:
            ist[I_ERROR] = STEP_FAILED
            return t, ENDS_NONE, NONE
        theta_new, omega_new, acceleration_new, error_theta, error_omega = nystrom_step(
            t, theta, omega, acceleration, side, h, seg8, params)
        ist[I_EVALUATIONS] += PER_STEP
        accepted, step_size, previous_error, just_rejected = control(
            h, theta, omega, theta_new, omega_new, error_theta, error_omega, rtol,
            atol_theta, atol_omega, step_size, previous_error, just_rejected)
        if not accepted:
            continue
        ist[I_STEPS] += 1
        # the landing and the overturn, located on the stepper
        tau, kind, theta_new, omega_new, acceleration_new, located = step_events(
            t, theta, omega, acceleration, side, h, theta_new, omega_new, acceleration_new,
            seg8, params, rigid[5])
        ist[I_EVALUATIONS] += PER_STEP * located
        # a seated corner's force reaching zero before that: the earliest one
        ug, vg = ground(seg, t + tau)
        cosine, sine = trig(rigid[6], theta_new)
        rigid_forces(rigid[0], j, s, cosine, sine, omega_new, acceleration_new, ug, vg,
                     rigid[2])
        seated_margin(rigid[2], pattern, tol, g_new)
        first, first_k = math.inf, NONE
        for k in range(n):
            for corner in range(2):
                if g_old[k, corner] >= 0.0 and g_new[k, corner] <= 0.0:
                    root, trials = locate_uplift(rigid, j, s, t, theta, omega, acceleration,
                                                 side, tau, g_new[k, corner], seg, seg8,
                                                 params, k, corner, tol, g_old[k, corner])
                    ist[I_EVALUATIONS] += PER_STEP * trials
                    if root < first:
                        first, first_k = root, k
        if first_k >= 0:
            if first < tau:
                _, theta_new, omega_new, acceleration_new = force_at(
                    rigid, j, s, t, theta, omega, acceleration, side, first, seg, seg8,
                    params, first_k, np.int64(0), tol)
            tau, what, where = first, ENDS_LIFT, first_k
        elif kind == _IMPACT:
            what, where = ENDS_IMPACT, j
        elif kind == _OVERTURN:
            what, where = ENDS_OVERTURN, j
        # (one block: the single-block engine's t + tau, whatever it rounds to)
        t = t + tau if (tau < t_end - t) | (n == 1) else t_end
        theta, omega, acceleration = theta_new, omega_new, acceleration_new
        if what != ENDS_NONE:
            break
        for k in range(n):
            g_old[k, 0], g_old[k, 1] = g_new[k, 0], g_new[k, 1]
    if what == ENDS_IMPACT:
        # the next flight is shorter than the last one: no longer step (the rocking engine's
        # rule)
        step_size = min(step_size, max(t - fs[F_LAST_IMPACT], 1e-3 * step_size))
        fs[F_LAST_IMPACT] = t
    phi[j], phi_dot[j] = theta, omega
    cosine, sine = trig(rigid[6], theta)
    energy_end = rigid_energy(rigid[1], cosine, sine, omega)
    fs[F_WORK] = work_start + energy_end - energy_start
    fs[F_ENERGY], fs[F_ENERGY_THETA], fs[F_ENERGY_OMEGA], fs[F_ENERGY_SIDE] = \
        energy_end, theta, omega, 2 * j + s
    fs[F_STEP], fs[F_PREVIOUS_ERROR] = step_size, previous_error
    if n == 1:
        fs[F_ONE_ACCELERATION] = acceleration if what == ENDS_NONE else math.nan
    return t, what, where


@kernel
def one_block_impact(chain, ws, run, time, seg, before, flat, zeros):
    """A stack of one block lands: the single-block engine's impact (theta' times the
    ratio it is given, Section 2.7 (5): Housner's 1 - 1.5 sin^2(alpha) for the plastic law,
    as :func:`shaketable.models.rocking.physics.impact_cors` computes it, or the constant
    COR) and its rest after it (the cascade summed, ``_rest_after_impact``); the time the
    run goes on from. ``before``, ``flat``, ``zeros``: rows of the event workspace."""
    phi, phi_dot, pattern, fs, par = run[0], run[1], run[2], run[3], run[5]
    before[0], flat[0], zeros[0] = pattern[0], 0, 0.0
    energy_before = energy(chain, phi, phi_dot, before, ws[:6])
    cor = par[P_HOUSNER] if par[P_LAW] == 0.0 else par[P_COR]
    rate_before = phi_dot[0]
    phi[0], phi_dot[0], pattern[0] = 0.0, cor * rate_before, -pattern[0]
    energy_after = energy(chain, phi, phi_dot, pattern, ws[:6])
    record(run, time, IMPACT, ZERO, before, pattern, ONE,
           (rate_before, phi_dot[0], energy_before, energy_after), (ONE, NONE, NONE))
    _, _, _, _, rest_tolerance, velocity_floor, _ = one_block_settings(par)
    remaining = rest_after_impact(time, phi_dot[0], float(pattern[0]), table_segment(seg),
                                  one_block_parameters(par), cor, rest_tolerance,
                                  velocity_floor)
    if remaining >= 0.0:
        record(run, time + remaining, REST, ZERO, pattern, flat, ONE,
               (math.nan, math.nan, energy_after, energy(chain, phi, zeros, flat, ws[:6])),
               (NONE, ONE if phi_dot[0] != 0.0 else ZERO, NONE))
        phi_dot[0], pattern[0] = 0.0, 0
        fs[F_REST_UNTIL] = time + remaining
    return time


@kernel
def one_block_uplift(run, t, t_end, seg, after):
    """A stack of one block at rest at ``t``: when it starts rocking before ``t_end``, as
    the single-block engine finds it (Eq. 2-1's margin crossed, ``_start_of_rocking``), the
    uplift recorded and its pattern set (``after``: a row of the event workspace), as
    (time, 0); (inf, -1) when it stays at rest."""
    phi, phi_dot, pattern, par = run[0], run[1], run[2], run[5]
    time, side = start_of_rocking(t, t_end, table_segment(seg), one_block_parameters(par))
    if side == 0.0:
        return math.inf, NONE
    after[0] = 1 if side > 0.0 else -1
    record(run, time, UPLIFT, ZERO, pattern, after, ONE,
           (math.nan, math.nan, math.nan, math.nan), (ONE, NONE, R_UPLIFT))
    phi[0], phi_dot[0], pattern[0] = 0.0, 0.0, after[0]
    return time, ZERO


@inlined
def far_from_uplift(forces, arm):
    """Whether both corner forces of a block at rest (``forces``, one row of (N, F, N at the
    -x corner, N at the +x corner) [N]) exceed 10^-12 of the scale of their terms, N/2 and
    F h / (2 b) (``arm`` = h / b): far beyond the rounding of Eq. (2-1)'s margin, whose sign
    they give."""
    scale = 1e-12 * (abs(forces[0]) + abs(forces[1]) * arm)
    return forces[2] > scale and forces[3] > scale


@inlined
def one_block_rested(coefficients, phi, pattern, fs, ist, par, t, ug, vg, k, forces):
    """:func:`rested` for a stack of one block over the input interval from sample ``k``
    (``forces``: the run's history, (samples, 1, 4) [N]), decided as the single-block engine
    decides it (no start of rocking in it, ``_start_of_rocking``): at once when the corner
    forces at both ends are far from zero (affine in time in between, they stay positive:
    no margin crosses zero), else by that engine's test."""
    if ist[I_RIGID_J] != -1 or fs[F_REST_UNTIL] != -math.inf or G + vg[k] <= 0.0 or \
            G + vg[k + 1] <= 0.0 or pattern[0] != 0 or phi[0] != 0.0:
        return False
    rigid_forces(coefficients, NONE, ZERO, 1.0, 0.0, 0.0, 0.0, ug[k + 1], vg[k + 1],
                 forces[k + 1])
    arm = par[P_BLOCK + 1] / par[P_BLOCK]
    if far_from_uplift(forces[k, 0], arm) and far_from_uplift(forces[k + 1, 0], arm):
        return True
    segment = (t[k], t[k + 1] - t[k], ug[k], ug[k + 1] - ug[k], vg[k], vg[k + 1] - vg[k], 0.0,
               0.0)
    _, side = start_of_rocking(t[k], t[k + 1], segment, one_block_parameters(par))
    return side == 0.0
