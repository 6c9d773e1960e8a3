"""An independent solver for the tests: SciPy DOP853 on the analytic pulse, events located by SciPy.

Eq. (2-13) of Aslam, Godden & Scalise (1978) for a rectangular block on a
horizontally moving table, written here from scratch (not from the package):
theta'' = -p^2 (sin(s alpha - theta) + (a_g / g) cos(s alpha - theta)), s = sign of
theta; impacts at theta = 0 multiply theta' by the COR (one signed theta).
Rocking starts when |a_g| exceeds g tan alpha. After the pulse the run goes on
(table at rest) until the block overturns (|theta| = pi/2) or, just after an
impact, its energy is below the barrier p^2 (1 - cos alpha) (then it can
never overturn: free rocking only loses energy).
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

G = 9.80665


def shape(kind, omega):
    """(f, duration) of a unit pulse, written independently of shaketable.ground.pulses."""
    if kind == "half-sine":
        return (lambda t: math.sin(omega * t) if t <= math.pi / omega else 0.0), math.pi / omega
    if kind == "one-sine":
        return (lambda t: math.sin(omega * t) if t <= 2 * math.pi / omega else 0.0), \
            2 * math.pi / omega
    if kind == "one-cosine":
        return (lambda t: math.cos(omega * t) if t <= 2 * math.pi / omega else 0.0), \
            2 * math.pi / omega
    raise ValueError(kind)


def overturns(x, kind, ratio, alpha=0.25, p=2.0, cor=None, rtol=1e-12):
    """(overturns, impacts) for amplitude a = x g tan(alpha) of the pulse at omega = ratio p."""
    cor = 1 - 1.5 * math.sin(alpha) ** 2 if cor is None else cor
    f, duration = shape(kind, ratio * p)
    a = x * math.tan(alpha)          # a / g

    # start: first time |a f(t)| > tan(alpha) (bisection on the analytic pulse)
    ts = np.linspace(0.0, duration, 20001)
    above = [abs(a * f(t)) > math.tan(alpha) for t in ts]
    if not any(above):
        return False, 0
    k = above.index(True)
    if k == 0:
        t0 = 0.0
    else:
        lo, hi = ts[k - 1], ts[k]
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if abs(a * f(mid)) > math.tan(alpha) else (mid, hi)
        t0 = hi
    side = -math.copysign(1.0, f(t0 if t0 > 0 else 1e-12))
    theta, omega, t = 0.0, 0.0, t0
    impacts = 0
    end = duration + 200.0 / p

    def rhs(t, y, s):
        s_ = s if y[0] == 0.0 else math.copysign(1.0, y[0])
        return [y[1], -p * p * (math.sin(s_ * alpha - y[0]) + a * f(t) * math.cos(s_ * alpha - y[0]))]

    def hit(t, y, s):
        return s * y[0]          # active side s: s theta >= 0 until the impact
    hit.terminal = True
    hit.direction = -1

    def fall(t, y, s):
        return abs(y[0]) - math.pi / 2
    fall.terminal = True

    barrier = p * p * (1 - math.cos(alpha))
    while t < end:
        # integrate pulse and after-pulse separately (f has a kink/jump at the end)
        stop = duration if t < duration else end
        # nudge off theta = 0 so the impact event does not fire at the start
        sol = solve_ivp(rhs, (t, stop), [theta, omega], method="DOP853", rtol=rtol,
                        atol=1e-14, events=[hit, fall], args=(side,), first_step=1e-7)
        theta, omega, t = sol.y[0, -1], sol.y[1, -1], sol.t[-1]
        if sol.t_events[1].size:
            return True, impacts
        if sol.t_events[0].size:
            impacts += 1
            theta, omega = 0.0, cor * omega
            side = math.copysign(1.0, omega) if omega != 0 else side
            if t > duration and 0.5 * omega ** 2 < barrier:
                return False, impacts
    return False, impacts
