"""Stacks whose blocks are offset from the centre of the block below, against closed forms
from statics and rigid-body dynamics, their mirror image, the centred column and the Python
engine."""

import math
import warnings

import numpy as np
import pytest

import shaketable as st
from shaketable.core.constants import G
from shaketable.ground import records
from shaketable.models.stack import (
    Stack,
    StackFrictionWarning,
    StackTensionWarning,
    simulate_stack,
)
from tests.models.stack.one_body import (
    assert_every_pattern_is_newton_euler,
    first_base_impact,
    rigid_pair,
)


def _quiet(stack, motion, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StackTensionWarning)
        warnings.simplefilter("ignore", StackFrictionWarning)
        return simulate_stack(stack, motion, **options)


@pytest.mark.parametrize("offset", [0.15, -0.15])
def test_uplift_thresholds_with_an_offset_differ_by_direction(offset):
    # statics of the column at rest under a table acceleration a (inertial force -m a):
    # the whole stack tips about its base corner at -x (a > 0) when
    #   a = g (m0 b0 + m1 (b0 + e)) / (m0 h0 + m1 (2 h0 + h1)),
    # about the one at +x (a < 0) when |a| = g (m0 b0 + m1 (b0 - e)) / (same), and the top
    # block alone about either of its corners when |a| = g b1 / h1; the first uplift is at
    # the smaller one of each direction and enters that pattern. Here (e = +0.15 m) the top
    # lifts first toward +a (0.545 g > 0.5 g) and the whole stack toward -a (0.485 g)
    b0, h0, b1, h1 = 0.3, 0.5, 0.1, 0.2
    m0, m1 = 4 * b0 * h0, 4 * b1 * h1          # the default masses: the areas B H
    stack = Stack([st.Block(2 * h0, 2 * b0), st.Block(2 * h1, 2 * b1)], offsets=[offset])
    height = m0 * h0 + m1 * (2 * h0 + h1)
    entered = []
    for sign in (1.0, -1.0):
        whole = G * (m0 * b0 + m1 * (b0 + sign * offset)) / height
        top = G * b1 / h1
        threshold = min(whole, top)
        motion = st.Motion([0.0, 1.0, 1.0 + 1e-4],
                           sign * np.array([0.0, 1.02, 1.02]) * threshold)
        uplift = simulate_stack(stack, motion).events[0]
        assert uplift["kind"] == "uplift"
        assert uplift["t"] * 1.02 * threshold == pytest.approx(threshold, rel=1e-6)
        s = int(sign)
        assert uplift["pattern_after"] == ((s, 0) if whole < top else (0, s))
        entered.append(uplift["pattern_after"])
    # the two directions differ: the whole stack lifts first away from the offset, the top
    # alone toward it
    assert entered == ([(0, 1), (-1, 0)] if offset > 0 else [(1, 0), (0, -1)])


def test_a_rigid_release_of_an_offset_stack_falls_as_one_body():
    # released from rest at theta0 on the base corner at -x with the interface shut, the
    # column is one rigid body: its centre of mass from the pivot (x_c, y_c) =
    # (m0 b0 + m1 (b0 + e), m0 h0 + m1 (2 h0 + h1)) / M, I_O = m0 (b0^2 + h0^2) 4/3
    # + m1 [(b1^2 + h1^2)/3 + (b0 + e)^2 + (2 h0 + h1)^2], theta'' = -(M g R / I_O)
    # sin(alpha_eq - theta), alpha_eq = atan(x_c / y_c): the time to theta = 0 is the
    # quadrature of the energy integral. At the plastic impact onto the corner at +x the
    # angular momentum about it is kept: r = (I_O - 2 M b0 x_c) / (I_O - 4 M b0 x_c
    # + 4 M b0^2) (the parallel-axis theorem about the new corner)
    b0, h0, b1, h1, m0, m1, e = 0.15, 0.5, 0.08, 0.1, 2.0, 0.6, 0.05
    stack = Stack([st.Block(2 * h0, 2 * b0), st.Block(2 * h1, 2 * b1)], masses=(m0, m1),
                  offsets=[e])
    mass, x_c, _, radius, alpha, inertia = rigid_pair(b0, h0, b1, h1, m0, m1, e)
    theta0 = 0.5 * alpha
    fall, rate = first_base_impact(mass, radius, alpha, inertia, theta0)
    result = simulate_stack(stack, None, theta0=[theta0, theta0], duration=0.6, output_dt=0.01)
    impact = next(event for event in result.events if event["kind"] == "impact")
    assert impact["pattern_before"] == (1, 0) and impact["pattern_after"] == (-1, 0)
    assert impact["t"] == pytest.approx(fall, abs=1e-9)
    assert impact["rate_before"] == pytest.approx(rate, rel=1e-9)
    ratio = (inertia - 2 * mass * b0 * x_c) / (inertia - 4 * mass * b0 * x_c
                                               + 4 * mass * b0 ** 2)
    assert impact["rate_after"] / impact["rate_before"] == pytest.approx(ratio, rel=1e-12)


