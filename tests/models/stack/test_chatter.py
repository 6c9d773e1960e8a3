"""Columns whose contacts chatter below the integrator's resolution run to the end, and their
answers converge with the tolerance and agree between the two engines.

Every case here stopped the engines before (StackChatter, at every tolerance tried):

- a landing that leaves phi = 0 from rest (an uplift, s phi'' > 0) was "found" at its start
  when the flight was shorter than the step carried into it (its event function, s phi /
  elapsed, is zero there): the interface closed at rate zero, opened again a look-ahead
  later, ... (200 events in a row);
- a plastic landing that opens another interface with a flight below the resolution (it
  rises less than rtol alpha_min): that one lands at once, its landing opens the first
  again at a smaller rate, ... (a cascade over two or more interfaces, each flight shorter
  than the last, without end). The engines now hold such interfaces flat: the limit of
  those alternating plastic landings, each an energy projection of the velocities, is the
  projection with all of them held (``Run.closure``).

The record of each: the "olive-view" substitute (seed 3, 4 s) at 0.15 g, or the first
2 s of El Centro 1940 (180), plastic law.
"""

from __future__ import annotations

import numpy as np
import pytest

from shaketable import Block
from shaketable.core.motion import Motion
from shaketable.ground import records
from shaketable.ground.artificial import artificial
from shaketable.models.stack import Stack
from shaketable.models.stack.engine import StackChatter


def _olive_view():
    return artificial("olive-view", seed=3, duration=4.0).scaled(0.3)   # pga 0.15 g


def _run(stack, motion, rtol, method="compiled"):
    """theta [rad] (samples x blocks) and the number of events of one run at ``rtol``."""
    from shaketable.models.stack import compiled, engine

    integrate = compiled.integrate if method == "compiled" else engine.integrate
    zeros = np.zeros(stack.n)
    out = integrate(stack, motion, law="plastic", cor=0.0, theta0=zeros, theta_dot0=zeros,
                    rtol=rtol, rest_tolerance=1e-6 / stack.blocks[0].p,
                    max_recorded_events=10)
    assert out["run"].status == "completed" and out["filled"] == motion.t.size
    return out["theta"], out["run"].n_events


def test_a_three_high_column_runs_to_the_end_converged_in_both_engines():
    # 30 x 6 in on two 4 x 1 ft blocks (one density): stopped at t = 2.316 s before, at
    # rtol 1e-10, 1e-11 and 1e-12. Now: the compiled engine at 1e-10 against itself at
    # 1e-12 and against the SciPy engine at 1e-10 (measured: within 1.2e-13 of alpha)
    stack = Stack([Block.parse("4x1ft"), Block.parse("4x1ft"), Block.parse("30x6in")])
    motion = _olive_view()
    alpha = stack.alpha_min
    theta, _ = _run(stack, motion, 1e-10)
    tight, _ = _run(stack, motion, 1e-12)
    scipy, _ = _run(stack, motion, 1e-10, method="reference")
    assert np.abs(theta).max() > 0.1 * alpha   # it rocks: 0.18 alpha
    assert np.abs(theta - tight).max() < 1e-11 * alpha
    assert np.abs(theta - scipy).max() < 1e-11 * alpha


def test_a_cascade_over_two_interfaces_runs_to_the_end():
    # the same column with masses 1, 0.5, 0.25: the bottom two interfaces land in turn,
    # each landing opening the other (rates 1e-5 .. 1e-8 rad/s, flights of microseconds),
    # then all three; stopped at t = 2.46-2.55 s before at every tolerance. It barely rocks
    # (peak theta/alpha 1e-3 .. 2e-3) and its chatter is chaotic (the event sequences of
    # two tolerances part), but the peaks agree (measured: to 3e-11 relative, 1e-10 to 1e-12)
    stack = Stack([Block.parse("4x1ft"), Block.parse("4x1ft"), Block.parse("30x6in")],
                  masses=(1.0, 0.5, 0.25))
    motion = _olive_view()
    theta, events = _run(stack, motion, 1e-10)
    tighter, _ = _run(stack, motion, 1e-11)
    assert events > 1000   # the chatter is there, and ends
    np.testing.assert_allclose(np.abs(theta).max(axis=0), np.abs(tighter).max(axis=0),
                               rtol=1e-4)


def test_a_two_block_column_that_stalled_completes_at_every_tolerance():
    # 30 x 6 in (mass ratio 0.5) on 60 x 12 in: stopped at t = 2.088 s at rtol 1e-10
    # before (the top block at its uplift threshold); now it completes at 1e-10 and agrees
    # with 1e-12 to 1e-5 of alpha (the block barely rocks: peak theta/alpha ~2e-4)
    stack = Stack([Block.parse("60x12in"), Block.parse("30x6in")], masses=(1.0, 0.5))
    motion = _olive_view()
    theta, _ = _run(stack, motion, 1e-10)
    tight, _ = _run(stack, motion, 1e-12)
    assert np.abs(theta - tight).max() < 1e-5 * stack.alpha_min


def test_a_column_of_ten_runs_to_the_end():
    # ten 8 x 2 ft blocks under the first 2 s of El Centro 1940 (180): stopped at
    # t = 1.78 s before (200 events in a row). From there on the column rocks by a few
    # thousandths of alpha with its ten contacts chattering (~5,000 events): which of two
    # contacts at zero gap lands first depends on the tolerance, so the histories of two
    # tolerances part by up to a tenth of the peak (measured from 1e-9 to 1e-13); the peak
    # of the column agrees to a few per cent
    record = records.load("el-centro-1940-180")
    count = int(round(2.0 / record.dt)) + 1
    vertical = None if record.vertical is None else record.vertical[:count]
    motion = Motion(record.t[:count], record.horizontal[:count], vertical)
    stack = Stack([Block.parse("8x2ft")] * 10)
    theta, _ = _run(stack, motion, 1e-10)
    tighter, _ = _run(stack, motion, 1e-11)
    assert np.abs(theta).max() > 1e-3 * stack.alpha_min
    assert np.abs(theta).max() == pytest.approx(np.abs(tighter).max(), rel=0.05)


def test_impacts_without_end_in_one_input_interval_stop_the_run(monkeypatch):
    # the guard behind every other: past MAX_EVENTS_PER_INTERVAL events in one input
    # interval the run stops with StackChatter instead of running on (the SciPy engine,
    # whose limit can be lowered here: the compiled engine's is compiled in). The column of
    # the first test has 48 events in its busiest input interval (261 over its 400, the
    # first past 5 at t = 2.21 s), so a limit of 5 is passed
    from shaketable.models.stack import engine

    monkeypatch.setattr(engine, "MAX_EVENTS_PER_INTERVAL", 5)
    stack = Stack([Block.parse("4x1ft"), Block.parse("4x1ft"), Block.parse("30x6in")])
    with pytest.raises(StackChatter, match="more than 5 events in one input interval"):
        _run(stack, _olive_view(), 1e-10, method="reference")
