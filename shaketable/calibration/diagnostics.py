"""Warnings that say when a calibration's constant-COR answer should not be trusted.

A least-squares fit always returns a number with a narrow interval; these checks
say when the record does not obey the model behind that interval (one COR for
every impact, a plain anti-alias filter, the nominal block). Each check and its
threshold (:data:`THRESHOLDS`) was set on the records of an independent generator
(``benchmarks/calibration_scatter.py``, ``benchmarks/CALIBRATION.md``): silent on
clean constant-COR records, firing on records whose COR scatters from impact to
impact or depends on the impact velocity.

* **filter**: a fitted anti-alias cutoff below 0.15 x the sample rate (7.5 Hz at
  50 samples/s). Acquisition filters sit at 0.2-0.45 x the rate; a lower fitted
  cutoff means the filter is smoothing over a model error (typically the scatter
  of the COR), not describing the acquisition.
* **residuals**: lag-1 autocorrelation of the residuals above 0.5 (the 20 Hz
  filtered noise of a clean record gives about 0.1): the model misses a
  structure of the record.
* **methods**: the least-squares COR and the random-effects mean of the
  per-impact CORs (:mod:`~shaketable.calibration.scatter`) differ by more than
  2.58 standard errors of their difference (99 %).
* **scatter**: the impact-to-impact scatter of the COR is resolved (the lower end
  of its 95 % interval above 0) and at least 0.005: the least-squares interval
  describes one record's average of the impacts, not the block's COR.
* **velocity**: the slope of the per-impact COR against the impact velocity is
  more than 2.58 standard errors from 0 (Section 3.7 (1) of the report does not
  hold for this block).
* **size**: the period fit's corner-to-centroid distance R, fitted with alpha held
  at the nominal block's (``Calibration.periods_alpha_held``), differs from the
  nominal R by more than 3 standard errors and more than 2 %. (With alpha free, R
  and alpha trade off: on clean records R is then off by up to 7 % at up to 3
  standard errors, too loose to test the size.)
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from shaketable.calibration.peaks import PeakEstimate, PeriodFit
    from shaketable.calibration.scatter import CorScatter

#: The kinds of warning, in the order they are checked.
KINDS = ("filter", "residuals", "methods", "scatter", "velocity", "size")

#: Thresholds of the checks (see the module's docstring).
THRESHOLDS = {"filter_cutoff_per_rate": 0.15, "residual_lag1": 0.5, "methods_z": 2.58,
              "scatter_sigma": 0.005, "velocity_z": 2.58, "size_z": 3.0, "size_relative": 0.02}


def diagnose(*, rate: float, anti_alias: str, filter_cutoff: float, residual_lag1: float,
             cor: float, cor_se: float, peaks: PeakEstimate | None,
             scatter: CorScatter | None, periods: PeriodFit | None) -> list[tuple[str, str]]:
    """The warnings of one calibration as (kind, message) pairs, none when the record obeys
    the model (the kinds are :data:`KINDS`).

    Parameters
    ----------
    rate : float
        Samples per second of the record [1/s].
    anti_alias : str
        ``"fit"``, ``"known"`` or ``"none"``.
    filter_cutoff : float
        The modelled filter's cutoff [Hz] (inf for none).
    residual_lag1 : float
        Lag-1 autocorrelation of the least-squares residuals [-].
    cor, cor_se : float
        Least-squares COR and its standard error [-].
    peaks : PeakEstimate or None
    scatter : CorScatter or None
    periods : PeriodFit or None
        The period fit whose R is compared with the nominal block's (alpha held).
    """
    limits = THRESHOLDS
    warnings: list[tuple[str, str]] = []

    def warn(kind: str, message: str) -> None:
        warnings.append((kind, message))

    if anti_alias == "fit" and math.isfinite(filter_cutoff) \
            and filter_cutoff < limits["filter_cutoff_per_rate"] * rate:
        warn("filter",
            f"the fitted anti-alias filter ({filter_cutoff:.3g} Hz) is implausible for "
            f"{rate:.4g} samples/s (an acquisition's filter sits at 0.2-0.45 x the rate): it is "
            "smoothing over something the constant-COR model misses")
    if math.isfinite(residual_lag1) and residual_lag1 > limits["residual_lag1"]:
        warn("residuals",
            f"the residuals are strongly autocorrelated (lag-1 {residual_lag1:.2f}; noise "
            "gives about 0.1): the record does not follow one constant COR, and the "
            "least-squares interval is too narrow")
    if scatter is not None:
        difference = cor - scatter.mean
        z = difference / math.hypot(cor_se, scatter.mean_se)
        if abs(z) > limits["methods_z"]:
            warn("methods",
                f"least squares (COR {cor:.4f}) and the per-impact method (mean "
                f"{scatter.mean:.4f}, {scatter.mean_interval[0]:.4f} to "
                f"{scatter.mean_interval[1]:.4f}) disagree by {abs(z):.1f} standard errors")
        if scatter.sigma_interval[0] > 0 and scatter.sigma >= limits["scatter_sigma"]:
            warn("scatter",
                f"the COR scatters from impact to impact (sigma {scatter.sigma:.3f}, 95 % "
                f"{scatter.sigma_interval[0]:.3f} to {scatter.sigma_interval[1]:.3f}): use the "
                f"block's mean COR {scatter.mean:.4f} ({scatter.mean_interval[0]:.4f} to "
                f"{scatter.mean_interval[1]:.4f}), not the least-squares interval")
    if peaks is not None and abs(peaks.slope_z) > limits["velocity_z"]:
        warn("velocity",
            f"the COR depends on the impact velocity (slope {peaks.slope:+.3f} +- "
            f"{peaks.slope_se:.3f} s/rad, standard error; {abs(peaks.slope_z):.1f} standard errors): "
            "one COR does not describe this block (report Section 3.7 (1))")
    if periods is not None and periods.nominal is not None:
        z = periods.nominal_discrepancy()
        relative = periods.R / periods.nominal.R - 1.0
        if math.isfinite(z) and abs(z) > limits["size_z"] \
                and abs(relative) > limits["size_relative"]:
            warn("size",
                f"the period fit's size R = {periods.R:.4f} +- {periods.R_se:.4f} m is "
                f"{100 * abs(relative):.1f} % {'below' if relative < 0 else 'above'} the "
                f"nominal block's {periods.nominal.R:.4f} m ({abs(z):.1f} standard errors): "
                "check the block's size or its base")
    return warnings
