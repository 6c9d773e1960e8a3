"""Records read through ObsPy (MiniSEED, SAC, K-NET, ...): trace selection and units.
ObsPy is imported lazily, on the first such read.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from shaketable.core.constants import acceleration_factor
from shaketable.ground.readers.common import Record, RecordError, units_argument


# --------------------------------------------------------------------- ObsPy
def _select_trace(stream, component, path: Path):
    if component is not None:
        key = "component" if len(component) == 1 else "channel"
        stream = stream.select(**{key: component})
    if len(stream) != 1:
        ids = [trace.id for trace in stream]
        raise RecordError(
            f"{path}: expected exactly one trace, found {len(ids)} {ids}"
            + ("" if component is None else f" with component {component!r}")
            + "; choose one with component= (a gappy trace must be merged first)"
        )
    return stream[0]


def read_obspy(path, *, units=None, component=None, format=None) -> Record:
    """Read any waveform format ObsPy understands (SAC, MiniSEED, GSE2, SEG-Y, ...).

    ObsPy is imported here only, when the function is called.

    Parameters
    ----------
    path : str or os.PathLike
        The waveform file.
    units : str
        Unit of the samples (``g``, ``m/s2``, ``cm/s2``, ``gal``): waveform
        files rarely state it reliably, so it must be given.
    component : str, optional
        One letter selects by component (last letter of the channel code, e.g.
        ``"Z"``); a longer string selects by channel code (e.g. ``"HNZ"``).
        Needed when the file holds more than one trace.
    format : str, optional
        ObsPy format name (``"SAC"``, ``"MSEED"``, ``"GSE2"``, ...); default:
        ObsPy detects it.

    Returns
    -------
    Record
        ``acceleration`` [m/s^2], ``t0 = 0`` at the trace start, ``component``
        the channel code, ``description`` the trace id and start time.

    Raises
    ------
    RecordError
        ObsPy cannot read the file, the trace choice is ambiguous, or a sample
        is not finite (the message names the file and the sample index).
    ValueError
        ``units`` missing or unknown, or a bad ``format``/``component``
        argument; the message names the file.
    """
    path = Path(path)
    if units is None:
        raise ValueError(f"{path}: waveform files do not state acceleration units reliably; "
                         "pass units= (one of 'g', 'm/s2', 'cm/s2', 'gal')")
    unit = units_argument(units, path)
    for name, value in (("format", format), ("component", component)):
        if value is not None and (not isinstance(value, str) or not value.strip()):
            raise ValueError(f"{path}: {name} must be a non-empty string, got {value!r}")
    return record_from_stream(obspy_stream(path, format), path, unit, component)


def record_from_stream(stream, path: Path, unit: str, component) -> Record:
    """The :class:`Record` of the one selected trace of an ObsPy stream."""
    trace = _select_trace(stream, component, path)
    samples = np.asarray(trace.data, dtype=float)
    bad = np.flatnonzero(~np.isfinite(samples))
    if bad.size:
        raise RecordError(f"{path}, sample {int(bad[0])}: value {samples[bad[0]]!r} is not finite")
    stats = trace.stats
    return Record(
        dt=float(stats.delta),
        acceleration=samples * acceleration_factor(unit),
        component=str(stats.channel or stats.component),
        description=f"{trace.id} starting {stats.starttime}",
        source=str(path),
        units_in_file=unit,
    )


class UnknownToObspy(RecordError):
    """ObsPy does not recognise the file's format (it may be plain text)."""


def obspy_stream(path: Path, format: str | None):
    """``obspy.read`` with errors that name the file."""
    import obspy  # the only ObsPy import in shaketable

    if not path.is_file():
        raise RecordError(f"{path}: cannot read the file: no such file")
    try:
        return obspy.read(str(path), format=None if format is None else format.upper())
    except TypeError as error:  # ObsPy's "Unknown format" / "Format ... is not supported"
        if format is None and "unknown format" in str(error).lower():
            raise UnknownToObspy(f"{path}: ObsPy does not recognise the format") from None
        raise RecordError(f"{path}: ObsPy cannot read the file: {error}") from None
    except Exception as error:  # ObsPy raises many types for unreadable files
        raise RecordError(f"{path}: ObsPy cannot read the file: {error}") from None
