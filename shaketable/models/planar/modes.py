"""Helpers of the planar engine (:mod:`shaketable.models.planar.engine`), compiled with numba:
the two state representations, the rest conditions and their first failure, the checks of
a block entering a contact mode, the measured quantities (slip, corner excursions) and the
Hermite estimate that decides whether an extremum is worth locating.
"""

from __future__ import annotations

import math

from numba import njit

from shaketable.core.constants import G
from shaketable.models.planar.physics import (
    FLIGHT,
    HELPER,
    INCONSISTENT,
    PAINLEVE,
    REST,
    ROCK,
    SLIDE,
    SLIDE_ROCK,
    corner_vector,
    half_width,
    impact,
    kinetic_energy,
    pivot_acceleration,
    rock_forces,
    slide_rock_accelerations,
    two_corner_impact,
)
from shaketable.models.planar.steps import ground
from shaketable.models.rocking.physics import (
    ASYMMETRIC,
    ERROR_MODEL,
    HALF_HEIGHT,
    HALF_WIDTH,
    HALF_WIDTH_MINUS,
    RHO_MINUS,
    RHO_PLUS,
)

#: Columns of the engine's output rows (x, y, theta, x', y', theta', slip, mode).
OUT_X, OUT_Y, OUT_THETA, OUT_X_DOT, OUT_Y_DOT, OUT_OMEGA, OUT_SLIP, OUT_MODE = range(8)
N_OUT = 8


@njit(**HELPER)
def z_from_q(q, side, z, parameters):
    """Contact-mode state z from the full state q = (x, y, theta, x', y', theta')."""
    r_x, r_y = corner_vector(q[2], side, parameters)
    z[0] = q[2]
    z[1] = q[5]
    z[2] = q[0] + r_x
    z[3] = q[3] - r_y * q[5]
    z[4] = 0.0
    z[5] = 0.0


@njit(**HELPER)
def q_from_z(z, side, q, parameters):
    """Full state q from a contact-mode state z (the corner on the table)."""
    r_x, r_y = corner_vector(z[0], side, parameters)
    q[0] = z[2] - r_x
    q[1] = -r_y
    q[2] = z[0]
    q[3] = z[3] + r_y * z[1]
    q[4] = -r_x * z[1]
    q[5] = z[1]


@njit(**HELPER)
def measures(q, parameters):
    """Slip of the base midpoint [m], the largest corner excursion |X - X_rest| [m] and
    the base's slide [m]: the displacement of the bottom corner the block stands or turns
    on (on theta's side; x when flat), x + h sin(theta) + sign(theta) b (1 - cos(theta)),
    0 for a block that rocks without sliding."""
    h = parameters[HALF_HEIGHT]
    cosine = math.cos(q[2])
    sine = math.sin(q[2])
    slip = q[0] + h * sine
    largest = 0.0
    for u in (-parameters[HALF_WIDTH], parameters[HALF_WIDTH_MINUS]):
        for w in (-h, h):
            excursion = abs(q[0] + u * cosine - w * sine - u)
            if excursion > largest:
                largest = excursion
    if q[2] == 0.0:
        return slip, largest, slip
    b = half_width(1.0 if q[2] > 0.0 else -1.0, parameters)
    base = slip + math.copysign(b * (1.0 - cosine), q[2])
    return slip, largest, base


@njit(**HELPER)
def rest_margin(condition, ug, vg, mu_s, parameters):
    """Margin of a rest condition, positive when it fails: 0 lift-off, 1/2 slip toward
    -/+x driven by ug > 0 / < 0, 3/4 tipping onto side +1 / -1 (the rocking engine's test)."""
    if condition == 0:
        return -(G + vg)
    if condition == 1:
        return ug - mu_s * (G + vg)
    if condition == 2:
        return -ug - mu_s * (G + vg)
    if condition == 3:
        return pivot_acceleration(0.0, 1.0, ug, vg, parameters)
    return -pivot_acceleration(0.0, -1.0, ug, vg, parameters)


