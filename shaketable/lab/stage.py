"""The table stage of a virtual test: command, servo and pitch between the record and the block.

A scene's ``[table]`` section names what the table does to the motion the
experimenter asked for (the *commanded* accelerations):

1. ``command``: the displacement command the controller needed
   (:func:`shaketable.lab.command.displacement_command`), checked against the
   table's limits (:func:`shaketable.lab.limits.check_limits`);
2. ``actuator``: the command through a second-order servo
   (:func:`shaketable.lab.servo.achieved`);
3. ``pitch``: the 12 Hz pitching of the table (Section 3.7 (2)) folded into
   the motion the block feels (:func:`shaketable.lab.pitch.motion_at_block`).

Whatever the section does not name is not run (no command, no servo, no
pitch). Without any ``[table]`` section the block feels the commanded motion
exactly, as in the report's theory runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, NoReturn

import numpy as np

from shaketable.core.motion import Motion
from shaketable.core.units import parse
from shaketable.core.validation import check_keys, unknown_keys
from shaketable.lab.command import TableCommand, displacement_command
from shaketable.lab.limits import LimitExceedance, TableLimits, check_limits
from shaketable.lab.pitch import Pitch, motion_at_block
from shaketable.lab.servo import Actuator, achieved

#: Samples per pitch cycle when the motion is resampled for a pitching table
#: (linear interpolation of a sine at 20 samples per cycle: 1.2 % peak error).
SAMPLES_PER_PITCH_CYCLE = 20


@dataclass(frozen=True)
class TableSetup:
    """What the table does between the commanded motion and the block.

    Parameters
    ----------
    command : bool
        Derive the displacement command (zero-phase high-pass at ``highpass``,
        double integration, baseline) and check it against ``limits``. The
        block then feels the command's accelerations (or the servo's).
    highpass : float
        Corner of the command's high-pass filter [Hz].
    limits : TableLimits
        The table's stroke, velocity and acceleration limits (assumed values
        for the Berkeley table, see :class:`shaketable.lab.limits.TableLimits`).
    actuator : Actuator or None
        Servo between command and table; needs ``command``.
    pitch : Pitch or None
        The table's pitching (about 12 Hz, 0.2-0.25 rad/s^2, Section 3.7 (2)).
    block_position : float
        Distance of the block's centre from the pitch axis along +x [m].
    axis_depth : float
        Height of the table surface above the pitch axis [m].
    """

    command: bool = False
    highpass: float = 0.1
    limits: TableLimits = field(default_factory=TableLimits)
    actuator: Actuator | None = None
    pitch: Pitch | None = None
    block_position: float = 0.0
    axis_depth: float = 0.0

    def __post_init__(self) -> None:
        if self.actuator is not None and not self.command:
            raise ValueError("table.actuator needs table.command = true (the servo follows "
                             "a displacement command)")
        if not (isinstance(self.highpass, (int, float)) and math.isfinite(self.highpass)
                and self.highpass > 0):
            raise ValueError(f"table.highpass must be a positive frequency [Hz], got "
                             f"{self.highpass!r}")

    @property
    def empty(self) -> bool:
        """True when the table does nothing to the motion."""
        return not self.command and self.pitch is None

    def with_pitch_phase(self, phase: float) -> "TableSetup":
        """The same table with the pitch's phase set to ``phase`` [rad]."""
        if self.pitch is None:
            raise ValueError("with_pitch_phase: this table does not pitch")
        return replace(self, pitch=replace(self.pitch, phase=float(phase)))


@dataclass(frozen=True)
class TableRun:
    """The table stage's output.

    Attributes
    ----------
    commanded : Motion or None
        The accelerations asked for [m/s^2] (``None``: a table at rest).
    command : TableCommand or None
        The displacement command, when derived.
    exceedances : tuple of LimitExceedance
        What the command asks beyond the table's limits (empty: it can run).
    felt : Motion or None
        The accelerations the block feels [m/s^2], with the pitch's angular
        acceleration in ``rotation``; ``None`` only for free rocking on a table
        at rest without pitch.
    """

    commanded: Motion | None
    command: TableCommand | None
    exceedances: tuple
    felt: Motion | None

    def warnings(self) -> list[str]:
        """One line per limit exceeded."""
        return [str(entry) for entry in self.exceedances]


