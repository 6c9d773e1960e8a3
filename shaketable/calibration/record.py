"""A measured free-rocking record (:class:`FreeRockingRecord`): reading CSV or text files
with units, and the options the calibration accepts.
"""

from __future__ import annotations

import math
import numbers
import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import numpy.typing as npt

from shaketable.core.constants import LENGTH_UNITS
from shaketable.core.equality import fields_equal
from shaketable.core.geometry import Block
from shaketable.lab.sensors import (
    Measurement,
    theta_from_top_displacement,
    top_displacement,
)

#: What a record can hold.
QUANTITIES = ("angle", "top displacement")

#: Angle units accepted at the edges, name -> radians.
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0, "mrad": 1e-3}


class CalibrationError(ValueError):
    """A record that cannot give a COR: no rocking, too short, clipped, too noisy."""


@dataclass(frozen=True)
class FreeRockingRecord:
    """A free-rocking record: times and one measured quantity.

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing (uniform sampling is not
        required, but the interval uses the median step).
    values : array_like
        The angle [rad] or the top displacement relative to the table [m],
        positive along +x (``docs/conventions.md``: negative for theta > 0).
    quantity : str
        ``"angle"`` or ``"top displacement"``.
    height : float, optional
        Height of the potentiometer wire above the rocking edges [m]
        (default: the block's height), only for a top displacement.
    clipped : array_like of bool, optional
        Per-sample clipping flags, if the acquisition gives them.
    name : str
        Label.
    display_unit : str, optional
        Length unit the figures and the CSV show a top displacement in (the record
        file's own unit when it was read from a file); None: inches, as the report.
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    t: np.ndarray
    values: np.ndarray
    quantity: str = "angle"
    height: float | None = None
    clipped: np.ndarray | None = None
    name: str = ""
    display_unit: str | None = None

    def __post_init__(self) -> None:
        if self.display_unit is not None and self.display_unit not in LENGTH_UNITS:
            raise ValueError(f"display_unit must be one of {', '.join(LENGTH_UNITS)} or None, "
                             f"got {self.display_unit!r}")
        if self.quantity not in QUANTITIES:
            raise ValueError(f"quantity must be one of {QUANTITIES}, got {self.quantity!r}")
        t = np.array(self.t, dtype=float)
        values = np.array(self.values, dtype=float)
        if t.ndim != 1 or values.ndim != 1 or t.size != values.size:
            raise ValueError(f"t and values must be one-dimensional and of equal length, got "
                             f"shapes {t.shape} and {values.shape}")
        for name, array in (("t", t), ("values", values)):
            bad = np.flatnonzero(~np.isfinite(array))
            if bad.size:
                raise ValueError(f"{name} contains non-finite values, first at index {bad[0]}")
        if t.size > 1 and np.any(np.diff(t) <= 0):
            index = int(np.flatnonzero(np.diff(t) <= 0)[0])
            raise ValueError(f"t must be strictly increasing; t[{index + 1}] <= t[{index}]")
        if self.height is not None:
            height = float(self.height)
            if not (math.isfinite(height) and height > 0):
                raise ValueError(f"height must be a positive length [m], got {self.height!r}")
            object.__setattr__(self, "height", height)
        for key, array in (("t", t), ("values", values)):
            array.setflags(write=False)
            object.__setattr__(self, key, array)
        if self.clipped is not None:
            clipped = np.array(self.clipped, dtype=bool)
            if clipped.shape != t.shape:
                raise ValueError("clipped must have one flag per sample")
            clipped.setflags(write=False)
            object.__setattr__(self, "clipped", clipped)

    # ------------------------------------------------------------ builders
    @classmethod
    def from_angle(cls, t: npt.ArrayLike, theta: npt.ArrayLike, *, units: str = "rad",
                   name: str = "") -> FreeRockingRecord:
        """FreeRockingRecord of the angle, in ``units`` (rad, deg, mrad)."""
        factor = _unit_factor(units, ANGLE_UNITS, "units")
        return cls(np.asarray(t, dtype=float), np.asarray(theta, dtype=float) * factor, "angle",
                   name=name)

    @classmethod
    def from_top_displacement(cls, t: npt.ArrayLike, displacement: npt.ArrayLike, *,
                              height: float | None = None, units: str = "m",
                              name: str = "") -> FreeRockingRecord:
        """FreeRockingRecord of the top displacement in ``units`` (m, cm, mm, in, ft); ``height`` [m]."""
        factor = _unit_factor(units, LENGTH_UNITS, "units")
        return cls(np.asarray(t, dtype=float), np.asarray(displacement, dtype=float) * factor,
                   "top displacement",
                   height=height, name=name)

    @classmethod
    def from_measurement(cls, measurement: Measurement,
                         quantity: str = "top displacement") -> FreeRockingRecord:
        """The potentiometer channel of a :class:`~shaketable.lab.sensors.Measurement`.

        ``quantity="angle"`` takes the report's angle (top displacement / height).
        """
        if not isinstance(measurement, Measurement):
            raise ValueError(f"measurement must be a Measurement, got "
                             f"{type(measurement).__name__}")
        top_displacement, theta = measurement.top_displacement, measurement.theta
        if top_displacement is None or theta is None:
            raise ValueError("the measurement has no potentiometer channel")
        values = top_displacement if quantity == "top displacement" else theta
        return cls(measurement.t, values, quantity, height=measurement.block.height
                   if quantity == "top displacement" else None,
                   clipped=measurement.top_clipped, name=measurement.name)

    # ------------------------------------------------------------ queries
    @property
    def dt(self) -> float:
        """Median sample interval [s]."""
        return float(np.median(np.diff(self.t)))

    @property
    def rate(self) -> float:
        """Samples per second [1/s] (1 / median interval)."""
        return 1.0 / self.dt

    @property
    def duration(self) -> float:
        """Length of the record [s]."""
        return float(self.t[-1] - self.t[0])

    def display_scale(self) -> tuple[float, str]:
        """Factor and unit for plots: rad for angles; for displacements the record file's
        unit (:attr:`display_unit`), else in."""
        if self.quantity == "angle":
            return 1.0, "rad"
        unit = self.display_unit or "in"
        return 1.0 / LENGTH_UNITS[unit], unit

    def to_quantity(self, theta: npt.ArrayLike, block: Block) -> np.ndarray:
        """The record's quantity for rotations ``theta`` [rad] (no offset)."""
        if self.quantity == "angle":
            return np.asarray(theta, dtype=float)
        height = self.height if self.height is not None else block.height
        return top_displacement(theta, _wire_block(block, height))

    def to_angle(self, values: npt.ArrayLike, block: Block) -> np.ndarray:
        """Rotation [rad] of quantity ``values`` (exact inversion for displacements)."""
        if self.quantity == "angle":
            return np.asarray(values, dtype=float)
        height = self.height if self.height is not None else block.height
        return theta_from_top_displacement(values, _wire_block(block, height))


