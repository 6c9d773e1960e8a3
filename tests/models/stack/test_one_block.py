"""A stack of one block against the single-block engine: bit for bit."""

import math
import warnings

import numpy as np
import pytest

import shaketable as st
from shaketable.core.constants import G
from shaketable.ground import records
from shaketable.models.stack import Stack, simulate_stack


def _el_centro_15s():
    # the first 15 s of El Centro 1940 (180 and up), x 1.5: a strong record with vertical
    record = records.load("el-centro-1940-180").scaled(1.5)
    count = int(np.searchsorted(record.t, 15.0, side="right"))
    return st.Motion(record.t[:count], record.horizontal[:count], record.vertical[:count])


@pytest.mark.parametrize("size, law", [("8x2ft", "plastic"), ("30x6in", "plastic"),
                                       ("4x1ft", "cor")])
def test_a_stack_of_one_block_is_the_rocking_engine_bit_for_bit(size, law):
    # the reference: the single-block engine (its default method, RKN6(4), at the stack's
    # rtol 1e-12) with cor = Housner's 1 - 1.5 sin^2(alpha) (Section 2.7 (5): the plastic
    # law of one block) or the constant COR. The one-block stack runs that engine's own
    # start of rocking, stepper, step-size control, event location, impact and rest, so
    # every sample and every event is the same number (measured: equal, 8 x 2 ft: 32
    # impacts and 15 s completed; 30 x 6 in: overturns at 4.96 s; 4 x 1 ft, COR 0.8: 210
    # impacts)
    block = st.Block.parse(size)
    motion = _el_centro_15s()
    cor = 1.0 - 1.5 * math.sin(block.alpha) ** 2 if law == "plastic" else 0.8
    options = {} if law == "plastic" else {"impact": "cor", "cor": cor}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the fall's tension and friction warnings
        stack = simulate_stack(Stack([block]), motion, rtol=1e-12, **options)
    engine = st.simulate(block, motion, cor=cor, rtol=1e-12)
    assert engine.n_impacts > 3
    assert stack.status == engine.status
    n = len(stack.t)   # an overturned stack keeps the samples before the overturn
    assert n >= len(engine.theta) - 1
    np.testing.assert_array_equal(stack.theta[:, 0], engine.theta[:n])
    np.testing.assert_array_equal(stack.theta_dot[:, 0], engine.theta_dot[:n])
    impacts = [e["t"] for e in stack.events if e["kind"] == "impact"]
    np.testing.assert_array_equal(impacts, engine.impact_times)
    assert stack.events[0]["kind"] == "uplift" and stack.events[0]["t"] == engine.t_start
    if engine.status == "overturned":
        assert stack.t_overturn == engine.t_overturn


def test_a_one_block_stack_rests_and_starts_again_as_the_rocking_engine():
    # two 1 s bursts 3 s apart (0.4 g at 2 Hz, 0.1 g vertical at 3 Hz): the 1 x 0.25 m block
    # rocks, comes to rest through a cascade summed in closed form, starts again with the
    # second burst and rests again; every sample, impact, start and rest time equals the
    # single-block engine's (measured: equal; 356 impacts, rests at 3.681 s and 7.681 s)
    t = np.arange(0.0, 8.0, 0.01)
    bursts = (t < 1.0) | ((t >= 4.0) & (t < 5.0))
    motion = st.Motion(t, np.where(bursts, 0.4 * G * np.sin(4.0 * np.pi * t), 0.0),
                       np.where(bursts, 0.1 * G * np.sin(6.0 * np.pi * t), 0.0))
    block = st.Block(1.0, 0.25)
    stack = simulate_stack(Stack([block]), motion, rtol=1e-12)
    engine = st.simulate(block, motion, cor=1.0 - 1.5 * math.sin(block.alpha) ** 2, rtol=1e-12)
    np.testing.assert_array_equal(stack.theta[:, 0], engine.theta)
    np.testing.assert_array_equal(stack.theta_dot[:, 0], engine.theta_dot)
    impacts = [e["t"] for e in stack.events if e["kind"] == "impact"]
    np.testing.assert_array_equal(impacts, engine.impact_times)
    starts = [e["t"] for e in stack.events if e["kind"] == "uplift"]
    rests = [e["t"] for e in stack.events if e["kind"] == "rest"]
    assert len(starts) == 2 and starts[0] == engine.t_start
    assert len(rests) == 2 and rests[-1] == engine.t_rest
