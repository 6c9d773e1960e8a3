"""A run that stalls (StackChatter) is made again at a tighter tolerance, says so, and gives
the tighter run's answer (one run, the batch).

The stall is injected (``tests.helpers.stack_engine_stalling``: the compiled engine raises
StackChatter at rtol 1e-10 and runs as usual at any other tolerance): which real runs
stall is a defect the engines remove where one is found (``test_chatter.py``), while the
retry stays the safety net for the next one. The runs themselves are real: a 30 x 6 in
block (mass ratio 0.5) on a 60 x 12 in one, the "olive-view" substitute record (seed 3,
4 s) at 0.15 g, the plastic law.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from shaketable import Block
from shaketable.ground.artificial import artificial
from shaketable.models.stack import (
    Stack,
    StackRetryWarning,
    StackStalledWarning,
    simulate_stack,
)
from shaketable.models.stack.batch import simulate_many
from shaketable.models.stack.engine import StackChatter
from shaketable.models.stack.model import integrate_retrying
from tests.helpers import stack_engine_stalling

STALLED_RTOL = 1e-10


@pytest.fixture(scope="module")
def case():
    stack = Stack([Block.parse("60x12in"), Block.parse("30x6in")], masses=(1.0, 0.5))
    motion = artificial("olive-view", seed=3, duration=4.0).scaled(0.3)   # pga 0.15 g
    return stack, motion


def test_the_stalled_run_is_made_again_tighter_and_says_so(case, monkeypatch):
    stack, motion = case
    stack_engine_stalling(monkeypatch, STALLED_RTOL)
    with pytest.warns(StackRetryWarning, match=r"stalled \(at rtol 1e-10: .*2\.08799.*\) and "
                                               r"was run again at rtol 1e-11"):
        result = simulate_stack(stack, motion, rtol=STALLED_RTOL)
    assert result.status == "completed" and result.t[-1] == motion.t[-1]
    assert result.statistics["rtol"] == pytest.approx(1e-11, rel=1e-12)
    # the answer is the tighter run's: the same bits as a run asked at rtol / 10 (no retry)
    tighter = simulate_stack(stack, motion, rtol=STALLED_RTOL / 10.0)
    assert np.array_equal(result.theta, tighter.theta)
    # and against the default tolerance (1e-12, ten times tighter still), the rotations
    # agree to 1e-5 of alpha (the block barely rocks: its peak theta/alpha is ~2e-4)
    reference = simulate_stack(stack, motion)
    alpha = stack.alpha_min
    assert np.abs(result.theta - reference.theta).max() < 1e-5 * alpha
    assert np.abs(result.theta).max() == pytest.approx(np.abs(reference.theta).max(), rel=0.05)


def test_a_run_that_completes_warns_nothing_and_keeps_its_tolerance(case):
    stack, motion = case
    with warnings.catch_warnings():
        warnings.simplefilter("error", StackRetryWarning)
        result = simulate_stack(stack, motion, rtol=1e-9)
    assert result.statistics["rtol"] == 1e-9


@pytest.mark.parametrize("threads", [1, 2])
def test_the_batch_row_is_the_retried_run_and_carries_its_tolerance(case, threads,
                                                                  monkeypatch):
    # two runs that share the stack and the motion (scale 1 stalls, scale 0.5 does not):
    # the warning names the run, its scale and its law, and points at this call whichever
    # thread ran it
    stack, motion = case
    stack_engine_stalling(monkeypatch, STALLED_RTOL, above_pga=0.75 * motion.pga)
    with pytest.warns(StackRetryWarning) as caught:
        table = simulate_many([stack], {"olive-view 3": motion}, scales=(1.0, 0.5),
                              rtol=STALLED_RTOL, threads=threads)
    said = [item for item in caught if issubclass(item.category, StackRetryWarning)]
    assert len(said) == 1, [str(item.message) for item in said]
    assert str(said[0].message).startswith(
        f"run 0 ({stack.describe()}, olive-view 3, scale 1, plastic impacts): the run stalled "
        "(at rtol 1e-10: "), str(said[0].message)
    assert str(said[0].message).endswith("was run again at rtol 1e-11")
    assert said[0].filename == __file__
    row = table.iloc[0]
    assert list(table["scale [-]"]) == [1.0, 0.5]
    assert list(table["rtol [-]"]) == pytest.approx([1e-11, STALLED_RTOL], rel=1e-12)
    with pytest.warns(StackRetryWarning):
        result = simulate_stack(stack, motion, rtol=STALLED_RTOL)
    assert row["status"] == "completed"
    assert row["max |theta| top [rad]"] == np.abs(result.theta[:, -1]).max()
    assert row["max |theta| bottom [rad]"] == np.abs(result.theta[:, 0]).max()


def test_every_tolerance_stalling_is_an_error_naming_each():
    calls = []

    def always_chatters(stack, motion, *, rtol):
        calls.append(rtol)
        raise StackChatter(f"stack model: 200 events in a row at t = 1.5 s (rtol {rtol:g})")

    with pytest.raises(StackChatter, match=r"at rtol 1e-10: .*; at rtol 1e-11: .*; at rtol "
                                           r"1e-12: .*every tolerance tried"):
        integrate_retrying(always_chatters, None, None, rtol=1e-10)
    assert calls == pytest.approx([1e-10, 1e-11, 1e-12], rel=1e-12)
    calls.clear()
    with pytest.raises(StackChatter):   # never below 1e-14, each tolerance once
        integrate_retrying(always_chatters, None, None, rtol=1e-13)
    assert calls == pytest.approx([1e-13, 1e-14], rel=1e-12)


def test_a_run_stalled_at_every_tolerance_is_a_row_and_the_others_are_kept(case, monkeypatch):
    # the three-block run stalls at every tolerance tried: its row says so and holds no
    # results; the two-block run beside it is the row it is alone
    stack, motion = case
    tall = Stack([Block.parse("60x12in")] * 3)
    alone = simulate_many([stack], {"olive-view 3": motion}, rtol=STALLED_RTOL)
    stack_engine_stalling(monkeypatch, None, blocks=3)
    with pytest.warns(StackStalledWarning) as caught:
        table = simulate_many([stack, tall], {"olive-view 3": motion}, rtol=STALLED_RTOL)
    said = [str(item.message) for item in caught if item.category is StackStalledWarning]
    assert len(said) == 1 and said[0].startswith(
        f"run 1 ({tall.describe()}, olive-view 3, scale 1, plastic impacts): stalled"), said
    assert "every tolerance tried" in said[0]
    assert caught[0].filename == __file__
    assert list(table["status"]) == ["completed", "stalled"]
    stalled = table.iloc[1]
    assert stalled["verdict"].startswith("stalled: at rtol 1e-10: ")
    assert "2.08799" in stalled["verdict"] and "at rtol 1e-12" in stalled["verdict"]
    assert stalled["rtol [-]"] == pytest.approx(1e-12, rel=1e-12)   # the last tried
    assert not stalled["overturned"] and stalled["overturned block"] == -1
    for column in ("max_theta_ratio [-]", "max |theta| top [rad]", "t_start [s]",
                   "max |theta| block 2 [rad]", "t_end [s]"):
        assert np.isnan(stalled[column]), column
    # the good row is the one computed alone, column by column
    pd.testing.assert_frame_equal(table.iloc[[0]].drop(columns=[
        name for name in table if "block 2" in name]), alone, check_dtype=False)