def _wire_block(block: Block, height: float) -> Block:
    return block if height == block.height else Block(height, block.width)


def _unit_factor(unit: str, table: dict[str, float], name: str) -> float:
    key = str(unit).strip().lower()
    if key not in table:
        raise ValueError(f"{name}: unknown unit {unit!r}; expected one of {sorted(table)}")
    return table[key]


def _unit_in_name(name: str) -> str | None:
    """The unit in brackets or parentheses at the end of a column name, e.g. ``theta [deg]``."""
    stripped = name.strip()
    for opening, closing in (("[", "]"), ("(", ")")):
        if stripped.endswith(closing) and opening in stripped:
            return stripped[stripped.rindex(opening) + 1:-1].strip()
    return None


#: Time units accepted in a time column's header, name -> seconds.
TIME_UNITS = {"s": 1.0, "sec": 1.0, "secs": 1.0, "second": 1.0, "seconds": 1.0,
              "ms": 1e-3, "msec": 1e-3, "us": 1e-6, "µs": 1e-6, "μs": 1e-6, "usec": 1e-6,
              "min": 60.0}

#: Names of a time column (any language a lab exports in), before the unit.
TIME_NAMES = ("time", "t", "zeit", "temps", "tiempo", "tempo", "tid", "czas", "tijd")


def _base_name(name: str) -> str:
    """A column name without its unit in brackets or parentheses, lower case."""
    stripped = name.strip()
    unit = _unit_in_name(stripped)
    if unit is not None:
        closing = stripped[-1]
        opening = "[" if closing == "]" else "("
        stripped = stripped[:stripped.rindex(opening)]
    return stripped.strip().lower()


