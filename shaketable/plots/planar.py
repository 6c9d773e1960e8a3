"""The planar block's figure: the report's Calcomp layout with a slip panel and a mode band."""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.constants import LENGTH_UNITS
from shaketable.core.units import display_length_unit, format_length, shared_length_unit
from shaketable.models.planar.result import base_slip
from shaketable.plots.calcomp import (
    describe_block,
    describe_motion,
    ground_panels,
    has_signal,
    mark_overturn,
)
from shaketable.plots.mode_map import VERDICT_COLOURS

#: Colours of the modes shown in the band, by mode code (rest is left blank): those of the
#: verdicts in the mode map (:data:`shaketable.plots.mode_map.VERDICT_COLOURS`).
MODE_COLOURS = {1: ("slide", VERDICT_COLOURS["slid"]), 2: ("rock", VERDICT_COLOURS["rocked"]),
                3: ("slide-rock", VERDICT_COLOURS["slide-rocked"]),
                4: ("flight", VERDICT_COLOURS["flew"])}


def mode_changes(result):
    """(event times [s], mode codes after them, whether every event is recorded) of either
    planar result: :class:`~shaketable.models.planar.result.PlanarResult` (its ``events``,
    the first ``max_recorded_events`` of ``n_events``) or
    :class:`~shaketable.models.planar.reference_result.PlanarReferenceResult` (every event)."""
    if hasattr(result, "events"):
        events = result.events
        return events[:, 0], events[:, 3], result.n_events <= events.shape[0]
    return result.event_times, result.event_mode_after, True


def mode_spans(result):
    """(start, end, mode code) of every stretch of one mode [s], from the located events
    (exact instants), the samples where the recorded events ran out; ``result`` either
    planar result (:func:`mode_changes`)."""
    end = float(result.t[-1])
    changes = [(float(result.t[0]), int(result.mode[0]))]
    times, modes_after, complete = mode_changes(result)
    for time, after in zip(times, modes_after):
        if int(after) != changes[-1][1]:
            changes.append((float(time), int(after)))
    if not complete:
        last = changes[-1][0]
        for time, code in zip(result.t, result.mode):
            if time > last and int(code) != changes[-1][1]:
                changes.append((float(time), int(code)))
    spans = []
    for (start, code), (stop, _) in zip(changes, changes[1:] + [(end, -1)]):
        if stop > start:
            spans.append((start, stop, code))
    return spans


