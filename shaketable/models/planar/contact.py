"""Contact mechanics of the planar block for the reference solver (Newton-Euler, numpy).

Per unit mass, table frame, the conventions of ``docs/planar.md``. In each
mode the accelerations (x'', y'', theta'') and the contact force (F, N) come from one
small linear system (``numpy.linalg.solve``): the Newton-Euler equations
M q'' = f + W lambda, M = diag(1, 1, Ic), f = (-ug, -(g + vg), 0), with the contact
constraints written on accelerations. The impact map is the same kind of linear system
for the impulse. See :mod:`shaketable.models.planar.reference` for the solver.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.models.planar.shenton import FLIGHT, REST, ROCK, SLIDE, SLIDE_ROCK


class PlanarGeometry:
    """b, h [m], Ic, I0 [m^2] per mass, alpha [rad], Housner's c_H [-]."""

    def __init__(self, block: Block | AsymmetricBlock):
        if isinstance(block, AsymmetricBlock):
            # each pivot's b and alpha, the centroidal k^2, Housner's ratio of an impact
            # onto each pivot (b, alpha, c_housner: the weaker side's, for scales)
            self.h, self.b_plus, self.b_minus = block.h, block.b_plus, block.b_minus
            self.Ic = block.k_squared
            self.alpha_plus, self.alpha_minus = block.alpha_plus, block.alpha_minus
            self.c_plus, self.c_minus = block.housner_cor(1.0), block.housner_cor(-1.0)
            self.b, self.alpha = min(self.b_plus, self.b_minus), block.alpha
            self.c_housner = min(self.c_plus, self.c_minus)
            self.I0 = self.Ic + self.b ** 2 + self.h ** 2
            return
        self.b, self.h = block.b, block.h
        self.Ic = (self.b ** 2 + self.h ** 2) / 3.0
        self.I0 = 4.0 * self.Ic
        self.alpha = block.alpha
        self.c_housner = 1.0 - 1.5 * math.sin(self.alpha) ** 2
        self.b_plus = self.b_minus = self.b
        self.alpha_plus = self.alpha_minus = self.alpha
        self.c_plus = self.c_minus = self.c_housner

    def b_of(self, side):
        """b_s [m]: centre to the bottom corner of ``side`` horizontally."""
        return self.b_plus if side > 0 else self.b_minus

    def alpha_of(self, side):
        """alpha_s [rad] of the pivot ``side``."""
        return self.alpha_plus if side > 0 else self.alpha_minus

    def c_of(self, onto):
        """Housner's ratio c_H of a rock-to-rock impact onto the pivot ``onto`` [-]."""
        return self.c_plus if onto > 0 else self.c_minus

    def arm(self, side, theta):
        """(r_x, r_y): centre to the bottom corner ``side`` [m]."""
        c, s = math.cos(theta), math.sin(theta)
        b = self.b_of(side)
        return -side * b * c + self.h * s, -side * b * s - self.h * c


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


def frame_momentum(geometry, state, corner):
    """H_k' [m^2/s]: the angular momentum about the striking corner in the frame moving with
    the corner's incoming slip u = x' - r_y theta' (independent of a uniform sliding speed):
    (Ic + r_y^2) theta' - r_x y'."""
    r_x, r_y = geometry.arm(corner, state[2])
    return (geometry.Ic + r_y * r_y) * state[5] - r_x * state[4]


