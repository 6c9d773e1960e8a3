"""``shaketable sweep``: spec validation, rows equal to single runs, resume, Dask, CLI.

No expected value here comes from the sweep code: each row is compared with an
independent :func:`shaketable.models.api` on a motion built by hand from the
documented recipe (record -> ``scale_to_pga`` / ``Motion.scaled`` -> pitching table),
and resumed or distributed sweeps are compared with an uninterrupted local one.
"""

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import shaketable as st
from shaketable import sweeps
from shaketable.cli import main
from shaketable.core.constants import G
from shaketable.ground import generators, records, signals
from shaketable.lab.pitch import Pitch, motion_at_block
from shaketable.sweeps import execute
from tests.helpers import REPOSITORY  # noqa: E402

SPEC = """
name = "tiny"
seed = 7
[blocks]
height = ["30 in", "4 ft"]
aspect = [4, 5]
[rocking]
cor = [0.9, 1.0]
duration = "6 s"
[[records]]
name = "pacoima-dam-s16e"
[[records]]
preset = "B-1"
seeds = 2
duration = "6 s"
[intensity]
pga = ["0.4 g", "0.8 g"]
[run]
chunk_size = 10
"""
# 2 heights x 2 aspects = 4 blocks, 2 COR, (1 + 2 realisations) x 2 PGA levels: 48 runs,
# 5 chunks (the last one short).


