"""ObsPy in and out: waveform files, ``Trace`` and ``Stream`` objects to records and motions.

This module (with :mod:`shaketable.ground.readers.strong_motion`) is the only
place in shaketable that imports ObsPy, and it does so inside the functions
that need it: ``import shaketable`` never imports ObsPy.

Amplitudes
----------
ObsPy keeps the samples as stored (often integer counts) and the factor to
physical units in ``trace.stats.calib``. Every reader here returns
the samples in physical units converted to [m/s^2]; the first of these that
applies decides how:

1. an instrument response: ``inventory=`` (an ``obspy.Inventory``, or the
   path of a StationXML, dataless SEED or RESP file that
   ``obspy.read_inventory`` reads; each trace's response is
   ``inventory.get_response(trace.id, trace.stats.starttime)``) or, without
   ``inventory=``, a response attached to the trace (``trace.stats.response``,
   from ObsPy's deprecated ``stream.attach_response(inventory)``). An explicit
   ``inventory=`` wins over an attached response, as in ObsPy's
   ``remove_response``. The samples (counts) are divided by the overall
   sensitivity (``response.instrument_sensitivity.value``, what ObsPy's
   ``remove_sensitivity`` does), ``calib`` is not applied again, and the
   response's input units (``M/S**2``, ``CM/S**2``, ``GAL``, ``G``) are the
   units;
2. the format, where it declares one: ObsPy's K-NET/KiK-net reader
   (``format="KNET"``) puts the file's ``Scale Factor`` (gal per count)
   times 0.01 in ``calib``, so ``data * calib`` is in m/s^2;
3. ``units=`` given by the caller for ``data * calib`` (required otherwise:
   SAC, MiniSEED and the other waveform formats do not state acceleration
   units reliably).

A ``units=`` that contradicts the response or the format raises
``ValueError`` (an agreeing one is accepted). Where the units came from is kept
in the record's ``metadata["units_source"]``, the sensitivity divided by in
``metadata["sensitivity"]`` (0.0 when no response was used).

Instrument responses
--------------------
* Dividing by the overall sensitivity is a flat-response correction: right
  for an accelerometer inside its pass band (the sensitivity is stated at one
  frequency). For a full deconvolution, run ObsPy's
  ``stream.remove_response(inventory=..., output="ACC")`` and read the result
  with ``units="m/s2"`` and without ``inventory=``.
* A response whose input units are a velocity (``M/S``, a seismometer) or a
  displacement (``M``) raises ``ValueError`` naming the trace and the unit:
  shaketable reads accelerations and never differentiates a record. Convert
  it with ObsPy's ``remove_response(output="ACC")`` first, as above. Any
  other non-acceleration unit (``V``, ``PA``, ...) is refused the same way.
* A trace the inventory has no response for (network, station, location,
  channel codes, or a start time outside the channel's epoch) raises
  ``ValueError`` naming the trace id, its start time and the inventory (its
  file, or the channels it holds).
* A trace whose processing history (``trace.stats.processing``) shows
  ``remove_response``, ``remove_sensitivity`` or ``simulate`` is already in
  physical units: an attached response is not applied again (``units=`` is
  then needed), and ``inventory=`` raises ``ValueError``.
* An inventory response without an overall sensitivity raises ``ValueError``
  (an attached one is ignored, as before: ``calib`` and ``units=`` apply).

Mean removal
------------
Only where the format requires it. K-NET and KiK-net ASCII files are
uncorrected records with a constant offset; NIED's format description has the
user subtract the mean, and the header's ``Max. Acc. (gal)`` is the peak after
that subtraction (obspy's own ``test.knet``: 4.383 gal after removal, 8.42 gal
before). So ``remove_mean=None`` (the default) subtracts the mean for
``format="KNET"`` only; every other format is returned as stored. Pass
``remove_mean=True`` or ``False`` to decide yourself; the choice is kept in
the record's ``metadata["mean_removed"]``.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from shaketable.core.constants import acceleration_factor
from shaketable.core.motion import Motion
from shaketable.ground.readers.common import (
    Record,
    RecordError,
    combine,
    missing_file_message,
    units_argument,
)

#: Unit of ``data * calib`` declared by the format (ObsPy's ``stats._format``).
DECLARED_UNITS = {"KNET": "m/s2"}

#: Formats whose records carry an offset that must be removed (see module docstring).
MEAN_REMOVAL_FORMATS = frozenset({"KNET"})

#: Response input units (upper case) that are accelerations, to shaketable unit names.
_RESPONSE_UNITS = {"M/S**2": "m/s2", "M/S2": "m/s2", "M/S/S": "m/s2", "M/S^2": "m/s2",
                   "CM/S**2": "cm/s2", "CM/S2": "cm/s2", "CM/S/S": "cm/s2", "CM/S^2": "cm/s2",
                   "GAL": "gal", "G": "g"}

#: Response input units (upper case) that are not accelerations but what a record of
#: acceleration integrates to: refused (shaketable does not differentiate records).
_MOTION_UNITS = {"M/S": "velocity", "M/SEC": "velocity", "CM/S": "velocity",
                 "MM/S": "velocity", "NM/S": "velocity",
                 "M": "displacement", "CM": "displacement", "MM": "displacement",
                 "NM": "displacement"}

#: ObsPy processing steps after which the samples are no longer counts.
_RESPONSE_REMOVALS = ("remove_response", "remove_sensitivity", "simulate")

#: Default channel codes written by :func:`motion_to_stream` (SEED: strong-motion
#: band H, instrument N = accelerometer, orientation 1 = a horizontal, Z = up).
DEFAULT_CHANNELS = {"horizontal": "HN1", "vertical": "HNZ"}


# --------------------------------------------------------------------- helpers
def is_obspy_waveform(value: Any) -> bool:
    """True for an ObsPy ``Trace`` or ``Stream`` (checked without importing ObsPy)."""
    module = type(value).__module__ or ""
    return module.startswith("obspy.") or module.startswith("gmprocess.") or (
        hasattr(value, "stats") and hasattr(value, "data")) or hasattr(value, "traces")


def _as_stream(value: Any) -> Any:
    """A ``Stream`` holding ``value`` (a ``Trace`` or a ``Stream``)."""
    import obspy  # the only ObsPy import in shaketable (with strong_motion.py)

    if isinstance(value, obspy.Stream):
        return value
    if isinstance(value, obspy.Trace):
        return obspy.Stream([value])
    raise ValueError(f"expected an ObsPy Trace or Stream, got {type(value).__name__}")


def select_trace(stream: Any, component: str | int | None, path: Any) -> Any:
    if isinstance(component, (int, np.integer)) and not isinstance(component, bool):
        if not -len(stream) <= int(component) < len(stream):
            raise RecordError(f"{path}: trace index {component} out of range for "
                              f"{len(stream)} traces {[trace.id for trace in stream]}")
        return stream[int(component)]
    if component is not None:
        key = "component" if len(str(component)) == 1 else "channel"
        stream = stream.select(**{key: str(component)})
    if len(stream) != 1:
        ids = [trace.id for trace in stream]
        raise RecordError(
            f"{path}: expected exactly one trace, found {len(ids)} {ids}"
            + ("" if component is None else f" with component {component!r}")
            + "; choose one with component= (a gappy trace must be merged first)"
        )
    return stream[0]


class StationInventory(NamedTuple):
    """An ObsPy ``Inventory`` and how messages name it (its file, or its channels)."""

    inventory: Any
    label: str


def load_inventory(inventory: Any) -> StationInventory | None:
    """The ``inventory=`` argument read once: ``None``, an ``obspy.Inventory`` or a path.

    Parameters
    ----------
    inventory : obspy.Inventory, str or os.PathLike, optional
        Station metadata, or a StationXML, dataless SEED or RESP file that
        ``obspy.read_inventory`` reads.

    Returns
    -------
    StationInventory or None

    Raises
    ------
    RecordError
        The file is missing or ObsPy cannot read it (the message names it).
    TypeError
        ``inventory`` is neither an inventory nor a path.
    """
    if inventory is None or isinstance(inventory, StationInventory):
        return inventory
    if isinstance(inventory, (str, os.PathLike)):
        import obspy  # the only ObsPy import in shaketable (with strong_motion.py)

        path = Path(inventory)
        if not path.is_file():
            raise RecordError(f"inventory={str(path)!r}: " + (
                "is a folder, not an inventory file" if path.is_dir() else "no such file"))
        try:
            return StationInventory(obspy.read_inventory(str(path)), f"inventory file {path}")
        except Exception as error:  # ObsPy raises many types for unreadable files
            raise RecordError(f"inventory={str(path)!r}: ObsPy cannot read it as StationXML, "
                              f"dataless SEED or RESP: {error}") from None
    if not hasattr(inventory, "get_response"):
        raise TypeError("inventory= must be an obspy.Inventory or the path of a StationXML, "
                        f"dataless SEED or RESP file, got {type(inventory).__name__}")
    channels = sorted(set(inventory.get_contents().get("channels", [])))
    shown = ", ".join(channels[:6]) + (f", ... ({len(channels)} channels)"
                                       if len(channels) > 6 else "")
    return StationInventory(inventory, f"the given inventory (channels {shown or 'none'})")


def _response_removed(stats: Any) -> str | None:
    """The ObsPy processing step that already removed the response, or None."""
    for entry in stats.get("processing", None) or ():
        for step in _RESPONSE_REMOVALS:
            if f"{step}(" in str(entry):
                return step
    return None


def _response_sensitivity(trace: Any, inventory: StationInventory | None, label: Any = ""
                          ) -> tuple[float, str, str] | None:
    """(overall sensitivity, shaketable unit name, where from) of the trace's response.

    ``None`` when there is no response to apply: no ``inventory`` and no
    attached response (or an attached one already removed, or one without an
    overall sensitivity).
    """
    stats = trace.stats
    who = trace.id if str(label or trace.id) == trace.id else f"{label}, trace {trace.id}"
    removed = _response_removed(stats)
    if inventory is not None:
        if removed:
            raise ValueError(
                f"{who}: its response was already removed ({removed} in "
                f"trace.stats.processing); dividing by the sensitivity in {inventory.label} "
                "again would be wrong: leave inventory= out and pass units= for the corrected "
                "samples (units='m/s2' after remove_response(output='ACC'))")
        try:
            response = inventory.inventory.get_response(trace.id, stats.starttime)
        except Exception as error:  # ObsPy raises a bare Exception when nothing matches
            raise ValueError(
                f"{who}: {inventory.label} has no response for this channel at "
                f"{stats.starttime} ({error}); check the network, station, location and "
                "channel codes and the channel's epoch, or leave inventory= out and pass "
                "units=") from None
        source = f"the response in {inventory.label}"
    else:
        response = stats.get("response", None)
        if response is None or removed:
            return None
        source = "its attached instrument response"
    sensitivity = getattr(response, "instrument_sensitivity", None)
    if sensitivity is None or not sensitivity.value:
        if inventory is None:
            return None  # an attached response without a sensitivity: calib and units=
        raise ValueError(f"{who}: {source} states no overall sensitivity; compute it "
                         "with ObsPy (Response.recalculate_overall_sensitivity()) or remove "
                         "the response with remove_response(output='ACC') and pass units=")
    name = str(sensitivity.input_units or "").strip()
    if name.upper() in _RESPONSE_UNITS:
        return float(sensitivity.value), _RESPONSE_UNITS[name.upper()], source
    kind = _MOTION_UNITS.get(name.upper())
    if kind is not None:
        raise RecordError(
            f"{who}: {source} has input units {name!r}, not an acceleration but a "
            f"{kind}; shaketable reads accelerations and never differentiates a record. "
            "Convert it with ObsPy first: stream.remove_response(inventory=..., "
            "output='ACC') (a full deconvolution, in m/s^2), then read the result with "
            "units='m/s2' and without inventory=")
    raise RecordError(f"{who}: {source} has input units {name!r}, not an acceleration "
                      f"(expected one of {sorted(set(_RESPONSE_UNITS))})")


def _mean_removal(remove_mean: bool | None, file_format: str) -> bool:
    if remove_mean is None:
        return file_format in MEAN_REMOVAL_FORMATS
    if not isinstance(remove_mean, (bool, np.bool_)):
        raise ValueError(f"remove_mean must be True, False or None, got {remove_mean!r}")
    return bool(remove_mean)


def trace_to_record(trace: Any, *, units: str | None = None, inventory: Any = None,
                    remove_mean: bool | None = None, source: Any = "") -> Record:
    """One ObsPy ``Trace`` as a :class:`Record` in [m/s^2] (response, calib, units, mean:
    see the module docstring).

    Parameters
    ----------
    trace : obspy.Trace
        The trace; it is not changed.
    units : str, optional
        Unit of ``data * calib`` (``g``, ``m/s2``, ``cm/s2``, ``gal``); required
        unless a response or the format declares it (then it must agree).
    inventory : obspy.Inventory, str or os.PathLike, optional
        Station metadata (or a StationXML, dataless SEED or RESP file): the
        trace's response divides the counts and gives the units.
    remove_mean : bool, optional
        Subtract the mean; default: only for formats that require it (K-NET).
    source : str or os.PathLike, optional
        File the trace came from (for messages and ``Record.source``).

    Returns
    -------
    Record
        ``acceleration`` [m/s^2], ``t0 = 0`` at the trace start, ``component``
        the channel code, ``metadata`` with ``network``, ``station``,
        ``location``, ``channel``, ``starttime``, ``format``, ``calib``,
        ``units_in_file``, ``units_source`` (``"units="``, the format, or the
        response and where it came from), ``sensitivity`` (the overall
        sensitivity divided by, counts per unit; 0.0 when no response was used)
        and ``mean_removed``.

    Raises
    ------
    ValueError
        ``units`` missing, unknown or contradicting the response or format;
        a response that is not an acceleration (velocity, displacement) or
        that the inventory does not hold; an inventory given for a trace whose
        response was already removed; :class:`RecordError` for a non-finite
        sample.
    TypeError
        ``inventory`` is neither an inventory nor a path.
    """
    label: Any = str(source) or trace.id
    stats = trace.stats
    file_format = str(stats.get("_format", "") or "").upper()
    samples = np.asarray(trace.data, dtype=float)
    bad = np.flatnonzero(~np.isfinite(samples))
    if bad.size:
        raise RecordError(f"{label}, sample {int(bad[0])}: value {samples[bad[0]]!r} "
                          "is not finite")
    given = None if units is None else units_argument(units, label)
    response = _response_sensitivity(trace, load_inventory(inventory), label)
    declared: str | None
    sensitivity = 0.0
    if response is not None:
        sensitivity, declared, how = response
        samples = samples / sensitivity
        what = "counts divided by the overall sensitivity"
    else:
        samples = samples * float(stats.calib)
        declared = DECLARED_UNITS.get(file_format)
        how, what = f"the {file_format} format", "calib applied"
    if declared is not None and given is not None \
            and acceleration_factor(given) != acceleration_factor(declared):
        raise ValueError(f"{label}: units={units!r} contradicts {how}, which gives "
                         f"{declared!r} ({what}); leave units= out")
    unit = declared or given
    if unit is None:
        removed = _response_removed(stats)
        raise ValueError(
            f"{label}: "
            + (f"its response was already removed ({removed} in trace.stats.processing), "
               "so the samples are in physical units that the trace does not name"
               if removed else "waveform files do not state acceleration units reliably")
            + "; pass units= (one of 'g', 'm/s2', 'cm/s2', 'gal') for the samples times "
            "trace.stats.calib, or inventory= (station metadata with an acceleration "
            "response)")
    mean_removed = _mean_removal(remove_mean, file_format)
    if mean_removed:
        samples = samples - samples.mean()
    metadata = {
        "network": str(stats.network), "station": str(stats.station),
        "location": str(stats.location), "channel": str(stats.channel),
        "starttime": str(stats.starttime), "format": file_format,
        "calib": float(stats.calib), "units_in_file": unit,
        "units_source": how if declared is not None else "units=",
        "sensitivity": sensitivity, "mean_removed": mean_removed,
    }
    return Record(
        dt=float(stats.delta),
        acceleration=samples * acceleration_factor(unit),
        component=str(stats.channel or stats.component),
        description=f"{trace.id} starting {stats.starttime}",
        source=str(source),
        units_in_file=unit,
        metadata=metadata,
    )


# --------------------------------------------------------------------- readers
def read_obspy(path: Any, *, units: str | None = None, component: str | int | None = None,
               format: str | None = None, remove_mean: bool | None = None,
               inventory: Any = None) -> Record:
    """Read one trace of any waveform ObsPy understands (SAC, MiniSEED, K-NET, ...).

    ObsPy is imported here only, when the function is called.

    Parameters
    ----------
    path : str, os.PathLike, obspy.Trace or obspy.Stream
        The waveform file, or a trace or stream already in memory.
    units : str, optional
        Unit of the samples times ``trace.stats.calib`` (``g``, ``m/s2``,
        ``cm/s2``, ``gal``). Required unless a response (``inventory=`` or
        attached) or the format (K-NET/KiK-net: m/s^2 after calib) declares
        it; a contradicting value raises ``ValueError``.
    component : str or int, optional
        One letter selects by component (last letter of the channel code, e.g.
        ``"Z"``); a longer string selects by channel code (e.g. ``"HNZ"``); an
        integer selects by position. Needed when there is more than one trace.
    format : str, optional
        ObsPy format name (``"SAC"``, ``"MSEED"``, ``"KNET"``, ...); default:
        ObsPy detects it. Ignored for a trace or stream.
    remove_mean : bool, optional
        Subtract the mean. Default: only for the formats that require it
        (K-NET/KiK-net, see the module docstring).
    inventory : obspy.Inventory, str or os.PathLike, optional
        Station metadata, or a StationXML, dataless SEED or RESP file
        (``obspy.read_inventory``): the trace's response
        (``inventory.get_response(trace.id, trace.stats.starttime)``) divides
        the counts by its overall sensitivity and its input units are the
        units. Replaces ObsPy's deprecated ``stream.attach_response``.

    Returns
    -------
    Record
        ``acceleration`` [m/s^2], ``t0 = 0`` at the trace start, ``component``
        the channel code, ``description`` the trace id and start time,
        ``metadata`` the station, channel, start time and how it was read.

    Raises
    ------
    RecordError
        ObsPy cannot read the file or the inventory file, the trace choice is
        ambiguous, or a sample is not finite (the message names the file and
        the sample index).
    ValueError
        ``units`` missing, unknown or contradicting the response or format; a
        response that is not an acceleration or not in the inventory (the
        message names the trace id and the inventory); a bad
        ``format``/``component`` argument; the message names the file.
    TypeError
        ``inventory`` is neither an inventory nor a path.
    """
    in_memory = not isinstance(path, (str, Path)) and is_obspy_waveform(path)
    label: Any = "ObsPy stream" if in_memory else Path(path)
    if units is not None:
        units_argument(units, label)
    for name, value in (("format", format), ("component", component)):
        if isinstance(value, (int, np.integer)) and name == "component" \
                and not isinstance(value, bool):
            continue
        if value is not None and (not isinstance(value, str) or not value.strip()):
            raise ValueError(f"{label}: {name} must be a non-empty string, got {value!r}")
    stations = load_inventory(inventory)  # a bad inventory is reported before the waveform
    stream = _as_stream(path) if in_memory else obspy_stream(label, format)
    return record_from_stream(stream, "" if in_memory else label, units, component,
                               remove_mean, stations)


def record_from_stream(stream: Any, path: Any, unit: str | None, component: Any,
                        remove_mean: bool | None = None, inventory: Any = None) -> Record:
    """The :class:`Record` of the one selected trace of an ObsPy stream."""
    trace = select_trace(stream, component, path or "ObsPy stream")
    return trace_to_record(trace, units=unit, inventory=inventory, remove_mean=remove_mean,
                           source=path)


class UnknownToObspy(RecordError):
    """ObsPy does not recognise the file's format (it may be plain text)."""