def impact_map(geometry, state, corner, rho, mu_s, mu_d):
    """Post-impact velocities of a corner impact (docs/planar.md, "Impacts").

    Solves, for (x'+, y'+, theta'+, P_x, P_y), the 5 x 5 linear system of the
    impulse-momentum balance with the couple C = (rho - 1) H_k' (:func:`frame_momentum`),
    the plastic normal condition Y_k'+ = 0, and either X_k'+ = 0 (sticking, tried first,
    accepted if P_y > 0 and |P_x| <= mu_s P_y) or P_x = -sigma mu_d P_y (slipping,
    sigma = -sign of the sticking P_x, accepted if X_k'+ has the sign sigma; else the
    other sigma; if neither is consistent the corner sticks). If the kinetic energy grows
    or the normal impulse pulls (P_y < 0), rho is moved toward 1 until neither happens
    (the branch decided again at the new rho).

    Returns
    -------
    (velocities, impulse, sigma, capped)
        ``velocities`` (x'+, y'+, theta'+); ``sigma`` 0 for a sticking impact;
        ``capped`` whether rho was moved toward 1 (a gain of more than 1e-12 of the
        kinetic energy, or a pull).
    """
    x, y, theta, x_dot, y_dot, omega = state[:6]
    r_x, r_y = geometry.arm(corner, theta)
    angular_momentum = frame_momentum(geometry, state, corner)

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

    # the kinetic energy in the table's frame and in the frame moving with the corner's
    # incoming slip u (where the couple is defined): the law gains in neither
    slip = x_dot - r_y * omega
    frames = [(0.0, kinetic_energy(geometry, state)),
              (slip, kinetic_energy(geometry, np.r_[0, 0, 0, x_dot - slip, y_dot, omega]))]
    weight = np.array([1.0, 1.0, math.sqrt(geometry.Ic)])

    def gains(post):
        return [kinetic_energy(geometry, np.r_[0, 0, 0, post[0] - shift, post[1:3]]) - before
                for shift, before in frames]

    rho_eff = rho
    post, sigma = decide(rho_eff)
    capped = False
    for _ in range(8):
        gain = gains(post)
        if rho_eff == 1.0 or (max(gain) <= 0.0 and post[4] >= 0.0):
            break
        capped = capped or post[4] < 0.0 or any(
            g > 1e-12 * before for g, (_, before) in zip(gain, frames))
        # the post state is affine in rho (in one branch): the rho_eff nearest rho between
        # 1 and rho with no gain in either frame and P_y >= 0; then the branch is decided
        # again there
        one = solve(1.0, sigma)
        fraction = 1.0
        for shift, before in frames:
            base = (one[:3] - [shift, 0.0, 0.0]) * weight
            step = (post[:3] - one[:3]) * weight
            qa, qb, qc = step @ step, 2.0 * base @ step, base @ base - 2.0 * before
            root = 0.0
            if qa > 0.0 and qc <= 0.0:
                root = (-qb + math.sqrt(max(qb * qb - 4 * qa * qc, 0.0))) / (2 * qa)
            fraction = min(fraction, min(max(root, 0.0), 1.0))
        if post[4] < 0.0:
            fraction = min(fraction, max(one[4], 0.0) / (one[4] - post[4]))
        rho_eff = 1.0 + fraction * (rho_eff - 1.0)
        post, sigma = decide(rho_eff)
    return post[:3], post[3:], sigma, capped


def two_corner_impact(geometry, state, mu_s, mu_d):
    """Plastic impact at theta = 0 with both bottom corners on the table (docs/planar.md,
    "Both corners on the table").

    The cases of the two-corner problem (normal impulses P_s >= 0 with gap rates
    Y_s'+ >= 0, complementary; Coulomb friction on the base's common slip) are tried in
    order, each a linear solve: the base lands flat and sticks, lands flat and slips, or
    one corner s pushes alone (:func:`impact_map` at rho = 1) while the other rises.

    Returns
    -------
    (velocities, mode, side, sigma)
        ``mode`` REST, SLIDE, ROCK or SLIDE_ROCK; ``side`` the corner the block turns on
        (0 when flat); ``sigma`` the slip direction (0 when sticking).
    """
    x_dot, y_dot, omega = state[3:6]
    arms = [geometry.arm(corner, 0.0) for corner in (1, -1)]

    def flat(sigma):
        # unknowns x'+, y'+, theta'+, F, P_+, P_-
        (r1x, r_y), (r2x, _) = arms
        matrix = np.array([[1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
                           [0.0, 1.0, 0.0, 0.0, -1.0, -1.0],
                           [0.0, 0.0, geometry.Ic, r_y, -r1x, -r2x],
                           [0.0, 1.0, r1x, 0.0, 0.0, 0.0],
                           [0.0, 1.0, r2x, 0.0, 0.0, 0.0],
                           [1.0, 0.0, -r_y, 0.0, 0.0, 0.0] if sigma == 0 else
                           [0.0, 0.0, 0.0, 1.0, sigma * mu_d, sigma * mu_d]])
        return np.linalg.solve(matrix, np.array([x_dot, y_dot, geometry.Ic * omega, 0.0, 0.0,
                                                 0.0]))

    stick = flat(0)
    if stick[4] >= 0.0 and stick[5] >= 0.0 and abs(stick[3]) <= mu_s * (stick[4] + stick[5]):
        return np.array([0.0, 0.0, 0.0]), REST, 0, 0
    sigma = 1 if x_dot > 0.0 else -1
    slip = flat(sigma)
    if slip[4] >= 0.0 and slip[5] >= 0.0 and sigma * slip[0] > 0.0:
        return np.array([slip[0], 0.0, 0.0]), SLIDE, 0, sigma
    for corner, (r_x, _) in zip((1, -1), arms):
        if y_dot + r_x * omega >= 0.0:
            continue
        velocities, impulse, slip_sigma, _ = impact_map(geometry, state, corner, 1.0, mu_s, mu_d)
        if impulse[1] >= 0.0 and corner * velocities[2] >= 0.0:
            return velocities, (ROCK if slip_sigma == 0 else SLIDE_ROCK), corner, slip_sigma
    total = max(-y_dot, 0.0)
    if abs(x_dot) <= mu_s * total:
        return np.array([0.0, 0.0, 0.0]), REST, 0, 0
    return np.array([x_dot - sigma * mu_d * total, 0.0, 0.0]), SLIDE, 0, sigma
