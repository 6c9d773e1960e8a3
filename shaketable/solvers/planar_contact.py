"""Contact mechanics of the planar block for the reference solver (Newton-Euler, numpy).

Per unit mass, table frame, the conventions of ``docs/planar.md``. In each
mode the accelerations (x'', y'', theta'') and the contact force (F, N) come from one
small linear system (``numpy.linalg.solve``): the Newton-Euler equations
M q'' = f + W lambda, M = diag(1, 1, Ic), f = (-ug, -(g + vg), 0), with the contact
constraints written on accelerations. The impact map is the same kind of linear system
for the impulse. See :mod:`shaketable.solvers.planar_reference` for the solver.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.shenton import FLIGHT, ROCK, SLIDE, SLIDE_ROCK


class PlanarGeometry:
    """b, h [m], Ic, I0 [m^2] per mass, alpha [rad], Housner's c_H [-]."""

    def __init__(self, block: Block):
        self.b, self.h = block.b, block.h
        self.Ic = (self.b ** 2 + self.h ** 2) / 3.0
        self.I0 = 4.0 * self.Ic
        self.alpha = block.alpha
        self.c_housner = 1.0 - 1.5 * math.sin(self.alpha) ** 2

    def arm(self, side, theta):
        """(r_x, r_y): centre to the bottom corner ``side`` [m]."""
        c, s = math.cos(theta), math.sin(theta)
        return -side * self.b * c + self.h * s, -side * self.b * s - self.h * c


def rock_solution(geometry, side, theta, omega, ug, vg):
    """ROCK about corner ``side``: (x'', y'', theta'', F, N) from the 5 x 5 Newton-Euler system."""
    r_x, r_y = geometry.arm(side, theta)
    matrix = np.array([[1.0, 0.0, 0.0, -1.0, 0.0],
                       [0.0, 1.0, 0.0, 0.0, -1.0],
                       [0.0, 0.0, geometry.Ic, r_y, -r_x],
                       [1.0, 0.0, -r_y, 0.0, 0.0],
                       [0.0, 1.0, r_x, 0.0, 0.0]])
    rhs = np.array([-ug, -(G + vg), 0.0, r_x * omega * omega, r_y * omega * omega])
    return np.linalg.solve(matrix, rhs)


def slide_rock_effective_mass(geometry, side, sigma, theta, mu_d):
    """Normal 'effective mass' 1 + r_x (r_x + sigma mu_d r_y) / Ic [-]; <= 0: Painleve."""
    r_x, r_y = geometry.arm(side, theta)
    return 1.0 + r_x * (r_x + sigma * mu_d * r_y) / geometry.Ic


def slide_rock_solution(geometry, side, sigma, theta, omega, ug, vg, mu_d):
    """SLIDE_ROCK about ``side`` slipping ``sigma``: (x'', y'', theta'', F, N), 4 x 4 system."""
    r_x, r_y = geometry.arm(side, theta)
    matrix = np.array([[1.0, 0.0, 0.0, sigma * mu_d],
                       [0.0, 1.0, 0.0, -1.0],
                       [0.0, 0.0, geometry.Ic, -(r_x + sigma * mu_d * r_y)],
                       [0.0, 1.0, r_x, 0.0]])
    rhs = np.array([-ug, -(G + vg), 0.0, r_y * omega * omega])
    xdd, ydd, thdd, normal = np.linalg.solve(matrix, rhs)
    return np.array([xdd, ydd, thdd, -sigma * mu_d * normal, normal])


def mode_solution(geometry, mode, side, sigma, theta, omega, ug, vg, mu_d):
    """(x'', y'', theta'', F, N) of any mode [m/s^2, rad/s^2, m/s^2]."""
    if mode == ROCK:
        return rock_solution(geometry, side, theta, omega, ug, vg)
    if mode == SLIDE_ROCK:
        return slide_rock_solution(geometry, side, sigma, theta, omega, ug, vg, mu_d)
    if mode == SLIDE:
        normal = G + vg
        return np.array([-ug - sigma * mu_d * normal, 0.0, 0.0, -sigma * mu_d * normal, normal])
    if mode == FLIGHT:
        return np.array([-ug, -(G + vg), 0.0, 0.0, 0.0])
    return np.array([0.0, 0.0, 0.0, ug, G + vg])


