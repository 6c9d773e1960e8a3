"""The intensity-measure settings of a sweep spec's ``[intensity]``: which
measure is the target, the periods and damping of the spectra, and a target spectrum.
Parsed by :mod:`shaketable.sweeps.spec`; used by :mod:`shaketable.sweeps.execute`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from shaketable.core.constants import G
from shaketable.sweeps.base import SweepError

#: Periods [s] of the Sa columns every row records (and ``period`` when given).
RECORDED_PERIODS = (0.2, 0.5, 1.0, 2.0)


@dataclass(frozen=True)
class IntensitySettings:
    """The intensity-measure keys of ``[intensity]``.

    Attributes
    ----------
    measure : str
        Target measure (:data:`shaketable.ground.intensity.MEASURES`) when
        ``SweepSpec.intensity == "measure"``, else ``""``.
    period : float or None
        Period of ``sa`` [s].
    period_range : tuple of float
        Range of ``sa_avg`` and of spectrum matching [s].
    damping : float
        Damping ratio of the spectra [-].
    spectrum : tuple
        Target spectrum as ((period [s], Sa [m/s^2]), ...) or ``()``.
    """

    measure: str = ""
    period: float | None = None
    period_range: tuple = (0.2, 2.0)
    damping: float = 0.05
    spectrum: tuple = ()

    @property
    def periods(self) -> tuple:
        """Periods of the recorded Sa columns [s]."""
        extra = () if self.period is None or self.period in RECORDED_PERIODS else (self.period,)
        return RECORDED_PERIODS + extra

    @property
    def column(self) -> str:
        """Table column of the target measure."""
        from shaketable.ground.intensity import MEASURES, sa_avg_column, sa_column

        if self.measure == "sa":
            assert self.period is not None   # checked by the parser
            return sa_column(self.period)
        if self.measure == "sa_avg":
            return sa_avg_column(*self.period_range)
        return MEASURES[self.measure][0]


#: Physical bounds of a target spectrum's rows: periods [s] and Sa [g].
SPECTRUM_PERIODS = (1e-3, 100.0)
SPECTRUM_SA_G = (1e-6, 100.0)

#: Physical upper bounds of sweep levels, by the kind of quantity (SI): an earthquake's
#: PGA or Sa stays below 100 g, its PGV, Arias intensity and CAV below 100 m/s and
#: 1e4 m/s, its PGD below 100 m; a scale factor below 1e4.
LEVEL_LIMITS = {"acceleration": (100.0 * G, "100 g"), "velocity": (100.0, "100 m/s"),
                "length": (100.0, "100 m"), "scale": (1e4, "1e4")}
ARIAS_LIMIT = (1e4, "1e4 m/s")


def _header_units(line: str, path: Path, number: int) -> tuple[float, float]:
    """The period and Sa factors to SI of a spectrum header ``period [s], sa [g]``."""
    from shaketable.core.constants import ACCELERATION_UNITS

    names = [field.strip() for field in line.split(",")]
    units = []
    for name in names[:2]:
        found = re.search(r"[\[(]\s*([^\])]+?)\s*[\])]", name)
        units.append(found.group(1).strip().lower() if found else None)
    time_units = {"s": 1.0, "sec": 1.0, "ms": 1e-3}
    if len(names) < 2 or units[0] not in time_units or units[1] not in ACCELERATION_UNITS:
        raise SweepError(
            f"{path}:{number}: the header {line.strip()!r} must name the two columns with "
            f"their units, e.g. 'period [s], sa [g]' (period in {', '.join(time_units)}; Sa in "
            f"{', '.join(sorted(ACCELERATION_UNITS))})")
    return time_units[units[0]], ACCELERATION_UNITS[units[1]]


def read_spectrum(value, where: str, directory: Path | None) -> tuple:
    """A target spectrum CSV: ((T [s], Sa [m/s^2]), ...).

    The first line that is not a comment (``#``) is the header and must give each
    column's unit (``period [s], sa [g]``; periods in s or ms, Sa in g, m/s^2, cm/s^2 or
    gal): a file without a header is refused (its first row is not taken for one), as
    is a unit the reader does not know. Periods must increase, each from 1 ms to 100 s,
    Sa from 1e-6 g to 100 g (values outside are a unit or a typing error).
    """
    from shaketable.core.files import read_utf8

    if not isinstance(value, str) or not value:
        raise SweepError(f"{where}: intensity.spectrum must be a CSV file name")
    path = Path(value)
    path = path if path.is_absolute() or directory is None else directory / path
    if not path.is_file():
        raise SweepError(f"{where}: intensity.spectrum: no such file {str(path)!r}")
    pairs: list[tuple[float, float]] = []
    factors = None
    for number, line in enumerate(read_utf8(path, "target spectrum", SweepError).splitlines(), 1):
        text = line.split("#")[0].strip()
        if not text:
            continue
        fields = [field.strip() for field in text.split(",")]
        if factors is None:
            if _is_number(fields[0]):
                raise SweepError(f"{path}:{number}: no header: the first line must name the "
                                 "columns with their units, e.g. 'period [s], sa [g]'")
            factors = _header_units(text, path, number)
            continue
        try:
            period, sa = float(fields[0]), float(fields[1])
        except (ValueError, IndexError):
            raise SweepError(f"{path}:{number}: expected two numbers (period, Sa), got "
                             f"{line!r}") from None
        if len(fields) != 2:
            raise SweepError(f"{path}:{number}: expected two columns (period, Sa), got "
                             f"{len(fields)}: {line!r}")
        period, sa = period * factors[0], sa * factors[1]
        if not (SPECTRUM_PERIODS[0] <= period <= SPECTRUM_PERIODS[1]):
            raise SweepError(f"{path}:{number}: period {period:g} s is outside "
                             f"{SPECTRUM_PERIODS[0]:g} to {SPECTRUM_PERIODS[1]:g} s (check the "
                             "header's unit)")
        if not (SPECTRUM_SA_G[0] * G <= sa <= SPECTRUM_SA_G[1] * G):
            raise SweepError(f"{path}:{number}: Sa {sa / G:g} g is outside "
                             f"{SPECTRUM_SA_G[0]:g} to {SPECTRUM_SA_G[1]:g} g (check the "
                             "header's unit)")
        if pairs and period <= pairs[-1][0]:
            raise SweepError(f"{path}:{number}: periods must increase ({period:g} s after "
                             f"{pairs[-1][0]:g} s)")
        pairs.append((period, sa))
    if len(pairs) < 2:
        raise SweepError(f"{path}: a target spectrum needs a header and at least two rows "
                         "with increasing periods")
    return tuple(pairs)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def check_spectrum_covers(spectrum: tuple, period_range: tuple, where: str) -> None:
    """Refuse a target spectrum that does not cover the periods the scaling reads.

    The scaling reads the target at log-spaced periods over ``period_range``; outside
    the file's periods it would have to extrapolate, which is refused rather than done
    silently.
    """

    low, high = spectrum[0][0], spectrum[-1][0]
    if period_range[0] < low * (1 - 1e-12) or period_range[1] > high * (1 + 1e-12):
        raise SweepError(f"{where}: the target spectrum covers {low:g} to {high:g} s but the "
                         f"scaling reads it from {period_range[0]:g} to {period_range[1]:g} s "
                         "(intensity.period_range, default 0.2 to 2 s); extend the spectrum "
                         "or narrow intensity.period_range (nothing is extrapolated)")


def check_levels(levels: list, kind: str, where: str, key: str) -> None:
    """Refuse repeated levels and levels beyond what is physical (:data:`LEVEL_LIMITS`)."""

    limit, words = ARIAS_LIMIT if kind == "arias" else LEVEL_LIMITS[kind]
    for value in levels:
        if not value <= limit:
            raise SweepError(f"{where}: {key}: {value:g} (SI) is beyond any earthquake "
                             f"(at most {words})")
    repeated = sorted({value for value in levels if levels.count(value) > 1})
    if repeated:
        raise SweepError(f"{where}: {key} gives the level {repeated[0]:g} (SI) more than "
                         "once; each level must be given once")


def check_periods(settings: dict, table: dict, where: str) -> None:
    """Refuse an ``intensity.period`` or ``period_range`` outside :data:`SPECTRUM_PERIODS`."""

    for key, values in (("period", [settings.get("period", 1.0)]),
                        ("period_range", settings.get("period_range", ()))):
        if any(not SPECTRUM_PERIODS[0] <= value <= SPECTRUM_PERIODS[1] for value in values):
            raise SweepError(f"{where}: intensity.{key} must lie from "
                             f"{SPECTRUM_PERIODS[0]:g} to {SPECTRUM_PERIODS[1]:g} s (a period "
                             f"of a response spectrum), got {table[key]!r}")