def _is_time_name(name: str) -> bool:
    """``time``, ``Time (ms)``, ``Zeit [s]``, ``t [us]``, ``time_s``...: a time column."""
    base = _base_name(name)
    unit = _unit_in_name(name)
    if base in TIME_NAMES or base.startswith("time"):
        return True
    return bool(unit is not None and unit.strip().lower() in TIME_UNITS
                and base.split(" ")[0].split("_")[0] in TIME_NAMES)


def time_factor(path: Path | str, name: str) -> float:
    """Seconds per unit of the time column ``name`` (``time [ms]`` -> 1e-3; no unit -> 1).

    Raises
    ------
    ValueError
        A unit in the name that is not a time unit (naming the file and column).
    """
    unit = _unit_in_name(name)
    if unit is None:
        return 1.0
    key = unit.strip().lower()
    if key not in TIME_UNITS:
        raise ValueError(f"{path}: time column {name!r} is in {unit!r}, not a time unit; "
                         f"expected one of {sorted(set(TIME_UNITS))}")
    return TIME_UNITS[key]


def _checked_units(path: Path, column: str, units: str | None) -> str:
    """The column's unit: ``units`` (``--units``) or the one in its header, refusing a clash."""
    stated = _unit_in_name(column)
    if units is None:
        if stated is None:
            raise ValueError(f"{path}: column {column!r} has no unit in brackets; give --units "
                             f"(angle: {sorted(ANGLE_UNITS)}, length: {sorted(LENGTH_UNITS)})")
        return stated
    if stated is not None and _canonical_unit(stated) != _canonical_unit(units):
        raise ValueError(f"{path}: --units {units!r} contradicts the unit {stated!r} in the "
                         f"header of column {column!r}; drop --units (the header is read) or "
                         "correct the file")
    return units


def _canonical_unit(unit: str) -> str:
    key = unit.strip().lower()
    return {"inch": "in", "inches": "in", "degree": "deg", "degrees": "deg",
            "radian": "rad", "radians": "rad", "feet": "ft", "foot": "ft"}.get(key, key)


def _record_from_columns(path: Path, t: np.ndarray, values: np.ndarray, units: str, column: str,
                         height: float | None) -> FreeRockingRecord:
    unit_key = _canonical_unit(units)
    if unit_key in ANGLE_UNITS:
        return FreeRockingRecord.from_angle(t, values, units=unit_key, name=path.stem)
    if unit_key in LENGTH_UNITS:    # shown in the file's own unit
        return replace(FreeRockingRecord.from_top_displacement(
            t, values, units=unit_key, height=height, name=path.stem), display_unit=unit_key)
    raise ValueError(f"{path}: unknown unit {units!r} of column {column!r}; expected an angle "
                     f"({sorted(ANGLE_UNITS)}) or a length ({sorted(LENGTH_UNITS)})")


def _check_rate(rate: object) -> float:
    if isinstance(rate, bool) or not isinstance(rate, numbers.Real) or not (
            math.isfinite(float(rate)) and float(rate) > 0):
        raise ValueError(f"rate must be a positive number [samples/s], got {rate!r}")
    return float(rate)


def _is_csv_with_header(lines: list[str]) -> bool:
    """True when the first line that is neither blank nor a comment is a comma-separated header."""
    from shaketable.ground.readers.common import is_number

    for line in lines:
        stripped = line.strip()
        if not stripped or stripped[0] in "#%":
            continue
        fields = [field.strip() for field in stripped.split(",")]
        return len(fields) > 1 and not is_number(fields[0])
    return False


