"""The shaking table itself: displacement command, limits, servo, pitch.

Sections 3.4-3.7 of the report describe the 20 ft x 20 ft table of the
University of California (Richmond Field Station): it is commanded by
*displacement* histories that a mini-computer derives from the acceleration
records, it is driven by servo-controlled hydraulic actuators, and while it
runs it *pitches* "at approximately 12 Hz" with an angular acceleration
"between 0.2 to 0.25 radians/sec^2". This module models each step:

* :func:`displacement_command` -- the displacement (and velocity) the
  controller needs for an acceleration history: zero-phase high-pass,
  exact double integration and a polynomial baseline so the table starts and
  ends at rest; returns a :class:`TableCommand`.
* :class:`TableLimits`, :func:`check_limits` -- stroke, velocity and
  acceleration limits per axis, and what a command exceeds
  (:class:`LimitExceedance`).
* :class:`Actuator`, :func:`achieved` -- a second-order servo (with an
  optional pure delay) between command and table: the achieved
  accelerations.
* :class:`Pitch`, :func:`pitch_history` -- the table's pitching: angle,
  angular velocity and angular acceleration, seeded and reproducible.
* :func:`motion_at_block` -- the motion the block feels on a pitching table:
  the tilt of gravity and the rotation's tangential accelerations folded into
  ``horizontal``/``vertical``, the angular acceleration in ``rotation``.

How pitch enters the block's equation of motion is derived in
:func:`motion_at_block` and in ``docs/table.md``. Signs and units follow
``docs/conventions.md``: SI, vertical positive up, rotations positive in the
sense of positive theta (counterclockwise with +x to the right and up up).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.signal
from numpy.typing import ArrayLike

from shaketable.core.motion import Motion
from shaketable.core.motion import motion_argument as _motion
from shaketable.core.sampling import uniform_step
from shaketable.core.validation import integer as _integer
from shaketable.core.validation import positive as _positive

#: Axes of the table, in the order used everywhere in this module.
AXES = ("horizontal", "vertical")


# ------------------------------------------------------------------ validation
def _read_only(name: str, values: object, size: int | None = None) -> np.ndarray:
    try:
        array = np.array(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be an array of numbers: {error}") from None
    if array.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} contains non-finite values (NaN or inf)")
    if size is not None and array.size != size:
        raise ValueError(f"{name} has {array.size} samples but t has {size}")
    array.setflags(write=False)
    return array


@dataclass(frozen=True)
class TableCommand:
    """Displacement command of the table and the motion it implies.

    Each axis is either fully present (displacement, velocity and
    acceleration) or fully absent (all three ``None``); the horizontal axis is
    always present.

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing.
    horizontal_displacement : array_like
        Horizontal table displacement command [m], positive along +x.
    horizontal_velocity : array_like
        Horizontal table velocity [m/s] (exact derivative of the command).
    horizontal_acceleration : array_like
        Horizontal acceleration the command implies [m/s^2] (its exact
        second derivative; linear between samples).
    vertical_displacement : array_like, optional
        Vertical displacement command [m], positive upward.
    vertical_velocity : array_like, optional
        Vertical velocity [m/s], positive upward.
    vertical_acceleration : array_like, optional
        Vertical acceleration the command implies [m/s^2], positive upward.
    name : str, optional
        Label, normally the name of the motion commanded.
    """

    t: np.ndarray
    horizontal_displacement: np.ndarray
    horizontal_velocity: np.ndarray
    horizontal_acceleration: np.ndarray
    vertical_displacement: np.ndarray | None = None
    vertical_velocity: np.ndarray | None = None
    vertical_acceleration: np.ndarray | None = None
    name: str = ""

    def __post_init__(self) -> None:
        t = _read_only("TableCommand.t", self.t)
        if t.size < 2 or np.any(np.diff(t) <= 0.0):
            raise ValueError("TableCommand.t must have at least 2 strictly increasing samples")
        object.__setattr__(self, "t", t)
        for axis in AXES:
            keys = [f"{axis}_{quantity}" for quantity in ("displacement", "velocity",
                                                          "acceleration")]
            given = [getattr(self, key) is not None for key in keys]
            if axis == "horizontal" and not all(given):
                raise ValueError("TableCommand needs the horizontal displacement, velocity "
                                 "and acceleration")
            if any(given) and not all(given):
                raise ValueError(f"TableCommand: give all or none of {', '.join(keys)}")
            for key in keys:
                value = getattr(self, key)
                if value is not None:
                    object.__setattr__(self, key,
                                       _read_only(f"TableCommand.{key}", value, t.size))

    @property
    def axes(self) -> tuple[str, ...]:
        """The axes commanded, ``("horizontal",)`` or ``("horizontal", "vertical")``."""
        return tuple(axis for axis in AXES
                     if getattr(self, f"{axis}_displacement") is not None)

    def quantity(self, axis: str, quantity: str) -> np.ndarray | None:
        """One history: ``axis`` in :data:`AXES`, ``quantity`` in
        ``displacement`` [m], ``velocity`` [m/s], ``acceleration`` [m/s^2]."""
        if axis not in AXES:
            raise ValueError(f"axis must be one of {AXES}, got {axis!r}")
        if quantity not in QUANTITIES:
            raise ValueError(f"quantity must be one of {tuple(QUANTITIES)}, got {quantity!r}")
        return getattr(self, f"{axis}_{quantity}")

    def motion(self) -> Motion:
        """The accelerations the command implies, as a :class:`Motion` [m/s^2]."""
        return Motion(self.t, self.horizontal_acceleration, self.vertical_acceleration,
                      name=self.name)


def _butterworth_highpassed(acceleration: np.ndarray, dt: float, corner: float,
                            order: int) -> np.ndarray:
    """Zero-phase Butterworth high-pass of a record padded with zeros at both ends.

    ``sosfiltfilt`` runs the filter forward and backward (no phase shift,
    amplitude response squared). The zero padding, ``1.5 order / corner``
    seconds on each side, holds the filter's start-up and ringing; it is cut
    off again.
    """
    sos = scipy.signal.butter(order, corner, btype="highpass", fs=1.0 / dt, output="sos")
    pad = int(math.ceil(1.5 * order / (corner * dt)))
    padded = np.concatenate([np.zeros(pad), acceleration, np.zeros(pad)])
    return scipy.signal.sosfiltfilt(sos, padded, padtype=None)[pad:pad + acceleration.size]


def zero_phase_highpass(values: ArrayLike, dt: float, corner: float,
                        order: int = 4) -> np.ndarray:
    """Zero-phase Butterworth high-pass of a sampled history (any quantity).

    Parameters
    ----------
    values : array_like
        Samples every ``dt``, treated as zero before and after.
    dt : float
        Sample interval [s], positive.
    corner : float
        Corner frequency [Hz], positive and below the Nyquist frequency.
    order : int, optional
        Order of the filter [-], 1 to 8, run forward and backward.

    Returns
    -------
    numpy.ndarray
        The filtered samples, same length, no phase shift.
    """
    dt = _positive("dt", dt, " [s]")
    corner = _positive("corner", corner, " [Hz]")
    if corner >= 0.5 / dt:
        raise ValueError(f"corner ({corner!r} Hz) must be below the Nyquist frequency "
                         f"{0.5 / dt:g} Hz")
    order = _integer("order", order, 1, 8)
    return _butterworth_highpassed(np.asarray(values, dtype=float), dt, corner, int(order))


def _integrated_from_rest(acceleration: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocity [m/s] and displacement [m] of a piecewise-linear acceleration.

    Exact integrals from rest (zero velocity and displacement) at the first
    sample, uniform step ``dt``.
    """
    a0, a1 = acceleration[:-1], acceleration[1:]
    velocity = np.concatenate([[0.0], np.cumsum(0.5 * dt * (a0 + a1))])
    displacement = np.concatenate(
        [[0.0], np.cumsum(velocity[:-1] * dt + dt * dt * (2.0 * a0 + a1) / 6.0)])
    return velocity, displacement