@njit(**HELPER)
def first_failure(t, t_end, segment, mu_s, parameters):
    """First time in [t, t_end] at which a rest condition fails strictly [s]; inf if none.

    Each margin is affine in time: the crossing by linear interpolation, then (as the
    rocking engine's start of rocking) bisection to the first representable time with a
    positive margin.
    """
    ua, va = ground(segment, t)
    ub, vb = ground(segment, t_end)
    best = math.inf
    for condition in range(5):
        margin_a = rest_margin(condition, ua, va, mu_s, parameters)
        margin_b = rest_margin(condition, ub, vb, mu_s, parameters)
        if margin_a > 0.0:
            candidate = t
        elif margin_b > 0.0:
            candidate = t + (t_end - t) * (-margin_a) / (margin_b - margin_a)
            uc, vc = ground(segment, candidate)
            if not rest_margin(condition, uc, vc, mu_s, parameters) > 0.0:
                low = candidate
                high = t_end
                for _ in range(200):
                    middle = 0.5 * (low + high)
                    if middle <= low or middle >= high:
                        break
                    um, vm = ground(segment, middle)
                    if rest_margin(condition, um, vm, mu_s, parameters) > 0.0:
                        high = middle
                    else:
                        low = middle
                candidate = high
        else:
            continue
        if candidate < best:
            best = candidate
    return best


@njit(cache=True, error_model=ERROR_MODEL)
def enter_contact(mode, side, sigma, t, q, segment, mu_s, mu_d, parameters):
    """The mode a block entering ROCK or SLIDE_ROCK about ``side`` (state q) is really in.

    SLIDE_ROCK with D <= 0: PAINLEVE; N <= 0: FLIGHT (ROCK: only if the corner's free
    acceleration leaves the table, else SLIDE_ROCK with sigma = -sign(F)); a flat block
    at rest (theta = theta' = 0) that does not tip onto ``side``: REST (or SLIDE from
    SLIDE_ROCK, unless mu_d > b/h: INCONSISTENT); ROCK needing |F| > mu_s N: SLIDE_ROCK
    with sigma = -sign(F) (checked again). Returns (mode, sigma).
    """
    if mode == REST or mode == SLIDE:
        return mode, sigma   # flat after a two-corner impact: the rest rules decide
    ug, vg = ground(segment, t)
    for _ in range(4):
        if mode == ROCK:
            acceleration, _, _, friction, normal = rock_forces(q[2], q[5], side, ug, vg,
                                                               parameters)
        else:
            acceleration, _, friction, normal, d = slide_rock_accelerations(
                q[2], q[5], side, sigma, mu_d, ug, vg, parameters)
            if not d > 0.0:
                return PAINLEVE, sigma
        if normal <= 0.0:
            # the held corner would have to pull: it flies only if its free acceleration
            # leaves the table, Y_s'' = -(g + vg) - r_y theta'^2 >= 0; otherwise it slips
            # (SLIDE_ROCK's N = -Y_s'' Ic / D > 0; docs/planar.md, "Entering a contact")
            _, r_y = corner_vector(q[2], side, parameters)
            if mode == ROCK and G + vg + r_y * q[5] * q[5] > 0.0:
                mode = SLIDE_ROCK
                sigma = -1.0 if friction > 0.0 else 1.0
                continue
            return FLIGHT, sigma
        if q[2] == 0.0 and q[5] == 0.0 and side * acceleration <= 0.0:
            if mode == SLIDE_ROCK:
                if mu_d > half_width(-sigma, parameters) / parameters[HALF_HEIGHT]:
                    return INCONSISTENT, sigma
                return SLIDE, sigma
            return REST, sigma
        if mode == ROCK and abs(friction) > mu_s * normal:
            mode = SLIDE_ROCK
            sigma = -1.0 if friction > 0.0 else 1.0
            continue
        break
    return mode, sigma


@njit(**HELPER)
def quantity(which, q, parameters):
    """The slip (``which`` 0) or the excursion X - X_rest of corner ``which`` (1..4, the
    order of :func:`~shaketable.models.planar.steps.horizontal_rate`) [m]."""
    h = parameters[HALF_HEIGHT]
    if which == 0:
        return q[0] + h * math.sin(q[2])
    u = -parameters[HALF_WIDTH] if which == 1 or which == 3 else parameters[HALF_WIDTH_MINUS]
    w = -h if which <= 2 else h
    return q[0] + u * math.cos(q[2]) - w * math.sin(q[2]) - u


