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
    """Housner's half-sine overturning amplitude, Eq. (2-8) [m/s^2]: an approximation, not the minimum.

    a / (g alpha) = sqrt(1 + (omega / p)^2), omega = 2 pi / Ts.

    Section 2.4 derives it for a slender block (Eq. 2-4) asking theta to reach
    alpha while the pulse still acts, and leaves out the uplift delay (the block
    lifts only when a sin(omega t) reaches g alpha). The exact minimum of the same
    linearised model is lower (:func:`linear_pulse_threshold`, Voyagaki,
    Psycharis & Mylonakis 2013; Dimitrakopoulos & DeJong 2012): 2.7908 against
    Eq. (2-8)'s 4.1231 at omega/p = 4, 4.7871 against 8.0623 at omega/p = 8;
    ``docs/pulses.md`` compares both with the exact nonlinear thresholds.
    """
    omega = 2.0 * math.pi / pulse_period
    return G * block.alpha * math.sqrt(1.0 + (omega / block.p) ** 2)


def half_sine_overturn_amplitude_large_frequency(block: Block, pulse_period: float) -> float:
    """Eq. (2-9): a / (g alpha) = omega / p, valid for omega / p > 3 [m/s^2]."""
    omega = 2.0 * math.pi / pulse_period
    return G * block.alpha * omega / block.p


def periods(block: Block, amplitudes) -> np.ndarray:
    """Eq. (2-5) over an array of amplitudes [rad] -> periods [s]."""
    return np.array([housner_period(block, a) for a in np.atleast_1d(amplitudes)])


# --- Housner's linearised model (Eq. 2-4) under pulses, in closed form ---------------------
#
# With u = theta/alpha, tau = p t, x = a/(g alpha) and r = omega/p, Eq. (2-4) with the
# table acceleration a f(t) reads, on the corner s = sign(u),
#
#     u'' = u - s + x f(tau),
#
# and the pulses of :mod:`shaketable.ground.pulses` are f = sin(r tau + phi) on
# [0, tau_end]: half-sine (phi = 0, tau_end = pi/r), one-sine (phi = 0, 2 pi/r),
# one-cosine (phi = pi/2, 2 pi/r) and the rectangular pulse of Eq. (2-7) (r = 0,
# phi = pi/2: f = 1 for tau_end = p t1). Between events the solution is
#
#     u = s - K sin(r tau + phi) + C1 e^(tau - tau0) + C2 e^-(tau - tau0),  K = x/(1 + r^2),
#
# (K = 0 after the pulse). The block lifts (from rest) where x f first exceeds 1
# (onto s = +1) or falls below -1 (s = -1): the uplift delay of Voyagaki, Psycharis &
# Mylonakis (2013) and Dimitrakopoulos & DeJong (2012), which Housner's Eq. (2-8)
# leaves out. An impact is where u returns to 0: u' -> cor u' and the corner changes.
# When the pulse ends, the fate is decided by energy (:mod:`shaketable.core.fate`,
# linear model: E = u'^2/2 + |u| - u^2/2 against 1/2). The events are found on a
# fine grid and polished with Brent's method to rounding, so these are the exact
# linearised responses, to about 1e-14, against which the ``linear`` method is tested.

#: Pulses with a closed-form linearised response: (phase phi [rad], duration in pulse periods).
LINEAR_PULSES = {"half-sine": (0.0, 0.5), "one-sine": (0.0, 1.0), "one-cosine": (0.5 * math.pi, 1.0),
                 "type-A": (0.0, 1.0), "type-B": (0.5 * math.pi, 1.0)}

_CASCADE = 1e-6      # an impact cascade shorter than this (in 1/p) is rest, as in the engine


def _pulse_setup(kind: str, ratio: float | None, duration: float | None):
    """(r, phi, tau_end) of a pulse kind, or of the rectangular pulse of length ``duration`` [1/p]."""
    if kind == "rectangular":
        if not (duration is not None and math.isfinite(duration) and duration > 0):
            raise ValueError(f"duration must be a positive p t1 [-], got {duration!r}")
        return 0.0, 0.5 * math.pi, float(duration)
    if kind not in LINEAR_PULSES:
        raise ValueError(f"pulse must be one of {', '.join(LINEAR_PULSES)} or 'rectangular', "
                         f"got {kind!r}")
    if not (ratio is not None and math.isfinite(ratio) and ratio > 0):
        raise ValueError(f"ratio must be a positive omega/p [-], got {ratio!r}")
    phase, periods_long = LINEAR_PULSES[kind]
    return float(ratio), phase, periods_long * 2.0 * math.pi / ratio


