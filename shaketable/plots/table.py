"""Figures of the shaking-table model (:mod:`shaketable.lab.command`).

A plotting module: with :mod:`shaketable.plots.calcomp` the only kind of module of the
package that imports matplotlib.
"""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.plots.base import pyplot

__all__ = ["plot_command_vs_achieved"]

_TARGET = dict(color="k", lw=1.6, alpha=0.45, label="target (commanded)")

_WITHOUT = dict(color="tab:blue", lw=0.9, ls="--", label="achieved (command → servo)")

_WITH = dict(color="tab:red", lw=0.7, label="achieved + pitch, at the block")


def _check(name: str, motion) -> Motion:
    if not isinstance(motion, Motion):
        raise ValueError(f"{name} must be a shaketable Motion, got {type(motion).__name__}")
    return motion


def _on(motion: Motion, t: np.ndarray, component: str) -> np.ndarray:
    """A component of ``motion`` [m/s^2] interpolated onto the times ``t`` [s]."""
    values = motion.horizontal if component == "horizontal" else motion.vertical_or_zero
    return np.interp(t, motion.t, values)


def _shown(t: np.ndarray, window) -> np.ndarray:
    if window is None:
        return np.ones(t.size, dtype=bool)
    return (t >= window[0]) & (t <= window[1])


def plot_command_vs_achieved(table_motion, achieved_without_pitch, achieved_with_pitch,
                             ax=None, *, window=None, title=None):
    """Target table acceleration against what the table achieves, with and without pitch.

    Three panels sharing the time axis: horizontal and vertical acceleration
    [g] (target, achieved by the servo alone, and as felt by the block on the
    pitching table) and the difference achieved - target [g] for both axes.

    Parameters
    ----------
    table_motion : Motion
        The target accelerations [m/s^2] (what the table was asked to do).
    achieved_without_pitch : Motion
        Achieved accelerations [m/s^2], e.g. :func:`shaketable.lab.servo.achieved`.
    achieved_with_pitch : Motion
        The same seen by the block on the pitching table [m/s^2], e.g.
        :func:`shaketable.lab.pitch.motion_at_block`; its ``rotation``
        [rad/s^2] is quoted in the legend.
    ax : sequence of 3 matplotlib Axes, optional
        Axes for the horizontal, vertical and difference panels; a new figure
        otherwise.
    window : (float, float), optional
        Time range shown [s]; default the whole target.
    title : str, optional
        Figure title; default the target's name.

    Returns
    -------
    matplotlib.figure.Figure
    """
    motions = [_check("table_motion", table_motion),
               _check("achieved_without_pitch", achieved_without_pitch),
               _check("achieved_with_pitch", achieved_with_pitch)]
    if window is not None:
        window = (float(window[0]), float(window[1]))
        if not window[0] < window[1]:
            raise ValueError(f"window must be (start, end) with start < end [s], got {window}")
    plt = pyplot()
    if ax is None:
        fig, axes = plt.subplots(3, 1, sharex=True, figsize=(9.0, 7.5), layout="constrained",
                                 gridspec_kw={"height_ratios": [1.2, 1.2, 1.0]})
    else:
        axes = list(ax)
        if len(axes) != 3:
            raise ValueError(f"ax must hold 3 Axes (horizontal, vertical, difference), "
                             f"got {len(axes)}")
        fig = axes[0].figure
    t = table_motion.t
    shown = _shown(t, window)
    for axis, component in zip(axes[:2], ("horizontal", "vertical")):
        for motion, style in zip(motions, (_TARGET, _WITHOUT, _WITH)):
            axis.plot(t[shown], _on(motion, t, component)[shown] / G, **style)
        axis.set_ylabel(f"{component}\nacceleration [g]")
    for component, color in (("horizontal", "tab:green"), ("vertical", "tab:purple")):
        target = _on(table_motion, t, component)
        without = _on(achieved_without_pitch, t, component) - target
        with_pitch = _on(achieved_with_pitch, t, component) - target
        peak = np.max(np.abs(with_pitch[shown])) / G
        axes[2].plot(t[shown], with_pitch[shown] / G, color=color, lw=0.7,
                     label=f"{component}, + pitch (peak {peak:.3f} g)")
        axes[2].plot(t[shown], without[shown] / G, color=color, lw=1.0, ls="--", alpha=0.8,
                     label=f"{component}, no pitch (peak "
                           f"{np.max(np.abs(without[shown])) / G:.3f} g)")
    axes[2].set_ylabel("achieved − target\n[g]")
    axes[2].set_xlabel("time [s]")
    axes[0].legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), fontsize=8, ncol=3,
                   frameon=False)
    axes[2].legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), fontsize=7, ncol=2,
                   frameon=False)
    rotation = achieved_with_pitch.rotation
    if rotation is not None:
        axes[1].set_title(f"table pitch: peak φ'' = {np.max(np.abs(rotation)):.3f} rad/s²",
                          loc="right", fontsize=8)
    for axis in axes:
        axis.grid(True, lw=0.3, alpha=0.5)
        axis.set_xlim(*(window if window is not None else (t[0], t[-1])))
    fig.suptitle(title if title is not None else (table_motion.name or "table motion"),
                 fontsize=10)
    fig.align_ylabels(axes)
    return fig
