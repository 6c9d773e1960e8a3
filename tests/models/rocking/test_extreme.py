"""Stiff and extreme cases: each result finite, converged and physically right.

"Converged" is fast (default rtol 1e-11) against the independent SciPy DOP853 reference
(rtol 1e-12), to the issue's 1e-8 relative (1e-10 rad for tiny responses), or a
sequence of tightening tolerances. "Physically right" cites its source next to
each expected number: closed forms (Housner's period Eq. 2-5, the exact period
by quadrature of the energy integral, the Eq. 2-1 threshold, the energy relation
of an impact) or plain kinematics.
"""

import math

import numpy as np
import pytest

import shaketable as st
from shaketable.core import theory
from shaketable.core.constants import G
from shaketable.ground import records
from shaketable.studies import benchmark_cases, work_precision

BLOCK_30x6 = st.Block.parse("30x6in")


def _agree(fast, reference, rel=benchmark_cases.ACCEPT_RELATIVE):
    """The acceptance: 1e-8 relative (1e-10 rad for max |theta|), same events."""
    errors = benchmark_cases.compare(fast, reference)
    assert np.all(np.isfinite(fast.theta)) and np.all(np.isfinite(fast.theta_dot))
    assert errors["same verdict"] and errors["same impacts"], errors
    assert (errors["error max_theta [-]"] <= rel
            or errors["error max_theta [rad]"] <= benchmark_cases.ACCEPT_ABSOLUTE_THETA), errors
    assert errors["error events [-]"] <= rel, errors


def _case(name):
    return benchmark_cases.benchmark_cases(quick=True, names=[name])[0]


# --------------------------------------------------------------------------- size
def test_tiny_block_3x1cm_period_and_forced_response():
    tiny = st.Block.parse("3x1cm")
    # p = sqrt(3 g / 4 R), R = 0.5 sqrt(3^2 + 1^2) cm: 21.5 rad/s (the issue's "about
    # 35" is not this block's p; the test keeps the block, 3 x 1 cm).
    assert tiny.p == pytest.approx(math.sqrt(3 * G / (4 * 0.005 * math.sqrt(10))), rel=1e-12)
    amplitude = 0.5 * tiny.alpha
    free = st.simulate(tiny, cor=1.0, theta0=amplitude, duration=0.5, output_dt=0.001)
    # exact period by quadrature of the energy integral: first impact at T/4, then T/2
    period = theory.exact_period(tiny, amplitude)
    assert free.impact_times[0] == pytest.approx(period / 4, rel=1e-8)
    assert np.diff(free.impact_times) == pytest.approx(period / 2, rel=1e-8)
    case = _case("tiny-3x1cm")
    _agree(case.run("fast"), case.run("reference"))


def test_huge_block_20x5m_on_pacoima_matches_reference():
    huge = st.Block.parse("20x5m")
    motion = records.load("pacoima-dam-s16e")
    fast = st.simulate(huge, motion, cor=0.95, duration=12.0)
    reference = st.simulate(huge, motion, cor=0.95, duration=12.0, method="reference")
    _agree(fast, reference)
    # a 20 m block is far from overturning under a 1.2 g record (size effect, Housner):
    # p = 0.73 rad/s, so the pulse periods are short against 1/p
    assert not fast.overturned and 0 < fast.max_theta_ratio < 1


# --------------------------------------------------------------------------- slenderness
def test_very_slender_alpha_0_02_follows_housner_and_the_reference():
    slender = st.Block.from_slenderness(R=1.0, alpha=0.02)
    amplitude = 0.5 * slender.alpha
    free = st.simulate(slender, cor=1.0, theta0=amplitude, duration=3.0)
    # exact nonlinear period (quadrature) to 1e-8; Housner's linearised Eq. (2-5)
    # differs from it by O(alpha^2) = 4e-4 at most
    exact = theory.exact_period(slender, amplitude)
    assert free.impact_times[0] == pytest.approx(exact / 4, rel=1e-8)
    assert free.impact_times[0] == pytest.approx(theory.housner_period(slender, amplitude) / 4,
                                                 rel=4e-4)
    case = _case("slender-alpha-0.02")
    _agree(case.run("fast"), case.run("reference"))


def test_stocky_h_over_b_1_period_and_forced_response():
    stocky = st.Block.parse("1x1m")
    assert stocky.alpha == pytest.approx(math.pi / 4, rel=1e-15)
    amplitude = 0.5 * stocky.alpha
    free = st.simulate(stocky, cor=1.0, theta0=amplitude, duration=2.0)
    # alpha = 45 deg: Housner's small-angle period is far off; the exact period holds
    assert free.impact_times[0] == pytest.approx(theory.exact_period(stocky, amplitude) / 4,
                                                 rel=1e-8)
    case = _case("stocky-1x1m")
    _agree(case.run("fast"), case.run("reference"))


