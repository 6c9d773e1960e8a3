"""The actuator: what the table achieves for a commanded displacement (servo dynamics)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import scipy.signal

from shaketable.core.motion import Motion
from shaketable.core.validation import nonnegative as _nonnegative
from shaketable.core.validation import positive as _positive
from shaketable.lab.command import TableCommand


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

    def __post_init__(self) -> None:
        object.__setattr__(self, "natural_frequency",
                           _positive("natural_frequency", self.natural_frequency, " [Hz]"))
        object.__setattr__(self, "damping", _positive("damping", self.damping, " [-]"))
        object.__setattr__(self, "delay", _nonnegative("delay", self.delay, " [s]"))

    @property
    def omega(self) -> float:
        """Natural circular frequency wn [rad/s]."""
        return 2.0 * math.pi * self.natural_frequency

    def transfer(self, frequency: npt.ArrayLike) -> np.ndarray:
        """Complex frequency response X/U at ``frequency`` [Hz] (closed form)."""
        s = 2j * np.pi * np.asarray(frequency, dtype=float)
        wn = self.omega
        return wn**2 / (s**2 + 2.0 * self.damping * wn * s + wn**2) * np.exp(-s * self.delay)

    def gain(self, frequency: npt.ArrayLike) -> np.ndarray:
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


def _axis_history(command: TableCommand, axis: str, quantity: str) -> np.ndarray:
    """One history [SI] of an axis the command has (``axis`` from ``command.axes``)."""
    history = command.quantity(axis, quantity)
    assert history is not None, f"{axis} is one of the command's axes"
    return history


def achieved(command: TableCommand, actuator: Actuator | None = None) -> Motion:
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
    outputs = {axis: _servo_output(actuator, command.t, _axis_history(command, axis, "acceleration"))
               for axis in command.axes}
    return Motion(command.t, outputs["horizontal"], outputs.get("vertical"), name=name)


def achieved_displacement(command: TableCommand,
                          actuator: Actuator | None = None) -> dict[str, np.ndarray]:
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
    return {axis: _servo_output(actuator, command.t, _axis_history(command, axis, "displacement"))
            for axis in command.axes}
