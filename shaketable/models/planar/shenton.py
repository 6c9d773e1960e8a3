"""Shenton's (1996) initiation criteria of the planar rigid block, in closed form.

A free-standing rectangular block (width B = 2b, height H = 2h, tan(alpha) = b/h,
uniform density, per unit mass I0 = 4R^2/3 about a corner, R^2 = b^2 + h^2) rests
on a table that starts, at t = 0, to accelerate with a constant horizontal
acceleration ``a`` [m/s^2] (+x) and a constant vertical one ``vg`` [m/s^2] (up).
Coulomb friction: static mu_s, dynamic mu_d <= mu_s. Which of the five modes
(rest, slide, rock, slide-rock, flight) does the block enter? Shenton [1]_
answers this for mu_s = mu_d; below it is derived again, from the equations of
the planar model (``docs/planar.md``) and its start rules, which also
cover mu_d < mu_s.

Derivation
----------
By symmetry take a >= 0 (a < 0 is the mirror image). Write n = g + vg (the
normal force per mass at rest) and A = a / n, the acceleration ratio.

*Flight.* n <= 0: the table pulls away faster than gravity; nothing holds the
block down: FLIGHT.

*Rest.* The table holds the block with F = a, N = n while |F| <= mu_s N
(A <= mu_s) and the base's centre of pressure e = h F / N stays on the base,
|e| <= b (A <= tan(alpha), the report's Eq. 2-1).

*Rock* about the corner at -x (s = +1; a positive ug drives theta positive).
At theta = theta' = 0 Eq. (2-13) gives

    I0 theta'' = a h - n b = h (a - n tan(alpha)),

positive iff A > tan(alpha). The pivot is fixed and theta' = 0, so the centre
(at (b, h) from the pivot) accelerates as x'' = -h theta'', y'' = b theta''
(the spec's ROCK kinematics at theta = theta' = 0), and the contact force per
mass is

    F = x'' + a = a - h theta'',      N = y'' + n = n + b theta''.

Substituting theta'' with I0 = 4 (b^2 + h^2) / 3:

    F = [a (4 b^2 + h^2) + 3 n b h] / (3 I0),   N = [n (b^2 + 4 h^2) + 3 a b h] / (3 I0),

both positive for n > 0, a >= 0. Rocking holds the corner iff F <= mu_s N, i.e.
mu_s >= mu_cr with the critical friction

    mu_cr = F / N = (a - h theta'') / (n + b theta'')
          = [A (4 t^2 + 1) + 3 t] / [t^2 + 4 + 3 A t],      t = tan(alpha).

This is the spec's expression, confirmed. Its properties (algebra):
mu_cr - t = (A - t)(1 + t^2) / D and A - mu_cr = 3 (A - t)(1 + A t) / D with
D = t^2 + 4 + 3 A t > 0, so tan(alpha) < mu_cr(A) < A for A > tan(alpha)
(equal at A = t), mu_cr increases with A and tends to (4 t^2 + 1) / (3 t) as
A -> infinity. It depends on a and vg only through A = (a/g) / (1 + vg/g).

*Slide-rock* about the same corner, the corner slipping toward -x (sigma = -1:
the table runs away under it), friction F = -sigma mu_d N = +mu_d N. At
theta = theta' = 0 with r = (-b, -h):

    x'' = X'' - h theta'' = -a + mu_d N
    y'' = b theta''       = -n + N
    Ic theta'' = r_x N - r_y F = h N (mu_d - t),     Ic = (b^2 + h^2) / 3.

So theta'' > 0 iff mu_d > t. With k = h (mu_d - t) / Ic, N = n / (1 - b k):
N > 0 iff b h (mu_d - t) < Ic, i.e. mu_d < (4 t^2 + 1) / (3 t) (beyond it the
normal "effective mass" is not positive: Painleve's paradox). The corner slips
the assumed way (X'' < 0) iff n (mu_d + h k) < a (1 - b k); the left side grows
with mu_d and equality holds exactly at mu_d = mu_cr(A), so X'' < 0 iff
mu_d < mu_cr(A). Slide-rock is therefore consistent iff
tan(alpha) < mu_d < mu_cr(A) (which implies A > tan(alpha) and no Painleve).

*Slide* (flat, sigma = -1): x'' = -a + mu_d n; the centre of pressure of the
sliding block is e = sigma mu_d h, on the base iff mu_d <= tan(alpha).

The start rules (spec, "Leaving REST") try, in this order: flight (n <= 0);
if A > t, rock (mu_s >= mu_cr), then slide-rock (t < mu_d < mu_cr); then slide
(A > mu_s and mu_d <= t). With mu_d <= mu_s these give one mode everywhere:

=============  ===========================================================
mode           condition (n > 0, A = |a| / n, t = tan(alpha))
=============  ===========================================================
rest           A <= mu_s and A <= t
rock           A > t and mu_s >= mu_cr(A)
slide-rock     A > t, mu_s < mu_cr(A) and mu_d > t
slide          A > mu_s, not the above (then mu_d <= t; if A > t also
               mu_s < mu_cr(A) < A)
flight         n <= 0
=============  ===========================================================

With mu_s = mu_d = mu this is Shenton's classification: slide if A > mu and
mu < t; rock if A > t and mu >= mu_cr(A); slide-rock in the wedge
t < mu < mu_cr(A). The report's Section 2.1 rule (rock iff mu_s > B/H) misses
the wedge. (A "slide" cell with A > t, mu_d <= t < mu_s < mu_cr exists only for
mu_d < mu_s.)

References
----------
.. [1] H. W. Shenton III, "Criteria for initiation of slide, rock, and
   slide-rock rigid-body modes", Journal of Engineering Mechanics 122(7),
   690-693, 1996.
"""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G