def obspy_stream(path: Path, format: str | None) -> Any:
    """``obspy.read`` with errors that name the file."""
    import obspy  # the only ObsPy import in shaketable (with strong_motion.py)

    if not path.is_file():
        raise RecordError(missing_file_message(path))
    try:
        return obspy.read(str(path), format=None if format is None else format.upper())
    except TypeError as error:  # ObsPy's "Unknown format" / "Format ... is not supported"
        if format is None and "unknown format" in str(error).lower():
            raise UnknownToObspy(f"{path}: ObsPy does not recognise the format") from None
        raise RecordError(f"{path}: ObsPy cannot read the file: {error}") from None
    except Exception as error:  # ObsPy raises many types for unreadable files
        raise RecordError(f"{path}: ObsPy cannot read the file: {error}") from None


# --------------------------------------------------------------------- Motion <-> Stream
def motion_from_stream(stream: Any, horizontal: str | int | None = None,
                       vertical: str | int | None = None, *, units: str | None = None,
                       inventory: Any = None, remove_mean: bool | None = None,
                       vertical_positive: str = "up", name: str = "") -> Motion:
    """A :class:`Motion` from an ObsPy ``Stream`` (or one ``Trace``).

    Parameters
    ----------
    stream : obspy.Stream or obspy.Trace
        The traces; not changed.
    horizontal : str or int, optional
        The horizontal trace: a channel code (``"HNE"``), a component letter
        (``"E"``, ``"1"``) or an index. Default: the only trace.
    vertical : str or int, optional
        The vertical trace, chosen the same way; default: none.
    units : str, optional
        Unit of ``data * calib`` (see the module docstring); required unless
        a response or the format declares it.
    inventory : obspy.Inventory, str or os.PathLike, optional
        Station metadata, or a StationXML, dataless SEED or RESP file: each
        chosen trace's response (``inventory.get_response(trace.id,
        trace.stats.starttime)``) divides its counts by the overall
        sensitivity and gives its units.
    remove_mean : bool, optional
        Default: only where the format requires it (K-NET/KiK-net).
    vertical_positive : {"up", "down"}, optional
        Direction of the vertical trace's positive values; SEED's ``Z`` is up
        (the default).
    name : str, optional
        Motion name; default from the trace ids.

    Returns
    -------
    Motion
        Accelerations [m/s^2] from ``t = 0`` at the traces' start; ``metadata``
        holds ``"horizontal"`` (and ``"vertical"``) with ``network``,
        ``station``, ``location``, ``channel``, ``starttime``, ``format``,
        ``calib``, ``units_in_file``, ``units_source``, ``sensitivity``,
        ``mean_removed``, plus ``vertical_positive``.

    Raises
    ------
    ValueError
        Ambiguous or missing trace choice, different sampling or start times,
        units missing or contradicting, or a response that is not an
        acceleration or not in the inventory (see :func:`trace_to_record`).
    TypeError
        ``inventory`` is neither an inventory nor a path.
    """
    stream = _as_stream(stream)
    stations = load_inventory(inventory)  # a file is read once for both traces
    chosen_h = select_trace(stream, horizontal, "ObsPy stream")
    record_h = trace_to_record(chosen_h, units=units, inventory=stations,
                               remove_mean=remove_mean)
    record_v = None
    if vertical is not None:
        chosen_v = select_trace(stream, vertical, "ObsPy stream")
        if chosen_v is chosen_h:
            raise ValueError(f"horizontal and vertical select the same trace {chosen_h.id}")
        if abs(chosen_v.stats.starttime - chosen_h.stats.starttime) > 1e-6 * chosen_h.stats.delta:
            raise ValueError(f"traces start at different times: {chosen_h.id} at "
                             f"{chosen_h.stats.starttime}, {chosen_v.id} at "
                             f"{chosen_v.stats.starttime}; trim them to a common start first")
        record_v = trace_to_record(chosen_v, units=units, inventory=stations,
                                   remove_mean=remove_mean)
    label = name or " + ".join(record.description for record in (record_h, record_v) if record)
    return combine(record_h, record_v, vertical_positive=vertical_positive, name=label)