def _lift_time(x, r, phase, tau0, tau_end):
    """First tau >= tau0 at which a block at rest lifts, and the corner; (inf, 0) if never."""
    if x <= 1.0:
        return math.inf, 0
    if r == 0.0:                                   # rectangular: f = 1
        return (tau0, 1) if tau0 <= tau_end else (math.inf, 0)
    c = math.asin(1.0 / x)
    psi = (r * tau0 + phase) % (2.0 * math.pi)
    # x sin(psi) > 1 on (c, pi - c), < -1 on (pi + c, 2 pi - c)
    if c <= psi < math.pi - c:
        return tau0, 1
    if math.pi + c <= psi < 2.0 * math.pi - c:
        return tau0, -1
    starts = [(c, 1), (math.pi + c, -1), (2.0 * math.pi + c, 1)]
    start, side = next((a, s) for a, s in starts if a > psi)
    tau = tau0 + (start - psi) / r
    return (tau, side) if tau <= tau_end else (math.inf, 0)


class _Flight:
    """u(tau) on one corner from (tau0, u0, w0) under K sin(r tau + phi) (K = 0: free)."""

    def __init__(self, side, tau0, u0, w0, K, r, phase):
        self.side, self.tau0, self.u0, self.w0 = side, tau0, u0, w0
        self.K, self.r, self.phase = K, r, phase
        v0 = u0 - side
        sin0, cos0 = math.sin(r * tau0 + phase), math.cos(r * tau0 + phase)
        self.c1 = 0.5 * (v0 + K * sin0 + w0 + K * r * cos0)
        self.c2 = 0.5 * (v0 + K * sin0 - w0 - K * r * cos0)

    def rise(self, tau):
        """u(tau) - u0, written without cancellation near tau0 (expm1, sine of a half difference)."""
        d = np.asarray(tau, dtype=float) - self.tau0
        r, phase = self.r, self.phase
        sine_change = 2.0 * np.cos(r * (self.tau0 + 0.5 * d) + phase) * np.sin(0.5 * r * d)
        return -self.K * sine_change + self.c1 * np.expm1(d) + self.c2 * np.expm1(-d)

    def position(self, tau):
        return self.u0 + self.rise(tau)

    def velocity(self, tau):
        d = np.asarray(tau, dtype=float) - self.tau0
        return (-self.K * self.r * np.cos(self.r * np.asarray(tau) + self.phase)
                + self.c1 * np.exp(d) - self.c2 * np.exp(-d))


def _first_return(flight, tau_end):
    """First tau in (tau0, tau_end] at which side * u reaches 0, or inf."""
    from scipy.optimize import brentq  # loaded on first use

    span = tau_end - flight.tau0
    if span <= 0.0:
        return math.inf
    step = min(0.01, 2.0 * math.pi / max(flight.r, 1e-300) / 2000.0)
    count = int(math.ceil(span / step))
    uniform = np.linspace(flight.tau0, tau_end, count + 1)[1:]
    if flight.w0 != 0.0:
        # after an impact a short excursion may end before the first grid point
        near = (uniform[0] - flight.tau0) * 0.5 ** np.arange(30, 0, -1)
        grid = np.concatenate([flight.tau0 + near, uniform])
    else:
        # an uplift: s u'' >= 0 and growing at tau0 (x f passes 1), no return at once
        grid = uniform
    gap = flight.side * flight.position(grid)

    def g(tau):
        return float(flight.side * flight.position(tau))

    below = np.flatnonzero(gap <= 0.0)
    first = int(below[0]) if below.size else grid.size
    # a dip below 0 between two grid points: a local minimum of the gap before `first`
    minima = np.flatnonzero((gap[1:-1] < gap[:-2]) & (gap[1:-1] <= gap[2:]))[:] + 1
    for k in minima[minima < first]:
        rate = lambda tau: float(flight.side * flight.velocity(tau))  # noqa: E731
        lo, hi = grid[k - 1], grid[k + 1]
        if rate(lo) < 0.0 < rate(hi):
            bottom = brentq(rate, lo, hi, xtol=1e-15, rtol=8.9e-16)
            if g(bottom) <= 0.0:
                return brentq(g, lo, bottom, xtol=1e-15, rtol=8.9e-16)
    if first == grid.size:
        return math.inf
    if first == 0:
        # back within the first grid step: find a positive point closer to tau0 (a short
        # excursion, e.g. an uplift while x f is about to fall below 1 again)
        for k in range(1, 46):
            trial = flight.tau0 + (grid[0] - flight.tau0) * 0.5 ** k
            if g(trial) > 0.0:
                return brentq(g, trial, flight.tau0 + (grid[0] - flight.tau0) * 0.5 ** (k - 1),
                              xtol=1e-15, rtol=8.9e-16)
        return flight.tau0          # returns at once: the caller treats it as rest
    return brentq(g, grid[first - 1], grid[first], xtol=1e-15, rtol=8.9e-16)


