"""The risk integral (shaketable.sweeps.risk) against its closed form, and hazard files."""

from __future__ import annotations

import math

import pytest

from shaketable.core.constants import G
from shaketable.sweeps.fragility import FragilityFit
from shaketable.sweeps.risk import (
    HazardCurve,
    design_life_probability,
    overturning_rate,
    read_hazard_curve,
)


@pytest.mark.parametrize("k0, k, median, beta", [(1e-4, 2.5, 0.4, 0.3), (3e-3, 1.5, 1.2, 0.6)])
def test_power_law_hazard_with_a_lognormal_fragility_matches_the_closed_form(k0, k, median,
                                                                             beta):
    # lambda_IM = k0 im^-k and P = Phi(ln(im/m)/beta) give lambda = k0 m^-k exp(k^2 beta^2/2)
    # (e.g. Cornell et al. 2002, J. Struct. Eng. 128(4), Eq. 10). The curve starts 10 beta
    # below the peak of lambda dP (ln m - k beta^2) and ends where lambda_IM is 1e-9 of
    # the answer, so the parts outside it are negligible.
    exact = k0 * median**-k * math.exp(k**2 * beta**2 / 2)
    centre = math.log(median) - k * beta**2
    ims = (math.exp(centre - 10 * beta), (1e-9 * exact / k0) ** (-1 / k))
    hazard = HazardCurve(ims, tuple(k0 * x**-k for x in ims), "pgv", "pgv [m/s]")
    fragility = FragilityFit(median=median, beta=beta, n_runs=0, n_overturned=0)
    result = overturning_rate(fragility, hazard, years=50.0)
    assert result.rate == pytest.approx(exact, rel=5e-5)
    # the stated discretisation error bounds the actual one
    assert abs(result.rate - exact) <= result.error + 1e-12 * exact
    assert result.probability == pytest.approx(1 - math.exp(-exact * 50.0), rel=5e-5)
    # a curve cut at the median: the answer lies between the rate and its stated upper bound
    cut = HazardCurve((ims[0], median), (k0 * ims[0]**-k, k0 * median**-k), "pgv", "pgv [m/s]")
    short = overturning_rate(fragility, cut)
    assert short.rate < exact < short.upper


def test_design_life_probability_is_poisson():
    assert design_life_probability(1e-3, 50) == pytest.approx(1 - math.exp(-0.05), rel=1e-14)
    with pytest.raises(ValueError, match="years"):
        design_life_probability(1e-3, 0)


def test_hazard_csv_units_and_errors(tmp_path):
    path = tmp_path / "hazard.csv"
    path.write_text("# synthetic\npga [g], annual_rate [1/yr]\n0.1, 1e-2\n0.5, 1e-4\n")
    curve = read_hazard_curve(path)
    assert curve.im == pytest.approx((0.1 * G, 0.5 * G))
    assert curve.column == "pga [m/s^2]"
    # log-log interpolation: a power law between rows
    assert curve.rate_at(math.sqrt(0.05) * G) == pytest.approx(1e-3, rel=1e-12)
    path.write_text("pga [g], annual_rate [1/yr]\n0.1, 1e-2\n0.5, 1e-1\n")
    with pytest.raises(ValueError, match="decrease"):
        read_hazard_curve(path)
    path.write_text("pga, rate\n0.1, 1e-2\n0.5, 1e-3\n")
    with pytest.raises(ValueError, match=r"hazard.csv:1: the header"):
        read_hazard_curve(path)
    path.write_text("pgv [m/s], annual_rate [1/yr]\n0.1, 1e-2\n0.5, x\n")
    with pytest.raises(ValueError, match=r"hazard.csv:3"):
        read_hazard_curve(path)