def write(tmp_path, text, name="spec.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def reference_table(tmp_path_factory):
    """The tiny sweep run once, uninterrupted, locally."""
    folder = tmp_path_factory.mktemp("reference")
    outcome = sweeps.run_sweep(sweeps.load_spec(write(folder, SPEC)), folder / "out",
                              progress=False)
    assert outcome.complete and outcome.computed_runs == 48
    return outcome.table


def _without_bookkeeping(table):
    return table.drop(columns=["chunk"])


# --------------------------------------------------------------------------- results
def test_rows_equal_independent_single_runs(reference_table):
    table = reference_table
    assert list(table["run"]) == list(range(48))
    pacoima = records.load("pacoima-dam-s16e")
    realisations = {seed: generators.artificial("B-1", seed=seed, duration=6.0) for seed in (7, 8)}
    for _, row in table.iterrows():
        base = pacoima if row["record"] == "pacoima-dam-s16e" else realisations[row["seed"]]
        target_g = round(row["target_pga [m/s^2]"] / G, 12)         # 0.4 or 0.8, as written
        assert target_g in (0.4, 0.8)
        motion = signals.scale_to_pga(base, pga=target_g * G)
        block = st.Block(row["block_height [m]"], row["block_width [m]"])
        expected = st.simulate(block, motion, cor=row["cor [-]"], duration=6.0)
        assert row["max_abs_theta [rad]"] == expected.max_abs_theta, row["run"]
        assert row["status"] == expected.status
        assert (row["t_overturn [s]"] == expected.t_overturn
                or (math.isnan(row["t_overturn [s]"]) and math.isnan(expected.t_overturn)))
        assert row["n_impacts"] == expected.n_impacts
        assert row["pga [m/s^2]"] == pytest.approx(motion.pga, rel=1e-14)
    # the grid: heights as written, H/B as written
    assert sorted(set(np.round(table["block_height [m]"] / 0.0254, 9))) == [30.0, 48.0]
    assert sorted(set(np.round(table["aspect_ratio [-]"], 12))) == [4.0, 5.0]
    assert table["overturned"].any() and not table["overturned"].all()


def test_pitch_phase_rows_equal_runs_on_a_pitching_table(tmp_path):
    spec = sweeps.load_spec(write(tmp_path, """
name = "pitch"
[blocks]
sizes = ["30x6in"]
[rocking]
cor = 0.925
duration = "5 s"
[[records]]
preset = "olive-view"
seed = 1
duration = "5 s"
[intensity]
scale = [0.6]
[pitch]
phases = ["0 deg", "90 deg", "180 deg"]
"""))
    table = sweeps.run_sweep(spec, tmp_path / "out", progress=False).table
    base = generators.artificial("olive-view", seed=1, duration=5.0)
    block = st.Block.parse("30x6in")
    for _, row in table.iterrows():
        # Section 3.7 (2) defaults: 12 Hz, 0.22 rad/s^2; scaled first, then pitched
        pitched = motion_at_block(base.scaled(0.6),
                                  pitch=Pitch(12.0, 0.22, phase=row["pitch_phase [rad]"]))
        expected = st.simulate(block, pitched, cor=0.925, duration=5.0)
        assert row["max_abs_theta [rad]"] == expected.max_abs_theta
    assert table["pitch_phase [rad]"].tolist() == pytest.approx([0, math.pi / 2, math.pi])


# --------------------------------------------------------------------------- resume
def test_killed_sweep_resumes_without_loss_or_repeat(tmp_path, reference_table):
    spec = sweeps.load_spec(write(tmp_path, SPEC))
    out = tmp_path / "out"
    written = []

    def crash_after_two(chunk, frame):
        written.append(chunk)
        if len(written) == 2:
            raise KeyboardInterrupt("killed")  # what Ctrl-C or a kill looks like mid-sweep

    with pytest.raises(KeyboardInterrupt):
        sweeps.run_sweep(spec, out, progress=False, on_chunk=crash_after_two)
    parts = sorted((out / "parts").glob("part-*.parquet"))
    assert [p.name for p in parts] == ["part-000000.parquet", "part-000001.parquet"]
    assert not (out / "results.parquet").exists()
    partial = sweeps.read_results(out)
    assert list(partial["run"]) == list(range(20))

    # without --resume the folder is refused (nothing is overwritten)
    with pytest.raises(sweeps.SweepError, match="--resume"):
        sweeps.run_sweep(spec, out, progress=False)
    # one more chunk only, then the rest
    step = sweeps.run_sweep(spec, out, progress=False, resume=True, max_chunks=1)
    assert not step.complete and step.computed_runs == 10 and step.skipped_runs == 20
    final = sweeps.run_sweep(spec, out, progress=False, resume=True)
    assert final.complete and final.computed_runs == 18 and final.skipped_runs == 30
    table = final.table
    assert list(table["run"]) == list(range(48))   # none lost, none repeated
    pd.testing.assert_frame_equal(_without_bookkeeping(table),
                                  _without_bookkeeping(reference_table))
    assert pd.read_parquet(out / "results.parquet").equals(table)


def test_resume_refuses_a_changed_spec(tmp_path):
    out = tmp_path / "out"
    sweeps.run_sweep(sweeps.load_spec(write(tmp_path, SPEC)), out, progress=False,
                    max_chunks=1)
    changed = sweeps.load_spec(write(tmp_path, SPEC.replace("seed = 7", "seed = 8"), "b.toml"))
    with pytest.raises(sweeps.SweepError, match="cannot resume.*fingerprint"):
        sweeps.run_sweep(changed, out, progress=False, resume=True)
    assert json.loads((out / "manifest.json").read_text())["n_runs"] == 48


def test_same_seed_same_table_whatever_chunks_and_threads(tmp_path, reference_table):
    other = SPEC.replace("chunk_size = 10", "chunk_size = 17")
    table = sweeps.run_sweep(sweeps.load_spec(write(tmp_path, other)), tmp_path / "a",
                            progress=False, workers=1).table
    pd.testing.assert_frame_equal(_without_bookkeeping(table),
                                  _without_bookkeeping(reference_table))
    reseeded = sweeps.run_sweep(sweeps.load_spec(write(tmp_path, SPEC.replace(
        "seed = 7", "seed = 9"), "c.toml")), tmp_path / "b", progress=False).table
    artificial = reseeded["record_kind"] == "artificial"
    assert sorted(set(reseeded.loc[artificial, "seed"])) == [9, 10]
    assert not np.array_equal(reseeded.loc[artificial, "max_abs_theta [rad]"],
                              reference_table.loc[artificial, "max_abs_theta [rad]"])


def test_csv_format_holds_the_same_values(tmp_path, reference_table):
    outcome = sweeps.run_sweep(sweeps.load_spec(write(tmp_path, SPEC)), tmp_path / "out",
                              progress=False, fmt="csv")
    assert outcome.path.name == "results.csv"
    table = sweeps.read_results(tmp_path / "out")
    for column in ("run", "max_abs_theta [rad]", "t_overturn [s]", "status", "seed"):
        left, right = table[column], reference_table[column]
        assert left.astype(str).tolist() == right.astype(str).tolist() or np.allclose(
            left, right, rtol=1e-15, equal_nan=True), column


# --------------------------------------------------------------------------- Dask
def test_local_dask_cluster_gives_the_same_table(tmp_path, reference_table):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        outcome = sweeps.run_sweep(sweeps.load_spec(write(tmp_path, SPEC)), tmp_path / "out",
                                  scheduler=client, progress=False)
    assert outcome.complete
    pd.testing.assert_frame_equal(_without_bookkeeping(outcome.table),
                                  _without_bookkeeping(reference_table))


# A sweep of many chunks, to be killed mid-way: 10 heights x 5 aspects x 2 COR = 100 runs
# of 20 s of Pacoima Dam, one chunk each.
LONG_SPEC = """
name = "long"
seed = 3
[blocks]
height = ["2 ft", "3 ft", "4 ft", "5 ft", "6 ft", "8 ft", "10 ft", "12 ft", "14 ft", "16 ft"]
aspect = [3, 4, 5, 6, 7]
[rocking]
cor = [0.85, 0.95]
duration = "20 s"
[[records]]
name = "pacoima-dam-s16e"
[run]
chunk_size = 1
"""


def test_sigkilled_sweep_process_resumes_without_loss_or_repeat(tmp_path):
    # A real kill: the CLI in its own process, SIGKILLed (no clean-up runs) as soon as its
    # first chunk is on disk, with ~100 chunks to go; `--resume` must finish it into the
    # same table as an uninterrupted run (each part is written to a temporary file and
    # renamed, so a kill can leave a stray temporary but never a half part).
    import signal
    import subprocess
    import sys
    import time

    spec_path = write(tmp_path, LONG_SPEC)
    out = tmp_path / "killed"
    command = [sys.executable, "-m", "shaketable.cli", "sweep", str(spec_path), "--out",
               str(out), "--workers", "1", "--no-progress"]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    try:
        while not list((out / "parts").glob("part-*.parquet")):
            assert process.poll() is None, process.stderr.read().decode()
            assert time.monotonic() < deadline, "no chunk written in 120 s"
            time.sleep(0.002)
        process.send_signal(signal.SIGKILL)
        process.wait(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == -signal.SIGKILL
    assert not (out / "results.parquet").exists()
    kept = len(list((out / "parts").glob("part-*.parquet")))
    assert 1 <= kept < 100
    assert main(["sweep", str(spec_path), "--out", str(out), "--resume", "--workers", "1",
                 "--no-progress"]) == 0
    resumed = pd.read_parquet(out / "results.parquet")
    assert list(resumed["run"]) == list(range(100))             # none lost, none repeated
    # the same sweep uninterrupted (in one chunk: only the bookkeeping column differs)
    whole = write(tmp_path, LONG_SPEC.replace("chunk_size = 1", "chunk_size = 100"), "whole.toml")
    uninterrupted = sweeps.run_sweep(sweeps.load_spec(whole), tmp_path / "whole",
                                    progress=False, workers=1).table
    pd.testing.assert_frame_equal(_without_bookkeeping(resumed),
                                  _without_bookkeeping(uninterrupted))


def test_resume_refuses_parts_of_another_solver(tmp_path, monkeypatch):
    spec = sweeps.load_spec(write(tmp_path, SPEC))
    out = tmp_path / "out"
    sweeps.run_sweep(spec, out, progress=False, max_chunks=1)
    # another package version or another default tolerance must not be mixed in one table
    original = execute.solver_identity()
    monkeypatch.setattr(execute, "solver_identity",
                        lambda: {**original, "default rtol": {"fast": 1e-6}})
    with pytest.raises(sweeps.SweepError, match="cannot resume.*solver"):
        sweeps.run_sweep(spec, out, progress=False, resume=True)


def test_dask_cluster_by_address_with_worker_processes(tmp_path, reference_table):
    # `--scheduler ADDRESS` as a user runs it: the CLI connects to a scheduler by address
    # and the work runs in a separate worker process (which imports shaketable there: the
    # spec and each chunk's table cross a process boundary both ways). One worker process
    # (each costs ~3 s of CPU to start); chunks finishing out of order on several workers
    # are checked by test_local_dask_cluster_gives_the_same_table (two threads).
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        assert main(["sweep", str(write(tmp_path, SPEC)), "--out", str(tmp_path / "out"),
                     "--scheduler", cluster.scheduler_address, "--no-progress"]) == 0
    table = pd.read_parquet(tmp_path / "out" / "results.parquet")
    pd.testing.assert_frame_equal(_without_bookkeeping(table),
                                  _without_bookkeeping(reference_table))


# --------------------------------------------------------------------------- spec errors
@pytest.mark.parametrize("change, message", [
    (("name = \"tiny\"", ""), "missing 'name'"),
    (("seed = 7", "seed = 7\ncolour = 1"), "unknown key 'colour' in the top level"),
    (("height = [\"30 in\", \"4 ft\"]", "height = [30, 48]"), "blocks.height: 30 has no unit"),
    (("aspect = [4, 5]", "width = [\"1 ft\"]\naspect = [4, 5]"),
     r"\[blocks\] gives aspect, height, width"),
    (("aspect = [4, 5]", "aspect = [0, 5]"), r"blocks.aspect \(H/B\) must be a number"),
    (("cor = [0.9, 1.0]", "cor = [0.9, 1.1]"), "rocking.cor must be a number in"),
    (("duration = \"6 s\"\n[[records]]", "duration = \"6 ft\"\n[[records]]"),
     "rocking.duration: unknown time unit"),
    (("name = \"pacoima-dam-s16e\"", "name = \"pacoima\""),
     r"records\[0\].name 'pacoima' is not a bundled record"),
    (("preset = \"B-1\"", "preset = \"C-1\""), r"records\[1\].preset must be one of"),
    (("seeds = 2", "seeds = 0"), r"records\[1\].seeds must be a positive count"),
    (("seeds = 2", "seeds = 2\nscale = 3"), r"unknown key 'scale' in records\[1\]"),
    (("pga = [\"0.4 g\", \"0.8 g\"]", "pga = [\"0.4 g\"]\nscale = [1.0]"),
     "gives both scale and pga"),
    (("chunk_size = 10", "chunk_size = 0"), "run.chunk_size must be a positive integer"),
    (("[run]", "[pitch]\nfrequency = \"12 Hz\"\n[run]"),
     "needs exactly one of pitch.phases"),
    (("name = \"pacoima-dam-s16e\"", "file = \"absent.AT2\""), r"records\[0\].file: no such"),
])
def test_spec_errors_name_the_file_and_the_key(tmp_path, change, message):
    old, new = change
    assert old in SPEC
    path = write(tmp_path, SPEC.replace(old, new, 1))
    with pytest.raises(sweeps.SweepError, match=message) as caught:
        sweeps.load_spec(path)
    assert str(caught.value).startswith(str(path))


def test_bundled_sweep_specs_are_valid():
    specs = sorted((REPOSITORY / "experiments" / "sweeps").glob("*.toml"))
    assert len(specs) >= 3
    for path in specs:
        spec = sweeps.load_spec(path)
        assert spec.n_runs > 0, path


# --------------------------------------------------------------------------- CLI
def test_sweep_command_in_process(tmp_path, capsys):
    spec = write(tmp_path, SPEC.replace("chunk_size = 10", "chunk_size = 48"))
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--no-progress",
                 "--workers", "1"]) == 0
    captured = capsys.readouterr()
    # the answer on stdout, what ran (runs, chunks) on stderr
    assert "48 runs in 1 chunk(s)" in captured.err and "results.parquet" in captured.out
    assert len(pd.read_parquet(tmp_path / "out" / "results.parquet")) == 48
    assert main(["sweep", str(write(tmp_path, "name = 'x'", "bad.toml"))]) == 2
    assert "bad.toml: missing [blocks]" in capsys.readouterr().err