def _baseline_shapes(s: np.ndarray, duration: float) -> np.ndarray:
    """Accelerations [1/s^2] of the displacement shapes s^3, s^4, s^5, s = (t - t0)/T.

    Each is zero with its displacement and velocity at s = 0, so subtracting a
    combination keeps the start at rest and the acceleration at the start.
    """
    return np.array([k * (k - 1) * s ** (k - 2) for k in (3, 4, 5)]) / duration**2


def _rest_baseline_corrected(acceleration: np.ndarray, t: np.ndarray, dt: float) -> np.ndarray:
    """Subtract ``c3 g3 + c4 g4 + c5 g5`` (:func:`_baseline_shapes`) so the table ends at rest.

    The coefficients make the exactly integrated (piecewise-linear) corrected
    acceleration end with zero velocity and displacement while its last
    sample is unchanged: a 3 x 3 linear system on the shapes' end values.
    The result is consistent to rounding: its exact integrals are the command.
    """
    duration = float(t[-1] - t[0])
    shapes = _baseline_shapes((t - t[0]) / duration, duration)
    ends = np.array([_integrated_from_rest(shape, dt) for shape in shapes])[:, :, -1]
    velocity, displacement = _integrated_from_rest(acceleration, dt)
    system = np.vstack([ends.T, shapes[:, -1]])           # rows: v(T), d(T), a(T)
    coefficients = np.linalg.solve(system, [velocity[-1], displacement[-1], 0.0])
    return acceleration - coefficients @ shapes


