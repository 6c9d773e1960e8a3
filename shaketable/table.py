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
import numbers
from dataclasses import dataclass

import numpy as np
import scipy.signal

from .constants import G, INCH
from .motion import Motion
from .validation import motion_argument as _motion
from .validation import nonnegative as _nonnegative
from .validation import number as _number
from .validation import positive as _positive

__all__ = [
    "AXES",
    "Actuator",
    "LimitExceedance",
    "Pitch",
    "TableCommand",
    "TableLimits",
    "achieved",
    "achieved_displacement",
    "check_limits",
    "displacement_command",
    "motion_at_block",
    "pitch_history",
]

#: Axes of the table, in the order used everywhere in this module.
AXES = ("horizontal", "vertical")

#: Relative tolerance used to decide that a motion is uniformly sampled.
_UNIFORM_RTOL = 1e-6


# ------------------------------------------------------------------ validation
def _uniform_dt(t: np.ndarray, what: str) -> float:
    """Sample interval of uniformly sampled times [s], else a ValueError."""
    steps = np.diff(t)
    dt = float(np.mean(steps))
    if np.max(np.abs(steps - dt)) > _UNIFORM_RTOL * dt:
        raise ValueError(
            f"{what} needs a uniformly sampled motion; this one has steps from "
            f"{steps.min()!r} to {steps.max()!r} s"
        )
    return dt


def _seed(name: str, value) -> int | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)) \
            or value < 0:
        raise ValueError(f"{name} must be a non-negative integer or None, got {value!r}")
    return int(value)


def _read_only(name: str, values, size: int | None = None) -> np.ndarray:
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


# ------------------------------------------------------------------ command
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

    def __post_init__(self):
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
        if quantity not in _QUANTITIES:
            raise ValueError(f"quantity must be one of {tuple(_QUANTITIES)}, got {quantity!r}")
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


def _integrated_from_rest(acceleration: np.ndarray, dt: float):
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


def _rest_baseline_corrected(acceleration: np.ndarray, t: np.ndarray, dt: float):
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
                  highpass: float | None, order: int, baseline: bool):
    """Displacement, velocity and implied acceleration of one axis."""
    if highpass is not None:
        acceleration = _butterworth_highpassed(acceleration, dt, highpass, order)
    if baseline:
        acceleration = _rest_baseline_corrected(acceleration, t, dt)
    velocity, displacement = _integrated_from_rest(acceleration, dt)
    return displacement, velocity, acceleration


def displacement_command(motion, *, highpass=0.1, order=4, baseline=True) -> TableCommand:
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
    dt = _uniform_dt(motion.t, "displacement_command")
    if highpass is not None:
        highpass = _positive("highpass", highpass, " [Hz]")
        nyquist = 0.5 / dt
        if highpass >= nyquist:
            raise ValueError(f"highpass ({highpass!r} Hz) must be below the Nyquist "
                             f"frequency {nyquist:g} Hz of the motion")
    if isinstance(order, bool) or not isinstance(order, (numbers.Integral, np.integer)) \
            or not 1 <= order <= 8:
        raise ValueError(f"order must be an integer from 1 to 8, got {order!r}")
    if not isinstance(baseline, (bool, np.bool_)):
        raise ValueError(f"baseline must be True or False, got {baseline!r}")
    fields = {}
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
_QUANTITIES = {"displacement": ("stroke", "m"), "velocity": ("velocity", "m/s"),
               "acceleration": ("acceleration", "m/s^2")}


@dataclass(frozen=True)
class TableLimits:
    """Performance limits of the table, per axis (all peak absolute values).

    The defaults are **assumptions** for the 1970s Berkeley 20 ft x 20 ft
    table; the report (Section 3.4) gives none. They are the figures usually
    quoted for that table when it was built: horizontal stroke +-5 in, vertical
    +-2 in, velocity 25 in/s horizontal and 10 in/s vertical, acceleration
    1.5 g horizontal and 1.0 g vertical. Replace them when better data are at
    hand.

    Parameters
    ----------
    horizontal_stroke : float
        Largest horizontal displacement from centre [m] (default 5 in).
    horizontal_velocity : float
        Largest horizontal velocity [m/s] (default 25 in/s).
    horizontal_acceleration : float
        Largest horizontal acceleration [m/s^2] (default 1.5 g).
    vertical_stroke : float
        Largest vertical displacement from centre [m] (default 2 in).
    vertical_velocity : float
        Largest vertical velocity [m/s] (default 10 in/s).
    vertical_acceleration : float
        Largest vertical acceleration [m/s^2] (default 1.0 g).
    """

    horizontal_stroke: float = 5.0 * INCH
    horizontal_velocity: float = 25.0 * INCH
    horizontal_acceleration: float = 1.5 * G
    vertical_stroke: float = 2.0 * INCH
    vertical_velocity: float = 10.0 * INCH
    vertical_acceleration: float = 1.0 * G

    def __post_init__(self):
        for axis in AXES:
            for quantity, (limit, unit) in _QUANTITIES.items():
                key = f"{axis}_{limit}"
                object.__setattr__(self, key, _positive(key, getattr(self, key), f" [{unit}]"))

    def limit(self, axis: str, quantity: str) -> float:
        """Limit of ``quantity`` (displacement, velocity, acceleration) on ``axis``."""
        return getattr(self, f"{axis}_{_QUANTITIES[quantity][0]}")


