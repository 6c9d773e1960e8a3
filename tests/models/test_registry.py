"""The models behind one interface: each registered by name, chosen from the input (or by
``model=``), its result a :class:`~shaketable.models.base.ModelResult`.

What the front door returns for a name is checked against the model's own function, bit
for bit (the sliding model: :func:`~shaketable.models.sliding.engine.slide`); the rocking
and planar models are :func:`shaketable.simulate`'s own branches, run unchanged.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import shaketable as st
from shaketable.core.geometry import AsymmetricBlock
from shaketable.models.base import Model, ModelResult
from shaketable.models.planar.reference_result import PlanarReferenceResult
from shaketable.models.registry import MODELS, model_for, model_named
from shaketable.models.rocking.asymmetric_result import AsymmetricResult
from shaketable.models.sliding.engine import slide
from shaketable.models.sliding.result import SlidingResult
from shaketable.models.stack import Stack

BLOCK = st.Block(1.0, 0.3)


def test_every_model_is_registered_by_its_name_behind_the_interface():
    assert sorted(MODELS) == ["planar", "rocking", "sliding", "stack"]
    for name, model in MODELS.items():
        assert model.name == name and isinstance(model, Model)


def test_the_model_of_an_input():
    asymmetric = AsymmetricBlock(h=0.4, b_plus=0.08, b_minus=0.1)
    assert model_for(BLOCK) is MODELS["rocking"]
    assert model_for(BLOCK, {"friction": None}) is MODELS["rocking"]
    assert model_for(asymmetric) is MODELS["rocking"]
    # a Block with friction is the planar block's (the sliding model only by name)
    assert model_for(BLOCK, {"friction": st.Friction(0.3)}) is MODELS["planar"]
    assert model_for(Stack([(1.0, 0.3)])) is MODELS["stack"]
    assert model_for("30x6in") is None


def test_a_model_by_name_is_checked_against_the_input():
    assert model_named("sliding", BLOCK) is MODELS["sliding"]
    with pytest.raises(ValueError, match="model must be one of .*'rocking'.*got 'rock'"):
        model_named("rock", BLOCK)
    with pytest.raises(ValueError, match="model 'stack' does not take a Block"):
        st.simulate(BLOCK, model="stack", duration=1.0)


def test_a_models_options_are_checked_before_it_runs():
    with pytest.raises(ValueError, match="friction is not offered by the rocking model"):
        st.simulate(BLOCK, model="rocking", cor=0.9, theta0=0.05, duration=1.0,
                    friction=st.Friction(0.3))
    with pytest.raises(ValueError, match="the planar model needs friction"):
        st.simulate(BLOCK, model="planar", cor=0.9, theta0=0.05, duration=1.0)
    with pytest.raises(ValueError, match="the sliding model needs friction"):
        st.simulate(BLOCK, st.Motion.at_rest(1.0, 0.01), model="sliding")
    with pytest.raises(ValueError, match="cor is not offered by the sliding model"):
        st.simulate(BLOCK, st.Motion.at_rest(1.0, 0.01), model="sliding", cor=0.9,
                    friction=st.Friction(0.3))


def test_the_rocking_model_by_name_is_the_default_run():
    options = {"cor": 0.9, "theta0": 0.05, "duration": 1.0}
    assert st.simulate(BLOCK, model="rocking", **options) == st.simulate(BLOCK, **options)


def test_the_sliding_model_by_name_is_the_sliding_function_bit_for_bit():
    t = np.arange(0.0, 2.0, 0.01)
    motion = st.Motion(t, 4.0 * np.sin(2.0 * np.pi * 2.0 * t))   # 0.41 g: mu 0.3 slides
    friction = st.Friction(0.3, 0.25)
    result = st.simulate(BLOCK, motion, model="sliding", friction=friction)
    direct = slide(motion, friction, block=BLOCK)
    assert isinstance(result, SlidingResult) and result == direct
    assert np.array_equal(result.x, direct.x) and result.peak_slip > 0.0


def test_every_result_class_is_a_model_result_and_keeps_equality_and_pickling():
    for cls in (st.RockingResult, st.PlanarResult, PlanarReferenceResult, AsymmetricResult,
                SlidingResult):
        assert issubclass(cls, ModelResult)
    result = st.simulate(BLOCK, cor=0.9, theta0=0.05, duration=1.0)
    assert pickle.loads(pickle.dumps(result)) == result
    assert list(result.to_frame().columns)[:1] == ["time [s]"]