def test_the_mirrored_offset_under_the_mirrored_motion_mirrors_the_response():
    # x -> -x maps the stack with offset e onto the one with -e and the table's u'' onto
    # -u'': every rotation changes sign
    blocks = [st.Block(1.0, 0.4), st.Block(0.8, 0.2), st.Block(0.5, 0.12)]
    t = np.arange(0.0, 0.8, 0.005)
    motion = st.Motion(t, 4.5 * np.sin(9.0 * t), 1.0 * np.sin(5.0 * t))
    result = _quiet(Stack(blocks, offsets=[0.06, -0.03]), motion)
    mirrored = _quiet(Stack(blocks, offsets=[-0.06, 0.03]), motion.mirrored())
    assert len(result.events) >= 2 and result.theta.shape == mirrored.theta.shape
    assert np.abs(result.theta + mirrored.theta).max() < 1e-10
    assert [event["pattern_after"] for event in result.events] == [
        tuple(-s for s in event["pattern_after"]) for event in mirrored.events]


def test_zero_offsets_are_the_centred_stack_bit_for_bit():
    # the offsets enter as sums with zero: the same operations give the same bits
    blocks = [st.Block(1.0, 0.3), st.Block(0.8, 0.2)]
    t = np.arange(0.0, 1.0, 0.02)
    motion = st.Motion(t, 3.5 * np.sin(7 * t) * np.exp(-0.5 * t), 1.0 * np.sin(11 * t))
    for method in ("compiled", "reference"):
        centred = _quiet(Stack(blocks), motion, method=method)
        zero = _quiet(Stack(blocks, offsets=[0.0]), motion, method=method)
        assert len(centred.events) > 2
        assert np.array_equal(centred.theta, zero.theta)
        assert np.array_equal(centred.forces, zero.forces)
        assert centred.events == zero.events
        assert np.array_equal(centred.top_corner_excursion, zero.top_corner_excursion)


def test_the_compiled_engine_agrees_with_the_python_engine_on_an_offset_stack():
    # the SciPy engine (method="reference", every pattern by the reduced equations) against
    # the compiled one (one-DOF closed forms, DOP853 elsewhere): the 1e-9, on 1 s
    # of El Centro 1940 (180) that rocks the column in several patterns
    stack = Stack([st.Block(1.2, 0.5), st.Block(0.9, 0.3), st.Block(0.6, 0.16)],
                  offsets=[0.08, -0.05])
    record = records.load("el-centro-1940-180")
    kept = (record.t >= 1.5) & (record.t <= 2.5)
    motion = st.Motion(record.t[kept] - 1.5, 1.5 * record.horizontal[kept])
    compiled, python = _quiet(stack, motion), _quiet(stack, motion, method="reference")
    assert compiled.status == python.status and np.array_equal(compiled.patterns,
                                                                python.patterns)
    assert [(e["kind"], e["interface"], e["pattern_after"]) for e in compiled.events] == \
        [(e["kind"], e["interface"], e["pattern_after"]) for e in python.events]
    assert len({tuple(p) for p in compiled.patterns}) >= 3
    times = max(abs(x["t"] - y["t"]) for x, y in zip(compiled.events, python.events))
    assert max(np.abs(compiled.theta - python.theta).max(),
               np.abs(compiled.theta_dot - python.theta_dot).max(), times) < 1e-9
    assert np.abs(compiled.forces - python.forces).max() < 1e-9 * stack.weight


