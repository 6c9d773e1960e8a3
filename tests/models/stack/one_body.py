"""Independent statements shared by the stack tests: a two-block stack as one rigid body and
the first base impact of a column rocking as one rigid body, and every pattern of a chain against the full-coordinate
Newton-Euler equations."""

from __future__ import annotations

import itertools
import math

import numpy as np
from scipy.integrate import quad

from shaketable.core.constants import G
from shaketable.models.stack.physics import Chain, state_forces
from shaketable.models.stack.reference import newton_euler


def rigid_pair(b1, h1, b2, h2, m1, m2, e=0.0):
    """A two-block stack (half sizes, masses, the top's offset ``e`` [m]) rocking as one
    rigid body about the bottom block's base corner: its mass M, the centre of mass
    (x_c, y_c) from that corner, R = |(x_c, y_c)|, alpha = atan(x_c / y_c) and
    I_O = (4/3) m1 (b1^2 + h1^2) + m2 [(b2^2 + h2^2)/3 + (b1 + e)^2 + (2 h1 + h2)^2]
    (the issue's check 2; e = 0 for a centred stack)."""
    mass = m1 + m2
    x_c = b1 + m2 * e / mass
    y_c = (m1 * h1 + m2 * (2 * h1 + h2)) / mass
    inertia = 4 / 3 * m1 * (b1 ** 2 + h1 ** 2) + m2 * ((b2 ** 2 + h2 ** 2) / 3 + (b1 + e) ** 2
                                                       + (2 * h1 + h2) ** 2)
    return mass, x_c, y_c, math.hypot(x_c, y_c), math.atan(x_c / y_c), inertia


def first_base_impact(mass, radius, alpha, inertia, theta0):
    """The time [s] and the rate [rad/s] at which a rigid body released from rest at
    ``theta0`` on its base corner reaches theta = 0: theta'' = -(M g R / I_O)
    sin(alpha - theta), the time the quadrature of the energy integral, the rate its closed
    form (``radius`` R and ``alpha`` of the centre of mass from the pivot, ``inertia`` I_O
    about it)."""
    k = 2 * mass * G * radius / inertia
    # theta = theta0 - s^2 removes the integrable singularity at the start
    integrand = lambda s: 2 * s / math.sqrt(k * (math.cos(alpha - theta0)  # noqa: E731
                                                 - math.cos(alpha - theta0 + s * s)))
    fall, _ = quad(integrand, 0.0, math.sqrt(theta0), epsabs=0, epsrel=1e-13, limit=200)
    return fall, -math.sqrt(k * (math.cos(alpha - theta0) - math.cos(alpha)))


def assert_every_pattern_is_newton_euler(rng, b, h, m, e=None):
    """The reduced M(q) q'' = f of each pattern of the chain (b, h, m, offsets e) against
    the Newton-Euler equations with the contact forces as unknowns
    (models/stack/reference.py), at random states and table accelerations from ``rng``:
    theta'' to 1e-11 rad/s^2, the contact forces to 1e-11 of the weight."""
    n = len(b)
    chain = Chain(b, h, m, e)
    for pattern in itertools.product((0, 1, -1), repeat=n):
        phi = np.array([s * rng.uniform(0.01, 0.3) for s in pattern])
        rate = np.array([rng.normal() if s else 0.0 for s in pattern])
        ug, vg = 3.0 * rng.normal(), rng.normal()
        phi_ddot, forces = state_forces(chain, phi, rate, pattern, ug, vg)
        theta_ddot, reference = newton_euler(b, h, m, np.cumsum(phi), np.cumsum(rate), pattern,
                                             ug, vg, e)
        assert np.abs(np.cumsum(phi_ddot) - theta_ddot).max() < 1e-11
        assert np.abs(forces - reference).max() < 1e-11 * G * m.sum()
