"""The answer of a calibration (:class:`Calibration`): COR with its interval, the fit's
residuals, JSON/CSV output and a figure; :func:`predict` runs the calibrated block.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, overload

import numpy as np

from shaketable.calibration.model import PARAMETERS
from shaketable.calibration.peaks import PeakEstimate, PeriodFit
from shaketable.calibration.record import FreeRockingRecord
from shaketable.calibration.scatter import CorScatter
from shaketable.core.constants import length_factor
from shaketable.core.equality import fields_equal
from shaketable.core.files import json_ready
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.units import format_length
from shaketable.models.api import simulate
from shaketable.models.rocking.result import RockingResult

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

    from shaketable.calibration.uncertainty import CalibratedCor, CalibratedEnsemble

#: Warning kinds (:data:`~shaketable.calibration.diagnostics.KINDS`) under which the
#: block's mean COR of the random-effects model is the answer: the COR scatters from
#: impact to impact, or the least-squares COR disagrees with the per-impact CORs. The
#: least-squares interval then describes one record's average of its impacts, not the
#: block, and the least-squares fit is kept as a diagnostic.
MEAN_COR_KINDS = ("scatter", "methods")

#: Key of the least-squares fit in :meth:`Calibration.summary` (a diagnostic when the
#: block's mean COR leads).
LEAST_SQUARES_KEY = "least_squares_fit (diagnostic)"


@dataclass(frozen=True)
class Calibration:
    """The COR identified from one free-rocking record.

    Attributes
    ----------
    record : FreeRockingRecord
    block : Block
    cor : float
        Least-squares COR [-]: the answer on a record that obeys one COR, a diagnostic
        when the COR scatters (then :attr:`answer` is the block's mean COR; see
        :attr:`mean_cor_leads`).
    cor_interval : tuple of float
        95 % interval of the COR [-] (``interval_method``).
    cor_se : float
        Standard error of the COR [-].
    theta0, theta0_se : float
        Release angle and standard error [rad].
    t_release, t_release_se : float
        Release time and standard error [s]: when the block left theta0, the
        modelled filter's delay removed (with ``anti_alias="none"`` the
        apparent release, delay included).
    offset, offset_se : float
        Sensor offset and standard error [record unit: rad or m].
    covariance : ndarray
        Covariance of the fitted parameters (``parameters``): 4 x 4, or 5 x 5
        with the fitted filter (its ``t_release`` is the apparent one).
    interval_method : str
        ``"acf"``, ``"hac"`` or ``"iid"`` (see :data:`INTERVALS`), or ``"bootstrap"``.
    bootstrap_interval : tuple or None
        Percentile interval of the moving-block bootstrap [-].
    bootstrap_cors : ndarray or None
        The bootstrap replicates [-].
    fitted, residuals : ndarray
        Model and record minus model at the samples [record unit].
    goodness : dict
        rms [unit], noise estimate [unit], R^2 [-], lag-1 autocorrelation of
        the residuals [-], samples, lags of the covariance, evaluations, time [s].
    peaks : PeakEstimate or None
        The independent peak-amplitude estimate (None if it failed).
    periods : PeriodFit or None
        The period fit for R and alpha (None if it failed).
    periods_alpha_held : PeriodFit or None
        The period fit for R alone, alpha held at the nominal block's: R is
        then determined 10-20 times better (R and alpha are strongly
        correlated in the free fit), and this R is what the size warning tests.
    notes : tuple of str
        Notes (parameters at a bound, failed side methods) and the
        ``warnings``, each prefixed ``WARNING:``.
    warnings : tuple of str
        The diagnostics that fired (:func:`~shaketable.calibration.diagnostics.diagnose`):
        an implausible fitted filter, autocorrelated residuals, methods that
        disagree, a COR that scatters or depends on the impact velocity, a
        period-fit size off the nominal block. Empty on a record that obeys
        the constant-COR model.
    warning_kinds : tuple of str
        The kind of each warning (:data:`~shaketable.calibration.diagnostics.KINDS`).
    scatter : CorScatter or None
        The random-effects model of the per-impact CORs: the block's mean COR
        with its interval and the impact-to-impact scatter sigma with its
        interval (:func:`~shaketable.calibration.scatter.cor_scatter`).
    anti_alias : str
        How the acquisition's filter was modelled: ``"fit"``, ``"known"`` or
        ``"none"`` (:data:`ANTI_ALIAS`).
    filter_order : int
        Poles of the modelled Butterworth filter.
    filter_cutoff : float
        Its cutoff [Hz] (fitted or given; inf for none).
    filter_delay : float
        Its low-frequency group delay [s] (:func:`butterworth_delay` / (2 pi f_c)).
    t_release_apparent : float
        Release time plus the filter's delay [s]: where the record's release
        shows (the theory runs of :func:`compare_free_rocking` start there).
    parameters : tuple of str
        Names of the fitted parameters, in the covariance's order.
    jacobian : ndarray
        d(model)/d(parameters) at the optimum, n x k [record unit / parameter
        unit], from which ``covariance`` was made (:func:`covariance_of`
        recomputes it another way).
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    record: FreeRockingRecord
    block: Block
    cor: float
    cor_interval: tuple[float, float]
    cor_se: float
    theta0: float
    theta0_se: float
    t_release: float
    t_release_se: float
    offset: float
    offset_se: float
    covariance: np.ndarray
    interval_method: str
    fitted: np.ndarray
    residuals: np.ndarray
    goodness: dict[str, Any]
    peaks: PeakEstimate | None = None
    periods: PeriodFit | None = None
    periods_alpha_held: PeriodFit | None = None
    bootstrap_interval: tuple[float, float] | None = None
    bootstrap_cors: np.ndarray | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)
    warnings: tuple[str, ...] = field(default_factory=tuple)
    warning_kinds: tuple[str, ...] = field(default_factory=tuple)
    scatter: CorScatter | None = None
    anti_alias: str = "none"
    filter_order: int = 4
    filter_cutoff: float = math.inf
    filter_delay: float = 0.0
    t_release_apparent: float | None = None
    parameters: tuple[str, ...] = PARAMETERS
    jacobian: np.ndarray | None = field(default=None, repr=False)

    @property
    def confidence(self) -> float:
        """Level of ``cor_interval`` [-]."""
        return 0.95

    @property
    def mean_cor_leads(self) -> bool:
        """Whether the block's mean COR (``scatter``) is the answer, not the least-squares
        ``cor``: the COR scatters from impact to impact or the two methods disagree
        (:data:`MEAN_COR_KINDS`)."""
        return self.scatter is not None and any(kind in MEAN_COR_KINDS
                                                for kind in self.warning_kinds)

    @property
    def answer(self) -> CalibratedCor:
        """The calibrated COR: the block's mean COR with its standard error, degrees of
        freedom and impact-to-impact scatter when :attr:`mean_cor_leads`, else the
        least-squares COR and its standard error (with the scatter model's sigma when there
        is one). What :meth:`summary` heads with, :meth:`predict` runs and ``simulate
        --cor calibration.json`` reads."""
        from shaketable.calibration.uncertainty import CalibratedCor

        source = f"calibration of {self.record.name}"
        sigma = self.scatter.sigma if self.scatter is not None else 0.0
        if self.mean_cor_leads and self.scatter is not None:
            # a noisy record's mean may pass 1, which no block restores: kept in (0, 1]
            return CalibratedCor(min(max(self.scatter.mean, 1e-9), 1.0), self.scatter.mean_se,
                                 self.scatter.dof, sigma, source)
        dof = max(int(self.goodness.get("samples", 1000)) - len(self.parameters), 1)
        return CalibratedCor(min(max(self.cor, 1e-9), 1.0), self.cor_se, dof, sigma, source)

    @property
    def answer_interval(self) -> tuple[float, float]:
        """95 % interval of :attr:`answer` [-]: the mean's (t quantile) or ``cor_interval``."""
        if self.mean_cor_leads and self.scatter is not None:
            return self.scatter.mean_interval
        return self.cor_interval

    def filter_text(self) -> str:
        """How the acquisition's filter was modelled, in words; a fitted cutoff at or above
        the Nyquist frequency (half the sample rate) is no filter."""
        nyquist = 0.5 * self.record.rate
        if self.anti_alias == "fit":
            if not math.isfinite(self.filter_cutoff):
                return "fitted filter: no filter"
            if self.filter_cutoff >= nyquist:
                return (f"fitted filter: no filter (its cutoff {self.filter_cutoff:.3g} Hz is "
                        f"above the Nyquist frequency {nyquist:.3g} Hz)")
            return f"fitted {self.filter_order}-pole filter at {self.filter_cutoff:.3g} Hz"
        if self.anti_alias == "known":
            return f"given {self.filter_order}-pole filter at {self.filter_cutoff:.3g} Hz"
        return "no filter modelled"

    def headline(self) -> str:
        """The answer in one line: the COR that leads with its 95 % interval and whence."""
        low, high = self.answer_interval
        if self.mean_cor_leads and self.scatter is not None:
            sc = self.scatter
            return (f"COR = {sc.mean:.4f}  (95 % interval {low:.4f} to {high:.4f}): the "
                    f"block's mean COR over {sc.impacts} impacts; it scatters from impact to "
                    f"impact, sigma {sc.sigma:.4f} ({sc.sigma_interval[0]:.4f} to "
                    f"{sc.sigma_interval[1]:.4f})")
        digits = self.digits
        return (f"COR = {self.cor:.{digits}f}  (95 % interval {low:.{digits}f} to "
                f"{high:.{digits}f}, least squares, {self.interval_method}; "
                f"{self.filter_text()})")

    def to_frame(self) -> pd.DataFrame:
        """FreeRockingRecord, fit and residuals as a :class:`pandas.DataFrame` (units in the names)."""
        import pandas as pd

        scale, unit = self.record.display_scale()
        return pd.DataFrame({
            "time [s]": self.record.t,
            f"record [{unit}]": self.record.values * scale,
            f"fitted [{unit}]": self.fitted * scale,
            f"residual [{unit}]": self.residuals * scale,
            "theta fitted [rad]": self.record.to_angle(self.fitted - self.offset, self.block),
        })

    def summary(self) -> dict[str, Any]:
        """JSON-ready scalar results (units in the keys)."""
        unit = "rad" if self.record.quantity == "angle" else "m"
        answer, (low, high) = self.answer, self.answer_interval
        least_squares = {
            "cor [-]": self.cor, "cor_low [-]": self.cor_interval[0],
            "cor_high [-]": self.cor_interval[1],
            "cor_interval [-]": [float(self.cor_interval[0]), float(self.cor_interval[1])],
            "cor_se [-]": self.cor_se, "interval": self.interval_method}
        data = {
            "record": self.record.name, "quantity": self.record.quantity,
            "block_height [m]": self.block.height, "block_width [m]": self.block.width,
            # the headline: the COR that leads (read by CalibratedCor.from_summary)
            "cor_source": ("block mean (random effects)" if self.mean_cor_leads
                           else "least squares"),
            "cor [-]": answer.mean, "cor_low [-]": low, "cor_high [-]": high,
            "cor_interval [-]": [float(low), float(high)],
            "cor_interval_level [-]": self.confidence, "cor_se [-]": answer.mean_se,
            "cor_dof": answer.dof, "cor_sigma [-]": answer.sigma,
            "interval": ("Hartung-Knapp t" if self.mean_cor_leads else self.interval_method),
            LEAST_SQUARES_KEY: {key: json_ready(value) for key, value in least_squares.items()},
            "anti_alias": self.anti_alias, "filter_order": self.filter_order,
            "filter_cutoff [Hz]": self.filter_cutoff, "filter_delay [s]": self.filter_delay,
            "theta0 [rad]": self.theta0, "theta0_se [rad]": self.theta0_se,
            "theta0/alpha [-]": self.theta0 / self.block.alpha,
            "t_release [s]": self.t_release, "t_release_se [s]": self.t_release_se,
            "t_release_apparent [s]": self.t_release_apparent,
            f"offset [{unit}]": self.offset, f"offset_se [{unit}]": self.offset_se,
        }
        data.update({f"fit {key}": value for key, value in self.goodness.items()})
        if self.bootstrap_interval is not None and self.bootstrap_cors is not None:
            data["bootstrap_low [-]"], data["bootstrap_high [-]"] = self.bootstrap_interval
            data["bootstrap_samples"] = int(self.bootstrap_cors.size)
        if self.peaks is not None:
            data.update({"peak_cor [-]": self.peaks.cor,
                         "peak_cor_low [-]": self.peaks.cor_interval[0],
                         "peak_cor_high [-]": self.peaks.cor_interval[1],
                         "peaks_used": int(self.peaks.amplitudes.size),
                         "cor_vs_velocity_slope [s/rad]": self.peaks.slope,
                         "cor_vs_velocity_slope_se [s/rad]": self.peaks.slope_se,
                         "cor_velocity_independent": self.peaks.velocity_independent})
        if self.scatter is not None:
            data.update(self.scatter.summary())
        if self.periods is not None:
            effective = self.periods.block
            height_se, width_se = self.periods.size_se()
            data.update({"period_fit_height_se [m]": height_se,
                         "period_fit_width_se [m]": width_se})
            data.update({"period_fit_R [m]": self.periods.R,
                         "period_fit_R_se [m]": self.periods.R_se,
                         "period_fit_alpha [rad]": self.periods.alpha,
                         "period_fit_alpha_se [rad]": self.periods.alpha_se,
                         "period_fit_height [m]": effective.height,
                         "period_fit_width [m]": effective.width,
                         "period_fit_rms [s]": self.periods.rms})
        if self.periods_alpha_held is not None:
            held = self.periods_alpha_held
            data.update({"period_fit_alpha_held_R [m]": held.R,
                         "period_fit_alpha_held_R_se [m]": held.R_se,
                         "period_fit_alpha_held_R_discrepancy [se]": held.nominal_discrepancy()})
        data["notes"] = list(self.notes)
        data["warnings"] = list(self.warnings)
        data["warning_kinds"] = list(self.warning_kinds)
        return {key: json_ready(value) for key, value in data.items()}

    def to_json(self, path: str | os.PathLike[str] | None = None) -> str:
        """The summary as JSON text; written to ``path`` when given."""
        text = json.dumps(self.summary(), indent=2)
        if path is not None:
            from shaketable.core.files import write_text

            write_text(path, text + "\n")
        return text

    def plot(self, fig: Figure | None = None, title: str | None = None) -> Figure:
        """FreeRockingRecord, fitted curve, residuals, COR per impact and periods (PNG-ready figure)."""
        from shaketable.plots.calibration import plot_calibration

        return plot_calibration(self, fig=fig, title=title)

    def predict(self, motion: Motion | None = None,
                **kwargs: Any) -> RockingResult | CalibratedEnsemble:
        """The theory run (or ensemble) with the calibrated COR (see :func:`predict`)."""
        return predict(self, motion, **kwargs)

    @property
    def digits(self) -> int:
        """Decimals worth printing for the COR: one beyond the interval's half-width."""
        half = 0.5 * (self.cor_interval[1] - self.cor_interval[0])
        return max(4, int(math.ceil(-math.log10(half))) + 1) if half > 0 else 6

    def text(self) -> str:
        """Human summary: the answer first (:meth:`headline`), then the diagnostics.

        "+-" is one standard error everywhere in it; intervals are 95 %.
        """
        low, high = self.cor_interval
        digits = self.digits
        size_unit = self.block.length_unit     # lengths in the unit the block was given in
        if self.record.quantity == "angle":
            rms = f"{self.goodness['rms']:.3g} rad"
        elif size_unit == "m":
            rms = f"{self.goodness['rms']:.3g} m"
        else:
            rms = format_length(self.goodness["rms"], size_unit)
        lines = [self.headline()]
        if self.mean_cor_leads:
            lines.append(f"least-squares fit (diagnostic; its interval holds for one COR at "
                         f"every impact): COR {self.cor:.{digits}f} ({low:.{digits}f} to "
                         f"{high:.{digits}f}, {self.interval_method}; {self.filter_text()})")
        lines.append(f"release angle {self.theta0:.5f} rad = "
                     f"{self.theta0 / self.block.alpha:.3f} alpha at t = {self.t_release:.3f} "
                     f"s; fit rms {rms}, R^2 "
                     f"{self.goodness['r_squared']:.6f}")
        if self.bootstrap_interval is not None and self.bootstrap_cors is not None:
            lines.append(f"bootstrap ({self.bootstrap_cors.size}): "
                         f"{self.bootstrap_interval[0]:.{digits}f} to "
                         f"{self.bootstrap_interval[1]:.{digits}f}")
        if self.peaks is not None:
            p = self.peaks
            lines.append(f"peak method: COR = {p.cor:.4f} ({p.cor_interval[0]:.4f} to "
                         f"{p.cor_interval[1]:.4f}) from {p.amplitudes.size} peaks; COR vs "
                         f"impact velocity slope {p.slope:+.4f} +- {p.slope_se:.4f} s/rad"
                         + (" (no dependence)" if p.velocity_independent else " (DEPENDS)"))
        if self.scatter is not None and not self.mean_cor_leads:
            sc = self.scatter
            lines.append(f"block's mean COR (random effects over {sc.impacts} impacts) = "
                         f"{sc.mean:.4f} (95 % interval {sc.mean_interval[0]:.4f} to "
                         f"{sc.mean_interval[1]:.4f}); impact-to-impact scatter sigma = "
                         f"{sc.sigma:.4f} ({sc.sigma_interval[0]:.4f} to "
                         f"{sc.sigma_interval[1]:.4f})")
        if self.periods is not None:
            e = self.periods.block
            height_se, width_se = self.periods.size_se()
            scale = length_factor(size_unit)
            lines.append(f"period fit: R = {_radius(self.periods.R, self.periods.R_se, size_unit)}, "
                         f"alpha = {self.periods.alpha:.4f} +- {self.periods.alpha_se:.4f} rad "
                         f"-> {e.height / scale:.4g} +- {height_se / scale:.2g} x "
                         f"{e.width / scale:.4g} +- {width_se / scale:.2g} {size_unit} (standard errors; "
                         f"nominal {self.block.describe()})"
                         + (f"; at the nominal alpha R = "
                            f"{_radius(self.periods_alpha_held.R, self.periods_alpha_held.R_se, size_unit)}"
                            f" (nominal {_radius(self.block.R, None, size_unit)})"
                            if self.periods_alpha_held is not None else ""))
        lines.extend(note if note.startswith("WARNING: ") else f"note: {note}"
                     for note in self.notes)
        lines.append("(+- is one standard error; intervals are 95 %)")
        return "\n".join(lines)


