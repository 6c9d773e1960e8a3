"""Intensity measures (IMs) of a ground motion: peaks, spectral ordinates, energy, duration,
and the two block-normalised measures of Dimitrakopoulos & Paraskeva (2015).

Every function takes a :class:`~shaketable.core.motion.Motion` (horizontal component by
default) and returns SI values. The motion is the package's: linear between samples, so
the integrals below are exact for it (no quadrature error):

* velocity ``v(t) = int_0^t a dt`` from rest, per interval ``dt (a_k + a_{k+1}) / 2``;
* displacement ``d(t) = int_0^t v dt``, per interval ``v_k dt + dt^2 (2 a_k + a_{k+1}) / 6``,
  then **baseline-corrected** (below);
* ``int a^2 dt`` per interval ``dt (a_k^2 + a_k a_{k+1} + a_{k+1}^2) / 3``
  (:func:`shaketable.ground.signals.arias_intensity`);
* ``int |a| dt`` per interval ``dt (|a_k| + |a_{k+1}|) / 2`` without a sign change, and
  ``dt (a_k^2 + a_{k+1}^2) / (2 (|a_k| + |a_{k+1}|))`` across one.

Baseline correction of the displacement (for PGD only): a processed record (NGA-West2,
the package's artificial records) has a velocity that oscillates about a small residual
constant; integrated, that constant becomes a drift that dominates the displacement. The
least-squares straight line through ``d(t)`` is removed (equivalently, the best constant
velocity offset and a constant displacement); for a harmonic motion over whole cycles this
recovers the harmonic displacement exactly (``a = A cos wt`` gives PGD ``A / w^2``). PGV
uses the velocity from rest, uncorrected (records are processed already; a constant
removed from the acceleration would change the motion the block feels).

:data:`MEASURES` names the measures a sweep can scale to and record; each is homogeneous
in the scale factor of the motion with the exponent given there (PGA, PGV, PGD, Sa, CAV
1; Arias 2; PGV/PGA and the duration 0: not scaling targets).

References
----------
.. [1] Kramer, S. L. (1996). Geotechnical Earthquake Engineering. Prentice Hall, Sect. 3.3
   (peak values, Arias intensity, duration).
.. [2] Arias, A. (1970). A measure of earthquake intensity. In Seismic Design for Nuclear
   Power Plants, MIT Press, 438-483.
.. [3] EPRI (1988). A criterion for determining exceedance of the operating basis
   earthquake. Report NP-5930 (cumulative absolute velocity).
.. [4] Trifunac, M. D. & Brady, A. G. (1975). A study on the duration of strong earthquake
   ground motion. BSSA 65(3), 581-626 (significant duration).
.. [5] Eads, L., Miranda, E. & Lignos, D. G. (2015). Average spectral acceleration as an
   intensity measure for collapse risk assessment. EESD 44(12), 2057-2073.
.. [6] Dimitrakopoulos, E. G. & Paraskeva, T. S. (2015). Dimensionless fragility curves
   for rocking response to near-fault excitations. EESD 44(12), 2015-2033.
.. [7] Chopra, A. K. (2012). Dynamics of Structures, 4th ed., Sect. 6.6 (pseudo-
   acceleration spectrum).
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.core.motion import motion_argument as _motion
from shaketable.core.validation import number as _number
from shaketable.ground.signals import (
    arias_intensity as _arias_history,
)
from shaketable.ground.signals import (
    motion_component,
    response_spectrum,
    strong_motion_duration,
)

#: Scaling targets and recorded measures: name -> (table column, unit kind for parsing,
#: exponent of the scale factor). ``sa`` and ``sa_avg`` columns carry their periods.
MEASURES = {
    "pga": ("pga [m/s^2]", "acceleration", 1),
    "pgv": ("pgv [m/s]", "velocity", 1),
    "pgd": ("pgd [m]", "length", 1),
    "sa": ("sa [m/s^2]", "acceleration", 1),
    "sa_avg": ("sa_avg [m/s^2]", "acceleration", 1),
    "arias": ("arias [m/s]", "velocity", 2),
    "cav": ("cav [m/s]", "velocity", 1),
}

#: Default number of log-spaced periods of the average spectral acceleration.
SA_AVG_POINTS = 10


def _component(motion: Motion, component: str) -> np.ndarray:
    return motion_component(_motion("motion", motion), component)


def ground_velocity(motion, component: str = "horizontal") -> np.ndarray:
    """Ground velocity from rest, ``v(t) = int_0^t a dt`` [m/s], at ``motion.t``.

    Exact for the piecewise-linear acceleration (trapezoid per interval); not
    baseline-corrected (see the module docstring).
    """
    motion = _motion("motion", motion)
    a = _component(motion, component)
    return np.concatenate([[0.0], np.cumsum(np.diff(motion.t) * (a[:-1] + a[1:]) / 2.0)])


def ground_displacement(motion, component: str = "horizontal", *,
                        baseline: bool = True) -> np.ndarray:
    """Ground displacement [m] at ``motion.t``, by default baseline-corrected.

    ``d_{k+1} = d_k + v_k dt + dt^2 (2 a_k + a_{k+1}) / 6`` (exact for the
    piecewise-linear acceleration) from ``d = v = 0``; with ``baseline`` the
    least-squares straight line through ``d(t)`` is subtracted (module docstring).
    """
    motion = _motion("motion", motion)
    a = _component(motion, component)
    v = ground_velocity(motion, component)
    dt = np.diff(motion.t)
    d = np.concatenate([[0.0], np.cumsum(v[:-1] * dt + dt**2 * (2.0 * a[:-1] + a[1:]) / 6.0)])
    if baseline:
        slope, intercept = np.polyfit(motion.t - motion.t[0], d, 1)
        d = d - (intercept + slope * (motion.t - motion.t[0]))
    return d


def pga(motion, component: str = "horizontal") -> float:
    """Peak ground acceleration ``max |a(t)|`` [m/s^2] ([1]_ Sect. 3.3.1)."""
    return float(np.max(np.abs(_component(motion, component))))


def pgv(motion, component: str = "horizontal") -> float:
    """Peak ground velocity ``max |v(t)|`` [m/s], ``v`` from rest (:func:`ground_velocity`).

    A sine ``a = A cos(w t)`` gives ``A / w`` ([1]_ Sect. 3.3.1).
    """
    return float(np.max(np.abs(ground_velocity(motion, component))))


def pgd(motion, component: str = "horizontal") -> float:
    """Peak ground displacement ``max |d(t)|`` [m] of the baseline-corrected displacement.

    :func:`ground_displacement`; ``a = A cos(w t)`` over whole cycles gives ``A / w^2``.
    """
    return float(np.max(np.abs(ground_displacement(motion, component))))


def pgv_pga_ratio(motion, component: str = "horizontal") -> float:
    """PGV / PGA [s]: a period-like measure of the pulse content ([1]_ Sect. 3.3.1)."""
    peak = pga(motion, component)
    if peak == 0.0:
        raise ValueError(f"the {component} component is zero: PGV/PGA is undefined")
    return pgv(motion, component) / peak


def spectral_acceleration(motion, period, damping: float = 0.05,
                          component: str = "horizontal"):
    """Pseudo-spectral acceleration ``Sa(T, zeta) = w^2 max|u|`` [m/s^2] ([7]_).

    The package's exact piecewise-linear oscillator
    (:func:`shaketable.ground.signals.response_spectrum`). ``period`` [s] may be a
    number or an array.
    """
    return response_spectrum(motion, period, damping=damping, component=component)


def average_spectral_acceleration(motion, period_low: float, period_high: float, *,
                                  damping: float = 0.05, points: int = SA_AVG_POINTS,
                                  component: str = "horizontal") -> float:
    """Geometric mean of Sa over a period range, ``(prod_i Sa(T_i))^(1/n)`` [m/s^2] ([5]_).

    Parameters
    ----------
    period_low, period_high : float
        Ends of the range [s], ``0 < period_low < period_high``.
    points : int
        Number ``n`` of periods, log-spaced from ``period_low`` to ``period_high``
        inclusive (at least 2).
    """
    low = _number("period_low", period_low)
    high = _number("period_high", period_high)
    if not 0.0 < low < high:
        raise ValueError(f"need 0 < period_low < period_high [s], got {low!r}, {high!r}")
    if isinstance(points, bool) or not isinstance(points, int) or points < 2:
        raise ValueError(f"points must be an integer of at least 2, got {points!r}")
    periods = np.geomspace(low, high, points)
    values = spectral_acceleration(motion, periods, damping, component)
    if np.any(values <= 0.0):
        raise ValueError(f"the {component} component is zero: Sa_avg is undefined")
    return float(np.exp(np.mean(np.log(values))))


def arias_intensity(motion, component: str = "horizontal") -> float:
    """Arias intensity ``I_A = pi / (2 g) int a^2 dt`` [m/s] ([2]_).

    A sine of amplitude ``A`` over a whole number of half cycles lasting ``t_d``
    gives ``pi A^2 t_d / (4 g)``.
    """
    return float(_arias_history(motion, component)[-1])


def cumulative_absolute_velocity(motion, component: str = "horizontal") -> float:
    """Cumulative absolute velocity ``CAV = int |a| dt`` [m/s] ([3]_, without its 0.025 g
    threshold). A sine of amplitude ``A`` over whole half cycles of length ``t_d`` gives
    ``2 A t_d / pi``.
    """
    motion = _motion("motion", motion)
    a = _component(motion, component)
    dt = np.diff(motion.t)
    left, right = a[:-1], a[1:]
    same = left * right >= 0.0
    total_abs = np.abs(left) + np.abs(right)
    with np.errstate(invalid="ignore", divide="ignore"):
        crossing = np.where(total_abs > 0.0, (left**2 + right**2) / (2.0 * total_abs), 0.0)
    pieces = np.where(same, total_abs / 2.0, crossing) * dt
    return float(np.sum(pieces))


def significant_duration(motion, low: float = 0.05, high: float = 0.95,
                         component: str = "horizontal") -> float:
    """Significant duration ``D5-95``: time between 5 % and 95 % of the Arias intensity [s]
    ([4]_; :func:`shaketable.ground.signals.strong_motion_duration`)."""
    return strong_motion_duration(motion, low, high, component)


def normalised_pga(pga_value: float, alpha: float) -> float:
    """``PGA / (g tan(alpha))`` [-]: PGA over the block's static uplift threshold ([6]_).

    Parameters
    ----------
    pga_value : float
        Peak ground acceleration [m/s^2].
    alpha : float
        Slenderness angle of the block [rad], in (0, pi/2).
    """
    alpha = _slenderness(alpha)
    return float(pga_value) / (G * math.tan(alpha))


def normalised_pgv(pgv_value: float, p: float, alpha: float) -> float:
    """``PGV p / (g tan(alpha))`` [-]: PGV over the velocity scale of the block ([6]_).

    Under the exact similarity law of the rocking equation (lengths x k, times x sqrt(k))
    two geometrically similar blocks at equal ``PGV p / (g tan alpha)`` (and equal
    PGV/PGA times p) see the same dimensionless motion.

    Parameters
    ----------
    pgv_value : float
        Peak ground velocity [m/s].
    p : float
        Frequency parameter of the block ``sqrt(3 g / (4 R))`` [rad/s] (report Eq. 2.2).
    alpha : float
        Slenderness angle [rad], in (0, pi/2).
    """
    alpha = _slenderness(alpha)
    return float(pgv_value) * float(p) / (G * math.tan(alpha))


def _slenderness(alpha) -> float:
    alpha = _number("alpha", alpha)
    if not 0.0 < alpha < math.pi / 2:
        raise ValueError(f"alpha must be in (0, pi/2) [rad], got {alpha!r}")
    return alpha


def intensity_measures(motion, *, periods=(0.2, 0.5, 1.0, 2.0),
                       period_range=(0.2, 2.0), damping: float = 0.05,
                       component: str = "horizontal") -> dict:
    """Every measure of one motion, as a dict of table columns (SI).

    Columns: ``pga [m/s^2]``, ``pgv [m/s]``, ``pgd [m]``, ``pgv/pga [s]``,
    ``sa(T s) [m/s^2]`` for each ``T`` of ``periods``, ``sa_avg(T1-T2 s) [m/s^2]``
    over ``period_range``, ``arias [m/s]``, ``cav [m/s]``, ``d5-95 [s]``.
    (The block-normalised measures need a block: :func:`normalised_pga`,
    :func:`normalised_pgv`.)
    """
    motion = _motion("motion", motion)
    peak = pga(motion, component)
    if peak == 0.0:
        raise ValueError(f"the {component} component of motion {motion.name!r} is zero: "
                         "no intensity measure")
    velocity = pgv(motion, component)
    result = {
        "pga [m/s^2]": peak,
        "pgv [m/s]": velocity,
        "pgd [m]": pgd(motion, component),
        "pgv/pga [s]": velocity / peak,
    }
    periods = tuple(float(period) for period in periods)
    if periods:
        values = spectral_acceleration(motion, np.array(periods), damping, component)
        for period, value in zip(periods, values):
            result[sa_column(period)] = float(value)
    low, high = period_range
    result[sa_avg_column(low, high)] = average_spectral_acceleration(
        motion, low, high, damping=damping, component=component)
    result["arias [m/s]"] = arias_intensity(motion, component)
    result["cav [m/s]"] = cumulative_absolute_velocity(motion, component)
    result["d5-95 [s]"] = significant_duration(motion, component=component)
    return result


def sa_column(period: float) -> str:
    """Table column of Sa at ``period`` [s]."""
    return f"sa({period:g} s) [m/s^2]"


def sa_avg_column(low: float, high: float) -> str:
    """Table column of the average Sa over ``low`` to ``high`` [s]."""
    return f"sa_avg({low:g}-{high:g} s) [m/s^2]"


def scale_exponent(column: str) -> int:
    """Exponent ``n`` with ``IM(f a) = f^n IM(a)`` for a column of :func:`intensity_measures`."""
    if column in ("pgv/pga [s]", "d5-95 [s]"):
        return 0
    if column == "arias [m/s]":
        return 2
    return 1
