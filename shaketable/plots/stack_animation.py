"""Animations of a stack (:class:`~shaketable.models.stack.StackResult`): one drawing per
block, to scale, on the moving table, beside each block's theta/alpha.

Each block is drawn where the chain of pivots puts it (``docs/stack.md``: the positions
follow from the rotations and the contact pattern at that output time), the table moved by
:func:`shaketable.plots.animation.table_displacement`. Frames are drawn at the output
sample nearest their time (the pattern belongs to a sample; no interpolation across a
change of pivot). The pattern in words and the verdict are written on the stage. Written
as :func:`shaketable.plots.animation.animate` writes one block (GIF, or MP4 with ffmpeg).
"""

from __future__ import annotations

import os
import textwrap
from pathlib import Path
from typing import Any, cast

import numpy as np

from shaketable.core.constants import LENGTH_UNITS, G
from shaketable.plots.animation import (
    DEFAULT_DPI,
    DEFAULT_FPS,
    DEFAULT_SIZE,
    MAX_FRAMES,
    STAGE_UNITS,
    AnimationFile,
    checked_size,
    default_speed,
    frame_times,
    output_file,
    render_frames,
    stage_unit,
    table_displacement,
)
from shaketable.plots.stack import magnification

#: Face and line colours of the blocks, bottom first.
_FACES = ("#c9b79c", "#9ec5e8", "#f6b98a", "#a6d8a0", "#e9a3a3", "#cdb8e0")
_LINES = ("k", "tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple")


def stack_outlines(result, indices) -> np.ndarray:
    """Corners of every block at the output samples ``indices`` [m], shape
    (frames, n, 5, 2) (closed outlines), the bottom block's base centre at rest at 0."""
    from shaketable.models.stack.physics import Chain, kinematics, rotation

    chain = Chain.of(result.stack)
    corners = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0]])
    out = np.empty((len(indices), chain.n, 5, 2))
    for f, k in enumerate(indices):
        centroid, _, _ = kinematics(chain, result.theta[k], result.theta_dot[k],
                                    result.patterns[k])
        for i in range(chain.n):
            local = corners * np.array([chain.b[i], chain.h[i]])
            out[f, i] = centroid[i] + local @ rotation(result.theta[k, i]).T
    return out