#: Mode codes of the planar model (docs/planar.md), in this order.
REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT = range(5)

#: Names of the mode codes.
MODE_NAMES = ("rest", "slide", "rock", "slide-rock", "flight")


def _aspect(width, height) -> np.ndarray:
    width = np.asarray(width, dtype=float)
    height = np.asarray(height, dtype=float)
    if np.any(~np.isfinite(width)) or np.any(width <= 0):
        raise ValueError(f"width must be positive and finite [m], got {width!r}")
    if np.any(~np.isfinite(height)) or np.any(height <= 0):
        raise ValueError(f"height must be positive and finite [m], got {height!r}")
    return width / height


def critical_friction_ratio(acceleration_ratio, tan_alpha):
    """Shenton's critical friction mu_cr as a function of A = |a| / (g + vg) [-].

    Parameters
    ----------
    acceleration_ratio : float or array_like
        A = |a| / (g + vg) [-], >= 0.
    tan_alpha : float or array_like
        b / h = B / H [-].

    Returns
    -------
    ndarray or float
        mu_cr = [A (4 t^2 + 1) + 3 t] / [t^2 + 4 + 3 A t] [-] (module docstring).
        Meaningful for A > tan(alpha), where tan(alpha) < mu_cr < A.
    """
    ratio = np.asarray(acceleration_ratio, dtype=float)
    t = np.asarray(tan_alpha, dtype=float)
    value = (ratio * (4 * t * t + 1) + 3 * t) / (t * t + 4 + 3 * ratio * t)
    return value if value.ndim else float(value)


def critical_friction(horizontal_g, vertical_g=0.0, *, width, height):
    """Critical friction mu_cr(a/g, vg/g) of a block at rest [-].

    A block tipped by the table (A > B/H) rocks without slipping iff
    mu_s >= mu_cr; with B/H < mu < mu_cr it slide-rocks.

    Parameters
    ----------
    horizontal_g : float or array_like
        Constant horizontal table acceleration a / g [-] (either sign).
    vertical_g : float or array_like
        Constant vertical table acceleration vg / g [-], up; must be > -1.
    width, height : float
        Block width B and height H [m].

    Returns
    -------
    ndarray or float
        mu_cr [-] at A = |a/g| / (1 + vg/g).

    Raises
    ------
    ValueError
        ``vertical_g <= -1`` (no normal force: the block flies) or bad sizes.
    """
    t = _aspect(width, height)
    normal = 1.0 + np.asarray(vertical_g, dtype=float)
    if np.any(~(normal > 0)):
        raise ValueError(f"vertical_g must be above -1 (g + vg > 0), got {vertical_g!r}")
    return critical_friction_ratio(np.abs(np.asarray(horizontal_g, dtype=float)) / normal, t)


def initial_mode(width, height, static_friction, dynamic_friction, horizontal,
                 vertical=0.0):
    """Mode a block at rest enters under constant table accelerations (module docstring).

    Parameters
    ----------
    width, height : float or array_like
        Block width B and height H [m].
    static_friction, dynamic_friction : float or array_like
        mu_s and mu_d [-], 0 <= mu_d <= mu_s.
    horizontal : float or array_like
        Constant horizontal table acceleration [m/s^2] (+x).
    vertical : float or array_like
        Constant vertical table acceleration [m/s^2] (up).

    Returns
    -------
    ndarray of int
        Mode codes :data:`REST`, :data:`SLIDE`, :data:`ROCK`, :data:`SLIDE_ROCK`,
        :data:`FLIGHT` (broadcast shape of the inputs).

    Raises
    ------
    ValueError
        Negative or non-finite friction, mu_d > mu_s, non-finite accelerations
        or bad sizes; the message names the parameter.
    """
    t = _aspect(width, height)
    mu_s = np.asarray(static_friction, dtype=float)
    mu_d = np.asarray(dynamic_friction, dtype=float)
    for name, value in (("static_friction", mu_s), ("dynamic_friction", mu_d)):
        if np.any(~np.isfinite(value)) or np.any(value < 0):
            raise ValueError(f"{name} must be finite and >= 0 [-], got {value!r}")
    if np.any(mu_d > mu_s):
        raise ValueError("dynamic_friction must not exceed static_friction")
    a = np.abs(np.asarray(horizontal, dtype=float))
    normal = G + np.asarray(vertical, dtype=float)
    for name, value in (("horizontal", a), ("vertical", normal)):
        if np.any(~np.isfinite(value)):
            raise ValueError(f"{name} acceleration must be finite [m/s^2], got {value!r}")
    t, mu_s, mu_d, a, normal = np.broadcast_arrays(t, mu_s, mu_d, a, normal)
    flying = normal <= 0
    ratio = np.where(flying, np.inf, a / np.where(flying, 1.0, normal))
    mu_cr = critical_friction_ratio(np.where(flying, 0.0, ratio), t)
    tips = ratio > t
    mode = np.full(t.shape, SLIDE, dtype=int)
    mode[(ratio <= mu_s) & ~tips] = REST
    mode[tips & (mu_s >= mu_cr)] = ROCK
    mode[tips & (mu_s < mu_cr) & (mu_d > t)] = SLIDE_ROCK
    mode[flying] = FLIGHT
    return mode