def planar_figure(result, fig=None, title: str | None = None, time_range=None):
    """Ground, angular velocity, rotation (with +-alpha), slip of the base and a mode band.

    The Calcomp layout of :func:`shaketable.plots.calcomp.calcomp` (ground panels left
    out when a channel is zero), with the angular velocity alone on its panel (the
    coupled model's theta'' has no single formula across modes), then the slip of the
    base relative to the table (the bottom corner the block stands or turns on:
    :func:`~shaketable.models.planar.result.base_slip`, whose peak is ``peak_base_slip``;
    in the unit the block was given in, mm for metres) with its peak marked, and a band
    coloured by the mode the block is in (slide, rock, slide-rock, flight; left blank at
    rest). A block that never rocks gets the slip
    velocity instead of the two flat rotation panels, and a caption line saying so.

    The traces are the columns of ``result.to_frame()``, which the compiled engine's
    :class:`~shaketable.models.planar.result.PlanarResult` and the SciPy reference's
    :class:`~shaketable.models.planar.reference_result.PlanarReferenceResult` share, so one
    figure serves both (the reference computes no corner excursion: its caption leaves
    it out).

    Parameters
    ----------
    result : PlanarResult or PlanarReferenceResult
    fig : matplotlib.figure.Figure, optional
    title : str, optional
        First caption line; the block, COR and friction, motion and verdict follow.
    time_range : (float, float), optional
        Time axis limits [s].

    Returns
    -------
    matplotlib.figure.Figure
    """
    block, motion = result.block, result.motion
    frame = result.to_frame()
    t = frame["time [s]"].to_numpy()
    theta = frame["theta [rad]"].to_numpy()
    # the base's own slide, not its midpoint's motion (which rocking moves too)
    slip_values = base_slip(frame["x [m]"].to_numpy(), frame["theta [rad]"].to_numpy(), block)
    peak, t_peak = result.peak_base_slip, result.t_peak_base_slip
    end = t[-1]
    theta_dot = frame["theta_dot [rad/s]"].to_numpy()
    # the slip in the unit the block was given in (mm for a block in metres)
    unit = display_length_unit(float(np.max(np.abs(slip_values), initial=0.0)),
                               getattr(block, "length_unit", "m"))
    scale = LENGTH_UNITS[unit]
    rocked = bool(np.any(theta != 0.0) or np.any(theta_dot != 0.0))
    if rocked:
        fig, axes = ground_panels(motion, end, (1.0, 1.4, 1.2, 0.28), fig, height=(3.4, 1.7))
        rates, rotation, slip, band = axes[-4], axes[-3], axes[-2], axes[-1]
        _rotation_panels(rates, rotation, t, theta, theta_dot, block)
    else:
        # a block that never rocks: theta and theta' would be two flat panels; the slip
        # velocity of the base (x' + h cos(theta) theta' = x' here) says how it slides
        fig, axes = ground_panels(motion, end, (1.0, 1.2, 0.28), fig, height=(3.4, 1.7))
        velocity, slip, band = axes[-3], axes[-2], axes[-1]
        velocity.plot(t, frame["x_dot [m/s]"].to_numpy() / scale, color="tab:blue", lw=0.9,
                      label="slip velocity")
        velocity.axhline(0.0, color="0.6", lw=0.5)
        velocity.set_ylabel(f"slip velocity [{unit}/s]")
        velocity.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
                        borderaxespad=0.0)
    slip.plot(t, slip_values / scale, color="tab:red", lw=0.9, label="slip of the base")
    slip.axhline(0.0, color="0.6", lw=0.5)
    if peak > 0.0 and np.isfinite(t_peak):
        at = int(np.argmin(np.abs(t - t_peak)))
        direction = 1.0 if slip_values[at] >= 0 else -1.0
        slip.plot([t_peak], [direction * peak / scale], "v", color="tab:red", ms=5,
                  label=f"peak {format_length(peak, unit)}")
    slip.set_ylabel(f"slip [{unit}]")
    slip.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, borderaxespad=0.0)
    shown_modes = set()
    for start, stop, code in mode_spans(result):
        if code in MODE_COLOURS:
            name, colour = MODE_COLOURS[code]
            band.axvspan(start, stop, color=colour, lw=0,
                         label=None if code in shown_modes else name)
            shown_modes.add(code)
    band.set_yticks([])
    band.set_ylabel("mode", rotation=0, ha="right", va="center")
    if shown_modes:
        band.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
                    borderaxespad=0.0)
    else:
        band.text(0.5, 0.5, "at rest throughout", transform=band.transAxes, ha="center",
                  va="center", fontsize=7, color="0.4")
    band.set_xlabel("time [s]")
    start, stop = (motion.t[0], max(end, motion.t[0] + 1e-9)) if time_range is None \
        else time_range
    for axis in axes:
        if axis is not band:
            axis.grid(True, lw=0.3, alpha=0.5)
        axis.set_xlim(start, stop)
    mark_overturn(axes[:-1], result, stop)
    caption = planar_caption(result, title)
    if not rocked:
        caption.append("θ = 0 throughout: the block never rocked (no rotation panels)")
    fig.suptitle("\n".join(caption), fontsize=9.5)
    fig.align_ylabels(axes)
    return fig


def _rotation_panels(rates, rotation, t, theta, theta_dot, block) -> None:
    """theta' and theta (with +-alpha) of a block that rocked."""
    rates.plot(t, theta_dot, color="tab:blue", lw=0.9)
    rates.set_ylabel("θ' [rad/s]")
    rotation.plot(t, theta, color="k", lw=0.9, label="θ")
    # each side's own alpha (an AsymmetricBlock's alpha_plus, alpha_minus)
    alphas = {sign: block.alpha_of(sign) if hasattr(block, "alpha_of") else block.alpha
              for sign in (1, -1)}
    for sign in (1, -1):
        rotation.axhline(sign * alphas[sign], color="tab:gray", lw=0.8, ls="--",
                         label="±α (stability limit)" if sign > 0 else None)
    limit = max(1.3 * max(alphas.values()), 1.1 * float(np.max(np.abs(theta), initial=0.0)))
    rotation.set_ylim(-limit, limit)
    rotation.set_ylabel("θ [rad]")
    rotation.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
                    borderaxespad=0.0)


