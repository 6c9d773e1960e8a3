"""DOP853 for the stack's compiled engine (numba): steps, step-size start, dense output.

SciPy's Runge-Kutta pair of order 8 (Dormand & Prince; Hairer, Norsett & Wanner, Solving
ODEs I, Sec. II.10), its error norm, initial step and continuous extension of order 7
(:mod:`shaketable.numerics.dop853`, shared by the package's engines), for the state
y = (phi, phi', W) of a stack pattern (W the table's work [J]) so that the compiled engine
(:mod:`shaketable.models.stack.compiled`) takes the steps the Python engine's ``solve_ivp``
takes.
"""

from __future__ import annotations

import numpy as np

from shaketable.models.stack.compiled_physics import (
    accelerations,
    inlined,
    interface_forces,
    kernel,
    power,
)
from shaketable.numerics import dop853
from shaketable.numerics.dop853 import (  # noqa: F401  (the step control, re-exported)
    EPS,
    ERROR_EXPONENT,
    MAX_FACTOR,
    MIN_FACTOR,
    SAFETY,
)

#: False as a numpy bool: a literal False would compile the right-hand side once more.
NO = np.bool_(False)


@kernel
def ground(seg, time):
    """u'', v'' [m/s^2] at ``time`` in the input interval ``seg`` = (t0, span, u0, du, v0,
    dv) (linear)."""
    x = (time - seg[0]) / seg[1]
    return seg[2] + seg[3] * x, seg[4] + seg[5] * x


@inlined
def rhs(chain, ws, pattern, seg, time, y, out, with_forces):
    """y' = (phi', phi'', the table's power) at (time, y); with ``with_forces`` the contact
    forces into the workspace (``ws[8]``)."""
    n = pattern.size
    ug, vg = ground(seg, time)
    accelerations(chain, y[:n], y[n:2 * n], pattern, ug, vg, out[n:2 * n], ws[:15])
    for i in range(n):
        out[i] = y[n + i]
    if with_forces:
        interface_forces(chain, pattern, ug, vg, ws[:13], ws[8])
    out[2 * n] = power(chain, ug, vg, ws[:4])


@inlined
def pattern_rhs(time, y, out, args):
    """:func:`rhs` without the forces as :mod:`shaketable.numerics.dop853` calls it:
    ``args`` = (chain, ws, pattern, seg)."""
    chain, ws, pattern, seg = args
    rhs(chain, ws, pattern, seg, time, y, out, NO)


@inlined
def rk_step(chain, ws, pattern, seg, t, y, h, stages, y_new, work, atol, rtol, with_forces):
    """One DOP853 step (SciPy's ``rk_step``; :func:`shaketable.numerics.dop853.step`):
    y(t + h) into ``y_new``, the 13 stages into ``stages`` (row 0 given; the last is f at
    the step's end); returns SciPy's error norm. With ``with_forces`` the contact forces
    at the step's end are left in ``ws[8]`` (the inner stages need none: the forces enter
    no equation of motion)."""
    error = dop853.step(pattern_rhs, (chain, ws, pattern, seg), t, y, h, stages, y_new, work,
                        atol, rtol)
    rhs(chain, ws, pattern, seg, t + h, y_new, stages[12], with_forces)
    return error


@kernel
def initial_step(chain, ws, pattern, seg, t0, y0, f0, t_bound, atol, rtol, work, f1):
    """SciPy's ``select_initial_step`` for DOP853 (error estimator of order 7;
    :func:`shaketable.numerics.dop853.initial_step`)."""
    return dop853.initial_step(pattern_rhs, (chain, ws, pattern, seg), t0, y0, f0, t_bound,
                               atol, rtol, work, f1)


@inlined
def dense_output(chain, ws, pattern, seg, t_old, y_old, y, h, stages, dense, work):
    """DOP853's continuous extension of order 7 of the step (t_old, y_old) -> y into
    ``dense`` (7 rows; SciPy's ``_dense_output_impl``;
    :func:`shaketable.numerics.dop853.dense_output`)."""
    dop853.dense_output(pattern_rhs, (chain, ws, pattern, seg), t_old, y_old, y, h, stages,
                        dense, work)


@kernel
def dense_state(dense, y_old, t_old, h, time, out):
    """The state at ``time`` on the continuous extension (SciPy's Dop853DenseOutput)."""
    dop853.dense_state(dense, y_old, (time - t_old) / h, out)