def motion_to_stream(motion: Motion, *, network: str | None = None, station: str | None = None,
                     location: str | None = None, channels: Mapping[str, str] | None = None,
                     starttime: Any = None) -> Any:
    """Write a :class:`Motion` as an ObsPy ``Stream`` of accelerations [m/s^2].

    Parameters
    ----------
    motion : Motion
        Uniformly sampled (to 1e-9 relative); horizontal and, if present,
        vertical (positive up, as SEED's ``Z``). A table rotation is not
        written (a warning says so).
    network, station, location : str, optional
        SEED codes; default from ``motion.metadata`` (empty otherwise).
    channels : mapping, optional
        ``{"horizontal": "HNE", "vertical": "HNZ"}``; default from
        ``motion.metadata``, else :data:`DEFAULT_CHANNELS`.
    starttime : obspy.UTCDateTime or str, optional
        Absolute time of ``t = 0``; default from ``motion.metadata``, else
        1970-01-01. The first sample is at ``starttime + motion.t[0]``.

    Returns
    -------
    obspy.Stream
        float64 samples [m/s^2], ``calib = 1``; one trace per component.
        ``stream.write(path, format="MSEED")`` keeps them exactly; SAC stores
        float32.

    Raises
    ------
    ValueError
        The motion is not uniformly sampled (resample it first).
    """
    import obspy  # the only ObsPy import in shaketable (with strong_motion.py)

    steps = np.diff(motion.t)
    dt = float(steps.mean())
    if not np.allclose(steps, dt, rtol=1e-9, atol=0.0):
        raise ValueError(f"motion {motion.name!r} is not uniformly sampled (intervals from "
                         f"{steps.min()!r} to {steps.max()!r} s); resample it first")
    if motion.pitched:
        warnings.warn(f"motion {motion.name!r} carries a table rotation, which a Stream of "
                      "accelerations does not hold; it is not written", UserWarning,
                      stacklevel=2)
    components = {"horizontal": motion.horizontal}
    if motion.vertical is not None:
        components["vertical"] = motion.vertical
    traces = []
    for key, values in components.items():
        known = motion.metadata.get(key, {})
        origin = starttime if starttime is not None else known.get("starttime")
        start = obspy.UTCDateTime(origin if origin is not None else 0) + float(motion.t[0])
        header = {
            "network": network if network is not None else known.get("network", ""),
            "station": station if station is not None else known.get("station", ""),
            "location": location if location is not None else known.get("location", ""),
            "channel": (channels or {}).get(key) or known.get("channel")
            or DEFAULT_CHANNELS[key],
            "delta": dt, "starttime": start, "calib": 1.0,
        }
        traces.append(obspy.Trace(np.array(values, dtype=np.float64), header=header))
    return obspy.Stream(traces)
