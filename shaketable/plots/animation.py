"""Animations (GIF, or MP4 with ffmpeg) of rocking blocks on the moving table, beside theta/alpha.

For teaching: each block is drawn to scale as a rectangle rotating about its
pivot corner (Fig. 2.7 of [1]_; theta > 0 pivots on the -x corner, see
``docs/conventions.md``), standing on a table that moves by the table
displacement (:func:`table_displacement`: the ground acceleration integrated
twice, with its mean velocity removed so that the table shakes about where it
started instead of drifting, then high-passed). Beside it: theta/alpha with the
+-1 lines of the stable region and a moving cursor, and the horizontal ground
acceleration.

Every trace is revealed as time advances: at each frame theta/alpha and the
ground acceleration are drawn up to that frame's time, never ahead of it.

Several runs (two CORs, two release angles, two block sizes) are shown side by
side, each block on its own table, all drawn to the same scale in one length
unit, or overlaid on one table (``layout="overlay"``); their theta/alpha
traces share one panel, in the colours of their blocks.

The frames are drawn by blitting: the axes and the labels are drawn once, and
each frame redraws only the moving blocks, tables, cursors, texts and the traces
up to its time onto a copy of that background.

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
import shutil
import subprocess
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from shaketable.core.constants import LENGTH_UNITS, G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.validation import positive
from shaketable.models.rocking.result import RockingResult

__all__ = ["AnimationFile", "animate", "block_outline", "default_speed", "ffmpeg_available",
           "frame_times", "snapshot", "table_displacement"]

#: Default frames per second of the animation [1/s] and the largest number of frames allowed.
DEFAULT_FPS = 12

MAX_FRAMES = 1500

#: ``speed=None``: a span shown shorter than this [s] is slowed so that its animation lasts
#: this long (at 12 frames a second, 48 frames or more: a short event, an impact or a
#: kick, falls on or near a frame); a longer one plays in real time.
SHORT_SPAN = 4.0

#: Default frame size [pixels] and resolution [dots per inch]: 10.24 x 5.76 in figures,
#: whose 11-13 pt labels stay readable on a projector; ``dpi`` scales the fonts.
DEFAULT_SIZE = (1024, 576)
DEFAULT_DPI = 100

#: Largest frame side [pixels].
MAX_SIDE = 3840

#: Bounds of the resolution [dots per inch] and of the frame rate [1/s]: fonts are drawn
#: ``dpi / 72`` pixels a point, so a dpi far beyond a print's draws glyphs of thousands of
#: pixels (memory), and a frame rate far below one frame a second gives a frame duration
#: the GIF and MP4 writers cannot hold.
DPI_RANGE = (10.0, 1000.0)
FPS_RANGE = (0.5, 120.0)

#: Units a stage may be drawn in (the block's own unit by default).
STAGE_UNITS = ("mm", "cm", "m", "in", "ft")

#: Colours of the runs (block face, trace): one run keeps the report's black trace.
_FACES = ("#9ec5e8", "#f6b98a", "#a6d8a0", "#e9a3a3", "#cdb8e0", "#d9c19b")
_LINES = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")
_SINGLE_FACE = "#c9b79c"


@dataclass(frozen=True)
class AnimationFile:
    """What :func:`animate` wrote.

    Attributes
    ----------
    path : Path
        The GIF or MP4 written.
    n_frames : int
        Number of frames [-].
    fps : float
        Frames per second of the animation [1/s].
    speed : float
        Simulated seconds per second of the animation [-] (1 = real time).
    t_first, t_last : float
        Simulated times of the first and last frame [s].
    size : tuple of int
        Width and height of the frames [pixels].
    note : str
        What the caller should know (an MP4 asked for without ffmpeg, written as GIF).
    """

    path: Path
    n_frames: int
    fps: float
    speed: float
    t_first: float
    t_last: float
    size: tuple = DEFAULT_SIZE
    note: str = ""


def frame_times(t_first: float, t_last: float, fps: float, speed: float,
                max_frames: int = MAX_FRAMES) -> np.ndarray:
    """Simulated times of the frames [s]: every ``speed / fps`` seconds from ``t_first``.

    Parameters
    ----------
    t_first, t_last : float
        Simulated time span [s], ``t_first < t_last``.
    fps : float
        Frames per second of the animation [1/s].
    speed : float
        Simulated seconds per animation second [-].
    max_frames : int
        Largest number of frames; more is a ValueError naming fps and speed.
    """
    fps = positive("fps", fps)
    if not FPS_RANGE[0] <= fps <= FPS_RANGE[1]:
        raise ValueError(f"fps must be from {FPS_RANGE[0]:g} to {FPS_RANGE[1]:g} frames per "
                         f"second, got {fps:g}")
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


def default_speed(span: float) -> float:
    """The speed of ``speed=None`` for a span shown of ``span`` seconds [-]: 1 (real time)
    for :data:`SHORT_SPAN` (4 s) or more; a shorter span slowed to last :data:`SHORT_SPAN`
    seconds of animation, ``span / SHORT_SPAN`` to two significant digits (a 1-s run at 0.25,
    a 0.6-s run at 0.15)."""
    if not span > 0:
        return 1.0
    return min(1.0, float(f"{span / SHORT_SPAN:.2g}"))


def table_displacement(motion: Motion | None, times: ArrayLike, *,
                       highpass: float | None = 0.1) -> np.ndarray:
    """Horizontal table displacement at ``times`` [m] for a table motion [m/s^2].

    The displacement a shaking table has while it reproduces the acceleration:

    1. exact double integration of the (piecewise-linear) acceleration from
       rest at the first sample
       (:func:`shaketable.lab.command.displacement_command` with neither
       filter nor baseline);
    2. baseline correction for a zero mean velocity: the straight line
       ``(d(T) - d(0)) (t - t0) / (T - t0)`` is subtracted, so that the table
       ends where it started. Integrated from rest, a sine acceleration
       ``A sin(w t)`` has the mean velocity ``A / w`` and its displacement
       drifts by ``A t / w``; with the correction it is the closed form
       ``-A / w^2 sin(w t)`` over whole cycles (a table shaking about its
       centre), and the abrupt start of the sine moves the table no more
       than that;
    3. zero-phase Butterworth high-pass of the displacement at ``highpass``
       Hz (:func:`shaketable.lab.command.zero_phase_highpass`, ``None``
       skips it), which removes slower drifts of a record beyond a constant
       velocity.

    Linearly interpolated at ``times``; held at its last value after the motion
    ends. ``None`` (free rocking) or a table at rest gives zeros. The change in
    acceleration that this correction implies is drawn only, never simulated:
    the block is simulated on ``motion`` itself.
    """
    times = np.asarray(times, dtype=float)
    if motion is None or not np.any(motion.horizontal):
        return np.zeros_like(times)
    from shaketable.lab.command import displacement_command, zero_phase_highpass

    command = displacement_command(motion, highpass=None, baseline=False)
    t = command.t
    displacement = command.horizontal_displacement
    displacement = displacement - displacement[0] - (displacement[-1] - displacement[0]) * (
        (t - t[0]) / (t[-1] - t[0]))
    if highpass is not None:
        displacement = zero_phase_highpass(displacement, float(t[1] - t[0]), highpass)
    return np.interp(times, t, displacement)


def block_outline(block: Block, theta: float, base_x: float = 0.0) -> np.ndarray:
    """Corners of the block rocked by ``theta`` [rad] about its pivot corner [m], shape (5, 2).

    The base centre at rest is at ``(base_x, 0)``. theta > 0 turns the block
    counterclockwise about the corner at ``base_x - b`` (its top moves toward
    -x), theta < 0 clockwise about ``base_x + b`` (docs/conventions.md). The
    outline is closed (first corner repeated).
    """
    return _outlines(block, np.array([float(theta)]), np.array([float(base_x)]))[0]


def _outlines(block: Block, theta: np.ndarray, base_x: np.ndarray) -> np.ndarray:
    """:func:`block_outline` for every frame at once [m], shape (frames, 5, 2)."""
    b, height = block.b, block.height
    corners = np.array([[-b, 0.0], [b, 0.0], [b, height], [-b, height], [-b, 0.0]])
    pivot = np.where(theta >= 0, -b, b)                        # (frames,)
    cos, sin = np.cos(theta)[:, None], np.sin(theta)[:, None]
    x = corners[None, :, 0] - pivot[:, None]
    y = np.broadcast_to(corners[None, :, 1], x.shape)
    return np.stack([x * cos - y * sin + pivot[:, None] + base_x[:, None],
                     x * sin + y * cos], axis=-1)


def ffmpeg_available() -> bool:
    """Whether an ``ffmpeg`` executable is found (matplotlib's ``animation.ffmpeg_path``)."""
    import matplotlib

    return shutil.which(str(matplotlib.rcParams["animation.ffmpeg_path"])) is not None



def output_file(out) -> tuple[Path, str]:
    """The file an animation is written to, and a note when it is not the one asked for.

    ``out`` must end in ``.gif`` or ``.mp4`` (or have no suffix: an MP4); an MP4 becomes a
    GIF, with the note saying why, when ffmpeg is not found.
    """
    out = Path(out)
    note = ""
    suffix = out.suffix.lower()
    if suffix not in (".gif", ".mp4", ""):
        raise ValueError(f"out must be a .gif or .mp4 file, got {str(out)!r}")
    if suffix in (".mp4", "") and not ffmpeg_available():
        if suffix == ".mp4":
            note = "ffmpeg was not found, so the animation is a GIF instead of an MP4"
        out = out.with_suffix(".gif")
    elif suffix == "":
        out = out.with_suffix(".mp4")
    return out, note

def stage_unit(blocks: Sequence[Block]) -> str:
    """The length unit the stage is drawn in: the unit of the first block's label
    (``"6 x 2 ft"`` -> ft) when it is one of :data:`STAGE_UNITS`, else metres."""
    for block in blocks:
        words = getattr(block, "label", "").split()
        if words and words[-1] in STAGE_UNITS:
            return words[-1]
    return "m"


def _default_title(results, theta, ground_run, single) -> str:
    """The animation's title: the blocks, the COR when all runs share it, and the motion
    (free rocking: the release angle of a single run, ``theta`` its angles [rad])."""
    from shaketable.plots.calcomp import describe_block

    blocks = list(dict.fromkeys(describe_block(run.block) for run in results))
    if all(name.startswith("H × B = ") for name in blocks):
        blocks = ["H × B = " + ", ".join(name[8:] for name in blocks)]
    what = "; ".join(blocks)
    cors = {run.cor for run in results}
    if len(cors) == 1:  # several CORs: the labels give them
        what = f"{what}, COR {results[0].cor:g}"
    if not np.any(ground_run.horizontal) and not np.any(ground_run.vertical_or_zero):
        title = f"free rocking: {what}"
        if single:
            start = theta[0][0] / results[0].block.alpha
            title += f", released at θ/α = {start:.2f}"
    elif ground_run.name:
        title = f"{ground_run.name}: {what}"
    else:
        title = what
    return title


class _Stage:
    """The figure and the artists updated frame by frame, for one or several runs."""

    def __init__(self, results: Sequence[RockingResult], motions: Sequence[Motion | None],
                 times: np.ndarray, highpass, *, size=DEFAULT_SIZE, dpi=DEFAULT_DPI,
                 layout="side", labels=None, unit=None, title=None):
        from shaketable.plots.base import pyplot
        from shaketable.plots.calcomp import run_labels

        plt = pyplot()
        self.results, self.times = list(results), times
        count = len(self.results)
        self.unit = unit or stage_unit([run.block for run in self.results])
        factor = LENGTH_UNITS[self.unit]
        self.labels = list(labels) if labels is not None else run_labels(self.results)
        single = count == 1
        faces = [_SINGLE_FACE] if single else [_FACES[k % len(_FACES)] for k in range(count)]
        lines = ["k"] if single else [_LINES[k % len(_LINES)] for k in range(count)]
        # displacement once per distinct table motion
        cache: dict = {}
        self.theta, self.displacement = [], []
        for run, motion in zip(self.results, motions):
            key = id(motion)
            if key not in cache:
                cache[key] = table_displacement(motion, times, highpass=highpass) / factor
            self.displacement.append(cache[key])
            self.theta.append(np.interp(np.minimum(times, run.t[-1]), run.t, run.theta))
        self.outlines = [_outlines(run.block, theta, displacement * factor) / factor
                         for run, theta, displacement in zip(self.results, self.theta,
                                                             self.displacement)]
        width, height = size
        self.fig = fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi)
        stages = 1 if layout == "overlay" else count
        ground_run = self.results[0].motion
        with_ground = any(np.any(run.motion.horizontal) for run in self.results)
        grid = fig.add_gridspec(2, stages + 1, height_ratios=[1.5, 1],
                                width_ratios=[1] * stages + [max(1.4, 0.9 * stages)],
                                wspace=0.3, hspace=0.14, left=0.07, right=0.98, bottom=0.1,
                                top=0.84)
        self.stages = [fig.add_subplot(grid[:, k]) for k in range(stages)]
        self.history = fig.add_subplot(grid[0, -1] if with_ground else grid[:, -1])
        self.ground = fig.add_subplot(grid[1, -1], sharex=self.history) if with_ground else None

        self._lay_out_stages(layout, single, lines, faces)
        self._plot_history(times, lines, single)
        if self.ground is not None:
            self._plot_ground(times, lines)
        self.history.set_xlim(times[0], times[-1])
        self.clock = fig.text(0.07, 0.905, "", fontsize=12, ha="left", va="top",
                              family="monospace")
        if title is None:
            title = _default_title(self.results, self.theta, ground_run, single)
        fits = 0.95 * width / (0.55 * 12 * dpi / 72)  # characters of 12 pt on one line
        if len(title) > fits and ": " in title:
            title = title.replace(": ", ":\n", 1)  # two lines rather than past the edges
        fig.suptitle(title, fontsize=12, y=0.99)
        self.animated = [*self.tables, *self.blocks, *(trace for trace, _, _ in self.traces),
                         *self.cursors, *self.dots, *self.states, self.clock]

    def _lay_out_stages(self, layout, single, lines, faces):
        """The stages on one scale (the union of what any block and table covers), their
        tables and blocks at the first frame."""
        from matplotlib.patches import Polygon, Rectangle

        factor = LENGTH_UNITS[self.unit]
        count, stages = len(self.results), len(self.stages)
        tallest = max(run.block.height for run in self.results) / factor
        table_widths = []
        for run in self.results:
            block_width, block_height = run.block.width / factor, run.block.height / factor
            span = max(1.6 * block_width, 0.9 * block_height)
            if run.overturned:  # room for the block lying on its side
                span = 2.2 * block_height + block_width
            table_widths.append(span)
        x_low = min(min(outline[:, :, 0].min(), displacement.min() - span / 2)
                    for outline, displacement, span in zip(self.outlines, self.displacement,
                                                            table_widths))
        x_high = max(max(outline[:, :, 0].max(), displacement.max() + span / 2)
                     for outline, displacement, span in zip(self.outlines, self.displacement,
                                                             table_widths))
        margin = 0.08 * (x_high - x_low)
        y_high = 1.12 * max(tallest, max(outline[:, :, 1].max() for outline in self.outlines))
        thickness = 0.08 * tallest
        self.tables, self.blocks, self.states = [], [], []
        self.table_widths = table_widths
        for k, stage in enumerate(self.stages):
            stage.set_xlim(x_low - margin, x_high + margin)
            stage.set_ylim(-2.2 * thickness, y_high)
            stage.set_aspect("equal")
            stage.axhline(-thickness, color="0.3", lw=1.0)
            stage.axvline(0.0, color="0.6", lw=0.6, ls=":")
            stage.set_xlabel(f"x [{self.unit}]")
            if k == 0:
                stage.set_ylabel(f"y [{self.unit}]")
            else:
                stage.tick_params(labelleft=False)
            if layout != "overlay" and not single:
                stage.set_title(self.labels[k], color=lines[k], fontsize=11)
            self.states.append(stage.text(0.03, 0.97, "", transform=stage.transAxes, va="top",
                                          ha="left", fontsize=10))
        drawn_tables = range(1) if layout == "overlay" else range(count)
        for k in drawn_tables:
            stage = self.stages[min(k, stages - 1)]
            table = Rectangle((self.displacement[k][0] - table_widths[k] / 2, -thickness),
                              table_widths[k], thickness, facecolor="0.55", edgecolor="0.2")
            stage.add_patch(table)
            self.tables.append(table)
        for k in range(count):
            stage = self.stages[0 if layout == "overlay" else k]
            patch = Polygon(self.outlines[k][0][:4], closed=True, facecolor=faces[k],
                            edgecolor=lines[k] if not single else "k", lw=1.2,
                            alpha=0.75 if layout == "overlay" and not single else 1.0)
            stage.add_patch(patch)
            self.blocks.append(patch)
        if layout == "overlay" and not single:
            self.stages[0].legend(self.blocks, self.labels, loc="upper right", fontsize=9,
                                  framealpha=0.9)

    def _plot_history(self, times, lines, single):
        """The history of theta/alpha of every run, with a dot and a cursor at the frame."""
        history = self.history
        self.dots = []
        self.traces: list = []   # (line, times, values): drawn up to each frame's time
        limit = 1.2
        for k, run in enumerate(self.results):
            ratio = run.theta / run.block.alpha
            (trace,) = history.plot(run.t, ratio, color=lines[k], lw=1.0,
                                    label=None if single else self.labels[k])
            self.traces.append((trace, run.t, ratio))
            limit = max(limit, 1.05 * float(np.max(np.abs(ratio), initial=0.0)))
            (dot,) = history.plot([times[0]], [self.theta[k][0] / run.block.alpha], "o",
                                  color=lines[k] if not single else "tab:blue", ms=6)
            self.dots.append(dot)
        for sign in (1, -1):
            history.axhline(sign, color="tab:red", ls="--", lw=0.9)
        history.set_ylim(-min(limit, 4.0), min(limit, 4.0))
        history.set_ylabel("θ/α [-]")
        history.tick_params(labelbottom=self.ground is None)
        if self.ground is None:
            history.set_xlabel("time [s]")
        history.grid(True, lw=0.3, alpha=0.5)
        self.cursors = [history.axvline(times[0], color="tab:blue", lw=1.2)]

    def _plot_ground(self, times, lines):
        """The table's acceleration (once per distinct motion), with a cursor at the frame."""
        seen: list = []
        for k, run in enumerate(self.results):
            ground = run.motion
            if any(np.array_equal(ground.horizontal, other.horizontal)
                   and np.array_equal(ground.t, other.t) for other in seen):
                continue
            seen.append(ground)
            shown = ground.t <= times[-1] + 1e-12
            (trace,) = self.ground.plot(ground.t[shown], ground.horizontal[shown] / G,
                                        lw=0.7, color="0.3" if len(seen) == 1 else lines[k])
            self.traces.append((trace, ground.t[shown], ground.horizontal[shown] / G))
        self.ground.set_ylabel("ü [g]")
        self.ground.set_xlabel("time [s]")
        self.ground.grid(True, lw=0.3, alpha=0.5)
        self.cursors.append(self.ground.axvline(times[0], color="tab:blue", lw=1.2))

    def draw(self, index: int):
        """Move the artists to frame ``index``; return them."""
        t = self.times[index]
        for k, table in enumerate(self.tables):
            table.set_x(self.displacement[k][index] - self.table_widths[k] / 2)
        for k, (patch, outline) in enumerate(zip(self.blocks, self.outlines)):
            patch.set_xy(outline[index][:4])
            self.dots[k].set_data([t], [self.theta[k][index] / self.results[k].block.alpha])
        for cursor in self.cursors:
            cursor.set_xdata([t, t])
        for trace, trace_times, values in self.traces:   # up to t, never ahead of it
            shown = int(np.searchsorted(trace_times, t, side="right"))
            trace.set_data(trace_times[:shown], values[:shown])
        sign = "+" if self.displacement[0][index] >= 0 else "−"
        self.clock.set_text(f"t = {t:6.2f} s   table x = {sign}"
                            f"{abs(self.displacement[0][index]):.2f} {self.unit}")
        words = []
        for run in self.results:
            if run.overturned and t >= run.t_overturn:
                words.append(f"overturned at {run.t_overturn:.2f} s")
            elif np.isfinite(run.t_unstable) and t >= run.t_unstable:
                words.append(f"|θ| > α at {run.t_unstable:.2f} s")
            else:
                words.append("")
        if len(self.states) == len(words):
            for state, text in zip(self.states, words):
                state.set_text(text)
        else:  # overlay: one stage, a line per run that has something to say
            self.states[0].set_text("\n".join(f"{label}: {text}" for label, text
                                              in zip(self.labels, words) if text))
        return self.animated


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


