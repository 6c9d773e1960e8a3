"""The model axis of sweeps: stacks swept over records and intensities, stored, resumed and
fitted; a folder of store format 2 resumed; the spec's model chosen and refused by key.

The stack runs are kept short (a 1.5 s record of one half-sine pulse, DOP853 at 1e-8):
the stack model is SciPy's integrator, not a compiled batch.
"""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.sweeps.base import SweepError
from shaketable.sweeps.execute import run_sweep
from shaketable.sweeps.spec import spec_from_dict
from shaketable.sweeps.store import FORMAT_VERSION

FIXTURES = Path(__file__).parent / "data"

#: The spec of ``data/format-2-sweep`` (see :func:`test_a_format_2_folder_resumes`).
FORMAT_TWO_SPEC = {"name": "format-two", "seed": 1, "blocks": {"sizes": ["4x1ft", "30x6in"]},
                   "rocking": {"cor": 0.9},
                   "records": [{"preset": "A-1", "seeds": 1, "duration": "3 s",
                                "dt": "0.01 s"}],
                   "intensity": {"pga": ["0.3 g", "0.6 g"]}, "run": {"chunk_size": 2}}


def _pulses(folder: Path) -> dict:
    """Two record files [g]: one half-sine pulse of 0.25 s ("short") and of 0.6 s ("long"),
    then rest, to 1.5 s, sampled every 0.05 s (the table's acceleration is linear between
    samples: the runs are exact for that input, and short)."""
    paths = {}
    for name, width in (("short", 0.25), ("long", 0.6)):
        t = np.round(np.arange(0.0, 1.5 + 1e-9, 0.05), 10)
        a = np.where(t < width, np.sin(np.pi * t / width), 0.0)
        paths[name] = folder / f"{name}.csv"
        np.savetxt(paths[name], np.column_stack([t, a]), delimiter=",", header="t,a",
                   comments="")
    return paths


def _stack_spec(folder: Path, **changes) -> dict:
    paths = _pulses(folder)
    spec = {"name": "stack-pulses",
            "stacks": {"sizes": ["30x6in"], "blocks": 2, "mass_ratios": [0.5]},
            "rocking": {"rtol": 1e-7},
            "records": [{"file": str(paths["short"]), "units": "g"},
                        {"file": str(paths["long"]), "units": "g"}],
            "intensity": {"pga": ["0.15 g", "0.25 g", "0.4 g"]}, "run": {"chunk_size": 4}}
    spec.update(changes)
    return spec


@pytest.fixture(scope="module")
def stack_sweep(tmp_path_factory):
    """A stack sweep (2 records x 3 PGAs; two 30x6in blocks, the top one half the bottom
    one's mass), run whole."""
    folder = tmp_path_factory.mktemp("stack-sweep")
    spec = spec_from_dict(_stack_spec(folder), where="stack.toml")
    outcome = run_sweep(spec, folder / "out", progress=False, fmt="csv")
    return spec, outcome


def test_stack_rows_start_rocking_at_the_closed_form_uplift(stack_sweep):
    """Each run's first uplift is where the table's acceleration reaches (g) A1 =
    g b (m1 + m2) / (m1 h + m2 3 h): the two equal blocks tip as one body (the threshold of
    the whole stack about a base corner, below the top block's own b / h), found on the
    record as the sweep scaled it (linear between samples)."""
    spec, outcome = stack_sweep
    table = outcome.table
    assert len(table) == spec.n_runs == 6
    block = Block.parse("30x6in")
    for _, row in table.iterrows():
        ratio = row["mass ratio [-]"]
        a1 = block.b * (1.0 + ratio) / (block.h + ratio * 3.0 * block.h)
        record = np.loadtxt(spec.records[0].file if row["record"] == "short"
                            else spec.records[1].file, delimiter=",", skiprows=1)
        u = record[:, 1] * G * row["scale [-]"]
        k = int(np.argmax(u >= a1 * G))
        expected = record[k - 1, 0] + (a1 * G - u[k - 1]) / (u[k] - u[k - 1]) * 0.05
        assert row["t_start [s]"] == pytest.approx(expected, abs=1e-7)
    assert set(table["block"]) == {"2 blocks: 30 x 6 in on 30 x 6 in, mass ratio 0.5"}


