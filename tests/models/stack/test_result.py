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
from shaketable.models.stack import (
    Stack,
    StackFrictionWarning,
    StackTensionWarning,
    simulate_stack,
)


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
        result = st.simulate(stack, st.Motion.uniform(0.01, 3.0 * np.sin(np.linspace(0, 6, 200))))
    assert not math.isnan(result.t_tension)
    tension = [w for w in caught if issubclass(w.category, StackTensionWarning)]
    # once, and pointing at this call (not at a line inside the package)
    assert len(tension) == 1 and tension[0].filename == __file__
    k = int(np.searchsorted(result.t, result.t_tension))
    assert result.forces[k, :, 2:].min() < 0.0


def _plain(value) -> bool:
    if isinstance(value, list):
        return all(type(item) in (float, str) for item in value)
    return type(value) in (bool, int, float, str)


def test_the_summary_holds_plain_python_values_and_the_no_slip_check(rocking):
    summary = rocking.summary()
    assert all(_plain(value) for value in summary.values()), {
        key: type(value).__name__ for key, value in summary.items() if not _plain(value)}
    # at rest under u'' = 0.5 m/s^2 and v'' = 1 m/s^2 the stack needs F/N = 0.5 / (g + 1)
    # (the static closed form), far below 1: the no-slip assumption holds, no warning
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    with warnings.catch_warnings():
        warnings.simplefilter("error", StackFrictionWarning)
        still = simulate_stack(stack, st.Motion([0.0, 1.0], [0.5, 0.5], [1.0, 1.0]))
    assert still.summary()["no-slip assumption"].startswith("holds")
    assert math.isnan(still.summary()["t_friction_exceeded [s]"])


def test_a_friction_demand_above_one_is_reported_once_where_the_user_called():
    # at rest under a constant u'' = 1.5 g each interface needs F/N = 1.5 (static closed
    # form): more than any real contact gives, from the first output time. The squat stack
    # stays at rest: the top block alone uplifts at g b / h = 8 g, the column (centre of mass
    # 0.14 m up, base half-width 0.5 m, masses as the areas) at about 3.5 g
    stack = Stack([st.Block(0.2, 1.0), st.Block(0.1, 0.8)])
    t = np.arange(0.0, 0.2, 0.01)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = st.simulate(stack, st.Motion(t, np.full_like(t, 1.5 * G)))
    friction = [w for w in caught if issubclass(w.category, StackFrictionWarning)]
    assert len(friction) == 1 and friction[0].filename == __file__
    assert "above 1 from t = 0 s" in str(friction[0].message)
    summary = result.summary()
    assert summary["no-slip assumption"].startswith("fails from t = 0.000 s")
    assert summary["t_friction_exceeded [s]"] == 0.0
    assert summary["max F/N [-]"] == pytest.approx(1.5, rel=1e-9)


def test_the_stack_model_is_registered_behind_the_interface():
    model = MODELS["stack"]
    assert isinstance(model, Model)
    assert model_for(Stack([(1.0, 0.3)])) is model and model_for(st.Block(1.0, 0.3)) is not model


def test_the_verdict_says_what_the_run_did(rocking):
    # rest: a table at rest leaves the stack at rest (no uplift: theta stays exactly 0)
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    still = simulate_stack(stack, st.Motion([0.0, 1.0], [0.0, 0.0]))
    assert still.verdict() == "stayed at rest"
    # rocking: the peaks quoted are the run's own max |theta|, bottom block first
    peaks = np.abs(rocking.theta).max(axis=0)
    assert rocking.status == "completed" and peaks.any()
    # the sine still drives the stack at the run's end: not at rest, said so
    assert rocking.still_moving
    assert rocking.verdict() == ("rocked: max |θ| = " + ", ".join(f"{p:.3g}" for p in peaks)
                                 + " rad (bottom to top); " + rocking.end_state())
    # overturning: a constant table acceleration of 2 g topples a 4:1 column one way
    slender = Stack([st.Block(1.0, 0.25), st.Block(1.0, 0.25)])
    t = np.arange(0.0, 3.0, 0.01)
    fallen = simulate_stack(slender, st.Motion(t, np.full_like(t, 2.0 * G)))
    assert fallen.status == "overturned"
    name = ["block 0 (bottom)", "block 1 (top)"][fallen.overturned_block]
    assert fallen.verdict() == f"{name} overturned at {fallen.t_overturn:.2f} s"


def test_a_stack_cut_while_falling_is_said_to_be_still_moving():
    # released at 1.5 alpha on a table at rest, a block (and a stack moving as one body)
    # moves outward: theta'' = p^2 (theta - alpha) > 0 for theta > alpha (Eq. 2-3 with the
    # table at rest), so |theta| only grows: at the end of a short run it is past alpha,
    # not at rest, and the verdict must say so as the single block's does
    stack = Stack([st.Block(1.0, 0.1), st.Block(1.0, 0.1)])
    alpha = stack.blocks[0].alpha
    result = simulate_stack(stack, theta0=(1.5 * alpha, 1.5 * alpha), duration=0.05)
    assert result.status == "completed" and result.still_moving
    assert result.past_alpha_at_end == (0, 1)
    assert "still moving at the end of the run (t = 0.05 s)" in result.verdict()
    assert "block 0 (bottom), block 1 (top) past α" in result.verdict()
    summary = result.summary()
    assert summary["still moving at the end"] is True
    assert summary["past alpha at the end"] == ["block 0 (bottom)", "block 1 (top)"]
    # a stack standing still (no motion: nothing moves it) is not
    still = simulate_stack(stack, duration=0.05)
    assert not still.still_moving and still.end_state() == "" and still.verdict() == "stayed at rest"