def kinetic_energy(geometry, state) -> float:
    """0.5 (x'^2 + y'^2 + Ic theta'^2) per mass [J/kg]."""
    return 0.5 * (state[3] ** 2 + state[4] ** 2 + geometry.Ic * state[5] ** 2)


def impact_map(geometry, state, corner, rho, mu_s, mu_d):
    """Post-impact velocities of a corner impact (spec, "Impacts").

    Solves, for (x'+, y'+, theta'+, P_x, P_y), the 5 x 5 linear system of the
    impulse-momentum balance with the couple C = (rho - 1) H_k, the plastic
    normal condition Y_k'+ = 0, and either X_k'+ = 0 (sticking, tried first,
    accepted if P_y > 0 and |P_x| <= mu_s P_y) or P_x = -sigma mu_d P_y
    (slipping, sigma = -sign of the sticking P_x, accepted if X_k'+ has the sign
    sigma; else the other sigma; if neither is consistent the corner sticks).
    If the kinetic energy grows, rho is moved toward 1 until it does not (the
    branch decided again at the new rho).

    Returns
    -------
    (velocities, impulse, sigma, capped)
        ``velocities`` (x'+, y'+, theta'+); ``sigma`` 0 for a sticking impact;
        ``capped`` whether rho was moved toward 1 so that kinetic energy does not grow.
    """
    x, y, theta, x_dot, y_dot, omega = state[:6]
    r_x, r_y = geometry.arm(corner, theta)
    angular_momentum = geometry.Ic * omega - r_x * y_dot + r_y * x_dot

    def solve(rho_value, sigma):
        couple = (rho_value - 1.0) * angular_momentum
        matrix = np.array([[1.0, 0.0, 0.0, -1.0, 0.0],
                           [0.0, 1.0, 0.0, 0.0, -1.0],
                           [0.0, 0.0, geometry.Ic, r_y, -r_x],
                           [1.0, 0.0, -r_y, 0.0, 0.0] if sigma == 0 else
                           [0.0, 0.0, 0.0, 1.0, sigma * mu_d],
                           [0.0, 1.0, r_x, 0.0, 0.0]])
        rhs = np.array([x_dot, y_dot, geometry.Ic * omega + couple, 0.0, 0.0])
        return np.linalg.solve(matrix, rhs)

    def decide(rho_value):
        """The branch at rho_value: stick if it can; else slip the way the corner goes."""
        stick = solve(rho_value, 0)
        if stick[4] > 0.0 and abs(stick[3]) <= mu_s * stick[4]:
            return stick, 0
        first = -1 if stick[3] > 0.0 else 1
        for sigma in (first, -first):
            slipping = solve(rho_value, sigma)
            if sigma * (slipping[0] - r_y * slipping[2]) >= 0.0:
                return slipping, sigma
        return stick, 0  # no slip direction is consistent: the corner sticks

    before = kinetic_energy(geometry, state)
    rho_eff = rho
    post, sigma = decide(rho_eff)
    capped = False
    for _ in range(8):
        if rho_eff == 1.0 or kinetic_energy(geometry, np.r_[0, 0, 0, post[:3]]) <= before:
            break
        # the post state is affine in rho (in one branch): the rho_eff nearest rho between
        # 1 and rho with KE+ = KE- (the spec's rule for rho > 1; extended here to rho < 1,
        # where the couple can add energy too: DISAGREEMENTS.md); then the branch is
        # decided again at rho_eff
        one = solve(1.0, sigma)
        weight = np.array([1.0, 1.0, math.sqrt(geometry.Ic)])
        base, step = one[:3] * weight, (post[:3] - one[:3]) * weight
        qa, qb, qc = step @ step, 2.0 * base @ step, base @ base - 2.0 * before
        fraction = 0.0
        if qa > 0.0 and qc <= 0.0:
            root = (-qb + math.sqrt(max(qb * qb - 4 * qa * qc, 0.0))) / (2 * qa)
            fraction = min(max(root, 0.0), 1.0)
        rho_eff = 1.0 + fraction * (rho_eff - 1.0)
        post, sigma = decide(rho_eff)
        capped = True
    return post[:3], post[3:], sigma, capped