def test_stack_rows_say_which_block_fell(stack_sweep):
    """``overturned`` is some block falling; ``overturned block`` and the verdict name it."""
    _, outcome = stack_sweep
    table = outcome.table
    fell = table["overturned"].astype(bool)
    assert fell.any() and not fell.all()
    assert (fell == (table["status"] == "overturned")).all()
    assert (fell == (table["overturned block"] >= 0)).all()
    assert table["t_overturn [s]"][fell].notna().all()
    assert table["max_theta_ratio [-]"][fell].isna().all()
    for _, row in table[fell].iterrows():
        index = int(row["overturned block"])
        name = "block 0 (bottom)" if index == 0 else "block 1 (top)"
        assert row["verdict"].startswith(f"{name} overturned at")
    assert table["impact"].eq("plastic").all() and table["cor [-]"].isna().all()


def test_a_killed_stack_sweep_resumes_to_the_same_table(stack_sweep, tmp_path):
    spec, outcome = stack_sweep
    folder = tmp_path / "resumed"
    shutil.copytree(outcome.out, folder)
    (folder / "parts" / "part-000001.csv").unlink()
    (folder / "results.csv").unlink()
    resumed = run_sweep(spec, folder, resume=True, progress=False, fmt="csv")
    assert (resumed.computed_runs, resumed.skipped_runs) == (2, 4)
    assert (folder / "results.csv").read_bytes() == (outcome.out / "results.csv").read_bytes()
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["model"]["model"].startswith("stack")


def test_stack_sweeps_in_processes_give_the_sequential_table(tmp_path):
    """``workers=2``: a tiny stack sweep's two chunks in two processes of their own, written
    as they end; the parts and the table are byte-identical to the sequential run's."""
    data = _stack_spec(tmp_path, stacks={"sizes": ["30x6in"], "blocks": 1},
                       intensity={"pga": ["0.25 g", "0.4 g"]}, run={"chunk_size": 1})
    data["records"] = data["records"][1:]
    spec = spec_from_dict(data, where="tiny.toml")
    assert spec.n_chunks == 2 and spec.model.processes
    one = run_sweep(spec, tmp_path / "one", progress=False, fmt="csv")
    two = run_sweep(spec, tmp_path / "two", workers=2, progress=False, fmt="csv")
    assert two.computed_runs == 2 and two.table.equals(one.table)
    assert list(one.table["overturned"]) == [False, True]   # both kinds of row
    for name in ("results.csv", "parts/part-000000.csv", "parts/part-000001.csv"):
        assert (tmp_path / "two" / name).read_bytes() == (tmp_path / "one" / name).read_bytes()
    with pytest.raises(ValueError, match=r"workers \(--workers\) must be a positive integer "
                                         r"\(processes\), got 0"):
        run_sweep(spec, tmp_path / "none", workers=0, progress=False, fmt="csv")


def test_a_plastic_stack_spec_equals_its_pickled_copy(stack_sweep):
    """The plastic law's COR is NaN by design (and one density's mass ratio): a spec equals
    its pickled copy and its twin; NaN in another place, or another value, is not equal."""
    import dataclasses
    import pickle

    spec, outcome = stack_sweep
    data = _stack_spec(Path(outcome.out).parent)
    assert math.isnan(spec.cors[0])
    assert pickle.loads(pickle.dumps(spec)) == spec == spec_from_dict(data, where="stack.toml")
    mixed = dataclasses.replace(spec, cors=(math.nan, 0.9))
    assert mixed == pickle.loads(pickle.dumps(mixed))
    assert mixed != dataclasses.replace(spec, cors=(0.9, math.nan))
    assert spec != dataclasses.replace(spec, cors=(0.9,))
    one_density = spec_from_dict(dict(data, stacks={"sizes": ["30x6in"], "blocks": 2}))
    assert math.isnan(one_density.block_inputs[0]["mass ratio"])
    assert one_density == pickle.loads(pickle.dumps(one_density)) != spec
    assert outcome == pickle.loads(pickle.dumps(outcome))


