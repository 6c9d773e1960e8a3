"""The PEER NGA ``.AT2`` reader: header (NPTS, DT, units, component) and values."""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from shaketable.core.constants import acceleration_factor
from shaketable.ground.readers.common import (
    AT2_MAX_HEADER_LINES,
    AT2_UNITS,
    COMPONENT_PATTERN,
    NPTS_DT_PATTERNS,
    Record,
    RecordError,
    file_location,
    parse_number,
    read_lines,
    unit_or_error,
    units_argument,
)


# --------------------------------------------------------------------- AT2
def _find_npts_dt(lines: list[str], path: Path) -> tuple[int, int, float]:
    """Return ``(index of the NPTS/DT line, npts, dt [s])`` of an AT2 header."""
    searched = min(len(lines), AT2_MAX_HEADER_LINES)
    for index in range(searched):
        for pattern in NPTS_DT_PATTERNS:
            match = pattern.search(lines[index])
            if match:
                npts = int(match["npts"])
                dt = parse_number(match["dt"], path, index + 1)
                if npts < 1 or dt <= 0:
                    raise RecordError(
                        f"{file_location(path, index + 1)}: NPTS={npts} and DT={dt} must be positive"
                    )
                return index, npts, dt
    raise RecordError(
        f"{path}, lines 1-{max(searched, 1)}: no 'NPTS=..., DT=...' header line found "
        "(a PEER AT2 file has it on line 4)"
    )


def _at2_units(header: list[str], path: Path, units) -> str:
    """Unit of an AT2 file: the one its header names (e.g. ``UNITS OF G``),
    checked against ``units``; ``units`` when the header names none; else an error."""
    stated = None
    for index, line in enumerate(header):
        match = AT2_UNITS.search(line)
        if match:
            stated = unit_or_error(match["unit"], path, index + 1)
            break
    if units is None:
        if stated is None:
            raise RecordError(
                f"{path}, lines 1-{len(header)}: the header does not state the acceleration "
                "units (no 'UNITS OF ...'); pass units= (one of 'g', 'm/s2', 'cm/s2', 'gal')"
            )
        return stated
    given = units_argument(units, path)
    if stated is not None and acceleration_factor(stated) != acceleration_factor(given):
        raise ValueError(
            f"{path}: units={units!r} contradicts the header's units {stated!r}"
        )
    return given


def _at2_component(header: list[str]) -> str:
    """Component from the last comma field of header line 2 (``"164"``, ``"DWN"``, ``"UP"``)."""
    if len(header) < 2 or "," not in header[1]:
        return ""
    match = COMPONENT_PATTERN.match(header[1].rsplit(",", 1)[1])
    return match["component"] if match else ""


def _at2_description(header: list[str]) -> str:
    """Record identification: line 2 of a PEER header, otherwise line 1."""
    if len(header) >= 2 and "PEER" in header[0].upper():
        return header[1].strip()
    return header[0].strip() if header else ""


def _at2_values(lines: list[str], first: int, npts: int, path: Path) -> np.ndarray:
    """Read exactly ``npts`` whitespace-separated values from ``lines[first:]``."""
    values = np.empty(npts)
    count = 0
    shapes: dict = {}
    last = ("", 0)
    for index in range(first, len(lines)):
        for token in lines[index].replace(",", " ").split():
            if count == npts:
                raise RecordError(
                    f"{file_location(path, index + 1)}: more values than NPTS={npts} in the header"
                )
            values[count] = parse_number(token, path, index + 1)
            shape = _number_shape(token)
            shapes[shape] = shapes.get(shape, 0) + 1
            last = (token, index + 1)
            count += 1
    if count < npts:
        raise RecordError(
            f"{file_location(path, len(lines))}: the file ends after {count} of NPTS={npts} values "
            "(truncated data?)"
        )
    _check_last_value_complete(shapes, last, path)
    return values


_NUMBER_SHAPE = re.compile(r"^[+-]?(\d*)\.(\d*)(?:[eEdD]([+-]?)(\d*))?$")


def _number_shape(token: str) -> tuple:
    """(digits after the point, exponent digits) of a printed number; () if free-form."""
    match = _NUMBER_SHAPE.match(token)
    if match is None:
        return ()
    return len(match[2]), None if match[4] is None else len(match[4])


def _check_last_value_complete(shapes: dict, last: tuple, path: Path) -> None:
    """Refuse a file cut in the middle of its last number.

    AT2 values are printed in one fixed format (``-.1234567E-02``). A last value
    with fewer fraction or exponent digits than every other value of a file that
    uses one format (``.1234567E-0``: 1000 times too large) is a cut file, not data.
    """
    token, line = last
    shape = _number_shape(token)
    if not shape or len(shapes) != 2 or shapes.get(shape, 0) != 1:
        return
    (usual,) = [other for other in shapes if other != shape]
    if not usual or sum(shapes.values()) < 3:
        return
    fraction, exponent = shape
    if fraction < usual[0] or (usual[1] is not None and (exponent or 0) < usual[1]):
        raise RecordError(
            f"{file_location(path, line)}: the last value {token!r} has fewer digits than "
            f"every other value of the file: the file looks cut in the middle of a number "
            f"(download it again)")


def read_at2(path: str | os.PathLike[str], *, units: str | None = None) -> Record:
    """Read a PEER ``.AT2`` acceleration file.

    Handles the NGA-West2 header (``NPTS=   4172, DT=   .0100 SEC,`` possibly
    followed by filter-pole text), the older PEER header (``NPTS=  4000, DT=
    .01000 SEC``), the "Peknold" El Centro file (3 free-text lines then
    ``NPTS=  1559, DT= .02000 SEC``) and the NGA-West1 form (``4164  0.0100
    NPTS, DT``). NPTS and DT are parsed by regular expression among the first
    lines; the data follow the NPTS/DT line in any number of columns.

    Parameters
    ----------
    path : str or os.PathLike
        The file (CRLF or LF line endings).
    units : str, optional
        Unit of the values (``g``, ``m/s2``, ``cm/s2``, ``gal``). Required when
        the header does not state it (no ``UNITS OF ...``, ``The units are
        (g)``, ...); when both are there they must agree. Units are never
        assumed.

    Returns
    -------
    Record
        ``acceleration`` [m/s^2]; ``component`` from the last comma field of
        header line 2 (e.g. ``"164"``, ``"DWN"``, ``"UP"``); ``units_in_file``
        from the header or from ``units``.

    Raises
    ------
    RecordError
        Missing NPTS/DT line, a token that is not a finite number, fewer or
        more values than NPTS, an unknown unit in the header, or no unit in
        the header and no ``units``; the message names the file and the line.
    ValueError
        ``units`` unknown or contradicting the header; the message names the
        file.
    """
    path = Path(path)
    lines = read_lines(path)
    npts_line, npts, dt = _find_npts_dt(lines, path)
    header = lines[: npts_line + 1]
    units = _at2_units(header, path, units)
    values = _at2_values(lines, npts_line + 1, npts, path)
    return Record(
        dt=dt,
        acceleration=values * acceleration_factor(units),
        component=_at2_component(header),
        description=_at2_description(header),
        source=str(path),
        units_in_file=units,
    )