def pitch_sampled(motion: Motion, pitch: Pitch) -> Motion:
    """``motion`` on a grid fine enough for the pitch (>= 20 samples per pitch cycle).

    The motion is linear between its samples (Section 2.8), so subdividing
    each interval leaves it unchanged; only the pitch added later is sampled
    finer.
    """
    dt = float(np.max(np.diff(motion.t)))
    subdivisions = max(1, math.ceil(dt * pitch.frequency * SAMPLES_PER_PITCH_CYCLE - 1e-9))
    return motion if subdivisions == 1 else motion.subdivided(subdivisions)


def run_table(motion: Motion | None, setup: TableSetup | None, *,
              duration: float | None = None) -> TableRun:
    """The motion the block feels on the table ``setup`` for the commanded ``motion``.

    Parameters
    ----------
    motion : Motion or None
        Commanded accelerations [m/s^2]; ``None``: the table is not driven
        (free rocking), it may still pitch.
    setup : TableSetup or None
        ``None`` or an empty setup returns the motion unchanged.
    duration : float, optional
        Length of a table at rest [s] (needed when ``motion`` is ``None`` and
        the table pitches).
    """
    if setup is None or setup.empty:
        return TableRun(motion, None, (), motion)
    command = None
    exceedances: tuple[LimitExceedance, ...] = ()
    table_motion = motion
    if motion is None:
        if setup.command:
            raise ValueError("table.command needs a table motion ([motion] kind 'free' has "
                             "none)")
        if duration is None:
            raise ValueError("a pitching table at rest needs rocking.duration")
        # not empty and no command: the table pitches
        assert setup.pitch is not None
        table_motion = Motion.at_rest(duration, dt=1.0 / (setup.pitch.frequency
                                                          * SAMPLES_PER_PITCH_CYCLE))
    elif setup.command:
        command = displacement_command(motion, highpass=setup.highpass)
        exceedances = tuple(check_limits(command, setup.limits))
        if setup.actuator is not None:
            achieved_motion = achieved(command, setup.actuator)
        else:
            achieved_motion = command.motion()
        table_motion = Motion(achieved_motion.t, achieved_motion.horizontal,
                              achieved_motion.vertical, name=motion.name)
    if setup.pitch is not None:
        # a commanded motion, or a table at rest for the pitch (above)
        assert table_motion is not None
        table_motion = motion_at_block(pitch_sampled(table_motion, setup.pitch),
                                       pitch=setup.pitch, block_position=setup.block_position,
                                       axis_depth=setup.axis_depth)
    return TableRun(motion, command, exceedances, table_motion)


# --------------------------------------------------------------------------- scene section
_TABLE_KEYS = {"command", "highpass", "limits", "actuator", "pitch", "block_position",
               "axis_depth"}

_LIMIT_UNITS = {"stroke": "length", "velocity": "velocity", "acceleration": "acceleration"}

#: Keys of ``[table.pitch]`` and ``[table.actuator]`` -> what each holds: a quantity kind
#: of :func:`shaketable.core.units.parse` (written with its unit), a plain ``"number"``
#: or an ``"integer"``.
_PITCH_KEYS = {"frequency": "frequency", "amplitude": "angular acceleration", "phase": "angle",
               "seed": "integer", "frequency_drift": "number", "amplitude_drift": "number"}

_ACTUATOR_KEYS = {"natural_frequency": "frequency", "delay": "time", "damping": "number"}