def _radius(value: float, se: float | None, unit: str) -> str:
    """A fitted length [m] with its standard error [m] (None: none), in the block's ``unit``:
    ``"0.3800 +- 0.0045 m"``, ``"14.96 +- 0.18 in"``."""
    if unit == "m":
        return f"{value:.4f}" + ("" if se is None else f" +- {se:.4f}") + " m"
    scale = length_factor(unit)
    return f"{value / scale:#.4g}" + ("" if se is None else f" +- {se / scale:.2g}") + f" {unit}"


# ------------------------------------------------------------------ theory run
@overload
def predict(calibration: Calibration, motion: None = None, *, duration: float | None = None,
            theta0: float | None = None, members: int = 200, seed: int = 0,
            **kwargs: Any) -> RockingResult: ...


@overload
def predict(calibration: Calibration, motion: Motion, *, duration: float | None = None,
            theta0: float | None = None, members: int = 200, seed: int = 0,
            **kwargs: Any) -> RockingResult | CalibratedEnsemble: ...


def predict(calibration: Calibration, motion: Motion | None = None, *,
            duration: float | None = None, theta0: float | None = None,
            members: int = 200, seed: int = 0,
            **kwargs: Any) -> RockingResult | CalibratedEnsemble:
    """The theory run with the calibrated COR (the report's use of nu = 0.925, Section 3.6).

    The COR is the calibration's answer (:attr:`Calibration.answer`). When the block's
    mean COR leads (the COR scatters, :attr:`Calibration.mean_cor_leads`) a table motion
    is run as an ensemble over the COR that the mean's interval and the scatter imply
    (:func:`~shaketable.calibration.uncertainty.calibrated_ensemble`, what ``shaketable
    simulate --cor calibration.json`` runs); otherwise, and for free rocking, one run.

    Parameters
    ----------
    calibration : Calibration
    motion : Motion, optional
        Table motion; ``None`` repeats the free-rocking test from the fitted
        release angle (time measured from the release).
    duration : float, optional
        Length of the run [s] (default: the record's length after release).
    theta0 : float, optional
        Initial rotation [rad] (default: the fitted release angle for free
        rocking, 0 under a motion; an ensemble starts at rest).
    members, seed : int
        Size and seed of the ensemble (when one is run).
    **kwargs
        Passed to :func:`shaketable.models.api.simulate` (an ensemble takes
        ``method`` and ``threads``).

    Returns
    -------
    RockingResult or CalibratedEnsemble
    """
    if not isinstance(calibration, Calibration):
        raise ValueError(f"calibration must be a Calibration, got {type(calibration).__name__}")
    answer = calibration.answer
    if motion is not None and calibration.mean_cor_leads:
        from shaketable.calibration.uncertainty import calibrated_ensemble

        if theta0 not in (None, 0.0):
            raise ValueError(f"theta0 = {theta0!r}: the ensemble of a scattering COR starts "
                             "at rest (theta0 = 0)")
        unknown = sorted(set(kwargs) - {"method", "threads"})
        if unknown:
            raise ValueError(f"{', '.join(unknown)}: not options of the calibrated ensemble "
                             "(method, threads)")
        return calibrated_ensemble(calibration.block, motion, answer, members=members,
                                   seed=seed, duration=duration, **kwargs)
    if motion is None:
        theta0 = calibration.theta0 if theta0 is None else theta0
        if duration is None:
            duration = float(calibration.record.t[-1] - calibration.t_release)
    else:
        theta0 = 0.0 if theta0 is None else theta0
    return simulate(calibration.block, motion, cor=answer.mean, theta0=theta0,
                    duration=duration, **kwargs)
