"""A stack run made again at a tighter tolerance is said as the assumption warnings are
(the run's warnings list, the ``warning:`` lines of ``run`` and ``simulate --stack``), not
printed raw by Python; a study's quiet run keeps it out of sight and its rows carry the
tolerance; a stack sweep's summary counts the rows computed tighter than its spec's rtol.

The case is the one of ``tests/models/stack/test_retry.py``: a 30 x 6 in block (mass
ratio 0.5) on a 60 x 12 in one, the "olive-view" substitute record (seed 3, 4 s) at
0.15 g, with a stall at rtol 1e-10 injected (``tests.helpers.stack_engine_stalling``); the
runs at 1e-11 are real.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from shaketable import Block
from shaketable.ground.artificial import artificial
from shaketable.models.stack import Stack, StackRetryWarning
from tests.helpers import stack_engine_stalling

STALLED_RTOL = 1e-10


def _case():
    stack = Stack([Block.parse("60x12in"), Block.parse("30x6in")], masses=(1.0, 0.5))
    return stack, artificial("olive-view", seed=3, duration=4.0).scaled(0.3)   # 0.15 g


def test_a_retry_is_said_with_the_runs_warnings_and_not_raised(monkeypatch):
    from shaketable.scenes.stack import run_quietly
    from shaketable.studies.stacks import quiet_stack_run

    stack, motion = _case()
    stack_engine_stalling(monkeypatch, STALLED_RTOL)
    with warnings.catch_warnings():
        warnings.simplefilter("error", StackRetryWarning)   # raw: the test fails
        result, said = run_quietly(stack, motion, rtol=STALLED_RTOL)
        quiet = quiet_stack_run(stack, motion, rtol=STALLED_RTOL)
    assert len(said) == 1 and "at rtol 1e-10: " in said[0] and "2.08799" in said[0], said
    assert said[0].endswith("was run again at rtol 1e-11"), said
    assert result.statistics["rtol"] == pytest.approx(1e-11, rel=1e-12)
    assert quiet.statistics["rtol"] == result.statistics["rtol"]
    assert np.array_equal(quiet.theta, result.theta)


def test_the_study_text_names_the_rows_computed_tighter():
    from shaketable.studies.stacks import retried_runs

    records = pd.DataFrame({"record": ["r", "r", "r"], "blocks high": [1, 2, 3],
                            "rtol [-]": [np.nan, 1e-7, 1e-8]})
    assert retried_runs(records, 1e-7) == "; three high under r at rtol 1e-08 (a stall at 1e-07)"
    assert retried_runs(records.iloc[:2], 1e-7) == ""


def test_the_sweep_summary_counts_the_rows_computed_tighter():
    from shaketable.sweeps.stacks import retried_line

    table = pd.DataFrame({"rtol [-]": [1e-10, 1e-11, 1e-10, 1e-12, 1e-11]})
    assert retried_line(table, 1e-10) == (
        "3 of 5 runs stalled at the spec's rtol 1e-10 and were computed again at a tighter "
        "one (1e-11, 1e-12; the rtol [-] column)")
    assert retried_line(table[table["rtol [-]"] == 1e-10], 1e-10) == ""
    assert retried_line(pd.DataFrame({"blocks": [2]}), 1e-10) == ""


CHATTER_SWEEP = """name = "chatter"
description = "a stack whose run at rtol 1e-10 stalls (injected); 1e-11 completes"
seed = 3

[stacks]
columns = [["60x12in", "30x6in"]]
mass_ratios = [0.5]

[rocking]
rtol = 1e-10

[[records]]
preset = "olive-view"
duration = "4 s"

[intensity]
scale = [0.3]
"""


def test_a_stack_sweep_says_its_retried_run_in_the_summary_not_raw(tmp_path, capsys,
                                                                    monkeypatch):
    from shaketable.cli import main

    stack_engine_stalling(monkeypatch, STALLED_RTOL)   # one chunk: computed in this process
    (tmp_path / "chatter.toml").write_text(CHATTER_SWEEP, encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("error", StackRetryWarning)   # raw: the sweep stops
        assert main(["sweep", str(tmp_path / "chatter.toml"), "--out", str(tmp_path / "o"),
                     "--no-progress"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert ("chatter: 1 of 1 runs stalled at the spec's rtol 1e-10 and were computed again "
            "at a tighter one (1e-11; the rtol [-] column)") in lines, lines