def read_record(path: str | os.PathLike[str], *, column: str | int | None = None, units: str | None = None,
                rate: float | None = None, height: float | None = None,
                time_column: str | int | None = None) -> FreeRockingRecord:
    """Read a free-rocking record from a CSV or plain-text file.

    Two layouts are read:

    * CSV with a header row (``time [s],top displacement [in]``), by pandas;
    * anything else -- whitespace-, comma- or semicolon-separated columns,
      with or without a header line (``time theta`` or none at all) -- by the
      package's text-record machinery (:func:`shaketable.ground.readers.text.read_text`'s
      tokenizer: ``#`` and ``%`` comments, leading non-numeric lines are the
      header, errors name the file and line). Without a header the columns
      are ``time, value`` (two columns) or ``value`` (one, give ``rate``);
      the unit must then be given (``units``).

    Parameters
    ----------
    path : str or Path
        The file; lines starting with ``#`` (or ``%`` in plain text) are comments.
    column : str or int, optional
        The measured column, by name or 0-based index (default: the only
        column that is not time).
    units : str, optional
        Unit of that column: an angle unit (rad, deg, mrad) makes an angle
        record, a length unit (m, cm, mm, in, ft) a top-displacement record.
        Default: the unit in brackets in the column's name, e.g.
        ``top displacement [in]``; required when the file does not state it.
        A ``units`` that contradicts the header's unit is refused (ValueError
        naming both).
    rate : float, optional
        Samples per second [1/s], for a file without a time column.
    time_column : str or int, optional
        The time column, by name or 0-based index. Default: the column whose
        name is a time name (:data:`TIME_NAMES`: ``time``, ``t``, ``Zeit``,
        ... or any name starting with ``time``), with its unit in brackets or
        parentheses (:data:`TIME_UNITS`: s, sec, ms, us, µs, min; none means
        seconds): ``time [ms]``, ``Time (sec)``, ``Zeit [s]``; in a headerless
        file of two or more columns, the first.
    height : float, optional
        Height of the wire [m] for a top displacement (default: the block's).

    Raises
    ------
    FileNotFoundError
        No such file.
    ValueError
        Naming the file (and line) for a missing column or unit or a value
        that is not a number (:class:`shaketable.ground.readers.common.RecordError` from
        the text reader is a ValueError).
    """
    from shaketable.ground.readers.common import read_lines

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such record file")
    if rate is not None:
        rate = _check_rate(rate)
    lines = read_lines(path)
    if not _is_csv_with_header(lines):
        return _read_text_record(path, lines, column=column, units=units, rate=rate,
                                 height=height, time_column=time_column)
    import pandas as pd

    try:
        frame = pd.read_csv(path, comment="#", skipinitialspace=True)
    except Exception as error:     # pandas raises several parser errors
        raise ValueError(f"{path}: not a readable CSV file ({error})") from None
    names = [str(name).strip() for name in frame.columns]
    frame.columns = names
    time_names = [name for name in names if _is_time_name(name)]
    if time_column is not None:
        time_names = [_named_column(path, names, time_column, "--time-column")]
    if column is not None:
        column = _named_column(path, names, column, "--column")
    if column is None:
        candidates = [name for name in names if name not in time_names]
        if len(candidates) != 1:
            raise ValueError(f"{path}: give --column, one of {candidates}")
        column = candidates[0]
    if time_names and column == time_names[0]:
        raise ValueError(f"{path}: --column {column!r} is the time column")
    units = _checked_units(path, column, units)

    def numbers_of(name: str) -> np.ndarray:
        values = pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            line = _data_line(path, int(bad[0]))
            raise ValueError(f"{path}, line {line}: column {name!r} holds "
                             f"{str(frame[name].iloc[bad[0]])!r}, not a finite number")
        return values

    values = numbers_of(column)
    if time_names:
        t = numbers_of(time_names[0]) * time_factor(path, time_names[0])
    elif rate is not None:
        t = np.arange(values.size) / rate
    else:
        raise ValueError(f"{path}: no time column (a column named 'time [s]'); give --rate")
    return _record_from_columns(path, t, values, units, column, height)


def _named_column(path: Path, names: list[str], choice: str | int, option: str) -> str:
    """The column ``choice`` (name, case-insensitive, or 0-based index) of a CSV header."""
    if isinstance(choice, (int, np.integer)) and not isinstance(choice, bool):
        if not -len(names) <= choice < len(names):
            raise ValueError(f"{path}: {option} {choice} but the file has {len(names)} columns "
                             f"{names}")
        return names[int(choice)]
    lowered = [name.lower() for name in names]
    key = str(choice).strip().lower()
    if key not in lowered:
        raise ValueError(f"{path}: {option}: no column {choice!r}; columns are {names}")
    return names[lowered.index(key)]