def test_fragility_and_risk_work_on_a_stack_sweep(stack_sweep, capsys):
    """The fragility of "some block fell" and of each block as the one to fall, and
    ``shaketable risk`` on the folder: a fit per stack, the plastic impacts a group."""
    from shaketable.cli import main
    from shaketable.sweeps.stacks import first_to_fall_fits

    _, outcome = stack_sweep
    table = outcome.table
    rows = table
    fits = first_to_fall_fits(rows, "pga", intervals=False)
    assert list(fits) == ["any block", "block 1 (top)", "block 0 (bottom)"]
    fell = rows["overturned"].astype(bool)
    for name, fit in fits.items():
        outcome_of = fell if name == "any block" else \
            rows["overturned block"] == (1 if "top" in name else 0)
        if isinstance(fit, str):   # no fit: the outcome never, always or separately happened
            continue
        assert fit.n_overturned == int(outcome_of.sum()) and fit.n_runs == len(rows)
    assert not isinstance(fits["any block"], str)
    status = main(["risk", str(outcome.out), "--hazard", "example"])
    said = capsys.readouterr()
    # six runs leave the profile likelihood open: risk names the group and says why
    assert "2 blocks: 30 x 6 in on 30 x 6 in, mass ratio 0.5, plastic impacts" in \
        said.out + said.err
    assert status == 0 or "no rate of overturning can be given" in said.err


def test_one_block_stack_rows_agree_with_the_rocking_sweep(tmp_path):
    """A column of one block with the constant-COR law is the rocking block: the stack
    sweep (SciPy DOP853 with events) and the rocking sweep (the compiled engine) agree."""
    data = _stack_spec(tmp_path, stacks={"sizes": ["30x6in"], "blocks": 1},
                       rocking={"cor": 0.9, "rtol": 1e-10},
                       intensity={"pga": ["0.25 g", "0.4 g"]})
    data["records"] = data["records"][1:]
    stacks = run_sweep(spec_from_dict(data), tmp_path / "stacks", progress=False,
                       fmt="csv").table
    rocking = dict(data, blocks={"sizes": ["30x6in"]}, rocking={"cor": 0.9})
    del rocking["stacks"]
    blocks = run_sweep(spec_from_dict(rocking), tmp_path / "blocks", progress=False,
                       fmt="csv").table
    assert list(stacks["overturned"]) == list(blocks["overturned"]) == [False, True]
    assert stacks["t_overturn [s]"].iloc[1] == pytest.approx(blocks["t_overturn [s]"].iloc[1],
                                                             abs=1e-6)
    assert stacks["n_impacts"].iloc[0] == blocks["n_impacts"].iloc[0] > 0
    # the stack's peak is read at the record's samples, the rocking engine's located
    assert 0.98 * blocks["max_theta_ratio [-]"].iloc[0] < stacks["max_theta_ratio [-]"].iloc[0] \
        <= blocks["max_theta_ratio [-]"].iloc[0] * (1 + 1e-9)
    for column in ("pga [m/s^2]", "pgv [m/s]", "R [m]", "pga/(g tan a) [-]"):
        assert np.array_equal(stacks[column], blocks[column])


