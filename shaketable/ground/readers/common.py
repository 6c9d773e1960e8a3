"""What every reader shares: the one-component :class:`Record`, :class:`RecordError`
(naming file and line), number and unit parsing, and :func:`combine` (records to a
:class:`~shaketable.core.motion.Motion`).
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from shaketable.core.constants import acceleration_factor
from shaketable.core.equality import fields_equal
from shaketable.core.motion import Motion, frozen_metadata


class RecordError(ValueError):
    """A record file is malformed; the message names the file and the line."""


@dataclass(frozen=True, eq=False)
class Record:
    """One uniformly sampled acceleration component read from a file.

    Parameters
    ----------
    dt : float
        Sample interval [s], positive.
    acceleration : array_like
        Acceleration samples [m/s^2], in the sign convention of the file
        (a component labelled ``DWN`` is still positive downward here; the
        conversion to positive-up happens in :func:`combine`).
    component : str, optional
        Component or orientation label as written in the file, e.g. ``"164"``,
        ``"UP"``, ``"DWN"``; empty when the file does not state it.
    description : str, optional
        Free-text identification of the record taken from the file header.
    source : str, optional
        Path of the file the record was read from.
    units_in_file : str, optional
        Acceleration unit of the numbers in the file (``"g"``, ``"m/s2"``,
        ``"cm/s2"`` or ``"gal"``).
    t0 : float, optional
        Time of the first sample [s] (non-zero only when a time column says so).
    metadata : mapping, optional
        Provenance of a record read through ObsPy or gmprocess: ``network``,
        ``station``, ``location``, ``channel``, ``starttime`` (ISO 8601, UTC),
        ``format``, ``calib``, ``units_in_file``, ``mean_removed``; through
        ObsPy also ``units_source`` and ``sensitivity`` (the instrument
        response's overall sensitivity divided by, 0.0 without one). Read-only;
        carried into the :class:`~shaketable.core.motion.Motion` by
        :func:`~shaketable.ground.records.combine`.

    Notes
    -----
    The acceleration array is copied and made read-only.
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    dt: float
    acceleration: np.ndarray
    component: str = ""
    description: str = ""
    source: str = ""
    units_in_file: str = ""
    t0: float = 0.0
    metadata: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        dt = float(self.dt)
        if not (math.isfinite(dt) and dt > 0):
            raise ValueError(f"Record.dt must be a positive number of seconds, got {self.dt!r}")
        acceleration = np.array(self.acceleration, dtype=float)
        if acceleration.ndim != 1 or acceleration.size == 0:
            raise ValueError(
                f"Record.acceleration must be a non-empty 1-D array, got shape {acceleration.shape}"
            )
        if not np.all(np.isfinite(acceleration)):
            index = int(np.flatnonzero(~np.isfinite(acceleration))[0])
            raise ValueError(f"Record.acceleration[{index}] is not finite")
        acceleration.setflags(write=False)
        object.__setattr__(self, "dt", dt)
        object.__setattr__(self, "acceleration", acceleration)
        object.__setattr__(self, "source", str(self.source))
        object.__setattr__(self, "t0", float(self.t0))
        object.__setattr__(self, "metadata", frozen_metadata(self.metadata))

    @property
    def npts(self) -> int:
        """Number of samples."""
        return int(self.acceleration.size)

    @property
    def duration(self) -> float:
        """Record length ``npts * dt`` [s] (as PEER and PROVENANCE.md count it)."""
        return self.npts * self.dt

    @property
    def t(self) -> np.ndarray:
        """Sample times ``t0 + i * dt`` [s]."""
        return self.t0 + self.dt * np.arange(self.npts)

    @property
    def pga(self) -> float:
        """Peak absolute acceleration [m/s^2]."""
        return float(np.max(np.abs(self.acceleration)))

    @property
    def peak_acceleration(self) -> float:
        """Signed acceleration at the peak of ``|a|`` [m/s^2] (first peak if tied)."""
        return float(self.acceleration[self._peak_index])

    @property
    def peak_time(self) -> float:
        """Time of the peak of ``|a|`` [s] (first peak if tied)."""
        return self.t0 + self.dt * self._peak_index

    @property
    def _peak_index(self) -> int:
        return int(np.argmax(np.abs(self.acceleration)))


# --------------------------------------------------------------------- helpers
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"

NPTS_DT_PATTERNS = (
    # NGA-West2 "NPTS=   4172, DT=   .0100 SEC," and older PEER "NPTS=  4000, DT= .01000 SEC"
    re.compile(rf"NPTS\s*=\s*(?P<npts>\d+)\s*,?\s*DT\s*=\s*(?P<dt>{_NUMBER})", re.IGNORECASE),
    # NGA-West1 "4164    0.0100    NPTS, DT"
    re.compile(rf"^\s*(?P<npts>\d+)\s+(?P<dt>{_NUMBER})\s+NPTS\s*,\s*DT", re.IGNORECASE),
)

#: How many leading lines of an AT2 file are searched for the NPTS/DT line.
AT2_MAX_HEADER_LINES = 10

AT2_UNITS = re.compile(
    r"UNITS\s*(?:OF|ARE|IN|=|:)?\s*[(\[]?\s*(?P<unit>[A-Za-z][A-Za-z0-9/^*]*)", re.IGNORECASE
)

_UNIT_WORD = r"g|gal|cm/s(?:ec)?(?:\^?2|/s(?:ec)?)|m/s(?:ec)?(?:\^?2|/s(?:ec)?)"

TEXT_UNITS = (
    re.compile(rf"[(\[]\s*(?P<unit>{_UNIT_WORD})\s*[)\]]", re.IGNORECASE),
    re.compile(rf"\bunits?\s*(?:of|are|in|=|:)?\s*(?P<unit>{_UNIT_WORD})(?![\w/^])", re.IGNORECASE),
)

COMPONENT_PATTERN = re.compile(r"^\s*(?P<component>[A-Za-z0-9+\-]{1,8})\s*(?:\(.*\))?\s*$")

DOWN_LABELS = {"DWN", "DOWN", "DN"}


def missing_file_message(path: Path) -> str:
    """Why ``path`` cannot be read as a record file: a folder, or nothing there."""
    if Path(path).is_dir():
        return f"{path}: is a folder, not a record file"
    return f"{path}: cannot read the file: no such file"


def read_lines(path: Path) -> list[str]:
    """Lines of a text file, CRLF or LF, without line endings."""
    return read_text_file(path).splitlines()


def read_text_file(path: Path) -> str:
    """The text of a file, CRLF and CR read as LF (undecodable bytes replaced)."""
    if not Path(path).is_file():
        raise RecordError(missing_file_message(path))
    try:
        with open(path, encoding="utf-8", errors="replace", newline=None) as stream:
            return stream.read()
    except OSError as error:
        raise RecordError(f"{path}: cannot read the file: {error.strerror or error}") from None


def file_location(path: Path, line_number: int) -> str:
    return f"{path}, line {line_number}"


def parse_number(token: str, path: Path, line_number: int) -> float:
    """Parse one finite number (Fortran ``D`` exponents accepted)."""
    try:
        value = float(token.replace("D", "E").replace("d", "e"))
    except ValueError:
        raise RecordError(f"{file_location(path, line_number)}: {token!r} is not a number") from None
    if not math.isfinite(value):
        raise RecordError(f"{file_location(path, line_number)}: {token!r} is not a finite number")
    return value


def canonical_unit(word: str) -> str:
    """Map a unit as written (``G``, ``cm/sec/sec``, ``m/s^2`` ...) to a key of
    :data:`shaketable.core.constants.ACCELERATION_UNITS`; raise ``ValueError`` if unknown."""
    unit = word.strip().lower().replace(" ", "").replace("sec", "s")
    unit = unit.replace("**2", "2").replace("^2", "2").replace("²", "2").replace("/s/s", "/s2")
    acceleration_factor(unit)  # raises ValueError listing the accepted units
    return unit


def unit_or_error(word: str, path: Path, line_number: int) -> str:
    try:
        return canonical_unit(word)
    except ValueError as error:
        raise RecordError(f"{file_location(path, line_number)}: {error}") from None


def units_argument(units: object, path: Path) -> str:
    """The ``units=`` argument as a canonical unit, else a ValueError naming it and the file."""
    if not isinstance(units, str):
        raise ValueError(f"{path}: units must be a string such as 'g' or 'm/s2', got {units!r}")
    try:
        return canonical_unit(units)
    except ValueError as error:
        raise ValueError(f"{path}: units={units!r}: {error}") from None


# --------------------------------------------------------------------- text
def split_fields(line: str, delimiter: str | None) -> list[str]:
    if delimiter is None:
        return [field for field in re.split(r"[\s,;]+", line.strip()) if field]
    return [field.strip() for field in line.split(delimiter)]


def is_number(token: str) -> bool:
    try:
        float(token.replace("D", "E").replace("d", "e"))
    except ValueError:
        return False
    return True


def uniform_time_step(times: np.ndarray, line_numbers: Sequence[int], path: Path) -> float:
    """Sample interval [s] of a time column; every step must be within 1 % of
    the median step."""
    if times.size < 2:
        raise RecordError(f"{file_location(path, line_numbers[0])}: a time column needs 2 or more rows")
    steps = np.diff(times)
    backwards = np.flatnonzero(~(steps > 0))
    if backwards.size:
        index = int(backwards[0])
        raise RecordError(
            f"{file_location(path, line_numbers[index + 1])}: time {float(times[index + 1]):.10g} s "
            f"does not increase from {float(times[index]):.10g} s on the line before; the time "
            "column must increase")
    typical = float(np.median(steps))
    irregular = np.flatnonzero(~(np.abs(steps - typical) <= 0.01 * abs(typical)) | (steps <= 0))
    if irregular.size:
        index = int(irregular[0])
        raise RecordError(
            f"{file_location(path, line_numbers[index + 1])}: time step {float(steps[index]):g} s "
            f"differs from the usual step {typical:g} s; only uniformly sampled records "
            "are supported"
        )
    span = float(times[-1] - times[0])
    dt = span / (times.size - 1)
    # drop the rounding noise of printed times: 12 significant digits, fewer when the
    # times are large (an epoch offset, t0 = 1.7e9 s, leaves ~7 digits in the span)
    noise = 4.0 * float(np.spacing(max(abs(float(times[0])), abs(float(times[-1]))))) / span
    digits = int(min(12, max(3, math.floor(-math.log10(noise)))))
    return float(f"{dt:.{digits}g}")


def optional_positive(value: Any, name: str, unit: str, path: Path) -> float | None:
    """``None`` or a positive finite float, else a ValueError naming ``name`` and the file."""
    if value is None:
        return None
    if isinstance(value, bool):
        raise ValueError(f"{path}: {name} must be a positive number{unit}, got {value!r}")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{path}: {name} must be a positive number{unit}, "
                         f"got {value!r}") from None
    if not (math.isfinite(number) and number > 0.0):
        raise ValueError(f"{path}: {name} must be a positive finite number{unit}, got {value!r}")
    return number


