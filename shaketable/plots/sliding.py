"""Figures of the sliding mode: one run, and sliding against rocking for the same block.

The only sliding module that imports matplotlib.
"""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import INCH, G
from shaketable.plots.base import place_legend, pyplot


def sliding_figure(result, fig=None, title: str | None = None, length_unit: str = "in"):
    """Table acceleration [g], relative velocity and relative displacement.

    Sliding phases are shaded; the peak slip is marked. The time axis ends a
    little after the last slip (the x label gives the end of the record when
    it is cut). Lengths are in the user's ``length_unit`` (m, cm, mm, in, ft; in mm
    or in when the peak slip is under one m or ft: :func:`shaketable.core.units.
    display_length_unit`), inches by default as the report. Returns the figure.
    """
    from shaketable.core.constants import LENGTH_UNITS
    from shaketable.core.units import display_length_unit

    unit = display_length_unit(result.peak_slip, length_unit)
    scale = LENGTH_UNITS[unit]
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(9, 7), layout="constrained")
    else:
        fig.set_layout_engine("constrained")
    axes = fig.subplots(3, 1, sharex=True)
    t = result.t
    horizontal, vertical = result.ground_at(t)
    axes[0].plot(t, horizontal / G, lw=0.7, label="horizontal")
    if np.any(vertical):
        axes[0].plot(t, vertical / G, lw=0.7, label="vertical (up)")
    mu_s = result.friction.static
    normal = (G + vertical) / G
    axes[0].plot(t, mu_s * normal, "k--", lw=0.6, label=r"$\pm\mu_s(1+\ddot v/g)$ (Eq. 2-2)")
    axes[0].plot(t, -mu_s * normal, "k--", lw=0.6)
    axes[0].set_ylabel("table acc. [g]")
    axes[1].plot(t, result.v / scale, lw=0.8, color="C2")
    axes[1].set_ylabel(f"relative vel. [{unit}/s]")
    axes[2].plot(t, result.x / scale, lw=1.0, color="C3")
    axes[2].axhline(0.0, color="0.6", lw=0.5)
    peak_x = np.interp(result.t_peak, result.event_times, result.event_x) \
        if result.event_times.size else 0.0
    axes[2].plot([result.t_peak], [peak_x / scale], "ko", ms=4)
    axes[2].annotate(f"peak {result.peak_slip / scale:.3g} {unit}", (result.t_peak, peak_x / scale),
                     textcoords="offset points", xytext=(6, 6), fontsize=8)
    axes[2].set_ylabel(f"relative disp. [{unit}]")
    sliding = result.state != 0
    for axis in axes:
        axis.fill_between(t, 0, 1, where=sliding, step="post", color="C1", alpha=0.12,
                          transform=axis.get_xaxis_transform(), lw=0)
    # zoom on the sliding: to a little after the last slip, the rest of the record said
    label = "time [s]"
    if np.any(sliding):
        last = float(t[np.flatnonzero(sliding)[-1]])
        stop = min(float(t[-1]), last + max(2.0, 0.2 * (last - float(t[0]))))
        if stop < float(t[-1]):
            axes[2].set_xlim(float(t[0]), stop)
            label += (f"   (no slip after {last:.2f} s; the record goes on to "
                      f"{float(t[-1]):.1f} s)")
    axes[2].set_xlabel(label)
    place_legend(axes[0], fontsize=7, frameon=True)
    heading = title or (f"Sliding block, {result.motion.name}: μs = {mu_s:g}, "
                        f"μd = {result.friction.dynamic:g}")
    fig.suptitle(f"{heading} (shaded: sliding)", fontsize=10)
    return fig


def sliding_vs_rocking_figure(sliding, rocking, fig=None, title: str | None = None):
    """Teaching figure: the same block and record, sliding (low mu) and rocking (high mu).

    ``sliding`` and ``rocking`` are :class:`shaketable.studies.sliding.ModeResult`.
    """
    plt = pyplot()

    if fig is None:
        fig = plt.figure(figsize=(9, 7.5))
    axes = fig.subplots(3, 1, sharex=True)
    slide_run, rock_run = sliding.result, rocking.result
    t = rock_run.t
    axes[0].plot(slide_run.motion.t, slide_run.motion.horizontal / G, lw=0.7, color="0.3")
    ratio = sliding.choice["B/H [-]"]
    for mu, style, label in ((sliding.choice["mode mu_s [-]"], "C1--", "slides"),
                             (rocking.choice["mode mu_s [-]"], "C0:", None)):
        axes[0].axhline(mu, color=style[:2], ls=style[2:], lw=0.8,
                        label=f"μs = {mu:g}" + (f" ({label})" if label else "") + ", v = 0")
        axes[0].axhline(-mu, color=style[:2], ls=style[2:], lw=0.8)
    axes[0].axhline(ratio, color="k", lw=0.6, label=f"B/H = {ratio:.2f} (Eq. 2-1)")
    axes[0].axhline(-ratio, color="k", lw=0.6)
    axes[0].set_ylabel("table acc. [g]")
    axes[0].legend(loc="upper right", fontsize=7, ncol=3)
    axes[1].plot(slide_run.t, slide_run.x / INCH, color="C1", lw=1.0)
    axes[1].set_ylabel("slip [in]")
    axes[1].set_title(f"low friction μs = {sliding.choice['mode mu_s [-]']:g} < B/H: "
                      f"SLIDES from {sliding.choice['mode t_start [s]']:.2f} s, "
                      f"peak {slide_run.peak_slip_inches:.1f} in", fontsize=9)
    axes[2].plot(t, rock_run.theta / rock_run.block.alpha, color="C0", lw=1.0)
    axes[2].axhline(1.0, color="r", lw=0.5)
    axes[2].axhline(-1.0, color="r", lw=0.5)
    verdict = ("overturns" if rock_run.overturned else
               f"max |θ|/α {rock_run.max_theta_ratio:.2f}")
    extra = ""
    when = rocking.combined.get("required friction exceeds mu_s at [s]")
    if when is not None and not np.isnan(when):
        extra = f"; would also slide at {when:.2f} s (outside the model)"
    axes[2].set_title(f"high friction μs = {rocking.choice['mode mu_s [-]']:g} > B/H: ROCKS "
                      f"from {rocking.choice['mode t_start [s]']:.2f} s, {verdict}{extra}",
                      fontsize=9)
    axes[2].set_ylabel("θ/α [-]")
    axes[2].set_xlabel("time [s]")
    ends = [t[-1] if rock_run.overturned else rock_run.t_max]
    moving = np.abs(slide_run.x - slide_run.residual_slip) > 0.02 * max(slide_run.peak_slip,
                                                                        1e-12)
    if moving.any():
        ends.append(slide_run.t[np.flatnonzero(moving)[-1]])
    axes[2].set_xlim(slide_run.t[0], min(slide_run.t[-1], max(ends) + 3.0))
    block = rock_run.block
    fig.suptitle(title or f"Same block ({block.height / 0.3048:g} x {block.width / 0.3048:g} ft)"
                 f", same record ({rock_run.motion.name}): Section 2.1's two modes",
                 fontsize=10)
    fig.tight_layout()
    return fig