def test_a_format_2_folder_resumes(tmp_path):
    """A sweep folder written by the version of store format 2 (the block column always in
    inches) resumes: its parts are brought to format 3, the rest is computed, and the
    table is byte for byte the table of the whole sweep run now.

    ``data/format-2-sweep`` is the first of the two chunks of :data:`FORMAT_TWO_SPEC`,
    written by that version (commit 4745c1d^) with::

        git archive 4745c1d^ shaketable | tar -x -C /tmp/v2
        PYTHONPATH=/tmp/v2 python3 - <<'EOF'
        from shaketable.sweeps.execute import run_sweep
        from shaketable.sweeps.spec import spec_from_dict
        spec = spec_from_dict(FORMAT_TWO_SPEC, where="format-two.toml")
        run_sweep(spec, "format-2-sweep", progress=False, fmt="csv", max_chunks=1, workers=1)
        EOF

    (and the folder's lock file removed).
    """
    folder = tmp_path / "old"
    shutil.copytree(FIXTURES / "format-2-sweep", folder)
    old = pd.read_csv(folder / "parts" / "part-000000.csv")
    assert json.loads((folder / "manifest.json").read_text())["format_version"] == 2
    assert list(old["block"]) == ["48 x 12 in", "30 x 6 in"]
    spec = spec_from_dict(FORMAT_TWO_SPEC, where="format-two.toml")
    resumed = run_sweep(spec, folder, resume=True, progress=False, fmt="csv", workers=1)
    assert (resumed.computed_runs, resumed.skipped_runs, resumed.complete) == (2, 2, True)
    whole = run_sweep(spec, tmp_path / "whole", progress=False, fmt="csv", workers=1)
    assert (folder / "results.csv").read_bytes() == whole.path.read_bytes()
    assert list(resumed.table["block"][:2]) == ["4 x 1 ft", "30 x 6 in"]
    assert json.loads((folder / "manifest.json").read_text())["format_version"] == \
        FORMAT_VERSION == 3
    migrated = pd.read_csv(folder / "parts" / "part-000000.csv")
    pd.testing.assert_frame_equal(migrated.drop(columns="block"), old.drop(columns="block"))


@pytest.mark.parametrize("change, message", [
    ({"model": "planar"}, r"model = 'planar' needs \[friction\]"),
    ({"model": "tower"}, "'model' must be one of rocking, planar, stack"),
    ({"friction": {"static": 0.3}}, r"\[stacks\] with \[friction\]"),
    ({"blocks": {"sizes": ["30x6in"]}}, r"\[blocks\] with \[stacks\]"),
    ({"stacks": {"sizes": ["30x6in"], "blocks": 11}}, "stacks.blocks must be at most 10"),
    ({"stacks": {"sizes": ["30x6in"], "blocks": 0}}, "stacks.blocks must be a positive integer"),
    ({"stacks": {"columns": [["30x6in", "60x12in"]]}},
     r"stacks.columns 30x6in, 60x12in: block 1 \(top\) \(60 x 12 in\) is wider than block 0 "
     r"\(bottom\) \(30 x 6 in\) below it"),
    ({"stacks": {"sizes": ["30x6in"], "colour": 1}},
     r"unknown key 'colour' in \[stacks\]; expected one of blocks, columns, mass_ratios, sizes"),
    ({"stacks": {"sizes": ["0x6in"]}}, r"stacks.sizes '0x6in': the height"),
    ({"stacks": {"sizes": ["30x6in"], "mass_ratios": [0]}}, "stacks.mass_ratios must be positive"),
    ({"rocking": {"cor": "elastic"}}, 'rocking.cor of a stack sweep must be "plastic"'),
    ({"rocking": {"theta0": "0.1 alpha"}}, r"rocking.theta0 with \[stacks\]"),
    ({"pitch": {"phases": 2}}, r"\[pitch\] with \[stacks\] is not offered"),
])
def test_stack_spec_errors_name_the_key(tmp_path, change, message):
    with pytest.raises(SweepError, match=message):
        spec_from_dict(_stack_spec(tmp_path, **change), where="spec.toml")


def test_an_overhang_in_a_spec_file_names_the_key_its_line_and_the_users_units(tmp_path):
    # as `simulate --stack 8x3ft,6x4ft` and a scene say it: ft, not 1.2192 m and float noise
    from shaketable.sweeps.spec import load_spec

    path = tmp_path / "overhang.toml"
    path.write_text('name = "overhang"\n[stacks]\n\ncolumns = [["8x3ft", "6x4ft"]]\n'
                    '[[records]]\nname = "el-centro-1940-180"\n')
    with pytest.raises(SweepError) as raised:
        load_spec(path)
    assert str(raised.value) == (
        f"{path}: stacks.columns 8x3ft, 6x4ft: block 1 (top) (6 x 4 ft) is wider than block 0 "
        "(bottom) (8 x 3 ft) below it: an overhanging block is not offered by the stack model "
        "(docs/stack.md) (line 4)")


