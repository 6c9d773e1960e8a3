"""Figures of the sensors and the COR calibration (matplotlib is imported only here).

* :func:`plot_measurement` -- a digitized record (angle, table accelerations).
* :func:`plot_fit` -- the record, the fitted engine curve and the residuals.
* :func:`plot_cor_per_impact` -- COR of each impact against the impact velocity
  (the check of the report's Section 3.7 (1) claim).
* :func:`plot_periods` -- period against amplitude (Table 3.1 / Fig. 3.6 style).
* :func:`plot_calibration` -- the four panels above in one figure.

Every function takes ``ax=None`` (or ``fig=None``) and returns what it drew on.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from shaketable.core.constants import G, length_factor
from shaketable.plots.base import place_legend, pyplot

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from shaketable.calibration.peaks import PeakEstimate, PeriodFit
    from shaketable.calibration.result import Calibration
    from shaketable.calibration.scatter import CorScatter


def _figure(fig, nrows, ncols=1, figsize=(8.0, 6.0), **kwargs):
    plt = pyplot()

    if fig is None:
        fig = plt.figure(figsize=figsize, layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, **kwargs)
    return fig, axes


def plot_measurement(measurement, fig: Figure | None = None,
                     title: str | None = None) -> Figure:
    """Angle (report's and exact) and the table accelerations of a :class:`Measurement`.

    Draws the channels the measurement has: ``theta`` (with ``theta_exact``
    dashed when it is there: a :class:`~shaketable.lab.sensors.Measurement`
    built by hand may carry ``theta`` alone), ``table_horizontal`` and
    ``table_vertical``, one panel each, over a shared time axis.

    Parameters
    ----------
    measurement : shaketable.lab.sensors.Measurement
        The record; ``t`` [s], angles [rad], accelerations [m/s^2].
    fig : matplotlib.figure.Figure, optional
        Figure to draw in (empty); default a new one.
    title : str, optional
        Figure title; default the block and the sample rate.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        The measurement has none of the three channels.
    """
    channels = [("theta", measurement.theta is not None),
                ("horizontal", measurement.table_horizontal is not None),
                ("vertical", measurement.table_vertical is not None)]
    panels = [name for name, present in channels if present]
    if not panels:
        raise ValueError("the measurement has no channel to plot")
    fig, axes = _figure(fig, len(panels), figsize=(8.0, 2.2 * len(panels) + 0.8), sharex=True)
    alpha = measurement.block.alpha
    angle_axis = None
    for ax, name in zip(axes[:, 0], panels):
        if name == "theta":
            ax.plot(measurement.t, measurement.theta / alpha, lw=0.9,
                    label="-top displacement / H (report)")
            if measurement.theta_exact is not None:
                ax.plot(measurement.t, measurement.theta_exact / alpha, lw=0.9, ls="--",
                        label="exact geometry")
            ax.set_ylabel("θ/α [-]")
            angle_axis = ax
        elif name == "horizontal":
            ax.plot(measurement.t, measurement.table_horizontal / G, lw=0.8)
            ax.set_ylabel("table horizontal [g]")
        else:
            ax.plot(measurement.t, measurement.table_vertical / G, lw=0.8)
            ax.set_ylabel("table vertical [g]")
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    fig.suptitle(title or f"{measurement.block.describe()} block, {measurement.rate:g} samples/s")
    if angle_axis is not None:  # after the layout is complete: a corner free of data
        place_legend(angle_axis, fontsize=8)
    return fig


def plot_fit(calibration: Calibration,
             axes: tuple[Axes, Axes] | None = None) -> tuple[Axes, Axes]:
    """Record, fitted curve (top) and residuals (bottom). Returns the two axes."""
    if axes is None:
        _, grid = _figure(None, 2, figsize=(8.0, 5.0), sharex=True,
                          gridspec_kw={"height_ratios": [3, 1]})
        axes = grid[:, 0]
    top, bottom = axes
    record = calibration.record
    scale, unit = record.display_scale()
    top.plot(record.t, record.values * scale, ".", ms=2.5, color="0.35", label="record")
    digits = calibration.digits
    top.plot(record.t, calibration.fitted * scale, lw=1.0, color="C3",
             label=f"engine, least-squares COR {calibration.cor:.{digits}f}")
    top.axvline(calibration.t_release, color="C2", lw=0.8, ls=":", label="release (fitted)")
    if getattr(calibration, "anti_alias", "none") != "none":
        top.plot([], [], " ", label=calibration.filter_text())
    top.set_ylabel(f"{record.quantity} [{unit}]")
    place_legend(top, fontsize=8)
    top.grid(alpha=0.3)
    # the answer leads: the block's mean COR when it scatters, else the least-squares COR
    low, high = calibration.answer_interval
    if calibration.mean_cor_leads:
        title = (f"COR = {calibration.answer.mean:.4f}  (95 % interval {low:.4f} to "
                 f"{high:.4f}), the block's mean; the COR scatters (curve: least-squares "
                 "fit, a diagnostic)")
    else:
        title = (f"COR = {calibration.cor:.{digits}f}  (95 % interval {low:.{digits}f} to "
                 f"{high:.{digits}f}, {calibration.interval_method})")
    top.set_title(title, fontsize=10)
    bottom.plot(record.t, calibration.residuals * scale, lw=0.6, color="0.2")
    bottom.axhline(0.0, color="C3", lw=0.8)
    bottom.set_ylabel(f"residual [{unit}]")
    bottom.set_xlabel("time [s]")
    bottom.grid(alpha=0.3)
    return top, bottom


#: The least height of the block mean's band, as a fraction of the axis's height [-].
_MIN_BAND = 0.04


def plot_cor_per_impact(peaks: PeakEstimate, ax: Axes | None = None,
                        scatter: CorScatter | None = None) -> Axes:
    """COR of each impact (from successive peaks) against the impact velocity. Returns the axes.

    With ``scatter`` (the random-effects model) its mean COR and 95 % interval are shaded.
    """
    if ax is None:
        _, grid = _figure(None, 1, figsize=(6.0, 4.0))
        ax = grid[0, 0]
    ax.errorbar(peaks.impact_velocity, peaks.cor_per_impact, yerr=1.96 * peaks.cor_per_impact_se,
                fmt="o", ms=4, capsize=2, label="per impact (95 %)")
    ax.axhline(peaks.cor, color="C3", lw=1.0, label=f"constant fit {peaks.cor:.4f}")
    if scatter is not None:
        low, high = scatter.mean_interval
        label = (f"block mean {scatter.mean:.4f} (95 % {low:.4f} to {high:.4f}), "
                 f"scatter σ {scatter.sigma:.3f}")
        # an interval far narrower than the per-impact bars is a hairline under the constant
        # fit: drawn at least _MIN_BAND of the axis tall around the mean, and said so
        bottom, top = ax.get_ylim()
        if high - low < _MIN_BAND * (top - bottom):
            low = scatter.mean - 0.5 * _MIN_BAND * (top - bottom)
            high = scatter.mean + 0.5 * _MIN_BAND * (top - bottom)
            label += f";\nband drawn {_MIN_BAND:.0%} of the axis tall to be seen"
        ax.axhspan(low, high, color="C2", alpha=0.3, lw=0, label=label)
    if np.isfinite(peaks.slope):
        v = np.linspace(np.min(peaks.impact_velocity), np.max(peaks.impact_velocity), 2)
        ax.plot(v, peaks.intercept + peaks.slope * v, color="C1", ls="--", lw=1.0,
                label=f"linear trend: slope {peaks.slope:+.3f} ± {peaks.slope_se:.3f} s/rad (± se)")
    ax.set_xlabel("angular velocity before impact [rad/s]")
    ax.set_ylabel("COR of the impact [-]")
    ax.set_title("Section 3.7 (1): does the COR depend on the impact velocity?", fontsize=10)
    place_legend(ax, fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def _fitted_radius(period_fit: PeriodFit) -> str:
    """The fitted R [m] in the nominal block's unit (metres without a nominal block)."""
    unit = period_fit.nominal.length_unit if period_fit.nominal is not None else "m"
    if unit == "m":
        return f"{period_fit.R:.4f} m"
    return f"{period_fit.R / length_factor(unit):#.4g} {unit}"


def plot_periods(period_fit: PeriodFit, ax: Axes | None = None) -> Axes:
    """Measured periods against amplitude with the fitted and nominal exact curves. Returns the axes."""
    if ax is None:
        _, grid = _figure(None, 1, figsize=(6.0, 4.0))
        ax = grid[0, 0]
    degrees = 180.0 / np.pi
    how = ("2 x impact-to-impact" if period_fit.method == "zeros"
           else "4 x peak-to-zero, the report's way")
    ax.plot(period_fit.amplitudes * degrees, period_fit.periods, "o", ms=4,
            label=f"record ({how})")
    grid_amplitudes = np.linspace(0.03, 0.9, 60) * period_fit.alpha
    ax.plot(grid_amplitudes * degrees, period_fit.curve(grid_amplitudes), color="C3", lw=1.0,
            label=f"exact, fitted R = {_fitted_radius(period_fit)}, α = {period_fit.alpha:.4f}")
    if period_fit.nominal is not None:
        nominal = period_fit.nominal
        amplitudes = np.linspace(0.03, 0.9, 60) * nominal.alpha
        ax.plot(amplitudes * degrees, period_fit.curve(amplitudes, nominal.R, nominal.alpha),
                color="0.5", lw=0.8, ls="--", label=f"exact, nominal {nominal.describe()}")
    ax.set_xlabel("amplitude [deg]")
    ax.set_ylabel("period [s]")
    ax.set_title("Period against amplitude (Table 3.1 / Fig. 3.6)", fontsize=10)
    place_legend(ax, fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def plot_calibration(calibration: Calibration, fig: Figure | None = None,
                     title: str | None = None) -> Figure:
    """Fit, residuals, COR per impact and periods in one figure. Returns the figure."""
    plt = pyplot()

    if fig is None:
        fig = plt.figure(figsize=(11.0, 7.5), layout="constrained")
    grid = fig.add_gridspec(3, 2, height_ratios=[2.2, 1.0, 2.0])
    top = fig.add_subplot(grid[0, :])
    bottom = fig.add_subplot(grid[1, :], sharex=top)
    plot_fit(calibration, axes=(top, bottom))
    if calibration.peaks is not None:
        plot_cor_per_impact(calibration.peaks, ax=fig.add_subplot(grid[2, 0]),
                            scatter=calibration.scatter)
    if calibration.periods is not None:
        plot_periods(calibration.periods, ax=fig.add_subplot(grid[2, 1]))
    fig.suptitle(title or f"COR calibration, {calibration.block.describe()} block")
    warnings = getattr(calibration, "warnings", ())
    if warnings:
        import textwrap

        text = "\n".join(textwrap.fill(f"WARNING: {warning}", 150) for warning in warnings)
        fig.set_figheight(fig.get_figheight() + 0.14 * (text.count("\n") + 1))
        # a figure-level x label: the constrained layout keeps room for it below the panels
        fig.supxlabel(text, fontsize=7.5, color="C3", x=0.01, ha="left")
    for axis in fig.axes:  # the corners again, on the laid-out grid of all four panels
        if axis.get_legend() is not None:
            # the two lower panels side by side: a legend that cannot stay inside goes
            # below its panel (at the right it would take half the panel's width)
            place_legend(axis, fontsize=8, outside="right" if axis in (top, bottom)
                         else "below")
    return fig


def plot_calibrated_ensemble(ensemble, ax: Axes | None = None) -> Axes:
    """max |theta|/alpha of each member against its COR (overturned members at the top).

    ``ensemble`` is a :class:`~shaketable.calibration.uncertainty.CalibratedEnsemble`.
    Returns the axes.
    """
    if ax is None:
        _, grid = _figure(None, 1, figsize=(6.5, 4.2))
        ax = grid[0, 0]
    frame = ensemble.members
    cors = frame["cor [-]"].to_numpy()
    ratio = frame["max_theta_ratio [-]"].to_numpy()
    overturned = frame["overturned"].to_numpy(dtype=bool)
    ax.plot(cors[~overturned], ratio[~overturned], "o", ms=3, label="stands")
    if np.any(overturned):
        ax.plot(cors[overturned], np.full(np.count_nonzero(overturned), 1.0), "x", ms=4,
                color="C3", label="overturns (drawn at 1)")
    ax.axvline(ensemble.cor.mean, color="0.4", lw=0.8, ls="--",
               label=f"calibrated mean COR {ensemble.cor.mean:.4f}")
    s = ensemble.summary
    ax.set_title(f"P(overturn) = {s['P(overturn) [-]']:.3f} ({s['P low [-]']:.3f} to "
                 f"{s['P high [-]']:.3f}), {s['members']} members", fontsize=10)
    ax.set_xlabel("COR of the member [-]")
    ax.set_ylabel("max |θ|/α [-]")
    place_legend(ax, fontsize=8)
    ax.grid(alpha=0.3)
    return ax
