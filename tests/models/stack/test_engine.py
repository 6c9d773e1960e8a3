"""The stack model's runs against closed forms, the single-block engine and its own symmetries."""

import math
import warnings

import numpy as np
import pytest

import shaketable as st
from shaketable.core.constants import G
from shaketable.models.stack import Stack, StackTensionWarning, simulate_stack
from tests.models.stack.one_body import first_base_impact, rigid_pair


def test_a_stack_of_one_block_is_the_rocking_engine():
    # one block, the plastic law = the engine with cor = Housner's ratio (Section 2.7 (5)):
    # free rocking from 0.8 alpha (impacts, then a cascade summed in closed form) and a
    # harmonic table (uplift, impacts), both against the SciPy reference method
    block = st.Block(1.0, 0.25)
    ratio = 1.0 - 1.5 * math.sin(block.alpha) ** 2
    stack = Stack([block])
    free = simulate_stack(stack, None, theta0=[0.8 * block.alpha], duration=2.0, output_dt=0.01)
    engine = st.simulate(block, None, cor=ratio, theta0=0.8 * block.alpha, duration=2.0,
                         output_dt=0.01, method="reference")
    assert np.abs(free.theta[:, 0] - engine.theta).max() < 1e-12
    assert np.abs(free.theta_dot[:, 0] - engine.theta_dot).max() < 1e-12
    t = np.arange(0.0, 1.0, 0.005)
    motion = st.Motion(t, 4.0 * np.sin(9.0 * t), 1.0 * np.sin(5.0 * t))
    forced = simulate_stack(stack, motion)
    engine = st.simulate(block, motion, cor=ratio, method="reference")
    assert forced.events[0]["t"] == pytest.approx(engine.t_start, abs=1e-9)
    assert np.abs(forced.theta[:, 0] - engine.theta).max() < 1e-12
    impacts = [e["t"] for e in forced.events if e["kind"] == "impact"]
    assert np.abs(np.array(impacts) - engine.impact_times[:len(impacts)]).max() < 1e-9
    assert len(impacts) == engine.n_impacts


def test_a_rigid_release_falls_as_one_body_to_its_first_base_impact():
    # the stack rocking as one body is one rigid body about the base corner:
    # I_O = (4/3) m1 (b1^2 + h1^2) + m2 [(b2^2 + h2^2)/3 + b1^2 + (2 h1 + h2)^2],
    # theta'' = -(M g R_c / I_O) sin(alpha_eq - theta), alpha_eq = atan(b1 / y_c); the time
    # to reach theta = 0 from rest at theta0 is the quadrature of the energy integral and
    # the rate there its closed form; the plastic ratio r = 1 - 2 M b1^2 / I_O
    b1, h1, b2, h2, m1, m2 = 0.15, 0.5, 0.15, 0.1, 2.0, 0.6
    stack = Stack([st.Block(2 * h1, 2 * b1), st.Block(2 * h2, 2 * b2)], masses=(m1, m2))
    mass, _, y_c, radius, alpha, inertia = rigid_pair(b1, h1, b2, h2, m1, m2)
    theta0 = 0.6 * alpha
    fall, rate = first_base_impact(mass, radius, alpha, inertia, theta0)
    result = simulate_stack(stack, None, theta0=[theta0, theta0], duration=0.6, output_dt=0.01)
    impact = next(e for e in result.events if e["kind"] == "impact")
    assert impact["pattern_before"] == (1, 0) and impact["pattern_after"] == (-1, 0)
    assert impact["t"] == pytest.approx(fall, abs=1e-9)
    assert impact["rate_before"] == pytest.approx(rate, rel=1e-9)
    assert impact["rate_after"] / impact["rate_before"] == pytest.approx(
        1 - 2 * mass * b1 ** 2 / inertia, rel=1e-12)
    # the squat top never lifts: every impact keeps the interface shut
    assert all(e["pattern_after"][1] == 0 for e in result.events)


@pytest.mark.parametrize("b1, h1, b2, h2, ratio", [
    (0.15, 0.5, 0.15, 0.5, 1.0), (0.15, 0.5, 0.04, 0.3, 1.0), (0.3, 0.4, 0.2, 0.3, 1e-3),
    (0.3, 0.4, 0.2, 0.3, 1e3), (0.0006, 0.002, 0.0005, 0.004, 2.0), (40.0, 50.0, 8.0, 30.0, 0.5),
    (0.1, 0.1, 0.1, 0.02, 1.0)])