def planar_caption(result, title: str | None = None) -> list[str]:
    """Caption lines: heading, block, COR and friction, motion, verdict and the measures."""
    block, motion = result.block, result.motion
    free = not has_signal(motion.horizontal) and not has_signal(motion.vertical_or_zero)
    cor = result.cor if isinstance(result.cor, str) else f"{result.cor:g}"
    lines = [] if not title else [title]
    model = "" if hasattr(result, "events") else " (independent SciPy reference)"
    described = block.describe() if hasattr(block, "b_plus") else describe_block(block)
    lines.append(f"{described}, α = {block.alpha:.4g} rad, COR {cor}, "
                 f"μs = {result.friction.static:g}, μd = {result.friction.dynamic:g}{model}")
    lines.append(describe_motion(motion, free))
    ratio = ("F" if result.overturned else f"{result.max_theta_ratio:.2f}")
    verdict = result.verdict()
    if result.overturned:
        side = "+" if result.overturn_direction > 0 else "−"
        verdict = f"overturned ({side}) at {result.t_overturn:.2f} s"
    # the base's slip on the table, as the console and the slip panel say it
    slip = getattr(result, "peak_base_slip", math.nan)
    slip = result.peak_slip if math.isnan(slip) else slip
    excursion = getattr(result, "peak_excursion", None)  # the reference computes none
    # one unit for the caption's lengths: the block's, or the smaller one a length needs
    unit = shared_length_unit((slip, math.nan if excursion is None else excursion),
                              getattr(block, "length_unit", "m"))
    measures = f"{verdict}; max |θ|/α = {ratio}, peak slip {format_length(slip, unit)}"
    lines.append(measures if excursion is None
                 else f"{measures}, corner excursion {format_length(excursion, unit)}")
    if result.status not in ("completed", "overturned"):
        lines.append(f"stopped: {result.message}")
    return lines


def planar_ensemble_axes(ensemble, ax=None):
    """Peak slip and corner excursion of each member of a planar ensemble
    (:class:`~shaketable.studies.planar_ensemble.PlanarEnsemble`) against the member, in
    the unit the block was given in; members that overturned are marked on the axis.
    Returns the axes."""
    from shaketable.plots.base import pyplot

    if ax is None:
        _, ax = pyplot().subplots(figsize=(7.5, 4.2), layout="constrained")
    frame = ensemble.members
    standing = frame[~frame["overturned"]]
    largest = float(standing["peak corner excursion [m]"].max()) if len(standing) else 0.0
    unit = display_length_unit(largest, ensemble.block.length_unit)
    scale = LENGTH_UNITS[unit]
    ax.plot(standing["member"], standing["peak slip [m]"] / scale, "o", ms=3.5,
            color="tab:red", label="peak slip")
    ax.plot(standing["member"], standing["peak corner excursion [m]"] / scale, "s", ms=3,
            mfc="none", color="tab:blue", label="peak corner excursion (clearance)")
    fallen = frame[frame["overturned"]]
    if len(fallen):
        ax.plot(fallen["member"], np.zeros(len(fallen)), "x", color="black",
                label=f"overturned ({len(fallen)})")
    ax.set_xlabel("member (0: nominal)")
    ax.set_ylabel(f"peak slip, corner excursion [{unit}]")
    summary = ensemble.summary
    ax.set_title(f"{ensemble.block.describe()}, COR {ensemble.cor:g}, μs "
                 f"{ensemble.friction.static:g}, μd {ensemble.friction.dynamic:g}: "
                 f"P(overturn) = {summary['P(overturn) [-]']:.3f} ({summary['P low [-]']:.3f}"
                 f" to {summary['P high [-]']:.3f})", fontsize=9)
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(fontsize=7, loc="upper left")
    return ax