@dataclass(frozen=True)
class LimitExceedance:
    """One quantity of one axis of a command that exceeds the table's limit.

    Parameters
    ----------
    axis : str
        ``"horizontal"`` or ``"vertical"``.
    quantity : str
        ``"displacement"``, ``"velocity"`` or ``"acceleration"``.
    unit : str
        Unit of ``limit``, ``peak`` and ``excess`` (``m``, ``m/s``, ``m/s^2``).
    limit : float
        The limit [unit].
    peak : float
        Signed value of largest magnitude [unit].
    t_peak : float
        Time of the peak [s].
    t_first, t_last : float
        First and last sample times at which the limit is exceeded [s].
    excess : float
        ``|peak| - limit`` [unit], positive.
    """

    axis: str
    quantity: str
    unit: str
    limit: float
    peak: float
    t_peak: float
    t_first: float
    t_last: float
    excess: float

    @property
    def ratio(self) -> float:
        """``|peak| / limit`` [-], above 1."""
        return abs(self.peak) / self.limit

    def __str__(self) -> str:
        return (f"{self.axis} {self.quantity}: peak {self.peak:+.4g} {self.unit} at "
                f"{self.t_peak:.3f} s exceeds the limit {self.limit:.4g} {self.unit} by "
                f"{self.excess:.4g} {self.unit} ({100 * (self.ratio - 1):.1f} %), "
                f"from {self.t_first:.3f} s to {self.t_last:.3f} s")


def _exceedance(t, values, axis, quantity, limit) -> LimitExceedance | None:
    over = np.flatnonzero(np.abs(values) > limit)
    if over.size == 0:
        return None
    index = int(np.argmax(np.abs(values)))
    peak = float(values[index])
    return LimitExceedance(axis=axis, quantity=quantity, unit=_QUANTITIES[quantity][1],
                           limit=limit, peak=peak, t_peak=float(t[index]),
                           t_first=float(t[over[0]]), t_last=float(t[over[-1]]),
                           excess=abs(peak) - limit)


def check_limits(command, limits=None) -> list[LimitExceedance]:
    """What a command asks of the table beyond its limits.

    Parameters
    ----------
    command : TableCommand
        From :func:`displacement_command`.
    limits : TableLimits, optional
        Default :class:`TableLimits()` (assumed Berkeley limits).

    Returns
    -------
    list of LimitExceedance
        One entry per axis and quantity exceeded, in the order horizontal,
        vertical and displacement, velocity, acceleration; empty when the
        table can run the command.
    """
    if not isinstance(command, TableCommand):
        raise ValueError(f"command must be a TableCommand, got {type(command).__name__}")
    if limits is None:
        limits = TableLimits()
    elif not isinstance(limits, TableLimits):
        raise ValueError(f"limits must be TableLimits or None, got {type(limits).__name__}")
    found = []
    for axis in command.axes:
        for quantity in _QUANTITIES:
            entry = _exceedance(command.t, command.quantity(axis, quantity), axis, quantity,
                                limits.limit(axis, quantity))
            if entry is not None:
                found.append(entry)
    return found


