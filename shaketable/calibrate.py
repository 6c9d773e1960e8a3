"""Coefficient of restitution from a free-rocking record (Section 3.5 of the report, done rigorously).

The report released the 30 x 6 in block from theta0 < alpha on a table at rest,
digitized the angle at 50 samples/s and overlaid BLOKROC curves for several
COR values "by eye" (Section 3.5, Fig. 3.4: COR = 0.925). Here:

* :func:`calibrate` -- least squares on the whole record with the engine in
  the loop (``method="fast"``): the COR nu, the release angle theta0, the
  release time t_r and the sensor offset c are the parameters of::

      y_k = S(F[theta(t; nu, theta0, t_r)])(t_k) + c + e_k

  where theta(t) = theta0 for t < t_r (the block is held) and the engine's
  free rocking from (theta0, 0) after it (Eqs. 2-3, 2-6: rest between the
  impacts' cascades, then theta = 0), F is the record's quantity (the angle,
  or the exact top displacement of :func:`shaketable.sensors.top_displacement`)
  and S the acquisition's anti-alias filter. S is not optional: left out,
  its smoothing of each impact's velocity jump biases nu by up to two
  standard errors (e.g. 5e-5 at nu = 0.80, 1e-5 at 0.925, nearly nothing at
  0.98, for 50 samples/s and a 20 Hz 4-pole filter; the bias changes with nu
  and theta0), and the interval then misses the truth in up to a quarter of
  the records (benchmarks/CALIBRATION.md). So by default
  (``anti_alias="fit"``) S is an analog Butterworth low-pass whose cutoff is
  a fifth parameter (order 1, 2, 4 or 8, the best fit kept), discretised
  exactly for the piecewise-linear fine-grid signal; a known filter is
  given as a :class:`~shaketable.sensors.Digitizer`.
  The 95 % interval of nu comes from the Jacobian J at the optimum with the
  sandwich covariance ``(J^T J)^-1 J^T Sigma J (J^T J)^-1``, Sigma the
  Toeplitz matrix of the residuals' autocovariance (``interval="acf"``: the
  noise of a filtered 50 samples/s record is correlated, lag-1 ~ 0.1, but
  stationary); ``"hac"`` (Newey-West, per-sample e_t e_s: robust to
  heteroscedastic noise but noisier, 6 % narrower on average on the benchmark's
  records),
  ``"iid"`` the textbook ``s^2 (J^T J)^-1``, and ``bootstrap=N`` a
  moving-block bootstrap.
* :func:`peak_estimate` -- an independent estimate from successive peak
  amplitudes with the exact energy relation (Eq. 2-6; theory.amplitude_after_impact)::

      cos(alpha - theta_{n+1}) - cos(alpha) = nu^2 [cos(alpha - theta_n) - cos(alpha)]

  fitted as log E_n = log E_0 + 2 n log nu, and the COR of each impact against
  its impact velocity (the report's Section 3.7 (1) claim that the COR does
  not depend on it becomes a slope with an interval).
* :func:`period_fit` -- periods measured the report's way (time from a peak
  to the next zero, times 4; Section 3.7 (1), Table 3.1) fitted with the exact
  period of Eq. (2-3) (:func:`shaketable.theory.exact_period`) for the
  block's effective size R and slenderness alpha.
* :func:`predict`, :func:`compare_free_rocking`, :func:`reproduce_fig_3_4` --
  the calibrated COR fed back into the theory run (Section 3.7 (1), Fig. 3.4).

Inputs are :class:`Record` objects (time and angle, or time and top
displacement with the block height), built directly, from a
:class:`~shaketable.sensors.Measurement` or read from a CSV or plain-text file
(:func:`read_record`).
A record without rocking, too short, clipped or too noisy raises
:class:`CalibrationError` with a message saying which.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, *Rocking and overturning
   response of rigid bodies to earthquake motions*, Lawrence Berkeley
   Laboratory, University of California, Berkeley (program BLOKROC).
"""

from __future__ import annotations

import functools
import json
import math
import numbers
import time as _time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.optimize
import scipy.signal
import scipy.stats

from .constants import INCH, LENGTH_UNITS
from .geometry import Block
from .motion import Motion
from .sensors import Digitizer, Measurement, theta_from_top_displacement, top_displacement
from .simulate import simulate
from .theory import exact_period, impact_velocity

__all__ = [
    "ANGLE_UNITS",
    "ANTI_ALIAS",
    "FILTER_ORDERS",
    "INTERVALS",
    "QUANTITIES",
    "Calibration",
    "CalibrationError",
    "FreeRockingComparison",
    "PeakEstimate",
    "PeriodFit",
    "Record",
    "butterworth_delay",
    "calibrate",
    "compare_free_rocking",
    "covariance_of",
    "noise_level",
    "peak_estimate",
    "period_fit",
    "predict",
    "read_record",
    "reproduce_fig_3_4",
    "virtual_free_rocking_record",
]

#: What a record can hold.
QUANTITIES = ("angle", "top displacement")
#: Angle units accepted at the edges, name -> radians.
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0, "mrad": 1e-3}
#: Ways of computing the interval from the Jacobian.
INTERVALS = {"acf": "sandwich covariance with the residuals' autocovariance (stationary noise)",
             "hac": "Newey-West (autocorrelation-consistent) sandwich covariance",
             "iid": "s^2 (J^T J)^-1, independent residuals"}
#: Butterworth orders tried by ``calibrate(filter_order="auto")``.
FILTER_ORDERS = (1, 2, 4, 8)
#: Ways of modelling the acquisition's anti-alias filter (``calibrate(anti_alias=)``).
ANTI_ALIAS = {"fit": "Butterworth low-pass, cutoff fitted", "known": "the given Digitizer's filter",
              "none": "no filter"}
#: Order of the parameters in vectors and covariance matrices (a fifth, ``filter_u`` =
#: tau^2 [s^2] of the fitted filter, follows with ``anti_alias="fit"``; ``t_release`` is
#: there the apparent release time, see :class:`Calibration`).
PARAMETERS = ("cor", "theta0", "t_release", "offset")


class CalibrationError(ValueError):
    """A record that cannot give a COR: no rocking, too short, clipped, too noisy."""


# ------------------------------------------------------------------ record
@dataclass(frozen=True)
class Record:
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
    """

    t: np.ndarray
    values: np.ndarray
    quantity: str = "angle"
    height: float | None = None
    clipped: np.ndarray | None = None
    name: str = ""

    def __post_init__(self):
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
    def from_angle(cls, t, theta, *, units: str = "rad", name: str = "") -> "Record":
        """Record of the angle, in ``units`` (rad, deg, mrad)."""
        factor = _unit_factor(units, ANGLE_UNITS, "units")
        return cls(t, np.asarray(theta, dtype=float) * factor, "angle", name=name)

    @classmethod
    def from_top_displacement(cls, t, displacement, *, height: float | None = None,
                              units: str = "m", name: str = "") -> "Record":
        """Record of the top displacement in ``units`` (m, cm, mm, in, ft); ``height`` [m]."""
        factor = _unit_factor(units, LENGTH_UNITS, "units")
        return cls(t, np.asarray(displacement, dtype=float) * factor, "top displacement",
                   height=height, name=name)

    @classmethod
    def from_measurement(cls, measurement: Measurement,
                         quantity: str = "top displacement") -> "Record":
        """The potentiometer channel of a :class:`~shaketable.sensors.Measurement`.

        ``quantity="angle"`` takes the report's angle (top displacement / height).
        """
        if not isinstance(measurement, Measurement):
            raise ValueError(f"measurement must be a Measurement, got "
                             f"{type(measurement).__name__}")
        if measurement.top_displacement is None:
            raise ValueError("the measurement has no potentiometer channel")
        values = (measurement.top_displacement if quantity == "top displacement"
                  else measurement.theta)
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
        """Factor and unit for plots: rad for angles, in for displacements."""
        return (1.0, "rad") if self.quantity == "angle" else (1.0 / INCH, "in")

    def to_quantity(self, theta, block: Block) -> np.ndarray:
        """The record's quantity for rotations ``theta`` [rad] (no offset)."""
        if self.quantity == "angle":
            return np.asarray(theta, dtype=float)
        height = self.height if self.height is not None else block.height
        return top_displacement(theta, _wire_block(block, height))

    def to_angle(self, values, block: Block) -> np.ndarray:
        """Rotation [rad] of quantity ``values`` (exact inversion for displacements)."""
        if self.quantity == "angle":
            return np.asarray(values, dtype=float)
        height = self.height if self.height is not None else block.height
        return theta_from_top_displacement(values, _wire_block(block, height))


def _wire_block(block: Block, height: float) -> Block:
    return block if height == block.height else Block(height, block.width)


def _unit_factor(unit, table, name):
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


def _is_time_name(name: str) -> bool:
    lowered = name.strip().lower()
    return lowered.startswith("time") or lowered.split(" ")[0] in ("t", "t[s]", "t(s)")


def _record_from_columns(path: Path, t, values, units: str, column: str, height) -> Record:
    unit_key = units.strip().lower()
    if unit_key in ANGLE_UNITS:
        return Record.from_angle(t, values, units=unit_key, name=path.stem)
    if unit_key in LENGTH_UNITS:
        return Record.from_top_displacement(t, values, units=unit_key, height=height,
                                            name=path.stem)
    raise ValueError(f"{path}: unknown unit {units!r} of column {column!r}; expected an angle "
                     f"({sorted(ANGLE_UNITS)}) or a length ({sorted(LENGTH_UNITS)})")


