"""Quantities written with their unit, as scenes and the CLI accept them.

``parse("0.5 g", "acceleration")`` -> 4.903325 [m/s^2]. A dimensional quantity
must carry its unit (a bare number is refused); a dimensionless one must not.
"""

from __future__ import annotations

import math
import re

from shaketable.core.constants import ACCELERATION_UNITS, LENGTH_UNITS

_NUMBER_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")

#: Units accepted for each kind of quantity, name -> factor to SI.
UNITS = {
    "length": LENGTH_UNITS,
    "acceleration": ACCELERATION_UNITS,
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0},
    "frequency": {"hz": 1.0},
    "velocity": {"m/s": 1.0, "cm/s": 0.01, "in/s": LENGTH_UNITS["in"], "ft/s": LENGTH_UNITS["ft"]},
    "force": {"n": 1.0, "lbf": 4.4482216152605, "ozf": 4.4482216152605 / 16.0,
              "oz": 4.4482216152605 / 16.0},
    "angle": {"rad": 1.0, "deg": math.pi / 180.0},
    "angular acceleration": {"rad/s2": 1.0, "rad/s^2": 1.0},
    "angular frequency": {"rad/s": 1.0, "1/s": 1.0},
    "stiffness": {"w/m": 1.0, "w/in": 1.0 / LENGTH_UNITS["in"], "w/ft": 1.0 / LENGTH_UNITS["ft"]},
    "weight": {"w": 1.0},
    "mass": {"kg": 1.0, "t": 1000.0, "lb": 0.45359237},
    "density": {"kg/m3": 1.0, "kg/m^3": 1.0, "t/m3": 1000.0, "t/m^3": 1000.0},
}


def parse(value, kind: str, *, where: str = "value") -> float:
    """A quantity of ``kind`` in SI units.

    Parameters
    ----------
    value : str or float
        ``"30 in"``, ``"0.5 g"``, ``"2 Hz"``... Numbers are accepted only for
        a quantity whose SI value is given in SI units explicitly, i.e. never
        for a dimensional kind.
    kind : str
        A key of :data:`UNITS`.
    where : str
        What to name in an error message (e.g. ``"scene.toml: motion.frequency"``).

    Raises
    ------
    ValueError
        A missing or unknown unit, or text that is not a number with a unit.
    """
    units = UNITS[kind]
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise ValueError(f"{where}: expected a {kind} with its unit such as "
                         f"'{_example(kind)}', got {value!r}")
    if isinstance(value, (int, float)):
        raise ValueError(f"{where}: {value!r} has no unit; write the {kind} with its unit, "
                         f"e.g. '{_example(kind)}' (units: {', '.join(sorted(units))})")
    match = _NUMBER_UNIT.match(value)
    if match and not match.group(2):
        raise ValueError(f"{where}: {value!r} has no unit; write the {kind} with its unit, "
                         f"e.g. '{_example(kind)}' (units: {', '.join(sorted(units))})")
    if not match:
        raise ValueError(f"{where}: {value!r} is not a number with a unit; write e.g. "
                         f"'{_example(kind)}' (units: {', '.join(sorted(units))})")
    number, unit = float(match.group(1)), match.group(2).replace(" ", "").lower()
    if unit not in units:
        raise ValueError(f"{where}: unknown {kind} unit {match.group(2)!r}; expected one of "
                         f"{', '.join(sorted(units))}")
    return number * units[unit]


def parse_angle_or_ratio(value, alpha: float, *, where: str = "value") -> float:
    """An angle [rad] written in rad, deg or as a multiple of alpha (``"0.5 alpha"``); a
    bare zero is zero in every unit and needs none."""
    if isinstance(value, str) and value.strip().lower().endswith("alpha"):
        text = value.strip()[:-5].strip() or "1"
        try:
            return float(text) * alpha
        except ValueError:
            raise ValueError(f"{where}: {value!r} is not a multiple of alpha such as "
                             "'0.5 alpha'") from None
    if _is_zero(value):
        return 0.0
    try:
        return parse(value, "angle", where=where)
    except ValueError as error:
        raise ValueError(f"{error}, or as a multiple of the block's alpha, e.g. "
                         "'0.5 alpha'") from None


def _is_zero(value) -> bool:
    """Whether ``value`` is a bare zero (``0``, ``0.0``, ``"0"``), not a bool."""
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        return False
    try:
        return float(str(value).strip()) == 0.0
    except ValueError:
        return False


def _example(kind: str) -> str:
    return {"length": "30 in", "acceleration": "0.5 g", "time": "8 s", "frequency": "2 Hz",
            "velocity": "25 in/s", "force": "20 oz", "angle": "0.05 rad",
            "angular frequency": "2 rad/s", "angular acceleration": "0.22 rad/s2",
            "stiffness": "0.4 W/in", "weight": "0.4 W", "mass": "400 kg",
            "density": "2400 kg/m3"}[kind]


#: The smaller unit in which a length under one of the user's unit is shown.
_SMALLER_LENGTH = {"m": "mm", "ft": "in"}


def display_length_unit(value: float, unit: str) -> str:
    """The unit in which :func:`format_length` shows a length of ``value`` [m] for a user
    who writes lengths in ``unit``: ``unit``, or the next smaller one (m -> mm,
    ft -> in) for a length under one ``unit``."""
    if unit not in LENGTH_UNITS:
        raise ValueError(f"unit must be one of {', '.join(LENGTH_UNITS)}, got {unit!r}")
    if math.isfinite(value) and abs(value) < LENGTH_UNITS[unit] and unit in _SMALLER_LENGTH:
        return _SMALLER_LENGTH[unit]
    return unit


def shared_length_unit(values, unit: str) -> str:
    """The one unit in which the lengths ``values`` [m] of one output are shown for a user
    who writes lengths in ``unit``: the smallest :func:`display_length_unit` of the
    finite, non-zero ones (``unit`` when there is none), so that a slip of 1.79 in and a
    corner excursion of 30.4 in of a block given in feet read in one unit."""
    shown = {display_length_unit(float(value), unit) for value in values
             if math.isfinite(value) and value != 0.0}
    return min(shown, key=LENGTH_UNITS.__getitem__) if shown else unit


def format_length(value: float, unit: str, *, digits: int = 3, signed: bool = False) -> str:
    """A length [m] in the user's length ``unit``, with its unit: ``"225 mm"``.

    Lengths under one of ``unit`` are shown in the next smaller unit when there is one
    (m -> mm, ft -> in), so that a slip of 0.1 mm of a block given in metres does not
    read ``0.000104 m``; NaN reads ``"n/a"``.

    Parameters
    ----------
    value : float
        Length [m].
    unit : str
        The user's unit, one of ``m, cm, mm, in, ft``.
    digits : int
        Significant digits.
    signed : bool
        Write a + before positive values.
    """
    if not math.isfinite(value):
        return "n/a"
    unit = display_length_unit(value, unit)
    factor = LENGTH_UNITS[unit]
    # significant zeros kept (8.30 in), no bare trailing point (225 mm)
    number = f"{value / factor:{'+' if signed else ''}#.{digits}g}".replace(".e", "e")
    number = number[:-1] if number.endswith(".") else number
    return f"{number} {unit}"

