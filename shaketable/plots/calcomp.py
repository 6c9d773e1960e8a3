"""Figures. The only module of the package that imports matplotlib."""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G
from shaketable.plots.base import pyplot


def calcomp(result, fig=None, title: str | None = None):
    """The report's Calcomp layout (Figs. 2.8 and 4.1-4.17) for one result.

    From top to bottom: horizontal and vertical ground acceleration [g], the
    angular acceleration [rad/s^2] and velocity [rad/s] superimposed, and the
    angular displacement [rad] with the +-alpha lines that bound the stable
    region.

    Parameters
    ----------
    result : RockingResult
    fig : matplotlib.figure.Figure, optional
        Figure to draw into (a new one otherwise).
    title : str, optional
        Defaults to the block, COR and motion, in the report's style.

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(8.5, 9.0))
    axes = fig.subplots(4, 1, sharex=True, gridspec_kw={"height_ratios": [1, 1, 1.3, 1.5]})
    block = result.block
    motion = result.motion
    end = result.t[-1]
    shown = motion.t <= end + 1e-12
    axes[0].plot(motion.t[shown], motion.horizontal[shown] / G, color="k", lw=0.7)
    axes[0].set_ylabel("horizontal\nground acc. [g]")
    axes[1].plot(motion.t[shown], motion.vertical_or_zero[shown] / G, color="k", lw=0.7)
    axes[1].set_ylabel("vertical\nground acc. [g]")
    axes[2].plot(result.t, result.theta_ddot, color="tab:red", lw=0.6,
                 label="angular acceleration [rad/s²]")
    axes[2].plot(result.t, result.theta_dot, color="tab:blue", lw=0.9,
                 label="angular velocity [rad/s]")
    axes[2].set_ylabel("θ'' [rad/s²]\nθ' [rad/s]")
    axes[2].legend(loc="upper right", fontsize=7, frameon=False)
    axes[3].plot(result.t, result.theta, color="k", lw=0.9)
    for sign in (1, -1):
        axes[3].axhline(sign * block.alpha, color="tab:gray", lw=0.8, ls="--")
    axes[3].set_ylabel("θ [rad]")
    axes[3].set_xlabel("time [s]")
    limit = max(1.3 * block.alpha, 1.1 * float(np.max(np.abs(result.theta), initial=0.0)))
    axes[3].set_ylim(-limit, limit)
    note = f"max θ/α = {result.max_theta_ratio:.2f}"
    if result.overturned:
        note += f", overturns ({'+' if result.overturn_direction > 0 else '−'}) at " \
                f"{result.t_overturn:.2f} s"
    elif result.status == "airborne":
        note += f", leaves the ground at {result.t_airborne:.2f} s (vertical ≤ −g)"
    axes[3].text(0.01, 0.04, note, transform=axes[3].transAxes, fontsize=8)
    for axis in axes:
        axis.grid(True, lw=0.3, alpha=0.5)
        axis.set_xlim(motion.t[0], max(end, motion.t[0] + 1e-9))
    if title is None:
        inch = 0.0254
        title = (f"B = {block.width / inch:g} in, H = {block.height / inch:g} in, "
                 f"COR = {result.cor:g}")
        if block.rods is not None:
            title += (f", K = {block.rods.stiffness * inch:g} W/in, "
                      f"prestress = {block.rods.force:g} W")
        if motion.name:
            title = f"{motion.name}\n{title}"
    fig.suptitle(title, fontsize=10)
    fig.align_ylabels(axes)
    return fig