# --------------------------------------------------------------------------- input
def test_50hz_5g_input_matches_reference_and_stays_small():
    case = _case("50hz-5g")
    fast = case.run("fast")
    _agree(fast, case.run("reference"))
    # 5 g is 25 times Eq. (2-1)'s 0.2 g, so it rocks (hundreds of impacts), but at 50 Hz
    # the table moves a / omega^2 = 0.5 mm: each half cycle gives the block an angular
    # velocity of at most a h / (I0 omega) = 0.05 rad/s, far from toppling it.
    assert fast.n_impacts > 50 and not fast.overturned and fast.max_theta_ratio < 0.2


def test_100s_record_at_200hz_converges_and_matches_reference():
    motion = benchmark_cases.long_record()
    assert motion.t.size == 20001 and motion.dt == pytest.approx(0.005)
    block = st.Block.parse("16x4ft")
    fast = st.simulate(block, motion, cor=0.95)
    assert fast.status == "completed" and fast.t[-1] == pytest.approx(100.0)
    assert np.all(np.isfinite(fast.theta))
    # converged over the whole 100 s: the default rtol against 1e-13
    tight = st.simulate(block, motion, cor=0.95, rtol=1e-13)
    errors = benchmark_cases.compare(fast, tight, window=100.0)
    assert errors["same impacts"] and fast.n_impacts == tight.n_impacts
    assert errors["error events [-]"] < 1e-8
    assert errors["error max_theta [rad]"] < benchmark_cases.ACCEPT_ABSOLUTE_THETA
    # and the impacts before 20 s against the independent reference (first 30 s)
    short = st.simulate(block, motion, cor=0.95, duration=30.0)
    _agree(short, st.simulate(block, motion, cor=0.95, duration=30.0, method="reference"))


# --------------------------------------------------------------------------- stiff rods
def test_stiff_prestress_rods_explicit_scheme_shortens_its_steps():
    """K = 40 W/in, F0 = 0.4 W on the 8 x 2 ft block (rods at mid-width, S = 12 in).

    The rods add a rocking frequency omega_r = sqrt(g K/2 (d1^2 + d2^2) / I0) =
    26.1 rad/s, 10.8 times p = 2.42 rad/s. The Nystrom pair stays explicit: on
    theta'' = -omega^2 theta its amplitude error per step is about (h omega)^7 /
    10 (1e-7 at h omega = 1, 3e-6 at 1.5), with no stability cliff before h omega
    of 3 to 4, so the problem is not stiff for it; the error controller shortens
    the steps from about 5 ms (F0 alone) to about 1.3 ms (h omega_r ~ 0.035), and
    no switch of method is needed. Measured on Pacoima S16E + vertical, 15 s:
    9254 steps with the rods against 1472 with F0 alone.
    """
    rods = st.PrestressRods.from_inches(40, 0.4, 12)
    block = st.Block.parse("8x2ft", rods=rods)
    motion = records.load("pacoima-dam-s16e")
    fast = st.simulate(block, motion, cor=0.95, duration=15.0)
    reference = st.simulate(block, motion, cor=0.95, duration=15.0, method="reference")
    # the 1e-8: at the default rtol 1e-11 the fast engine is 9e-12 off the
    # reference at rtol 2.5e-14 in the event times, 7e-12 in max |theta| (RESULTS.md)
    _agree(fast, reference, rel=1e-8)
    from shaketable.models.rocking.physics import (
        INERTIA,
        ROD_ARM_1,
        ROD_ARM_2,
        ROD_STIFFNESS,
        block_parameters,
    )
    parameters = block_parameters(block)
    omega_r = math.sqrt(parameters[ROD_STIFFNESS] * (parameters[ROD_ARM_1] ** 2
                                                     + parameters[ROD_ARM_2] ** 2)
                        / parameters[INERTIA])
    assert omega_r == pytest.approx(26.1, rel=2e-3)
    no_stiffness = st.Block.parse("8x2ft", rods=st.PrestressRods.from_inches(0.0, 0.4, 12))
    soft = st.simulate(no_stiffness, motion, cor=0.95, duration=15.0)
    step = work_precision._time_in_flight(fast) / fast.statistics["steps"]
    soft_step = work_precision._time_in_flight(soft) / soft.statistics["steps"]
    assert step < 0.5 * soft_step            # shorter steps...
    assert step * omega_r < 0.3              # ...set by accuracy, far inside stability (3-4)
    # the rods hold the block: Eq. (2-1) with prestress raises the threshold to 1.4 B/H g
    assert block.rocking_threshold() == pytest.approx(1.4 * G * 0.25, rel=1e-12)
    assert not fast.overturned


# --------------------------------------------------------------------------- threshold
@pytest.mark.parametrize("factor", [1.0001, 0.9999])
def test_near_threshold_shaking(factor):
    block = BLOCK_30x6
    motion = benchmark_cases.threshold_harmonic(block, factor)
    fast = st.simulate(block, motion, cor=0.925)
    reference = st.simulate(block, motion, cor=0.925, method="reference")
    if factor < 1:
        # Eq. (2-1): the peak 0.9999 (B/H) g never exceeds the threshold: no rocking
        for result in (fast, reference):
            assert math.isnan(result.t_start) and np.all(result.theta == 0.0)
        return
    # the crest at t = 1/8 s is a sample; the motion is linear between samples, so the
    # start is where the line from the sample before (0.12 s) crosses the threshold
    dt = motion.dt
    before = factor * math.sin(2 * math.pi * 2.0 * (0.125 - dt))
    expected = (0.125 - dt) + dt * (1.0 - before) / (factor - before)
    assert fast.t_start == pytest.approx(expected, rel=1e-12)
    assert fast.max_abs_theta > 0
    _agree(fast, reference)