# ------------------------------------------------------------------ servo
@dataclass(frozen=True)
class Actuator:
    """Servo-hydraulic actuator as a second-order system with a pure delay.

    Table displacement x over command displacement u::

        X(s) / U(s) = wn^2 / (s^2 + 2 zeta wn s + wn^2) * exp(-s delay),
        wn = 2 pi natural_frequency.

    The defaults are **assumptions** (the report gives no servo data): a
    well-damped loop with its corner well above the 2 Hz tests and the
    12 Hz pitch.

    Parameters
    ----------
    natural_frequency : float
        Natural frequency of the closed loop [Hz], positive.
    damping : float
        Damping ratio zeta [-], positive.
    delay : float
        Pure time delay [s], zero or positive.
    """

    natural_frequency: float = 25.0
    damping: float = 0.7
    delay: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "natural_frequency",
                           _positive("natural_frequency", self.natural_frequency, " [Hz]"))
        object.__setattr__(self, "damping", _positive("damping", self.damping, " [-]"))
        object.__setattr__(self, "delay", _nonnegative("delay", self.delay, " [s]"))

    @property
    def omega(self) -> float:
        """Natural circular frequency wn [rad/s]."""
        return 2.0 * math.pi * self.natural_frequency

    def transfer(self, frequency) -> np.ndarray:
        """Complex frequency response X/U at ``frequency`` [Hz] (closed form)."""
        s = 2j * np.pi * np.asarray(frequency, dtype=float)
        wn = self.omega
        return wn**2 / (s**2 + 2.0 * self.damping * wn * s + wn**2) * np.exp(-s * self.delay)

    def gain(self, frequency) -> np.ndarray:
        """Amplitude ratio |X/U| at ``frequency`` [Hz] [-]: 1 at 0 Hz, 1/(2 zeta) at wn."""
        return np.abs(self.transfer(frequency))


def _servo_output(actuator: Actuator, t: np.ndarray, command: np.ndarray) -> np.ndarray:
    """Response of the actuator to a piecewise-linear input, from rest."""
    wn = actuator.omega
    system = scipy.signal.lti([wn**2], [1.0, 2.0 * actuator.damping * wn, wn**2])
    _, output, _ = scipy.signal.lsim(system, command, t - t[0])
    if actuator.delay > 0.0:
        output = np.interp(t - actuator.delay, t, output, left=0.0)
    return np.asarray(output, dtype=float)


def achieved(command, actuator=None) -> Motion:
    """Accelerations the table achieves for a displacement command.

    Each axis's displacement command goes through the :class:`Actuator`
    transfer function. The servo is linear and time-invariant and the command
    starts at rest, so the second derivative of the achieved displacement is
    the same transfer function applied to the command's acceleration; that is
    how it is computed (``scipy.signal.lsim``, exact for the piecewise-linear
    acceleration, then the delay as a shift).

    Parameters
    ----------
    command : TableCommand
        From :func:`displacement_command`.
    actuator : Actuator, optional
        The servo model. ``None`` (default) means no actuator model: the
        table does exactly what it is commanded, and the result is the
        command's own acceleration (:meth:`TableCommand.motion`). Pass
        ``Actuator()`` for the assumed 25 Hz, zeta = 0.7 servo.

    Returns
    -------
    Motion
        Achieved table accelerations [m/s^2] at the command's times; vertical
        only if the command has a vertical axis; no rotation.

    Raises
    ------
    ValueError
        ``command`` not a :class:`TableCommand` or ``actuator`` neither an
        :class:`Actuator` nor ``None``.
    """
    if not isinstance(command, TableCommand):
        raise ValueError(f"command must be a TableCommand, got {type(command).__name__}")
    if actuator is not None and not isinstance(actuator, Actuator):
        raise ValueError(f"actuator must be an Actuator or None, got {type(actuator).__name__}")
    name = f"{command.name} (achieved)" if command.name else "achieved"
    if actuator is None:
        return Motion(command.t, command.horizontal_acceleration, command.vertical_acceleration,
                      name=name)
    outputs = {axis: _servo_output(actuator, command.t, command.quantity(axis, "acceleration"))
               for axis in command.axes}
    return Motion(command.t, outputs["horizontal"], outputs.get("vertical"), name=name)


def achieved_displacement(command, actuator=None) -> dict[str, np.ndarray]:
    """Achieved table displacement per axis [m] (the command through the servo).

    Parameters
    ----------
    command : TableCommand
        From :func:`displacement_command`.
    actuator : Actuator, optional
        The servo model; ``None`` (default) means none: the achieved
        displacement is the command itself.

    Returns
    -------
    dict
        Axis name -> achieved displacement [m]. Through an actuator the
        displacement command is interpolated linearly between samples, so
        this is accurate to the sampling of the command (unlike
        :func:`achieved`, which is exact).

    Raises
    ------
    ValueError
        ``command`` not a :class:`TableCommand` or ``actuator`` neither an
        :class:`Actuator` nor ``None``.
    """
    if not isinstance(command, TableCommand):
        raise ValueError(f"command must be a TableCommand, got {type(command).__name__}")
    if actuator is not None and not isinstance(actuator, Actuator):
        raise ValueError(f"actuator must be an Actuator or None, got {type(actuator).__name__}")
    if actuator is None:
        return {axis: np.array(command.quantity(axis, "displacement")) for axis in command.axes}
    return {axis: _servo_output(actuator, command.t, command.quantity(axis, "displacement"))
            for axis in command.axes}