def test_the_model_is_chosen_by_the_spec(tmp_path):
    """Without ``model`` the sections choose it; the planar model's parameters are the
    friction pairs; columns of explicit sizes and the mass-ratio axis in grid order."""
    rocking = {k: v for k, v in FORMAT_TWO_SPEC.items()}
    assert spec_from_dict(rocking).model.name == "rocking"
    assert spec_from_dict(dict(rocking, model="rocking")).friction is None
    planar = spec_from_dict(dict(rocking, friction={"static": [0.2, 0.4]}))
    assert planar.model.name == "planar" and planar.model.axis == ((0.2, 0.2), (0.4, 0.4))
    assert planar.friction.pairs == planar.model.axis and planar.n_runs == 2 * 2 * 2
    spec = spec_from_dict(_stack_spec(tmp_path, stacks={
        "columns": [["60x12in", "30x6in"], ["30x6in"]], "mass_ratios": [2, 0.5]}))
    assert spec.model.name == "stack"
    assert [(s.n, s.masses) for s in spec.blocks] == [(2, (1.0, 2.0)), (2, (1.0, 0.5)),
                                                     (1, (1.0,)), (1, (1.0,))]
    assert [spec.model.label(s) for s in spec.blocks[:2]] == [
        "2 blocks: 30 x 6 in on 60 x 12 in, mass ratio 2",
        "2 blocks: 30 x 6 in on 60 x 12 in, mass ratio 0.5"]
    assert math.isnan(spec.cors[0]) and spec.n_runs == 2 * 3 * 4
    # a block alone has no mass ratio (one mass): NaN, as for one density
    assert [row["mass ratio"] for row in spec.block_inputs[:2]] == [2.0, 0.5]
    assert all(math.isnan(row["mass ratio"]) for row in spec.block_inputs[2:])


def test_a_resume_with_another_model_is_refused_by_name(stack_sweep, tmp_path):
    spec, outcome = stack_sweep
    folder = tmp_path / "other"
    shutil.copytree(outcome.out, folder)
    data = _stack_spec(tmp_path, blocks={"sizes": ["30x6in"]}, rocking={"cor": 0.9})
    del data["stacks"]
    with pytest.raises(SweepError, match=r"cannot resume: the sweep there runs stack \(a column "
                                         r"of rigid blocks.*and .* the rocking or planar model"):
        run_sweep(spec_from_dict(data), folder, resume=True, progress=False, fmt="csv")


@pytest.mark.parametrize("change, message", [
    ({"run": {"chunk_size": 0}}, "run.chunk_size must be a positive integer, got 0"),
    ({"run": {"chunk_size": 10**9}},
     "run.chunk_size must be at most 100,000 (a chunk's rows are held in memory), got "
     "1000000000"),
    ({"pitch": {"phases": 0}}, "pitch.phases must be a positive integer, got 0"),
    ({"pitch": {"random_phases": True}}, "pitch.random_phases must be a positive integer, "
                                         "got True"),
])
def test_counts_of_a_spec_read_as_everywhere(change, message):
    """The count checks of core.validation (the words of every other count), by key."""
    with pytest.raises(SweepError) as raised:
        spec_from_dict(dict(FORMAT_TWO_SPEC, **change), where="spec.toml")
    assert str(raised.value) == f"spec.toml: {message}"