@njit(**HELPER)
def hermite_peak(value0, value1, rate0, rate1, span):
    """Largest |H| at the interior turning points of the cubic Hermite interpolant of
    (value, rate) at both ends of a step of length ``span`` (0 if none)."""
    v0 = rate0 * span
    v1 = rate1 * span
    c2 = 3.0 * (value1 - value0) - 2.0 * v0 - v1
    c3 = 2.0 * (value0 - value1) + v0 + v1
    largest = 0.0
    if c3 == 0.0:
        if c2 != 0.0:
            root = -v0 / (2.0 * c2)
            if 0.0 < root < 1.0:
                largest = abs(value0 + root * (v0 + root * c2))
        return largest
    discriminant = c2 * c2 - 3.0 * c3 * v0
    if discriminant < 0.0:
        return largest
    square_root = math.sqrt(discriminant)
    for root in ((-c2 - square_root) / (3.0 * c3), (-c2 + square_root) / (3.0 * c3)):
        if 0.0 < root < 1.0:
            largest = max(largest, abs(value0 + root * (v0 + root * (c2 + root * c3))))
    return largest


@njit(**HELPER)
def store(out, row, q, slip, mode):
    for i in range(6):
        out[row, i] = q[i]
    out[row, OUT_SLIP] = slip
    out[row, OUT_MODE] = mode


@njit(**HELPER)
def flat(q, x_dot, parameters):
    q[1] = parameters[HALF_HEIGHT]
    q[2] = 0.0
    q[3] = x_dot
    q[4] = 0.0
    q[5] = 0.0


@njit(**HELPER)
def strike(q, striking, rho, mu_s, mu_d, parameters):
    """The impact of a block whose corner ``striking`` reaches the table (state q, whose
    velocities are replaced; docs/planar.md, "Impacts").

    A flat landing (theta = theta' = 0) is the two-corner problem
    (:func:`~shaketable.models.planar.physics.two_corner_impact`). Otherwise the corner is
    put on the table and struck (:func:`~shaketable.models.planar.physics.impact`); at
    theta = 0, where the other corner is on the table too, an impact that turns the block
    back onto that corner (striking * theta'+ < 0: it would enter the table) is followed
    at once by the two-corner problem from the state it left.

    Returns (mode after: ROCK, SLIDE_ROCK, REST, SLIDE or PAINLEVE, side of the corner
    the block turns on, slip direction sigma, kinetic energy lost [m^2/s^2], capped).
    """
    before = kinetic_energy(q[3], q[4], q[5], parameters)
    side = striking
    capped = 0.0
    if q[2] == 0.0 and q[5] == 0.0:
        x_dot, y_dot, omega, kind, pivot, sigma = two_corner_impact(q[3], q[4], 0.0, mu_s,
                                                                    mu_d, parameters)
        side = pivot if pivot != 0.0 else side
    else:
        _, r_y = corner_vector(q[2], striking, parameters)
        q[1] = -r_y   # the corner on the table (its root is located to the ulp)
        if parameters[ASYMMETRIC] != 0.0:   # the couple ratio of an impact onto that pivot
            rho = parameters[RHO_PLUS] if striking > 0.0 else parameters[RHO_MINUS]
        x_dot, y_dot, omega, kind, sigma, _, capped = impact(
            q[2], q[3], q[4], q[5], striking, rho, mu_s, mu_d, parameters)
        if kind != PAINLEVE and q[2] == 0.0 and striking * omega < 0.0:
            x_dot, y_dot, omega, kind, pivot, sigma = two_corner_impact(
                x_dot, y_dot, omega, mu_s, mu_d, parameters)
            side = pivot if pivot != 0.0 else side
    if kind == PAINLEVE:
        return kind, side, sigma, 0.0, capped
    if kind == REST or kind == SLIDE:
        flat(q, x_dot, parameters)
    else:
        q[3], q[4], q[5] = x_dot, y_dot, omega
    return kind, side, sigma, before - kinetic_energy(q[3], q[4], q[5], parameters), capped