# --------------------------------------------------------------------------- figures
def test_fragility_fit_recovers_a_known_lognormal_curve():
    # outcomes drawn from P = Phi(ln(a / 0.4) / 0.3): the fit must find median 0.4 g and
    # beta 0.3 within the sampling error of 4000 Bernoulli trials (a few per cent)
    from scipy.stats import norm

    from shaketable.sweeps.fragility import fragility_fit

    rng = np.random.default_rng(5)
    pga = np.repeat(np.linspace(0.1, 1.0, 40), 100)
    overturned = rng.random(pga.size) < norm.cdf(np.log(pga / 0.4) / 0.3)
    fit = fragility_fit(pga, overturned)
    assert fit.median == pytest.approx(0.4, rel=0.03)
    assert fit.beta == pytest.approx(0.3, rel=0.08)
    with pytest.raises(ValueError, match="no run overturned"):
        fragility_fit([0.1, 0.2], [False, False])


def test_sweep_figures_draw_from_a_table(reference_table):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from shaketable.plots import sweeps as sweep_plots

    one = reference_table[(reference_table["record"] == "pacoima-dam-s16e")
                          & (reference_table["target_pga [m/s^2]"] == 0.4 * G)]
    ax = sweep_plots.overturning_map(one, cor=1.0, y="height", length_unit="in")
    assert ax.get_ylabel() == "height H [in]"
    assert [t.get_text() for t in ax.get_yticklabels()] == ["30", "48"]
    n_f = sum(text.get_text() == "F" for text in ax.texts)
    assert n_f == int(one[one["cor [-]"] == 1.0]["overturned"].sum())
    with pytest.raises(ValueError, match="mix several 'cor"):
        sweep_plots.overturning_map(one)
    ax = sweep_plots.fragility_curve(reference_table, group=None, cor=0.9)
    assert ax.get_xlabel() == "PGA [g]"
    ax = sweep_plots.rocking_spectrum(one, cor=0.9, x="R")
    assert ax.get_xlabel() == "size R [m]"
    plt.close("all")