def _read_text_record(path: Path, lines: list[str], *, column: str | int | None, units: str | None,
                      rate: float | None, height: float | None,
                      time_column: str | int | None = None) -> FreeRockingRecord:
    """Headerless or whitespace-separated record, through shaketable.ground.records' text tokenizer."""
    from shaketable.ground.readers.text import (
        count_header_lines,
        header_column_names,
        text_rows,
    )

    first = count_header_lines(lines, None, None)
    header = lines[:first]
    table, line_numbers = text_rows(lines, first, None, path)
    ncolumns = table.shape[1]
    names = header_column_names(header, ncolumns, None)
    if isinstance(column, str):
        lowered = [name.strip().lower() for name in names]
        if column.strip().lower() not in lowered:
            raise ValueError(f"{path}: no column named {column!r}"
                             + (f"; columns are {names}" if names else
                                " (the file has no header line; give the column's index)"))
        value_index = lowered.index(column.strip().lower())
    elif column is not None:
        if isinstance(column, bool) or not -ncolumns <= int(column) < ncolumns:
            raise ValueError(f"{path}: column {column!r} but the file has {ncolumns} column(s)")
        value_index = int(column) % ncolumns
    else:
        value_index = None
    time_index = None
    if time_column is not None:
        if isinstance(time_column, str):
            if not names:
                raise ValueError(f"{path}: --time-column {time_column!r}: the file has no "
                                 "header line; give the column's index")
            time_index = names.index(_named_column(path, names, time_column, "--time-column"))
        else:
            time_index = names.index(_named_column(path, names, time_column, "--time-column")) \
                if names else _index_of(path, time_column, ncolumns, "--time-column")
    elif names:
        timed = [index for index, name in enumerate(names) if _is_time_name(name)]
        time_index = timed[0] if timed else None
    elif rate is None and ncolumns >= 2:
        time_index = 0
    if value_index is None:
        others = [index for index in range(ncolumns) if index != time_index]
        if len(others) != 1:
            raise ValueError(f"{path}: {ncolumns} columns{f' {names}' if names else ''}; give "
                             "--column (name or 0-based index)")
        value_index = others[0]
    if value_index == time_index:
        raise ValueError(f"{path}: the column {value_index} chosen is the time column")
    name = names[value_index] if names else f"column {value_index}"
    if names and units is not None:
        units = _checked_units(path, name, units)
    if units is None:
        units = _unit_in_name(name) if names else None
        if units is None:
            named = [index + 1 for index, line in enumerate(header) if line.strip()]
            where = named[-1] if names and named else line_numbers[0]
            raise ValueError(
                f"{path}, line {where}: the unit of "
                f"{name!r} is not stated; give --units (angle: {sorted(ANGLE_UNITS)}, length: "
                f"{sorted(LENGTH_UNITS)})")
    values = table[:, value_index]
    if time_index is not None:
        t = table[:, time_index] * (time_factor(path, names[time_index]) if names else 1.0)
        steps = np.diff(t)
        bad = np.flatnonzero(steps <= 0)
        if bad.size:
            raise ValueError(f"{path}, line {line_numbers[int(bad[0]) + 1]}: time "
                             f"{t[bad[0] + 1]!r} s does not increase")
    elif rate is not None:
        t = np.arange(values.size) / rate
    else:
        raise ValueError(f"{path}: no time column; give --rate (samples/s)")
    return _record_from_columns(path, t, values, units, name, height)


def _index_of(path: Path, choice: int, ncolumns: int, option: str) -> int:
    if isinstance(choice, bool) or not -ncolumns <= int(choice) < ncolumns:
        raise ValueError(f"{path}: {option} {choice!r} but the file has {ncolumns} column(s)")
    return int(choice) % ncolumns


def _data_line(path: Path, row: int) -> int:
    """1-based file line of data row ``row`` (skipping comments, blank lines and the header)."""
    count = -1
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if count == row:
            return number
        count += 1
    return number


#: Ways of computing the interval from the Jacobian.
INTERVALS = {"acf": "sandwich covariance with the residuals' autocovariance (stationary noise)",
             "hac": "Newey-West (autocorrelation-consistent) sandwich covariance",
             "iid": "s^2 (J^T J)^-1, independent residuals"}


#: Butterworth orders tried by ``calibrate(filter_order="auto")``.
FILTER_ORDERS = (1, 2, 4, 8)


#: Ways of modelling the acquisition's anti-alias filter (``calibrate(anti_alias=)``).
ANTI_ALIAS = {"fit": "Butterworth low-pass, cutoff fitted", "known": "the given Digitizer's filter",
              "none": "no filter"}


