"""Delimited text records: a time column or a step, named columns, units from the header
or given explicitly.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from shaketable.core.constants import acceleration_factor
from shaketable.ground.readers.common import (
    TEXT_UNITS,
    Record,
    RecordError,
    canonical_unit,
    file_location,
    is_number,
    option_integer,
    optional_positive,
    parse_number,
    read_text_file,
    split_fields,
    uniform_time_step,
    units_argument,
)


def _is_comment_or_blank(line: str) -> bool:
    stripped = line.strip()
    return not stripped or stripped[0] in "#%"


def count_header_lines(lines: list[str], skiprows: int | None, delimiter: str | None) -> int:
    """Number of leading header lines: ``skiprows``, or the leading lines that are
    blank, comments or start with something that is not a number."""
    if skiprows is not None:
        if skiprows < 0:
            raise ValueError(f"skiprows must be >= 0, got {skiprows!r}")
        return skiprows
    for index, line in enumerate(lines):
        if _is_comment_or_blank(line):
            continue
        fields = split_fields(line, delimiter)
        if fields and is_number(fields[0]):
            return index
    return len(lines)


#: Data lines from which :func:`text_rows` tries the compiled parser first.
FAST_PATH_LINES = 10_000


def _fast_rows(lines: list[str], first: int, delimiter: str | None) -> np.ndarray | None:
    """The table below the header through pandas' compiled CSV parser, or None.

    Only for a clean table: no comment or blank line inside, the same number of
    fields on every line, every value a finite number in a notation ``float``
    reads (so no Fortran ``D`` exponent). Anything else (and any failure) gives
    None, and the line-by-line parser then names the line at fault. Numbers are
    converted exactly as ``float()`` does (``float_precision="round_trip"``), so
    both paths give the same bits.
    """
    return _fast_table("\n".join(lines[first:]), len(lines) - first, delimiter)


def _fast_table(body: str, rows: int, delimiter: str | None) -> np.ndarray | None:
    """:func:`_fast_rows` of the text ``body`` of ``rows`` lines (LF line ends)."""
    import io
    import warnings

    import pandas as pd

    if any(mark in body for mark in "#%dD"):   # comments, Fortran exponents: the exact parser
        return None                            # (blank lines: NaN rows, refused below)
    if delimiter is None:
        if "," in body or ";" in body:
            body = body.translate(str.maketrans(",;", "  "))
        options: dict = {"sep": r"\s+"}
    elif len(delimiter) == 1 and not delimiter.isspace():
        options = {"sep": delimiter}
    else:
        return None
    try:
        with warnings.catch_warnings():   # pandas 3 deprecates the option, keeps its meaning
            warnings.simplefilter("ignore")
            frame = pd.read_csv(io.StringIO(body), header=None, dtype=float, engine="c",
                                float_precision="round_trip", skip_blank_lines=False,
                                **options)
    except Exception:  # anything unusual: the exact parser says what
        return None
    table = frame.to_numpy(dtype=float)
    if table.shape[0] != rows or not np.isfinite(table).all():
        return None
    return table


#: Characters of a text record read to find its header (the body is parsed whole).
_HEAD_CHARACTERS = 1 << 16


def _fast_body(content: str, header: list[str], delimiter: str | None,
               european: bool) -> np.ndarray | None:
    """The table after ``header`` in ``content`` by the compiled parser, or None (too short
    for it, a line break other than LF, or anything :func:`_fast_table` refuses)."""
    start = sum(len(line) + 1 for line in header)
    if header and content[:start] != "\n".join(header) + "\n":
        return None   # other line breaks (\f, \x1c, ...) in the header: the exact parser
    body = content[start:].rstrip()   # trailing blank lines are no rows
    rows = body.count("\n") + 1
    if rows < FAST_PATH_LINES:
        return None
    if european:
        body = body.replace(",", ".")
    return _fast_table(body, rows, delimiter)


def _decimal_comma(lines: list[str], first: int, sample: int = 50) -> bool:
    """Whether the data lines are a European CSV: ``0,005;0,1`` (``;`` between fields,
    ``,`` the decimal mark, no ``.``), judged on the first ``sample`` data lines."""
    seen = 0
    for line in lines[first:]:
        if _is_comment_or_blank(line):
            continue
        if ";" not in line or "." in line:
            return False
        fields = [field.strip().replace(",", ".") for field in line.split(";")]
        if not all(is_number(field) for field in fields if field):
            return False
        seen += 1
        if seen == sample:
            break
    return seen > 0 and any("," in line for line in lines[first:first + 4 * sample])


def text_rows(lines: list[str], first: int, delimiter: str | None,
              path: Path) -> tuple[np.ndarray, Sequence[int]]:
    """Parse the numeric table below the header; return ``(array, line_numbers)``.

    Long tables (:data:`FAST_PATH_LINES` lines or more) go through the compiled
    parser when they are clean (:func:`_fast_rows`, about 40 times faster); the
    line-by-line parser reads the rest and names the line of any fault.
    """
    if len(lines) - first >= FAST_PATH_LINES:
        table = _fast_rows(lines, first, delimiter)
        if table is not None:
            return table, range(first + 1, len(lines) + 1)
    rows: list[list[float]] = []
    line_numbers: list[int] = []
    for index in range(first, len(lines)):
        if _is_comment_or_blank(lines[index]):
            continue
        fields = split_fields(lines[index], delimiter)
        if rows and len(fields) != len(rows[0]):
            raise RecordError(
                f"{file_location(path, index + 1)}: {len(fields)} column(s), but the data "
                f"start with {len(rows[0])} (truncated or ragged line?)"
            )
        rows.append([parse_number(field, path, index + 1) for field in fields])
        line_numbers.append(index + 1)
    if not rows:
        raise RecordError(f"{file_location(path, max(len(lines), 1))}: no numeric data found in the file")
    return np.array(rows, dtype=float), line_numbers


def header_column_names(header: list[str], ncolumns: int, delimiter: str | None) -> list[str]:
    """Column names from the last non-blank header line, when it has one per column."""
    for line in reversed(header):
        if line.strip():
            if delimiter is not None:
                candidates = [[name.strip() for name in line.split(delimiter)]]
            else:
                candidates = [[name for name in re.split(r"[,;\t]|\s{2,}", line.strip()) if name],
                              line.split()]
            for names in candidates:
                if len(names) == ncolumns:
                    return names
            return []
    return []


def _column_index(choice: str | int, names: list[str], ncolumns: int, what: str, path: Path) -> int:
    if isinstance(choice, str):
        lowered = [name.strip().lower() for name in names]
        if choice.strip().lower() not in lowered:
            raise ValueError(f"{path}: no column named {choice!r} for {what}; columns are {names}")
        return lowered.index(choice.strip().lower())
    index = int(choice)
    if not -ncolumns <= index < ncolumns:
        raise ValueError(f"{path}: {what}={choice!r} but the file has {ncolumns} column(s)")
    return index % ncolumns


def _choose_columns(ncolumns: int, dt: float | None, time_column: str | int | None,
                    value_column: str | int | None, names: list[str],
                    path: Path) -> tuple[int | None, int]:
    """Return ``(time column index or None, value column index)``."""
    if time_column is None and dt is None and ncolumns >= 2:
        time_column = 0
    time_index = None if time_column is None else _column_index(
        time_column, names, ncolumns, "time_column", path)
    if value_column is None:
        others = [index for index in range(ncolumns) if index != time_index]
        if len(others) != 1:
            raise ValueError(
                f"{path} has {ncolumns} columns{f' {names}' if names else ''}; "
                "choose the acceleration column with value_column=<index or name> "
                "(command line: --column)"
            )
        return time_index, others[0]
    value_index = _column_index(value_column, names, ncolumns, "value_column", path)
    if value_index == time_index:
        raise ValueError(f"{path}: value_column and time_column are both column {value_index}")
    return time_index, value_index


def _units_in_text(text: str) -> set[str]:
    found: set[str] = set()
    for pattern in TEXT_UNITS:
        for match in pattern.finditer(text):
            found.add(canonical_unit(match["unit"]))
    return found


def _text_units(header: list[str], names: list[str], value_index: int, units: str | None,
                path: Path) -> str:
    """Units from the value column's header name, else from the whole header,
    checked against the ``units`` argument."""
    stated = _units_in_text(names[value_index]) if names else set()
    if not stated:
        stated = _units_in_text("\n".join(header))
    if len(stated) > 1:
        raise RecordError(
            f"{path}, lines 1-{len(header)}: the header names several units {sorted(stated)}; "
            "pass units= to say which applies"
        )
    if units is not None:
        given = canonical_unit(units)
        if stated and acceleration_factor(stated.pop()) != acceleration_factor(given):
            raise ValueError(
                f"{path}: units={units!r} contradicts the unit written in the file header"
            )
        return given
    if not stated:
        import re

        bracketed = re.search(r"[\[(]([^\])]+)[\])]", names[value_index]) if names else None
        if bracketed:
            raise ValueError(
                f"{path}, line {len(header)}: unknown acceleration unit {bracketed[1]!r} in the "
                f"header of column {names[value_index].strip()!r}; expected one of 'g', 'm/s2', "
                "'cm/s2', 'gal' (or pass units=)"
            )
        raise ValueError(
            f"{path}: the acceleration units are not stated in the file; "
            "pass units= (one of 'g', 'm/s2', 'cm/s2', 'gal')"
        )
    return stated.pop()


def read_text(path: str | os.PathLike[str], *, dt: float | None = None, units: str | None = None,
              time_column: str | int | None = None, value_column: str | int | None = None,
              skiprows: int | None = None, delimiter: str | None = None) -> Record:
    """Read a plain text or CSV acceleration record.

    Layouts: one column of accelerations (``dt`` required), or a time column
    [s] followed by one or more acceleration columns. Leading lines that do
    not start with a number are a header (or give ``skiprows``); a header such
    as ``time,acc (g)`` states the units. Lines starting with ``#`` or ``%`` are
    skipped. Fields are split on whitespace, commas or semicolons unless
    ``delimiter`` is given; a European export (``0,005;0,1``: semicolons between
    fields, a decimal comma and no decimal point) is recognised.

    Parameters
    ----------
    path : str or os.PathLike
        The file (CRLF or LF).
    dt : float, optional
        Sample interval [s]. Required for a file without a time column; when
        given, no time column is assumed unless ``time_column`` is given (then
        the two must agree within 1 %).
    units : str, optional
        Unit of the acceleration numbers: ``g``, ``m/s2``, ``m/s^2``, ``cm/s2``
        or ``gal``. Required unless the header states it; must agree with it.
    time_column : int or str, optional
        Index (0-based) or header name of the time column [s]. Default: column
        0 when the file has 2 or more columns and ``dt`` is not given.
    value_column : int or str, optional
        Index or header name of the acceleration column. Required when more
        than one column besides the time column remains.
    skiprows : int, optional
        Number of header lines to skip (default: detected).
    delimiter : str, optional
        Field separator (default: whitespace, ``,`` or ``;``).

    Returns
    -------
    Record
        ``acceleration`` [m/s^2]; ``t0`` is the first time of a time column.

    Raises
    ------
    RecordError
        A non-numeric or non-finite token, a ragged line, no data, or a
        non-uniform time column; the message names the file and the line.
    ValueError
        Units neither stated in the file nor given, missing ``dt`` or column
        choice, or contradictory arguments; the message names the file.
    """
    path = Path(path)
    dt = optional_positive(dt, "dt", " [s]", path)
    if skiprows is not None:
        skiprows = option_integer(skiprows, "skiprows", path)
    for name, column in (("time_column", time_column), ("value_column", value_column)):
        if column is not None and not isinstance(column, str):
            option_integer(column, name, path, minimum=None)
    if delimiter is not None and (not isinstance(delimiter, str) or not delimiter):
        raise ValueError(f"{path}: delimiter must be a non-empty string, got {delimiter!r}")
    if units is not None:
        units = units_argument(units, path)
    content = read_text_file(path)
    # the header from the first lines only: a long record's body goes to the compiled
    # parser as one string, never split into millions of Python lines
    lines = content[:_HEAD_CHARACTERS].splitlines()
    header_length = count_header_lines(lines, skiprows, delimiter)
    if header_length >= len(lines) - 1:   # the head holds no complete data line: all of it
        lines = content.splitlines()
        header_length = count_header_lines(lines, skiprows, delimiter)
    european = delimiter in (None, ";") and _decimal_comma(lines, header_length)
    if european:  # the common European export: ';' between fields, ',' the decimal mark
        delimiter = ";"
    header = lines[:header_length]
    table = _fast_body(content, header, delimiter, european)
    if table is not None:
        line_numbers: Sequence[int] = range(header_length + 1, header_length + 1 + len(table))
    else:
        lines = content.splitlines()
        if european:
            lines = header + [line.replace(",", ".") for line in lines[header_length:]]
        table, line_numbers = text_rows(lines, header_length, delimiter, path)
    ncolumns = table.shape[1]
    names = header_column_names(header, ncolumns, delimiter)
    time_index, value_index = _choose_columns(ncolumns, dt, time_column, value_column, names, path)
    unit = _text_units(header, names, value_index, units, path)
    t0 = 0.0
    if time_index is None:
        if dt is None:
            raise ValueError(f"{path} has no time column; pass dt= (sample interval [s])")
        sample_interval = dt
    else:
        sample_interval = uniform_time_step(table[:, time_index], line_numbers, path)
        t0 = float(table[0, time_index])
        if dt is not None and not math.isclose(dt, sample_interval, rel_tol=0.01):
            raise ValueError(
                f"{path}: dt={dt!r} s but the time column steps by {sample_interval!r} s"
            )
    return Record(
        dt=sample_interval,
        acceleration=table[:, value_index] * acceleration_factor(unit),
        component=names[value_index].strip() if names else "",
        description=path.stem,
        source=str(path),
        units_in_file=unit,
        t0=t0,
    )