@pytest.mark.usefixtures("figure_drafts")
def test_sweep_command_draws_the_figures_the_table_supports(tmp_path, capsys):
    # one PGA level: a map and a spectrum per (record, COR), no fragility curve
    one_level = SPEC.replace('pga = ["0.4 g", "0.8 g"]', 'pga = ["0.4 g"]')
    assert main(["sweep", str(write(tmp_path, one_level)), "--out", str(tmp_path / "a"),
                 "--no-progress", "--workers", "1", "--figures"]) == 0
    names = sorted(path.name for path in (tmp_path / "a" / "figures").iterdir())
    table = pd.read_parquet(tmp_path / "a" / "results.parquet")
    records = len(table[["record", "seed"]].drop_duplicates())  # each realisation its own
    assert sum(name.startswith("map-") for name in names) == 2 * records
    assert sum(name.startswith("spectrum-") for name in names) == 2 * records
    assert not any(name.startswith("fragility") for name in names)
    # three PGA levels over three records: one fragility figure per COR, no map
    levels = SPEC.replace('pga = ["0.4 g", "0.8 g"]', 'pga = ["0.2 g", "0.4 g", "0.8 g"]')
    assert main(["sweep", str(write(tmp_path, levels, "b.toml")), "--out",
                 str(tmp_path / "b"), "--no-progress", "--workers", "1", "--figures"]) == 0
    names = sorted(path.name for path in (tmp_path / "b" / "figures").iterdir())
    assert names == ["fragility-cor0.9.png", "fragility-cor1.png"]
    capsys.readouterr()