def test_stack_figures_draw_each_impact_law(stack_sweep, tmp_path, monkeypatch):
    """``--figures`` of a stack sweep: per impact law (the plastic law by its label, its NaN
    COR not dropped), P(some block overturns) per stack and which block fell first, whose
    bars are the shares counted in the table; sweep_figures hands a stack table over."""
    from matplotlib.patches import Rectangle

    from shaketable.plots import sweep_stacks
    from shaketable.plots.base import pyplot
    from shaketable.plots.sweep_stacks import first_to_fall
    from shaketable.plots.sweeps import sweep_figures

    drawn = {}   # the figures by file name, not rendered (a second's CPU each time)
    monkeypatch.setattr(sweep_stacks, "save", lambda figure, path: drawn.update(
        {path.name: figure}))
    _, outcome = stack_sweep
    table = outcome.table
    constant = table.assign(**{"cor [-]": 0.9, "impact": "cor"})   # a second law's rows
    both = pd.concat([table, constant], ignore_index=True)
    paths = sweep_figures(both, tmp_path / "figures")
    assert [path.name for path in paths] == [
        f"stacks-{kind}-{law}.{suffix}" for law in ("plastic", "cor0.9")
        for kind, suffix in (("fragility", "png"), ("first-to-fall", "png"),
                             ("fragility", "csv"))]
    summary = pd.read_csv(tmp_path / "figures" / "stacks-fragility-plastic.csv")
    fell = table["overturned"].astype(bool)
    assert list(summary["runs"]) == [6] and list(summary["overturned"]) == [int(fell.sum())]
    assert summary["impact law"].iloc[0] == "plastic impacts"
    assert set(drawn) == {path.name for path in paths if path.suffix == ".png"}
    assert drawn["stacks-fragility-plastic.png"].axes[0].get_ylabel() == \
        "P(some block overturns) [-]"
    figure = first_to_fall(table)
    axis = figure.axes[0]
    bars = [patch for patch in axis.patches if isinstance(patch, Rectangle)]
    levels = np.sort(table["pga [g]"].round(6).unique())
    # per level: the top block, the bottom block, then the runs that stood (bottom up)
    heights = np.array([bar.get_height() for bar in bars]).reshape(3, len(levels))
    for k, level in enumerate(levels):
        at = table[table["pga [g]"].round(6) == level]
        counted = [(at["overturned block"] == 1).mean(), (at["overturned block"] == 0).mean(),
                   (~at["overturned"].astype(bool)).mean()]
        assert heights[:, k] == pytest.approx(counted, abs=1e-12)
    pyplot().close("all")


def test_risk_on_stacks_leads_with_the_answer():
    """``risk`` on a stack sweep says first, per impact law, each stack's P(some block
    overturns in the design life), the most likely first, as a multiple of the block
    alone's (same bottom block), and which block fell first."""
    from shaketable.commands.risk import hazard_path, stack_headline
    from shaketable.sweeps.fragility import FragilityFit
    from shaketable.sweeps.risk import overturning_rate, read_hazard_curve

    hazard = read_hazard_curve(hazard_path("example"))
    block = Block.parse("30x6in")

    def rows(blocks, fell):   # which block fell in each run (-1: none)
        return pd.DataFrame({"R [m]": block.R, "base width [m]": block.width,
                             "blocks": blocks, "overturned": [k >= 0 for k in fell],
                             "overturned block": fell})

    alone = overturning_rate(FragilityFit(0.5, 0.3, 4, 2), hazard, interval=False)
    pair = overturning_rate(FragilityFit(0.3, 0.3, 4, 3), hazard, interval=False)
    lines = stack_headline([("1 block", "plastic impacts", alone, rows(1, [0, 0, -1, -1])),
                            ("2 blocks", "plastic impacts", pair, rows(2, [0, 1, 0, -1]))],
                           50.0)
    assert lines[0] == "P(some block overturns in 50 yr), plastic impacts:"
    assert pair.probability > alone.probability
    assert lines[1] == (f"    2 blocks: {pair.probability:.2g}, "
                        f"{pair.probability / alone.probability:.2g} x the block alone's; the "
                        "first to fall in its 3 runs that overturned: block 1 (top) 1, "
                        "block 0 (bottom) 2")
    assert lines[2] == f"    1 block: {alone.probability:.2g}" and len(lines) == 3


def test_the_stack_sweep_answer_keeps_the_stacks_and_the_blocks_alone_apart():
    # six rows counted by hand: two-block stacks whose top fell once and bottom twice, a
    # three-block stack whose middle block fell, a block alone that overturned and one
    # run that stood
    from shaketable.sweeps.stacks import overturn_answer

    table = pd.DataFrame({"blocks": [2, 2, 2, 3, 1, 2],
                          "overturned": [True, True, True, True, True, False],
                          "overturned block": [1, 0, 0, 1, 0, -1]})
    answer = overturn_answer(table)
    assert answer.startswith("5 of 6 runs overturn: 4 stacks (the block that fell: ")
    assert "block 1 (top) 1" in answer and "block 0 (bottom) 2" in answer
    assert "block 1 1" in answer and answer.endswith(") and 1 block alone")
    assert overturn_answer(table[~table["overturned"]]) == "0 of 1 runs overturn"