# ------------------------------------------------------------------ pitch
#: Number of random sinusoids in a drift signal, and their frequency band [Hz].
_DRIFT_TERMS = 4
_DRIFT_BAND = (0.02, 0.2)
#: Largest relative drift accepted: keeps the amplitude and frequency positive
#: (the drift signal never exceeds sqrt(2 * _DRIFT_TERMS) = 2.83 in magnitude).
_MAX_DRIFT = 0.25


@dataclass(frozen=True)
class Pitch:
    """Pitching of the table: a rotation about a horizontal axis.

    The report measured a pitch "at approximately 12 Hz" with an angular
    acceleration "between 0.2 to 0.25 radians/sec^2" (Section 3.7 (2)). The
    angular acceleration is modelled as ``A(t) sin(Psi(t))`` with
    ``Psi' = 2 pi f(t)`` (see :func:`pitch_history`).

    Parameters
    ----------
    frequency : float
        Pitch frequency f0 [Hz], positive (report: about 12 Hz).
    amplitude : float
        Amplitude A0 of the angular acceleration [rad/s^2], zero or positive
        (report: 0.2-0.25; default their middle, 0.22).
    phase : float or None
        Phase psi of the angular acceleration at t = 0 [rad]. ``None``: drawn
        uniformly in [0, 2 pi) from ``seed`` (0 when ``seed`` is ``None``).
    seed : int or None
        Seed of ``numpy.random.default_rng`` for the phase (if not given) and
        the drift. Same seed, same pitch.
    frequency_drift : float
        RMS of the relative drift of the frequency [-], 0 to 0.25 (0: none).
    amplitude_drift : float
        RMS of the relative drift of the amplitude [-], 0 to 0.25 (0: none).

    Notes
    -----
    A drift is a sum of 4 sinusoids with frequencies drawn in 0.02-0.2 Hz
    and random phases, scaled to unit RMS and multiplied by the drift given.
    A drift needs a ``seed``.
    """

    frequency: float = 12.0
    amplitude: float = 0.22
    phase: float | None = None
    seed: int | None = None
    frequency_drift: float = 0.0
    amplitude_drift: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "frequency", _positive("frequency", self.frequency, " [Hz]"))
        object.__setattr__(self, "amplitude",
                           _nonnegative("amplitude", self.amplitude, " [rad/s^2]"))
        if self.phase is not None:
            object.__setattr__(self, "phase", _number("phase", self.phase))
        object.__setattr__(self, "seed", _seed("seed", self.seed))
        for key in ("frequency_drift", "amplitude_drift"):
            value = _nonnegative(key, getattr(self, key), " [-]")
            if value > _MAX_DRIFT:
                raise ValueError(f"{key} must be at most {_MAX_DRIFT}, got {value!r}")
            object.__setattr__(self, key, value)
        if self.seed is None and (self.frequency_drift > 0.0 or self.amplitude_drift > 0.0):
            raise ValueError("seed is required when frequency_drift or amplitude_drift is "
                             "non-zero (the drift is random)")

    @property
    def omega(self) -> float:
        """Mean circular frequency 2 pi f0 [rad/s]."""
        return 2.0 * math.pi * self.frequency

    @property
    def angle_amplitude(self) -> float:
        """Amplitude of the pitch angle without drift, A0 / (2 pi f0)^2 [rad]."""
        return self.amplitude / self.omega**2

    def realised_phase(self) -> float:
        """The phase actually used [rad]: ``phase``, or the one drawn from ``seed``."""
        return _realisation(self)[0]