class _StackStage:
    """The figure and the artists moved frame by frame (the interface of
    :func:`shaketable.plots.animation.render_frames`: ``fig``, ``times``, ``animated``,
    ``draw``)."""

    def __init__(self, result, times, highpass, *, size, dpi, unit, title):
        from matplotlib.patches import Polygon, Rectangle
        from matplotlib.ticker import MaxNLocator

        from shaketable.plots.base import pyplot
        from shaketable.scenes.stack_patterns import pattern_words

        plt = pyplot()
        self.result, self.times = result, times
        stack = result.stack
        self.unit = unit or stage_unit(stack.blocks)
        factor = LENGTH_UNITS[self.unit]
        self.index = np.clip(np.searchsorted(result.t, times, side="left"), 0, result.t.size - 1)
        earlier = np.clip(self.index - 1, 0, None)
        closer = np.abs(result.t[earlier] - times) < np.abs(result.t[self.index] - times)
        self.index = np.where(closer, earlier, self.index)
        self.displacement = table_displacement(result.motion, times, highpass=highpass) / factor
        self.outlines = stack_outlines(result, self.index) / factor
        self.outlines[..., 0] += self.displacement[:, None, None]
        # in words on the stage, wrapped to its width (the results' code left out)
        self.words = ["\n".join(textwrap.wrap(pattern_words(result.patterns[k], code=False),
                                               44)) for k in self.index]
        width, height = size
        self.fig = fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi)
        with_ground = bool(np.any(result.motion.horizontal))
        grid = fig.add_gridspec(2, 2, height_ratios=[1.5, 1], width_ratios=[1, 1.4],
                                wspace=0.3, hspace=0.14, left=0.07, right=0.98, bottom=0.1,
                                top=0.84)
        stage = fig.add_subplot(grid[:, 0])
        history = fig.add_subplot(grid[0, 1] if with_ground else grid[:, 1])
        ground = fig.add_subplot(grid[1, 1], sharex=history) if with_ground else None
        total = 2.0 * float(stack.h.sum()) / factor
        widest = 2.0 * float(stack.b.max()) / factor
        span = max(1.6 * widest, 0.9 * total)
        x_low = min(self.outlines[..., 0].min(), self.displacement.min() - span / 2)
        x_high = max(self.outlines[..., 0].max(), self.displacement.max() + span / 2)
        margin = 0.08 * (x_high - x_low)
        thickness = 0.06 * total
        stage.set_xlim(x_low - margin, x_high + margin)
        stage.set_ylim(-2.2 * thickness, 1.12 * max(total, self.outlines[..., 1].max()))
        stage.set_aspect("equal")
        # a narrow stage (equal aspect, a tall column): at most 5 x ticks, or their labels
        # run together ("-0.75-0.50-0.25")
        stage.xaxis.set_major_locator(MaxNLocator(nbins=4, steps=[1, 2, 2.5, 5, 10]))
        stage.axhline(-thickness, color="0.3", lw=1.0)
        stage.axvline(0.0, color="0.6", lw=0.6, ls=":")
        stage.set_xlabel(f"x [{self.unit}]")
        stage.set_ylabel(f"y [{self.unit}]")
        self.table = Rectangle((self.displacement[0] - span / 2, -thickness), span, thickness,
                               facecolor="0.55", edgecolor="0.2")
        self.span = span
        stage.add_patch(self.table)
        self.blocks = []
        for i in range(stack.n):
            patch = Polygon(self.outlines[0, i, :4], closed=True,
                            facecolor=_FACES[i % len(_FACES)],
                            edgecolor=_LINES[i % len(_LINES)], lw=1.2)
            stage.add_patch(patch)
            self.blocks.append(patch)
        self.state = stage.text(0.03, 0.97, "", transform=stage.transAxes, va="top",
                                ha="left", fontsize=10)
        self.traces, self.dots = [], []
        ratios = [result.theta[:, i] / block.alpha for i, block in enumerate(stack.blocks)]
        peaks = [float(np.max(np.abs(ratio), initial=0.0)) for ratio in ratios]
        limit = max([1.2] + [1.05 * peak for peak in peaks])
        # a column moving far less than the axis shows is drawn magnified, every block by
        # one factor (in the labels): blocks rocking together must look as they rock, the
        # one that rocks less drawn smaller, never the other way round
        factor = magnification(max(peaks), min(limit, 4.0))
        for i, block in enumerate(stack.blocks):
            ratio = ratios[i] * factor
            label = (f"θ{i}/α{i}: {result.block_name(i)}" if factor == 1.0 else
                     f"θ{i}/α{i} × {factor:g}: {result.block_name(i)} (magnified)")
            # blocks moving together draw one curve: each block above is drawn wider and
            # under the ones below it, so that every curve shows
            (trace,) = history.plot(result.t, ratio, color=_LINES[i % len(_LINES)],
                                    lw=trace_width(i, stack.n), label=label,
                                    zorder=3 + stack.n - i)
            self.traces.append((trace, result.t, ratio))
            (dot,) = history.plot([times[0]], [ratio[self.index[0]]], "o",
                                  color=_LINES[i % len(_LINES)], ms=5)
            self.dots.append((dot, ratio))
        for sign in (1, -1):   # theta/alpha = +-1, off the axis of a magnified column
            history.axhline(sign * factor, color="tab:red", ls="--", lw=0.9)
        history.set_ylim(-min(limit, 4.0), min(limit, 4.0))
        history.set_ylabel("θ/α of each block [-]" if factor == 1.0 else
                           f"θ/α of each block × {factor:g} [-]")
        history.legend(loc="upper left", fontsize=8)
        history.grid(True, lw=0.3, alpha=0.5)
        history.set_xlim(times[0], times[-1])
        self.cursors = [history.axvline(times[0], color="tab:blue", lw=1.2)]
        if ground is not None:
            motion = result.motion
            shown = motion.t <= times[-1] + 1e-12
            (trace,) = ground.plot(motion.t[shown], motion.horizontal[shown] / G, lw=0.7,
                                   color="0.3")
            self.traces.append((trace, motion.t[shown], motion.horizontal[shown] / G))
            ground.set_ylabel("ü [g]")
            ground.set_xlabel("time [s]")
            ground.grid(True, lw=0.3, alpha=0.5)
            history.tick_params(labelbottom=False)
            self.cursors.append(ground.axvline(times[0], color="tab:blue", lw=1.2))
        else:
            history.set_xlabel("time [s]")
        self.clock = fig.text(0.07, 0.905, "", fontsize=12, ha="left", va="top",
                              family="monospace")
        if title is None:
            law = "plastic impacts" if result.impact == "plastic" else f"COR {result.cor:g}"
            what = f"stack, top first: {stack.describe().split(': ', 1)[1]}; {law}"
            title = f"{motion_name(result)}: {what}"
        fig.suptitle(title, fontsize=12, y=0.99)
        # drawn in this order frame by frame: the top block's curve first, the bottom's last
        curves = [trace for trace, _, _ in self.traces]
        self.animated = [self.table, *self.blocks, *curves[stack.n - 1::-1],
                         *curves[stack.n:], *self.cursors,
                         *(dot for dot, _ in self.dots[::-1]), self.state, self.clock]

    def draw(self, index: int):
        """Move the artists to frame ``index``; return them."""
        t = self.times[index]
        self.table.set_x(self.displacement[index] - self.span / 2)
        for i, patch in enumerate(self.blocks):
            patch.set_xy(self.outlines[index, i, :4])
        sample = self.index[index]
        for dot, ratio in self.dots:
            dot.set_data([t], [ratio[sample]])
        for cursor in self.cursors:
            cursor.set_xdata([t, t])
        for trace, trace_times, values in self.traces:   # up to t, never ahead of it
            shown = int(np.searchsorted(trace_times, t, side="right"))
            trace.set_data(trace_times[:shown], values[:shown])
        sign = "+" if self.displacement[index] >= 0 else "−"
        self.clock.set_text(f"t = {t:6.2f} s   table x = {sign}"
                            f"{abs(self.displacement[index]):.2f} {self.unit}")
        result = self.result
        text = self.words[index]
        if result.status == "overturned" and t >= result.t_overturn:
            text = (f"{result.block_name(result.overturned_block)} overturned at "
                    f"{result.t_overturn:.2f} s")
        self.state.set_text(text)
        return self.animated