def _size(size, dpi) -> tuple:
    if not (isinstance(size, (tuple, list)) and len(size) == 2):
        raise ValueError(f"size must be (width, height) in pixels, got {size!r}")
    width, height = (int(positive("size", value)) for value in size)
    if not (64 <= width <= MAX_SIDE and 64 <= height <= MAX_SIDE):
        raise ValueError(f"size must be from 64 to {MAX_SIDE} pixels a side, got "
                         f"{width} x {height}")
    dpi = positive("dpi", dpi)
    if not DPI_RANGE[0] <= dpi <= DPI_RANGE[1]:
        raise ValueError(f"dpi must be from {DPI_RANGE[0]:g} to {DPI_RANGE[1]:g} dots per inch, "
                         f"got {dpi:g}")
    return width, height


def _writer(path: Path, size: tuple, fps: float):
    """A function taking RGB frames (None ends), writing ``path`` (GIF or MP4)."""
    width, height = size
    if path.suffix.lower() == ".mp4":
        import matplotlib

        process = subprocess.Popen(
            [str(matplotlib.rcParams["animation.ffmpeg_path"]), "-y", "-loglevel", "error",
             "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", f"{width}x{height}", "-r", f"{fps:g}",
             "-i", "-", "-an", "-vcodec", "libx264", "-pix_fmt", "yuv420p", "-crf", "20",
             "-f", "mp4", str(path)], stdin=subprocess.PIPE, stderr=subprocess.PIPE)

        def write_mp4(frame):
            assert process.stdin is not None
            if frame is not None:
                process.stdin.write(frame.tobytes())
                return
            _, errors = process.communicate()
            if process.returncode:
                raise OSError(f"ffmpeg could not write {path}: "
                              f"{errors.decode(errors='replace').strip()[-300:]}")
        return write_mp4
    from PIL import Image

    frames: list = []

    def write_gif(frame):
        if frame is not None:  # one palette (the first frame's) keeps the colours steady
            image = Image.fromarray(frame)
            frames.append(image.quantize(colors=255) if not frames else
                          image.quantize(palette=frames[0], dither=Image.Dither.NONE))
            return
        frames[0].save(path, format="GIF", save_all=True, append_images=frames[1:],
                       duration=max(int(round(1000.0 / fps)), 20), loop=0, optimize=False)
    return write_gif


