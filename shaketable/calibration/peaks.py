"""Classical estimates from a free-rocking record: noise level, zero crossings, peaks,
the COR from successive peak ratios (Eq. 2-17) and from the periods (Eq. 2-7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import scipy.optimize
import scipy.signal
import scipy.stats

from shaketable.calibration.record import CalibrationError, FreeRockingRecord
from shaketable.core.geometry import Block
from shaketable.core.theory import exact_period, impact_velocity


# ------------------------------------------------------------------ signal helpers
def noise_level(values: npt.ArrayLike) -> float:
    """Robust estimate of the white-noise RMS of a smooth record [its unit].

    The median absolute fourth difference, scaled: for white noise of RMS
    sigma the fourth difference has RMS sqrt(70) sigma, and MAD/0.6745 is the
    RMS of a Gaussian. A free-rocking angle sampled at 50 Hz contributes
    ~ p^4 theta dt^4 ~ 1e-5 rad, below typical noise; correlated (filtered)
    noise is underestimated, so use this for checks only.
    """
    values = np.asarray(values, dtype=float)
    if values.size < 8:
        return float(np.std(values))
    fourth = np.diff(values, 4)
    return float(np.median(np.abs(fourth - np.median(fourth))) / 0.6745 / math.sqrt(70.0))


def threshold_crossings(theta: np.ndarray, threshold: float) -> list[int]:
    """Indices i where theta changes sign between i and i+1, with hysteresis ``threshold``."""
    crossings: list[int] = []
    state = 0
    last_index = 0          # index of the last sample beyond the threshold (once state != 0)
    for index, value in enumerate(theta):
        if value > threshold:
            sign = 1
        elif value < -threshold:
            sign = -1
        else:
            continue
        if state != 0 and sign != state:
            # the actual crossing: last sample of the old sign before this index
            segment = theta[last_index:index + 1] * state
            inside = np.flatnonzero(segment > 0)
            crossings.append(last_index + int(inside[-1]))
        state = sign
        last_index = index
    return crossings


@dataclass(frozen=True)
class _Peaks:
    times: np.ndarray        # [s]
    amplitudes: np.ndarray   # |theta| [rad]
    signs: np.ndarray
    zeros: np.ndarray        # time of the zero crossing after each peak [s] (NaN if none)
    first_is_release: bool
    zeros_before: np.ndarray  # time of the zero crossing before each peak [s] (NaN if none)


def zero_time(t: np.ndarray, theta: np.ndarray, index: int) -> float:
    """Linear interpolation of the zero of theta between samples index and index+1 [s]."""
    a, b = theta[index], theta[index + 1]
    return float(t[index] + (t[index + 1] - t[index]) * a / (a - b))


def find_peaks(t: np.ndarray, theta: np.ndarray, block: Block, sigma: float, *,
               plateau_end: float | None = None) -> _Peaks:
    """Peaks of a free-rocking angle: one extreme between successive zero crossings.

    Each peak is refined by a least-squares parabola over the samples within a
    quarter of the local quarter-period of the sample maximum (the solution
    near a turning point is a parabola to O(tau^4)). The first segment, which
    holds the release, takes its amplitude from the samples before
    ``plateau_end`` when the record starts before the release.
    """
    threshold = max(4.0 * sigma, 1e-3 * block.alpha)
    crossings = threshold_crossings(theta, threshold)
    bounds = [0] + [c + 1 for c in crossings] + [theta.size]
    times: list[float] = []
    amplitudes: list[float] = []
    signs: list[float] = []
    zeros: list[float] = []
    before: list[float] = []
    first_is_release = False
    for number, (start, stop) in enumerate(zip(bounds[:-1], bounds[1:])):
        segment = theta[start:stop]
        if segment.size == 0:
            continue
        sign = 1.0 if np.median(segment) >= 0 else -1.0
        local = int(np.argmax(segment * sign)) + start
        amplitude = abs(theta[local])
        if amplitude <= threshold or amplitude >= block.alpha:
            continue
        zero = (zero_time(t, theta, crossings[number]) if number < len(crossings)
                else math.nan)
        before.append(zero_time(t, theta, crossings[number - 1]) if number >= 1 else math.nan)
        if number == 0 and plateau_end is not None and plateau_end > t[0] + 2 * (t[1] - t[0]):
            held = (t < plateau_end) & (t >= t[0])
            times.append(float(plateau_end))
            amplitudes.append(float(abs(np.median(theta[held]))))
            signs.append(sign)
            zeros.append(zero)
            first_is_release = True
            continue
        quarter = exact_period(block, min(amplitude, 0.95 * block.alpha)) / 4.0
        window = (np.abs(t - t[local]) <= 0.25 * quarter) & (np.arange(t.size) >= start) & (
            np.arange(t.size) < stop)
        if np.count_nonzero(window) >= 3 and start < local < stop - 1:
            tau = t[window] - t[local]
            c2, c1, c0 = np.polyfit(tau, theta[window], 2)
            if c2 * sign < 0:
                vertex = -c1 / (2 * c2)
                if abs(vertex) <= np.max(np.abs(tau)):
                    times.append(float(t[local] + vertex))
                    amplitudes.append(float(abs(c0 - c1 * c1 / (4 * c2))))
                    signs.append(sign)
                    zeros.append(zero)
                    continue
        if start == 0 or stop == theta.size:
            before.pop()
            continue            # an extreme cut by the record's ends is not a peak
        times.append(float(t[local]))
        amplitudes.append(float(amplitude))
        signs.append(sign)
        zeros.append(zero)
    return _Peaks(np.array(times), np.array(amplitudes), np.array(signs), np.array(zeros),
                  first_is_release, np.array(before))


@dataclass(frozen=True)
class PeakEstimate:
    """COR from successive peak amplitudes (Eq. 2-6 between impacts).

    Attributes
    ----------
    cor : float
        Constant COR fitted to all peaks [-]: log E_n = log E_0 + 2 n log(cor),
        E_n = cos(alpha - theta_n) - cos(alpha).
    cor_interval : tuple of float
        95 % interval of ``cor`` (weighted regression, t quantile) [-].
    peak_times, amplitudes : ndarray
        Times [s] and amplitudes |theta_n| [rad] of the peaks used.
    cor_per_impact, cor_per_impact_se : ndarray
        sqrt(E_{n+1} / E_n) for each impact and its standard error [-].
    impact_velocity : ndarray
        Angular velocity reached before each impact, from theta_n by energy
        conservation (:func:`shaketable.core.theory.impact_velocity`) [rad/s].
    slope, slope_se, intercept : float
        Weighted linear trend of the per-impact COR against the impact
        velocity [s/rad], its standard error, and the intercept [-]: a slope
        consistent with 0 supports the report's Section 3.7 (1).
    log_energy_se : ndarray or None
        Standard error of log E_n of each peak from the noise [-] (the
        measurement covariance of the per-impact CORs is built from it:
        successive CORs share a peak).
    """

    cor: float
    cor_interval: tuple[float, float]
    peak_times: np.ndarray
    amplitudes: np.ndarray
    cor_per_impact: np.ndarray
    cor_per_impact_se: np.ndarray
    impact_velocity: np.ndarray
    slope: float
    slope_se: float
    intercept: float
    log_energy_se: np.ndarray | None = None

    @property
    def velocity_independent(self) -> bool:
        """True when the 95 % interval of the trend's slope contains 0."""
        return bool(abs(self.slope) <= 1.96 * self.slope_se) if np.isfinite(self.slope) else True

    @property
    def slope_z(self) -> float:
        """Slope of the COR against the impact velocity in standard errors [-] (0 if none)."""
        if not (np.isfinite(self.slope) and self.slope_se > 0):
            return 0.0
        return float(self.slope / self.slope_se)


