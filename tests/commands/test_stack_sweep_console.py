"""``risk`` and ``sweep`` on a stack sweep: the block alone's count is said apart from "which
block of a stack fell", and ``sweep`` leads its console output with the answer."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from shaketable.cli import main


def _stack_sweep_folder(path):
    """A finished stack sweep written by hand: one block alone and its two-block stack,
    14 runs each on 14 PGV levels (0 the weakest); the block alone overturns at levels 4 to
    13 but 12 (9 of 14; not separable, so a fragility fits), the stack at levels 3, 6 and 8
    to 13 (8 of 14), its top block at level 3, its bottom block the 7 other times."""
    pgv = np.geomspace(0.05, 2.0, 14)
    alone = np.zeros(14, bool)
    alone[5:] = True
    alone[12], alone[4] = False, True       # 9 of 14, not separable
    stack = np.zeros(14, bool)
    stack[6:] = True
    stack[3], stack[7] = True, False        # 8 - 1 + 1 = 8 of 14
    which = np.where(stack, 0, -1)
    which[np.flatnonzero(stack)[0]] = 1     # the top block fell once
    rows = []
    for blocks, label, fell, block_fell in ((1, "30 x 6 in", alone, np.where(alone, 0, -1)),
                                            (2, "2 blocks: 30 x 6 in on 30 x 6 in", stack,
                                             which)):
        for k in range(14):
            rows.append({"block": label, "cor [-]": np.nan, "record": f"r{k % 4}",
                         "pgv [m/s]": pgv[k], "overturned": bool(fell[k]),
                         "overturned block": int(block_fell[k]), "blocks": blocks,
                         "R [m]": 0.3, "base width [m]": 0.15, "status": "completed"})
    path.mkdir()
    pd.DataFrame(rows).to_csv(path / "results.csv", index=False)
    (path / "manifest.json").write_text(json.dumps({"format": "csv", "n_chunks": 1,
                                                   "n_runs": len(rows)}))
    return path


def test_risk_says_the_block_alone_apart_from_the_block_that_fell(tmp_path, capsys):
    folder = _stack_sweep_folder(tmp_path / "stacks")
    assert main(["risk", str(folder), "--hazard", "example"]) == 0
    out = capsys.readouterr().out
    assert "a block alone 9" not in out, out
    # counted by hand from the rows above
    assert "    overturned in 9 of 14 runs (a block alone)" in out.splitlines(), out
    assert ("    overturned in 8 of 14 runs; the block that fell: block 1 (top) 1, "
            "block 0 (bottom) 7") in out.splitlines(), out


def test_overturned_line_counts_by_hand():
    from shaketable.sweeps.stacks import overturned_line

    rows = pd.DataFrame({"blocks": [3, 3, 3, 3], "overturned": [True, True, False, True],
                         "overturned block": [1, 2, -1, 1]})
    assert overturned_line(rows) == ("overturned in 3 of 4 runs; the block that fell: "
                                     "block 2 (top) 1, block 1 2")
    alone = pd.DataFrame({"blocks": [1, 1], "overturned": [False, True],
                          "overturned block": [-1, 0]})
    assert overturned_line(alone) == "overturned in 1 of 2 runs (a block alone)"
    assert overturned_line(pd.DataFrame({"overturned": [True]})) == ""


TINY_STACK_SWEEP = """name = "tiny-stacks"
description = "two PGA levels, a block alone and two high, one 2-s substitute record"
seed = 1

[stacks]
sizes = ["30x6in"]
blocks = [1, 2]

[rocking]
cor = "plastic"

[[records]]
preset = "olive-view"
seeds = 1
duration = "2 s"

[intensity]
pga = ["0.1 g", "0.6 g"]
"""


def test_sweep_leads_its_output_with_the_answer(tmp_path, capsys):
    (tmp_path / "tiny.toml").write_text(TINY_STACK_SWEEP, encoding="utf-8")
    assert main(["sweep", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "o"),
                 "--no-progress"]) == 0
    printed = capsys.readouterr()
    lines = printed.out.splitlines()
    # the answer first; what ran (runs, chunks, the model) beside the progress, on stderr
    assert lines[0].startswith("tiny-stacks: ") and " of 4 runs overturn" in lines[0], lines
    assert lines[1].startswith("tiny-stacks: computed 4 runs in "), lines
    assert "4 runs in 1 chunk(s) of" in printed.err and "the stack model" in printed.err


def test_a_stalled_run_is_a_row_and_no_survivor(tmp_path, capsys, monkeypatch):
    # the two-block runs stall at every tolerance: the sweep still writes all four rows,
    # counts the falls over the two finished runs and says what it left out
    from tests.helpers import stack_engine_stalling

    stack_engine_stalling(monkeypatch, None, blocks=2)
    (tmp_path / "tiny.toml").write_text(TINY_STACK_SWEEP, encoding="utf-8")
    status = main(["sweep", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "o"),
                   "--no-progress"])
    printed = capsys.readouterr()
    assert status == 1   # runs without results: said on stderr, as stopped runs are
    table = pd.read_csv(tmp_path / "o" / "results.csv") if (
        tmp_path / "o" / "results.csv").exists() else pd.read_parquet(
        tmp_path / "o" / "results.parquet")
    assert len(table) == 4
    assert sorted(table["status"][table["blocks"] == 2]) == ["stalled", "stalled"]
    assert table["verdict"][table["blocks"] == 2].str.startswith("stalled: ").all()
    lines = printed.out.splitlines()
    assert " of 2 runs overturn" in lines[0] and "2 of 4 runs stalled (excluded)" in lines[0], \
        lines
    assert "a stack run that stalled has none and is left out of the fits" in printed.err


def test_risk_leaves_a_stalled_run_out_of_the_fit(tmp_path, capsys):
    # the hand-made sweep with one more run of the stack, stalled at the highest level: its
    # overturned is False, and counting it as a survival would change the fit
    folder = _stack_sweep_folder(tmp_path / "stacks")
    assert main(["risk", str(folder), "--hazard", "example"]) == 0
    before = capsys.readouterr().out.splitlines()
    table = pd.read_csv(folder / "results.csv")
    extra = table[table["blocks"] == 2].iloc[[-1]].assign(
        overturned=False, status="stalled", **{"overturned block": -1})
    pd.concat([table, extra]).to_csv(folder / "results.csv", index=False)
    assert main(["risk", str(folder), "--hazard", "example"]) == 0
    after = capsys.readouterr().out.splitlines()
    fragility = [line for line in before if line.startswith("    fragility")]
    assert fragility == [line for line in after if line.startswith("    fragility")]
    assert ("    overturned in 8 of 14 runs; the block that fell: block 1 (top) 1, "
            "block 0 (bottom) 7; 1 of 15 runs stalled (excluded)") in after, after


def test_columns_of_several_heights_are_named():
    from shaketable.sweeps.stacks import overturned_blocks

    rows = pd.DataFrame({"blocks": [3, 2, 2, 3, 3, 1], "overturned": [True] * 5 + [True],
                         "overturned block": [0, 0, 0, 2, 0, 0]})
    assert overturned_blocks(rows) == ("a block alone 1; 2 high: block 0 (bottom) 2; "
                                       "3 high: block 2 (top) 1, block 0 (bottom) 2")
    two = rows[rows["blocks"] == 2]
    assert overturned_blocks(two) == "block 0 (bottom) 2"
