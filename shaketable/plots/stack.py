"""The Calcomp layout of a stack run: the table, one rotation panel per block, the patterns."""

from __future__ import annotations

import numpy as np

from shaketable.core.units import format_length
from shaketable.plots.calcomp import describe_motion, ground_panels

#: Colours of the contact states of an interface in the pattern band.
STATE_COLOURS = {0: "white", 1: "tab:orange", -1: "tab:blue"}

#: A block's rotation panel is scaled to its own motion, not to +-alpha, when its peak
#: |theta| is below this fraction of its alpha (a landing's kick of 0.02 alpha would be a
#: flat line on the +-alpha scale).
OWN_SCALE_BELOW = 0.25


def magnification(peak: float, span: float) -> float:
    """A 1-2-5 factor that brings a curve of peak ``peak`` to about half of ``span`` on a
    shared axis (1 when it already reaches a tenth of it, or never moves) [-]. The
    animation gives it the largest peak of the column and draws every block by it."""
    if not (peak > 0.0) or peak >= 0.1 * span:
        return 1.0
    wanted = 0.5 * span / peak
    decade = 10.0 ** np.floor(np.log10(wanted))
    return float(max(step for step in (1.0, 2.0, 5.0, 10.0) if step * decade <= wanted)
                 * decade)


def stack_calcomp(result, fig=None, title: str | None = None, time_range=None):
    """The report's Calcomp layout (Figs. 2.8, 4.1-4.17) for a stack.

    From top to bottom: horizontal and vertical table acceleration [g] (a channel that is
    zero is left out), one rotation panel per block, the top block first, with its +-alpha
    lines (its own block angle: where a block alone on a fixed base would pass its corner),
    and the pattern band: one row per interface, white where flat, orange where it pivots on
    the upper block's -x corner (phi > 0), blue on its +x corner. Impacts are marked by
    ticks on the band, the overturn by a cross.

    Parameters
    ----------
    result : StackResult
    fig : matplotlib.figure.Figure, optional
    title : str, optional
        First caption line.
    time_range : (float, float), optional
        Time axis limits [s].

    Returns
    -------
    matplotlib.figure.Figure
    """
    stack = result.stack
    n = stack.n
    motion = result.motion
    end = float(result.t[-1]) if result.t.size else float(motion.t[0])
    fig, axes = ground_panels(motion, end, [1.2] * n + [0.25 + 0.22 * n], fig,
                              height=(3.0, 1.5))
    panels, band = axes[-(n + 1):-1], axes[-1]
    for row, axis in enumerate(panels):
        i = n - 1 - row
        block = stack.blocks[i]
        axis.plot(result.t, result.theta[:, i], color="k", lw=0.9, label=f"θ{i}")
        peak = float(np.max(np.abs(result.theta[:, i]), initial=0.0))
        if 0.0 < peak < OWN_SCALE_BELOW * block.alpha:
            # the block's own range: its +-alpha lines would be off the scale
            limit = 1.3 * peak
            axis.text(0.99, 0.96, f"scaled to this block's motion (peak {peak:.2g} rad = "
                      f"{peak / block.alpha:.2g} α); ±α = ±{block.alpha:.3g} rad off scale",
                      transform=axis.transAxes, ha="right", va="top", fontsize=7,
                      color="tab:gray")
        else:
            for sign in (1, -1):
                axis.axhline(sign * block.alpha, color="tab:gray", lw=0.8, ls="--",
                             label="±α of the block" if sign > 0 else None)
            limit = max(1.3 * block.alpha, 1.1 * peak)
        axis.set_ylim(-limit, limit)
        axis.set_ylabel(f"θ{i} [rad]\n{result.block_name(i)}")
        axis.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
                    borderaxespad=0.0)
    t = result.t
    for j in range(n):
        states = result.patterns[:, j]
        start = 0
        for k in range(1, t.size + 1):
            if k == t.size or states[k] != states[start]:
                stop = t[k] if k < t.size else t[-1]
                band.axvspan(t[start], stop, ymin=(j + 0.1) / n, ymax=(j + 0.9) / n,
                             color=STATE_COLOURS[int(states[start])], lw=0)
                start = k
    for event in result.events:
        if event["kind"] == "impact":
            j = event["interface"]
            band.plot([event["t"]] * 2, [j + 0.1, j + 0.9], color="k", lw=0.5)
        elif event["kind"] == "overturn":
            # at the run's last instant: not clipped by the frame
            band.plot(event["t"], event["interface"] + 0.5, "x", color="tab:red", ms=8,
                      clip_on=False)
    band.set_ylim(0, n)
    # phi of a contact: the rotation of the block above it relative to the one below
    band.set_yticks(np.arange(n) + 0.5,
                    ["base\nφ = θ0" if j == 0 else f"{j - 1}|{j}\nφ = θ{j} − θ{j - 1}"
                     for j in range(n)], fontsize=7)
    band.set_ylabel("contact")
    band.set_xlabel("time [s]")
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    band.legend(handles=[Patch(facecolor="white", edgecolor="k", label="flat"),
                         Patch(color="tab:orange", label="pivot on -x corner (φ > 0)"),
                         Patch(color="tab:blue", label="pivot on +x corner (φ < 0)"),
                         Line2D([], [], color="k", lw=0.5, label="impact"),
                         Line2D([], [], marker="x", ls="", color="tab:red", ms=6,
                                label="overturn")],
                # a pad of 1.2 font sizes (8.4 pt): clear of an overturn cross (8 pt wide)
                # drawn unclipped on the frame's right edge at the run's last instant
                loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, borderaxespad=1.2)
    first, last = (motion.t[0], max(end, motion.t[0] + 1e-9)) if time_range is None \
        else time_range
    for axis in axes:
        axis.grid(True, lw=0.3, alpha=0.5)
        axis.set_xlim(first, last)
    band.grid(False)
    lines = [title] if title else []
    lines.append("stack, top first, H × B: " + " on ".join(
        b.label.replace(" x ", " × ") if b.label else f"{b.height:g} × {b.width:g} m"
        for b in reversed(stack.blocks)))
    law = "plastic impacts" if result.impact == "plastic" else f"COR {result.cor:g}"
    lines.append(f"{describe_motion(motion, not np.any(motion.horizontal))}; {law}")
    if result.status == "overturned":
        lines.append(f"{result.block_name(result.overturned_block)} overturned at "
                     f"{result.t_overturn:.3f} s")
    else:
        state = "still moving at the end of the run" if result.still_moving else result.status
        # in the unit family of the blocks' sizes, as the console says it (ft -> in)
        unit = stack.blocks[0].length_unit if stack.blocks[0].label else "m"
        lines.append(f"{state}; peak top-corner excursion "
                     f"{format_length(result.peak_excursion, unit)}")
    fig.suptitle("\n".join(lines), fontsize=9.5)
    fig.align_ylabels(axes)
    return fig