def table_setup_from_dict(spec: dict, where: str = "<scene>") -> TableSetup:
    """Validate a scene's ``[table]`` section (values with units) into a :class:`TableSetup`.

    Keys: ``command`` (true/false), ``highpass = "0.1 Hz"``,
    ``block_position = "0 in"``, ``axis_depth = "0 in"``, and the tables
    ``[table.limits]`` (``horizontal_stroke = "5 in"``,
    ``horizontal_velocity = "25 in/s"``, ``horizontal_acceleration = "1.5 g"``
    and the same for ``vertical_``), ``[table.actuator]``
    (``natural_frequency = "25 Hz"``, ``damping = 0.7``, ``delay = "0 s"``; or
    ``actuator = true`` for the defaults) and ``[table.pitch]``
    (``frequency = "12 Hz"``, ``amplitude = "0.22 rad/s2"``, ``phase = "0 rad"``
    or ``seed = 3``, ``frequency_drift``, ``amplitude_drift``; or
    ``pitch = true`` for the defaults).

    Raises
    ------
    ValueError
        Naming the file and the key.
    """
    def fail(key: str, message: str) -> NoReturn:
        raise ValueError(f"{where}: table.{key}: {message}")

    if not isinstance(spec, dict):
        raise ValueError(f"{where}: [table] must be a table")
    check_keys(spec, _TABLE_KEYS, where, "[table]")
    options: dict[str, Any] = {}
    command = spec.get("command", "actuator" in spec and spec["actuator"] is not False)
    if not isinstance(command, bool):
        fail("command", f"must be true or false, got {command!r}")
    options["command"] = command
    if "highpass" in spec:
        options["highpass"] = parse(spec["highpass"], "frequency", where=f"{where}: table.highpass")
    for key in ("block_position", "axis_depth"):
        if key in spec:
            options[key] = parse(spec[key], "length", where=f"{where}: table.{key}")
    if "limits" in spec:
        limits = spec["limits"]
        if not isinstance(limits, dict):
            fail("limits", "must be a table such as { horizontal_stroke = '5 in' }")
        values: dict[str, Any] = {}
        for key, value in limits.items():
            axis, _, quantity = key.partition("_")
            if axis not in ("horizontal", "vertical") or quantity not in _LIMIT_UNITS:
                fail(f"limits.{key}", "unknown limit; expected horizontal_ or vertical_ "
                     "followed by stroke, velocity or acceleration")
            values[key] = parse(value, _LIMIT_UNITS[quantity], where=f"{where}: table.limits.{key}")
        options["limits"] = TableLimits(**values)
    for name, kind, keys in (("actuator", Actuator, _ACTUATOR_KEYS),
                             ("pitch", Pitch, _PITCH_KEYS)):
        if name in spec:
            part = _part_of_table(spec[name], name, kind, keys, where)
            if part is not None:
                options[name] = part
    try:
        return TableSetup(**options)
    except ValueError as error:
        raise ValueError(f"{where}: [table]: {error}") from None


def _part_of_table(value: Any, name: str, kind: type, keys: dict[str, str],
                   where: str) -> Any:
    """A ``[table.actuator]`` or ``[table.pitch]`` entry: ``true`` (the defaults of
    ``kind``), ``false`` (``None``: absent) or a table of ``keys``, each parsed as
    ``keys`` says; errors name the file and the key."""
    if value is False:
        return None
    if value is True:
        return kind()
    if not isinstance(value, dict):
        raise ValueError(f"{where}: table.{name}: must be true, false or a table, got {value!r}")
    unknown = unknown_keys(value, keys)
    if unknown:
        raise ValueError(f"{where}: table.{name}.{unknown[0]}: unknown key; expected one of "
                         f"{', '.join(sorted(keys))}")
    values: dict[str, Any] = {}
    for key, given in value.items():
        what = keys[key]
        if what == "number":
            values[key] = _plain_number(given, where, f"{name}.{key}")
        elif what == "integer":
            if isinstance(given, bool) or not isinstance(given, int):
                raise ValueError(f"{where}: table.{name}.{key}: must be an integer, got "
                                 f"{given!r}")
            values[key] = given
        else:
            values[key] = parse(given, what, where=f"{where}: table.{name}.{key}")
    try:
        return kind(**values)
    except ValueError as error:
        raise ValueError(f"{where}: table.{name}: {error}") from None


def _plain_number(value: Any, where: str, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{where}: table.{key} must be a plain number, got {value!r}")
    return float(value)
