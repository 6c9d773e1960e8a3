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

#: Integration points per decade of IM (the error is stated by halving them), and the
#: most a caller may ask for (the work grows with it).
POINTS_PER_DECADE = 200
MAX_POINTS_PER_DECADE = 100_000

#: A hazard curve's widest IM span (ratio of its ends) and its range of annual rates
#: [1/yr]: wider is a unit or typing error, and would make the integral's work unbounded.
MAX_IM_SPAN = 1e12
MIN_RATE, MAX_RATE = 1e-15, 1e3

#: Design lives accepted [yr].
MAX_YEARS = 1e5

#: Fewer records than this in a fragility: ``risk`` warns (the fit, and lambda, rest on
#: few ground motions; 10-20 records per stripe is the usual practice).
FEW_RECORDS = 10


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

    def __post_init__(self) -> None:
        # the checks read_hazard_curve makes of a file, for a curve built in Python
        for name in ("measure", "column", "source"):
            if not isinstance(getattr(self, name), str):
                raise TypeError(f"HazardCurve.{name} must be text, got "
                                f"{getattr(self, name)!r}")
        if not self.measure or not self.column:
            raise ValueError("HazardCurve.measure and column must name the intensity measure "
                             "(e.g. 'pgv', 'pgv [m/s]')")
        values = {}
        for name in ("im", "rate"):
            given = getattr(self, name)
            if isinstance(given, (str, bytes)) or not hasattr(given, "__len__"):
                raise TypeError(f"HazardCurve.{name} must be a sequence of numbers, got "
                                f"{type(given).__name__}")
            if any(isinstance(value, bool) or not isinstance(value, (int, float, np.floating,
                                                                     np.integer))
                   for value in given):
                raise TypeError(f"HazardCurve.{name} must hold numbers only")
            values[name] = [float(value) for value in given]
            object.__setattr__(self, name, tuple(values[name]))
        im, rate = values["im"], values["rate"]
        if len(im) != len(rate) or len(im) < 2:
            raise ValueError(f"HazardCurve: im and rate must have the same length, at least 2 "
                             f"(got {len(im)} and {len(rate)})")
        if not all(math.isfinite(x) and x > 0 for x in im + rate):
            raise ValueError("HazardCurve: im and rate must be positive and finite")
        if any(b <= a for a, b in zip(im, im[1:])):
            raise ValueError("HazardCurve.im must increase")
        if any(b >= a for a, b in zip(rate, rate[1:])):
            raise ValueError("HazardCurve.rate must decrease as the IM increases")
        if im[-1] / im[0] > MAX_IM_SPAN:
            raise ValueError(f"HazardCurve.im spans {im[0]:.3g} to {im[-1]:.3g} (SI), "
                             f"{math.log10(im[-1] / im[0]):.0f} decades; a hazard curve spans "
                             f"at most {math.log10(MAX_IM_SPAN):.0f} (check the units)")
        if not (MIN_RATE <= rate[-1] and rate[0] <= MAX_RATE):
            raise ValueError(f"HazardCurve.rate runs from {rate[0]:.3g} to {rate[-1]:.3g} /yr; "
                             f"annual rates lie from {MIN_RATE:g} to {MAX_RATE:g} /yr")

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
    from shaketable.core.files import read_utf8

    lines = [(number, line.split("#")[0].strip()) for number, line in
             enumerate(read_utf8(path, "hazard curve").splitlines(), 1)]
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
    try:
        return HazardCurve(tuple(ims), tuple(rates), measure, _column_of(measure, unit),
                           source=str(path))
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from None


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
    rate_interval : tuple of float
        Confidence interval of ``rate`` from the fragility fit's uncertainty [1/yr]: the
        range of ``rate`` over the fit's profile-likelihood region of (median, beta)
        (:func:`rate_interval`); NaN when the fit has no intervals.
    probability_interval : tuple of float
        The same for ``probability`` [-].
    confidence : float
        Level of the intervals [-].
    """

    rate: float
    error: float
    below: float
    above: float
    upper: float
    years: float
    probability: float
    probability_upper: float
    rate_interval: tuple = (math.nan, math.nan)
    probability_interval: tuple = (math.nan, math.nan)
    confidence: float = math.nan

    def to_frame(self):
        import pandas as pd

        return pd.DataFrame([{"lambda [1/yr]": self.rate,
                              "lambda low [1/yr]": self.rate_interval[0],
                              "lambda high [1/yr]": self.rate_interval[1],
                              "confidence [-]": self.confidence,
                              "discretisation error [1/yr]": self.error,
                              "tail bound below [1/yr]": self.below,
                              "tail bound above [1/yr]": self.above,
                              "lambda upper [1/yr]": self.upper, "design life [yr]": self.years,
                              "P(overturn in life) [-]": self.probability,
                              "P low [-]": self.probability_interval[0],
                              "P high [-]": self.probability_interval[1],
                              "P upper [-]": self.probability_upper}])

    def summary(self) -> str:
        """The design-life probability (the answer) and lambda with their interval, to two
        significant digits (what the fit's uncertainty supports), then the integral's own
        errors."""
        period = 1.0 / self.rate if self.rate > 0 else math.inf
        known = all(math.isfinite(x) for x in self.rate_interval)
        level = f"{100 * self.confidence:g} %" if math.isfinite(self.confidence) else ""
        rate = (f"lambda = {self.rate:.2g} /yr ({level} interval {self.rate_interval[0]:.2g} "
                f"to {self.rate_interval[1]:.2g} from the fragility fit)" if known
                else f"lambda = {self.rate:.3g} /yr (no interval: the fragility has none)")
        probability = (f"P(overturn in {self.years:g} yr) = {self.probability:.2g}"
                       + (f" ({self.probability_interval[0]:.2g} to "
                          f"{self.probability_interval[1]:.2g})" if known else ""))
        return (f"{probability}; {rate}; return period {period:.2g} yr; the hazard curve's "
                f"tails add at most {self.upper - self.rate:.1g} /yr, the integration "
                f"{self.error:.1g} /yr")


def _check_risk_inputs(fragility, hazard, years, points_per_decade) -> None:
    """The parameters of :func:`overturning_rate`, each named when refused."""
    if fragility is None or not callable(getattr(fragility, "probability", None)):
        raise TypeError(f"fragility must have a probability(im) method (e.g. a FragilityFit "
                        f"of fragility_fit), got {type(fragility).__name__}")
    if not isinstance(hazard, HazardCurve):
        raise TypeError(f"hazard must be a HazardCurve (read_hazard_curve), got "
                        f"{type(hazard).__name__}")
    if isinstance(years, bool) or not isinstance(years, (int, float, np.integer, np.floating)):
        raise TypeError(f"years (the design life) must be a number of years, got {years!r}")
    if not (math.isfinite(years) and 0 < years <= MAX_YEARS):
        raise ValueError(f"years (the design life) must be from 0 to {MAX_YEARS:g} yr, got "
                         f"{years!r}")
    if isinstance(points_per_decade, bool) or not isinstance(points_per_decade,
                                                             (int, np.integer)) \
            or not 4 <= points_per_decade <= MAX_POINTS_PER_DECADE:
        raise ValueError(f"points_per_decade must be an integer from 4 to "
                         f"{MAX_POINTS_PER_DECADE}, got {points_per_decade!r}")


def _integral(probability, hazard: HazardCurve, per_decade: int) -> float:
    """The midpoint sum of ``P d lambda`` over the hazard curve's range (module docstring)."""
    low, high = hazard.im[0], hazard.im[-1]
    n = max(2, int(math.ceil(per_decade * math.log10(high / low))))
    x = np.geomspace(low, high, n + 1)
    rates = hazard.rate_at(x)
    values = np.asarray(probability(np.sqrt(x[:-1] * x[1:])), dtype=float)
    return float(np.sum(values * (rates[:-1] - rates[1:])))


def overturning_rate(fragility, hazard: HazardCurve, *, years: float = 50.0,
                     points_per_decade: int = POINTS_PER_DECADE,
                     interval: bool = True) -> RiskResult:
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
        Design life [yr], positive, at most :data:`MAX_YEARS`.
    points_per_decade : int
        From 4 to :data:`MAX_POINTS_PER_DECADE`.
    interval : bool
        With a :class:`~shaketable.sweeps.fragility.FragilityFit` that has intervals, also
        the interval of ``lambda`` and of the probability (:func:`rate_interval`).

    Raises
    ------
    TypeError, ValueError
        Naming the parameter.
    """
    _check_risk_inputs(fragility, hazard, years, points_per_decade)
    rate = _integral(fragility.probability, hazard, points_per_decade)
    error = abs(rate - _integral(fragility.probability, hazard, points_per_decade // 2))
    p_low = float(fragility.probability(hazard.im[0]))
    above = hazard.rate[-1]
    below = p_low * hazard.rate[0]
    upper = rate + below + above
    from shaketable.sweeps.fragility import FragilityFit

    rates, confidence = (math.nan, math.nan), math.nan
    if interval and isinstance(fragility, FragilityFit) and all(
            math.isfinite(x) for x in (*fragility.median_interval, *fragility.beta_interval)):
        rates = rate_interval(fragility, hazard, points_per_decade)
        rates = (min(rates[0], rate), max(rates[1], rate))
        confidence = float(fragility.confidence)
    years = float(years)
    return RiskResult(rate=rate, error=error, below=below, above=above, upper=upper,
                      years=years, probability=-math.expm1(-rate * years),
                      probability_upper=-math.expm1(-upper * years),
                      rate_interval=rates,
                      probability_interval=tuple(-math.expm1(-x * years) for x in rates),
                      confidence=confidence)


def rate_interval(fit, hazard: HazardCurve, points_per_decade: int = POINTS_PER_DECADE,
                  directions: int = 96) -> tuple:
    """Confidence interval of ``lambda`` carrying the fragility fit's uncertainty [1/yr].

    ``lambda`` is a function of the fit's (median, beta). Its profile-likelihood interval
    at the fit's level is the range of ``lambda`` over the region
    ``2 (l_max - l(median, beta)) <= chi2_1(confidence)`` of the fit's likelihood (the
    region whose projections are the fit's own profile intervals of median and beta,
    and which gives its pointwise band): ``lambda`` is evaluated at ``directions`` points
    on the region's boundary (where a function monotone in each parameter takes its
    extremes). For an IDA fit (no stripes) the corners of the two intervals' rectangle
    (conservative).

    Parameters
    ----------
    fit : FragilityFit
        With intervals (``fragility_fit(..., intervals=True)``, the default).
    hazard : HazardCurve
    """
    from scipy.stats import norm

    from shaketable.sweeps.fragility import FragilityFit, region_boundary

    if not isinstance(fit, FragilityFit):
        raise TypeError(f"fit must be a FragilityFit, got {type(fit).__name__}")
    if fit.method == "ida" or not fit.stripes:
        points = [(m, b) for m in fit.median_interval for b in fit.beta_interval]
    else:
        points = region_boundary(fit, directions)
    values = [_integral(lambda im, m=m, b=b: norm.cdf(np.log(im / m) / b), hazard,
                        points_per_decade) for m, b in points]
    return float(min(values)), float(max(values))


def share_outside(fragility, hazard: HazardCurve, low: float, high: float,
                  points_per_decade: int = POINTS_PER_DECADE) -> float:
    """Fraction of ``lambda`` that comes from IMs outside ``[low, high]`` [-] (where the
    fragility was not fitted, so the lognormal is extrapolated there)."""
    total = _integral(fragility.probability, hazard, points_per_decade)
    if not total > 0:
        return 0.0

    def inside(im):
        im = np.asarray(im, dtype=float)
        return np.where((im >= low) & (im <= high), fragility.probability(im), 0.0)

    return float(max(0.0, 1.0 - _integral(inside, hazard, points_per_decade) / total))


def design_life_probability(rate: float, years: float) -> float:
    """``1 - exp(-rate years)``: at least one overturning in ``years`` [-] (Poisson)."""
    for name, value in (("rate", rate), ("years", years)):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer,
                                                             np.floating)):
            raise TypeError(f"design_life_probability: {name} must be a number, got "
                            f"{value!r}")
    if not (rate >= 0 and math.isfinite(rate)) or not (0 < years <= MAX_YEARS):
        raise ValueError(f"design_life_probability: need rate >= 0 [1/yr] (finite) and years "
                         f"from 0 to {MAX_YEARS:g}, got rate {rate!r}, years {years!r}")
    return -math.expm1(-rate * years)