def _check_rate(rate) -> float:
    if isinstance(rate, bool) or not isinstance(rate, numbers.Real) or not (
            math.isfinite(rate) and rate > 0):
        raise ValueError(f"rate must be a positive number [samples/s], got {rate!r}")
    return float(rate)


def _is_csv_with_header(lines: list[str]) -> bool:
    """True when the first line that is neither blank nor a comment is a comma-separated header."""
    from .records import _is_number

    for line in lines:
        stripped = line.strip()
        if not stripped or stripped[0] in "#%":
            continue
        fields = [field.strip() for field in stripped.split(",")]
        return len(fields) > 1 and not _is_number(fields[0])
    return False


def read_record(path, *, column: str | int | None = None, units: str | None = None,
                rate: float | None = None, height: float | None = None) -> Record:
    """Read a free-rocking record from a CSV or plain-text file.

    Two layouts are read:

    * CSV with a header row (``time [s],top displacement [in]``), by pandas;
    * anything else -- whitespace-, comma- or semicolon-separated columns,
      with or without a header line (``time theta`` or none at all) -- by the
      package's text-record machinery (:func:`shaketable.records.read_text`'s
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
    rate : float, optional
        Samples per second [1/s], for a file without a time column
        (a column named ``time ...`` or ``t ...``, in seconds; in a headerless
        file of two or more columns, the first).
    height : float, optional
        Height of the wire [m] for a top displacement (default: the block's).

    Raises
    ------
    FileNotFoundError
        No such file.
    ValueError
        Naming the file (and line) for a missing column or unit or a value
        that is not a number (:class:`shaketable.records.RecordError` from
        the text reader is a ValueError).
    """
    from .records import _read_lines

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such record file")
    if rate is not None:
        rate = _check_rate(rate)
    lines = _read_lines(path)
    if not _is_csv_with_header(lines):
        return _read_text_record(path, lines, column=column, units=units, rate=rate,
                                 height=height)
    import pandas as pd

    try:
        frame = pd.read_csv(path, comment="#", skipinitialspace=True)
    except Exception as error:     # pandas raises several parser errors
        raise ValueError(f"{path}: not a readable CSV file ({error})") from None
    names = [str(name).strip() for name in frame.columns]
    frame.columns = names
    time_names = [name for name in names if _is_time_name(name)]
    if isinstance(column, (int, np.integer)) and not isinstance(column, bool):
        if not -len(names) <= column < len(names):
            raise ValueError(f"{path}: column {column} but the file has {len(names)} columns "
                             f"{names}")
        column = names[column]
    if column is None:
        candidates = [name for name in names if name not in time_names]
        if len(candidates) != 1:
            raise ValueError(f"{path}: give --column, one of {candidates}")
        column = candidates[0]
    if column not in names:
        raise ValueError(f"{path}: no column {column!r}; columns are {names}")
    if units is None:
        units = _unit_in_name(column)
        if units is None:
            raise ValueError(f"{path}: column {column!r} has no unit in brackets; give --units "
                             f"(angle: {sorted(ANGLE_UNITS)}, length: {sorted(LENGTH_UNITS)})")

    def numbers_of(name):
        values = pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            line = _data_line(path, int(bad[0]))
            raise ValueError(f"{path}, line {line}: column {name!r} holds "
                             f"{frame[name].iloc[bad[0]]!r}, not a number")
        return values

    values = numbers_of(column)
    if time_names:
        t = numbers_of(time_names[0])
    elif rate is not None:
        t = np.arange(values.size) / rate
    else:
        raise ValueError(f"{path}: no time column (a column named 'time [s]'); give --rate")
    return _record_from_columns(path, t, values, units, column, height)


def _read_text_record(path: Path, lines, *, column, units, rate, height) -> Record:
    """Headerless or whitespace-separated record, through shaketable.records' text tokenizer."""
    from .records import _column_names, _header_length, _text_rows

    first = _header_length(lines, None, None)
    header = lines[:first]
    table, line_numbers = _text_rows(lines, first, None, path)
    ncolumns = table.shape[1]
    names = _column_names(header, ncolumns, None)
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
    if names:
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
        t = table[:, time_index]
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


# ------------------------------------------------------------------ signal helpers
def noise_level(values) -> float:
    """Robust estimate of the white-noise RMS of a smooth record [its unit].

    The median absolute fourth difference, scaled: for white noise of RMS
    sigma the fourth difference has RMS sqrt(70) sigma, and MAD/0.6745 is the
    RMS of a Gaussian. A free-rocking angle sampled at 50 Hz contributes
    ~ p^4 theta dt^4 ~ 1e-5 rad, below typical noise; correlated (filtered)
    noise is underestimated, so use this for checks only.
    """
    values = np.asarray(values, dtype=float)
    if values.size < 8:
        return float(np.std(values))
    fourth = np.diff(values, 4)
    return float(np.median(np.abs(fourth - np.median(fourth))) / 0.6745 / math.sqrt(70.0))


def _crossings(theta: np.ndarray, threshold: float) -> list[int]:
    """Indices i where theta changes sign between i and i+1, with hysteresis ``threshold``."""
    crossings, state = [], 0
    last_index = None
    for index, value in enumerate(theta):
        if value > threshold:
            sign = 1
        elif value < -threshold:
            sign = -1
        else:
            continue
        if state != 0 and sign != state:
            # the actual crossing: last sample of the old sign before this index
            segment = theta[last_index:index + 1] * state
            inside = np.flatnonzero(segment > 0)
            crossings.append(last_index + int(inside[-1]))
        if sign != state or last_index is None:
            pass
        state = sign
        last_index = index
    return crossings


@dataclass(frozen=True)
class _Peaks:
    times: np.ndarray        # [s]
    amplitudes: np.ndarray   # |theta| [rad]
    signs: np.ndarray
    zeros: np.ndarray        # time of the zero crossing after each peak [s] (NaN if none)
    first_is_release: bool
    zeros_before: np.ndarray = None   # time of the zero crossing before each peak [s]


def _zero_time(t, theta, index):
    """Linear interpolation of the zero of theta between samples index and index+1 [s]."""
    a, b = theta[index], theta[index + 1]
    return float(t[index] + (t[index + 1] - t[index]) * a / (a - b))


def _find_peaks(t, theta, block: Block, sigma: float, *, plateau_end: float | None = None):
    """Peaks of a free-rocking angle: one extreme between successive zero crossings.

    Each peak is refined by a least-squares parabola over the samples within a
    quarter of the local quarter-period of the sample maximum (the solution
    near a turning point is a parabola to O(tau^4)). The first segment, which
    holds the release, takes its amplitude from the samples before
    ``plateau_end`` when the record starts before the release.
    """
    threshold = max(4.0 * sigma, 1e-3 * block.alpha)
    crossings = _crossings(theta, threshold)
    bounds = [0] + [c + 1 for c in crossings] + [theta.size]
    times, amplitudes, signs, zeros, before = [], [], [], [], []
    first_is_release = False
    for number, (start, stop) in enumerate(zip(bounds[:-1], bounds[1:])):
        segment = theta[start:stop]
        if segment.size == 0:
            continue
        sign = 1.0 if np.median(segment) >= 0 else -1.0
        local = int(np.argmax(segment * sign)) + start
        amplitude = abs(theta[local])
        if amplitude <= threshold or amplitude >= block.alpha:
            continue
        zero = (_zero_time(t, theta, crossings[number]) if number < len(crossings)
                else math.nan)
        before.append(_zero_time(t, theta, crossings[number - 1]) if number >= 1 else math.nan)
        if number == 0 and plateau_end is not None and plateau_end > t[0] + 2 * (t[1] - t[0]):
            held = (t < plateau_end) & (t >= t[0])
            times.append(float(plateau_end))
            amplitudes.append(float(abs(np.median(theta[held]))))
            signs.append(sign)
            zeros.append(zero)
            first_is_release = True
            continue
        quarter = exact_period(block, min(amplitude, 0.95 * block.alpha)) / 4.0
        window = (np.abs(t - t[local]) <= 0.25 * quarter) & (np.arange(t.size) >= start) & (
            np.arange(t.size) < stop)
        if np.count_nonzero(window) >= 3 and start < local < stop - 1:
            tau = t[window] - t[local]
            c2, c1, c0 = np.polyfit(tau, theta[window], 2)
            if c2 * sign < 0:
                vertex = -c1 / (2 * c2)
                if abs(vertex) <= np.max(np.abs(tau)):
                    times.append(float(t[local] + vertex))
                    amplitudes.append(float(abs(c0 - c1 * c1 / (4 * c2))))
                    signs.append(sign)
                    zeros.append(zero)
                    continue
        if start == 0 or stop == theta.size:
            before.pop()
            continue            # an extreme cut by the record's ends is not a peak
        times.append(float(t[local]))
        amplitudes.append(float(amplitude))
        signs.append(sign)
        zeros.append(zero)
    return _Peaks(np.array(times), np.array(amplitudes), np.array(signs), np.array(zeros),
                  first_is_release, np.array(before))