def peak_estimate(record: FreeRockingRecord, block: Block, *, offset: float = 0.0,
                  t_release: float | None = None, min_amplitude: float | None = None,
                  sigma: float | None = None) -> PeakEstimate:
    """COR from successive peaks with the exact energy relation between impacts.

    Between impacts energy is conserved; an impact scales the energy of
    rotation by COR^2 (Eq. 2-6, :func:`shaketable.core.theory.amplitude_after_impact`),
    so with E_n = cos(alpha - theta_n) - cos(alpha) (potential energy at the
    n-th peak over M g R), E_{n+1} = COR^2 E_n exactly for free rocking.

    Parameters
    ----------
    record : FreeRockingRecord
    block : Block
        Gives alpha (and the height for a displacement record).
    offset : float
        Sensor offset removed first [record unit].
    t_release : float, optional
        Release time [s] when the record starts with the block held.
    min_amplitude : float, optional
        Smallest amplitude used [rad] (default max(20 sigma, 0.03 alpha)):
        below it the peak's relative error grows as sigma / theta_n.
    sigma : float, optional
        Noise RMS of the angle [rad] (default :func:`noise_level`).
    """
    theta = record.to_angle(record.values - offset, block)
    sigma = noise_level(theta) if sigma is None else sigma
    peaks = find_peaks(record.t, theta, block, sigma, plateau_end=t_release)
    floor = max(20.0 * sigma, 0.03 * block.alpha) if min_amplitude is None else min_amplitude
    keep = peaks.amplitudes >= floor
    # keep the leading run of consecutive peaks above the floor
    last = int(np.argmin(keep)) if not np.all(keep) else keep.size
    amplitudes, times = peaks.amplitudes[:last], peaks.times[:last]
    if amplitudes.size < 3:
        raise CalibrationError(
            f"only {amplitudes.size} peak(s) above {floor:.3g} rad: too short or too little "
            "rocking for the peak method (3 are needed)")
    alpha = block.alpha
    energy = np.cos(alpha - amplitudes) - math.cos(alpha)
    # d E / d theta = sin(alpha - theta): the standard error of log E_n is sigma_n sin()/E
    sigma_peak = max(sigma, 1e-12) * np.ones_like(amplitudes)
    log_se = sigma_peak * np.sin(alpha - amplitudes) / energy
    n = np.arange(amplitudes.size, dtype=float)
    weights = 1.0 / log_se**2
    design = np.column_stack([np.ones_like(n), n])
    wls = design * np.sqrt(weights)[:, None]
    coefficients, *_ = np.linalg.lstsq(wls, np.log(energy) * np.sqrt(weights), rcond=None)
    residual = (np.log(energy) - design @ coefficients) * np.sqrt(weights)
    dof = max(amplitudes.size - 2, 1)
    # the scatter about the line measures the peaks' real noise (sigma from noise_level is a
    # rough guess): scale by it, with the t quantile for the few degrees of freedom
    scale = float(np.sum(residual**2) / dof) if amplitudes.size > 3 else 1.0
    covariance = np.linalg.inv(wls.T @ wls) * scale
    slope, slope_se = coefficients[1], math.sqrt(covariance[1, 1])
    quantile = scipy.stats.t.ppf(0.975, dof)
    cor = math.exp(slope / 2.0)
    interval = (math.exp((slope - quantile * slope_se) / 2.0),
                math.exp((slope + quantile * slope_se) / 2.0))
    per_impact = np.sqrt(energy[1:] / energy[:-1])
    per_impact_se = 0.5 * per_impact * np.sqrt(log_se[1:]**2 + log_se[:-1]**2)
    velocity = np.array([impact_velocity(block, a) for a in amplitudes[:-1]])
    trend_slope = trend_se = math.nan
    intercept = float(np.mean(per_impact))
    if per_impact.size >= 3 and np.ptp(velocity) > 0:
        w = 1.0 / per_impact_se**2
        a = np.column_stack([np.ones_like(velocity), velocity]) * np.sqrt(w)[:, None]
        fit, *_ = np.linalg.lstsq(a, per_impact * np.sqrt(w), rcond=None)
        res = per_impact * np.sqrt(w) - a @ fit
        scale = max(float(np.sum(res**2) / max(per_impact.size - 2, 1)), 1.0)
        cov = np.linalg.inv(a.T @ a) * scale
        intercept, trend_slope, trend_se = float(fit[0]), float(fit[1]), math.sqrt(cov[1, 1])
    return PeakEstimate(cor=cor, cor_interval=interval, peak_times=times, amplitudes=amplitudes,
                        cor_per_impact=per_impact, cor_per_impact_se=per_impact_se,
                        impact_velocity=velocity, slope=trend_slope, slope_se=trend_se,
                        intercept=intercept, log_energy_se=log_se)


