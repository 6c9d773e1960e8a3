"""The stack's result: its views, the assumption checks it reports, the model interface."""

import math
import pickle
import warnings

import numpy as np
import pytest

import shaketable as st
from shaketable.core.constants import G
from shaketable.models.base import Model
from shaketable.models.registry import MODELS, model_for
from shaketable.models.stack import Stack, StackTensionWarning, simulate_stack


@pytest.fixture(scope="module")
def rocking():
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)], masses=(2.0, 1.0))
    t = np.arange(0.0, 0.8, 0.01)
    return simulate_stack(stack, st.Motion(t, 4.0 * np.sin(9.0 * t), name="sine"))


def test_the_views_and_equality(rocking):
    frame = rocking.to_frame()
    assert len(frame) == rocking.t.size and "theta_1 [rad]" in frame and "F/N_0 [-]" in frame
    events = rocking.events_frame()
    assert list(events["kind"]) == [e["kind"] for e in rocking.events]
    assert events["pattern_after"].iloc[0] == "stack as one body (+)"
    summary = rocking.summary()
    assert summary["blocks"] == 2 and summary["impacts"] == list(events["kind"]).count("impact")
    assert summary["events not unique"] == 0
    assert pickle.loads(pickle.dumps(rocking)) == rocking


def test_friction_demand_is_the_static_closed_form_at_rest():
    # at rest under u'' the whole stack needs F/N = u'' / (g + v'') at the base and at the
    # interface (each part's inertial force over its weight)
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    result = simulate_stack(stack, st.Motion([0.0, 1.0], [0.5, 0.5], [1.0, 1.0]))
    assert not result.events
    demand = 0.5 / (G + 1.0)
    assert np.allclose(result.friction_demand, demand, rtol=1e-13)
    assert result.t_friction_exceeded(0.99 * demand) == 0.0
    assert math.isnan(result.t_friction_exceeded(1.01 * demand))
    with pytest.raises(ValueError, match="mu"):
        result.t_friction_exceeded(-1.0)


def test_a_tensile_contact_is_reported_with_a_warning():
    # a slow push topples the stack; late in the fall a pivot would have to pull
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = simulate_stack(stack, st.Motion.uniform(0.01, 3.0 * np.sin(np.linspace(0, 6, 200))))
    assert not math.isnan(result.t_tension)
    assert any(issubclass(w.category, StackTensionWarning) for w in caught)
    k = int(np.searchsorted(result.t, result.t_tension))
    assert result.forces[k, :, 2:].min() < 0.0


def test_the_stack_model_is_registered_behind_the_interface():
    model = MODELS["stack"]
    assert isinstance(model, Model)
    assert model_for(Stack([(1.0, 0.3)])) is model and model_for(st.Block(1.0, 0.3)) is None


def test_the_verdict_says_what_the_run_did(rocking):
    # rest: a table at rest leaves the stack at rest (no uplift: theta stays exactly 0)
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    still = simulate_stack(stack, st.Motion([0.0, 1.0], [0.0, 0.0]))
    assert still.verdict() == "stayed at rest"
    # rocking: the peaks quoted are the run's own max |theta|, bottom block first
    peaks = np.abs(rocking.theta).max(axis=0)
    assert rocking.status == "completed" and peaks.any()
    assert rocking.verdict() == ("rocked: max |θ| = " + ", ".join(f"{p:.3g}" for p in peaks)
                                 + " rad (bottom to top)")
    # overturning: a constant table acceleration of 2 g topples a 4:1 column one way
    slender = Stack([st.Block(1.0, 0.25), st.Block(1.0, 0.25)])
    t = np.arange(0.0, 3.0, 0.01)
    fallen = simulate_stack(slender, st.Motion(t, np.full_like(t, 2.0 * G)))
    assert fallen.status == "overturned"
    assert fallen.verdict() == (f"block {fallen.overturned_block} overturned at "
                                f"{fallen.t_overturn:.2f} s")