def _realisation(pitch: Pitch):
    """Phase [rad] and the two drift signals' (frequencies [Hz], phases [rad])."""
    rng = np.random.default_rng(0 if pitch.seed is None else pitch.seed)
    drawn_phase = float(rng.uniform(0.0, 2.0 * math.pi))
    if pitch.phase is not None:
        phase = pitch.phase
    else:
        phase = 0.0 if pitch.seed is None else drawn_phase
    drifts = []
    for _ in range(2):  # frequency, then amplitude: always drawn, so independent
        drifts.append((rng.uniform(*_DRIFT_BAND, _DRIFT_TERMS),
                       rng.uniform(0.0, 2.0 * math.pi, _DRIFT_TERMS)))
    return phase, drifts[0], drifts[1]


def _drift_signal(t: np.ndarray, terms):
    """Unit-RMS drift r(t), its integral from 0, and r', r''."""
    frequencies, phases = terms
    scale = 1.0 / math.sqrt(_DRIFT_TERMS / 2.0)
    w = 2.0 * np.pi * frequencies[:, None]
    angle = w * t[None, :] + phases[:, None]
    value = scale * np.sin(angle).sum(axis=0)
    integral = scale * ((np.cos(phases[:, None]) - np.cos(angle)) / w).sum(axis=0)
    first = scale * (w * np.cos(angle)).sum(axis=0)
    second = -scale * (w**2 * np.sin(angle)).sum(axis=0)
    return value, integral, first, second


def pitch_history(pitch, t):
    """Pitch angle, angular velocity and angular acceleration of the table.

    The angle is the primary quantity, and the three histories are exact
    derivatives of one another::

        phi(t) = -a(t) sin(Psi(t)),   a = A(t) / Omega(t)^2,
        Psi(t) = psi + 2 pi f0 (t + df * integral_0^t r_f),  Omega = Psi',
        A(t) = A0 (1 + dA r_A(t)),

    so ``phi'' = A sin(Psi) - a'' sin(Psi) - (2 a' Omega + a Omega') cos(Psi)``.
    Without drift this is exactly ``phi'' = A0 sin(2 pi f0 t + psi)`` and
    ``phi = -phi'' / (2 pi f0)^2``; with drift the extra terms are of relative
    size (drift frequency / pitch frequency) x drift, below 0.2 / 12 x 0.25 ~ 4e-3.

    Parameters
    ----------
    pitch : Pitch
    t : array_like
        Times [s].

    Returns
    -------
    angle : ndarray
        phi [rad], positive in the sense of positive theta.
    angular_velocity : ndarray
        phi' [rad/s].
    angular_acceleration : ndarray
        phi'' [rad/s^2].
    """
    if not isinstance(pitch, Pitch):
        raise ValueError(f"pitch must be a Pitch, got {type(pitch).__name__}")
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or not np.all(np.isfinite(t)):
        raise ValueError("t must be a one-dimensional array of finite times [s]")
    phase, frequency_terms, amplitude_terms = _realisation(pitch)
    r_f, r_f_integral, r_f_1, r_f_2 = _drift_signal(t, frequency_terms)
    r_a, _, r_a_1, r_a_2 = _drift_signal(t, amplitude_terms)
    w0, df, da, a0 = pitch.omega, pitch.frequency_drift, pitch.amplitude_drift, pitch.amplitude

    psi = phase + w0 * (t + df * r_f_integral)
    omega, omega_1, omega_2 = w0 * (1.0 + df * r_f), w0 * df * r_f_1, w0 * df * r_f_2
    amp, amp_1, amp_2 = a0 * (1.0 + da * r_a), a0 * da * r_a_1, a0 * da * r_a_2
    a = amp / omega**2
    a_1 = amp_1 / omega**2 - 2.0 * amp * omega_1 / omega**3
    a_2 = (amp_2 / omega**2 - 4.0 * amp_1 * omega_1 / omega**3
           - 2.0 * amp * omega_2 / omega**3 + 6.0 * amp * omega_1**2 / omega**4)
    sine, cosine = np.sin(psi), np.cos(psi)
    angle = -a * sine
    angular_velocity = -a_1 * sine - a * omega * cosine
    angular_acceleration = (a * omega**2 - a_2) * sine - (2.0 * a_1 * omega + a * omega_1) * cosine
    return angle, angular_velocity, angular_acceleration


