"""The intensity-measure settings of a sweep spec's ``[intensity]``: which
measure is the target, the periods and damping of the spectra, and a target spectrum.
Parsed by :mod:`shaketable.sweeps.spec`; used by :mod:`shaketable.sweeps.execute`.
"""

from __future__ import annotations

import math
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


def read_spectrum(value, where: str, directory: Path | None) -> tuple:
    """A target spectrum CSV (``period [s], sa [g]`` with a header): ((T, Sa [m/s^2]), ...)."""
    if not isinstance(value, str) or not value:
        raise SweepError(f"{where}: intensity.spectrum must be a CSV file name")
    path = Path(value)
    path = path if path.is_absolute() or directory is None else directory / path
    if not path.is_file():
        raise SweepError(f"{where}: intensity.spectrum: no such file {str(path)!r}")
    pairs = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        text = line.split("#")[0].strip()
        if not text or number == 1:
            continue
        fields = [field.strip() for field in text.split(",")]
        try:
            period, sa = float(fields[0]), float(fields[1])
        except (ValueError, IndexError):
            raise SweepError(f"{path}:{number}: expected 'period [s], sa [g]', got "
                             f"{line!r}") from None
        if not (period > 0 and sa > 0 and math.isfinite(period) and math.isfinite(sa)):
            raise SweepError(f"{path}:{number}: period and sa must be positive, got {line!r}")
        pairs.append((period, sa * G))
    if len(pairs) < 2 or any(b[0] <= a[0] for a, b in zip(pairs, pairs[1:])):
        raise SweepError(f"{path}: a target spectrum needs at least two rows with increasing "
                         "periods")
    return tuple(pairs)
