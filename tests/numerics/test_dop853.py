"""The shared DOP853 (shaketable.numerics.dop853) on closed forms and against SciPy.

The functions run as plain Python (``py_func``: the same source numba compiles into the
engines, whose bit-identity the engine tests check) with a Python right-hand side.
"""

import math

import numpy as np
import pytest
from scipy.integrate import DOP853
from scipy.integrate._ivp import dop853_coefficients as scipy_dop853

from shaketable.numerics import dop853

STEP = dop853.step.py_func
DENSE_OUTPUT = dop853.dense_output.py_func
DENSE_STATE = dop853.dense_state.py_func
INITIAL_STEP = dop853.initial_step.py_func


def growth(t, y, out, args):
    """y' = k y (exact: y0 exp(k t))."""
    out[0] = args[0] * y[0]


def oscillator(t, y, out, args):
    """x'' = -w^2 x as (x, x'): exact x = cos(w t) from (1, 0)."""
    w = args[0]
    out[0] = y[1]
    out[1] = -w * w * y[0]


def _step(rhs, args, t, y, h, rtol=1e-12, atol=1e-12):
    stages = np.zeros((dop853.N_STAGES_EXTENDED, y.size))
    rhs(t, y, stages[0], args)
    y_new, work = np.empty(y.size), np.empty(y.size)
    error = STEP(rhs, args, t, y, h, stages, y_new, work, np.full(y.size, atol), rtol)
    return y_new, error, stages


def _integrate(rhs, args, y0, t_end, n):
    y, h = np.array(y0, float), t_end / n
    for k in range(n):
        y, _, _ = _step(rhs, args, k * h, y, h)
    return y


def test_the_tableau_is_scipys():
    assert np.array_equal(dop853.A, scipy_dop853.A[:12, :12])
    assert np.array_equal(dop853.B, scipy_dop853.B)
    assert np.array_equal(dop853.C, scipy_dop853.C[:12])
    assert np.array_equal(dop853.E3, scipy_dop853.E3[:12]) and scipy_dop853.E3[12] == 0.0
    assert np.array_equal(dop853.E5, scipy_dop853.E5[:12]) and scipy_dop853.E5[12] == 0.0
    assert np.array_equal(dop853.A_EXTRA, scipy_dop853.A[13:])
    assert np.array_equal(dop853.C_EXTRA, scipy_dop853.C[13:])
    assert np.array_equal(dop853.D, scipy_dop853.D)


@pytest.mark.parametrize("rhs, args, y0, t_end, exact, steps", [
    (growth, (1.0,), [1.0], 1.0, math.e, 4),
    (oscillator, (1.0,), [1.0, 0.0], 5.0, math.cos(5.0), 10),
])
def test_the_global_error_falls_as_the_eighth_power_of_the_step(rhs, args, y0, t_end, exact,
                                                                 steps):
    errors = [abs(_integrate(rhs, args, y0, t_end, n)[0] - exact) for n in (steps, 2 * steps)]
    order = math.log2(errors[0] / errors[1])
    assert 7.5 < order < 8.8, errors


def test_one_step_is_scipys_step():
    # SciPy's own DOP853 step on the oscillator (its rk_step: the same tableau, another
    # order of summation): the same state to rounding
    from scipy.integrate._ivp.rk import rk_step

    y0, h = np.array([0.3, -1.2]), 0.37

    def fun(t, y):
        out = np.empty(2)
        oscillator(t, y, out, (2.0,))
        return out

    stages = np.empty((scipy_dop853.N_STAGES + 1, 2))
    expected, _ = rk_step(fun, 0.1, y0, fun(0.1, y0), h, scipy_dop853.A[:12, :12],
                          scipy_dop853.B, scipy_dop853.C[:12], stages)
    got, _, _ = _step(oscillator, (2.0,), 0.1, y0, h)
    assert np.allclose(got, expected, rtol=1e-14, atol=1e-15)


def test_the_error_estimate_bounds_the_true_error_and_shrinks_with_the_step():
    # Hairer's estimate (orders 5 and 3 blended) is conservative for the order-8 result
    estimates = []
    for h in (0.4, 0.2):
        y_new, error, _ = _step(growth, (1.0,), 0.0, np.array([1.0]), h, rtol=0.0, atol=1e-10)
        true = abs(y_new[0] - math.exp(h)) / 1e-10
        assert error > true
        estimates.append(error)
    assert estimates[0] / estimates[1] > 2.0 ** 5


def test_the_continuous_extension_is_of_order_seven_inside_the_step():
    def interior_error(h):
        y0 = np.array([1.0, 0.0])
        y_new, _, stages = _step(oscillator, (1.0,), 0.0, y0, h)
        oscillator(h, y_new, stages[12], (1.0,))
        dense = np.empty((dop853.N_DENSE, 2))
        DENSE_OUTPUT(oscillator, (1.0,), 0.0, y0, y_new, h, stages, dense, np.empty(2))
        out = np.empty(2)
        worst = 0.0
        for fraction in (0.1, 0.25, 0.5, 0.7, 0.9):
            DENSE_STATE(dense, y0, fraction, out)
            t = fraction * h
            worst = max(worst, abs(out[0] - math.cos(t)), abs(out[1] + math.sin(t)))
        DENSE_STATE(dense, y0, 0.0, out)
        assert np.array_equal(out, y0)
        DENSE_STATE(dense, y0, 1.0, out)
        assert np.allclose(out, y_new, rtol=0.0, atol=1e-15)
        return worst

    coarse, fine = interior_error(1.0), interior_error(0.5)
    assert coarse < 1e-6
    assert math.log2(coarse / fine) > 7.0   # local error O(h^8)


def test_the_initial_step_is_scipys():
    y0, atol, rtol = np.array([1.0, 0.0]), np.full(2, 1e-9), 1e-6
    f0 = np.empty(2)
    oscillator(0.0, y0, f0, (3.0,))
    h = INITIAL_STEP(oscillator, (3.0,), 0.0, y0, f0, 10.0, atol, rtol, np.empty(2),
                     np.empty(2))

    def fun(t, y):
        out = np.empty(2)
        oscillator(t, y, out, (3.0,))
        return out

    assert h == pytest.approx(DOP853(fun, 0.0, y0, 10.0, rtol=rtol, atol=atol).h_abs,
                              rel=1e-14)
    assert INITIAL_STEP(oscillator, (3.0,), 1.0, y0, f0, 1.0, atol, rtol, np.empty(2),
                        np.empty(2)) == 0.0