@dataclass(frozen=True)
class PeriodFit:
    """Effective block size from periods alone (Table 3.1 / Fig. 3.6).

    Attributes
    ----------
    amplitudes, periods : ndarray
        Peak amplitude [rad] and the report's period, 4 x (time from the peak
        to the next zero) [s] (Section 3.7 (1)).
    R, R_se : float
        Fitted corner-to-centroid distance [m] and its standard error.
    alpha, alpha_se : float
        Fitted block angle [rad] (held at the nominal value, se 0, when
        ``fit_alpha`` is False).
    nominal : Block or None
        The block the user named, for comparison.
    rms : float
        RMS of the period residuals [s].
    method : str
        How the periods were measured: ``"zeros"`` or ``"report"``.
    covariance : ndarray or None
        Covariance of (R, alpha) [m^2, m rad, rad^2] (1 x 1 of R with alpha
        held).
    """

    amplitudes: np.ndarray
    periods: np.ndarray
    R: float
    R_se: float
    alpha: float
    alpha_se: float
    nominal: Block | None
    rms: float
    method: str = "zeros"
    covariance: np.ndarray | None = None

    @property
    def block(self) -> Block:
        """The effective block: height 2 R cos(alpha), width 2 R sin(alpha)."""
        return Block.from_slenderness(self.R, self.alpha)

    def size_se(self) -> tuple[float, float]:
        """Standard errors of the effective height and width [m] (delta method, with the
        covariance of R and alpha)."""
        gradient = np.array([[2 * math.cos(self.alpha), -2 * self.R * math.sin(self.alpha)],
                             [2 * math.sin(self.alpha), 2 * self.R * math.cos(self.alpha)]])
        if self.covariance is not None and self.covariance.shape == (2, 2):
            covariance = self.covariance
        else:
            covariance = np.diag([self.R_se**2, self.alpha_se**2])
        size = gradient @ covariance @ gradient.T
        return float(math.sqrt(max(size[0, 0], 0.0))), float(math.sqrt(max(size[1, 1], 0.0)))

    def nominal_discrepancy(self) -> float:
        """(fitted R - nominal R) / its standard error [-] (NaN without a nominal block)."""
        if self.nominal is None or not (self.R_se > 0):
            return math.nan
        return (self.R - self.nominal.R) / self.R_se

    def curve(self, amplitudes: npt.ArrayLike, R: float | None = None,
              alpha: float | None = None) -> np.ndarray:
        """Exact period [s] at ``amplitudes`` [rad] for (R, alpha) (default: fitted)."""
        block = Block.from_slenderness(self.R if R is None else R,
                                       self.alpha if alpha is None else alpha)
        return np.array([exact_period(block, a) if 0 < a < block.alpha else math.nan
                         for a in np.atleast_1d(amplitudes)])


