"""Fragility functions fitted to a sweep's table, against any intensity measure (IM).

* :func:`fragility_fit` -- multiple-stripe analysis (MSA): a lognormal
  ``P(overturn | IM) = Phi(ln(IM / median) / beta)`` by maximum likelihood (Baker 2015,
  Eq. 11), with **profile-likelihood** confidence intervals on the median and on beta and
  a pointwise band on the curve.
* :func:`ida_fit` -- incremental dynamic analysis (IDA): one collapse (overturning)
  capacity per record; the lognormal by its moments (Baker 2015, Eqs. 1-2, which is the
  maximum-likelihood fit of complete data), exact normal-theory intervals (Student t on
  ``ln median``, chi-square on beta). :func:`ida_capacities` reads the capacities off a
  sweep run at several levels per record.
* :func:`fragility_surface` -- ``P(overturn | PGA, PGV) = Phi(b0 + b1 ln PGA + b2 ln PGV)``
  (a probit in both logs) by maximum likelihood.
* :func:`compare_measures` -- one fit per IM and block: efficiency (beta, smaller is
  better) and collapse of different blocks onto one curve (spread of the medians).

Reference: Baker, J. W. (2015). Efficient analytical fragility function fitting using
dynamic structural analysis. Earthquake Spectra 31(1), 579-599.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: Short names of the measures a table records (:mod:`shaketable.sweeps.execute`).
MEASURE_COLUMNS = {
    "pga": "pga [m/s^2]", "pgv": "pgv [m/s]", "pgd": "pgd [m]", "arias": "arias [m/s]",
    "cav": "cav [m/s]", "pga*": "pga/(g tan a) [-]", "pgv*": "pgv p/(g tan a) [-]",
}

#: Figure labels of the columns.
MEASURE_LABELS = {
    "pga [m/s^2]": "PGA [m/s²]", "pga [g]": "PGA [g]", "pgv [m/s]": "PGV [m/s]",
    "pgd [m]": "PGD [m]", "arias [m/s]": "Arias intensity [m/s]", "cav [m/s]": "CAV [m/s]",
    "pga/(g tan a) [-]": "PGA / (g tan α) [-]", "pgv p/(g tan a) [-]": "PGV p / (g tan α) [-]",
}


def measure_column(table, measure: str) -> str:
    """The column of a measure: a short name (:data:`MEASURE_COLUMNS`, ``"sa(1)"``,
    ``"sa_avg"``) or a column of ``table``."""
    if measure in table:
        return measure
    if measure in MEASURE_COLUMNS:
        return MEASURE_COLUMNS[measure]
    if measure.startswith("sa(") and measure.endswith(")"):
        column = f"sa({float(measure[3:-1].replace('s', '').strip()):g} s) [m/s^2]"
        if column in table:
            return column
    if measure == "sa_avg":
        found = [column for column in table.columns if str(column).startswith("sa_avg(")]
        if found:
            return found[0]
    known = sorted(c for c in table.columns if any(c.startswith(p) for p in (
        "pga", "pgv", "pgd", "sa", "arias", "cav")))
    raise ValueError(f"measure {measure!r}: the table has no such column; short names "
                     f"{', '.join(MEASURE_COLUMNS)}, sa(T), sa_avg, or one of "
                     f"{', '.join(known)}")


# --------------------------------------------------------------------------- 1-D, MSA
@dataclass(frozen=True)
class FragilityFit:
    """A lognormal fragility ``P(overturn | IM) = Phi(ln(IM / median) / beta)``.

    Attributes
    ----------
    median : float
        IM with a 50 % probability of overturning [unit of the IMs fitted].
    beta : float
        Logarithmic standard deviation [-].
    n_runs : int
        Runs fitted (records, for an IDA fit).
    n_overturned : int
        Of which overturned.
    median_interval, beta_interval : tuple of float
        Confidence intervals (profile likelihood for MSA, exact normal theory for
        IDA); NaN when not computed.
    confidence : float
        Their level [-].
    method : str
        ``"msa"`` (maximum likelihood on stripes) or ``"ida"`` (moments).
    measure : str
        Name or column of the IM (for labels).
    stripes : tuple
        (IM levels, runs, overturned) of the data, for :meth:`band`.
    """

    median: float
    beta: float
    n_runs: int
    n_overturned: int
    median_interval: tuple = (math.nan, math.nan)
    beta_interval: tuple = (math.nan, math.nan)
    confidence: float = 0.95
    method: str = "msa"
    measure: str = ""
    stripes: tuple = field(default=(), repr=False, compare=False)

    def __post_init__(self) -> None:
        for name in ("median", "beta"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer,
                                                                 np.floating)):
                raise TypeError(f"FragilityFit.{name} must be a number, got {value!r}")
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"FragilityFit.{name} must be positive and finite, got "
                                 f"{value!r}")
        for name in ("n_runs", "n_overturned"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
                raise ValueError(f"FragilityFit.{name} must be a non-negative integer, got "
                                 f"{value!r}")
        if not (isinstance(self.confidence, (int, float)) and 0 < self.confidence < 1):
            raise ValueError(f"FragilityFit.confidence must be in (0, 1), got "
                             f"{self.confidence!r}")
        if self.method not in ("msa", "ida"):
            raise ValueError(f"FragilityFit.method must be 'msa' or 'ida', got {self.method!r}")

    def probability(self, im):
        """P(overturn) at ``im`` [unit of the fit]."""
        from scipy.stats import norm

        im = np.asarray(im, dtype=float)
        return norm.cdf(np.log(im / self.median) / self.beta)

    def band(self, im, directions: int = 96):
        """Pointwise confidence band of the curve at ``im``: (low, high) arrays.

        MSA: the range of the curve over the profile-likelihood region
        ``2 (l_max - l(mu, beta)) <= chi2_1(confidence)`` (the profile-likelihood
        interval of P at each IM), traced along ``directions`` rays. IDA: the same
        over the rectangle of the two intervals (conservative).
        """
        from scipy.stats import norm

        im = np.asarray(im, dtype=float)
        if self.method == "ida" or not self.stripes:
            corners = [(m, b) for m in self.median_interval for b in self.beta_interval]
        else:
            corners = region_boundary(self, directions)
        curves = np.array([norm.cdf(np.log(im / m) / b) for m, b in corners]
                          + [self.probability(im)])
        return curves.min(axis=0), curves.max(axis=0)

    def to_frame(self):
        """One row: median, its interval, beta, its interval, runs, method."""
        import pandas as pd

        return pd.DataFrame([{
            "measure": self.measure, "method": self.method, "median": self.median,
            "median low": self.median_interval[0], "median high": self.median_interval[1],
            "beta [-]": self.beta, "beta low [-]": self.beta_interval[0],
            "beta high [-]": self.beta_interval[1], "confidence [-]": self.confidence,
            "runs": self.n_runs, "overturned": self.n_overturned}])

    def summary(self) -> str:
        """One line: median and beta with their intervals."""
        level = f"{100 * self.confidence:g} %"
        # the median to 3 significant digits, its interval to as many decimals
        places = max(0, 2 - math.floor(math.log10(abs(self.median)))) \
            if math.isfinite(self.median) and self.median != 0 else 3
        low, high = (f"{value:.{places}f}" if math.isfinite(value) else f"{value:g}"
                     for value in self.median_interval)
        return (f"{self.measure or 'IM'}: median {self.median:.{places}f} [{low}, "
                f"{high}], beta {self.beta:.3f} "
                f"[{self.beta_interval[0]:.3f}, {self.beta_interval[1]:.3f}] ({level}, "
                f"{self.method_label}, {self.n_overturned} of {self.n_runs} overturned)")

    @property
    def method_label(self) -> str:
        """The fit's method in words: ``IDA``, ``MSA`` (maximum likelihood on stripes of
        several runs at one IM) or, when every run has an IM of its own (a suite scaled in
        another measure than the fit's), ``ML, one run per IM``: the same likelihood, but
        no stripe holds more than one run."""
        if self.method == "msa" and self.stripes and max(self.stripes[1]) <= 1:
            return "ML, one run per IM"
        return self.method.upper()

    def plot(self, ax=None, **options):
        """The curve with its band (:func:`shaketable.plots.sweeps.fragility_with_band`)."""
        from shaketable.plots.sweeps import fragility_with_band

        return fragility_with_band(self, ax=ax, **options)


def _stripes(im, overturned, what="im"):
    given_type = type(im).__name__
    try:
        im = np.asarray(im, dtype=float)
    except (TypeError, ValueError):
        im = np.zeros(())
    if im.ndim == 0:
        raise TypeError(f"{what} must be an array of positive numbers, got {given_type}")
    if im.ndim != 1:
        raise ValueError(f"{what} must be a one-dimensional array, got shape {im.shape}")
    given = np.asarray(overturned)
    if given.dtype == object or not (given.dtype == bool or np.issubdtype(given.dtype, np.number)):
        raise TypeError(f"overturned must be an array of booleans, got {given.dtype} values")
    if np.issubdtype(given.dtype, np.number) and not np.all(np.isin(given, (0, 1))):
        raise ValueError("overturned must hold booleans (or 0 and 1) only")
    overturned = given.astype(bool)
    if im.shape != overturned.shape or im.size == 0:
        raise ValueError(f"{what} and overturned must be non-empty and of the same length")
    if not np.all(np.isfinite(im)) or np.any(im <= 0):
        raise ValueError(f"{what} must be positive and finite")
    k = int(overturned.sum())
    if k == 0 or k == im.size:
        raise ValueError(f"{'no' if k == 0 else 'every'} run overturned: a fragility curve "
                         f"needs both outcomes (extend the {what} range)")
    levels, inverse = np.unique(im, return_inverse=True)
    runs = np.bincount(inverse).astype(float)
    failures = np.bincount(inverse, weights=overturned.astype(float))
    return np.log(levels), runs, failures


def _log_likelihood(mu, beta, log_im, runs, failures):
    """Binomial log-likelihood of the stripes (Baker 2015, Eq. 11, without the constant)."""
    return _likelihood_of(log_im, runs, failures)(mu, beta)


def _likelihood_of(log_im, runs, failures):
    """:func:`_log_likelihood` of these stripes as a function of ``(mu, beta)``.

    The optimisers and the profile intervals call it some thousand times per fit: the
    standing counts are subtracted once here, and each call sums with the array's own
    ``sum`` (the reduction ``np.sum`` makes, without its dispatch): the same numbers.
    """
    from scipy.special import log_ndtr

    standing = runs - failures

    def log_likelihood(mu, beta):
        z = (log_im - mu) / beta
        return float((failures * log_ndtr(z) + standing * log_ndtr(-z)).sum())

    return log_likelihood


def fragility_fit(im, overturned, *, confidence: float = 0.95, intervals: bool = True,
                  measure: str = "") -> FragilityFit:
    """Maximum-likelihood lognormal fragility from (IM, overturned) outcomes (MSA).

    Each run is a Bernoulli trial with probability ``Phi(ln(im / median) / beta)``; runs
    at the same IM form a stripe with a binomial likelihood, whose product is maximised
    over ``(ln median, ln beta)`` (Baker 2015, Eq. 11). Intervals by profile likelihood:
    the values of ``median`` (or ``beta``) where twice the drop of the log-likelihood,
    maximised over the other parameter, reaches the chi-square(1) quantile.

    Parameters
    ----------
    im : array_like
        Intensity of each run, positive [any unit; the median comes out in it].
    overturned : array_like of bool
    confidence : float
        Level of the intervals [-], in (0, 1).
    intervals : bool
        Compute the intervals (a little slower).
    measure : str
        Name of the IM (labels only).

    Raises
    ------
    ValueError
        No run overturned or every run did, outcomes separated by the IM (every
        overturning run above every standing one: beta -> 0, not identified),
        non-positive IMs, or a confidence outside (0, 1).
    """
    from scipy.optimize import minimize

    if isinstance(confidence, bool) or not isinstance(confidence, (int, float)) \
            or not 0.0 < confidence < 1.0:
        raise ValueError(f"fragility_fit: confidence must be a number in (0, 1), got "
                         f"{confidence!r}")
    if not isinstance(intervals, (bool, np.bool_)):
        raise TypeError(f"fragility_fit: intervals must be True or False, got {intervals!r}")
    log_im, runs, failures = _stripes(im, overturned)
    over = failures > 0
    stand = failures < runs
    if log_im[over].min() > log_im[stand].max():
        raise ValueError("the outcomes are separated: every run above some IM overturns and "
                         "none below it does, so beta is not identified (add records or "
                         "levels between the two)")

    log_likelihood = _likelihood_of(log_im, runs, failures)

    def objective(params):
        return -log_likelihood(params[0], math.exp(params[1]))

    weights = runs / runs.sum()
    mean = float(np.sum(weights * log_im))
    spread = math.sqrt(max(float(np.sum(weights * (log_im - mean) ** 2)), 1e-4))
    start = np.array([0.5 * (log_im[over].min() + log_im[stand].max()),
                      math.log(max(0.05, 0.5 * spread))])
    best = minimize(objective, start, method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    best = minimize(objective, best.x, method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    mu, log_beta = best.x
    fit = FragilityFit(median=math.exp(mu), beta=math.exp(log_beta),
                       n_runs=int(runs.sum()), n_overturned=int(failures.sum()),
                       confidence=confidence, method="msa", measure=measure,
                       stripes=(tuple(np.exp(log_im)), tuple(runs), tuple(failures)))
    if not intervals:
        return fit
    median_interval, beta_interval = _profile_intervals(mu, log_beta, -best.fun, log_im,
                                                        runs, failures, confidence)
    return FragilityFit(median=fit.median, beta=fit.beta, n_runs=fit.n_runs,
                        n_overturned=fit.n_overturned, median_interval=median_interval,
                        beta_interval=beta_interval, confidence=confidence, method="msa",
                        measure=measure, stripes=fit.stripes)


def _profile_intervals(mu, log_beta, best, log_im, runs, failures, confidence):
    """Profile-likelihood intervals of exp(mu) and exp(log_beta)."""
    from scipy.optimize import brentq, minimize_scalar
    from scipy.stats import chi2

    limit = chi2.ppf(confidence, 1) / 2.0
    log_likelihood = _likelihood_of(log_im, runs, failures)

    def drop_mu(value):
        inner = minimize_scalar(lambda lb: -log_likelihood(value, math.exp(lb)),
                                bracket=(log_beta - 0.5, log_beta + 0.5), tol=1e-10)
        return best + inner.fun - limit

    def drop_beta(value):
        inner = minimize_scalar(lambda m: -log_likelihood(m, math.exp(value)),
                                bracket=(mu - 0.5, mu + 0.5), tol=1e-10)
        return best + inner.fun - limit

    def ends(drop, centre, step):
        found = []
        for sign in (-1.0, 1.0):
            far = centre + sign * step
            tries = 0
            while drop(far) < 0.0:
                far = centre + (far - centre) * 2.0
                tries += 1
                if tries > 40:
                    raise ValueError("the likelihood does not fall off: no confidence interval")
            found.append(brentq(drop, centre, far, xtol=1e-10) if sign > 0 else
                         brentq(drop, far, centre, xtol=1e-10))
        return math.exp(found[0]), math.exp(found[1])

    beta = math.exp(log_beta)
    return ends(drop_mu, mu, 0.5 * beta), ends(drop_beta, log_beta, 0.3)


def region_boundary(fit: FragilityFit, directions: int):
    """(median, beta) on the boundary of the profile-likelihood region of ``fit``."""
    from scipy.optimize import brentq
    from scipy.stats import chi2

    levels, runs, failures = (np.asarray(part, dtype=float) for part in fit.stripes)
    log_im = np.log(levels)
    mu, log_beta = math.log(fit.median), math.log(fit.beta)
    log_likelihood = _likelihood_of(log_im, runs, failures)
    best = log_likelihood(mu, fit.beta)
    limit = chi2.ppf(fit.confidence, 1) / 2.0
    scale_mu = 0.5 * (math.log(fit.median_interval[1]) - math.log(fit.median_interval[0]))
    scale_beta = 0.5 * (math.log(fit.beta_interval[1]) - math.log(fit.beta_interval[0]))
    if not (scale_mu > 0 and scale_beta > 0):
        scale_mu, scale_beta = fit.beta / 4.0, 0.2
    points = []
    for angle in np.linspace(0.0, 2.0 * math.pi, directions, endpoint=False):
        du, db = math.cos(angle) * scale_mu, math.sin(angle) * scale_beta

        def drop(radius, du=du, db=db):
            return best - log_likelihood(mu + radius * du,
                                         math.exp(log_beta + radius * db)) - limit

        # the search stops where the median or beta would pass a factor e^50 (exp would
        # overflow long before 2^10 on a steep direction): a region still open there is
        # bounded at that point, far beyond anything the data can say
        reach = min(1e3, 50.0 / max(abs(du), abs(db)))
        far = min(1.0, reach)
        while drop(far) < 0.0 and far < reach:
            far = min(2.0 * far, reach)
        radius = brentq(drop, 0.0, far, xtol=1e-8) if drop(far) >= 0.0 else far
        points.append((math.exp(mu + radius * du), math.exp(log_beta + radius * db)))
    return points


# --------------------------------------------------------------------------- 1-D, IDA
def ida_fit(capacities, *, confidence: float = 0.95, measure: str = "") -> FragilityFit:
    """Lognormal fragility from IDA capacities (one overturning IM per record).

    ``ln median = mean(ln IM_c)``, ``beta = std(ln IM_c)`` with ``n - 1`` (Baker 2015,
    Eqs. 1-2). Intervals: ``ln median +- t_{n-1} beta / sqrt(n)``, and
    ``beta^2 (n-1) / chi2_{n-1}`` at both tails (exact for lognormal capacities).
    """
    from scipy.stats import chi2, t

    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence!r}")
    capacities = np.asarray(capacities, dtype=float)
    if capacities.ndim != 1 or capacities.size < 2:
        raise ValueError("capacities must hold at least two records' overturning IMs")
    if not np.all(np.isfinite(capacities)) or np.any(capacities <= 0):
        raise ValueError("capacities must be positive and finite")
    logs = np.log(capacities)
    n = logs.size
    mu, beta = float(logs.mean()), float(logs.std(ddof=1))
    if beta == 0.0:
        raise ValueError("every record overturns at the same IM: beta is zero")
    tail = (1.0 - confidence) / 2.0
    half = t.ppf(1.0 - tail, n - 1) * beta / math.sqrt(n)
    beta_low = beta * math.sqrt((n - 1) / chi2.ppf(1.0 - tail, n - 1))
    beta_high = beta * math.sqrt((n - 1) / chi2.ppf(tail, n - 1))
    return FragilityFit(median=math.exp(mu), beta=beta, n_runs=n, n_overturned=n,
                        median_interval=(math.exp(mu - half), math.exp(mu + half)),
                        beta_interval=(beta_low, beta_high), confidence=confidence,
                        method="ida", measure=measure)


def ida_capacities(table, measure: str, *, by=("record", "seed", "block", "cor [-]",
                                               "static friction mu_s [-]",
                                               "dynamic friction mu_d [-]")):
    """Overturning capacity of each motion, from a sweep run at several levels per record.

    For each group of ``by`` (one record realisation on one block, COR and, in a friction
    sweep, friction pair; the columns of ``by`` the table has), the
    smallest IM (column of ``measure``) at which the run overturns: IDA's capacity, to
    within the spacing of the levels. Groups that never overturn are left out (their
    capacity is above the last level; say so); a group that overturns and then stands at
    a higher level ("resurrection") keeps its first overturning IM.

    Returns
    -------
    capacities : ndarray
        [unit of the column].
    censored : int
        Groups that never overturned.
    """
    column = measure_column(table, measure)
    keys = [key for key in by if key in table]
    capacities, censored = [], 0
    for _, rows in table.groupby(keys, sort=False, dropna=False):
        over = rows[rows["overturned"].astype(bool)]
        if over.empty:
            censored += 1
        else:
            capacities.append(float(over[column].min()))
    return np.array(capacities), censored


# --------------------------------------------------------------------------- 2-D
@dataclass(frozen=True)
class FragilitySurface:
    """``P(overturn | x, y) = Phi(b0 + b1 ln x + b2 ln y)`` (a probit in both logs).

    Attributes
    ----------
    coefficients : tuple of float
        ``(b0, b1, b2)``.
    x_measure, y_measure : str
        Columns of the two IMs.
    n_runs, n_overturned : int
    """

    coefficients: tuple
    x_measure: str
    y_measure: str
    n_runs: int
    n_overturned: int

    def probability(self, x, y):
        """P(overturn) at IMs ``x``, ``y`` (arrays broadcast)."""
        from scipy.stats import norm

        b0, b1, b2 = self.coefficients
        return norm.cdf(b0 + b1 * np.log(np.asarray(x, dtype=float))
                        + b2 * np.log(np.asarray(y, dtype=float)))

    def to_frame(self):
        import pandas as pd

        b0, b1, b2 = self.coefficients
        return pd.DataFrame([{"x": self.x_measure, "y": self.y_measure, "b0": b0,
                              "b1 (ln x)": b1, "b2 (ln y)": b2, "runs": self.n_runs,
                              "overturned": self.n_overturned}])

    def summary(self) -> str:
        b0, b1, b2 = self.coefficients
        return (f"P(overturn) = Phi({b0:.3f} + {b1:.3f} ln {self.x_measure} + {b2:.3f} ln "
                f"{self.y_measure}) ({self.n_overturned} of {self.n_runs} overturned)")

    def plot(self, ax=None, **options):
        from shaketable.plots.sweeps import fragility_contours

        return fragility_contours(self, ax=ax, **options)


def fragility_surface(x, y, overturned, *, x_measure: str = "pga [m/s^2]",
                      y_measure: str = "pgv [m/s]") -> FragilitySurface:
    """Maximum-likelihood probit ``Phi(b0 + b1 ln x + b2 ln y)`` of the outcomes.

    Raises
    ------
    ValueError
        Non-positive IMs, a single outcome, or outcomes separated by a line in
        (ln x, ln y) (the coefficients run away; add runs near the boundary).
    """
    from scipy.optimize import minimize
    from scipy.special import log_ndtr

    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    over = np.asarray(overturned, dtype=bool)
    if not (x.shape == y.shape == over.shape) or x.size == 0:
        raise ValueError("x, y and overturned must be non-empty and of the same length")
    for name, values in (("x", x), ("y", y)):
        if not np.all(np.isfinite(values)) or np.any(values <= 0):
            raise ValueError(f"{name} ({x_measure if name == 'x' else y_measure}) must be "
                             "positive and finite")
    k = int(over.sum())
    if k == 0 or k == over.size:
        raise ValueError("a fragility surface needs runs that overturn and runs that stand")
    design = np.column_stack([np.ones(x.size), np.log(x), np.log(y)])
    sign = np.where(over, 1.0, -1.0)

    def objective(beta):
        return -float(np.sum(log_ndtr(sign * (design @ beta))))

    def gradient(beta):
        from scipy.stats import norm

        z = sign * (design @ beta)
        ratio = np.exp(norm.logpdf(z) - log_ndtr(z))
        return -(design.T @ (sign * ratio))

    best = minimize(objective, np.zeros(3), jac=gradient, method="BFGS",
                    options={"gtol": 1e-9, "maxiter": 2000})
    if not np.all(np.isfinite(best.x)) or np.max(np.abs(best.x)) > 1e3:
        raise ValueError("the outcomes are separated in (ln x, ln y): the probit surface is "
                         "not identified")
    return FragilitySurface(tuple(float(b) for b in best.x), x_measure, y_measure,
                            int(over.size), k)


# --------------------------------------------------------------------------- comparison
def compare_measures(table, measures=("pga", "pgv", "pga*", "pgv*"), *, group="block",
                     confidence: float = 0.95):
    """One MSA fit per measure and group (block): which IM is efficient, which collapses.

    Returns
    -------
    pandas.DataFrame
        One row per measure: ``beta (mean) [-]`` over the groups (efficiency: smaller is
        better, Baker 2015), ``median spread [-]`` = largest / smallest median over the
        groups (collapse: 1 is a single curve), ``groups`` fitted, and the median and beta
        of each group (``median <group>``, ``beta <group>``). Groups that cannot be fitted
        (one outcome, separated) are left out of the row and counted in ``unfitted``.
    """
    import pandas as pd

    from shaketable.sweeps.friction import refuse_mixed_friction

    refuse_mixed_friction(table, "compare_measures")
    rows = []
    for measure in measures:
        column = measure_column(table, measure)
        row: dict = {"measure": measure, "column": column}
        medians, betas, unfitted = [], [], 0
        for name, part in table.groupby(group, sort=False):
            try:
                fit = fragility_fit(part[column], part["overturned"], confidence=confidence,
                                    intervals=False)
            except ValueError:
                unfitted += 1
                continue
            medians.append(fit.median)
            betas.append(fit.beta)
            row[f"median {name}"] = fit.median
            row[f"beta {name}"] = fit.beta
        row["groups"] = len(medians)
        row["unfitted"] = unfitted
        row["beta (mean) [-]"] = float(np.mean(betas)) if betas else math.nan
        row["median spread [-]"] = (max(medians) / min(medians)) if medians else math.nan
        rows.append(row)
    frame = pd.DataFrame(rows)
    first = ["measure", "column", "beta (mean) [-]", "median spread [-]", "groups",
             "unfitted"]
    return frame[first + [c for c in frame.columns if c not in first]]