# --------------------------------------------------------------------------- restitution
def test_cor_0_every_impact_ends_the_motion():
    case = _case("cor-0")
    fast = case.run("fast")
    _agree(fast, case.run("reference"))
    assert fast.n_impacts >= 2 and fast.cascades == 0
    # COR 0: the impact takes all the kinetic energy (Section 2.7 (5) with nu = 0): the
    # block rests at the instant of its last impact
    assert fast.t_rest == fast.impact_times[fast.n_impacts - 1]


def test_cor_1_conserves_energy_for_20_seconds():
    block = BLOCK_30x6
    amplitude = 0.6 * block.alpha
    result = st.simulate(block, cor=1.0, theta0=amplitude, duration=20.0)
    period = theory.exact_period(block, amplitude)
    # energy conserved (Eq. 2-3): every impact at the release velocity, every half
    # period T/2 of the exact period; the amplitude never grows
    assert result.n_impacts == int((20.0 - period / 4) / (period / 2)) + 1
    assert np.abs(result.impact_velocities) == pytest.approx(
        theory.impact_velocity(block, amplitude), rel=1e-7)
    assert np.diff(result.impact_times) == pytest.approx(period / 2, rel=1e-8)
    assert result.max_abs_theta == pytest.approx(amplitude, rel=1e-10)
    assert math.isnan(result.t_rest)


def test_decaying_cascade_rest_time_converges_with_bounded_cost():
    block = st.Block.parse("36x9in")
    amplitude, cor = 0.9 * block.alpha, 0.7
    # the rest time from the energy relation: T(a0)/4 to the first impact, then half
    # an exact period per amplitude a_k+1 = amplitude_after_impact(a_k); the flights
    # shrink like cor^k, so 400 terms are exact to rounding
    amplitudes = [amplitude]
    for _ in range(400):
        amplitudes.append(theory.amplitude_after_impact(block, amplitudes[-1], cor))
    expected = theory.exact_period(block, amplitude) / 4 + sum(
        theory.exact_period(block, a) / 2 for a in amplitudes[1:] if a > 0)
    rest_times, evaluations = [], []
    for rtol in (1e-7, 1e-9, 1e-11, 1e-13):
        result = st.simulate(block, cor=cor, theta0=amplitude, duration=4.0, rtol=rtol)
        assert result.cascades == 1 and result.theta[-1] == 0.0
        rest_times.append(result.t_rest)
        evaluations.append(result.statistics["evaluations"])
    # the tail below rest_tolerance (1e-6 / p = 2.5e-7 s) is summed with a constant
    # deceleration near theta = 0: agreement with the energy relation to that order
    assert abs(rest_times[-1] - expected) < 1e-6 / block.p
    changes = np.abs(np.diff(rest_times))
    assert np.all(changes < 1e-9)  # converged: independent of rtol to 1e-9 s
    # cost: the summed tail replaces the endless impacts; tightening the tolerance
    # 1e6-fold costs about (1e6)^(1/5) = 16 times the evaluations, not unbounded
    assert evaluations[-1] < 30 * evaluations[0]
    assert max(evaluations) < 50_000


# --------------------------------------------------------------------------- leaving the ground
@pytest.mark.parametrize("method", ["fast", "reference", "predictor-corrector", "linear"])
def test_vertical_acceleration_reaching_minus_g_flags_airborne_at_the_right_time(method):
    motion = benchmark_cases.vertical_to_minus_g(t_airborne=1.37)
    result = st.simulate(BLOCK_30x6, motion, cor=0.925, method=method)
    # the ramp -g t / 1.37 s reaches -g (g + v'' = 0, no contact) at 1.37 s exactly
    assert result.status == "airborne"
    assert result.t_airborne == pytest.approx(1.37, rel=1e-12)
    assert np.all(np.isfinite(result.theta)) and result.t[-1] == pytest.approx(1.37, rel=1e-12)


def test_reference_at_its_tightest_tolerance_passes_impacts():
    # DOP853 once gave up at an impact at rtol 2.5e-14 (the switch of corner at theta = 0
    # is a jump in theta'' that no step could resolve) and the driver retried forever.
    # Integrating the active corner's equation continued past 0 removes the jump: the
    # tightest run must finish and agree with fast on every impact time (to 1e-9 s).
    block = BLOCK_30x6
    reference = st.simulate(block, cor=0.925, theta0=0.5 * block.alpha, duration=2.0,
                            method="reference", rtol=2.5e-14)
    fast = st.simulate(block, cor=0.925, theta0=0.5 * block.alpha, duration=2.0)
    assert reference.n_impacts == fast.n_impacts >= 4
    np.testing.assert_allclose(reference.impact_times, fast.impact_times, rtol=0, atol=1e-9)
