"""Ground motion: sampled horizontal and vertical ground accelerations.

Sign convention (stated once for the whole package, see ``docs/conventions.md``):

* ``horizontal`` is the table (ground) acceleration along +x [m/s^2].
* ``vertical`` is the table acceleration, positive **upward** [m/s^2].

Between samples the accelerations vary linearly (Section 2.8 of the report).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from shaketable.core.constants import G
from shaketable.core.equality import fields_equal

#: Shortest sample interval a motion accepts [s] (1 ns). Digitised records
#: are sampled at 0.005-0.02 s and the report's subdivision (Section 2.8)
#: divides that by a few; an interval 1e6 times shorter is a mistake, and
#: the adaptive solvers cannot advance across intervals near the spacing of
#: floating-point numbers.
MIN_SAMPLE_INTERVAL = 1e-9

#: Largest magnitude accepted for an acceleration channel [m/s^2 or rad/s^2]:
#: about 1e5 g, five orders of magnitude above the strongest records (about
#: 1.2 g in the report) and far below where squares of the values overflow.
MAX_ACCELERATION = 1e6


def _scalar(name: str, value, unit: str, *, positive: bool = False) -> float:
    """``value`` as a finite float (positive if asked), else a ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, np.integer,
                                                        np.floating)):
        raise ValueError(f"{name} must be a real number{unit}, got {value!r}")
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite{unit}, got {value!r}")
    if positive and number <= 0.0:
        raise ValueError(f"{name} must be positive{unit}, got {value!r}")
    return number


def whole_number(name: str, value, minimum: int = 1) -> int:
    """``value`` as an int >= ``minimum``, else a ValueError naming ``name``.

    Integers (Python or NumPy) and floats with an integral value (``4.0``)
    are accepted; ``2.7``, booleans, strings and non-finite values are not.
    """
    if isinstance(value, bool):
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if isinstance(value, (numbers.Integral, np.integer)):
        number = int(value)
    elif isinstance(value, (numbers.Real, np.floating)) and math.isfinite(value) \
            and float(value).is_integer():
        number = int(value)  # type: ignore[arg-type]
    else:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if number < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return number


def _bounded(name: str, array: np.ndarray, unit: str) -> np.ndarray:
    """``array`` if every value is within :data:`MAX_ACCELERATION`, else a ValueError."""
    if array.size and np.max(np.abs(array)) > MAX_ACCELERATION:
        index = int(np.argmax(np.abs(array)))
        raise ValueError(
            f"{name}[{index}] = {float(array[index])!r} {unit} exceeds the largest accepted "
            f"magnitude {MAX_ACCELERATION:g} {unit} (about 1e5 g); check the units"
        )
    return array


def _component(name: str, values, unit: str, samples: int) -> np.ndarray:
    """One component of a Motion as a checked float array of ``samples`` values."""
    array = _bounded(f"Motion.{name}", _as_float_array(f"Motion.{name}", values), unit)
    if array.size != samples:
        raise ValueError(f"Motion.{name} has {array.size} samples but Motion.t has {samples}")
    return array


def _as_float_array(name: str, values) -> np.ndarray:
    """``values`` as a new float array (never the caller's own array), checked."""
    kind = getattr(getattr(values, "dtype", None), "kind", None)
    if kind is None:
        try:
            kind = np.asarray(values).dtype.kind
        except (TypeError, ValueError):
            kind = None
    if kind in ("M", "m"):
        raise ValueError(f"{name} must be numbers (seconds or m/s^2), got datetime64/"
                         f"timedelta64 values; convert them, e.g. times in seconds as "
                         f"(t - t[0]) / np.timedelta64(1, 's')")
    if kind == "c":
        raise ValueError(f"{name} must be real numbers, got complex values (their imaginary "
                         f"part would be dropped); pass the real part if that is meant")
    try:
        array = np.array(values, dtype=float)   # a copy: the caller's array stays writable
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be an array of numbers: {error}") from None
    if array.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {array.shape}")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise ValueError(
            f"{name} contains {bad.size} non-finite value(s) (NaN or inf), "
            f"first at index {bad[0]}"
        )
    return array


def _read_only_zeros(like: np.ndarray) -> np.ndarray:
    """Zeros shaped as ``like``, read-only (as a motion's own arrays)."""
    zeros = np.zeros_like(like)
    zeros.setflags(write=False)
    return zeros