def trace_width(index: int, count: int) -> float:
    """The line width [pt] of block ``index``'s θ/α curve of ``count``: 1 for the bottom
    block, 1.25 more for each block above (at most 4 for the top one): where curves
    coincide, each shows as a band around the one below it."""
    return 1.0 + min(1.25, 3.0 / max(count - 1, 1)) * index


def motion_name(result) -> str:
    motion = result.motion
    if not np.any(motion.horizontal) and not np.any(motion.vertical_or_zero):
        return "free rocking"
    return motion.name or "table motion"


def animate_stack(result, *, out: str | os.PathLike[str], fps: float = DEFAULT_FPS,
                  speed: float | None = 1.0, start: float | None = None,
                  end: float | None = None,
                  size: tuple = DEFAULT_SIZE, dpi: float = DEFAULT_DPI, unit: str | None = None,
                  highpass: float | None = 0.1, title: str | None = None,
                  max_frames: int = MAX_FRAMES) -> AnimationFile:
    """Write an animation of a stack run (GIF, or MP4 with ffmpeg); the parameters are
    those of :func:`shaketable.plots.animation.animate` for one result.

    Raises
    ------
    ValueError
        For a bad parameter; the message names it.
    """
    from shaketable.core.files import atomic_write, prepare_output_file
    from shaketable.plots.base import pyplot

    if unit is not None and unit not in STAGE_UNITS:
        raise ValueError(f"unit must be one of {', '.join(STAGE_UNITS)}, got {unit!r}")
    width, height = checked_size(size, dpi)
    width, height = width - width % 2, height - height % 2
    out, note = output_file(out)
    t_first = float(result.t[0]) if start is None else float(start)
    t_last = float(result.t[-1]) if end is None else min(float(end), float(result.t[-1]))
    speed = default_speed(t_last - t_first) if speed is None else speed
    times = frame_times(t_first, t_last, fps, speed, max_frames)
    out = prepare_output_file(out, "out")
    stage = _StackStage(result, times, highpass, size=(width, height), dpi=dpi, unit=unit,
                        title=title)
    try:
        # the frame loop needs fig, times, animated and draw: what a _StackStage has
        atomic_write(out, lambda temporary: render_frames(cast(Any, stage), temporary,
                                                          (width, height), fps))
    finally:
        pyplot().close(stage.fig)
    return AnimationFile(path=out, n_frames=len(times), fps=float(fps), speed=float(speed),
                         t_first=float(times[0]), t_last=float(times[-1]),
                         size=(width, height), note=note)


def stack_snapshot(result, time: float, *, out: str | os.PathLike[str],
                   size: tuple = DEFAULT_SIZE, dpi: float = DEFAULT_DPI,
                   highpass: float | None = 0.1) -> Path:
    """One frame of :func:`animate_stack` at simulated ``time`` [s], saved as an image."""
    from shaketable.core.files import atomic_write, prepare_output_file
    from shaketable.plots.base import pyplot

    width, height = checked_size(size, dpi)
    times = np.array([float(result.t[0]), float(time), float(result.t[-1])])
    stage = _StackStage(result, times, highpass, size=(width, height), dpi=dpi, unit=None,
                        title=None)
    stage.draw(1)
    out = prepare_output_file(out, "out")
    try:
        atomic_write(out, lambda temporary: stage.fig.savefig(temporary, dpi=dpi))
    finally:
        pyplot().close(stage.fig)
    return out