def animate(result: RockingResult | Sequence[RockingResult], block: Block | None = None,
            motion: Motion | None = None, *, out: str | os.PathLike[str],
            fps: float = DEFAULT_FPS, speed: float | None = 1.0, start: float | None = None,
            end: float | None = None, size: tuple = DEFAULT_SIZE, dpi: float = DEFAULT_DPI,
            layout: str = "side", labels: Sequence[str] | None = None, unit: str | None = None,
            highpass: float | None = 0.1, title: str | None = None,
            max_frames: int = MAX_FRAMES) -> AnimationFile:
    """Write an animation (GIF, or MP4 with ffmpeg) of blocks rocking on the moving table.

    Parameters
    ----------
    result : RockingResult or sequence of RockingResult
        The simulation(s) to show; several are drawn side by side or overlaid, to
        one scale, with their theta/alpha traces in one panel.
    block : Block, optional
        One result only: the block drawn; default (and it must be) ``result.block``.
    motion : Motion, optional
        One result only: the table motion whose displacement moves the table
        [m/s^2]; default ``result.motion`` (the accelerations the block felt).
    out : str or Path
        The file to write: ``.gif``, or ``.mp4`` (written by ffmpeg; without ffmpeg
        the same name with ``.gif`` is written instead and :attr:`AnimationFile.note`
        says so). No suffix: MP4 when ffmpeg is found, else GIF. Its folder is created.
    fps : float
        Frames per second of the animation [1/s].
    speed : float or None
        Simulated seconds per second of the animation [-]; 1 is real time, 2
        twice as fast. One frame every ``speed / fps`` simulated seconds. None: real
        time for a span of 4 s or more, a shorter one slowed to last 4 s
        (:func:`default_speed`).
    start, end : float, optional
        Simulated time span shown [s]; default the whole (longest) result.
    size : (int, int)
        Width and height of the frames [pixels] (default 1024 x 576).
    dpi : float
        Dots per inch: the figure is ``size / dpi`` inches, so a larger dpi makes the
        fonts and lines larger in the same frame (default 100).
    layout : {"side", "overlay"}
        Several results: each block on its own table side by side, or all on one.
    labels : sequence of str, optional
        One per result; default what tells them apart (``COR 0.93``, ``6 x 2 ft``).
    unit : str, optional
        Length unit of the stage, one of :data:`STAGE_UNITS`; default the unit the
        first block was written in (``Block.label``), else metres.
    highpass : float or None
        Corner of the table's displacement high-pass [Hz]
        (:func:`table_displacement`, which also removes the drift of the
        integrated acceleration).
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
    results = [result] if isinstance(result, RockingResult) else list(result)
    if not results:
        raise ValueError("result must be a RockingResult or a non-empty sequence of them")
    if len(results) == 1:
        block, motion = _inputs(results[0], block, motion)
        motions: list = [motion]
    else:
        if block is not None or motion is not None:
            raise ValueError("block and motion are for one result; several results are "
                             "drawn with their own")
        for run in results:
            _inputs(run, None, None)
        motions = [run.motion for run in results]
    if layout not in ("side", "overlay"):
        raise ValueError(f"layout must be 'side' or 'overlay', got {layout!r}")
    if labels is not None and len(labels) != len(results):
        raise ValueError(f"labels must give one label per result ({len(results)}), "
                         f"got {len(labels)}")
    if unit is not None and unit not in STAGE_UNITS:
        raise ValueError(f"unit must be one of {', '.join(STAGE_UNITS)}, got {unit!r}")
    if layout == "side" and len(results) > 6:
        raise ValueError(f"at most 6 results side by side, got {len(results)}; use "
                         "layout='overlay' or fewer")
    width, height = _size(size, dpi)
    width, height = width - width % 2, height - height % 2  # even: the MP4 codec needs it
    out, note = output_file(out)
    t_first = min(float(run.t[0]) for run in results) if start is None else float(start)
    t_last = max(float(run.t[-1]) for run in results)
    t_last = t_last if end is None else min(float(end), t_last)
    speed = default_speed(t_last - t_first) if speed is None else speed
    times = frame_times(t_first, t_last, fps, speed, max_frames)
    from shaketable.core.files import atomic_write, prepare_output_file
    from shaketable.plots.base import pyplot

    out = prepare_output_file(out, "out")
    stage = _Stage(results, motions, times, highpass, size=(width, height), dpi=dpi,
                   layout=layout, labels=labels, unit=unit, title=title)
    try:
        atomic_write(out, lambda temporary: _render(stage, temporary, (width, height), fps))
    finally:
        pyplot().close(stage.fig)
    return AnimationFile(path=out, n_frames=len(times), fps=float(fps), speed=float(speed),
                         t_first=float(times[0]), t_last=float(times[-1]),
                         size=(width, height), note=note)


def _render(stage: _Stage, path: Path, size: tuple, fps: float) -> None:
    """Every frame by blitting: the still parts drawn once, the moving artists per frame."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(stage.fig)
    for artist in stage.animated:
        artist.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(stage.fig.bbox)
    width, height = size
    write = None
    for index in range(len(stage.times)):
        canvas.restore_region(background)
        for artist in stage.draw(index):
            stage.fig.draw_artist(artist)
        frame = np.asarray(canvas.buffer_rgba())[:height, :width, :3]
        if write is None:  # the canvas may round the figure's size by a pixel
            write = _writer(path, (frame.shape[1] - frame.shape[1] % 2,
                                   frame.shape[0] - frame.shape[0] % 2), fps)
            width, height = frame.shape[1] - frame.shape[1] % 2, frame.shape[0] - frame.shape[0] % 2
        write(np.ascontiguousarray(frame[:height, :width]))
    assert write is not None  # frame_times gives at least one frame
    write(None)