@dataclass(frozen=True)
class Motion:
    """Ground (table) acceleration history, linear between samples.

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing.
    horizontal : array_like
        Horizontal ground acceleration [m/s^2], positive along +x.
    vertical : array_like, optional
        Vertical ground acceleration [m/s^2], positive upward. ``None`` means
        no vertical component (zeros).
    name : str, optional
        A label used in plots and summaries.
    rotation : array_like, optional
        Angular acceleration of the table (pitch) [rad/s^2], positive in the
        sense of positive theta. ``None`` means a table that does not rotate.
        Its other effects (tilt of gravity, vertical acceleration at the block's
        distance from the pitch axis) are folded into ``horizontal`` and
        ``vertical`` by :mod:`shaketable.lab.command`.
    metadata : mapping, optional
        Where the motion came from, for people and for writing it back: for a
        record read through ObsPy, one entry per component (``"horizontal"``,
        ``"vertical"``) with ``network``, ``station``, ``location``,
        ``channel``, ``starttime`` (ISO 8601, UTC), ``format``, ``calib``,
        ``units_in_file`` and ``mean_removed``; for a bundled or combined
        record, ``vertical_positive`` and ``vertical_sign_source`` say how the
        vertical's sign was read. Never used by the physics. Stored as a
        read-only mapping; not compared by ``==``. Kept by :meth:`scaled`,
        :meth:`mirrored` and :meth:`subdivided`.

    Raises
    ------
    ValueError
        Non-numeric or non-finite values, fewer than 2 samples, times not
        strictly increasing or closer than :data:`MIN_SAMPLE_INTERVAL`,
        lengths that differ from ``t``, or a value beyond
        :data:`MAX_ACCELERATION`; the message names the field.

    Notes
    -----
    The arrays are copied and the copies made read-only: a motion never changes
    after it is built, running a simulation never changes it, and the caller's own
    arrays are never touched. A motion pickles (``metadata`` as a
    :class:`FrozenMapping`).
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    t: np.ndarray
    horizontal: np.ndarray
    vertical: np.ndarray | None = None
    name: str = ""
    rotation: np.ndarray | None = None
    metadata: Mapping[str, Any] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "metadata", frozen_metadata(self.metadata))
        t = _as_float_array("Motion.t", self.t)
        if t.size < 2:
            raise ValueError(f"Motion.t needs at least 2 samples, got {t.size}")
        steps = np.diff(t)
        if np.any(steps <= 0):
            index = int(np.flatnonzero(steps <= 0)[0])
            raise ValueError(
                "Motion.t must be strictly increasing; "
                f"t[{index + 1}] = {t[index + 1]!r} <= t[{index}] = {t[index]!r}"
            )
        if np.any(steps < MIN_SAMPLE_INTERVAL):
            index = int(np.flatnonzero(steps < MIN_SAMPLE_INTERVAL)[0])
            raise ValueError(
                f"Motion.t: the sample interval t[{index + 1}] - t[{index}] = "
                f"{float(steps[index])!r} s is below the shortest accepted "
                f"{MIN_SAMPLE_INTERVAL:g} s"
            )
        horizontal = _component("horizontal", self.horizontal, "m/s^2", t.size)
        vertical = (None if self.vertical is None
                    else _component("vertical", self.vertical, "m/s^2", t.size))
        rotation = (None if self.rotation is None
                    else _component("rotation", self.rotation, "rad/s^2", t.size))
        for key, value in (("t", t), ("horizontal", horizontal), ("vertical", vertical),
                           ("rotation", rotation)):
            if value is not None:
                value.setflags(write=False)
            object.__setattr__(self, key, value)

    # ------------------------------------------------------------------ builders
    @classmethod
    def from_g(cls, t, horizontal_g, vertical_g=None, name: str = "") -> "Motion":
        """Build a motion from accelerations given in units of g.

        Parameters
        ----------
        t : array_like
            Sample times [s].
        horizontal_g : array_like
            Horizontal acceleration [g].
        vertical_g : array_like, optional
            Vertical acceleration, positive upward [g].
        name : str, optional
            A label used in plots and summaries.

        Returns
        -------
        Motion
            Accelerations converted to [m/s^2].

        Raises
        ------
        ValueError
            Values that are not numbers, not finite, or of the wrong length;
            the message names the argument.
        """
        horizontal = _as_float_array("horizontal_g", horizontal_g) * G
        vertical = None if vertical_g is None else _as_float_array("vertical_g", vertical_g) * G
        return cls(t, horizontal, vertical, name=name)

    @classmethod
    def uniform(cls, dt: float, horizontal, vertical=None, t0: float = 0.0,
                name: str = "", metadata: Mapping[str, Any] | None = None) -> "Motion":
        """Build a motion sampled every ``dt`` seconds starting at ``t0``.

        Parameters
        ----------
        dt : float
            Sample interval [s], positive and at least
            :data:`MIN_SAMPLE_INTERVAL`.
        horizontal : array_like
            Horizontal acceleration [m/s^2].
        vertical : array_like, optional
            Vertical acceleration, positive upward [m/s^2].
        t0 : float, optional
            Time of the first sample [s].
        name : str, optional
            A label used in plots and summaries.
        metadata : mapping, optional
            Provenance (see :class:`Motion`).

        Returns
        -------
        Motion

        Raises
        ------
        ValueError
            ``dt`` or ``t0`` not a finite number, ``dt`` not positive, or bad
            samples; the message names the argument.
        """
        dt = _scalar("dt", dt, " [s]", positive=True)
        t0 = _scalar("t0", t0, " [s]")
        horizontal = _as_float_array("horizontal", horizontal)
        return cls(t0 + dt * np.arange(horizontal.size), horizontal, vertical, name=name,
                   metadata=metadata if metadata is not None else {})

    @classmethod
    def at_rest(cls, duration: float, dt: float = 0.005) -> "Motion":
        """A table at rest for exactly ``duration`` seconds (free rocking).

        Parameters
        ----------
        duration : float
            Length [s], positive. The last sample is at exactly ``duration``.
        dt : float, optional
            Sample interval [s], positive: samples at 0, dt, 2 dt, ... and a
            last, shorter interval ending at ``duration`` when ``duration`` is
            not a whole number of ``dt`` (a ``dt`` longer than ``duration``
            gives the two samples 0 and ``duration``).

        Returns
        -------
        Motion
            Zero horizontal acceleration, no vertical, no rotation.

        Raises
        ------
        ValueError
            ``duration`` or ``dt`` not a positive finite number.
        """
        duration = _scalar("duration", duration, " [s]", positive=True)
        dt = _scalar("dt", dt, " [s]", positive=True)
        if duration < MIN_SAMPLE_INTERVAL:
            raise ValueError(f"duration must be at least {MIN_SAMPLE_INTERVAL:g} s, "
                             f"got {duration!r}")
        from shaketable.core.validation import sample_count

        whole = sample_count(math.floor(duration / dt + 1e-9),
                             f"a table at rest for {duration:g} s at dt = {dt:g} s")
        t = np.linspace(0.0, whole * dt, whole + 1)
        if duration - t[-1] > max(1e-9 * dt, MIN_SAMPLE_INTERVAL):
            t = np.append(t, duration)   # a last, shorter interval
        else:
            t[-1] = duration             # a whole number of dt (to rounding)
        return cls(t, np.zeros(t.size), None, name="at rest")

    # ------------------------------------------------------------------ ObsPy
    @classmethod
    def from_stream(cls, stream: Any, horizontal: str | int | None = None,
                    vertical: str | int | None = None, *, units: str | None = None,
                    inventory: Any = None, remove_mean: bool | None = None,
                    vertical_positive: str = "up", name: str = "") -> "Motion":
        """Build a motion from an ObsPy ``Stream`` (response or calib, and units applied).

        A thin delegate of :func:`shaketable.ground.readers.waveform.motion_from_stream`
        (ObsPy is imported only there; the amplitude rules are in the docstring
        of :mod:`shaketable.ground.readers.waveform`).

        Parameters
        ----------
        stream : obspy.Stream or obspy.Trace
            The traces; not changed.
        horizontal, vertical : str or int, optional
            The traces to use: a channel code (``"HNE"``), a component letter
            (``"E"``) or an index. Default: the only trace, and no vertical.
        units : str, optional
            Unit of ``data * calib`` (``g``, ``m/s2``, ``cm/s2``, ``gal``);
            required unless a response or the format declares it.
        inventory : obspy.Inventory, str or os.PathLike, optional
            Station metadata, or a StationXML, dataless SEED or RESP file:
            each trace's response (``inventory.get_response(trace.id,
            trace.stats.starttime)``) divides its counts by the overall
            sensitivity, and its input units (an acceleration) are the units.
        remove_mean : bool, optional
            Default: only where the format requires it (K-NET/KiK-net).
        vertical_positive : {"up", "down"}, optional
            Direction of the vertical trace's positive values (SEED ``Z``: up).
        name : str, optional
            Motion name; default from the trace ids.

        Returns
        -------
        Motion
            Accelerations [m/s^2]; station, channel and start time in ``metadata``.

        Raises
        ------
        ValueError
            Ambiguous trace choice, units missing or contradicting, a response
            that is not an acceleration (velocity, displacement: convert with
            ObsPy's ``remove_response(output="ACC")`` first) or a trace the
            inventory has no response for.
        """
        from shaketable.ground.readers.waveform import motion_from_stream

        return motion_from_stream(stream, horizontal=horizontal, vertical=vertical, units=units,
                                  inventory=inventory, remove_mean=remove_mean,
                                  vertical_positive=vertical_positive, name=name)

    @classmethod
    def from_trace(cls, trace: Any, *, units: str | None = None, inventory: Any = None,
                   remove_mean: bool | None = None, name: str = "") -> "Motion":
        """Build a horizontal-only motion from one ObsPy ``Trace``.

        A thin delegate of :func:`shaketable.ground.readers.waveform.motion_from_stream`;
        the parameters are those of :meth:`from_stream`.
        """
        from shaketable.ground.readers.waveform import motion_from_stream

        return motion_from_stream(trace, units=units, inventory=inventory,
                                  remove_mean=remove_mean, name=name)

    def to_stream(self, *, network: str | None = None, station: str | None = None,
                  location: str | None = None, channels: Mapping[str, str] | None = None,
                  starttime: Any = None) -> Any:
        """This motion as an ObsPy ``Stream`` of accelerations [m/s^2].

        A thin delegate of :func:`shaketable.ground.readers.waveform.motion_to_stream`
        (see it for the parameters: SEED codes and the absolute start time,
        default from ``metadata``); write the result with
        ``stream.write(path, format="MSEED")`` or ``"SAC"``.
        """
        from shaketable.ground.readers.waveform import motion_to_stream

        return motion_to_stream(self, network=network, station=station, location=location,
                                channels=channels, starttime=starttime)

    # ------------------------------------------------------------------ queries
    @property
    def vertical_or_zero(self) -> np.ndarray:
        """Vertical acceleration [m/s^2], zeros when the motion has none (read-only either
        way: the compiled engines then see one array type, and numba compiles each once
        whether or not the motion has a vertical component)."""
        return self.vertical if self.vertical is not None else _read_only_zeros(self.t)

    def at(self, times) -> tuple[np.ndarray, np.ndarray]:
        """Horizontal and vertical acceleration at ``times`` [m/s^2] (linear between samples)."""
        return (np.interp(times, self.t, self.horizontal),
                np.interp(times, self.t, self.vertical_or_zero))

    def columns_in_g(self, times) -> dict[str, np.ndarray]:
        """``{"ground horizontal [g]": ..., "ground vertical [g]": ...}`` at ``times``.

        The ground columns of every result's :meth:`to_frame`, in units of g.
        """
        horizontal, vertical = self.at(times)
        return {"ground horizontal [g]": horizontal / G, "ground vertical [g]": vertical / G}

    @property
    def pitched(self) -> bool:
        """True when the motion carries a non-zero table rotation (pitch)."""
        return self.rotation is not None and bool(np.any(self.rotation != 0.0))

    @property
    def rotation_or_zero(self) -> np.ndarray:
        """Table angular acceleration [rad/s^2], zeros when the table does not rotate
        (read-only either way, as :attr:`vertical_or_zero`)."""
        return self.rotation if self.rotation is not None else _read_only_zeros(self.t)

    @property
    def duration(self) -> float:
        """Time from first to last sample [s]."""
        return float(self.t[-1] - self.t[0])

    @property
    def dt(self) -> float:
        """Median sample interval [s]."""
        return float(np.median(np.diff(self.t)))

    @property
    def pga(self) -> float:
        """Peak absolute horizontal acceleration [m/s^2]."""
        return float(np.max(np.abs(self.horizontal)))

    def scaled(self, factor: float) -> "Motion":
        """Return a copy with the horizontal and vertical multiplied by ``factor``.

        Parameters
        ----------
        factor : float
            Scale factor [-], a finite number.

        Returns
        -------
        Motion

        Raises
        ------
        ValueError
            ``factor`` is not a finite number, or the motion carries a table
            pitch (a non-zero ``rotation``) and ``factor`` is not 1.

        Notes
        -----
        The pitch is a disturbance of the table, not part of the earthquake,
        and :func:`shaketable.lab.pitch.motion_at_block` has already folded its
        tilt of gravity and tangential accelerations into ``horizontal`` and
        ``vertical``: they cannot be separated again, so scaling would scale
        the pitch with the record. Scale the table motion first, then add
        the pitch (the order :mod:`shaketable.sweeps.spec` uses). A ``rotation`` of
        zeros is kept as it is.
        """
        factor = _scalar("factor", factor, " [-]")
        if factor == 1.0:
            return Motion(self.t, self.horizontal, self.vertical, name=self.name,
                          rotation=self.rotation, metadata=self.metadata)
        if self.pitched:
            raise ValueError(
                f"cannot scale motion {self.name!r} by factor {factor!r}: it carries a table "
                "pitch (rotation), whose tilt and tangential accelerations are already in "
                "its horizontal and vertical; scale the table motion first, then add the "
                "pitch with shaketable.lab.pitch.motion_at_block"
            )
        vertical = None if self.vertical is None else self.vertical * factor
        return Motion(self.t, self.horizontal * factor, vertical, name=self.name,
                      rotation=self.rotation, metadata=self.metadata)

    def mirrored(self) -> "Motion":
        """Return the mirror image: horizontal and rotation reversed in sign."""
        rotation = None if self.rotation is None else -self.rotation
        return Motion(self.t, -self.horizontal, self.vertical, name=self.name,
                      rotation=rotation, metadata=self.metadata)

    def subdivided(self, parts: int) -> "Motion":
        """Insert ``parts - 1`` equally spaced samples in every interval.

        The report's BLOKROC subdivided each digitized interval into equal
        parts with a straight line between given points (Section 2.8); the
        linear interpolation here reproduces that exactly, for every channel
        (horizontal, vertical and rotation).

        Parameters
        ----------
        parts : int
            Number of equal parts per interval [-], an integer >= 1
            (``4.0`` is accepted, ``2.7`` is not).

        Returns
        -------
        Motion
            ``(n - 1) parts + 1`` samples; ``self`` when ``parts`` is 1.

        Raises
        ------
        ValueError
            ``parts`` is not an integer >= 1.
        """
        parts = whole_number("parts", parts)
        if parts == 1:
            return self
        fractions = np.arange(parts) / parts
        t = (self.t[:-1, None] + np.diff(self.t)[:, None] * fractions).ravel()
        t = np.append(t, self.t[-1])

        def resample(values):
            return None if values is None else np.interp(t, self.t, values)

        return Motion(t, resample(self.horizontal), resample(self.vertical),
                      name=self.name, rotation=resample(self.rotation), metadata=self.metadata)


class FrozenMapping(Mapping):
    """A read-only mapping that pickles (``types.MappingProxyType`` does not).

    Compares equal to any mapping with the same items; unhashable, like a dict.
    """

    __slots__ = ("_items",)
    _items: dict[str, Any]

    def __init__(self, items: Mapping[str, Any] | None = None) -> None:
        object.__setattr__(self, "_items", dict(items or {}))

    def __getitem__(self, key):
        return self._items[key]

    def __iter__(self):
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __setattr__(self, key, value):
        raise AttributeError("a FrozenMapping is read-only")

    def __reduce__(self):
        return (type(self), (self._items,))

    def __repr__(self) -> str:
        return f"FrozenMapping({self._items!r})"


def frozen_metadata(metadata: Mapping[str, Any] | None) -> Mapping[str, Any]:
    """A read-only copy of ``metadata`` (nested mappings frozen too); empty for ``None``."""
    if metadata is None:
        return FrozenMapping()
    if not isinstance(metadata, Mapping):
        raise ValueError(f"metadata must be a mapping, got {type(metadata).__name__}")
    return FrozenMapping({str(key): frozen_metadata(value) if isinstance(value, Mapping)
                          else value for key, value in metadata.items()})


def motion_argument(name: str, motion) -> Motion:
    """``motion`` if it is a :class:`~shaketable.core.motion.Motion`, else a ValueError naming ``name``."""
    if not isinstance(motion, Motion):
        raise ValueError(f"{name} must be a shaketable Motion, got {type(motion).__name__}")
    return motion