@pytest.mark.parametrize("vertical", [0.0, -0.5 * G, -0.999 * G])
def test_uplift_threshold_and_the_pattern_entered(b1, h1, b2, h2, ratio, vertical):
    # a slowly rising table acceleration from rest: uplift at |u''| = (g + v'') min(A1, A2),
    # A1 = b1 (m1 + m2) / (m1 h1 + m2 (2 h1 + h2)) (the stack about a base corner),
    # A2 = b2 / h2 (the top alone); the pattern entered is the smaller one's
    m1, m2 = 1.0, ratio
    a1 = b1 * (m1 + m2) / (m1 * h1 + m2 * (2 * h1 + h2))
    a2 = b2 / h2
    threshold = (G + vertical) * min(a1, a2)
    stack = Stack([st.Block(2 * h1, 2 * b1), st.Block(2 * h2, 2 * b2)], masses=(m1, m2))
    for sign in (1.0, -1.0):
        motion = st.Motion([0.0, 1.0, 1.0 + 1e-4], sign * np.array([0.0, 1.02, 1.02]) * threshold,
                           [vertical] * 3)
        result = simulate_stack(stack, motion)
        uplift = result.events[0]
        assert uplift["kind"] == "uplift"
        assert uplift["t"] * 1.02 * threshold == pytest.approx(threshold, rel=1e-6)
        s = int(sign)
        assert uplift["pattern_after"] == ((s, 0) if a1 < a2 else (0, s))


def test_a_force_touching_zero_does_not_start_rocking():
    # a triangle of table acceleration peaking exactly at the threshold: the corner force
    # touches zero and recovers (grazing); a hair above it rocks
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)], masses=(2.0, 1.0))
    threshold = G * 0.15 * 3.0 / (2.0 * 0.5 + 1.0 * 1.4)
    for peak, rocks in ((threshold, False), (threshold * (1 + 1e-6), True)):
        motion = st.Motion([0.0, 0.5, 1.0], [0.0, peak, 0.0])
        result = simulate_stack(stack, motion)
        assert (len(result.events) > 0) == rocks


def test_energy_balance_between_impacts_under_a_record():
    # kinetic + potential energy change = the table's work, the impact and cascade losses
    # counted: to 1e-9 of the initial energy (shaking with a vertical component that rocks
    # both blocks, same and opposite ways, until the top one falls)
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    t = np.arange(0.0, 4.0, 0.005)
    motion = st.Motion(t, 3.5 * np.sin(7 * t) * np.exp(-0.5 * t), 1.0 * np.sin(11 * t))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StackTensionWarning)
        result = simulate_stack(stack, motion)
    kinds = {e["kind"] for e in result.events}
    assert "impact" in kinds and "uplift" in kinds
    energy = result.energy
    for k in range(1, result.t.size):
        lost = sum(e["energy_before"] - e["energy_after"] for e in result.events
                   if "energy_before" in e and e["t"] <= result.t[k])
        assert abs(energy[k] - energy[0] - result.work[k] + lost) < 1e-9 * energy[0]
    assert all(e["energy_after"] <= e["energy_before"] * (1 + 1e-12) for e in result.events
               if e["kind"] == "impact")


def test_mirror_symmetry_and_dimensional_similarity():
    # the mirrored motion gives the mirrored response; lengths times 4 and time times 2
    # (accelerations unchanged) give the same rotations at the scaled times
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)], masses=(2.0, 1.0))
    big = Stack([st.Block(4.0, 1.2), st.Block(3.2, 0.8)], masses=(2.0, 1.0))
    t = np.arange(0.0, 0.6, 0.005)
    motion = st.Motion(t, 4.0 * np.sin(9.0 * t))
    result = simulate_stack(stack, motion)
    mirrored = simulate_stack(stack, motion.mirrored())
    assert np.abs(result.theta + mirrored.theta).max() < 1e-10
    scaled = simulate_stack(big, st.Motion(2.0 * t, 4.0 * np.sin(4.5 * 2.0 * t)))
    assert np.abs(result.theta - scaled.theta).max() < 1e-8
    assert len(result.events) >= 2


def test_a_decaying_stack_comes_to_rest_without_a_stall():
    # free rocking of a rigid stack: the plastic impacts shrink the rocking geometrically and
    # the endless cascade is summed in closed form; the stack rests before the end
    stack = Stack([st.Block(1.0, 0.6), st.Block(0.2, 0.5)])
    result = simulate_stack(stack, None, theta0=[0.3, 0.3], duration=1.9, output_dt=0.01)
    assert result.events[-1]["kind"] == "rest"
    assert np.all(result.theta[-1] == 0.0) and result.status == "completed"