def test_a_pitch_sweep_draws_the_spread_over_phases_not_a_fragility(tmp_path):
    """A [pitch] sweep repeats one record at several phases of the table's pitch: its
    figure is the spread over the phases per record (Section 3.7 (2)), with the count of
    overturning phases; the phases are not 'records' of a fragility curve (which, mixing
    two records' PGA levels, drew one curve through both)."""
    import matplotlib

    matplotlib.use("Agg")
    from shaketable.plots.sweeps import sweep_figures

    spec = sweeps.load_spec(write(tmp_path, """
name = "pitch"
[blocks]
sizes = ["30x6in"]
[rocking]
cor = 0.925
duration = "5 s"
[[records]]
preset = "olive-view"
seed = 1
duration = "5 s"
[[records]]
preset = "A-1"
seed = 2
duration = "5 s"
[intensity]
scale = [0.2, 0.6, 1.0]
[pitch]
phases = 4
"""))
    table = sweeps.run_sweep(spec, tmp_path / "out", progress=False).table
    paths = sweep_figures(table, tmp_path / "figures")
    names = sorted(path.name for path in paths)
    assert names == ["pitch-A-1-seed2-30x6in-cor0.925.png",
                     "pitch-olive-view-seed1-30x6in-cor0.925.png"]
    from shaketable.plots.base import pyplot
    from shaketable.plots.sweeps import pitch_phase_spread

    rows = table[table["seed"] == 1]
    ax = pitch_phase_spread(rows)
    counts = [text.get_text() for text in ax.texts]
    expected = [f"{int(part['overturned'].sum())}/4 F"
                for _, part in rows.groupby(rows["pga [g]"].round(6))]
    assert counts == expected
    assert "4 pitch phases" in ax.get_title()
    pyplot().close("all")


def test_sweep_quiet_prints_nothing_but_errors_without_pyarrow(tmp_path, capsys, monkeypatch):
    from shaketable.sweeps import execute

    monkeypatch.setattr(execute, "parquet_available", lambda: False)   # what run_sweep asks
    spec = write(tmp_path, """name = "one"
[blocks]
sizes = ["30x6in"]
[rocking]
cor = 0.9
duration = "1 s"
[[records]]
name = "el-centro-1940-180"
""")
    assert main(["sweep", str(spec), "--out", str(tmp_path / "quiet"), "-q"]) == 0
    assert capsys.readouterr() == ("", "")
    assert (tmp_path / "quiet" / "results.csv").is_file()
    assert main(["sweep", str(spec), "--out", str(tmp_path / "said"), "--no-progress"]) == 0
    assert "note: pyarrow is not installed, writing CSV" in capsys.readouterr().err
