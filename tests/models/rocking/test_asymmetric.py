"""The asymmetric block: closed forms on each side, energy, the symmetric special case."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from shaketable import AsymmetricBlock, Block, Friction, Motion, simulate
from shaketable.core.constants import G
from shaketable.models.rocking.asymmetric import simulate_many_asymmetric
from shaketable.models.rocking.layout import INFO_STATUS, INFO_T_START, N_INFO, STATUS_OVERTURNED
from shaketable.models.rocking.physics import block_parameters, impact_cors, side_parameters

BLOCK = AsymmetricBlock.from_angles(0.15, 0.35, 0.5)


def quarter_period(alpha, p, theta0):
    """Time from rest at theta0 to theta = 0 of free rocking, theta'' = -p^2 sin(alpha - theta).

    Energy: theta'^2 / 2 = p^2 (cos(alpha - theta0) - cos(alpha - theta)); the time is the
    integral of d theta / |theta'|, with theta = theta0 - u^2 to remove the end singularity.
    """
    def integrand(u):
        return 2 * u / (p * math.sqrt(2 * (math.cos(alpha - theta0)
                                           - math.cos(alpha - theta0 + u * u))))
    return quad(integrand, 0.0, math.sqrt(theta0), epsabs=1e-15, epsrel=1e-13)[0]


def test_side_quantities_and_uplift_threshold():
    h, bp, bm = 0.5, 0.5 * math.tan(0.15), 0.5 * math.tan(0.35)
    assert BLOCK.alpha_plus == pytest.approx(0.15, abs=1e-15)
    assert BLOCK.alpha_minus == pytest.approx(0.35, abs=1e-15)
    assert BLOCK.R_of(1.0) == pytest.approx(math.hypot(bp, h), rel=1e-15)
    # the default inertia: the rectangle 2h x (bp + bm), I_cm = M (H^2 + B^2) / 12
    k2 = ((2 * h) ** 2 + (bp + bm) ** 2) / 12
    assert BLOCK.I0_of(-1.0) == pytest.approx(k2 + bm ** 2 + h ** 2, rel=1e-14)
    for side, alpha in ((1.0, 0.15), (-1.0, 0.35)):
        assert BLOCK.rocking_threshold(side) == pytest.approx(G * math.tan(alpha), rel=1e-14)


@pytest.mark.parametrize("method", ["fast", "reference"])
@pytest.mark.parametrize("side", [1.0, -1.0])
def test_uplift_at_g_tan_alpha_of_each_side(method, side):
    # a ramp ug = side * a t: rocking toward `side` starts at t = g tan(alpha_side) / a
    # (theta > 0 is driven by a positive table acceleration)
    rate = 2.0
    t = np.linspace(0.0, 4.0, 401)
    motion = Motion(t, side * rate * t)
    result = simulate(BLOCK, motion, cor=0.8, method=method, duration=2.5)
    expected = G * math.tan(BLOCK.alpha_of(side)) / rate
    assert result.t_start == pytest.approx(expected, rel=1e-12)
    assert np.sign(result.theta[-1]) == side


@pytest.mark.parametrize("method", ["fast", "reference"])
@pytest.mark.parametrize("side", [1.0, -1.0])
def test_free_rocking_quarter_period_of_each_side(method, side):
    alpha, p = BLOCK.alpha_of(side), BLOCK.p_of(side)
    theta0 = 0.5 * alpha
    result = simulate(BLOCK, None, cor=1.0, theta0=side * theta0, duration=1.0, method=method)
    assert result.impact_times[0] == pytest.approx(quarter_period(alpha, p, theta0), abs=1e-9)
    # two blocks with different alpha_s give different quarter periods: the test can fail
    assert abs(quarter_period(BLOCK.alpha_plus, BLOCK.p_of(1.0), 0.07)
               - quarter_period(BLOCK.alpha_minus, BLOCK.p_of(-1.0), 0.07)) > 1e-3


@pytest.mark.parametrize("method", ["fast", "reference"])
def test_energy_conserved_between_impacts_at_cor_1(method):
    # released on the stocky side; after the impact it rocks on the other pivot with the
    # same theta' (COR 1) and its own I0: energy is constant inside each flight
    result = simulate(BLOCK, None, cor=1.0, theta0=-0.05, duration=0.9, method=method,
                      output_dt=0.002)
    energy = result.energy()
    impact = result.impact_times[0]
    before, after = energy[result.t < impact - 1e-3], energy[result.t > impact + 1e-3]
    after = after[result.t[result.t > impact + 1e-3] < (result.impact_times[1] - 1e-3
                                                       if result.n_impacts > 1 else 1.0)]
    for flight in (before, after):
        assert flight.size > 20
        assert np.ptp(flight) <= 1e-9 * abs(flight[0])
    # the kinetic energy jumps at the impact by I0_+ / I0_-: the two flights differ
    assert abs(after[0] - before[0]) > 1e-4 * abs(before[0])


def test_housner_cor_of_each_pivot():
    # symmetric rectangle: Housner's 1 - 1.5 sin^2(alpha)
    square = AsymmetricBlock(0.5, 0.1, 0.1)
    alpha = math.atan2(0.1, 0.5)
    assert square.housner_cor(1.0) == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, rel=1e-14)
    # asymmetric: angular momentum about the new pivot from vectors (independent of the
    # formula): pivot 1 at x = 0, centroid at (b1, h), pivot 2 at (b1 + b2, 0)
    h, b1, b2 = BLOCK.h, BLOCK.b_plus, BLOCK.b_minus
    k2 = BLOCK.k_squared
    omega = 1.0
    velocity = omega * np.array([-h, b1])          # omega z x (b1, h)
    arm = np.array([b1 - (b1 + b2), h])            # centroid from pivot 2
    momentum_before = k2 * omega + (arm[0] * velocity[1] - arm[1] * velocity[0])
    momentum_after_per_omega = k2 + arm @ arm
    assert BLOCK.housner_cor(-1.0) == pytest.approx(momentum_before / momentum_after_per_omega,
                                                    rel=1e-14)
    assert np.array_equal(impact_cors(BLOCK, "housner"),
                          [BLOCK.housner_cor(1.0), BLOCK.housner_cor(-1.0)])


def test_symmetric_block_is_the_special_case_bit_for_bit():
    block = Block.from_inches(30, 6)
    rows = side_parameters(block)
    assert np.array_equal(rows[0], block_parameters(block))
    assert np.array_equal(rows[1], block_parameters(block))
    # the reference's per-pivot path with a symmetric block's rows: the same numbers
    from shaketable.models.rocking.reference import integrate_reference

    t = np.linspace(0.0, 3.0, 601)
    ug = 3.0 * np.sin(2 * math.pi * 1.5 * t)
    outputs = []
    for sides in (None, (rows, np.array([0.8, 0.8]))):
        arrays = [np.zeros(t.size) for _ in range(3)] + [np.zeros(1000), np.zeros(1000),
                                                         np.zeros(N_INFO)]
        integrate_reference(t, ug, np.zeros(t.size), np.zeros(t.size), rows[0], block.alpha,
                            block.p, 0.8, 0.0, 0.0, 1e-10, -1.0, *arrays, sides=sides)
        outputs.append(arrays)
    for first, second in zip(*outputs):
        assert np.array_equal(first, second, equal_nan=True)


def test_equal_sides_agree_with_the_symmetric_engine():
    # an AsymmetricBlock with equal sides and the rectangle's inertia is the symmetric block:
    # this module's solver against the compiled engine (independent integrators)
    block = Block.from_inches(30, 6)
    twin = AsymmetricBlock(block.h, block.b, block.b)
    t = np.linspace(0.0, 4.0, 801)
    motion = Motion(t, 3.5 * np.sin(2 * math.pi * 1.2 * t))
    reference = simulate(block, motion, cor=0.9)
    result = simulate(twin, motion, cor=0.9)
    assert result.n_impacts == reference.n_impacts
    assert result.overturned and reference.overturned
    assert result.t_overturn == pytest.approx(reference.t_overturn, abs=1e-6)
    common = min(result.theta.size, reference.theta.size) - 1  # the engine adds the event time
    assert np.max(np.abs(result.theta[:common] - reference.theta[:common])) < 1e-8


def test_batch_matches_single_runs():
    t = np.linspace(0.0, 3.0, 601)
    motions = [Motion(t, a * np.sin(2 * math.pi * 2.0 * t)) for a in (2.0, 6.0)]
    blocks = [BLOCK, AsymmetricBlock.from_angles(0.35, 0.15, 0.5)]
    cases = np.array([[0, 0], [0, 1], [1, 0], [1, 1]])
    info = simulate_many_asymmetric(blocks, motions, cases, ["housner"] * 4, threads=1)
    for row, (j, q) in zip(info, cases):
        single = simulate(blocks[j], motions[q], cor="housner")  # type: ignore[arg-type]
        assert row[INFO_STATUS] == single.info[INFO_STATUS]
        assert row[INFO_T_START] == single.info[INFO_T_START] or math.isnan(single.t_start)
    assert (info[:, INFO_STATUS] == STATUS_OVERTURNED).any()


def test_friction_runs_the_planar_model_and_its_batch_refuses_an_asymmetric_block():
    # the planar model of an asymmetric block: tests/models/planar/test_planar_asymmetric.py
    from shaketable.models.planar.result import PlanarResult

    result = simulate(BLOCK, None, cor=0.9, duration=1.0, friction=Friction(0.6, 0.6),
                      theta0=0.03)
    assert isinstance(result, PlanarResult) and result.block == BLOCK
    from shaketable.models.planar.batch import simulate_many_planar

    with pytest.raises(ValueError, match="batch takes Blocks"):
        simulate_many_planar(BLOCK, Motion.at_rest(1.0, 0.01), frictions=Friction(0.6, 0.6),
                             cors=0.9)


def test_bad_input_names_the_parameter():
    with pytest.raises(ValueError, match="alpha_minus"):
        AsymmetricBlock.from_angles(0.1, 2.0, 0.5)
    with pytest.raises(ValueError, match="AsymmetricBlock.b_plus"):
        AsymmetricBlock(0.5, -0.1, 0.1)
    with pytest.raises(ValueError, match="cor"):
        simulate(BLOCK, None, cor="elastic", duration=1.0)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="method"):
        simulate(BLOCK, None, cor=0.9, duration=1.0, method="linear")