# ------------------------------------------------------------------ peak method
@dataclass(frozen=True)
class PeakEstimate:
    """COR from successive peak amplitudes (Eq. 2-6 between impacts).

    Attributes
    ----------
    cor : float
        Constant COR fitted to all peaks [-]: log E_n = log E_0 + 2 n log(cor),
        E_n = cos(alpha - theta_n) - cos(alpha).
    cor_interval : tuple of float
        95 % interval of ``cor`` (weighted regression, t quantile) [-].
    peak_times, amplitudes : ndarray
        Times [s] and amplitudes |theta_n| [rad] of the peaks used.
    cor_per_impact, cor_per_impact_se : ndarray
        sqrt(E_{n+1} / E_n) for each impact and its standard error [-].
    impact_velocity : ndarray
        Angular velocity reached before each impact, from theta_n by energy
        conservation (:func:`shaketable.theory.impact_velocity`) [rad/s].
    slope, slope_se, intercept : float
        Weighted linear trend of the per-impact COR against the impact
        velocity [s/rad], its standard error, and the intercept [-]: a slope
        consistent with 0 supports the report's Section 3.7 (1).
    """

    cor: float
    cor_interval: tuple
    peak_times: np.ndarray
    amplitudes: np.ndarray
    cor_per_impact: np.ndarray
    cor_per_impact_se: np.ndarray
    impact_velocity: np.ndarray
    slope: float
    slope_se: float
    intercept: float

    @property
    def velocity_independent(self) -> bool:
        """True when the 95 % interval of the trend's slope contains 0."""
        return bool(abs(self.slope) <= 1.96 * self.slope_se) if np.isfinite(self.slope) else True


def peak_estimate(record: Record, block: Block, *, offset: float = 0.0,
                  t_release: float | None = None, min_amplitude: float | None = None,
                  sigma: float | None = None) -> PeakEstimate:
    """COR from successive peaks with the exact energy relation between impacts.

    Between impacts energy is conserved; an impact scales the energy of
    rotation by COR^2 (Eq. 2-6, :func:`shaketable.theory.amplitude_after_impact`),
    so with E_n = cos(alpha - theta_n) - cos(alpha) (potential energy at the
    n-th peak over M g R), E_{n+1} = COR^2 E_n exactly for free rocking.

    Parameters
    ----------
    record : Record
    block : Block
        Gives alpha (and the height for a displacement record).
    offset : float
        Sensor offset removed first [record unit].
    t_release : float, optional
        Release time [s] when the record starts with the block held.
    min_amplitude : float, optional
        Smallest amplitude used [rad] (default max(20 sigma, 0.03 alpha)):
        below it the peak's relative error grows as sigma / theta_n.
    sigma : float, optional
        Noise RMS of the angle [rad] (default :func:`noise_level`).
    """
    theta = record.to_angle(record.values - offset, block)
    sigma = noise_level(theta) if sigma is None else sigma
    peaks = _find_peaks(record.t, theta, block, sigma, plateau_end=t_release)
    floor = max(20.0 * sigma, 0.03 * block.alpha) if min_amplitude is None else min_amplitude
    keep = peaks.amplitudes >= floor
    # keep the leading run of consecutive peaks above the floor
    last = int(np.argmin(keep)) if not np.all(keep) else keep.size
    amplitudes, times = peaks.amplitudes[:last], peaks.times[:last]
    if amplitudes.size < 3:
        raise CalibrationError(
            f"only {amplitudes.size} peak(s) above {floor:.3g} rad: too short or too little "
            "rocking for the peak method (3 are needed)")
    alpha = block.alpha
    energy = np.cos(alpha - amplitudes) - math.cos(alpha)
    # d E / d theta = sin(alpha - theta): the standard error of log E_n is sigma_n sin()/E
    sigma_peak = max(sigma, 1e-12) * np.ones_like(amplitudes)
    log_se = sigma_peak * np.sin(alpha - amplitudes) / energy
    n = np.arange(amplitudes.size, dtype=float)
    weights = 1.0 / log_se**2
    design = np.column_stack([np.ones_like(n), n])
    wls = design * np.sqrt(weights)[:, None]
    coefficients, *_ = np.linalg.lstsq(wls, np.log(energy) * np.sqrt(weights), rcond=None)
    residual = (np.log(energy) - design @ coefficients) * np.sqrt(weights)
    dof = max(amplitudes.size - 2, 1)
    # the scatter about the line measures the peaks' real noise (sigma from noise_level is a
    # rough guess): scale by it, with the t quantile for the few degrees of freedom
    scale = float(np.sum(residual**2) / dof) if amplitudes.size > 3 else 1.0
    covariance = np.linalg.inv(wls.T @ wls) * scale
    slope, slope_se = coefficients[1], math.sqrt(covariance[1, 1])
    quantile = scipy.stats.t.ppf(0.975, dof)
    cor = math.exp(slope / 2.0)
    interval = (math.exp((slope - quantile * slope_se) / 2.0),
                math.exp((slope + quantile * slope_se) / 2.0))
    per_impact = np.sqrt(energy[1:] / energy[:-1])
    per_impact_se = 0.5 * per_impact * np.sqrt(log_se[1:]**2 + log_se[:-1]**2)
    velocity = np.array([impact_velocity(block, a) for a in amplitudes[:-1]])
    trend_slope = trend_se = math.nan
    intercept = float(np.mean(per_impact))
    if per_impact.size >= 3 and np.ptp(velocity) > 0:
        w = 1.0 / per_impact_se**2
        a = np.column_stack([np.ones_like(velocity), velocity]) * np.sqrt(w)[:, None]
        fit, *_ = np.linalg.lstsq(a, per_impact * np.sqrt(w), rcond=None)
        res = per_impact * np.sqrt(w) - a @ fit
        scale = max(float(np.sum(res**2) / max(per_impact.size - 2, 1)), 1.0)
        cov = np.linalg.inv(a.T @ a) * scale
        intercept, trend_slope, trend_se = float(fit[0]), float(fit[1]), math.sqrt(cov[1, 1])
    return PeakEstimate(cor=cor, cor_interval=interval, peak_times=times, amplitudes=amplitudes,
                        cor_per_impact=per_impact, cor_per_impact_se=per_impact_se,
                        impact_velocity=velocity, slope=trend_slope, slope_se=trend_se,
                        intercept=intercept)


# ------------------------------------------------------------------ period fit
@dataclass(frozen=True)
class PeriodFit:
    """Effective block size from periods alone (Table 3.1 / Fig. 3.6).

    Attributes
    ----------
    amplitudes, periods : ndarray
        Peak amplitude [rad] and the report's period, 4 x (time from the peak
        to the next zero) [s] (Section 3.7 (1)).
    R, R_se : float
        Fitted corner-to-centroid distance [m] and its standard error.
    alpha, alpha_se : float
        Fitted block angle [rad] (held at the nominal value, se 0, when
        ``fit_alpha`` is False).
    nominal : Block or None
        The block the user named, for comparison.
    rms : float
        RMS of the period residuals [s].
    method : str
        How the periods were measured: ``"zeros"`` or ``"report"``.
    """

    amplitudes: np.ndarray
    periods: np.ndarray
    R: float
    R_se: float
    alpha: float
    alpha_se: float
    nominal: Block | None
    rms: float
    method: str = "zeros"

    @property
    def block(self) -> Block:
        """The effective block: height 2 R cos(alpha), width 2 R sin(alpha)."""
        return Block.from_slenderness(self.R, self.alpha)

    def curve(self, amplitudes, R: float | None = None, alpha: float | None = None):
        """Exact period [s] at ``amplitudes`` [rad] for (R, alpha) (default: fitted)."""
        block = Block.from_slenderness(self.R if R is None else R,
                                       self.alpha if alpha is None else alpha)
        return np.array([exact_period(block, a) if 0 < a < block.alpha else math.nan
                         for a in np.atleast_1d(amplitudes)])


def period_fit(record: Record, block: Block, *, offset: float = 0.0,
               t_release: float | None = None, fit_alpha: bool = True,
               sigma: float | None = None, method: str = "zeros") -> PeriodFit:
    """Fit the exact period of Eq. (2-3) to the record's periods for R (and alpha).

    Each peak after the release gives a period at amplitude theta_n:

    * ``method="zeros"`` (default): twice the time between the zero crossings
      (impacts) around the peak. Free rocking between two impacts is
      symmetric, so this is exactly half the period at theta_n, and zero
      crossings (where |theta'| is largest) are timed far more precisely
      than peaks.
    * ``method="report"``: 4 x (time from the peak to the next zero), the
      report's measurement (Section 3.7 (1), Table 3.1).

    The exact period
    T(theta; R, alpha) (:func:`shaketable.theory.exact_period`; p = sqrt(3 g / 4 R))
    is fitted by least squares, starting from ``block``.

    Raises
    ------
    CalibrationError
        Fewer than 3 periods (2 with ``fit_alpha=False``).
    """
    theta = record.to_angle(record.values - offset, block)
    sigma = noise_level(theta) if sigma is None else sigma
    peaks = _find_peaks(record.t, theta, block, sigma, plateau_end=t_release)
    if method not in ("zeros", "report"):
        raise ValueError(f"method must be 'zeros' or 'report', got {method!r}")
    if method == "report":
        measured = 4.0 * (peaks.zeros - peaks.times)
    else:
        measured = 2.0 * (peaks.zeros - peaks.zeros_before)
    use = np.isfinite(measured) & (peaks.amplitudes > max(10 * sigma, 0.05 * block.alpha))
    if peaks.first_is_release:
        use[0] = False          # the release time is not a measured peak
    amplitudes = peaks.amplitudes[use]
    periods = measured[use]
    needed = 3 if fit_alpha else 2
    if amplitudes.size < needed:
        raise CalibrationError(f"only {amplitudes.size} measurable period(s): too short or too "
                               f"little rocking for the period fit ({needed} are needed)")

    def residuals(x):
        R, alpha = x[0], (x[1] if fit_alpha else block.alpha)
        trial = Block.from_slenderness(R, alpha)
        return np.array([exact_period(trial, min(a, 0.999 * alpha)) for a in amplitudes]) - periods

    x0 = [block.R, block.alpha] if fit_alpha else [block.R]
    upper = [10 * block.R, 0.45 * math.pi] if fit_alpha else [10 * block.R]
    lower = [0.1 * block.R, 1.001 * float(np.max(amplitudes))] if fit_alpha else [0.1 * block.R]
    if fit_alpha and lower[1] >= x0[1]:
        x0[1] = 1.05 * lower[1]
    solution = scipy.optimize.least_squares(residuals, x0, bounds=(lower, upper),
                                            x_scale=[block.R, block.alpha][:len(x0)])
    dof = max(amplitudes.size - len(x0), 1)
    s2 = float(np.sum(solution.fun**2) / dof)
    try:
        cov = np.linalg.inv(solution.jac.T @ solution.jac) * s2
        se = np.sqrt(np.diag(cov))
    except np.linalg.LinAlgError:
        se = np.full(len(x0), math.nan)
    return PeriodFit(amplitudes=amplitudes, periods=periods, R=float(solution.x[0]),
                     R_se=float(se[0]),
                     alpha=float(solution.x[1]) if fit_alpha else block.alpha,
                     alpha_se=float(se[1]) if fit_alpha else 0.0, nominal=block,
                     rms=float(np.sqrt(np.mean(solution.fun**2))), method=method)