def linear_pulse_response(kind: str, ratio: float | None, amplitude: float, cor: float, *,
                          duration: float | None = None) -> dict:
    """Closed-form response of Housner's linearised block (Eq. 2-4) to one pulse.

    Parameters
    ----------
    kind : str
        ``"half-sine"``, ``"one-sine"`` (type-A), ``"one-cosine"`` (type-B) or
        ``"rectangular"`` (a constant acceleration for ``duration``, Eq. 2-7).
    ratio : float
        omega/p [-] (ignored for ``"rectangular"``).
    amplitude : float
        a/(g alpha) [-], the linearised literature's amplitude (a/(g tan alpha)
        times tan(alpha)/alpha).
    cor : float
        Coefficient of restitution [-].
    duration : float, optional
        p t1 [-] of the rectangular pulse.

    Returns
    -------
    dict
        ``lift`` (p t of the first uplift, inf if none), ``u_end`` and ``rate_end``
        (theta/alpha and theta'/(p alpha) when the pulse ends), ``impacts``
        (during the pulse), ``overturns`` (by energy at the end of the pulse,
        :mod:`shaketable.core.fate`), ``impacts_after`` (0 or 1),
        ``energy_ratio`` (E / E* at the end) and ``reason``.
    """
    from shaketable.core.fate import fate_of

    r, phase, tau_end = _pulse_setup(kind, ratio, duration)
    x = float(amplitude)
    if not (math.isfinite(x) and x > 0):
        raise ValueError(f"amplitude must be a positive a/(g alpha) [-], got {amplitude!r}")
    K = x / (1.0 + r * r)
    tau, u, w, side, impacts = 0.0, 0.0, 0.0, 0, 0
    lift = math.inf
    while True:
        if side == 0:                                       # at rest: wait for uplift
            tau, side = _lift_time(x, r, phase, tau, tau_end)
            if side == 0:
                u, w = 0.0, 0.0
                break
            lift = min(lift, tau)
        flight = _Flight(side, tau, u, w, K, r, phase)
        back = _first_return(flight, tau_end)
        if back == tau and w == 0.0:
            # an uplift that ends at once (x f leaves its band within rounding of tau):
            # the block stays on the ground; look for the next uplift a little later
            tau, side = tau + 1e-12 * max(1.0, tau), 0
            continue
        if back == math.inf:
            u, w = float(flight.position(tau_end)), float(flight.velocity(tau_end))
            break
        before = float(flight.velocity(back)) if back > tau else w
        tau, u, w, side = back, 0.0, cor * before, -side
        impacts += 1
        if impacts > 100_000:
            raise RuntimeError(f"{kind} omega/p={ratio} x={x}: more than 100000 impacts")
        # an impact with the table pushing the block back at once: the endless cascade
        # of Section 2.7 (5), summed in closed form as the engine does
        push = -1.0 + side * x * math.sin(r * tau + phase)
        if push < 0.0 and (abs(w) == 0.0 or 2.0 * abs(w) / (-push * (1.0 - cor + 1e-300))
                           < _CASCADE):
            side, w = 0, 0.0
    fate = fate_of(u, w, 1.0, 1.0, cor, "linear")
    return {"lift": lift, "u_end": u, "rate_end": w, "impacts": impacts,
            "overturns": fate.will_overturn, "impacts_after": fate.impacts,
            "energy_ratio": fate.energy_ratio, "reason": fate.reason}


def _linear_class(kind, ratio, x, cor, duration):
    response = linear_pulse_response(kind, ratio, x, cor, duration=duration)
    if not response["overturns"]:
        return -1
    return response["impacts"] + response["impacts_after"]


def linear_pulse_bands(kind: str, ratio: float | None, cor: float, *, ceiling: float | None = None,
                       scan_step: float = 0.002, tolerance: float = 1e-13,
                       duration: float | None = None) -> list:
    """Overturn/safe bands of the linearised block under a pulse, from the closed form.

    Every band edge of :func:`linear_pulse_response`'s verdict in x = a/(g alpha)
    from 1 (uplift) to ``ceiling`` (default 2 sqrt(1 + (omega/p)^2) + 2, as
    :func:`shaketable.studies.overturning_spectrum.overturning_spectrum`): a
    geometric scan of relative step ``scan_step``, every change of class bisected
    to ``tolerance`` relative. The linearised model has no other parameter: the
    edges hold for every alpha (Zhang & Makris 2001; Dimitrakopoulos & DeJong 2012).

    Returns
    -------
    list of (float, float, int)
        (from, to, impacts) per band, impacts -1 for a safe band, else the
        impacts before it overturns.
    """
    r, _, _ = _pulse_setup(kind, ratio, duration)
    top = ceiling if ceiling is not None else 2.0 * math.sqrt(1.0 + r * r) + 2.0
    count = int(math.ceil(math.log(top) / math.log1p(scan_step)))
    grid = np.exp(np.linspace(0.0, math.log(top), count + 1))
    classes = [_linear_class(kind, ratio, x, cor, duration) for x in grid]
    points, kinds = [1.0], [classes[0]]

    def refine(lo, hi, c_lo, c_hi):
        while hi / lo - 1.0 > tolerance:
            middle = math.sqrt(lo * hi)
            c = _linear_class(kind, ratio, middle, cor, duration)
            if c == c_lo:
                lo = middle
            elif c == c_hi:
                hi = middle
            else:                        # a band inside: both of its edges
                refine(lo, middle, c_lo, c)
                lo, c_lo = middle, c
        points.append(0.5 * (lo + hi))
        kinds.append(c_hi)

    for k in range(count):
        if classes[k] != classes[k + 1]:
            refine(grid[k], grid[k + 1], classes[k], classes[k + 1])
    points.append(top)
    return [(points[k], points[k + 1], kinds[k]) for k in range(len(kinds))]


