"""Closed forms of Sections 2.2-2.4 of the report and exact counterparts.

These are the analytic curves of Figs. 2.3-2.6 (slender-block approximations)
and the exact results they approximate, used to check the solvers.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad

from .constants import G
from .geometry import Block


def housner_period(block: Block, amplitude: float) -> float:
    """Free-rocking period of a slender block, Eq. (2-5) [s].

    T = (4/p) arccosh(1 / (1 - theta0/alpha)).

    Parameters
    ----------
    block : Block
    amplitude : float
        Rocking amplitude theta0 [rad], 0 < theta0 < alpha.
    """
    ratio = amplitude / block.alpha
    if not 0 < ratio < 1:
        raise ValueError(f"amplitude must be between 0 and alpha ({block.alpha:.4g} rad), "
                         f"got {amplitude!r}")
    return 4.0 / block.p * math.acosh(1.0 / (1.0 - ratio))


def exact_period(block: Block, amplitude: float) -> float:
    """Free-rocking period of Eq. (2-3) without the slender approximation [s].

    Energy conservation gives theta'^2 = 2 p^2 (cos(alpha - theta) -
    cos(alpha - theta0)); the quarter period is the integral of d theta /
    theta' from 0 to theta0, computed by adaptive quadrature after the
    substitution theta = theta0 (1 - u^2), which removes the inverse square
    root singularity at the turning point.
    """
    alpha = block.alpha
    if not 0 < amplitude < alpha:
        raise ValueError(f"amplitude must be between 0 and alpha ({alpha:.4g} rad), "
                         f"got {amplitude!r}")
    p = block.p

    def integrand(u):
        theta = amplitude * (1.0 - u * u)
        # cos(alpha - theta) - cos(alpha - theta0) written without cancellation
        difference = 2.0 * math.sin(alpha - 0.5 * (theta + amplitude)) * math.sin(
            0.5 * (amplitude - theta))
        if difference <= 0.0:
            difference = 2.0 * math.sin(alpha - amplitude) * math.sin(0.5 * amplitude * u * u)
        return 2.0 * amplitude * u / math.sqrt(2.0 * p * p * difference)

    quarter, _ = quad(integrand, 0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)
    return 4.0 * quarter


def impact_velocity(block: Block, amplitude: float) -> float:
    """Angular velocity reached at theta = 0 after release from ``amplitude`` at rest [rad/s].

    From energy conservation of Eq. (2-3): w^2 = 2 p^2 (cos(alpha - theta0) ... ) with
    w = p sqrt(2 (cos(alpha - theta0) - cos(alpha))).
    """
    alpha = block.alpha
    return block.p * math.sqrt(2.0 * (math.cos(alpha - amplitude) - math.cos(alpha)))


def amplitude_after_impact(block: Block, amplitude: float, cor: float) -> float:
    """Amplitude of the next half cycle of free rocking [rad].

    Energy between impacts is conserved and an impact multiplies the kinetic
    energy by cor^2 (Eq. 2-6), so cos(alpha - theta_next) = cos(alpha) -
    cor^2 (cos(alpha) - cos(alpha - theta)).
    """
    alpha = block.alpha
    value = math.cos(alpha) - cor * cor * (math.cos(alpha) - math.cos(alpha - amplitude))
    return alpha - math.acos(min(1.0, value))


def constant_pulse_overturn_duration(block: Block, acceleration: float) -> float:
    """Duration t1 of a constant acceleration a that just overturns a slender block, Eq. (2-7) [s].

    cosh(p t1) = 1 + 1 / [2 (a / g alpha) (a / g alpha - 1)].
    """
    ratio = acceleration / (G * block.alpha)
    if ratio <= 1.0:
        raise ValueError(f"acceleration must exceed g alpha = {G * block.alpha:.4g} m/s^2 "
                         "for motion to start (Section 2.3)")
    return math.acosh(1.0 + 1.0 / (2.0 * ratio * (ratio - 1.0))) / block.p


def half_sine_overturn_amplitude(block: Block, pulse_period: float) -> float:
    """Minimum amplitude of a sine pulse of period Ts that overturns a slender block, Eq. (2-8) [m/s^2].

    a / (g alpha) = sqrt(1 + (omega / p)^2), omega = 2 pi / Ts.
    """
    omega = 2.0 * math.pi / pulse_period
    return G * block.alpha * math.sqrt(1.0 + (omega / block.p) ** 2)


def half_sine_overturn_amplitude_large_frequency(block: Block, pulse_period: float) -> float:
    """Eq. (2-9): a / (g alpha) = omega / p, valid for omega / p > 3 [m/s^2]."""
    omega = 2.0 * math.pi / pulse_period
    return G * block.alpha * omega / block.p


def sliding_or_rocking(block: Block, static_friction: float) -> str:
    """Which mode an unrestrained block enters first, Section 2.1: 'rocking' if mu > B/H."""
    return "rocking" if static_friction > block.width / block.height else "sliding"


def periods(block: Block, amplitudes) -> np.ndarray:
    """Eq. (2-5) over an array of amplitudes [rad] -> periods [s]."""
    return np.array([housner_period(block, a) for a in np.atleast_1d(amplitudes)])
