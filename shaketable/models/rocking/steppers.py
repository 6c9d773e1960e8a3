"""The rocking model and the three steppers of the compiled engine (numba).

:mod:`shaketable.models.rocking.engine` drives them: theta'' of the model each method
integrates (Eq. 2-13/2-14, or its slender-block linearisation Eq. 2-4 for
``linear``), the ground acceleration inside an input interval, and one step of each
method (the Runge-Kutta-Nystrom pair RKN6(4) for ``fast``, the report's
predictor-corrector, Section 2.8, and the linear model's closed form).

Each method's three functions are in :data:`METHOD_FUNCTIONS`, under the names the engine's
driver calls them by (``model_acceleration``, ``flight_model``, ``advance``): the engine
compiles one integrator per method with that method's functions bound to those names, so the
default method's first compile neither types nor optimises the others' code, and a call goes
straight to the method's function (no compiled layer that chooses it). They are called from
compiled code only.
"""

from __future__ import annotations

import math
from typing import Any

from numba import njit

from shaketable.core.constants import G
from shaketable.models.rocking import physics as dynamics
from shaketable.models.rocking.layout import METHOD_FAST, METHOD_LINEAR, METHOD_PREDICTOR_CORRECTOR
from shaketable.models.rocking.physics import (
    ALPHA,
    ERROR_MODEL,
    HALF_HEIGHT,
    HALF_WIDTH,
    INERTIA,
    ROD_ARM_1,
    ROD_ARM_2,
    ROD_FORCE,
    ROD_STIFFNESS,
    TOP_FORCE,
)

# The compiled helpers below are compiled without the Python entry numba makes for a
# function called from Python (no_cpython_wrapper, no_cfunc_wrapper): they are only called
# from compiled code, and that entry's code generation was a third of each helper's
# first compile (about 50 ms each, 1 s in all). Calling one from Python crashes; only
# `nystrom` (tested on its own) and the integrators keep theirs. Nor are they cached:
# numba caches the integrators whole, with every helper they call linked in. Nor do they
# use numba's reference counting (_nrt=False): they take numbers and tuples (one takes the
# integrator's info array, which its caller holds) and allocate nothing. forceinline is
# False so that a helper first compiled by one that LLVM must inline (the engine's
# step_events) does not inherit it. (options numba accepts beyond those its type stubs
# list: typed Any for mypy)
HELPER_OPTIONS: Any = {"no_cpython_wrapper": True, "no_cfunc_wrapper": True, "_nrt": False,
                       "forceinline": False, "error_model": ERROR_MODEL}
helper = njit(**HELPER_OPTIONS)

# Eq. (2-13)/(2-14) as the engine's own compiled helpers (the same Python functions as
# shaketable.models.rocking.physics', whose compiled versions keep their Python entry).
flight_acceleration = helper(dynamics.flight_acceleration.py_func)


@helper
def linear_flight_acceleration(theta, side, ug, vg, rg, parameters):
    """Slender-block linearisation (Eq. 2-4) about the corner ``side``, analytic in theta."""
    s = side
    b = parameters[HALF_WIDTH]
    h = parameters[HALF_HEIGHT]
    radius = math.sqrt(b * b + h * h)
    inertia = parameters[INERTIA]
    arm_1 = parameters[ROD_ARM_1]
    arm_2 = parameters[ROD_ARM_2]
    rods = (parameters[ROD_FORCE] * (arm_1 + arm_2)
            + parameters[ROD_STIFFNESS] * (arm_1 * arm_1 + arm_2 * arm_2) * s * theta)
    top = parameters[TOP_FORCE] * 2.0 * parameters[HALF_HEIGHT]
    return (radius * (ug - (G + vg) * (s * parameters[ALPHA] - theta)) - s * rods - top) / inertia - rg


@helper
def linear_acceleration(theta, side, ug, vg, rg, parameters):
    """Slender-block linearisation of Eq. (2-13)/(2-14) [rad/s^2] (Eq. 2-4) on the corner
    theta stands on (``side`` at theta = 0)."""
    s = side
    if theta > 0.0:
        s = 1.0
    elif theta < 0.0:
        s = -1.0
    return linear_flight_acceleration(theta, s, ug, vg, rg, parameters)


@helper
def angular_acceleration(theta, side, ug, vg, rg, parameters):
    """Eq. (2-13)/(2-14) on the corner the block stands on (as
    :func:`shaketable.models.rocking.physics.angular_acceleration`; ``side`` at theta = 0)."""
    s = side
    if theta > 0.0:
        s = 1.0
    elif theta < 0.0:
        s = -1.0
    return flight_acceleration(theta, s, ug, vg, rg, parameters)


