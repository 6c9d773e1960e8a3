"""DOP853 for the stack's compiled engine (numba): steps, step-size start, dense output.

SciPy's Runge-Kutta pair of order 8 (Dormand & Prince; Hairer, Norsett & Wanner, Solving
ODEs I, Sec. II.10), its coefficients (``scipy.integrate._ivp.dop853_coefficients``), its
error norm, initial step and continuous extension of order 7, written for the state
y = (phi, phi', W) of a stack pattern (W the table's work [J]) so that the compiled engine
(:mod:`shaketable.models.stack.compiled`) takes the steps the Python engine's ``solve_ivp``
takes.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate._ivp import dop853_coefficients as dop853

from shaketable.models.stack.compiled_physics import (
    accelerations,
    interface_forces,
    kernel,
    power,
)

# SciPy's DOP853 (scipy.integrate._ivp.dop853_coefficients): 12 stages, the 13th is f at
# the step's end, three more for the continuous extension
_A = np.ascontiguousarray(dop853.A[:12, :12])
_B = np.ascontiguousarray(dop853.B)
_C = np.ascontiguousarray(dop853.C[:12])
_E3 = np.ascontiguousarray(dop853.E3)
_E5 = np.ascontiguousarray(dop853.E5)
_A_EXTRA = np.ascontiguousarray(dop853.A[13:])
_C_EXTRA = np.ascontiguousarray(dop853.C[13:])
_D = np.ascontiguousarray(dop853.D)
#: SciPy's step-size control of its Runge-Kutta methods.
SAFETY, MIN_FACTOR, MAX_FACTOR, ERROR_EXPONENT = 0.9, 0.2, 10.0, -1.0 / 8.0
EPS = float(np.finfo(float).eps)
#: False as a numpy bool: a literal False would compile the right-hand side once more.
NO = np.bool_(False)


@kernel
def ground(seg, time):
    """u'', v'' [m/s^2] at ``time`` in the input interval ``seg`` = (t0, span, u0, du, v0,
    dv) (linear)."""
    x = (time - seg[0]) / seg[1]
    return seg[2] + seg[3] * x, seg[4] + seg[5] * x


@kernel
def rhs(chain, ws, pattern, seg, time, y, out, with_forces):
    """y' = (phi', phi'', the table's power) at (time, y); with ``with_forces`` the contact
    forces into the workspace (``ws[8]``)."""
    n = pattern.size
    ug, vg = ground(seg, time)
    accelerations(chain, y[:n], y[n:2 * n], pattern, ug, vg, out[n:2 * n], ws)
    for i in range(n):
        out[i] = y[n + i]
    if with_forces:
        interface_forces(chain, pattern, ug, vg, ws, ws[8])
    out[2 * n] = power(chain, ug, vg, ws)


@kernel
def rk_step(chain, ws, pattern, seg, t, y, h, stages, y_new, work, atol, rtol, with_forces):
    """One DOP853 step (SciPy's ``rk_step``): y(t + h) into ``y_new``, the 13 stages into
    ``stages`` (the last is f at the step's end); returns SciPy's error norm. With
    ``with_forces`` the contact forces at the step's end are left in ``ws[8]`` (the inner
    stages need none: the forces enter no equation of motion)."""
    size = y.size
    for s in range(1, 12):
        for i in range(size):
            total = 0.0
            for j in range(s):
                total += stages[j, i] * _A[s, j]
            work[i] = y[i] + total * h
        rhs(chain, ws, pattern, seg, t + _C[s] * h, work, stages[s], NO)
    for i in range(size):
        total = 0.0
        for j in range(12):
            total += stages[j, i] * _B[j]
        y_new[i] = y[i] + h * total
    rhs(chain, ws, pattern, seg, t + h, y_new, stages[12], with_forces)
    err5, err3 = 0.0, 0.0
    for i in range(size):
        scale = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
        e5, e3 = 0.0, 0.0
        for j in range(13):
            e5 += stages[j, i] * _E5[j]
            e3 += stages[j, i] * _E3[j]
        err5 += (e5 / scale) ** 2
        err3 += (e3 / scale) ** 2
    if err5 == 0.0 and err3 == 0.0:
        return 0.0
    return abs(h) * err5 / math.sqrt((err5 + 0.01 * err3) * size)


@kernel
def initial_step(chain, ws, pattern, seg, t0, y0, f0, t_bound, atol, rtol, work, f1):
    """SciPy's ``select_initial_step`` for DOP853 (error estimator of order 7)."""
    size = y0.size
    length = abs(t_bound - t0)
    if length == 0.0:
        return 0.0
    d0, d1 = 0.0, 0.0
    for i in range(size):
        scale = atol[i] + abs(y0[i]) * rtol
        d0 += (y0[i] / scale) ** 2
        d1 += (f0[i] / scale) ** 2
    d0, d1 = math.sqrt(d0 / size), math.sqrt(d1 / size)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, length)
    for i in range(size):
        work[i] = y0[i] + h0 * f0[i]
    rhs(chain, ws, pattern, seg, t0 + h0, work, f1, NO)
    d2 = 0.0
    for i in range(size):
        scale = atol[i] + abs(y0[i]) * rtol
        d2 += ((f1[i] - f0[i]) / scale) ** 2
    d2 = math.sqrt(d2 / size) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, length)


@kernel
def dense_output(chain, ws, pattern, seg, t_old, y_old, y, h, stages, dense, work):
    """DOP853's continuous extension of order 7 of the step (t_old, y_old) -> y into
    ``dense`` (7 rows; SciPy's ``_dense_output_impl``)."""
    size = y.size
    for s in range(13, 16):
        for i in range(size):
            total = 0.0
            for j in range(s):
                total += stages[j, i] * _A_EXTRA[s - 13, j]
            work[i] = y_old[i] + total * h
        rhs(chain, ws, pattern, seg, t_old + _C_EXTRA[s - 13] * h, work, stages[s], NO)
    for i in range(size):
        delta = y[i] - y_old[i]
        dense[0, i] = delta
        dense[1, i] = h * stages[0, i] - delta
        dense[2, i] = 2.0 * delta - h * (stages[12, i] + stages[0, i])
        for row in range(4):
            total = 0.0
            for s in range(16):
                total += _D[row, s] * stages[s, i]
            dense[3 + row, i] = h * total


@kernel
def dense_state(dense, y_old, t_old, h, time, out):
    """The state at ``time`` on the continuous extension (SciPy's Dop853DenseOutput)."""
    x = (time - t_old) / h
    for i in range(y_old.size):
        value = 0.0
        for row in range(6, -1, -1):
            value += dense[row, i]
            value *= x if row % 2 == 0 else 1.0 - x
        out[i] = value + y_old[i]


