"""Closed forms of Sections 2.2-2.4 of the report and exact counterparts.

These are the analytic curves of Figs. 2.3-2.6 (slender-block approximations)
and the exact results they approximate, used to check the solvers.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block


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
        # cos(alpha - theta) - cos(alpha - theta0) = 2 sin(alpha - (theta + theta0)/2)
        # sin((theta0 - theta)/2), with theta0 - theta = theta0 u^2 and theta + theta0 =
        # theta0 (2 - u^2) written out: no difference of nearly equal numbers near u = 0
        half_lift = 0.5 * amplitude * u * u
        difference = 2.0 * math.sin(alpha - amplitude + half_lift) * math.sin(half_lift)
        if difference <= 0.0:  # u = 0: the integrand's limit
            return 2.0 * amplitude / math.sqrt(2.0 * p * p * math.sin(alpha - amplitude)
                                               * amplitude)
        return 2.0 * amplitude * u / math.sqrt(2.0 * p * p * difference)

    from scipy.integrate import quad  # loaded on first use (import shaketable stays light)

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


def constant_pulse_unstable_time(block: Block, acceleration: float,
                                 pulse_duration: float) -> float:
    """Time at which a slender block reaches theta = alpha under a constant pulse (Fig. 2.5) [s].

    The table accelerates at ``a`` for ``t1`` seconds, then moves on at constant
    velocity (Section 2.3). With the slender-block linearisation (Eq. 2-4)
    theta'' = p^2 (theta - alpha + a/g) during the pulse and p^2 (theta - alpha)
    after it, starting from rest at theta = 0:

    * during the pulse theta = alpha e (cosh(p t) - 1), e = a/(g alpha) - 1,
      which reaches alpha at cosh(p t) = 1 + 1/e if that is before t1;
    * after it, with x1 = alpha - theta(t1) and v1 = theta'(t1), the block
      reaches alpha at t1 + artanh(x1 p / v1) / p when v1 > p x1, and never
      otherwise (it falls back).

    The boundary v1 = p x1 is Eq. (2-7); past theta = alpha the linearised
    block runs away, so this is the time the report's Fig. 2.5 calls the
    overturning time. Returns ``inf`` when the block falls back.

    Parameters
    ----------
    block : Block
    acceleration : float
        Table acceleration a [m/s^2], above g alpha (else no rocking starts).
    pulse_duration : float
        t1 [s], positive.
    """
    ratio = acceleration / (G * block.alpha)
    if ratio <= 1.0:
        raise ValueError(f"acceleration must exceed g alpha = {G * block.alpha:.4g} m/s^2 "
                         "for motion to start (Section 2.3)")
    if not pulse_duration > 0.0:
        raise ValueError(f"pulse_duration must be positive [s], got {pulse_duration!r}")
    p, alpha, excess = block.p, block.alpha, ratio - 1.0
    during = math.acosh(1.0 + 1.0 / excess) / p
    if during <= pulse_duration:
        return during
    gap = alpha - alpha * excess * (math.cosh(p * pulse_duration) - 1.0)
    velocity = alpha * excess * p * math.sinh(p * pulse_duration)
    if velocity <= p * gap:
        return math.inf
    return pulse_duration + math.atanh(p * gap / velocity) / p


def half_sine_impulse_overturn_amplitude(block: Block, pulse_duration: float) -> float:
    """Amplitude of a very short half-sine pulse that overturns the block, exactly [m/s^2].

    The impulsive limit of Section 2.4 without the slender-block approximation:
    a pulse a sin(omega t) of duration Ts/2 = pi/omega changes the table's
    velocity by 2a/omega; about the pivot the block takes the angular momentum
    (I0/M) theta'_0 = (2a/omega) h, and it overturns when that kinetic energy
    lifts the centre of mass over the corner, (1/2)(I0/M) theta'_0^2 =
    g R (1 - cos alpha). Hence a = (omega / 2h) sqrt(2 g R (1 - cos alpha) I0/M),
    with I0/M = 4R^2/3. For slender blocks this is a/(g alpha) = omega/(2p),
    half of Eq. (2-9). Longer pulses need more (gravity acts during the pulse).
    """
    if not pulse_duration > 0.0:
        raise ValueError(f"pulse_duration must be positive [s], got {pulse_duration!r}")
    omega = math.pi / pulse_duration
    inertia = 4.0 * block.R ** 2 / 3.0
    return omega / (2.0 * block.h) * math.sqrt(2.0 * G * block.R * (1.0 - math.cos(block.alpha))
                                               * inertia)


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
