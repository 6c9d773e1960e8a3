"""Animated GIF of a rocking block on the moving table, beside its time history.

For teaching: the block is drawn to scale as a rectangle rotating about its
pivot corner (Fig. 2.7 of [1]_; theta > 0 pivots on the -x corner, see
``docs/conventions.md``), standing on a table that moves by the table
displacement (:func:`shaketable.lab.command.displacement_command`: the ground
acceleration integrated twice, high-passed and brought to rest the way the
table's controller does, Section 3.4 of [1]_). Beside it: theta/alpha with the
+-1 lines of the stable region and a moving cursor, and the horizontal ground
acceleration.

Like :mod:`shaketable.plots.calcomp`, this module is at the edge: it is the only one,
with the plotting modules, that imports matplotlib.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.results import RockingResult
from shaketable.core.validation import positive

__all__ = ["AnimationFile", "animate", "block_outline", "frame_times", "snapshot",
           "table_displacement"]

#: Default frames per second of the GIF [1/s] and the largest number of frames allowed.
DEFAULT_FPS = 12

MAX_FRAMES = 1500


@dataclass(frozen=True)
class AnimationFile:
    """What :func:`animate` wrote.

    Attributes
    ----------
    path : Path
        The GIF.
    n_frames : int
        Number of frames [-].
    fps : float
        Frames per second of the GIF [1/s].
    speed : float
        Simulated seconds per second of the GIF [-] (1 = real time).
    t_first, t_last : float
        Simulated times of the first and last frame [s].
    """

    path: Path
    n_frames: int
    fps: float
    speed: float
    t_first: float
    t_last: float


def frame_times(t_first: float, t_last: float, fps: float, speed: float,
                max_frames: int = MAX_FRAMES) -> np.ndarray:
    """Simulated times of the frames [s]: every ``speed / fps`` seconds from ``t_first``.

    Parameters
    ----------
    t_first, t_last : float
        Simulated time span [s], ``t_first < t_last``.
    fps : float
        Frames per second of the GIF [1/s].
    speed : float
        Simulated seconds per GIF second [-].
    max_frames : int
        Largest number of frames; more is a ValueError naming fps and speed.
    """
    fps = positive("fps", fps)
    speed = positive("speed", speed)
    if not t_last > t_first:
        raise ValueError(f"the end time ({t_last!r} s) must be after the start ({t_first!r} s)")
    step = speed / fps
    count = int(math.floor((t_last - t_first) / step + 1e-9)) + 1
    if count > max_frames:
        raise ValueError(f"{count} frames for {t_last - t_first:.3g} s at fps {fps:g} and speed "
                         f"{speed:g}: more than {max_frames}; raise speed, lower fps or "
                         "shorten the time span")
    return t_first + step * np.arange(count)


def table_displacement(motion: Motion | None, times: ArrayLike, *,
                       highpass: float | None = 0.1) -> np.ndarray:
    """Horizontal table displacement at ``times`` [m] for a table motion [m/s^2].

    The displacement command of :func:`shaketable.lab.command.displacement_command`
    (zero-phase high-pass at ``highpass`` Hz, exact double integration, end at
    rest), linearly interpolated; held at its last value after the motion
    ends. ``None`` (free rocking) or a table at rest gives zeros.
    """
    times = np.asarray(times, dtype=float)
    if motion is None or not np.any(motion.horizontal):
        return np.zeros_like(times)
    from shaketable.lab.command import displacement_command

    command = displacement_command(motion, highpass=highpass)
    return np.interp(times, command.t, command.horizontal_displacement)


def block_outline(block: Block, theta: float, base_x: float = 0.0) -> np.ndarray:
    """Corners of the block rocked by ``theta`` [rad] about its pivot corner [m], shape (5, 2).

    The base centre at rest is at ``(base_x, 0)``. theta > 0 turns the block
    counterclockwise about the corner at ``base_x - b`` (its top moves toward
    -x), theta < 0 clockwise about ``base_x + b`` (docs/conventions.md). The
    outline is closed (first corner repeated).
    """
    b, height = block.b, block.height
    corners = np.array([[-b, 0.0], [b, 0.0], [b, height], [-b, height], [-b, 0.0]])
    pivot = np.array([-b if theta >= 0 else b, 0.0])
    cos, sin = math.cos(theta), math.sin(theta)
    rotation = np.array([[cos, -sin], [sin, cos]])
    return (corners - pivot) @ rotation.T + pivot + np.array([base_x, 0.0])


class _Scene:
    """The figure and the artists updated frame by frame."""

    def __init__(self, result: RockingResult, block: Block, motion: Motion | None,
                 times: np.ndarray, highpass, figsize=(8.0, 3.6), title=None):
        from matplotlib.patches import Polygon, Rectangle

        from shaketable.plots.base import pyplot

        plt = pyplot()
        self.result, self.block, self.times = result, block, times
        end = result.t[-1]
        self.theta = np.interp(np.minimum(times, end), result.t, result.theta)
        self.displacement = table_displacement(motion, times, highpass=highpass)
        ground = result.motion
        self.fig = fig = plt.figure(figsize=figsize)
        grid = fig.add_gridspec(2, 2, width_ratios=[1, 1.35], height_ratios=[1.6, 1],
                                wspace=0.28, hspace=0.12)
        self.stage = fig.add_subplot(grid[:, 0])
        # no ground panel without horizontal ground motion (free rocking): it would be empty
        with_ground = bool(np.any(ground.horizontal))
        self.history = fig.add_subplot(grid[0, 1] if with_ground else grid[:, 1])
        self.ground = fig.add_subplot(grid[1, 1], sharex=self.history) if with_ground else None

        outlines = np.array([block_outline(block, th, d)
                             for th, d in zip(self.theta, self.displacement)])
        height = block.height
        table_width = max(1.6 * block.width, 0.9 * height)
        if result.overturned:  # room for the block lying on its side
            table_width = 2.2 * height + block.width
        x_low = min(outlines[:, :, 0].min(), self.displacement.min() - table_width / 2)
        x_high = max(outlines[:, :, 0].max(), self.displacement.max() + table_width / 2)
        margin = 0.08 * (x_high - x_low)
        stage = self.stage
        stage.set_xlim(x_low - margin, x_high + margin)
        stage.set_ylim(-0.18 * height, 1.12 * max(height, outlines[:, :, 1].max()))
        stage.set_aspect("equal")
        stage.axhline(-0.08 * height, color="0.3", lw=1.0)
        stage.axvline(0.0, color="0.6", lw=0.6, ls=":")
        stage.set_xlabel("x [m]")
        stage.set_ylabel("y [m]")
        stage.tick_params(labelsize=7)
        self.table = Rectangle((self.displacement[0] - table_width / 2, -0.08 * height),
                               table_width, 0.08 * height, facecolor="0.55", edgecolor="0.2")
        stage.add_patch(self.table)
        self.table_width = table_width
        self.block_patch = Polygon(outlines[0][:4], closed=True, facecolor="#c9b79c",
                                   edgecolor="k", lw=1.0)
        stage.add_patch(self.block_patch)
        self.clock = stage.set_title("", fontsize=8, loc="left")
        self.outlines = outlines

        ratio = result.theta / block.alpha
        history = self.history
        history.plot(result.t, ratio, color="k", lw=0.8)
        for sign in (1, -1):
            history.axhline(sign, color="tab:red", ls="--", lw=0.8)
        limit = max(1.2, 1.05 * float(np.max(np.abs(ratio), initial=0.0)))
        history.set_ylim(-limit, limit)
        history.set_ylabel("θ/α [-]", fontsize=8)
        history.tick_params(labelbottom=not with_ground, labelsize=7)
        if not with_ground:
            history.set_xlabel("time [s]", fontsize=8)
        history.grid(True, lw=0.3, alpha=0.5)
        self.cursor = history.axvline(times[0], color="tab:blue", lw=1.0)
        (self.dot,) = history.plot([times[0]], [self.theta[0] / block.alpha], "o",
                                   color="tab:blue", ms=4)
        self.ground_cursor = None
        if self.ground is not None:
            shown = ground.t <= max(end, times[-1]) + 1e-12
            self.ground.plot(ground.t[shown], ground.horizontal[shown] / G, color="0.3", lw=0.6)
            self.ground.set_ylabel("ü [g]", fontsize=8)
            self.ground.set_xlabel("time [s]", fontsize=8)
            self.ground.tick_params(labelsize=7)
            self.ground.grid(True, lw=0.3, alpha=0.5)
            self.ground_cursor = self.ground.axvline(times[0], color="tab:blue", lw=1.0)
        history.set_xlim(times[0], times[-1])
        if title is None:
            from shaketable.plots.calcomp import describe_block

            title = f"{describe_block(block)}, COR {result.cor:g}"
            if not np.any(ground.horizontal) and not np.any(ground.vertical_or_zero):
                title = f"free rocking: {title}, released at θ/α = {ratio[0]:.2f}"
            elif ground.name:
                title = f"{ground.name}: {title}"
        fig.suptitle(title, fontsize=9)
        fig.subplots_adjust(left=0.08, right=0.98, top=0.85, bottom=0.14)

    def draw(self, index: int):
        """Move the artists to frame ``index``; return them."""
        t = self.times[index]
        d = self.displacement[index]
        self.table.set_x(d - self.table_width / 2)
        self.block_patch.set_xy(self.outlines[index][:4])
        self.cursor.set_xdata([t, t])
        if self.ground_cursor is not None:
            self.ground_cursor.set_xdata([t, t])
        self.dot.set_data([t], [self.theta[index] / self.block.alpha])
        result = self.result
        state = ""
        if result.overturned and t >= result.t_overturn:
            state = f"\noverturned at {result.t_overturn:.2f} s"
        elif np.isfinite(result.t_unstable) and t >= result.t_unstable:
            state = f"\n|θ| > α at {result.t_unstable:.2f} s"
        self.clock.set_text(f"t = {t:5.2f} s, table x = {100 * d:+.1f} cm{state}")
        return tuple(artist for artist in (self.table, self.block_patch, self.cursor,
                                           self.ground_cursor, self.dot, self.clock)
                     if artist is not None)


def _inputs(result, block, motion):
    if not isinstance(result, RockingResult):
        raise ValueError(f"result must be a shaketable RockingResult, got {type(result).__name__}")
    if block is None:
        block = result.block
    elif not isinstance(block, Block):
        raise ValueError(f"block must be a shaketable.Block or None, got {type(block).__name__}")
    elif (block.height, block.width) != (result.block.height, result.block.width):
        raise ValueError(f"block ({block.describe()}) is not the block of the result "
                         f"({result.block.describe()})")
    if motion is None:
        motion = result.motion
    elif not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable.Motion or None, got {type(motion).__name__}")
    return block, motion


def animate(result: RockingResult, block: Block | None = None, motion: Motion | None = None, *,
            out: str | os.PathLike[str], fps: float = DEFAULT_FPS, speed: float = 1.0, start: float | None = None,
            end: float | None = None, dpi: int = 72, highpass: float | None = 0.1,
            title: str | None = None, max_frames: int = MAX_FRAMES) -> AnimationFile:
    """Write an animated GIF of the block rocking on the moving table.

    Parameters
    ----------
    result : RockingResult
        The simulation to show.
    block : Block, optional
        The block drawn; default (and it must be) ``result.block``.
    motion : Motion, optional
        The table motion whose displacement moves the table [m/s^2]; default
        ``result.motion`` (the accelerations the block felt). ``None`` with a
        free-rocking result keeps the table still.
    out : str or Path
        The GIF to write (suffix ``.gif``); its folder is created.
    fps : float
        Frames per second of the GIF [1/s].
    speed : float
        Simulated seconds per second of the GIF [-]; 1 is real time, 2 twice
        as fast. One frame every ``speed / fps`` simulated seconds: the
        result is subsampled, which keeps the GIF small.
    start, end : float, optional
        Simulated time span shown [s]; default the whole result.
    dpi : int
        Resolution [dots per inch] of the 8 x 3.6 in frames.
    highpass : float or None
        Corner of the table's displacement high-pass [Hz]
        (:func:`shaketable.lab.command.displacement_command`).
    title : str, optional
    max_frames : int
        Refuse to write more frames than this.

    Returns
    -------
    AnimationFile

    Raises
    ------
    ValueError
        For a bad parameter; the message names it.
    """
    from matplotlib.animation import FuncAnimation, PillowWriter

    block, motion = _inputs(result, block, motion)
    out = Path(out)
    if out.suffix.lower() != ".gif":
        raise ValueError(f"out must be a .gif file, got {str(out)!r}")
    t_first = float(result.t[0]) if start is None else float(start)
    t_last = float(result.t[-1]) if end is None else min(float(end), float(result.t[-1]))
    times = frame_times(t_first, t_last, fps, speed, max_frames)
    scene = _Scene(result, block, motion, times, highpass, title=title)
    from shaketable.core.files import atomic_write, prepare_output_file

    out = prepare_output_file(out, "out")
    animation = FuncAnimation(scene.fig, scene.draw, frames=len(times), blit=False,
                              repeat=False)
    try:
        atomic_write(out, lambda temporary: animation.save(
            # matplotlib's stub says int; PillowWriter only computes 1000 / fps, and a
            # fractional fps is meant (a frame every speed / fps simulated seconds)
            str(temporary), writer=PillowWriter(fps=fps),  # type: ignore[arg-type]
            dpi=int(dpi)))
    finally:
        from shaketable.plots.base import pyplot

        pyplot().close(scene.fig)
    return AnimationFile(path=out, n_frames=len(times), fps=float(fps), speed=float(speed),
                         t_first=float(times[0]), t_last=float(times[-1]))


def snapshot(result: RockingResult, time: float, *, out: str | os.PathLike[str],
             motion: Motion | None = None,
             span: tuple | None = None, dpi: int = 90, highpass: float | None = 0.1) -> Path:
    """One frame of :func:`animate` at simulated ``time`` [s], saved as an image (PNG...).

    ``span`` (start, end) [s] is the time axis of the history (default the whole result).
    """
    block, motion = _inputs(result, None, motion)
    first, last = span if span is not None else (float(result.t[0]), float(result.t[-1]))
    times = np.array([first, float(time), last])
    scene = _Scene(result, block, motion, times, highpass)
    scene.draw(1)
    from shaketable.core.files import atomic_write, prepare_output_file
    from shaketable.plots.base import pyplot

    out = prepare_output_file(out, "out")
    try:
        atomic_write(out, lambda temporary: scene.fig.savefig(temporary, dpi=dpi))
    finally:
        pyplot().close(scene.fig)
    return out
