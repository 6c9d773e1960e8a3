"""Instruments of the virtual test: potentiometers, accelerometers, digitizer.

Section 3.3 of the report [1]_: the horizontal displacement of the top of the
block *relative to the table* was measured by a spring-loaded wire
potentiometer (range +-15 in) whose wire pulls the top with 20 oz; a second
potentiometer on the other side cancelled that force. The table's horizontal
acceleration was measured by an accelerometer near the base of the block and
its vertical acceleration by two accelerometers, averaged. Everything was
digitized at 50 samples/s (Sections 3.5, 3.6; the table system itself could
sample at 100 samples/s, Section 3.4), and the angle of the block was obtained
from the top displacement divided by the height.

This module turns a simulation (:class:`~shaketable.models.rocking.result.RockingResult`)
and the motion the block felt into such a :class:`Measurement`:

1. the true signals on a fine uniform grid (``Digitizer.oversample`` points per
   sample): the exact top displacement :func:`top_displacement` of the
   rotation, and the table accelerations (linear between the motion's
   samples, like :class:`~shaketable.core.motion.Motion`);
2. sensor noise (white on the fine grid, scaled so that its RMS *after* the
   anti-alias filter is the value given), then the sensor's range (the
   potentiometer's +-stroke) with clipping;
3. the anti-alias filter, a causal analog-style Butterworth low-pass
   (``Digitizer.filter_order`` poles at ``Digitizer.cutoff``, default 4 poles
   at 0.4 x rate = 20 Hz for 50 samples/s), started at rest on the first value;
4. sampling at ``Digitizer.rate``, ADC noise, quantisation to ``bits`` over
   +-full scale and clipping at full scale.

Geometry of the potentiometer reading (``docs/conventions.md`` for the sign of
theta). The wire is attached at the middle of the top face. With
s = sign(theta) the block pivots on its corner at -s b; the top middle point,
at (0, H) at rest, moves to::

    x_top(theta) = -H sin(theta) - s b (1 - cos(theta))        (exact)

so ``top_displacement`` is negative for theta > 0 (the top moves toward -x).
The report converted with the small-angle relation theta = |x_top| / H; with
the signed convention here that is ``theta = -x_top / H`` (:attr:`Measurement.theta`).
The exact inverse (:func:`theta_from_top_displacement`): for theta > 0,
H sin(theta) - b cos(theta) = -x_top - b, i.e. D sin(theta - beta) = -x_top - b
with D = sqrt(H^2 + b^2), beta = arctan(b / H); theta < 0 is the mirror image::

    theta = -sign(x_top) [beta + arcsin((|x_top| - b) / D)]

The report's value exceeds the exact one by (b/2H) theta^2 - theta^3/6 + O(theta^4)
(expand sin(theta) + (b/H)(1 - cos(theta))): 0.33 % of theta at theta = alpha/2
for the 30 x 6 in block.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, *Rocking and overturning
   response of rigid bodies to earthquake motions*, Lawrence Berkeley
   Laboratory, University of California, Berkeley (program BLOKROC).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from shaketable.core.constants import INCH, G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.validation import nonnegative, positive
from shaketable.lab.digitizer import Digitizer, digitize
from shaketable.models.rocking.result import RockingResult

#: One ounce-force [N] (avoirdupois ounce x standard gravity).
OUNCE_FORCE = 0.028349523125 * G

#: Where potentiometer wires can be fitted.
WIRES = ("both", "minus-x", "plus-x")

# ------------------------------------------------------------------ validation


# ------------------------------------------------------------------ geometry
def top_displacement(theta, block: Block) -> np.ndarray:
    """Horizontal displacement of the middle of the top face relative to the table [m].

    Exact rigid-body geometry for rocking about either bottom corner
    (sign convention of ``docs/conventions.md``; s = sign(theta))::

        x_top = -H sin(theta) - s b (1 - cos(theta))

    Parameters
    ----------
    theta : float or array_like
        Rotation [rad], |theta| <= pi/2.
    block : Block
        The block (H = ``block.height``, b = ``block.b``) [m].

    Returns
    -------
    ndarray
        x_top [m], positive along +x; negative for theta > 0.
    """
    theta = np.asarray(theta, dtype=float)
    return -block.height * np.sin(theta) - np.sign(theta) * block.b * (1.0 - np.cos(theta))


def theta_from_top_displacement(displacement, block: Block) -> np.ndarray:
    """Exact rotation [rad] from the top displacement, the inverse of :func:`top_displacement`.

    With D = sqrt(H^2 + b^2) and beta = arctan(b/H)::

        theta = -sign(x) [beta + arcsin((|x| - b) / D)]

    x_top is a strictly decreasing function of theta on |theta| < pi/2, so the
    inverse is unique. A magnitude beyond D - b (not reachable by rocking)
    is clipped to the arcsine's domain.

    Parameters
    ----------
    displacement : float or array_like
        x_top [m], positive along +x.
    block : Block

    Returns
    -------
    ndarray
        theta [rad].
    """
    x = np.asarray(displacement, dtype=float)
    height, b = block.height, block.b
    d = math.hypot(height, b)
    beta = math.atan2(b, height)
    argument = np.clip((np.abs(x) - b) / d, -1.0, 1.0)
    return -np.sign(x) * (beta + np.arcsin(argument))


@dataclass(frozen=True)
class Potentiometers:
    """Spring-loaded wire potentiometers at the top of the block (Section 3.3).

    Parameters
    ----------
    wires : str
        Where wires are fitted: ``"both"`` (the report's set-up: the two 20 oz
        forces cancel), ``"minus-x"`` (one wire, pulling the top toward -x) or
        ``"plus-x"`` (one wire, pulling toward +x).
    wire_force : float
        Horizontal pull of one wire [N] (report: 20 oz = 5.56 N).
    stroke : float
        Range of the reading, +-stroke [m] (report: 15 in); the reading clips
        beyond it.
    noise : float
        RMS of the reading's noise after the anti-alias filter [m] (default
        0.005 in, an assumption: the report gives none).
    block_mass : float, optional
        Mass of the block [kg]; by default ``density x H x B x block_depth``.
    density : float
        Density of the block [kg/m^3] (default 2400, normal-weight concrete;
        an assumption).
    block_depth : float
        Third dimension of the block, along the rocking edges [m] (default
        12 in, an assumption; the report gives 18 in only for the 36 x 9 in
        block and says it does not affect the free response).
    """

    wires: str = "both"
    wire_force: float = 20.0 * OUNCE_FORCE
    stroke: float = 15.0 * INCH
    noise: float = 0.005 * INCH
    block_mass: float | None = None
    density: float = 2400.0
    block_depth: float = 12.0 * INCH

    def __post_init__(self):
        if self.wires not in WIRES:
            raise ValueError(f"wires must be one of {WIRES}, got {self.wires!r}")
        object.__setattr__(self, "wire_force", nonnegative("wire_force", self.wire_force, " [N]"))
        object.__setattr__(self, "stroke", positive("stroke", self.stroke, " [m]"))
        object.__setattr__(self, "noise", nonnegative("noise", self.noise, " [m]"))
        if self.block_mass is not None:
            object.__setattr__(self, "block_mass",
                               positive("block_mass", self.block_mass, " [kg]"))
        object.__setattr__(self, "density", positive("density", self.density, " [kg/m^3]"))
        object.__setattr__(self, "block_depth",
                           positive("block_depth", self.block_depth, " [m]"))

    def mass(self, block: Block) -> float:
        """Mass of the block [kg]: ``block_mass`` or density x H x B x depth."""
        if self.block_mass is not None:
            return self.block_mass
        return self.density * block.height * block.width * self.block_depth

    def top_force(self, block: Block) -> float:
        """Net horizontal wire force at the top per unit mass [m/s^2], for ``simulate(top_force=)``.

        Each wire pulls the top toward its post: a wire on the -x side gives
        ``-wire_force / M``, one on the +x side ``+wire_force / M`` (positive
        along +x, ``docs/conventions.md``); with both fitted they cancel (0).
        """
        if not isinstance(block, Block):
            raise ValueError(f"block must be a shaketable.Block, got {type(block).__name__}")
        if self.wires == "both":
            return 0.0
        sign = -1.0 if self.wires == "minus-x" else 1.0
        return sign * self.wire_force / self.mass(block)


@dataclass(frozen=True)
class Accelerometers:
    """Table accelerometers (Section 3.3).

    One horizontal accelerometer on the table near the base of the block; two
    vertical ones at +-``spacing`` from the block's centre, averaged. On a
    pitching table each vertical one reads ``v + (x +- spacing) phi''``; the
    average cancels the +-spacing phi'' part and leaves the vertical at the
    block's centre (the ``vertical`` of
    :func:`shaketable.lab.pitch.motion_at_block`), with the noise of one divided
    by sqrt(2).

    Parameters
    ----------
    spacing : float
        Distance of each vertical accelerometer from the block's centre [m]
        (default 12 in, an assumption).
    noise : float
        RMS noise of each accelerometer after the anti-alias filter [m/s^2]
        (default 0.002 g, an assumption).
    vertical : bool
        Whether the vertical pair is fitted (``False``: horizontal only).
    """

    spacing: float = 12.0 * INCH
    noise: float = 0.002 * G
    vertical: bool = True

    def __post_init__(self):
        object.__setattr__(self, "spacing", nonnegative("spacing", self.spacing, " [m]"))
        object.__setattr__(self, "noise", nonnegative("noise", self.noise, " [m/s^2]"))
        if not isinstance(self.vertical, (bool, np.bool_)):
            raise ValueError(f"vertical must be True or False, got {self.vertical!r}")


@dataclass(frozen=True)
class Sensors:
    """The instrumentation of one test (Section 3.3).

    Parameters
    ----------
    potentiometers : Potentiometers or None
        Top-displacement potentiometers; ``None``: not fitted.
    accelerometers : Accelerometers or None
        Table accelerometers; ``None``: not fitted.
    digitizer : Digitizer
        Filter, sampling and ADC of every channel.
    seed : int or None
        Seed of ``numpy.random.default_rng`` for all the noise: same seed,
        same record.
    """

    potentiometers: Potentiometers | None = field(default_factory=Potentiometers)
    accelerometers: Accelerometers | None = field(default_factory=Accelerometers)
    digitizer: Digitizer = field(default_factory=Digitizer)
    seed: int | None = None

    def __post_init__(self):
        if self.potentiometers is not None and not isinstance(self.potentiometers,
                                                              Potentiometers):
            raise ValueError("potentiometers must be Potentiometers or None, got "
                             f"{type(self.potentiometers).__name__}")
        if self.accelerometers is not None and not isinstance(self.accelerometers,
                                                              Accelerometers):
            raise ValueError("accelerometers must be Accelerometers or None, got "
                             f"{type(self.accelerometers).__name__}")
        if not isinstance(self.digitizer, Digitizer):
            raise ValueError(f"digitizer must be a Digitizer, got "
                             f"{type(self.digitizer).__name__}")
        if self.seed is not None and (isinstance(self.seed, bool) or not isinstance(
                self.seed, (numbers.Integral, np.integer)) or self.seed < 0):
            raise ValueError(f"seed must be a non-negative integer or None, got {self.seed!r}")

    def top_force(self, block: Block) -> float:
        """Wire force per unit mass to pass to ``simulate(top_force=)`` [m/s^2] (0 without wires)."""
        return 0.0 if self.potentiometers is None else self.potentiometers.top_force(block)


@dataclass(frozen=True)
class Measurement:
    """A digitized record of one virtual test.

    Attributes
    ----------
    t : ndarray
        Sample times [s].
    top_displacement : ndarray or None
        Potentiometer reading: horizontal displacement of the top of the block
        relative to the table [m], positive along +x (negative for theta > 0).
    theta : ndarray or None
        Rotation the report's way, ``-top_displacement / height`` [rad]
        (Section 3.6: "angular block displacements, obtained from the top
        displacements of the block").
    theta_exact : ndarray or None
        Rotation by the exact inversion of the geometry
        (:func:`theta_from_top_displacement`) [rad].
    table_horizontal : ndarray or None
        Horizontal table acceleration near the block's base [m/s^2], +x.
    table_vertical : ndarray or None
        Average of the two vertical accelerometers [m/s^2], positive up.
    rate : float
        Samples per second [1/s].
    block : Block
        The block measured (for conversions).
    top_clipped, horizontal_clipped, vertical_clipped : ndarray of bool or None
        Per sample: the sensor's range or the ADC's full scale was reached.
    name : str
        Label.
    """

    t: np.ndarray
    top_displacement: np.ndarray | None
    theta: np.ndarray | None
    theta_exact: np.ndarray | None
    table_horizontal: np.ndarray | None
    table_vertical: np.ndarray | None
    rate: float
    block: Block
    top_clipped: np.ndarray | None = None
    horizontal_clipped: np.ndarray | None = None
    vertical_clipped: np.ndarray | None = None
    name: str = ""

    def __post_init__(self):
        for key in ("t", "top_displacement", "theta", "theta_exact", "table_horizontal",
                    "table_vertical", "top_clipped", "horizontal_clipped", "vertical_clipped"):
            value = getattr(self, key)
            if value is not None:
                value = np.array(value)
                value.setflags(write=False)
                object.__setattr__(self, key, value)

    @property
    def clipped(self) -> bool:
        """True when any channel clipped at any sample."""
        return any(bool(np.any(flags)) for flags in
                   (self.top_clipped, self.horizontal_clipped, self.vertical_clipped)
                   if flags is not None)

    @property
    def dt(self) -> float:
        """Sample interval [s]."""
        return 1.0 / self.rate

    def motion(self, name: str | None = None) -> Motion:
        """The digitized table accelerations as a :class:`Motion`.

        This is what the report fed BLOKROC for the "theory" runs
        (Section 3.6: "the measured shaking table accelerations were
        transferred to tape ... to carry out the computer analysis").
        """
        if self.table_horizontal is None:
            raise ValueError("this measurement has no accelerometers "
                             "(Sensors.accelerometers was None)")
        label = name if name is not None else (f"{self.name} (digitized)" if self.name
                                               else "digitized table motion")
        return Motion(self.t, self.table_horizontal, self.table_vertical, name=label)

    def to_frame(self):
        """The record as a :class:`pandas.DataFrame`, units in the column names."""
        import pandas as pd

        columns = {"time [s]": self.t}
        if self.top_displacement is not None:
            columns["top displacement [m]"] = self.top_displacement
            columns["top displacement [in]"] = self.top_displacement / INCH
            columns["theta [rad]"] = self.theta
            columns["theta exact [rad]"] = self.theta_exact
            columns["top clipped"] = self.top_clipped
        if self.table_horizontal is not None:
            columns["table horizontal [g]"] = self.table_horizontal / G
        if self.table_vertical is not None:
            columns["table vertical [g]"] = self.table_vertical / G
        return pd.DataFrame(columns)

    def plot(self, fig=None, title: str | None = None):
        """Record layout: angle, and table accelerations when measured.

        See :func:`shaketable.plots.calibration.plot_measurement`.
        """
        from shaketable.plots.calibration import plot_measurement

        return plot_measurement(self, fig=fig, title=title)


def _fine_theta(result: RockingResult, times: np.ndarray) -> np.ndarray:
    """theta at ``times`` [rad]: cubic Hermite on (theta, theta_dot), held outside the run."""
    t, theta, omega = result.t, result.theta, result.theta_dot
    keep = np.concatenate([[True], np.diff(t) > 0])
    t, theta, omega = t[keep], theta[keep], omega[keep]
    if t.size < 2:
        return np.full(times.shape, theta[0] if theta.size else 0.0)
    spline = CubicHermiteSpline(t, theta, omega)
    inside = np.clip(times, t[0], t[-1])
    values = spline(inside)
    values[times < t[0]] = theta[0]
    values[times > t[-1]] = theta[-1]
    return values


def measure(result: RockingResult, block: Block | None = None, motion: Motion | None = None,
            sensors: Sensors | None = None) -> Measurement:
    """The virtual test's record: a run seen through the sensors of Section 3.3.

    Parameters
    ----------
    result : RockingResult
        The engine run (for the block on the pitching table, with the wire
        force ``sensors.top_force(block)`` if a single wire is fitted).
    block : Block, optional
        The block (default ``result.block``).
    motion : Motion, optional
        The accelerations the block felt (default ``result.motion``); may
        carry the pitch in ``rotation``: the accelerometers, fixed to the
        table, read its ``horizontal`` (which already contains the tilt and
        tangential terms at the block, :func:`shaketable.lab.pitch.motion_at_block`)
        and, averaged over the pair, its ``vertical``.
    sensors : Sensors, optional
        Default ``Sensors()``: both potentiometers, the accelerometers and a
        50 samples/s digitizer with a 20 Hz 4-pole anti-alias filter, 12 bits.

    Returns
    -------
    Measurement
        Samples at ``start + k / rate`` up to ``end`` (default: the motion's
        first and last times). Before the run the block is held at its
        initial rotation; after it ends (overturned, airborne) it is held at
        its last rotation (it lies on the catcher arms, Section 3.3).

    Raises
    ------
    ValueError
        For arguments of the wrong type; the message names the argument.
    """
    if not isinstance(result, RockingResult):
        raise ValueError(f"result must be a RockingResult, got {type(result).__name__}")
    block = result.block if block is None else block
    if not isinstance(block, Block):
        raise ValueError(f"block must be a shaketable.Block, got {type(block).__name__}")
    motion = result.motion if motion is None else motion
    if not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable.Motion, got {type(motion).__name__}")
    sensors = Sensors() if sensors is None else sensors
    if not isinstance(sensors, Sensors):
        raise ValueError(f"sensors must be a shaketable.lab.sensors.Sensors, got "
                         f"{type(sensors).__name__}")
    digitizer = sensors.digitizer
    start = motion.t[0] if digitizer.start is None else digitizer.start
    end = max(motion.t[-1], result.t[-1]) if digitizer.end is None else digitizer.end
    if end <= start:
        raise ValueError(f"Digitizer.end ({end!r} s) must be after the start ({start!r} s)")
    n_samples = int(math.floor((end - start) * digitizer.rate + 1e-9)) + 1
    if n_samples < 2:
        raise ValueError(f"the record from {start!r} s to {end!r} s holds fewer than 2 samples "
                         f"at {digitizer.rate:g} samples/s")
    fine_dt = digitizer.dt / digitizer.oversample
    fine_t = start + fine_dt * np.arange((n_samples - 1) * digitizer.oversample + 1)
    t = fine_t[::digitizer.oversample].copy()
    rng = np.random.default_rng(sensors.seed)

    top = theta = theta_exact = top_clipped = None
    if sensors.potentiometers is not None:
        pots = sensors.potentiometers
        fine_top = top_displacement(_fine_theta(result, fine_t), block)
        full_scale = (pots.stroke if digitizer.displacement_full_scale is None
                      else digitizer.displacement_full_scale)
        top, top_clipped = digitize(fine_top, digitizer, full_scale, rng, pots.noise,
                                     pots.stroke)
        theta = -top / block.height
        theta_exact = theta_from_top_displacement(top, block)

    horizontal = vertical = horizontal_clipped = vertical_clipped = None
    if sensors.accelerometers is not None:
        accelerometers = sensors.accelerometers
        scale = digitizer.acceleration_full_scale

        def at_fine(values):
            return np.interp(fine_t, motion.t, values, left=0.0, right=0.0)

        horizontal, horizontal_clipped = digitize(
            at_fine(motion.horizontal), digitizer, scale, rng, accelerometers.noise, None)
        if accelerometers.vertical:
            centre = at_fine(motion.vertical_or_zero)
            pitch = at_fine(motion.rotation_or_zero) * accelerometers.spacing
            pair = [digitize(centre + side * pitch, digitizer, scale, rng,
                              accelerometers.noise, None) for side in (-1.0, 1.0)]
            vertical = 0.5 * (pair[0][0] + pair[1][0])
            vertical_clipped = pair[0][1] | pair[1][1]

    return Measurement(t=t, top_displacement=top, theta=theta, theta_exact=theta_exact,
                       table_horizontal=horizontal, table_vertical=vertical,
                       rate=digitizer.rate, block=block, top_clipped=top_clipped,
                       horizontal_clipped=horizontal_clipped, vertical_clipped=vertical_clipped,
                       name=motion.name)