def _axis_command(acceleration: np.ndarray, t: np.ndarray, dt: float,
                  highpass: float | None, order: int,
                  baseline: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Displacement, velocity and implied acceleration of one axis."""
    if highpass is not None:
        acceleration = _butterworth_highpassed(acceleration, dt, highpass, order)
    if baseline:
        acceleration = _rest_baseline_corrected(acceleration, t, dt)
    velocity, displacement = _integrated_from_rest(acceleration, dt)
    return displacement, velocity, acceleration


def displacement_command(motion: Motion, *, highpass: float | None = 0.1, order: int = 4,
                         baseline: bool = True) -> TableCommand:
    """The displacement history that commands the table for ``motion``.

    The report's table is driven by displacement-time histories derived from
    the acceleration records by a mini-computer (Section 3.4). Per axis:

    1. zero-phase high-pass: a Butterworth filter of ``order`` at
       ``highpass`` run forward and backward (``scipy.signal.sosfiltfilt``) on
       the record padded with zeros, which removes the low frequencies that
       would need metres of stroke without shifting the phase;
    2. exact double integration of the (piecewise-linear) acceleration from
       rest at the first sample;
    3. baseline: the second derivative of the quintic
       ``c3 s^3 + c4 s^4 + c5 s^5`` in ``s = (t - t0) / T`` (a smooth cubic in
       time) subtracted from the acceleration so that the table *ends* at
       rest where it started (zero displacement and velocity at both ends);
       it leaves the acceleration at both ends unchanged. ``c3, c4, c5``
       solve those three conditions for the exactly integrated samples.

    The returned acceleration is linear between samples and the returned
    velocity and displacement are its exact integrals, so the acceleration is
    exactly the second derivative of the command (to rounding): what a
    perfect table would do. A target that does not itself start and end at
    rest cannot be met everywhere; the baseline spreads the difference over
    the whole record (for Fig. 3.7's 2 Hz, 0.5 g stopped abruptly at full
    velocity, 3-4 % of the PGA), so end a harmonic at a velocity zero
    crossing (a quarter period after a whole number of cycles).

    Parameters
    ----------
    motion : Motion
        Target table accelerations [m/s^2], uniformly sampled. ``rotation`` is
        ignored (the table is not commanded to pitch).
    highpass : float or None, optional
        Corner frequency of the high-pass [Hz], positive and below the
        Nyquist frequency ``1 / (2 dt)``; ``None`` skips the filter.
    order : int, optional
        Order of the Butterworth filter [-], 1 to 8 (the forward-backward pass
        doubles its roll-off).
    baseline : bool, optional
        Apply the end-at-rest baseline (step 3). Without it the command ends
        with whatever displacement and velocity the integration leaves.

    Returns
    -------
    TableCommand
        Same times as ``motion``; a vertical axis only if ``motion`` has one.

    Raises
    ------
    ValueError
        If ``motion`` is not a uniformly sampled Motion, or a parameter is
        out of range; the message names it.
    """
    motion = _motion("motion", motion)
    dt = uniform_step(motion.t, "displacement_command")
    if highpass is not None:
        highpass = _positive("highpass", highpass, " [Hz]")
        nyquist = 0.5 / dt
        if highpass >= nyquist:
            raise ValueError(f"highpass ({highpass!r} Hz) must be below the Nyquist "
                             f"frequency {nyquist:g} Hz of the motion")
    order = _integer("order", order, 1, 8)
    if not isinstance(baseline, (bool, np.bool_)):
        raise ValueError(f"baseline must be True or False, got {baseline!r}")
    fields: dict[str, np.ndarray] = {}
    for axis in AXES:
        acceleration = getattr(motion, axis)
        if acceleration is None:
            continue
        displacement, velocity, implied = _axis_command(acceleration, motion.t, dt, highpass,
                                                        int(order), bool(baseline))
        fields.update({f"{axis}_displacement": displacement, f"{axis}_velocity": velocity,
                       f"{axis}_acceleration": implied})
    return TableCommand(motion.t, name=motion.name, **fields)


# ------------------------------------------------------------------ limits
QUANTITIES = {"displacement": ("stroke", "m"), "velocity": ("velocity", "m/s"),
               "acceleration": ("acceleration", "m/s^2")}