# ------------------------------------------------------------------ the model
def butterworth_delay(order: int) -> float:
    """Low-frequency group delay of a Butterworth low-pass in units of 1 / omega_c [-].

    The normalised poles p_k = exp(i pi (2k + N - 1) / (2N)), k = 1..N, lie on the
    unit circle, so the delay at omega -> 0, sum_k -Re(1 / p_k) / omega_c, is
    sum_k sin((2k - 1) pi / (2N)) / omega_c: 2.6131 / omega_c for N = 4
    (0.0208 s at 20 Hz), 1.4142 / omega_c for N = 2, 1 / omega_c for N = 1.
    """
    k = np.arange(1, int(order) + 1)
    return float(np.sum(np.sin((2 * k - 1) * math.pi / (2 * int(order)))))


@functools.lru_cache(maxsize=8)
def _butterworth_prototype(order: int):
    """Modal form of the analog Butterworth low-pass with omega_c = 1 rad/s.

    Returns (poles, V, V^-1 B_1, C_1 V) of a state-space realisation
    (A_1, B_1, C_1) with A_1 = V diag(poles) V^-1 (the poles are distinct).
    """
    zeros, poles, gain = scipy.signal.butter(order, 1.0, analog=True, output="zpk")
    a_matrix, b_matrix, c_matrix, _ = scipy.signal.zpk2ss(zeros, poles, gain)
    eigenvalues, vectors = np.linalg.eig(a_matrix)
    return (eigenvalues, vectors, np.linalg.solve(vectors, b_matrix.astype(complex)),
            c_matrix @ vectors)


def _analog_butterworth_foh(order: int, tau: float, dt: float):
    """Modal first-order-hold discretisation of an analog Butterworth low-pass (omega_c = 1/tau).

    H(s) = H_1(s tau) with H_1 the unit-cutoff prototype, so A = A_1 / tau,
    B = B_1 / tau, C = C_1. The first-order hold (as
    ``scipy.signal.cont2discrete(method="foh")``) is exact when the input is
    linear between the fine-grid points, for any cutoff, even one above the
    fine grid's Nyquist frequency, and tends to the identity as tau -> 0. In
    modal form, with x_i = p_i dt / tau, the state of mode i obeys
    z_i[k+1] = e^{x_i} z_i[k] + beta_i u[k] with
    beta_i = [(e^x - 1)/x - (e^x - 1 - x)/x^2 + e^x (e^x - 1 - x)/x^2] b_i dt / tau,
    and y[k] = sum_i c_i z_i[k] + D u[k], D = sum_i c_i (e^x - 1 - x)/x^2 b_i dt / tau.
    Parallel first-order sections stay well conditioned where a polynomial
    transfer function of order 8 with poles clustered near z = 1 does not.

    Returns
    -------
    (alpha, gain, direct)
        Complex mode poles e^{x_i}, complex gains c_i beta_i, and the real
        feed-through D.
    """
    poles, vectors, b_modal, c_modal = _butterworth_prototype(int(order))
    x = poles * (dt / tau)
    exponential = np.exp(x)
    small = np.abs(x) < 1e-4
    safe = np.where(small, 1.0, x)
    first = np.where(small, 1.0 + x / 2.0, np.expm1(x) / safe)
    second = np.where(small, 0.5 + x / 6.0, (np.expm1(x) - x) / safe**2)
    b = b_modal[:, 0] * (dt / tau)
    c = c_modal[0, :]
    beta = (first - second + exponential * second) * b
    direct = float(np.real(np.sum(c * second * b)))
    return exponential, c * beta, direct


def _foh_filter(coefficients, values, initial: float):
    """Apply :func:`_analog_butterworth_foh` coefficients, at rest on ``initial`` before."""
    alpha, gain, direct = coefficients
    out = direct * values
    for pole, weight in zip(alpha, gain):
        state = weight * initial / (1.0 - pole)            # steady state of the mode
        section, _ = scipy.signal.lfilter([0.0, weight], [1.0, -pole],
                                          values.astype(complex), zi=[state])
        out = out + np.real(section)
    return out


#: Smallest filter time constant modelled [s]: below it the fitted filter is the identity.
_TAU_FLOOR = 1e-6


class _Model:
    """Record-space prediction y(t_k; x) with the engine in the loop.

    ``x = (cor, theta0, t_release, offset)`` and, when the anti-alias filter is
    fitted (``filter="fit"``), a fifth parameter u = tau^2 [s^2], the square of
    the time constant tau = 1 / (2 pi f_c) of an analog Butterworth low-pass of
    ``order`` poles. The fitted filter is delay-compensated: the model is
    S_tau[F theta](t + d tau) (d = :func:`butterworth_delay`), so that
    ``t_release`` stays the *apparent* release time (the filter's delay stays
    in it, as without a filter) and u enters at second order; u = 0 is the
    unfiltered model, reached smoothly, which keeps the Jacobian regular there.
    """

    def __init__(self, record: Record, block: Block, mode: str, digitizer: Digitizer | None,
                 order: int, rtol: float, method: str = "fast"):
        self.record, self.block, self.mode, self.rtol = record, block, mode, rtol
        self.digitizer, self.order, self.method = digitizer, int(order), method
        self.evaluations = 0
        self.delay = butterworth_delay(self.order)
        if mode == "known":
            self.fine_dt = 1.0 / (digitizer.rate * digitizer.oversample)
        elif mode == "fit":
            self.fine_dt = record.dt / 8.0
        self._filters = {}

    @property
    def size(self) -> int:
        """Number of parameters."""
        return 5 if self.mode == "fit" else 4

    def theta(self, cor, theta0, t_release, times):
        """Rotation [rad] at ``times`` [s] (held at theta0 before the release)."""
        self.evaluations += 1
        tau = times - t_release
        after = tau > 0
        out = np.full(times.shape, theta0)
        if not np.any(after):
            return out
        grid = np.concatenate([[0.0], tau[after]])
        run = simulate(self.block, Motion(grid, np.zeros_like(grid)), cor=cor, theta0=theta0,
                       rtol=self.rtol, method=self.method)
        values = run.theta
        if values.size < grid.size:            # the run stopped (overturned): hold the end
            values = np.concatenate([values[:grid.size], np.full(grid.size - values.size,
                                                                 values[-1])])
        out[after] = values[1:grid.size]
        return out

    def _filter(self, tau):
        key = float(tau)
        if key not in self._filters:
            if len(self._filters) > 64:
                self._filters.clear()
            self._filters[key] = _analog_butterworth_foh(self.order, tau, self.fine_dt)
        return self._filters[key]

    def cutoff(self, x) -> float:
        """Cutoff frequency [Hz] of the filter in the model (inf: none)."""
        if self.mode == "known":
            return float(self.digitizer.cutoff) if self.digitizer.anti_alias else math.inf
        if self.mode == "fit":
            tau = math.sqrt(max(float(x[4]), 0.0))
            return 1.0 / (2.0 * math.pi * tau) if tau > _TAU_FLOOR else math.inf
        return math.inf

    def __call__(self, x) -> np.ndarray:
        cor, theta0, t_release, offset = x[:4]
        t = self.record.t
        if self.mode == "none":
            return self.record.to_quantity(self.theta(cor, theta0, t_release, t),
                                           self.block) + offset
        # run on a fine grid from the release, filter (at rest on the held value before
        # it), read at the samples
        shift = 0.0
        if self.mode == "fit":
            tau = math.sqrt(max(float(x[4]), 0.0))
            shift = self.delay * tau
        span = t[-1] - t_release + shift
        fine = self.fine_dt * np.arange(int(math.ceil(max(span, 0.0) / self.fine_dt)) + 2)
        theta = self.theta(cor, theta0, 0.0, fine)
        theta[0] = theta0
        quantity = self.record.to_quantity(theta, self.block)
        if self.mode == "known":
            filtered = self.digitizer.apply_filter(quantity)
        elif tau > _TAU_FLOOR:
            filtered = _foh_filter(self._filter(tau), quantity, quantity[0])
        else:
            filtered = quantity
        return np.interp(t - t_release + shift, fine, filtered, left=quantity[0]) + offset


def _jacobian(model, x, steps, lower, upper):
    """Central differences, one-sided where a step would cross a bound."""
    columns = []
    for index, step in enumerate(steps):
        up, down = np.array(x, dtype=float), np.array(x, dtype=float)
        up[index] = min(up[index] + step, upper[index])
        down[index] = max(down[index] - step, lower[index])
        columns.append((model(up) - model(down)) / (up[index] - down[index]))
    return np.column_stack(columns)