def option_integer(value: object, name: str, path: Path, minimum: int | None = 0) -> int:
    """An integer option (``skiprows``, a column index), else a ValueError naming it and the file."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{path}: {name} must be an integer, got {value!r}")
    if minimum is not None and value < minimum:
        raise ValueError(f"{path}: {name} must be >= {minimum}, got {value!r}")
    return int(value)


class VerticalSignWarning(UserWarning):
    """A ``DWN``-labelled vertical was combined without an explicit sign reading."""


def _vertical_sign_warning(vertical: Record) -> None:
    warnings.warn(
        f"vertical component {vertical.component!r}{_from(vertical)} is labelled positive "
        "down and is flipped to positive up; the bundled names 'pacoima-dam-s16e' and "
        "'pacoima-dam-s74w' read the same file the other way (pacoima_vertical_sign='up', "
        "the reading that reproduces Tables 4.2-4.3). Pass vertical_positive='down' or "
        "'up' to combine() to choose explicitly and silence this warning",
        VerticalSignWarning, stacklevel=3)


# --------------------------------------------------------------------- combine
def vertical_is_positive_down(vertical: Record, vertical_positive: str | None) -> bool:
    if vertical_positive is None:
        return vertical.component.strip().upper() in DOWN_LABELS
    choice = str(vertical_positive).strip().lower()
    if choice not in ("up", "down"):
        raise ValueError(f"vertical_positive must be 'up' or 'down', got {vertical_positive!r}")
    return choice == "down"


def _padded(values: np.ndarray, length: int) -> np.ndarray:
    """``values`` followed by zeros up to ``length`` samples."""
    return np.concatenate([values, np.zeros(length - values.size)])


def _from(record: Record) -> str:
    return f" (from {record.source})" if record.source else ""


def _check_same_sampling(horizontal: Record, vertical: Record) -> None:
    if not math.isclose(horizontal.dt, vertical.dt, rel_tol=1e-6):
        raise ValueError(
            f"cannot combine records with different sample intervals: horizontal dt = "
            f"{horizontal.dt} s{_from(horizontal)}, vertical dt = {vertical.dt} s"
            f"{_from(vertical)}; resample one of them first"
        )
    if abs(horizontal.t0 - vertical.t0) > 1e-6 * horizontal.dt:
        raise ValueError(
            f"cannot combine records starting at different times: horizontal t0 = "
            f"{horizontal.t0} s, vertical t0 = {vertical.t0} s"
        )


def combine(horizontal: Record, vertical: Record | None = None, *,
            vertical_positive: str | None = None, name: str = "") -> Motion:
    """Join a horizontal and an optional vertical record into a :class:`Motion`.

    Components of different lengths are aligned at their first sample and the
    shorter is padded with zeros at the end to the length of the longer.

    Parameters
    ----------
    horizontal : Record
        Horizontal acceleration [m/s^2], used as +x.
    vertical : Record, optional
        Vertical acceleration [m/s^2]; same ``dt`` and ``t0`` as ``horizontal``.
    vertical_positive : {"up", "down"}, optional
        Direction in which the vertical file's positive values point. ``"down"``
        multiplies the vertical by -1 so that the motion is positive up (the
        package convention). Default: from the record's component label --
        ``"DWN"``, ``"DOWN"`` or ``"DN"`` mean down, anything else (``"UP"``,
        an empty label, ...) means up; a down label read this way gives a
        :class:`VerticalSignWarning`, because the bundled Pacoima Dam names
        read their ``DWN`` file the other way (see the module docstring).
    name : str, optional
        Motion name; default built from the records' descriptions.

    Returns
    -------
    Motion
        Sampled every ``dt`` from t = 0 (the records' own start ``t0``, when not
        0, is kept in ``metadata["start time [s]"]``); vertical positive up.
        ``metadata`` holds each record's own metadata under ``"horizontal"``
        and ``"vertical"``, and ``"vertical_positive"`` (``"up"``/``"down"``,
        the reading applied) with ``"vertical_sign_source"`` (``"argument"``
        or ``"label"``).

    Raises
    ------
    ValueError
        Different ``dt`` or ``t0``, or an invalid ``vertical_positive``.
    """
    # the motion's clock starts at 0: a record whose time column starts at an epoch
    # offset (t0 = 1.7e9 s) would leave the engine's event location no digits; the
    # record's own start is kept in the metadata
    start = {"start time [s]": horizontal.t0} if horizontal.t0 != 0.0 else {}
    if vertical is None:
        return Motion.uniform(horizontal.dt, horizontal.acceleration, None,
                              name=name or _default_name(horizontal, None, False),
                              metadata={"horizontal": horizontal.metadata, **start})
    _check_same_sampling(horizontal, vertical)
    positive_down = vertical_is_positive_down(vertical, vertical_positive)
    if positive_down and vertical_positive is None:
        _vertical_sign_warning(vertical)
    length = max(horizontal.npts, vertical.npts)
    vertical_up = -vertical.acceleration if positive_down else vertical.acceleration
    metadata = {"horizontal": horizontal.metadata, "vertical": vertical.metadata,
                "vertical_positive": "down" if positive_down else "up",
                "vertical_sign_source": "label" if vertical_positive is None else "argument",
                **start}
    return Motion.uniform(
        horizontal.dt, _padded(horizontal.acceleration, length), _padded(vertical_up, length),
        name=name or _default_name(horizontal, vertical, positive_down),
        metadata=metadata,
    )


def _default_name(horizontal: Record, vertical: Record | None, positive_down: bool) -> str:
    label = f"{horizontal.description} [{horizontal.component}]".strip()
    if vertical is None:
        return label
    flip = " (sign flipped: file positive down)" if positive_down else ""
    return f"{label} + vertical [{vertical.component}]{flip}"