# ------------------------------------------------------------------ at the block
def motion_at_block(table_motion, *, pitch=None, block_position=0.0,
                    axis_depth=0.0) -> Motion:
    """The motion a block feels on a table that translates and pitches.

    Derivation (also in ``docs/table.md``). The table translates with the
    accelerations of ``table_motion`` (those of its pitch axis, in the fixed
    frame) and rotates by phi(t) about a horizontal axis, phi in the same
    sense as theta: phi > 0 lowers the table's -x side (counterclockwise with
    +x to the right and up up). theta is measured relative to the table, so
    the block's absolute rotation is theta + phi. Take moments about the
    pivot corner P, which moves with the table while the block rocks:
    ``I0 (theta'' + phi'') = M_P(gravity) - M_P(m a_P)``, written in the
    table's axes (x along the table, y normal to it):

    (a) Gravity, (0, -g) in the fixed frame, has components
        (-g sin(phi), -g cos(phi)) in the table's axes: a pull toward -x for
        phi > 0, downhill. That is exactly the inertial force per mass of an
        extra horizontal ground acceleration +g sin(phi) (a positive ``u``
        pushes the block toward -x and drives theta positive,
        ``docs/conventions.md``), so tilt adds ``g sin(phi)`` to the
        horizontal and positive phi drives theta positive, as a positive
        horizontal acceleration does. (g cos(phi) = g to 1e-9.)
    (b) A table point at (x, d) from the pitch axis (x along the table,
        d = ``axis_depth`` above the axis) has the rigid-body acceleration
        ``a_axis + phi'' k x r - phi'^2 r``, i.e. tangential components
        (-d phi'', x phi''): ``-axis_depth phi''`` is added to the horizontal
        and ``block_position phi''`` to the vertical.
    (c) Dividing by I0 = 4R^2/3 gives theta'' = (Eq. 2-13 with the
        accelerations of (a), (b)) / I0 - phi''. The ``-phi''`` is the
        inertia of the base rotation; it is the ``rotation`` channel of
        :class:`Motion`, which the engine subtracts.

    At theta = 0, rocking onto the corner of side s (+1: the corner at -x)
    starts when
    ``s (u + g phi - d phi'') h > (g + v + x phi'') b + s I0 phi''``: the
    rotational term I0 phi'' dominates (for a 30 x 6 in block at 12 Hz it is
    300 times the tilt term g phi h).

    Neglected (all below 3e-4 m/s^2 = 3e-5 g for the report's pitch, 0.25
    rad/s^2 at 12 Hz, and table accelerations up to 1 g): the rotation of the
    table's own accelerations into its tilted axes (``v sin(phi)`` in the
    horizontal, ``-u sin(phi)`` in the vertical), ``g (1 - cos(phi))``, and
    the centripetal terms ``-phi'^2 r``. ``g sin(phi)`` itself (3.8e-4 m/s^2)
    is of the same order; it is kept because it is the tilt term. The
    vertical acceleration is taken at ``block_position``; the pivot corners
    are +-b from it (use ``block_position -+ b`` for the exact value on one
    side).

    Do not apply this to accelerations *measured on the table*: an
    accelerometer fixed to a tilting table already reads ``g sin(phi)`` and
    the tangential terms at its own location.

    Parameters
    ----------
    table_motion : Motion
        Translation of the table (its pitch axis) [m/s^2]; typically
        :func:`achieved`. Its own ``rotation``, if any, is replaced.
    pitch : Pitch, optional
        The pitching; ``None`` returns ``table_motion`` unchanged.
    block_position : float, optional
        Horizontal distance x of the block's centre from the pitch axis [m],
        positive along +x.
    axis_depth : float, optional
        Height d of the table surface above the pitch axis [m] (negative if
        the axis is above the surface).

    Returns
    -------
    Motion
        ``horizontal = u + g sin(phi) - d phi''``,
        ``vertical = v + x phi''`` (``None`` if ``table_motion`` has no
        vertical and x = 0), ``rotation = phi''``; ``None`` rotation without
        pitch.
    """
    table_motion = _motion("table_motion", table_motion)
    block_position = _number("block_position", block_position)
    axis_depth = _number("axis_depth", axis_depth)
    if pitch is None:
        return table_motion
    if not isinstance(pitch, Pitch):
        raise ValueError(f"pitch must be a Pitch or None, got {type(pitch).__name__}")
    angle, _, angular_acceleration = pitch_history(pitch, table_motion.t)
    horizontal = (table_motion.horizontal + G * np.sin(angle)
                  - axis_depth * angular_acceleration)
    vertical = table_motion.vertical
    if block_position != 0.0:
        vertical = table_motion.vertical_or_zero + block_position * angular_acceleration
    name = f"{table_motion.name} + pitch" if table_motion.name else "pitch"
    return Motion(table_motion.t, horizontal, vertical, name=name,
                  rotation=angular_acceleration)