def test_default_masses_are_concrete_per_metre_of_depth():
    # no masses given: 2400 kg/m^3 (concrete) over 1 m of depth, m_i = 2400 B_i H_i [kg];
    # at rest on a table accelerating 0.5 m/s^2 up and across, the base carries the whole
    # weight, N_0 = (m_0 + m_1) (g + v'') [N] (statics), the interface m_1 (g + v'')
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    masses = 2400.0 * np.array([0.3 * 1.0, 0.2 * 0.8])
    assert np.allclose(stack.mass, masses, rtol=1e-15)
    assert stack.weight == pytest.approx(G * masses.sum(), rel=1e-15)
    result = simulate_stack(stack, st.Motion([0.0, 1.0], [0.5, 0.5], [0.5, 0.5]))
    assert np.allclose(result.forces[:, 0, 0], masses.sum() * (G + 0.5), rtol=1e-12)
    assert np.allclose(result.forces[:, 1, 0], masses[1] * (G + 0.5), rtol=1e-12)
    summary = result.summary()
    assert summary["masses [kg]"] == pytest.approx(list(masses), rel=1e-15)
    assert summary["masses"].startswith("masses: uniform density, assumed 2400 kg/m^3")
    assert "1 m of depth" in summary["masses"]
    # the motion depends on the mass ratios only: the same run with the areas given as
    # masses moves bit for bit alike, its forces 2400 times smaller
    t = np.arange(0.0, 0.6, 0.01)
    motion = st.Motion(t, 4.0 * np.sin(9.0 * t), name="sine")
    default = simulate_stack(stack, motion)
    areas = simulate_stack(Stack(stack.blocks, masses=tuple(stack.m)), motion)
    assert np.array_equal(default.theta, areas.theta)
    assert np.allclose(default.forces, 2400.0 * areas.forces, rtol=1e-13, atol=0.0)
    assert np.allclose(default.energy, 2400.0 * areas.energy, rtol=1e-12)
    assert "(given, bottom first)" in areas.summary()["masses"]


def test_the_demands_of_a_standing_column_are_told_apart_from_those_of_its_fall():
    # a 4:1 column under a constant 2 g table acceleration topples: the friction it needs
    # and the top corner's excursion while it falls (F/N grows without bound as a corner
    # force tends to zero) say nothing of what a standing column needs; the result gives
    # the peaks before the first block passes its own alpha (beyond static stability:
    # with the table at rest gravity no longer pulls it back, Eq. 2-3)
    slender = Stack([st.Block(1.0, 0.25), st.Block(1.0, 0.25)])
    t = np.arange(0.0, 3.0, 0.01)
    with pytest.warns(StackFrictionWarning) as caught:
        fallen = simulate_stack(slender, st.Motion(t, np.full_like(t, 2.0 * G)))
    assert fallen.status == "overturned"
    alphas = np.array([block.alpha for block in slender.blocks])
    falling = fallen.t_past_alpha
    k = int(np.searchsorted(fallen.t, falling))
    # the first sample past alpha, and none before it
    assert np.any(np.abs(fallen.theta[k]) > alphas)
    assert np.all(np.abs(fallen.theta[:k]) <= alphas)
    demand, excursion = fallen.peak_before_past_alpha()
    whole = fallen.friction_demand[np.isfinite(fallen.friction_demand)]
    assert 0.0 <= demand <= whole.max() and demand < 1.0 < whole.max()
    assert 0.0 < excursion < fallen.peak_excursion
    # the warning says the model left its assumptions only while the column fell
    friction = [str(item.message) for item in caught
                if issubclass(item.category, StackFrictionWarning)]
    assert friction and "the column was already falling" in friction[0]
    summary = fallen.summary()
    assert summary["t_past_alpha [s]"] == falling
    assert summary["max F/N before past alpha [-]"] == demand
    # a column that never passes its alpha: the whole run, and no time
    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)])
    still = simulate_stack(stack, st.Motion([0.0, 1.0], [0.0, 0.0]))
    assert np.isnan(still.t_past_alpha) and still.peak_before_past_alpha() == (0.0, 0.0)


def test_a_column_that_barely_reaches_its_uplift_threshold_is_not_said_to_rock():
    # two equal 1 x 0.2 m blocks tip as one body at A1 = g b (m1 + m2) / (m1 h + m2 3 h)
    # = 0.1 g (docs/stack.md, uplift thresholds); a table acceleration that passes it by
    # 1e-6 of itself for 0.02 s turns the column by about 1e-9 rad, under 1e-6 alpha
    stack = Stack([st.Block(1.0, 0.2), st.Block(1.0, 0.2)])
    t = np.arange(0.0, 0.2, 0.01)
    u = np.where((t > 0.05) & (t < 0.07), (1.0 + 1e-6) * 0.1 * G, 0.09 * G)
    result = simulate_stack(stack, st.Motion(t, u))
    peaks = np.abs(result.theta).max(axis=0)
    alpha = math.atan(0.2)
    assert 0.0 < peaks.max() < 1e-6 * alpha
    assert result.verdict().startswith(
        "touched its uplift threshold (max |θ| " + ", ".join(f"{p:.3g}" for p in peaks)
        + " rad, bottom to top: under 1e-06 α, no rocking to speak of)")
    # a block past 1e-6 of its alpha rocked, whatever the other's peak
    from shaketable.models.stack.result import verdict_text

    alphas = np.array([alpha, alpha])
    for peaks, word in (((1e-9, 2e-6 * alpha), "rocked"), ((1e-9, 0.5e-6 * alpha), "touched")):
        assert verdict_text(2, "completed", -1, math.nan, math.nan, np.array(peaks), alphas,
                            False, 1.0, ()).startswith(word)
