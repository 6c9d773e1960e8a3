"""Fragility fits (shaketable.sweeps.fragility) on synthetic data drawn from a known
lognormal: Baker's (2015) multiple-stripe MLE and its intervals, the IDA special case,
the 2-D probit, and the comparison table."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy.stats import binom, norm

from shaketable.sweeps.fragility import (
    compare_measures,
    fragility_fit,
    fragility_surface,
    ida_capacities,
    ida_fit,
)

MEDIAN, BETA = 0.5, 0.4        # the true fragility the data are drawn from
STRIPES = np.geomspace(0.2, 1.25, 10)
RECORDS = 20                    # per stripe (Baker 2015 uses 10-40)
REPETITIONS = 200


def _coverage_bounds(confidence=0.95, n=REPETITIONS, tail=0.001):
    """Counts of covering intervals consistent with the nominal rate: the central
    1 - 2 * 0.001 range of Binomial(n, confidence)."""
    return int(binom.ppf(tail, n, confidence)), int(binom.ppf(1 - tail, n, confidence))


def test_multiple_stripe_mle_intervals_cover_at_the_nominal_rate():
    rng = np.random.default_rng(2015)
    im = np.repeat(STRIPES, RECORDS)
    covered_median = covered_beta = 0
    estimates = []
    for _ in range(REPETITIONS):
        overturned = rng.random(im.size) < norm.cdf(np.log(im / MEDIAN) / BETA)
        fit = fragility_fit(im, overturned)
        covered_median += fit.median_interval[0] <= MEDIAN <= fit.median_interval[1]
        covered_beta += fit.beta_interval[0] <= BETA <= fit.beta_interval[1]
        assert fit.median_interval[0] < fit.median < fit.median_interval[1]
        estimates.append((fit.median, fit.beta))
    low, high = _coverage_bounds()
    assert low <= covered_median <= high, covered_median
    assert low <= covered_beta <= high, covered_beta
    # and the estimator is close to unbiased for the median (mean of ln median)
    log_medians = np.log([m for m, _ in estimates])
    assert abs(log_medians.mean() - math.log(MEDIAN)) < 3 * log_medians.std() / math.sqrt(
        REPETITIONS)


def test_mle_is_a_maximum_of_the_binomial_likelihood():
    # Baker (2015) Eq. 11 written out here independently: the fit's (median, beta)
    # beat every neighbour on a small grid
    rng = np.random.default_rng(3)
    im = np.repeat(STRIPES, RECORDS)
    overturned = rng.random(im.size) < norm.cdf(np.log(im / MEDIAN) / BETA)
    fit = fragility_fit(im, overturned)

    def likelihood(median, beta):
        p = norm.cdf(np.log(STRIPES / median) / beta)
        z = overturned.reshape(STRIPES.size, RECORDS).sum(axis=1)
        return np.sum(binom.logpmf(z, RECORDS, p))

    best = likelihood(fit.median, fit.beta)
    for dm in (0.99, 1.01):
        for db in (0.99, 1.0, 1.01):
            assert likelihood(fit.median * dm, fit.beta * db) < best


def test_ida_intervals_cover_at_the_nominal_rate_and_equal_the_moments():
    rng = np.random.default_rng(1)
    covered_median = covered_beta = 0
    for _ in range(REPETITIONS):
        capacities = np.exp(rng.normal(math.log(MEDIAN), BETA, 30))
        fit = ida_fit(capacities)
        covered_median += fit.median_interval[0] <= MEDIAN <= fit.median_interval[1]
        covered_beta += fit.beta_interval[0] <= BETA <= fit.beta_interval[1]
    low, high = _coverage_bounds()
    assert low <= covered_median <= high
    assert low <= covered_beta <= high
    # Baker (2015) Eqs. 1-2: the geometric mean and the standard deviation of the logs
    capacities = np.array([0.3, 0.45, 0.6, 0.9])
    fit = ida_fit(capacities)
    assert fit.median == pytest.approx(float(np.prod(capacities) ** 0.25), rel=1e-12)
    assert fit.beta == pytest.approx(float(np.std(np.log(capacities), ddof=1)), rel=1e-12)


def test_ida_capacities_from_a_sweep_with_levels():
    # two records on one block: the first overturns from level 0.4 on, the second never
    table = pd.DataFrame({
        "record": ["a"] * 3 + ["b"] * 3, "seed": [None] * 6, "block": ["x"] * 6,
        "cor [-]": [0.9] * 6, "pgv [m/s]": [0.2, 0.4, 0.6] * 2,
        "overturned": [False, True, True, False, False, False]})
    capacities, censored = ida_capacities(table, "pgv")
    assert capacities.tolist() == [0.4]
    assert censored == 1


def test_fragility_surface_recovers_a_known_probit():
    rng = np.random.default_rng(7)
    pga = np.exp(rng.uniform(np.log(0.5), np.log(8.0), 6000))
    pgv = np.exp(rng.uniform(np.log(0.05), np.log(1.5), 6000))
    truth = (-1.0, 0.5, 1.5)
    p = norm.cdf(truth[0] + truth[1] * np.log(pga) + truth[2] * np.log(pgv))
    surface = fragility_surface(pga, pgv, rng.random(p.size) < p)
    # sampling error of 6000 runs: a few hundredths
    np.testing.assert_allclose(surface.coefficients, truth, atol=0.12)


def test_compare_measures_ranks_the_measure_that_drives_the_outcome():
    # overturning driven by pgv alone; pga a noisy proxy of it: pgv has the smaller beta
    rng = np.random.default_rng(11)
    rows = []
    for block, median in (("small", 0.3), ("large", 0.6)):
        pgv = np.repeat(np.geomspace(0.1, 1.5, 12), 30)
        pga = pgv * np.exp(rng.normal(1.5, 0.5, pgv.size))
        over = rng.random(pgv.size) < norm.cdf(np.log(pgv / median) / 0.2)
        rows.append(pd.DataFrame({"block": block, "pgv [m/s]": pgv, "pga [m/s^2]": pga,
                                  "overturned": over}))
    table = pd.concat(rows, ignore_index=True)
    frame = compare_measures(table, ("pga", "pgv"))
    beta = dict(zip(frame["measure"], frame["beta (mean) [-]"]))
    assert beta["pgv"] < beta["pga"]
    spread = dict(zip(frame["measure"], frame["median spread [-]"]))
    assert spread["pgv"] == pytest.approx(2.0, rel=0.15)     # 0.6 / 0.3


def test_bad_inputs_name_the_problem():
    with pytest.raises(ValueError, match="separated"):
        fragility_fit([0.1, 0.2, 0.3, 0.4], [False, False, True, True])
    with pytest.raises(ValueError, match="every run overturned"):
        fragility_fit([0.1, 0.2], [True, True])
    with pytest.raises(ValueError, match="confidence"):
        fragility_fit([0.1, 0.2, 0.3], [False, True, False], confidence=1.5)
    with pytest.raises(ValueError, match="capacities"):
        ida_fit([0.3])


def test_a_fit_with_one_run_per_im_is_not_called_multiple_stripe():
    """A suite scaled in another measure than the fit's gives every run an IM of its own:
    the likelihood is the same, but no stripe holds more than one run, so the summary must
    not say MSA, and the figure's points are single outcomes (0 or 1), not fractions."""
    from matplotlib.figure import Figure

    from shaketable.plots.sweeps import risk_curves
    from shaketable.sweeps.risk import HazardCurve

    fell = np.array([0, 0, 1, 0, 1, 1, 0, 1, 1, 1], dtype=bool)
    spread = fragility_fit(np.geomspace(0.1, 1.0, fell.size), fell, intervals=False)
    stripes = fragility_fit(np.repeat([0.1, 0.3, 0.5, 0.7, 1.0], 2), fell, intervals=False)
    assert "ML, one run per IM" in spread.summary() and "MSA" not in spread.summary()
    assert "MSA" in stripes.summary()
    im = np.geomspace(0.02, 5.0, 20)
    hazard = HazardCurve(im=tuple(im), rate=tuple(1e-3 * (im / 0.1) ** -2.5), measure="pgv",
                         column="pgv [m/s]")
    labels = []
    for fit in (spread, stripes):
        axis = Figure().add_subplot()
        risk_curves(fit, hazard, ax=axis)
        labels.append([text.get_text() for text in axis.get_legend().get_texts()])
    assert any(label.startswith("each run: 1 overturned") for label in labels[0])
    assert any(label.startswith("fraction overturned at each level") for label in labels[1])