@pytest.mark.parametrize("n", [2, 3])
def test_reduced_equations_with_offsets_equal_newton_euler_in_every_pattern(n):
    # the chain vectors with the offsets against the full-coordinate Newton-Euler equations
    # (models/stack/reference.py: each pivot placed from the lower block's top centre):
    # random geometry with offsets that keep each base on the block below
    rng = np.random.default_rng(10 + n)
    b = np.array([0.5, 0.3, 0.15])[:n]
    h, m = rng.uniform(0.2, 1.5, n), rng.uniform(0.5, 3.0, n)
    e = np.concatenate([[0.0], [(-1) ** i * rng.uniform(0.3, 1.0) * (b[i - 1] - b[i])
                                for i in range(1, n)]])
    assert_every_pattern_is_newton_euler(rng, b, h, m, e)


@pytest.mark.parametrize("offsets, masses, error, match", [
    ([0.1, 0.0], None, ValueError, r"Stack.offsets has 2 values for 2 blocks: give 1"),
    ([], None, ValueError, r"Stack.offsets has 0 values for 2 blocks"),
    ([math.nan], None, ValueError, r"Stack.offsets\[0\] \(block 1 \(top\)\) must be finite"),
    ([math.inf], None, ValueError, r"Stack.offsets\[0\] \(block 1 \(top\)\) must be finite"),
    (["2 in"], None, ValueError, r"Stack.offsets\[0\] \(block 1 \(top\)\) must be a real"),
    ([0.21], None, ValueError, r"Stack.offsets\[0\] \(block 1 \(top\)\) = 0.21 m puts the base "
                               r"of block 1 \(top\) .* past the top of block 0"),
    ([-0.21], None, ValueError, r"\|offset\| \+ b_1 must be at most b_0"),
    (0.1, None, TypeError, r"Stack.offsets must be a sequence of numbers"),
])
def test_bad_offsets_are_refused_naming_the_parameter_and_block(offsets, masses, error, match):
    # block 0: 0.6 m wide (b0 = 0.3), block 1: 0.2 m wide (b1 = 0.1): |e| <= 0.2 m
    with pytest.raises(error, match=match):
        Stack([(1.0, 0.6), (0.5, 0.2)], masses=masses, offsets=offsets)


def test_a_base_flush_with_the_edge_below_is_accepted():
    # |e| + b1 = b0 to rounding (0.2 + 0.1 is 0.30000000000000004 > 0.3 in floats)
    edge = Stack([(1.0, 0.6), (0.4, 0.2)], offsets=[0.2])
    assert edge.offsets == (0.2,) and edge.centres[-1] == 0.2
    assert Stack([(1.0, 0.6), (0.4, 0.2)], offsets=[-0.2]).offsets == (-0.2,)


def test_the_closed_forms_of_centred_columns_refuse_offsets():
    # the studies' closed forms (rigid_stack, the uplift thresholds) are the centred
    # column's: with an offset they would give a centred column's numbers
    from shaketable.studies.stack_spectrum import uplift_threshold
    from shaketable.studies.stacks import rigid_stack, uplift_closed_form

    stack = Stack([(1.0, 0.6), (0.4, 0.2)], offsets=[0.1])
    for function in (rigid_stack, uplift_closed_form, uplift_threshold):
        with pytest.raises(ValueError, match="closed form of a centred column; Stack.offsets"):
            function(stack)
    assert uplift_closed_form(Stack([(1.0, 0.6), (0.4, 0.2)], offsets=[0.0]))[1] == 0.5
