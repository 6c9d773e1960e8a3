"""Seismic risk of overturning: the mean annual rate ``lambda`` from a fragility and a site's
hazard curve, and the probability of overturning in a design life.

``lambda_overturn = int P(overturn | im) |d lambda_IM(im)|`` (the PEER framework's
risk integral; e.g. Baker 2015, Sect. "Collapse risk"), with ``lambda_IM(im)`` the annual
rate of exceeding ``im`` at the site (a hazard curve, as from OpenQuake). The probability
of at least one overturning in ``years`` is ``1 - exp(-lambda years)`` (Poisson
occurrences).

Hazard curve CSV: a header line naming the measure and its unit in the first column
(``pgv [m/s]``, ``pga [g]``, ``pga [m/s^2]``, ``sa(1 s) [g]``...) and the annual rate in
the second (``annual_rate [1/yr]``), then rows with increasing IM and decreasing,
positive rates; ``#`` starts a comment.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shaketable.core.constants import G

#: Units a hazard curve's IM column may carry, and their SI factor.
HAZARD_UNITS = {"g": G, "m/s^2": 1.0, "m/s2": 1.0, "cm/s^2": 0.01, "m/s": 1.0, "cm/s": 0.01,
                "m": 1.0, "cm": 0.01, "-": 1.0}

#: Integration points per decade of IM (the error is stated by halving them).
POINTS_PER_DECADE = 200


@dataclass(frozen=True)
class HazardCurve:
    """Annual rate of exceeding an intensity measure at a site.

    Attributes
    ----------
    im : tuple of float
        IM values, increasing [SI: m/s^2, m/s, m or -].
    rate : tuple of float
        Annual rates of exceedance, decreasing, positive [1/yr].
    measure : str
        Measure name as in the sweep table (``pgv``, ``pga``, ``sa(1 s)``, ``pgv*``).
    column : str
        The table column it corresponds to (SI), e.g. ``pgv [m/s]``.
    source : str
        Where it came from (file).
    """

    im: tuple
    rate: tuple
    measure: str
    column: str
    source: str = ""

    def rate_at(self, im):
        """Annual rate of exceeding ``im`` [1/yr]: log-log interpolation between rows
        (a power law in each interval)."""
        x = np.log(np.asarray(self.im))
        y = np.log(np.asarray(self.rate))
        return np.exp(np.interp(np.log(np.asarray(im, dtype=float)), x, y))


def read_hazard_curve(path: str | os.PathLike[str]) -> HazardCurve:
    """Read a hazard curve CSV (module docstring); errors name the file and line."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"hazard curve {str(path)!r}: no such file")
    lines = [(number, line.split("#")[0].strip()) for number, line in
             enumerate(path.read_text(encoding="utf-8").splitlines(), 1)]
    lines = [(number, text) for number, text in lines if text]
    if len(lines) < 3:
        raise ValueError(f"{path}: a hazard curve needs a header and at least two rows")
    number, header = lines[0]
    names = [name.strip() for name in header.split(",")]
    if len(names) < 2 or "[" not in names[0] or not names[0].endswith("]"):
        raise ValueError(f"{path}:{number}: the header must name the measure and its unit, "
                         f"such as 'pgv [m/s], annual_rate [1/yr]', got {header!r}")
    measure, unit = names[0][:-1].split("[", 1)
    measure, unit = measure.strip(), unit.strip()
    if unit not in HAZARD_UNITS:
        raise ValueError(f"{path}:{number}: unit [{unit}] of {measure!r}: expected one of "
                         f"{', '.join(HAZARD_UNITS)}")
    ims, rates = [], []
    for number, text in lines[1:]:
        fields = [field.strip() for field in text.split(",")]
        try:
            im, rate = float(fields[0]), float(fields[1])
        except (ValueError, IndexError):
            raise ValueError(f"{path}:{number}: expected two numbers 'im, rate', got "
                             f"{text!r}") from None
        if not (im > 0 and rate > 0 and math.isfinite(im) and math.isfinite(rate)):
            raise ValueError(f"{path}:{number}: IM and rate must be positive and finite, got "
                             f"{text!r}")
        ims.append(im * HAZARD_UNITS[unit])
        rates.append(rate)
    if any(b <= a for a, b in zip(ims, ims[1:])):
        raise ValueError(f"{path}: the IM column must increase row by row")
    if any(b >= a for a, b in zip(rates, rates[1:])):
        raise ValueError(f"{path}: the annual rates must decrease as the IM increases")
    return HazardCurve(tuple(ims), tuple(rates), measure, _column_of(measure, unit),
                       source=str(path))


