"""The stack's multi-DOF patterns between events, compiled (numba): DOP853, events located.

A segment (:func:`segment`) integrates the current pattern from a time to its first event or
the input interval's end with the explicit Runge-Kutta pair DOP853 of Dormand & Prince
(:mod:`shaketable.models.stack.compiled_steps`: SciPy's coefficients, error norm and
step-size control; the step size carried from one segment to the next), its events (a
landing, an overturn, a flat interface's corner force reaching zero) located on the accepted
step's continuous extension of order 7 by Brent's method (SciPy's ``brentq``, :func:`brent`),
a landing passed inside a step found from its turning point on the wrong side
(:func:`passed_landing`). :mod:`shaketable.models.stack.compiled` drives it.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.models.stack.compiled_physics import inlined, kernel, state_forces
from shaketable.models.stack.compiled_steps import (
    EPS,
    ERROR_EXPONENT,
    MAX_FACTOR,
    MIN_FACTOR,
    NO,
    SAFETY,
    dense_output,
    dense_state,
    ground,
    rhs,
    rk_step,
)
from shaketable.models.stack.layout import (
    ENDS_IMPACT,
    ENDS_LIFT,
    ENDS_NONE,
    ENDS_OVERTURN,
    F_DOP_STEP,
    F_ERROR_TIME,
    F_WORK,
    I_ERROR,
    I_EVALUATIONS,
    I_STEPS,
    NONE,
    P_RTOL,
    P_TOL_FORCE,
    STEP_FAILED,
    ZERO,
)
from shaketable.numerics import roots as root_finding

#: Event functions of a segment.
EV_LANDING, EV_OVERTURN, EV_LIFT, EV_TURN, EV_SIDE = (np.int64(code) for code in range(5))


@kernel
def event_value(chain, ws, run, seg, kind, j, corner, time, y, t_start, from_zero, opening):
    """An event function at (time, y): positive before its event (see the Python engine's
    ``segment``). A landing leaving phi = 0 (``from_zero``) is s phi / elapsed (-> s phi'
    at the start) or, leaving it from rest, s phi / elapsed^2 (-> ``opening``, s phi'' / 2
    at the start)."""
    pattern = run[2]
    n = pattern.size
    s = pattern[j]
    if kind == EV_LANDING:
        if from_zero:
            if opening > 0.0:
                return opening if time <= t_start else s * y[j] / (time - t_start) ** 2
            return s * y[n + j] if time <= t_start else s * y[j] / (time - t_start)
        return s * y[j]
    if kind == EV_OVERTURN:
        return 0.5 * math.pi - s * y[j]
    if kind == EV_TURN:
        return y[n + j]
    if kind == EV_SIDE:
        return s * y[j]
    ug, vg = ground(seg, time)
    forces = ws[8]
    state_forces(chain, y[:n], y[n:2 * n], pattern, ug, vg, ws[15], forces, ws)
    return forces[j, corner] + run[5][P_TOL_FORCE]


@inlined
def event_at(chain, ws, run, seg, kind, j, corner, time, t_start, from_zero, opening, dense,
             y_old, t_old, h, state):
    dense_state(dense, y_old, t_old, h, time, state)
    return event_value(chain, ws, run, seg, kind, j, corner, time, state, t_start, from_zero,
                       opening)


@inlined
def event_of_time(time, args):
    """:func:`event_at` as :func:`shaketable.numerics.roots.brent` calls it."""
    chain, ws, run, seg, kind, j, corner, t_start, from_zero, opening, dense, y_old, t_old, h, \
        state = args
    return event_at(chain, ws, run, seg, kind, j, corner, time, t_start, from_zero, opening,
                    dense, y_old, t_old, h, state)


@kernel
def brent(chain, ws, run, seg, kind, j, corner, t_start, from_zero, opening, dense, y_old,
          t_old, h, state, xa, xb, xtol, rtol):
    """The zero of an event function on the continuous extension in [xa, xb] (SciPy's
    ``brentq``: :func:`shaketable.numerics.roots.brent`)."""
    return root_finding.brent(event_of_time, (chain, ws, run, seg, kind, j, corner, t_start,
                                              from_zero, opening, dense, y_old, t_old, h,
                                              state),
                              xa, xb, xtol, rtol)


@inlined
def passed_landing(chain, ws, run, seg, t, t_now, h, y, dense, state, roots, which, terminal,
                   count, first_time, earlier, settled, from_zero):
    """A landing the step (t_now, h) passed without seeing it, as (time, interface), else
    (inf, -1) (:meth:`shaketable.models.stack.engine.Run.passed_landing`): the zero of
    s phi before a turning point found on the wrong side of the pivot."""
    pattern = run[2]
    found, found_j = math.inf, NONE
    for e in range(terminal, count):
        tau = roots[e]
        j = which[e]
        if math.isnan(tau) or tau > first_time or settled[j]:
            continue
        dense_state(dense, y, t_now, h, tau, state)
        s = pattern[j]
        if s * state[j] >= 0.0:
            earlier[j] = tau
            continue
        settled[j] = True
        low = max(t_now, earlier[j])
        if (low <= t and from_zero[j]) or event_at(
                chain, ws, run, seg, EV_SIDE, j, ZERO, low, t, NO, 0.0, dense, y, t_now, h,
                state) <= 0.0:
            continue
        time = brent(chain, ws, run, seg, EV_SIDE, j, ZERO, t, NO, 0.0, dense, y, t_now, h,
                     state, low, tau, 1e-300, 4.0 * EPS)
        if time < found:
            found, found_j = time, j
    return found, found_j


@inlined
def openings(pattern, phi_dot, from_zero, derivative, opening):
    """The start of the landing event of each interface leaving phi = 0 from rest (an
    uplift): s phi'' / 2 into ``opening`` (0 for the others; ``derivative`` the right-hand
    side at the start); the first interface that cannot open (s phi'' <= 0), else -1."""
    n = pattern.size
    for j in range(n):
        opening[j] = 0.0
        if pattern[j] != 0 and from_zero[j] and phi_dot[j] == 0.0:
            opening[j] = 0.5 * pattern[j] * derivative[n + j]
            if not opening[j] > 0.0:
                return j
    return NONE


@kernel
def segment(chain, ws, run, t, t_end, seg, buffers):
    """Integrate the current (moving) pattern from ``t`` to its first event or ``t_end``
    (:meth:`shaketable.models.stack.engine.Run.segment`): returns (time, what, interface),
    ``what`` one of ENDS_*."""
    phi, phi_dot, pattern, fs, ist, par, atol = run[0], run[1], run[2], run[3], run[4], \
        run[5], run[6]
    stages, y, y_new, work, dense, state, g, g_new, roots, codes, flags, earlier, opening = \
        buffers
    n = phi.size
    size = 2 * n + 1
    for j in range(n):
        if pattern[j] != 0 and (pattern[j] * phi[j] < 0.0 or (
                phi[j] == 0.0 and pattern[j] * phi_dot[j] < 0.0)):
            phi[j] = 0.0   # on the wrong side of its pivot, or leaving it the wrong way
            return t, ENDS_IMPACT, j
    # the event functions: landing and overturn of each open interface, the two corners of
    # each flat one (terminal), then the turning point of each open one
    kinds, which, corners = codes[0], codes[1], codes[2]
    count = ZERO
    flat = NO
    for j in range(n):
        if pattern[j] != 0:
            kinds[count], which[count], corners[count] = EV_LANDING, j, 0
            kinds[count + 1], which[count + 1], corners[count + 1] = EV_OVERTURN, j, 0
            count += 2
    for j in range(n):
        if pattern[j] == 0:
            flat = True
            kinds[count], which[count], corners[count] = EV_LIFT, j, 2
            kinds[count + 1], which[count + 1], corners[count + 1] = EV_LIFT, j, 3
            count += 2
    terminal = count
    for j in range(n):
        if pattern[j] != 0:
            kinds[count], which[count], corners[count] = EV_TURN, j, 0
            count += 1
    from_zero, settled = flags[0], flags[1]
    for j in range(n):
        from_zero[j] = phi[j] == 0.0
        settled[j] = False
        earlier[j] = t
        y[j] = phi[j]
        y[n + j] = phi_dot[j]
    y[2 * n] = fs[F_WORK]
    rtol = par[P_RTOL]
    lean = run[:6]   # what the event functions read: fewer arrays passed at each call
    rhs(chain, ws, pattern, seg, t, y, stages[0], flat)
    j = openings(pattern, phi_dot, from_zero, stages[0], opening)
    if j >= 0:
        return t, ENDS_IMPACT, j   # it cannot open: it lands now, at rate zero
    for e in range(count):
        g[e] = event_value(chain, ws, lean, seg, kinds[e], which[e], corners[e], t, y, t,
                           from_zero[which[e]], opening[which[e]]) \
            if kinds[e] != EV_LIFT else ws[8][which[e], corners[e]] + par[P_TOL_FORCE]
    # the step size carried from the last DOP853 step (no restart at each input interval)
    h_abs = fs[F_DOP_STEP]
    t_now = t
    while True:
        min_step = 10.0 * abs(np.nextafter(t_now, np.inf) - t_now)
        h_abs = max(h_abs, min_step)
        rejected = False
        while True:
            if h_abs < min_step:
                ist[I_ERROR] = STEP_FAILED
                fs[F_ERROR_TIME] = t_now
                return t_now, ENDS_NONE, NONE
            planned = h_abs
            t_new = t_now + h_abs
            if t_new > t_end:
                t_new = t_end
            h = t_new - t_now
            h_abs = abs(h)
            norm = rk_step(chain, ws, pattern, seg, t_now, y, h, stages, y_new, work, atol,
                           rtol, flat)
            ist[I_EVALUATIONS] += 12
            if norm < 1.0:
                factor = MAX_FACTOR if norm == 0.0 else min(MAX_FACTOR,
                                                            SAFETY * norm ** ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                if h < planned:
                    # a step cut short by the interval's end says nothing against the
                    # step size planned (the single-block engine's rule)
                    h_abs = max(h_abs, planned)
                fs[F_DOP_STEP] = h_abs
                break
            h_abs *= max(MIN_FACTOR, SAFETY * norm ** ERROR_EXPONENT)
            rejected = True
        ist[I_STEPS] += 1
        for e in range(count):
            g_new[e] = event_value(chain, ws, lean, seg, kinds[e], which[e], corners[e], t_new,
                                   y_new, t, from_zero[which[e]], opening[which[e]]) \
                if kinds[e] != EV_LIFT else ws[8][which[e], corners[e]] + par[P_TOL_FORCE]
        active = False
        for e in range(count):
            down = g[e] >= 0.0 and g_new[e] <= 0.0
            up = g[e] <= 0.0 and g_new[e] >= 0.0
            roots[e] = math.nan
            if down or (e >= terminal and up):
                roots[e] = math.inf
                active = True
        if active:
            dense_output(chain, ws, pattern, seg, t_now, y, y_new, h, stages, dense, work)
            ist[I_EVALUATIONS] += 3
            first, first_time = NONE, math.inf
            for e in range(count):
                if roots[e] == math.inf:
                    roots[e] = brent(chain, ws, lean, seg, kinds[e], which[e], corners[e], t,
                                     from_zero[which[e]], opening[which[e]], dense, y, t_now,
                                     h, state, t_now, t_new, 4.0 * EPS, 4.0 * EPS)
                    if e < terminal and roots[e] < first_time:
                        first, first_time = e, roots[e]
            # a turning point on the wrong side of a landing: the landing before it
            found, found_j = passed_landing(chain, ws, lean, seg, t, t_now, h, y, dense, state,
                                            roots, which, terminal, count, first_time,
                                            earlier, settled, from_zero)
            if found_j >= 0 and found < first_time:
                dense_state(dense, y, t_now, h, found, state)
                for i in range(n):
                    phi[i] = state[i]
                    phi_dot[i] = state[n + i]
                fs[F_WORK] = state[2 * n]
                phi[found_j] = 0.0
                return found, ENDS_IMPACT, found_j
            if first >= 0:
                dense_state(dense, y, t_now, h, first_time, state)
                for i in range(n):
                    phi[i] = state[i]
                    phi_dot[i] = state[n + i]
                fs[F_WORK] = state[2 * n]
                kind = kinds[first]
                what = ENDS_IMPACT if kind == EV_LANDING else (
                    ENDS_OVERTURN if kind == EV_OVERTURN else ENDS_LIFT)
                return first_time, what, which[first]
        for e in range(count):
            g[e] = g_new[e]
        for i in range(size):
            y[i] = y_new[i]
            stages[0, i] = stages[12, i]
        t_now = t_new
        if t_now >= t_end:
            for i in range(n):
                phi[i] = y[i]
                phi_dot[i] = y[n + i]
            fs[F_WORK] = y[2 * n]
            return t_end, ENDS_NONE, NONE
