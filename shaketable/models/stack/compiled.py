"""The stack's compiled event-driven engine (numba): each pattern by its cheapest exact method.

The algorithm of :mod:`shaketable.models.stack.engine` (its docstring and ``docs/stack.md``
say what it does), compiled whole: the stack at rest costs one evaluation of its (linear)
corner forces per input interval; a one-DOF pattern (one open interface: a single rigid body
rocking on a base that moves with the table) is integrated with the single block's
Runge-Kutta-Nystrom stepper and event location (:mod:`shaketable.models.stack.compiled_one`);
the multi-DOF patterns with DOP853, events located on its continuous extension
(:mod:`shaketable.models.stack.compiled_segment`). At each event the pattern is chosen by the
acceleration-level complementarity check, the plastic multi-contact law or the constant COR
applied at impacts, cascades summed in closed form. The physics is
:mod:`shaketable.models.stack.compiled_physics` (the general N-block equations) and
:mod:`shaketable.models.stack.compiled_rigid` (the closed forms of rest and one-DOF patterns).

:func:`run_stack` is the one compiled entry; :func:`integrate` (Python) calls it and returns
what :func:`shaketable.models.stack.engine.integrate` returns. :func:`integrate` allocates
every array of the run (the histories, the events' rows and three zeroed pools that the
workspaces are views of): the entry then needs no reference counting, and no allocating
wrapper around it optimizes the whole engine once more when it is first compiled.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from shaketable.core.constants import G
from shaketable.models.stack.compiled_events import CompiledRun, record
from shaketable.models.stack.compiled_one import (
    ensure_coefficients,
    one_block_impact,
    one_block_rested,
    one_block_settings,
    one_block_uplift,
    one_dof_segment,
    one_dof_state,
    rigid_workspace,
    rigid_workspace_size,
)
from shaketable.models.stack.compiled_physics import (
    COMPILED,
    FREE_INT_ROWS,
    FREE_ROWS,
    FULL_ENUMERATION,
    accelerations,
    cor_impact,
    energy,
    event_workspace,
    event_workspace_size,
    fill_candidate,
    first_combination,
    inlined,
    kernel,
    next_combination,
    open_count,
    plastic_impact,
    state_forces,
    table_power,
    workspace,
    workspace_size,
)
from shaketable.models.stack.compiled_rigid import rigid_forces
from shaketable.models.stack.compiled_segment import segment
from shaketable.models.stack.compiled_steps import (
    ground,
)
from shaketable.models.stack.layout import (
    AIRBORNE,
    ENDLESS,
    ENDS_IMPACT,
    ENDS_LIFT,
    ENDS_NONE,
    ENDS_OVERTURN,
    F_DOP_STEP,
    F_ERROR_TIME,
    F_LAST_IMPACT,
    F_PREVIOUS_ERROR,
    F_REST_ENERGY,
    F_REST_UNTIL,
    F_SAMPLE_ACCELERATION,
    F_STEP,
    F_T_AIRBORNE,
    F_T_OVERTURN,
    F_WORK,
    I_ERROR,
    I_EVENTS,
    I_INTERVAL_EVENTS,
    I_OVERTURNED,
    I_RECORDED,
    I_RIGID_J,
    I_SAMPLED,
    I_STALLED,
    I_STATUS,
    IMPACT,
    N_BLOCK,
    N_FLOATS,
    N_INTS,
    NO_PATTERN,
    NONE,
    OVERTURN,
    P_ALPHA,
    P_ALPHA_P,
    P_COR,
    P_DELTA,
    P_HOUSNER,
    P_LAW,
    P_REST,
    P_TOL_FORCE,
    R_IMPACT,
    R_NOISE,
    R_REST,
    R_START,
    R_UPLIFT,
    REST,
    STALLED,
    STEP_FAILED,
    UPLIFT,
    ZERO,
)

#: What an input interval's general path ends with (:func:`run_stack`).
STOPS, DONE, ONE_DOF = (np.int64(code) for code in range(3))

# the engine's constants (as shaketable.models.stack.engine's)
FLOOR = 1e-10
MAX_EVENTS_AT_ONE_INSTANT = 200
MAX_EVENTS_PER_INTERVAL = 100_000

ONE = np.int64(1)
# rows of the event workspace (compiled_physics.event_workspace) past the plastic law's: the
# pattern check's (float, int) and the impact's
C_ACCELERATION, C_AHEAD, C_AHEAD_DOT, C_PHI_DDOT, C_RATES, C_AFTER_DOT, C_ZEROS = \
    range(FREE_ROWS, FREE_ROWS + 7)
C_FREE, C_CANDIDATE, C_BEST, C_CHOSEN, C_BEFORE, C_AFTER, C_FLAT = \
    range(FREE_INT_ROWS, FREE_INT_ROWS + 7)



# ------------------------------------------------------------------------- choice
@kernel
def choose(chain, ws, floats, ints, run, time, seg, reason, interface, end):
    """Choose the pattern at ``time`` (:meth:`shaketable.models.stack.engine.Run.choose`);
    the time the run goes on from (NaN: no consistent pattern, the run's error set).
    ``floats``, ``ints``: the event workspace's rows (those past the plastic law's); the
    candidates' forces go to ``ws[8]`` (free between events). It allocates nothing: compiled
    without reference counting."""
    phi, phi_dot, pattern, fs, ist, par = run[0], run[1], run[2], run[3], run[4], run[5]
    n = phi.size
    for j in range(n):
        if pattern[j] != 0 and phi[j] == 0.0 and \
                pattern[j] * phi_dot[j] <= FLOOR * par[P_ALPHA_P]:
            pattern[j] = 0
            phi_dot[j] = 0.0
    free = ints[C_FREE]
    n_free = ZERO   # not a literal 0: one compile of its callees
    for j in range(n):
        if pattern[j] == 0:
            free[n_free] = j
            n_free += 1
    if n_free == 0:
        return time
    acceleration = floats[C_ACCELERATION]
    ug, vg = ground(seg, time)
    accelerations(chain, phi, phi_dot, pattern, ug, vg, acceleration, ws[:15])
    delta = min(par[P_DELTA], max(end - time, 0.0))
    ahead, ahead_dot = floats[C_AHEAD], floats[C_AHEAD_DOT]
    for j in range(n):
        ahead[j] = phi[j] + phi_dot[j] * delta + 0.5 * acceleration[j] * delta ** 2
        ahead_dot[j] = phi_dot[j] + acceleration[j] * delta
    ug, vg = ground(seg, time + delta)
    candidate, best, chosen = ints[C_CANDIDATE], ints[C_BEST], ints[C_CHOSEN]
    phi_ddot, forces = floats[C_PHI_DDOT], ws[8]
    consistent = ZERO
    tol = par[P_TOL_FORCE]
    for count in range(n_free + 1):
        first_combination(chosen, count)
        going = True
        while going:
            for sides in range(1 << count):
                fill_candidate(pattern, free, n_free, chosen, count, sides, candidate)
                state_forces(chain, ahead, ahead_dot, candidate, ug, vg, phi_ddot, forces, ws)
                good = True
                for p in range(n_free):
                    j = free[p]
                    if candidate[j] != 0:
                        good = good and candidate[j] * phi_ddot[j] > 0.0
                    else:
                        good = good and forces[j, 2] >= -tol and forces[j, 3] >= -tol
                if good:
                    consistent += 1
                    if consistent == 1:
                        for q in range(n):
                            best[q] = candidate[q]
            going = next_combination(chosen, count, n_free)
        if consistent and count == 0:
            # the first candidate is the pattern itself: consistent, it is kept (the other
            # candidates would only be counted)
            return time
        if consistent and n > FULL_ENUMERATION:
            break   # the fewest open interfaces: the levels above are not searched
    if consistent == 0:
        ist[I_ERROR] = NO_PATTERN
        fs[F_ERROR_TIME] = time
        return math.nan
    same = True
    for j in range(n):
        same = same and best[j] == pattern[j]
    if same:
        return time
    record(run, time, UPLIFT, interface, pattern, best, ONE,
           (math.nan, math.nan, math.nan, math.nan), (consistent, NONE, reason))
    ug0, vg0 = ground(seg, time)
    fs[F_WORK] += delta * table_power(chain, phi, phi_dot, pattern, ug0, vg0, ws)
    for j in range(n):
        pattern[j], phi[j], phi_dot[j] = best[j], ahead[j], ahead_dot[j]
    return time + delta


# ------------------------------------------------------------------------- impact
@kernel
def largest(values):
    """max |values|."""
    top = 0.0
    for value in values:
        top = max(top, abs(value))
    return top


@inlined
def rest_energy(chain, ws, fs, zeros, flat):
    """The energy of the stack at rest [J] (:func:`energy` of zeros), evaluated once per run."""
    if math.isnan(fs[F_REST_ENERGY]):
        fs[F_REST_ENERGY] = energy(chain, zeros, zeros, flat, ws[:6])
    return fs[F_REST_ENERGY]


@inlined
def take(phi_dot, pattern, after_dot, after):
    """The rates and the pattern after an impact made the run's (one loop: a slice
    assignment of an array would copy it first, which needs reference counting)."""
    for j in range(phi_dot.size):
        phi_dot[j], pattern[j] = after_dot[j], after[j]


@inlined
def noise_flights(chain, ws, scratch, run, time, seg, skip):
    """The interfaces other than ``skip`` open at zero gap in the impact's rows C_AFTER_DOT
    and C_AFTER whose flight would rise less than the integrator's absolute tolerance, as
    the bits of an int64 (:meth:`shaketable.models.stack.engine.Run.noise_flights`)."""
    phi, atol = run[0], run[6]
    floats, ints = scratch[0], scratch[1]
    after_dot, after, phi_ddot = floats[C_AFTER_DOT], ints[C_AFTER], floats[C_PHI_DDOT]
    noise = ZERO
    for k in range(phi.size):
        if k != skip and after[k] != 0 and phi[k] == 0.0:
            noise = ONE   # one to check: the accelerations are needed
    if noise == 0:
        return noise
    ug, vg = ground(seg, time)
    accelerations(chain, phi, after_dot, after, ug, vg, phi_ddot, ws[:15])
    noise = ZERO
    for k in range(phi.size):
        deceleration = -after[k] * phi_ddot[k]
        if k != skip and after[k] != 0 and phi[k] == 0.0 and deceleration > 0.0 and \
                after_dot[k] ** 2 <= 2.0 * deceleration * atol[0]:
            noise |= ONE << k
    return noise


@inlined
def closure(chain, ws, scratch, run, time, seg, rates_before, before, interface, held, skip):
    """The landing of ``interface`` with the interfaces of the bits ``held`` held flat, and
    every interface but ``skip`` it would open at zero gap with a flight rising less than
    the integrator's absolute tolerance held flat too, into the impact's rows C_AFTER_DOT
    and C_AFTER (:meth:`shaketable.models.stack.engine.Run.closure`: the limit of a cascade
    of landings over several interfaces)."""
    phi = run[0]
    floats, ints = scratch[0], scratch[1]
    after_dot, after = floats[C_AFTER_DOT], ints[C_AFTER]
    while True:
        plastic_impact(chain, phi, rates_before, before, interface, held, ws, scratch,
                       after_dot, after)
        noise = noise_flights(chain, ws, scratch, run, time, seg, skip)
        if noise & ~held == 0:
            return
        held |= noise


@inlined
def impact(chain, ws, scratch, run, time, seg, interface, end):
    """The impact law at a landing of ``interface``, cascades, then the pattern chosen
    afresh (:meth:`shaketable.models.stack.engine.Run.impact`); the time the run goes on
    from. The choice is made at one call (each call site of a compiled function passes
    the run's arrays again)."""
    phi, phi_dot, pattern, fs, par = run[0], run[1], run[2], run[3], run[5]
    if phi.size == 1 and (par[P_LAW] != 0.0 or par[P_HOUSNER] >= 0.0):
        return one_block_impact(chain, ws, run, time, seg, scratch[1][C_BEFORE],
                                scratch[1][C_FLAT], scratch[0][C_ZEROS])
    floats, ints = scratch[0], scratch[1]
    alpha_p = par[P_ALPHA_P]
    before, after, flat = ints[C_BEFORE], ints[C_AFTER], ints[C_FLAT]
    rates_before, after_dot, zeros = floats[C_RATES], floats[C_AFTER_DOT], floats[C_ZEROS]
    for j in range(phi.size):   # one loop: each slice assignment compiles a loop of its own
        before[j], rates_before[j], zeros[j], flat[j] = pattern[j], phi_dot[j], 0.0, 0
    energy_before = energy(chain, phi, phi_dot, before, ws[:6])
    rate_before = phi_dot[interface]
    phi[interface] = 0.0
    reason = R_IMPACT
    if abs(rate_before) <= FLOOR * alpha_p and largest(rates_before) > FLOOR * alpha_p:
        # a landing at the noise level while the stack moves: the interface closes
        closure(chain, ws, scratch, run, time, seg, rates_before, before, interface,
                ONE << interface, NONE)
        take(phi_dot, pattern, after_dot, after)
        record(run, time, REST, interface, before, after, ONE,
               (math.nan, math.nan, energy_before, energy(chain, phi, phi_dot, pattern, ws[:6])),
               (NONE, ZERO, NONE))
        reason = R_NOISE
    else:
        if par[P_LAW] == 0.0:
            solutions = plastic_impact(chain, phi, phi_dot, before, interface, ZERO, ws,
                                       scratch, after_dot, after)
            noise = noise_flights(chain, ws, scratch, run, time, seg, interface)
            if noise != 0:
                # the impact opens other interfaces with flights below the resolution: they
                # are held flat (the landing's own rebound is the cascade's, below)
                closure(chain, ws, scratch, run, time, seg, rates_before, before, interface,
                        noise, interface)
        else:
            cor_impact(phi_dot, before, interface, par[P_COR], after_dot, after)
            solutions = ONE
        take(phi_dot, pattern, after_dot, after)
        energy_after = energy(chain, phi, phi_dot, pattern, ws[:6])
        record(run, time, IMPACT, interface, before, pattern, ONE,
               (rate_before, phi_dot[interface], energy_before, energy_after),
               (solutions, NONE, NONE))
        if largest(phi_dot) <= FLOOR * alpha_p and largest(phi) <= FLOOR * par[P_ALPHA]:
            record(run, time, REST, interface, pattern, flat, ONE,
                   (math.nan, math.nan, energy_after, rest_energy(chain, ws, fs, zeros, flat)),
                   (NONE, ONE, NONE))
            phi[:] = 0.0
            phi_dot[:] = 0.0
            pattern[:] = 0
            reason = R_REST
        else:
            if pattern[interface] != 0 and rate_before != 0.0:
                ratio = abs(phi_dot[interface] / rate_before)
                phi_ddot = floats[C_PHI_DDOT]
                ug, vg = ground(seg, time)
                accelerations(chain, phi, phi_dot, pattern, ug, vg, phi_ddot, ws[:15])
                deceleration = -pattern[interface] * phi_ddot[interface]
                remaining = math.inf
                if deceleration > 0.0 and ratio < 1.0:
                    remaining = 2.0 * abs(phi_dot[interface]) / (deceleration * (1.0 - ratio))
                # a rebound rising less than the absolute tolerance is noise: it ends here
                # too (early by the series' length: docs/stack.md, Cascades)
                if deceleration > 0.0 and phi_dot[interface] ** 2 <= 2.0 * deceleration * run[6][0]:
                    remaining = 0.0
                if remaining <= par[P_REST] and open_count(pattern) == 1:
                    record(run, time + remaining, REST, interface, pattern, flat, ONE,
                           (math.nan, math.nan, energy_after,
                            energy(chain, phi, zeros, flat, ws[:6])),
                           (NONE, ONE, NONE))
                    phi_dot[:] = 0.0
                    pattern[:] = 0
                    fs[F_REST_UNTIL] = time + remaining
                    return time
                if remaining <= par[P_REST]:
                    # the others move on: this interface closes now (a plastic landing held
                    # flat)
                    closure(chain, ws, scratch, run, time, seg, rates_before, before,
                            interface, ONE << interface, NONE)
                    energy_closed = energy(chain, phi, after_dot, after, ws[:6])
                    record(run, time, REST, interface, pattern, after, ONE,
                           (math.nan, math.nan, energy_after, energy_closed), (NONE, ONE, NONE))
                    take(phi_dot, pattern, after_dot, after)
            if open_count(pattern) == 0:
                phi_dot[:] = 0.0
    return choose(chain, ws, scratch[0], scratch[1], run, time, seg, reason, interface, end)


# ------------------------------------------------------------------------- run
@inlined
def rest_uplift(chain, ws, run, t, t_end, seg, rigid):
    """The first time in [t, t_end] a rest corner force reaches -tol, as (time, interface);
    (inf, -1) when none does."""
    pattern, par = run[2], run[5]
    n = pattern.size
    start, end = ws[8], ws[17]
    # the closed form of rest (linear in u'', v''; phi = phi' = phi'' = 0)
    ensure_coefficients(chain, rigid, run[4], NONE, ZERO)
    ug, vg = ground(seg, t)
    rigid_forces(rigid[0], NONE, ZERO, 1.0, 0.0, 0.0, 0.0, ug, vg, start)
    ug, vg = ground(seg, t_end)
    rigid_forces(rigid[0], NONE, ZERO, 1.0, 0.0, 0.0, 0.0, ug, vg, end)
    first, first_j = math.inf, NONE
    tol = par[P_TOL_FORCE]
    for j in range(n):
        for corner in (2, 3):
            a, b = start[j, corner] + tol, end[j, corner] + tol
            if b >= 0.0:
                continue
            time = t if a <= 0.0 else t + (t_end - t) * a / (a - b)
            if time < first:
                first, first_j = time, j
    return first, first_j


@inlined
def progress(run, t, t_new):
    """Count events in a row without progress; False (the run's error set) past the limit."""
    ist = run[4]
    ist[I_STALLED] = ist[I_STALLED] + 1 if t_new <= t else 0
    if ist[I_STALLED] > MAX_EVENTS_AT_ONE_INSTANT:
        ist[I_ERROR] = STALLED
        run[3][F_ERROR_TIME] = t
        return False
    if ist[I_EVENTS] - ist[I_INTERVAL_EVENTS] > MAX_EVENTS_PER_INTERVAL:
        ist[I_ERROR] = ENDLESS
        run[3][F_ERROR_TIME] = t
        return False
    return True


@inlined
def airborne(run, t0, t1, v0, v1):
    """The table's vertical acceleration reaching -g over the input interval (t0, t1): the
    stack leaves it (the run's status and the time recorded)."""
    pattern, fs, ist = run[2], run[3], run[4]
    support0, support1 = G + v0, G + v1
    ist[I_STATUS] = 2
    fs[F_T_AIRBORNE] = t0 if support0 <= 0.0 else \
        t0 + (t1 - t0) * support0 / (support0 - support1)
    record(run, fs[F_T_AIRBORNE], AIRBORNE, NONE, pattern, pattern, ZERO,
           (math.nan, math.nan, math.nan, math.nan), (NONE, NONE, NONE))


@inlined
def sample(chain, ws, run, ug, vg, k, theta, rate, acceleration, patterns, forces, work,
           rigid):
    """theta, theta', theta'' of every block, the pattern, the contact forces and the
    table's work at sample ``k``."""
    phi, phi_dot, pattern = run[0], run[1], run[2]
    n = phi.size
    phi_ddot = ws[15]
    if open_count(pattern) <= 1:
        # rest or a one-DOF pattern: the closed forms
        j, _, _, _, a = one_dof_state(chain, run, rigid, ug, vg, forces[k])
        for i in range(n):
            phi_ddot[i] = a if i == j else 0.0
        if j >= 0:
            # the state the next interval's one-DOF segment starts from (the same u'', v'')
            run[4][I_SAMPLED] = 1
            run[3][F_SAMPLE_ACCELERATION] = a
            for i in range(n):
                for c in range(4):
                    rigid[2][i, c] = forces[k, i, c]
    else:
        state_forces(chain, phi, phi_dot, pattern, ug, vg, phi_ddot, forces[k], ws)
    a, b, c = 0.0, 0.0, 0.0
    for i in range(n):
        a += phi[i]
        b += phi_dot[i]
        c += phi_ddot[i]
        theta[k, i] = a
        rate[k, i] = b
        acceleration[k, i] = c
        patterns[k, i] = pattern[i]
    work[k] = run[3][F_WORK]


@inlined
def rested(coefficients, phi, pattern, fs, ist, tol, v0, ug1, vg1, forces):
    """Whether the stack, at rest with the closed forms of rest current, stays at rest over
    an input interval (no corner force past -tol at its end, as :func:`rest_uplift` finds
    it, the table pressing on it): then its contact forces at the end are in ``forces``."""
    if ist[I_RIGID_J] != -1 or fs[F_REST_UNTIL] != -math.inf or G + v0 <= 0.0 or \
            G + vg1 <= 0.0:
        return False
    for j in range(pattern.size):
        if pattern[j] != 0 or phi[j] != 0.0:
            return False
    rigid_forces(coefficients, NONE, ZERO, 1.0, 0.0, 0.0, 0.0, ug1, vg1, forces)
    for j in range(pattern.size):
        if forces[j, 2] + tol < 0.0 or forces[j, 3] + tol < 0.0:
            return False
    return True


def segment_buffers_size(n):
    """The float, int64 and bool elements of the DOP853 path's arrays of ``n`` blocks
    (:func:`segment_buffers`)."""
    size = 2 * n + 1
    return 27 * size + 11 * n, 9 * n, 2 * n


@inlined
def segment_buffers(reals, f, integers, i, flags, n):
    """The arrays of :func:`~shaketable.models.stack.compiled_segment.segment` (stages,
    states, dense output, event values, roots, codes, flags, times) as views of the zeroed
    pools (as :func:`~shaketable.models.stack.compiled_physics.workspace`'s)."""
    size = 2 * n + 1
    s0, f = reals[f:f + 16 * size].reshape((16, size)), f + 16 * size
    s1, s2, s3, f = reals[f:f + size], reals[f + size:f + 2 * size], \
        reals[f + 2 * size:f + 3 * size], f + 3 * size
    s4, s5, f = reals[f:f + 7 * size].reshape((7, size)), reals[f + 7 * size:f + 8 * size], \
        f + 8 * size
    s6, s7, s8, s11 = reals[f:f + 3 * n], reals[f + 3 * n:f + 6 * n], \
        reals[f + 6 * n:f + 9 * n], reals[f + 9 * n:f + 10 * n]
    s12 = reals[f + 10 * n:f + 11 * n]
    s9, s10 = integers[i:i + 9 * n].reshape((3, 3 * n)), flags[:2 * n].reshape((2, n))
    return s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11, s12


def pool_sizes(n):
    """The float, int64 and bool elements of the pools a run of ``n`` blocks takes its
    arrays from (:func:`run_stack`)."""
    sizes = [(N_FLOATS + 2 * n + 6, N_INTS + n, 0), (*workspace_size(n), 0),
             (*event_workspace_size(n), 0), (rigid_workspace_size(n), 0, 0),
             segment_buffers_size(n)]
    return tuple(sum(size[k] for size in sizes) for k in range(3))


#: numba options of the entry: called from Python (threads: without the GIL), no reference
#: counting (it allocates nothing).
ENTRY: Any = {"cache": True, "nogil": True, "error_model": COMPILED["error_model"], "_nrt": False}


@njit(**ENTRY)
def run_stack(b, h, m, inertia, t, ug, vg, phi0, phi_dot0, pattern0, par, atol, reals,
              integers, flags, histories, events):
    """One run of the stack over the samples ``t`` (the compiled engine's entry; its
    arguments are those :func:`integrate` prepares), into ``histories`` (theta, theta',
    theta'' [rad, rad/s, rad/s^2], patterns, forces [N], work [J]) and ``events`` (the
    recorded events' times and values, kinds and integers, patterns before and after);
    returns the number of samples filled.

    Every other array is a view of the zeroed pools ``reals``, ``integers``, ``flags``
    (:func:`pool_sizes`): the float and int states (``F_*``, ``I_*``) first, then the
    angles and the pattern. It allocates nothing: compiled without reference counting (an
    array taken from a tuple, or a row of one, is then no counted reference: the loop over
    the samples and the one-DOF steps pay for none), and its caller's arrays are passed
    once, not returned.
    """
    theta, rate, acceleration, patterns, forces, work = histories
    n = b.size
    count = t.size
    chain = (b, h, m, inertia)
    fs, ist = reals[:N_FLOATS], integers[:N_INTS]
    f, i = N_FLOATS + 2 * n + 6, N_INTS + n
    phi, phi_dot = reals[N_FLOATS:N_FLOATS + n], reals[N_FLOATS + n:N_FLOATS + 2 * n]
    pattern, seg = integers[N_INTS:i], reals[N_FLOATS + 2 * n:f]
    for j in range(n):
        phi[j], phi_dot[j], pattern[j] = phi0[j], phi_dot0[j], pattern0[j]
    ws, f, i = workspace(reals, f, integers, i, n)
    scratch, f, i = event_workspace(reals, f, integers, i, n)
    rigid, f = rigid_workspace(reals, f, n)
    buffers = segment_buffers(reals, f, integers, i, flags, n)
    fs[:] = math.nan
    fs[F_WORK], fs[F_REST_UNTIL] = 0.0, -math.inf
    fs[F_STEP], fs[F_PREVIOUS_ERROR], fs[F_LAST_IMPACT] = 0.1 / par[P_ALPHA_P] * par[P_ALPHA] \
        if n > 1 else 0.1 / one_block_settings(par)[1], 1e-4, t[0]   # one block: 0.1 / p
    fs[F_DOP_STEP] = 0.01 / par[P_ALPHA_P] * par[P_ALPHA]
    ist[I_OVERTURNED] = -1
    ist[I_RIGID_J] = -2   # no closed forms computed yet
    run = (phi, phi_dot, pattern, fs, ist, par, atol, events[0], events[1], events[2],
           events[3])
    seg[0], seg[1], seg[2], seg[3], seg[4], seg[5] = t[0], t[1] - t[0], ug[0], \
        ug[1] - ug[0], vg[0], vg[1] - vg[0]
    if n > 1:   # one block starts as the single-block engine (one_block_uplift)
        choose(chain, ws, scratch[0], scratch[1], run, t[0], seg, R_START, NONE, t[0])
    filled = 0
    if ist[I_ERROR] == 0:
        coefficients, tol = rigid[0], par[P_TOL_FORCE]
        for k in range(-1, count - 1):
            if k >= 0:   # the interval from sample k (k = -1: the first sample only)
                fresh = ist[I_SAMPLED] == 1   # sample k's one-DOF state: the segment's start
                ist[I_SAMPLED] = 0
                if (rested(coefficients, phi, pattern, fs, ist, tol, vg[k], ug[k + 1], vg[k + 1],
                           forces[k + 1]) if n > 1 else
                        one_block_rested(coefficients, phi, pattern, fs, ist, par, t, ug, vg, k,
                                         forces)):
                    # at rest: theta, theta', theta'' and the pattern are zeros
                    work[k + 1] = fs[F_WORK]
                    filled = k + 2
                    continue
                seg[0], seg[1], seg[2] = t[k], t[k + 1] - t[k], ug[k]
                seg[3], seg[4], seg[5] = ug[k + 1] - ug[k], vg[k], vg[k + 1] - vg[k]
                start, what, j = t[k], ENDS_NONE, NONE
                ist[I_INTERVAL_EVENTS] = ist[I_EVENTS]
                code = ONE_DOF if open_count(pattern) == 1 and \
                    fs[F_REST_UNTIL] == -math.inf and G + vg[k] > 0.0 and G + vg[k + 1] > 0.0 \
                    else DONE
                fresh = fresh and code == ONE_DOF
                while True:
                    if code == ONE_DOF:
                        # a one-DOF pattern: its segment here, the general path for its event
                        t_new, what, j = one_dof_segment(chain, run, start, t[k + 1], seg, rigid,
                                                         fresh)
                        fresh = False
                        if ist[I_ERROR] or not progress(run, start, t_new):
                            code = STOPS
                            break
                        start = t_new
                        if what == ENDS_NONE:
                            code = DONE   # the interval's end reached
                            break
                    # the general path to the interval's end (rest, uplifts, multi-DOF
                    # segments, events) from ``start``, or from the one-DOF segment's event
                    # ``what`` of interface ``j``: it stops the run (STOPS), reaches the end
                    # (DONE) or enters a one-DOF pattern (ONE_DOF, integrated above)
                    code, now, t1 = DONE, start, t[k + 1]
                    if G + vg[k] <= 0.0 or G + vg[k + 1] <= 0.0:
                        airborne(run, t[k], t1, vg[k], vg[k + 1])
                        code = STOPS
                    while code == DONE and (now < t1 or what != ENDS_NONE):
                        if what == ENDS_NONE:
                            if fs[F_REST_UNTIL] > now:
                                if fs[F_REST_UNTIL] >= t1:
                                    break
                                now = fs[F_REST_UNTIL]
                            if fs[F_REST_UNTIL] > -math.inf and now >= fs[F_REST_UNTIL]:
                                fs[F_REST_UNTIL] = -math.inf
                                if n > 1:   # one block: one_block_uplift below
                                    now = choose(chain, ws, scratch[0], scratch[1], run, now,
                                                 seg, R_REST, NONE, t1)
                                if ist[I_ERROR]:
                                    code = STOPS
                                    break
                            if open_count(pattern) == 0:
                                t_new, j = rest_uplift(chain, ws, run, now, t1, seg, rigid) \
                                    if n > 1 else \
                                    one_block_uplift(run, now, t1, seg, scratch[1][C_AFTER])
                                if j < 0:
                                    break
                                if not progress(run, now, t_new):
                                    code = STOPS
                                    break
                                # the uplift: the pattern is chosen below, as after a segment
                                # (one block: already set, as the single-block engine starts)
                                now, what = t_new, ENDS_LIFT if n > 1 else ENDS_NONE
                                continue
                            if open_count(pattern) == 1:
                                code = ONE_DOF
                                break
                            t_new, what, j = segment(chain, ws, run, now, t1, seg, buffers)
                            if ist[I_ERROR] or not progress(run, now, t_new):
                                code = STOPS
                                break
                            now = t_new
                            if what == ENDS_NONE:
                                continue
                        if what == ENDS_IMPACT:
                            now = impact(chain, ws, scratch, run, now, seg, j, t1)
                        elif what == ENDS_OVERTURN:
                            ist[I_STATUS] = 1
                            fs[F_T_OVERTURN] = now
                            ist[I_OVERTURNED] = j
                            record(run, now, OVERTURN, j, pattern, pattern, ONE,
                                   (math.nan, math.nan, math.nan, math.nan), (NONE, NONE, NONE))
                            code = STOPS
                            break
                        else:
                            now = choose(chain, ws, scratch[0], scratch[1], run, now, seg,
                                         R_UPLIFT, j, t1)
                        what = ENDS_NONE
                        if ist[I_ERROR]:
                            code = STOPS
                            break
                    start = now
                    what, j = ENDS_NONE, NONE
                    if code != ONE_DOF:
                        break
                if code == STOPS:
                    break
            sample(chain, ws, run, ug[k + 1], vg[k + 1], k + 1, theta, rate, acceleration,
                   patterns, forces, work, rigid)
            filled = k + 2
    return filled


#: Events kept by a first run; a run that records more runs again with room for all.
FIRST_CAPACITY = 4096


def integrate(stack, motion, *, law: str, cor: float, theta0, theta_dot0, rtol: float,
              rest_tolerance: float, max_recorded_events: int) -> dict:
    """Run the stack over ``motion`` with the compiled engine: the sampled histories and
    the events (the dict of :func:`shaketable.models.stack.engine.integrate`)."""
    from shaketable.models.rocking.physics import block_parameters, impact_cors
    from shaketable.models.stack.engine import LOOKAHEAD, StackChatter, StackStalled, pattern_of
    from shaketable.models.stack.physics import Chain

    chain = Chain.of(stack)
    # the half heights, then the offsets if any (compiled_physics' chain): a centred
    # column's chain is the one without offsets
    heights = np.concatenate([chain.h, chain.e]) if np.any(chain.e) else chain.h
    scale = stack.alpha_min
    tol_force = 1e-12 * G * float(stack.m.min())
    # then, read for a stack of one block only: Housner's ratio and the block's parameters
    # as the single-block engine is given them (its run, bit for bit: compiled_one)
    bottom = stack.blocks[0]
    par = np.concatenate([[LOOKAHEAD / stack.p_max, tol_force, scale, scale * stack.p_max, rtol,
                           rest_tolerance, cor, 0.0 if law == "plastic" else 1.0,
                           impact_cors(bottom, "housner")[0]],
                          block_parameters(bottom)[:N_BLOCK]])
    n = chain.n
    atol = np.concatenate([np.full(n, rtol * scale), np.full(n, rtol * scale * stack.p_max),
                           [rtol * float(G * stack.m.sum()) * float(np.hypot(stack.b, stack.h).max())]])
    phi = np.diff(np.asarray(theta0, dtype=float), prepend=0.0)
    phi_dot = np.diff(np.asarray(theta_dot0, dtype=float), prepend=0.0)
    pattern = np.array(pattern_of(phi, phi_dot), dtype=np.int64)
    t = np.ascontiguousarray(motion.t, dtype=float)
    ug = np.ascontiguousarray(motion.horizontal, dtype=float)
    vg = np.ascontiguousarray(motion.vertical_or_zero, dtype=float)
    capacity = max(1, min(int(max_recorded_events), FIRST_CAPACITY))
    count = t.size
    size_reals, size_integers, size_flags = pool_sizes(n)
    while True:
        histories = (np.zeros((count, n)), np.zeros((count, n)), np.zeros((count, n)),
                     np.zeros((count, n), dtype=np.int8), np.zeros((count, n, 4)),
                     np.zeros(count))
        # the events' rows up to the count recorded are written: left uninitialised, the
        # pages of the rows never used are never touched
        events = (np.empty((capacity, 5)), np.empty((capacity, 6), dtype=np.int64),
                  np.empty((capacity, n), dtype=np.int64), np.empty((capacity, n), dtype=np.int64))
        reals, integers = np.zeros(size_reals), np.zeros(size_integers, dtype=np.int64)
        filled = run_stack(chain.b, heights, chain.m, chain.inertia, t, ug, vg, phi, phi_dot,
                           pattern, par, atol, reals, integers,
                           np.zeros(size_flags, dtype=np.bool_), histories, events)
        ist = integers[:N_INTS]
        if ist[I_RECORDED] < capacity or capacity >= max_recorded_events:
            break
        capacity = int(min(max_recorded_events, max(int(ist[I_EVENTS]), 2 * capacity)))
    theta, rate, acceleration, patterns, forces, work = histories
    fs, (ev_f, ev_i, ev_pb, ev_pa) = reals[:N_FLOATS], events
    pattern_end = integers[N_INTS:N_INTS + n]
    error, when = int(ist[I_ERROR]), float(fs[F_ERROR_TIME])
    if error == NO_PATTERN:
        raise StackStalled(f"stack model: no consistent contact pattern at t = {when!r} s "
                           f"(from {tuple(int(s) for s in pattern_end)}); the input is "
                           "outside the model")
    if error == STALLED:
        raise StackChatter(f"stack model: {MAX_EVENTS_AT_ONE_INSTANT} events in a row at "
                           f"t = {when!r} s without progress")
    if error == ENDLESS:
        raise StackChatter(f"stack model: more than {MAX_EVENTS_PER_INTERVAL:,} events in one "
                           f"input interval, the last at t = {when!r} s: impacts without end "
                           "(contacts chattering, each flight shorter than the last)")
    if error == STEP_FAILED:
        raise StackStalled(f"stack model: DOP853 failed at t = {when!r} s: the step size "
                           "fell below the rounding of the time")
    run = CompiledRun(fs, ist, ev_f, ev_i, ev_pb, ev_pa)
    return dict(run=run, filled=filled, theta=theta[:filled], rate=rate[:filled],
                acceleration=acceleration[:filled], patterns=patterns[:filled],
                forces=forces[:filled], work=work[:filled])