def _bandwidth(n: int) -> int:
    """Lag window: 4 (n / 100)^(2/9), Newey and West's automatic choice."""
    return max(2, int(math.ceil(4.0 * (n / 100.0) ** (2.0 / 9.0))))


def _autocovariance(residuals, lags: int) -> np.ndarray:
    """Biased sample autocovariance gamma_k = sum e_t e_{t+k} / n, k = 0..lags [unit^2]."""
    n = residuals.size
    return np.array([float(residuals[:n - k] @ residuals[k:]) / n for k in range(lags + 1)])


def _covariance(jacobian, residuals, method: str, lags: int):
    """Covariance of the least-squares parameters, ``(J^T J)^-1 M (J^T J)^-1``.

    * ``"acf"``: M = J^T Sigma J with Sigma the Toeplitz matrix of the residuals'
      Bartlett-tapered sample autocovariance to ``lags`` (stationary noise:
      one autocovariance for the whole record, estimated from all n samples;
      positive semi-definite by the Bartlett taper);
    * ``"hac"``: Newey-West, M = sum_t sum_s w(|t-s|) e_t e_s J_t^T J_s;
    * ``"iid"``: M = s^2 J^T J.

    All are scaled by n / (n - k) for the k fitted parameters.
    """
    n, k = jacobian.shape
    bread = np.linalg.inv(jacobian.T @ jacobian)
    if method == "iid":
        return bread * float(residuals @ residuals) / (n - k)
    if method == "acf":
        gamma = _autocovariance(residuals, lags)
        meat = gamma[0] * (jacobian.T @ jacobian)
        for lag in range(1, lags + 1):
            weight = 1.0 - lag / (lags + 1.0)
            cross = jacobian[lag:].T @ jacobian[:-lag]
            meat += weight * gamma[lag] * (cross + cross.T)
        return bread @ meat @ bread * n / (n - k)
    scores = jacobian * residuals[:, None]
    meat = scores.T @ scores
    for lag in range(1, lags + 1):
        weight = 1.0 - lag / (lags + 1.0)
        gamma = scores[lag:].T @ scores[:-lag]
        meat += weight * (gamma + gamma.T)
    return bread @ meat @ bread * n / (n - k)


def covariance_of(calibration: "Calibration", interval: str) -> np.ndarray:
    """The covariance of a calibration's parameters computed with another ``interval`` method.

    Parameters
    ----------
    calibration : Calibration
    interval : str
        One of :data:`INTERVALS`.

    Returns
    -------
    ndarray
        k x k covariance, in the order of ``calibration.parameters``.
    """
    if interval not in INTERVALS:
        raise ValueError(f"interval must be one of {sorted(INTERVALS)}, got {interval!r}")
    return _covariance(calibration.jacobian, calibration.residuals, interval,
                       int(calibration.goodness["lags"]))


# ------------------------------------------------------------------ calibration result
@dataclass(frozen=True)
class Calibration:
    """The COR identified from one free-rocking record.

    Attributes
    ----------
    record : Record
    block : Block
    cor : float
        Least-squares COR [-].
    cor_interval : tuple of float
        95 % interval of the COR [-] (``interval_method``).
    cor_se : float
        Standard error of the COR [-].
    theta0, theta0_se : float
        Release angle and standard error [rad].
    t_release, t_release_se : float
        Release time and standard error [s]: when the block left theta0, the
        modelled filter's delay removed (with ``anti_alias="none"`` the
        apparent release, delay included).
    offset, offset_se : float
        Sensor offset and standard error [record unit: rad or m].
    covariance : ndarray
        Covariance of the fitted parameters (``parameters``): 4 x 4, or 5 x 5
        with the fitted filter (its ``t_release`` is the apparent one).
    interval_method : str
        ``"acf"``, ``"hac"`` or ``"iid"`` (see :data:`INTERVALS`), or ``"bootstrap"``.
    bootstrap_interval : tuple or None
        Percentile interval of the moving-block bootstrap [-].
    bootstrap_cors : ndarray or None
        The bootstrap replicates [-].
    fitted, residuals : ndarray
        Model and record minus model at the samples [record unit].
    goodness : dict
        rms [unit], noise estimate [unit], R^2 [-], lag-1 autocorrelation of
        the residuals [-], samples, lags of the covariance, evaluations, time [s].
    peaks : PeakEstimate or None
        The independent peak-amplitude estimate (None if it failed).
    periods : PeriodFit or None
        The period fit (None if it failed).
    notes : tuple of str
        Warnings (parameters at a bound, failed side methods).
    anti_alias : str
        How the acquisition's filter was modelled: ``"fit"``, ``"known"`` or
        ``"none"`` (:data:`ANTI_ALIAS`).
    filter_order : int
        Poles of the modelled Butterworth filter.
    filter_cutoff : float
        Its cutoff [Hz] (fitted or given; inf for none).
    filter_delay : float
        Its low-frequency group delay [s] (:func:`butterworth_delay` / (2 pi f_c)).
    t_release_apparent : float
        Release time plus the filter's delay [s]: where the record's release
        shows (the theory runs of :func:`compare_free_rocking` start there).
    parameters : tuple of str
        Names of the fitted parameters, in the covariance's order.
    jacobian : ndarray
        d(model)/d(parameters) at the optimum, n x k [record unit / parameter
        unit], from which ``covariance`` was made (:func:`covariance_of`
        recomputes it another way).
    """

    record: Record
    block: Block
    cor: float
    cor_interval: tuple
    cor_se: float
    theta0: float
    theta0_se: float
    t_release: float
    t_release_se: float
    offset: float
    offset_se: float
    covariance: np.ndarray
    interval_method: str
    fitted: np.ndarray
    residuals: np.ndarray
    goodness: dict
    peaks: PeakEstimate | None = None
    periods: PeriodFit | None = None
    bootstrap_interval: tuple | None = None
    bootstrap_cors: np.ndarray | None = None
    notes: tuple = field(default_factory=tuple)
    anti_alias: str = "none"
    filter_order: int = 4
    filter_cutoff: float = math.inf
    filter_delay: float = 0.0
    t_release_apparent: float | None = None
    parameters: tuple = PARAMETERS
    jacobian: np.ndarray | None = field(default=None, repr=False)

    @property
    def confidence(self) -> float:
        """Level of ``cor_interval`` [-]."""
        return 0.95

    def to_frame(self):
        """Record, fit and residuals as a :class:`pandas.DataFrame` (units in the names)."""
        import pandas as pd

        scale, unit = self.record.display_scale()
        return pd.DataFrame({
            "time [s]": self.record.t,
            f"record [{unit}]": self.record.values * scale,
            f"fitted [{unit}]": self.fitted * scale,
            f"residual [{unit}]": self.residuals * scale,
            "theta fitted [rad]": self.record.to_angle(self.fitted - self.offset, self.block),
        })

    def summary(self) -> dict:
        """JSON-ready scalar results (units in the keys)."""
        unit = "rad" if self.record.quantity == "angle" else "m"
        data = {
            "record": self.record.name, "quantity": self.record.quantity,
            "block_height [m]": self.block.height, "block_width [m]": self.block.width,
            "cor [-]": self.cor, "cor_low [-]": self.cor_interval[0],
            "cor_high [-]": self.cor_interval[1],
            "cor_interval [-]": [float(self.cor_interval[0]), float(self.cor_interval[1])],
            "cor_interval_level [-]": self.confidence, "cor_se [-]": self.cor_se,
            "interval": self.interval_method,
            "anti_alias": self.anti_alias, "filter_order": self.filter_order,
            "filter_cutoff [Hz]": self.filter_cutoff, "filter_delay [s]": self.filter_delay,
            "theta0 [rad]": self.theta0, "theta0_se [rad]": self.theta0_se,
            "theta0/alpha [-]": self.theta0 / self.block.alpha,
            "t_release [s]": self.t_release, "t_release_se [s]": self.t_release_se,
            "t_release_apparent [s]": self.t_release_apparent,
            f"offset [{unit}]": self.offset, f"offset_se [{unit}]": self.offset_se,
        }
        data.update({f"fit {key}": value for key, value in self.goodness.items()})
        if self.bootstrap_interval is not None:
            data["bootstrap_low [-]"], data["bootstrap_high [-]"] = self.bootstrap_interval
            data["bootstrap_samples"] = int(self.bootstrap_cors.size)
        if self.peaks is not None:
            data.update({"peak_cor [-]": self.peaks.cor,
                         "peak_cor_low [-]": self.peaks.cor_interval[0],
                         "peak_cor_high [-]": self.peaks.cor_interval[1],
                         "peaks_used": int(self.peaks.amplitudes.size),
                         "cor_vs_velocity_slope [s/rad]": self.peaks.slope,
                         "cor_vs_velocity_slope_se [s/rad]": self.peaks.slope_se,
                         "cor_velocity_independent": self.peaks.velocity_independent})
        if self.periods is not None:
            effective = self.periods.block
            data.update({"period_fit_R [m]": self.periods.R,
                         "period_fit_R_se [m]": self.periods.R_se,
                         "period_fit_alpha [rad]": self.periods.alpha,
                         "period_fit_alpha_se [rad]": self.periods.alpha_se,
                         "period_fit_height [m]": effective.height,
                         "period_fit_width [m]": effective.width,
                         "period_fit_rms [s]": self.periods.rms})
        data["notes"] = list(self.notes)
        return {key: _clean(value) for key, value in data.items()}

    def to_json(self, path=None) -> str:
        """The summary as JSON text; written to ``path`` when given."""
        text = json.dumps(self.summary(), indent=2)
        if path is not None:
            Path(path).write_text(text + "\n")
        return text

    def plot(self, fig=None, title: str | None = None):
        """Record, fitted curve, residuals, COR per impact and periods (PNG-ready figure)."""
        from .calibration_plots import plot_calibration

        return plot_calibration(self, fig=fig, title=title)

    def predict(self, motion: Motion | None = None, **kwargs):
        """The theory run with the calibrated COR (see :func:`predict`)."""
        return predict(self, motion, **kwargs)

    @property
    def digits(self) -> int:
        """Decimals worth printing for the COR: one beyond the interval's half-width."""
        half = 0.5 * (self.cor_interval[1] - self.cor_interval[0])
        return max(4, int(math.ceil(-math.log10(half))) + 1) if half > 0 else 6

    def text(self) -> str:
        """One-paragraph human summary."""
        low, high = self.cor_interval
        digits = self.digits
        unit = "rad" if self.record.quantity == "angle" else "m"
        if self.anti_alias == "fit":
            filter_text = (f"fitted {self.filter_order}-pole filter: none"
                           if not math.isfinite(self.filter_cutoff) else
                           f"fitted {self.filter_order}-pole filter at {self.filter_cutoff:.3g} Hz")
        elif self.anti_alias == "known":
            filter_text = f"given {self.filter_order}-pole filter at {self.filter_cutoff:.3g} Hz"
        else:
            filter_text = "no filter modelled"
        lines = [f"COR = {self.cor:.{digits}f}  (95 % interval {low:.{digits}f} to "
                 f"{high:.{digits}f}, {self.interval_method}; {filter_text})",
                 f"release angle {self.theta0:.5f} rad = {self.theta0 / self.block.alpha:.3f} "
                 f"alpha at t = {self.t_release:.3f} s; fit rms {self.goodness['rms']:.3g} "
                 f"{unit}, R^2 {self.goodness['r_squared']:.6f}"]
        if self.bootstrap_interval is not None:
            lines.append(f"bootstrap ({self.bootstrap_cors.size}): "
                         f"{self.bootstrap_interval[0]:.{digits}f} to "
                         f"{self.bootstrap_interval[1]:.{digits}f}")
        if self.peaks is not None:
            p = self.peaks
            lines.append(f"peak method: COR = {p.cor:.4f} ({p.cor_interval[0]:.4f} to "
                         f"{p.cor_interval[1]:.4f}) from {p.amplitudes.size} peaks; COR vs "
                         f"impact velocity slope {p.slope:+.4f} +- {1.96 * p.slope_se:.4f} s/rad"
                         + (" (no dependence)" if p.velocity_independent else " (DEPENDS)"))
        if self.periods is not None:
            e = self.periods.block
            lines.append(f"period fit: R = {self.periods.R:.4f} m, alpha = "
                         f"{self.periods.alpha:.4f} rad -> {e.height / INCH:.2f} x "
                         f"{e.width / INCH:.2f} in (nominal {self.block.describe()})")
        lines.extend(f"note: {note}" for note in self.notes)
        return "\n".join(lines)