def period_fit(record: FreeRockingRecord, block: Block, *, offset: float = 0.0,
               t_release: float | None = None, fit_alpha: bool = True,
               sigma: float | None = None, method: str = "zeros") -> PeriodFit:
    """Fit the exact period of Eq. (2-3) to the record's periods for R (and alpha).

    Each peak after the release gives a period at amplitude theta_n:

    * ``method="zeros"`` (default): twice the time between the zero crossings
      (impacts) around the peak. Free rocking between two impacts is
      symmetric, so this is exactly half the period at theta_n, and zero
      crossings (where |theta'| is largest) are timed far more precisely
      than peaks.
    * ``method="report"``: 4 x (time from the peak to the next zero), the
      report's measurement (Section 3.7 (1), Table 3.1).

    The exact period
    T(theta; R, alpha) (:func:`shaketable.core.theory.exact_period`; p = sqrt(3 g / 4 R))
    is fitted by least squares, starting from ``block``.

    Raises
    ------
    CalibrationError
        Fewer than 3 periods (2 with ``fit_alpha=False``).
    """
    theta = record.to_angle(record.values - offset, block)
    sigma = noise_level(theta) if sigma is None else sigma
    peaks = find_peaks(record.t, theta, block, sigma, plateau_end=t_release)
    if method not in ("zeros", "report"):
        raise ValueError(f"method must be 'zeros' or 'report', got {method!r}")
    if method == "report":
        measured = 4.0 * (peaks.zeros - peaks.times)
    else:
        measured = 2.0 * (peaks.zeros - peaks.zeros_before)
    use = np.isfinite(measured) & (peaks.amplitudes > max(10 * sigma, 0.05 * block.alpha))
    if peaks.first_is_release:
        use[0] = False          # the release time is not a measured peak
    amplitudes = peaks.amplitudes[use]
    periods = measured[use]
    needed = 3 if fit_alpha else 2
    if amplitudes.size < needed:
        raise CalibrationError(f"only {amplitudes.size} measurable period(s): too short or too "
                               f"little rocking for the period fit ({needed} are needed)")

    def residuals(x: np.ndarray) -> np.ndarray:
        R, alpha = x[0], (x[1] if fit_alpha else block.alpha)
        trial = Block.from_slenderness(R, alpha)
        return np.array([exact_period(trial, min(a, 0.999 * alpha)) for a in amplitudes]) - periods

    x0 = [block.R, block.alpha] if fit_alpha else [block.R]
    upper = [10 * block.R, 0.45 * math.pi] if fit_alpha else [10 * block.R]
    lower = [0.1 * block.R, 1.001 * float(np.max(amplitudes))] if fit_alpha else [0.1 * block.R]
    if fit_alpha and lower[1] >= x0[1]:
        x0[1] = 1.05 * lower[1]
    solution = scipy.optimize.least_squares(residuals, x0, bounds=(lower, upper),
                                            x_scale=[block.R, block.alpha][:len(x0)])
    dof = max(amplitudes.size - len(x0), 1)
    s2 = float(np.sum(solution.fun**2) / dof)
    try:
        cov = np.linalg.inv(solution.jac.T @ solution.jac) * s2
        se = np.sqrt(np.diag(cov))
    except np.linalg.LinAlgError:
        cov = None
        se = np.full(len(x0), math.nan)
    return PeriodFit(amplitudes=amplitudes, periods=periods, R=float(solution.x[0]),
                     R_se=float(se[0]),
                     alpha=float(solution.x[1]) if fit_alpha else block.alpha,
                     alpha_se=float(se[1]) if fit_alpha else 0.0, nominal=block,
                     rms=float(np.sqrt(np.mean(solution.fun**2))), method=method,
                     covariance=cov)