@helper
def ground(segment, time):
    """Horizontal, vertical [m/s^2] and rotational [rad/s^2] table acceleration at ``time``."""
    fraction = (time - segment[0]) / segment[1]
    return (segment[2] + segment[3] * fraction, segment[4] + segment[5] * fraction,
            segment[6] + segment[7] * fraction)


@helper
def _stage(segment, side, parameters, time, x):
    """theta'' = f(time, x) of one Nystrom stage (a function called six times, not a
    closure that numba copies into each call)."""
    ug, vg, rg = ground(segment, time)
    return flight_acceleration(x, side, ug, vg, rg, parameters)


@helper
def nystrom_step(t, theta, omega, acceleration, side, h, segment, parameters):
    """One Runge-Kutta-Nystrom 6(4) step from a known theta''(t) = ``acceleration`` (k1).

    Eq. (2-13)/(2-14) is a special second-order equation, theta'' = f(t, theta)
    with no theta' term, which Nystrom formulas integrate directly: the pair
    RKN6(4)6FM of Dormand, El-Mikkawy and Prince (IMA J. Numer. Anal. 7 (1987)
    235-250) is of order 6 with an embedded order-4 estimate, and its sixth
    stage is f(t + h, theta_new), reused as the next step's first (five new
    evaluations per step against Dormand-Prince 5(4)'s six, at one order more).
    Stages: theta_i = theta + c_i h omega + h^2 sum_j a_ij k_j,
    k_i = f(t + c_i h, theta_i); theta_new = theta + h omega + h^2 sum b_i k_i,
    omega_new = omega + h sum b'_i k_i.

    Returns theta, omega and theta'' at ``t + h`` and the error estimates of
    theta and omega (main minus embedded formula).
    """
    k1 = acceleration
    hh = h * h
    k2 = _stage(segment, side, parameters, t + 0.1 * h,
                theta + 0.1 * h * omega + hh * (1.0 / 200.0) * k1)
    k3 = _stage(segment, side, parameters, t + 0.3 * h,
                theta + 0.3 * h * omega + hh * (-1.0 / 2200.0 * k1 + 1.0 / 22.0 * k2))
    k4 = _stage(segment, side, parameters, t + 0.7 * h, theta + 0.7 * h * omega
                + hh * (637.0 / 6600.0 * k1 - 7.0 / 110.0 * k2 + 7.0 / 33.0 * k3))
    k5 = _stage(segment, side, parameters, t + 0.68 * h, theta + 0.68 * h * omega
                + hh * (225437.0 / 1968750.0 * k1 - 30073.0 / 281250.0 * k2
                        + 65569.0 / 281250.0 * k3 - 9367.0 / 984375.0 * k4))
    theta_new = theta + h * omega + hh * (151.0 / 2142.0 * k1 + 5.0 / 116.0 * k2
                                          + 385.0 / 1368.0 * k3 + 55.0 / 168.0 * k4
                                          - 6250.0 / 28101.0 * k5)
    k6 = _stage(segment, side, parameters, t + h, theta_new)
    omega_new = omega + h * (151.0 / 2142.0 * k1 + 25.0 / 522.0 * k2 + 275.0 / 684.0 * k3
                             + 275.0 / 252.0 * k4 - 78125.0 / 112404.0 * k5 + 1.0 / 12.0 * k6)
    # main minus embedded weights (the embedded formula's are 1349/157500,
    # 7873/50000, 192199/900000, 521683/2100000, -16/125 for theta and 1349/157500,
    # 7873/45000, 27457/90000, 521683/630000, -2/5, 1/12 for omega)
    e1 = 151.0 / 2142.0 - 1349.0 / 157500.0
    error_theta = hh * (e1 * k1 + (5.0 / 116.0 - 7873.0 / 50000.0) * k2
                        + (385.0 / 1368.0 - 192199.0 / 900000.0) * k3
                        + (55.0 / 168.0 - 521683.0 / 2100000.0) * k4
                        + (-6250.0 / 28101.0 + 16.0 / 125.0) * k5)
    error_omega = h * (e1 * k1 + (25.0 / 522.0 - 7873.0 / 45000.0) * k2
                       + (275.0 / 684.0 - 27457.0 / 90000.0) * k3
                       + (275.0 / 252.0 - 521683.0 / 630000.0) * k4
                       + (-78125.0 / 112404.0 + 2.0 / 5.0) * k5)
    return theta_new, omega_new, k6, error_theta, error_omega


