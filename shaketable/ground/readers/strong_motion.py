"""Strong-motion formats read through USGS ``gmprocess`` (optional extra ``formats``).

``gmprocess`` (https://github.com/DOI-USGS/ghsc-esi-groundmotion-processing,
on PyPI) reads the formats earthquake engineers download records in: COSMOS
V0/V1/V2 (CESMD, the format the Pacoima Dam record is distributed in), CSMIP
(DMG) V1/V2, USGS SMC, K-NET/KiK-net, ESM ASCII, GeoNet, CWB, NSMN, UNAM,
RENADIC, BHRC and others. It is heavy (it pulls in OpenQuake, GeoPandas, h5py,
...), so it is an optional extra::

    pip install "shaketable[formats]"

Without it, these functions raise :class:`MissingExtraError` (an
``ImportError``) naming the extra. The PEER AT2 reader
(:func:`~shaketable.ground.readers.at2.read_at2`) stays in shaketable: no
library reads every AT2 variant well.

Amplitudes: gmprocess returns accelerations in the unit of
``trace.stats.standard.units`` (cm/s^2 for every format it reads); they are
converted to [m/s^2] here. No mean is removed: V2 files are already corrected,
and V1/V0 (uncorrected) data are returned as gmprocess gives them, which is
what the file's header ``Max`` refers to.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from shaketable.core.constants import acceleration_factor
from shaketable.core.motion import Motion
from shaketable.ground.readers.common import Record, RecordError, missing_file_message

#: The optional extra that installs gmprocess.
EXTRA = "formats"

#: gmprocess unit strings (``stats.standard.units``) to shaketable unit names.
_GMPROCESS_UNITS = {"cm/s^2": "cm/s2", "cm/s/s": "cm/s2", "cm/s**2": "cm/s2", "gal": "gal",
                    "m/s^2": "m/s2", "m/s/s": "m/s2", "m/s**2": "m/s2", "g": "g"}


class MissingExtraError(ImportError):
    """An optional dependency is not installed; the message names the extra."""


def _read_data() -> Any:
    """gmprocess's ``read_data``, or a :class:`MissingExtraError` naming the extra."""
    try:
        from gmprocess.io.read import read_data
    except ImportError as error:
        raise MissingExtraError(
            "reading COSMOS, CSMIP, SMC, K-NET/KiK-net, ESM and the other strong-motion "
            f"formats needs the optional extra {EXTRA!r}: pip install "
            f"\"shaketable[{EXTRA}]\" (it installs USGS gmprocess; import failed: {error}). "
            "PEER AT2, text, SAC, MiniSEED and K-NET (through ObsPy) are read without it"
        ) from error
    return read_data


def read_strong_motion_stream(path: str | Path) -> Any:
    """All traces of a strong-motion file as one ObsPy ``Stream``, as gmprocess reads them.

    Parameters
    ----------
    path : str or os.PathLike
        A file in any format gmprocess detects.

    Returns
    -------
    obspy.Stream
        gmprocess ``StationTrace`` objects (ObsPy traces) in the units of
        ``stats.standard.units``.

    Raises
    ------
    MissingExtraError
        gmprocess is not installed (the message names the ``formats`` extra).
    RecordError
        The file is missing or gmprocess cannot read it.
    """
    read_data = _read_data()
    import obspy  # ObsPy is imported only in shaketable.ground.readers

    path = Path(path)
    if not path.is_file():
        raise RecordError(missing_file_message(path))
    try:
        streams = read_data(str(path))
    except Exception as error:  # gmprocess raises many types for unreadable files
        raise RecordError(f"{path}: gmprocess cannot read the file: {error}") from None
    traces = [trace for stream in streams for trace in stream]
    if not traces:
        raise RecordError(f"{path}: gmprocess found no trace in the file")
    return obspy.Stream(traces)


def _record(trace: Any, path: Path) -> Record:
    standard = trace.stats.get("standard", {})
    units_type = str(standard.get("units_type", "acc")).lower()
    if units_type != "acc":
        raise RecordError(f"{path}: trace {trace.id} holds {units_type!r}, not acceleration")
    raw_unit = str(standard.get("units", "")).strip().lower()
    if raw_unit not in _GMPROCESS_UNITS:
        raise RecordError(f"{path}: trace {trace.id} has units {raw_unit!r}, which shaketable "
                          f"does not know; known: {sorted(_GMPROCESS_UNITS)}")
    unit = _GMPROCESS_UNITS[raw_unit]
    stats = trace.stats
    samples = np.asarray(trace.data, dtype=float) * float(stats.calib)
    metadata = {
        "network": str(stats.network), "station": str(stats.station),
        "location": str(stats.location), "channel": str(stats.channel),
        "starttime": str(stats.starttime),
        "format": str(standard.get("source_format", "")).upper(),
        "process_level": str(standard.get("process_level", "")),
        "horizontal_orientation": standard.get("horizontal_orientation"),
        "calib": float(stats.calib), "units_in_file": unit, "mean_removed": False,
    }
    return Record(dt=float(stats.delta), acceleration=samples * acceleration_factor(unit),
                  component=str(stats.channel), source=str(path), units_in_file=unit,
                  description=f"{trace.id} starting {stats.starttime} "
                              f"({metadata['format']} {metadata['process_level']})",
                  metadata=metadata)


def read_strong_motion(path: str | Path, *, component: str | int | None = None) -> Record:
    """One component of a COSMOS, CSMIP, SMC, K-NET, ESM, ... file as a :class:`Record`.

    Parameters
    ----------
    path : str or os.PathLike
        The file; gmprocess detects the format.
    component : str or int, optional
        Channel code (``"HN1"``), component letter (``"Z"``) or index; needed
        when the file holds more than one trace.

    Returns
    -------
    Record
        Acceleration [m/s^2]; ``metadata`` with station, channel, start time,
        ``format``, ``process_level`` and ``horizontal_orientation`` [deg].

    Raises
    ------
    MissingExtraError
        gmprocess is not installed (the message names the ``formats`` extra).
    RecordError
        Unreadable file, ambiguous component, or not an acceleration.
    """
    from shaketable.ground.readers.waveform import select_trace

    path = Path(path)
    stream = read_strong_motion_stream(path)
    return _record(select_trace(stream, component, path), path)


def load_strong_motion(path: str | Path, horizontal: str | int | None = None,
                       vertical: str | int | None = None, *, name: str = "") -> Motion:
    """A :class:`Motion` from a strong-motion file (vertical positive up).

    Parameters
    ----------
    path : str or os.PathLike
        The file; gmprocess detects the format.
    horizontal, vertical : str or int, optional
        Channel codes, component letters or indices (see
        :func:`read_strong_motion`); ``vertical=None`` leaves it out.
    name : str, optional
        Motion name; default from the trace ids.

    Returns
    -------
    Motion
        Accelerations [m/s^2]; gmprocess names the vertical channel ``Z``
        and gives it positive up.

    Raises
    ------
    MissingExtraError
        gmprocess is not installed (the message names the ``formats`` extra).
    """
    from shaketable.ground.readers.common import combine
    from shaketable.ground.readers.waveform import select_trace

    path = Path(path)
    stream = read_strong_motion_stream(path)
    record_h = _record(select_trace(stream, horizontal, path), path)
    record_v = None if vertical is None else _record(select_trace(stream, vertical, path), path)
    return combine(record_h, record_v, vertical_positive="up", name=name)