def snapshot(result: RockingResult | Sequence[RockingResult], time: float, *,
             out: str | os.PathLike[str], motion: Motion | None = None,
             span: tuple | None = None, size: tuple = DEFAULT_SIZE, dpi: float = DEFAULT_DPI,
             layout: str = "side", highpass: float | None = 0.1) -> Path:
    """One frame of :func:`animate` at simulated ``time`` [s], saved as an image (PNG...).

    ``span`` (start, end) [s] is the time axis of the history (default the whole result).
    """
    results = [result] if isinstance(result, RockingResult) else list(result)
    if len(results) == 1:
        _, motion = _inputs(results[0], None, motion)
        motions: list = [motion]
    else:
        motions = [run.motion for run in results]
    width, height = _size(size, dpi)
    first, last = span if span is not None else (min(float(run.t[0]) for run in results),
                                                 max(float(run.t[-1]) for run in results))
    times = np.array([first, float(time), last])
    stage = _Stage(results, motions, times, highpass, size=(width, height), dpi=dpi,
                   layout=layout)
    stage.draw(1)
    from shaketable.core.files import atomic_write, prepare_output_file
    from shaketable.plots.base import pyplot

    out = prepare_output_file(out, "out")
    try:
        atomic_write(out, lambda temporary: stage.fig.savefig(temporary, dpi=dpi))
    finally:
        pyplot().close(stage.fig)
    return out


#: The frame loop, the frame-size check and the writer, for the stack's animation
#: (:mod:`shaketable.plots.stack_animation`).
render_frames, checked_size = _render, _size