def linear_pulse_threshold(kind: str, ratio: float | None, cor: float = 1.0, *,
                           duration: float | None = None, ceiling: float | None = None) -> float:
    """Smallest a/(g alpha) [-] that overturns the linearised block (Eq. 2-4), exactly.

    The lower edge of the first overturning band of :func:`linear_pulse_bands`
    (with the uplift delay; Voyagaki, Psycharis & Mylonakis 2013, Dimitrakopoulos
    & DeJong 2012, Zhang & Makris 2001). For the half-sine (no impact before
    the pulse ends, near the threshold) it is the root of u' + u = 1 at the end
    of the pulse, which is also what the general solver finds. The rectangular
    pulse (``duration`` = p t1) has the explicit inverse of Eq. (2-7),
    :func:`rectangular_pulse_threshold`. inf when nothing up to ``ceiling``
    overturns.
    """
    for low, _, impacts in linear_pulse_bands(kind, ratio, cor, ceiling=ceiling,
                                              duration=duration):
        if impacts >= 0:
            return low
    return math.inf


def rectangular_pulse_threshold(duration: float) -> float:
    """a/(g alpha) [-] of a constant pulse of length t1 that just overturns the linearised block.

    Eq. (2-7) solved for the amplitude: with c = cosh(p t1), 2 x (x - 1) =
    1/(c - 1) = 1/(2 sinh^2(p t1/2)), so x = (1 + coth(p t1 / 2)) / 2
    (``duration`` is p t1 [-]). It holds for any cor: below it the block turns
    before alpha with less energy than the barrier, and an impact only removes
    energy (the pulse pushes one way only and is over by then).
    """
    if not (isinstance(duration, (int, float)) and math.isfinite(duration) and duration > 0):
        raise ValueError(f"duration must be a positive p t1 [-], got {duration!r}")
    return 0.5 * (1.0 + 1.0 / math.tanh(0.5 * duration))


def linear_half_sine_threshold(ratio: float) -> float:
    """Smallest a/(g alpha) [-] of a half-sine pulse that overturns the linearised block, explicitly.

    The block lifts at p t0 = arcsin(1/x)/r (x = a/(g alpha), r = omega/p) and,
    near the threshold, makes no impact before the pulse ends at p T = pi/r;
    integrating Eq. (2-4) from rest at t0 (:func:`linear_pulse_response`'s
    closed form) the condition of overturning after the pulse, u' + u = 1 at T
    (the energy on the barrier, :mod:`shaketable.core.fate`), reduces to

        r = sqrt(x^2 - 1) + x exp(-(pi - arcsin(1/x)) / r),

    whose right-hand side grows with x from below r at x = 1 to above r at
    x = sqrt(1 + r^2) (Eq. 2-8): one root, always below Eq. (2-8). With the
    uplift delay of Voyagaki, Psycharis & Mylonakis (2013) and Dimitrakopoulos
    & DeJong (2012). 2.7908 at r = 4 and 4.7871 at r = 8 (Eq. 2-8: 4.1231, 8.0623).
    Independent of cor (no impact before overturning).
    """
    from scipy.optimize import brentq

    if not (isinstance(ratio, (int, float)) and math.isfinite(ratio) and ratio > 0):
        raise ValueError(f"ratio must be a positive omega/p [-], got {ratio!r}")
    r = float(ratio)

    def excess(x):
        return math.sqrt(x * x - 1.0) + x * math.exp(-(math.pi - math.asin(1.0 / x)) / r) - r

    # excess(1) = exp(-pi / (2 r)) - r < 0 and excess(sqrt(1 + r^2)) > 0 for every r > 0
    return brentq(excess, 1.0, math.sqrt(1.0 + r * r), xtol=1e-15, rtol=8.9e-16)