def _column_of(measure: str, unit: str) -> str:
    si = {"g": "m/s^2", "m/s^2": "m/s^2", "m/s2": "m/s^2", "cm/s^2": "m/s^2", "m/s": "m/s",
          "cm/s": "m/s", "m": "m", "cm": "m", "-": "-"}[unit]
    from shaketable.sweeps.fragility import MEASURE_COLUMNS

    if measure in MEASURE_COLUMNS:
        return MEASURE_COLUMNS[measure]
    return f"{measure} [{si}]"


@dataclass(frozen=True)
class RiskResult:
    """The rate of overturning at a site.

    Attributes
    ----------
    rate : float
        Mean annual rate of overturning ``lambda`` [1/yr], over the hazard curve's range.
    error : float
        Discretisation error of ``rate``: its change when the integration points are
        halved [1/yr] (the rule is second order, so the error of ``rate`` is about a third
        of this).
    below, above : float
        Contributions outside the curve's range, bounded: ``above`` in
        ``[P(im_max) lambda(im_max), lambda(im_max)]`` is reported at its upper bound,
        ``below`` = ``P(im_min) (lambda(im_min) - 0)`` at most; both are included in
        ``upper`` [1/yr].
    upper : float
        ``rate`` plus the two tail bounds [1/yr].
    years : float
        Design life [yr].
    probability : float
        ``1 - exp(-rate years)`` [-].
    probability_upper : float
        The same with ``upper`` [-].
    """

    rate: float
    error: float
    below: float
    above: float
    upper: float
    years: float
    probability: float
    probability_upper: float

    def to_frame(self):
        import pandas as pd

        return pd.DataFrame([{"lambda [1/yr]": self.rate, "discretisation error [1/yr]":
                              self.error, "tail bound below [1/yr]": self.below,
                              "tail bound above [1/yr]": self.above,
                              "lambda upper [1/yr]": self.upper, "design life [yr]": self.years,
                              "P(overturn in life) [-]": self.probability,
                              "P upper [-]": self.probability_upper}])

    def summary(self) -> str:
        period = 1.0 / self.rate if self.rate > 0 else math.inf
        return (f"lambda = {self.rate:.4g} /yr (return period {period:.4g} yr; discretisation "
                f"error {self.error:.2g} /yr; with the tails beyond the hazard curve at most "
                f"{self.upper:.4g} /yr); P(overturn in {self.years:g} yr) = "
                f"{self.probability:.4g} (at most {self.probability_upper:.4g})")


def overturning_rate(fragility, hazard: HazardCurve, *, years: float = 50.0,
                     points_per_decade: int = POINTS_PER_DECADE) -> RiskResult:
    """``lambda = int P(overturn | im) |d lambda_IM|`` over the hazard curve's range.

    The hazard curve is interpolated log-log (a power law in each interval); the
    integral is a midpoint sum over ``points_per_decade`` log-spaced intervals per decade
    of IM: ``sum_i P(sqrt(x_i x_{i+1})) (lambda(x_i) - lambda(x_{i+1}))``, and once more
    with half the points to state the discretisation error.

    Parameters
    ----------
    fragility : object with ``probability(im)``
        E.g. a :class:`shaketable.sweeps.fragility.FragilityFit` in the hazard's units (SI).
    hazard : HazardCurve
    years : float
        Design life [yr], positive.
    points_per_decade : int
    """
    if not (isinstance(years, (int, float)) and math.isfinite(years) and years > 0):
        raise ValueError(f"years (the design life) must be positive, got {years!r}")
    if isinstance(points_per_decade, bool) or not isinstance(points_per_decade, int) \
            or points_per_decade < 4:
        raise ValueError(f"points_per_decade must be an integer of at least 4, got "
                         f"{points_per_decade!r}")
    low, high = hazard.im[0], hazard.im[-1]

    def midpoint(per_decade):
        n = max(2, int(math.ceil(per_decade * math.log10(high / low))))
        x = np.geomspace(low, high, n + 1)
        rates = hazard.rate_at(x)
        probability = np.asarray(fragility.probability(np.sqrt(x[:-1] * x[1:])), dtype=float)
        return float(np.sum(probability * (rates[:-1] - rates[1:])))

    rate = midpoint(points_per_decade)
    error = abs(rate - midpoint(points_per_decade // 2))
    p_low = float(fragility.probability(low))
    above = hazard.rate[-1]
    below = p_low * hazard.rate[0]
    upper = rate + below + above
    return RiskResult(rate=rate, error=error, below=below, above=above, upper=upper,
                      years=float(years), probability=-math.expm1(-rate * years),
                      probability_upper=-math.expm1(-upper * years))


def design_life_probability(rate: float, years: float) -> float:
    """``1 - exp(-rate years)``: at least one overturning in ``years`` [-] (Poisson)."""
    if not rate >= 0 or not years > 0:
        raise ValueError(f"need rate >= 0 [1/yr] and years > 0, got {rate!r}, {years!r}")
    return -math.expm1(-rate * years)