@pytest.mark.parametrize("blocks, masses, match", [
    ([], None, r"Stack.blocks must hold at least one block"),
    ([(1.0, 0.3), (0.5, 0.4)], None, r"Stack.blocks\[1\].width .* wider than the block below"),
    ([(1.0, 0.3), (-0.5, 0.2)], None, r"Stack.blocks\[1\] height must be positive"),
    ([(1.0, 0.3), (0.5, 0.2)], (1.0, 0.0), r"Stack.masses\[1\] must be a positive"),
    ([(1.0, 0.3), (0.5, 0.2)], (1.0,), r"Stack.masses has 1 values for 2 blocks"),
])
def test_bad_stacks_are_refused_naming_the_parameter_and_block(blocks, masses, match):
    with pytest.raises(ValueError, match=match):
        Stack(blocks, masses=masses)


def test_friction_given_to_a_stack_is_refused():
    stack = Stack([(1.0, 0.3), (0.5, 0.2)])
    with pytest.raises(ValueError, match="friction is not offered for a Stack"):
        st.simulate(stack, None, duration=1.0, friction=st.Friction(0.5))
    result = st.simulate(stack, None, duration=0.05)
    assert result.status == "completed" and result.events == ()


def test_a_dip_inside_one_long_interval_is_a_landing():
    # the single-block engine's case (tests/models/rocking/test_substep_impacts.py): a block rocking
    # back towards theta = 0 under a constant push of 1.5 g tan(alpha) dips below zero and
    # returns inside one 0.5 s input interval; the landing must be found, at the time of the
    # same run on 1 ms samples
    block = st.Block.parse("4x1ft")
    push = 1.5 * G * math.tan(block.alpha)

    def first_landing(dt, end):
        t = np.arange(0.0, end + dt / 2, dt)
        result = simulate_stack(Stack([block]), st.Motion(t, np.full(t.size, push)),
                                impact="cor", cor=0.9, theta0=[1e-3], theta_dot0=[-0.06])
        return next(e["t"] for e in result.events if e["kind"] == "impact")

    assert first_landing(0.5, 0.5) == pytest.approx(first_landing(0.001, 0.03), abs=1e-9)


@pytest.mark.parametrize("b1, h1, b2, h2, m1, m2", [
    (0.05, 0.5, 0.05, 0.5, 1.0, 1.0), (0.1, 0.5, 0.1, 0.5, 1.0, 1.0),
    (0.1, 0.5, 0.06, 0.4, 2.0, 1.0)])
def test_a_strong_step_starts_the_blocks_opposite_ways_above_a_closed_form(b1, h1, b2, h2,
                                                                            m1, m2):
    # from rest, a step u'' > 0: the stack as one body rotates about its -x base corner with
    # alpha = M (u'' y_c - g b1) / I_O; the top block's centroid then accelerates by
    # alpha (-(2 h1 + h2), b1) and the moment about its +x interface corner (b2, 2 h1) of
    # what it needs is M_R = m2 [alpha (h2 (2 h1 + h2) - b1 b2) - b2 g - h2 u''] + I2 alpha.
    # The -x interface corner unloads (N = -M_R / 2 b2 = 0) at
    # u* = g (m2 b2 + K M b1 / I_O) / (K M y_c / I_O - m2 h2), K = m2 (h2 (2h1 + h2) - b1 b2) + I2:
    # below it the stack rocks as one body, above it the top starts the other way
    mass, _, y_c, _, _, inertia = rigid_pair(b1, h1, b2, h2, m1, m2)
    k = m2 * (h2 * (2 * h1 + h2) - b1 * b2) + m2 * (b2 ** 2 + h2 ** 2) / 3
    step = G * (m2 * b2 + k * mass * b1 / inertia) / (k * mass * y_c / inertia - m2 * h2)
    stack = Stack([st.Block(2 * h1, 2 * b1), st.Block(2 * h2, 2 * b2)], masses=(m1, m2))
    for factor, pattern in ((1 - 1e-6, (1, 0)), (1 + 1e-6, (1, -1))):
        result = simulate_stack(stack, st.Motion([0.0, 0.01], [factor * step] * 2))
        assert result.events[0]["t"] == 0.0
        assert result.events[0]["pattern_after"] == pattern
        assert result.events[0]["solutions"] == 1