@helper
def heun(t, theta, omega, acceleration, side, h, segment, parameters):
    """The report's predictor-corrector step (Section 2.8): Euler predictor, trapezoidal corrector.

    ``acceleration`` is theta'' at the start; theta'' at the end is returned
    for the next step.
    """
    theta_predicted = theta + h * omega
    ug, vg, rg = ground(segment, t + h)
    acceleration_predicted = flight_acceleration(theta_predicted, side, ug, vg, rg, parameters)
    omega_new = omega + 0.5 * h * (acceleration + acceleration_predicted)
    theta_new = theta + 0.5 * h * (omega + omega_new)
    acceleration_new = flight_acceleration(theta_new, side, ug, vg, rg, parameters)
    return theta_new, omega_new, acceleration_new, 0.0, 0.0


@helper
def closed_form(t, theta, omega, acceleration, side, h, segment, parameters):
    """Exact solution of the linearised equation over a time ``h`` (METHOD_LINEAR).

    ``acceleration`` (theta'' at ``t``) is not used: the closed form needs none. It is an
    argument so that the three steppers are called alike.
    """
    span, du, v0, dv, dr = segment[1], segment[3], segment[4], segment[5], segment[7]
    b = parameters[HALF_WIDTH]
    hh = parameters[HALF_HEIGHT]
    radius = math.sqrt(b * b + hh * hh)
    inertia = parameters[INERTIA]
    q = radius / inertia  # = 3 / (4 R)
    s = side
    arm_1 = parameters[ROD_ARM_1]
    arm_2 = parameters[ROD_ARM_2]
    # held at its value at the middle of the step (not of the input interval): as
    # h -> 0 the closed form's theta'' tends to the model's at t, so a start of
    # rocking found with v(t) never turns into an impact at zero elapsed time
    # (which looped forever when v changed fast near -g)
    vertical = v0 + dv * ((t - segment[0]) + 0.5 * h) / span
    mu = q * (G + vertical) - parameters[ROD_STIFFNESS] * (arm_1 * arm_1 + arm_2 * arm_2) / inertia
    ug_here, _, rg_here = ground(segment, t)
    c0 = (q * ug_here - q * (G + vertical) * s * parameters[ALPHA]
          - s * parameters[ROD_FORCE] * (arm_1 + arm_2) / inertia
          - parameters[TOP_FORCE] * 2.0 * hh / inertia - rg_here)
    c1 = q * du / span - dr / span
    if abs(mu) * h * h < 1e-12:
        theta_new = theta + omega * h + c0 * h * h / 2.0 + c1 * h * h * h / 6.0 + mu * theta * h * h / 2.0
        omega_new = omega + c0 * h + c1 * h * h / 2.0 + mu * theta * h
    else:
        particular = -c0 / mu
        particular_rate = -c1 / mu
        a = theta - particular
        if mu > 0.0:
            lam = math.sqrt(mu)
            bb = (omega - particular_rate) / lam
            ch = math.cosh(lam * h)
            sh = math.sinh(lam * h)
            theta_new = a * ch + bb * sh + particular + particular_rate * h
            omega_new = lam * (a * sh + bb * ch) + particular_rate
        else:
            lam = math.sqrt(-mu)
            bb = (omega - particular_rate) / lam
            co = math.cos(lam * h)
            si = math.sin(lam * h)
            theta_new = a * co + bb * si + particular + particular_rate * h
            omega_new = lam * (-a * si + bb * co) + particular_rate
    # theta'' = mu theta + c0 + c1 tau exactly along the closed form
    return theta_new, omega_new, mu * theta_new + c0 + c1 * h, 0.0, 0.0


#: Each method's functions, under the names the engine's driver calls them by:
#: ``model_acceleration`` (theta'' of the model on the corner theta stands on),
#: ``flight_model`` (theta'' of the flight model about a given corner, analytic in theta)
#: and ``advance`` (one step: theta, theta', theta'' at ``t + h`` and two error estimates).
METHOD_FUNCTIONS = {
    METHOD_FAST: {"model_acceleration": angular_acceleration,
                  "flight_model": flight_acceleration, "advance": nystrom_step},
    METHOD_PREDICTOR_CORRECTOR: {"model_acceleration": angular_acceleration,
                                 "flight_model": flight_acceleration, "advance": heun},
    METHOD_LINEAR: {"model_acceleration": linear_acceleration,
                    "flight_model": linear_flight_acceleration, "advance": closed_form},
}


@njit(cache=True, error_model=ERROR_MODEL)  # with its Python entry: tests/models/rocking/test_engine.py calls it
def nystrom(t, theta, omega, k1, side, h, segment, parameters):
    """One Runge-Kutta-Nystrom 6(4) step (:func:`nystrom_step`) from theta''(t) = ``k1``."""
    return nystrom_step(t, theta, omega, k1, side, h, segment, parameters)