def _clean(value):
    if isinstance(value, (float, np.floating)):
        return None if not np.isfinite(value) else float(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


# ------------------------------------------------------------------ calibrate
def _check_record(record: Record, block: Block, stroke: float | None):
    """Clear messages for records that cannot give a COR. Returns (theta, sigma)."""
    t, values = record.t, record.values
    if t.size < 20:
        raise CalibrationError(f"record {record.name!r} has {t.size} samples: too short "
                               "(at least 20 are needed)")
    flags = np.zeros(t.size, dtype=bool) if record.clipped is None else record.clipped.copy()
    if stroke is not None:
        flags |= np.abs(values) >= stroke * (1 - 1e-9)
    # a flat top: a run of equal samples at the record's extreme lasting >= 0.08 s (and >= 4
    # samples), away from the start (where the block may be held). A free-rocking peak curves
    # by p^2 sin(alpha - theta) tau^2 / 2 ~ 1e-3 rad over +-0.04 s, several ADC steps.
    shortest = max(4, int(math.ceil(0.08 / record.dt)))
    for extreme in (np.max(values), np.min(values)):
        at = np.flatnonzero(np.abs(values - extreme) <= 1e-12 * max(1.0, abs(extreme)))
        if at.size >= shortest and at[0] > 0.1 * t.size:
            runs = np.split(at, np.flatnonzero(np.diff(at) > 1) + 1)
            if max(len(run) for run in runs) >= shortest:
                flags[at] = True
    if np.any(flags):
        first = int(np.flatnonzero(flags)[0])
        raise CalibrationError(
            f"record {record.name!r} is clipped ({np.count_nonzero(flags)} samples, first at "
            f"t = {t[first]:.3f} s): the sensor's range was reached, the peaks are lost")
    # the offset is the reading at rest: the end of the record if the block rests there
    tail = values[-max(5, t.size // 10):]
    at_rest = np.std(tail) < 0.02 * np.ptp(values)
    offset_guess = float(np.median(tail)) if at_rest else 0.0
    theta = record.to_angle(values - offset_guess, block)
    sigma = noise_level(theta)
    amplitude = float(np.max(np.abs(theta)))
    if amplitude >= block.alpha:
        raise CalibrationError(f"record {record.name!r} exceeds alpha ({amplitude:.3f} rad > "
                               f"{block.alpha:.3f} rad): not free rocking (overturning?)")
    crossings = _crossings(theta, max(4 * sigma, 1e-3 * block.alpha))
    if amplitude < 10 * sigma or amplitude < 0.01 * block.alpha or not crossings:
        raise CalibrationError(
            f"record {record.name!r} shows no rocking: largest excursion {amplitude:.3g} rad "
            f"({amplitude / block.alpha:.3f} alpha), noise {sigma:.3g} rad, "
            f"{len(crossings)} zero crossing(s)")
    if sigma > 0.05 * amplitude:
        raise CalibrationError(
            f"record {record.name!r} is too noisy to decide: noise {sigma:.3g} rad is "
            f"{100 * sigma / amplitude:.1f} % of the amplitude {amplitude:.3g} rad (limit 5 %)")
    if len(crossings) < 2:
        raise CalibrationError(
            f"record {record.name!r} is too short: {len(crossings)} impact(s) in "
            f"{record.duration:.2f} s; at least 2 are needed to separate the COR from the "
            "release angle")
    return theta, sigma, offset_guess, crossings


def _filter_mode(anti_alias):
    """("none" | "known" | "fit", Digitizer or None) for the ``anti_alias`` argument."""
    if anti_alias is None or (isinstance(anti_alias, str) and anti_alias == "none"):
        return "none", None
    if isinstance(anti_alias, str) and anti_alias == "fit":
        return "fit", None
    if isinstance(anti_alias, Digitizer):
        return ("known", anti_alias) if anti_alias.anti_alias else ("none", None)
    raise ValueError(f"anti_alias must be 'fit', 'none', None or a shaketable.sensors.Digitizer, "
                     f"got {anti_alias!r}")


def calibrate(record: Record, block: Block, *, anti_alias="fit", filter_order="auto",
              interval: str = "acf", bootstrap: int = 0, seed: int | None = None,
              stroke: float | None = None, rtol: float = 1e-9,
              max_interval: float = 0.05) -> Calibration:
    """Identify the COR, release angle, release time and offset of a free-rocking record.

    Parameters
    ----------
    record : Record
        The whole record (may begin before the release and end long after rest).
    block : Block
        The nominal block (Eq. 2-3 needs alpha and p).
    anti_alias : {"fit", "none", None} or Digitizer
        The acquisition's anti-alias filter in the model. ``"fit"`` (default,
        for an acquisition whose filter is not known): an analog Butterworth
        low-pass of ``filter_order`` poles whose cutoff is a fifth parameter
        (from no filter at all to 0.05 x the sample rate). This removes the
        bias an unmodelled filter leaves in the COR (its smoothing of each
        impact's velocity jump: e.g. 5e-5 at COR 0.80, 1e-5 at 0.925 for the
        report's 50 samples/s with a 20 Hz filter, up to two standard errors;
        benchmarks/CALIBRATION.md), and its uncertainty enters the interval.
        A :class:`~shaketable.sensors.Digitizer`: that known filter, exactly.
        ``"none"``/``None``: no filter (a record known to be unfiltered; the
        delay of an unknown filter is then absorbed by the release time, its
        smoothing is not).
    filter_order : int or "auto"
        Poles of the fitted Butterworth filter (``anti_alias="fit"``), 1 to 8.
        ``"auto"`` (default) fits each of :data:`FILTER_ORDERS` (1, 2, 4, 8
        poles) and keeps the smallest residual sum of squares: a wrong order
        leaves a model error that the interval does not cover (a 2-pole
        10 Hz filter fitted as 4-pole: 78-88 % coverage, chosen: 94-98 %,
        benchmarks/CALIBRATION.md), and it shows in the residuals.
    interval : str
        ``"acf"`` (default), ``"hac"`` or ``"iid"``, see :data:`INTERVALS`.
    bootstrap : int
        Number of moving-block bootstrap refits (0: none). The blocks are
        4 x the lag window long; the percentile interval is stored in
        ``bootstrap_interval`` and becomes ``cor_interval``.
    seed : int, optional
        Seed of the bootstrap.
    stroke : float, optional
        Range of the sensor [record unit]; values at it count as clipped.
    rtol : float
        Relative tolerance of the engine in the loop [-].
    max_interval : float
        Largest acceptable half-width of the 95 % interval [-]; wider means
        the record is too noisy to decide.

    Returns
    -------
    Calibration

    Raises
    ------
    CalibrationError
        No rocking, too short, clipped or too noisy (the message says which).
    ValueError
        Bad arguments, naming the argument.
    """
    started = _time.perf_counter()
    if not isinstance(record, Record):
        raise ValueError(f"record must be a shaketable.calibrate.Record, got "
                         f"{type(record).__name__}")
    if not isinstance(block, Block):
        raise ValueError(f"block must be a shaketable.Block, got {type(block).__name__}")
    if interval not in INTERVALS:
        raise ValueError(f"interval must be one of {sorted(INTERVALS)}, got {interval!r}")
    mode, digitizer = _filter_mode(anti_alias)
    if not (isinstance(filter_order, str) and filter_order == "auto") and (
            isinstance(filter_order, (bool, str)) or not isinstance(filter_order, numbers.Real)
            or int(filter_order) != filter_order or not 1 <= filter_order <= 8):
        raise ValueError(f"filter_order must be 'auto' or an integer from 1 to 8, got "
                         f"{filter_order!r}")
    if isinstance(bootstrap, bool) or int(bootstrap) != bootstrap or bootstrap < 0:
        raise ValueError(f"bootstrap must be a non-negative integer, got {bootstrap!r}")
    theta, sigma, offset_guess, crossings = _check_record(record, block, stroke)

    # ---- initial guess from the record: release angle from the first extreme, release time
    # from the first zero crossing minus the exact quarter period, COR from the peaks
    t = record.t
    first_zero = _zero_time(t, theta, crossings[0])
    first_segment = theta[:crossings[0] + 1]
    sign = 1.0 if np.median(first_segment) > 0 else -1.0
    theta0_guess = float(np.median(first_segment[np.abs(first_segment) >= 0.98 * np.max(
        np.abs(first_segment))])) if first_segment.size else theta[0]
    theta0_guess = sign * min(max(abs(theta0_guess), 1e-4), 0.98 * block.alpha)
    t_release_guess = first_zero - exact_period(block, abs(theta0_guess)) / 4.0
    notes = []
    try:
        cor_guess = peak_estimate(record, block, offset=offset_guess,
                                  t_release=t_release_guess if t_release_guess > t[0] else None,
                                  sigma=sigma).cor
    except CalibrationError:
        cor_guess = 0.9
    cor_guess = float(np.clip(cor_guess, 0.3, 0.999))

    unit_scale = float(np.max(np.abs(record.values - offset_guess)))
    lower = [0.05, 0.0 if sign > 0 else -0.999 * block.alpha, t[0] - 5.0, -np.inf]
    upper = [1.0, 0.999 * block.alpha if sign > 0 else 0.0, first_zero, np.inf]
    scales = [0.01, 0.01 * block.alpha, 0.01, max(sigma, 1e-6 * unit_scale)]
    if record.quantity == "top displacement":
        height = record.height if record.height is not None else block.height
        scales[3] = max(sigma * height, 1e-9)
    steps = [2e-4, 2e-4 * block.alpha, 2e-3 * record.dt * 5, max(1e-6 * unit_scale, 1e-12)]

    def solve(model, x0, low, high, scale, **options):
        x0 = np.clip(x0, np.array(low) + 1e-12, np.array(high) - 1e-12)
        return scipy.optimize.least_squares(lambda x: record.values - model(x), x0,
                                            bounds=(low, high), x_scale=np.array(scale),
                                            diff_step=1e-5, **options)

    tight = dict(xtol=1e-10, ftol=1e-12, gtol=1e-10, max_nfev=400)
    # stage 1: the unfiltered model, cheap (the engine at the samples only)
    plain = _Model(record, block, "none", None, 4, rtol)
    solution = solve(plain, np.array([cor_guess, theta0_guess, t_release_guess, offset_guess]),
                     lower, upper, scales, **tight)
    x = solution.x
    models = [plain]  # every model made: their runs of the engine add up to the cost
    model = plain
    if mode == "known":
        # the known filter: its delay leaves the release time
        model = _Model(record, block, "known", digitizer, digitizer.filter_order, rtol)
        models.append(model)
        x[2] -= butterworth_delay(digitizer.filter_order) / (2 * math.pi * digitizer.cutoff)
    elif mode == "fit":
        tau_max = 1.0 / (2.0 * math.pi * 0.05 * record.rate)
        tau_start = 1.0 / (2.0 * math.pi * 0.4 * record.rate)
        lower, upper = lower + [0.0], upper + [tau_max**2]
        scales = scales + [tau_start**2]
        steps = steps + [0.05 * tau_start**2]
        # stage 2: the filtered model from the unfiltered optimum, for each candidate order;
        # the smallest residual sum of squares wins
        # (chi-square differences between orders are > 1, so a loose tolerance ranks them)
        orders = FILTER_ORDERS if filter_order == "auto" else (int(filter_order),)
        loose = dict(xtol=1e-6, ftol=1e-7, gtol=1e-8, max_nfev=200) if len(orders) > 1 else tight
        best = None
        for order in orders:
            candidate = _Model(record, block, "fit", None, order, rtol)
            trial = solve(candidate, np.append(x, tau_start**2), lower, upper, scales, **loose)
            models.append(candidate)
            if best is None or trial.cost < best[1].cost:
                best = (candidate, trial)
        model, solution = best
        if len(orders) > 1:
            solution = solve(model, solution.x, lower, upper, scales, **tight)
    if mode == "known":
        # stage 2: the known filter, from the unfiltered optimum
        solution = solve(model, x, lower, upper, scales, **tight)
    x = solution.x
    fitted = model(x)
    res = record.values - fitted
    jacobian = _jacobian(model, x, steps, lower, upper)
    lags = _bandwidth(t.size)
    covariance = _covariance(jacobian, res, interval, lags)
    se = np.sqrt(np.clip(np.diag(covariance), 0.0, None))
    quantile = scipy.stats.t.ppf(0.975, t.size - x.size)
    cor_interval = (max(0.0, x[0] - quantile * se[0]), min(1.0, x[0] + quantile * se[0]))
    method = interval
    if x[0] >= 0.9999:
        notes.append("the COR reached its bound 1: the record shows no energy loss")

    # the release time: the fitted one is apparent (it holds the fitted filter's delay)
    apparent = float(x[2])
    t_release, t_release_se = apparent, float(se[2])
    cutoff = model.cutoff(x)
    delay = 0.0
    if mode == "fit":
        tau = math.sqrt(max(float(x[4]), 0.0))
        delay = model.delay * tau
        t_release = apparent - delay
        if tau > _TAU_FLOOR:
            gradient = np.zeros(x.size)
            gradient[2], gradient[4] = 1.0, -model.delay / (2.0 * tau)
            t_release_se = float(math.sqrt(max(gradient @ covariance @ gradient, 0.0)))
        if x[4] <= 1e-12 * upper[4]:
            notes.append("the fitted anti-alias filter reached no filter at all")
        elif x[4] >= 0.999 * upper[4]:
            notes.append(f"the fitted anti-alias filter reached its lowest cutoff "
                         f"{cutoff:.3g} Hz: the record looks smoothed beyond a plain filter")
    elif mode == "known":
        delay = butterworth_delay(digitizer.filter_order) / (2 * math.pi * digitizer.cutoff)
        apparent = t_release + delay

    boot_interval = boot = None
    if bootstrap:
        rng = np.random.default_rng(seed)
        length = 4 * lags
        boot = []
        for _ in range(int(bootstrap)):
            starts = rng.integers(0, t.size - length + 1, size=int(math.ceil(t.size / length)))
            sample = np.concatenate([res[s:s + length] for s in starts])[:t.size]
            sample = sample - np.mean(sample) + np.mean(res)
            target = fitted + sample
            replicate = scipy.optimize.least_squares(
                lambda y: target - model(y), x, bounds=(lower, upper), x_scale=np.array(scales),
                diff_step=1e-5, max_nfev=100)
            boot.append(replicate.x[0])
        boot = np.array(boot)
        boot_interval = (float(np.percentile(boot, 2.5)), float(np.percentile(boot, 97.5)))
        cor_interval, method = boot_interval, "bootstrap"

    half_width = 0.5 * (cor_interval[1] - cor_interval[0])
    if not np.isfinite(half_width) or half_width > max_interval:
        raise CalibrationError(
            f"record {record.name!r} is too noisy to decide: the COR's 95 % interval is "
            f"{cor_interval[0]:.3f} to {cor_interval[1]:.3f} (half-width {half_width:.3f} > "
            f"{max_interval})")

    total = float(np.sum((record.values - np.mean(record.values))**2))
    lag1 = float(np.corrcoef(res[:-1], res[1:])[0, 1]) if res.size > 2 else math.nan
    peaks = periods = None
    release = apparent if apparent > t[0] else None
    try:
        peaks = peak_estimate(record, block, offset=float(x[3]), t_release=release, sigma=sigma)
    except CalibrationError as error:
        notes.append(f"peak method: {error}")
    try:
        periods = period_fit(record, block, offset=float(x[3]), t_release=release, sigma=sigma)
    except CalibrationError as error:
        notes.append(f"period fit: {error}")
    goodness = {
        "rms": float(np.sqrt(np.mean(res**2))),
        "noise_estimate": float(sigma if record.quantity == "angle"
                                else sigma * (record.height or block.height)),
        "r_squared": 1.0 - float(res @ res) / total if total > 0 else math.nan,
        "residual_lag1_autocorrelation": lag1,
        "samples": int(t.size),
        "lags": int(lags),
        "engine_runs": int(sum(made.evaluations for made in models)),  # Jacobian included
        "optimizer_status": int(solution.status),
        "seconds": _time.perf_counter() - started,
    }
    return Calibration(record=record, block=block, cor=float(x[0]), cor_interval=cor_interval,
                       cor_se=float(se[0]), theta0=float(x[1]), theta0_se=float(se[1]),
                       t_release=float(t_release), t_release_se=float(t_release_se),
                       offset=float(x[3]), offset_se=float(se[3]), covariance=covariance,
                       interval_method=method, fitted=fitted, residuals=res, goodness=goodness,
                       peaks=peaks, periods=periods, bootstrap_interval=boot_interval,
                       bootstrap_cors=boot, notes=tuple(notes), anti_alias=mode,
                       filter_order=int(model.order),
                       filter_cutoff=float(cutoff), filter_delay=float(delay),
                       t_release_apparent=float(apparent),
                       parameters=PARAMETERS + (("filter_u",) if mode == "fit" else ()),
                       jacobian=jacobian)


# ------------------------------------------------------------------ theory run
def predict(calibration: Calibration, motion: Motion | None = None, *,
            duration: float | None = None, theta0: float | None = None, **kwargs):
    """The theory run with the calibrated COR (the report's use of nu = 0.925, Section 3.6).

    Parameters
    ----------
    calibration : Calibration
    motion : Motion, optional
        Table motion; ``None`` repeats the free-rocking test from the fitted
        release angle (time measured from the release).
    duration : float, optional
        Length of the run [s] (default: the record's length after release).
    theta0 : float, optional
        Initial rotation [rad] (default: the fitted release angle for free
        rocking, 0 under a motion).
    **kwargs
        Passed to :func:`shaketable.simulate`.
    """
    if not isinstance(calibration, Calibration):
        raise ValueError(f"calibration must be a Calibration, got {type(calibration).__name__}")
    if motion is None:
        theta0 = calibration.theta0 if theta0 is None else theta0
        if duration is None:
            duration = float(calibration.record.t[-1] - calibration.t_release)
    else:
        theta0 = 0.0 if theta0 is None else theta0
    return simulate(calibration.block, motion, cor=calibration.cor, theta0=theta0,
                    duration=duration, **kwargs)


def _visible_rest(t, theta, threshold):
    """Time after which |theta| stays below ``threshold`` [s] (NaN if it never does)."""
    above = np.flatnonzero(np.abs(theta) >= threshold)
    if above.size == 0:
        return float(t[0])
    if above[-1] == t.size - 1:
        return math.nan
    return float(t[above[-1] + 1])


@dataclass(frozen=True)
class FreeRockingComparison:
    """Test (the record) against theory (the engine with the calibrated COR), Fig. 3.4.

    Attributes
    ----------
    calibration : Calibration
    theory : RockingResult
        Free rocking from the fitted release angle with the calibrated COR.
    t, test_theta, theory_theta : ndarray
        Record times [s] and the two angles [rad] (offset removed; theory
        shifted to the fitted release time).
    peak_ratios : ndarray
        Test / theory amplitude of the successive peaks [-].
    rest_threshold : float
        |theta| below which the block counts as at rest [rad].
    test_rest, theory_rest : float
        Time from the release after which |theta| stays below the threshold [s].
    theory_t_rest : float
        The engine's exact rest time (end of the impact cascade) [s].
    cycles : int
        Full cycles (two impacts each) of the theory run above the threshold.
    rms_difference : float
        RMS of test minus theory after the release [rad].
    """

    calibration: Calibration
    theory: object
    t: np.ndarray
    test_theta: np.ndarray
    theory_theta: np.ndarray
    peak_ratios: np.ndarray
    rest_threshold: float
    test_rest: float
    theory_rest: float
    theory_t_rest: float
    cycles: int
    rms_difference: float

    def summary(self) -> dict:
        """Scalar results (JSON-ready)."""
        return {key: _clean(value) for key, value in {
            "cor [-]": self.calibration.cor,
            "peak_ratio_mean [-]": float(np.mean(self.peak_ratios)),
            "peak_ratio_max_deviation [-]": float(np.max(np.abs(self.peak_ratios - 1.0))),
            "test_rest [s]": self.test_rest, "theory_rest [s]": self.theory_rest,
            "theory_t_rest [s]": self.theory_t_rest, "cycles": self.cycles,
            "rms_difference [rad]": self.rms_difference,
            "rest_threshold [rad]": self.rest_threshold}.items()}


def compare_free_rocking(calibration: Calibration, *, rest_threshold: float | None = None,
                         peaks: int = 8) -> FreeRockingComparison:
    """Feed the calibrated COR back into the theory run and compare with the record (Fig. 3.4).

    Parameters
    ----------
    calibration : Calibration
    rest_threshold : float, optional
        |theta| counted as rest [rad] (default 0.01 alpha, or 5 x the noise
        if larger); the same rule is applied to test and theory.
    peaks : int
        Number of successive peaks compared.
    """
    block, record = calibration.block, calibration.record
    theory = predict(calibration)
    t = record.t
    # the theory starts where the release shows in the record (the filter's delay included)
    start = (calibration.t_release_apparent if calibration.t_release_apparent is not None
             else calibration.t_release)
    tau = t - start
    theory_theta = np.where(tau <= 0, calibration.theta0,
                            np.interp(tau, theory.t, theory.theta))
    test_theta = record.to_angle(record.values - calibration.offset, block)
    sigma = noise_level(test_theta)
    threshold = rest_threshold if rest_threshold is not None else max(0.01 * block.alpha,
                                                                      5 * sigma)
    release = start if start > t[0] else None
    test_peaks = _find_peaks(t, test_theta, block, sigma, plateau_end=release)
    theory_peaks = _find_peaks(theory.t + start, theory.theta, block, 0.0,
                               plateau_end=None)
    theory_amplitudes = np.concatenate([[abs(calibration.theta0)], theory_peaks.amplitudes])
    count = min(peaks, test_peaks.amplitudes.size, theory_amplitudes.size)
    ratios = test_peaks.amplitudes[:count] / theory_amplitudes[:count]
    after = tau > 0
    test_rest = _visible_rest(tau[after], test_theta[after], threshold)
    theory_rest = _visible_rest(tau[after], theory_theta[after], threshold)
    above = theory_peaks.amplitudes >= threshold
    return FreeRockingComparison(
        calibration=calibration, theory=theory, t=t, test_theta=test_theta,
        theory_theta=theory_theta, peak_ratios=ratios, rest_threshold=threshold,
        test_rest=test_rest, theory_rest=theory_rest, theory_t_rest=float(theory.t_rest),
        cycles=int((np.count_nonzero(above) + 1) // 2),
        rms_difference=float(np.sqrt(np.mean((test_theta[after] - theory_theta[after])**2))))


def virtual_free_rocking_record(block: Block, cor: float, theta0: float, *, seed: int | None = 0,
                                before: float = 1.0, duration: float = 10.0, sensors=None,
                                method: str = "fast", rtol: float | None = None):
    """A virtual free-rocking test seen through the sensors (Section 3.5 set-up).

    Both potentiometers (their forces cancel), 50 samples/s with the 20 Hz
    anti-alias filter and 12-bit ADC of :class:`~shaketable.sensors.Digitizer`,
    the record starting ``before`` seconds before the release (block held at
    ``theta0``) and lasting ``duration`` seconds in all.

    Parameters
    ----------
    block : Block
    cor : float
        The true COR [-].
    theta0 : float
        Release angle [rad].
    seed : int or None
        Seed of the sensors' noise (ignored when ``sensors`` is given).
    before, duration : float
        Record time before the release and in all [s].
    sensors : Sensors, optional
        Default ``Sensors(seed=seed)``.
    method, rtol
        Solver of the "test" run and its tolerance (:func:`shaketable.simulate`;
        default the fast engine at its default 1e-11, tighter than the
        calibration's 1e-9; ``method="reference"`` for SciPy's DOP853).

    Returns
    -------
    (Record, Measurement)
    """
    from .sensors import Sensors, measure

    sensors = Sensors(seed=seed) if sensors is None else sensors
    # 1 ms output: the sensors interpolate the run (cubic Hermite) between outputs, which
    # near an impact errs by ~ jump in theta' x output step / 8
    run = simulate(block, cor=cor, theta0=theta0, duration=duration - before,
                   top_force=sensors.top_force(block), output_dt=0.001, method=method,
                   rtol=rtol)
    digitizer = sensors.digitizer
    if digitizer.start is None:
        from dataclasses import replace

        sensors = replace(sensors, digitizer=replace(digitizer, start=-before,
                                                     end=duration - before))
    measurement = measure(run, block, sensors=sensors)
    return Record.from_measurement(measurement), measurement


def reproduce_fig_3_4(*, cor: float = 0.925, theta0_ratio: float = 0.5, seed: int = 0,
                      duration: float = 9.0) -> FreeRockingComparison:
    """Fig. 3.4: virtual free-rocking test of the 30 x 6 in block, calibrated and re-run.

    The "test" is the engine with the true ``cor`` released from
    ``theta0_ratio x alpha`` (the fig-3-4 scene: 0.5 alpha) seen through the
    sensors (50 samples/s, noise, both potentiometers); the COR is calibrated
    from that record and the theory run with it is compared (the report: "the
    two curves are identical, for all practical purposes ... the block came
    to rest in approximately 6 seconds, after about 10 vibrations").
    """
    block = Block.parse("30x6in")
    record, _ = virtual_free_rocking_record(block, cor, theta0_ratio * block.alpha, seed=seed,
                                            duration=duration)
    return compare_free_rocking(calibrate(record, block))
