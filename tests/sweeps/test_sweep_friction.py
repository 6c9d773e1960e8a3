"""Friction as a sweep axis: ``[friction]`` runs the coupled
planar model.

No expected value here comes from the sweep code: each row is compared with an
independent ``shaketable.simulate(..., friction=Friction(mu_s, mu_d))`` call on a motion
built by hand from the documented recipe (record -> ``scale_to_pga``), a resumed sweep
with an uninterrupted one, and the store of a sweep without friction with the manifest
the code before this change wrote (its fingerprint, copied from that run).
"""

import json
import math

import numpy as np
import pandas as pd
import pytest

import shaketable as st
from shaketable import sweeps
from shaketable.cli import main
from shaketable.core.constants import G
from shaketable.ground import generators, records, signals
from shaketable.models.sliding.result import Friction
from shaketable.sweeps import execute
from tests.sweeps.test_sweeps import SPEC as ROCKING_SPEC
from tests.sweeps.test_sweeps import write

SPEC = """
name = "tiny-friction"
seed = 7
[blocks]
sizes = ["30x6in", "4x1ft"]
[rocking]
cor = [0.9, 0.8]
duration = "5 s"
[[records]]
name = "pacoima-dam-s16e"
[[records]]
preset = "B-1"
seeds = 1
duration = "5 s"
[intensity]
pga = ["0.3 g", "0.6 g"]
[friction]
static = [0.2, 0.5]
dynamic_ratio = [1.0, 0.8]
[run]
chunk_size = 7
"""
# 2 blocks x 4 friction pairs x 2 COR x 2 records x 2 PGA levels: 64 runs, 10 chunks (the
# last one short, and chunk edges inside a block's friction x COR grid).


@pytest.fixture(scope="module")
def friction_outcome(tmp_path_factory):
    """The tiny friction sweep run once, uninterrupted."""
    folder = tmp_path_factory.mktemp("friction")
    outcome = sweeps.run_sweep(sweeps.load_spec(write(folder, SPEC)), folder / "out",
                              progress=False)
    assert outcome.complete and outcome.computed_runs == 64
    return outcome


@pytest.fixture(scope="module")
def friction_table(friction_outcome):
    return friction_outcome.table


def same(a, b) -> bool:
    """Equal bit for bit, NaN equal to NaN."""
    return a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b))


# --------------------------------------------------------------------------- results
def test_every_row_equals_a_direct_simulate_call_bit_for_bit(friction_table):
    table = friction_table
    assert list(table["run"]) == list(range(64))
    pacoima = records.load("pacoima-dam-s16e")
    artificial = generators.artificial("B-1", seed=7, duration=5.0)
    # the grid, by hand: record, level, block, (mu_s, mu_d) with mu_d = ratio * mu_s, COR
    pairs = [(mu_s, ratio * mu_s) for mu_s in (0.2, 0.5) for ratio in (1.0, 0.8)]
    grid = [(record, level, size, pair, cor) for record in ("pacoima-dam-s16e", "B-1")
            for level in (0.3, 0.6) for size in ("30x6in", "4x1ft") for pair in pairs
            for cor in (0.9, 0.8)]
    for (_, row), (record, level, size, (mu_s, mu_d), cor) in zip(table.iterrows(), grid):
        assert row["record"] == record and row["cor [-]"] == cor
        assert round(row["target_pga [m/s^2]"] / G, 12) == level
        assert (row["static friction mu_s [-]"], row["dynamic friction mu_d [-]"]) == (mu_s, mu_d)
        block = st.Block.parse(size)
        assert (row["block_height [m]"], row["block_width [m]"]) == (block.height, block.width)
        base = pacoima if record == "pacoima-dam-s16e" else artificial
        motion = signals.scale_to_pga(base, pga=level * G)
        expected = st.simulate(block, motion, cor=cor, friction=Friction(mu_s, mu_d),
                               duration=5.0)
        summary = expected.summary()
        for column in ("status", "verdict", "peak slip [m]", "residual slip [m]",
                       "peak corner excursion [m]", "n_impacts", "time rest [s]",
                       "time slide [s]", "time rock [s]", "time slide-rock [s]",
                       "time flight [s]"):
            assert same(row[column], summary[column]), (row["run"], column)
        assert same(row["max_theta_ratio [-]"], expected.max_theta_ratio), row["run"]
        assert same(row["t_overturn [s]"], expected.t_overturn), row["run"]
        assert row["overturned"] == expected.overturned
        assert row["pga [m/s^2]"] == pytest.approx(motion.pga, rel=1e-14)
    # the model is exercised: more than one verdict, and sliding happens
    assert table["verdict"].nunique() >= 3
    assert (table["peak slip [m]"] > 0).any()


def test_the_run_order_puts_friction_between_block_and_cor(tmp_path):
    spec = sweeps.load_spec(write(tmp_path, SPEC))
    runs = execute.runs_table(spec)
    assert spec.n_runs == len(runs) == 64
    # COR fastest, then the friction pair, then the block (written out by hand)
    assert list(runs["cor [-]"][:4]) == [0.9, 0.8, 0.9, 0.8]
    assert list(runs["friction_index"][:10]) == [0, 0, 1, 1, 2, 2, 3, 3, 0, 0]
    assert list(runs["block_index"][:10]) == [0] * 8 + [1] * 2
    assert spec.friction.pairs == ((0.2, 0.2), (0.2, 0.2 * 0.8), (0.5, 0.5), (0.5, 0.5 * 0.8))


def test_dynamic_friction_as_its_own_axis_and_same_as_static_by_default(tmp_path):
    explicit = sweeps.load_spec(write(tmp_path, SPEC.replace(
        "dynamic_ratio = [1.0, 0.8]", "dynamic = [0.1, 0.2]")))
    assert explicit.friction.pairs == ((0.2, 0.1), (0.2, 0.2), (0.5, 0.1), (0.5, 0.2))
    default = sweeps.load_spec(write(tmp_path, SPEC.replace("dynamic_ratio = [1.0, 0.8]\n", ""),
                                     "b.toml"))
    assert default.friction.pairs == ((0.2, 0.2), (0.5, 0.5))
    assert default.n_runs == 32
    # mu_s = 0 with a list of ratios: the pair (0, 0) once, not once per ratio (review)
    frictionless = sweeps.load_spec(write(tmp_path, SPEC.replace(
        "static = [0.2, 0.5]", "static = [0.0, 0.5]"), "c.toml"))
    assert frictionless.friction.pairs == ((0.0, 0.0), (0.5, 0.5), (0.5, 0.4))


# --------------------------------------------------------------------------- resume
def test_interrupted_friction_sweep_resumes_to_the_same_store(tmp_path, friction_outcome):
    friction_table = friction_outcome.table
    spec = sweeps.load_spec(write(tmp_path, SPEC))
    out = tmp_path / "out"

    def crash_after_three(chunk, frame):
        if chunk == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        sweeps.run_sweep(spec, out, progress=False, on_chunk=crash_after_three)
    assert sorted(p.name for p in (out / "parts").glob("part-*")) == [
        f"part-{k:06d}.parquet" for k in range(3)]
    resumed = sweeps.run_sweep(spec, out, progress=False, resume=True)
    assert resumed.skipped_runs == 21 and resumed.computed_runs == 43
    pd.testing.assert_frame_equal(resumed.table, friction_table)
    # the same store, byte for byte, as the uninterrupted sweep's
    assert (out / "results.parquet").read_bytes() == friction_outcome.path.read_bytes()
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["friction"]["pairs (mu_s, mu_d)"] == [[0.2, 0.2], [0.2, 0.2 * 0.8],
                                                          [0.5, 0.5], [0.5, 0.5 * 0.8]]


def test_the_table_does_not_depend_on_the_chunking_or_a_pickle_round_trip(tmp_path,
                                                                           friction_table):
    # chunks of 5 and 64 cut the (block x friction x COR) grid of a motion elsewhere than 7
    for size in (5, 64):
        spec = sweeps.load_spec(write(tmp_path, SPEC.replace("chunk_size = 7",
                                                             f"chunk_size = {size}"),
                                      f"spec{size}.toml"))
        table = sweeps.run_sweep(spec, tmp_path / f"out{size}", progress=False).table
        pd.testing.assert_frame_equal(table.drop(columns="chunk"),
                                      friction_table.drop(columns="chunk"))
    # what a Dask worker receives: the spec pickled
    import pickle

    spec = sweeps.load_spec(write(tmp_path, SPEC))
    chunk = execute.compute_chunk(pickle.loads(pickle.dumps(spec)), 3)
    pd.testing.assert_frame_equal(chunk, friction_table.iloc[21:28].reset_index(drop=True))


@pytest.mark.parametrize("other, there, now", [
    (SPEC.replace("static = [0.2, 0.5]", "static = [0.2, 0.4]"),
     r"\[friction\] \(mu_s, mu_d\) = \(0.2, 0.2\), \(0.2, 0.16\), \(0.5, 0.5\), \(0.5, 0.4\)",
     r"\(0.2, 0.2\), \(0.2, 0.16\), \(0.4, 0.4\), \(0.4, 0.32\);"),
    (SPEC.replace("[friction]\nstatic = [0.2, 0.5]\ndynamic_ratio = [1.0, 0.8]\n", ""),
     r"\[friction\]", r"no \[friction\] \(the rocking model\)"),
], ids=["other friction", "no friction"])
def test_resume_refuses_another_friction_by_name(tmp_path, other, there, now):
    out = tmp_path / "out"
    sweeps.run_sweep(sweeps.load_spec(write(tmp_path, SPEC)), out, progress=False,
                     max_chunks=1)
    with pytest.raises(sweeps.SweepError, match=f"cannot resume: the sweep there has "
                                                 f"{there}.* has .*{now}"):
        sweeps.run_sweep(sweeps.load_spec(write(tmp_path, other, "b.toml")), out,
                         progress=False, resume=True)


def test_a_rocking_store_refuses_a_friction_spec_and_keeps_its_format(tmp_path):
    out = tmp_path / "out"
    spec = sweeps.load_spec(write(tmp_path, ROCKING_SPEC))
    sweeps.run_sweep(spec, out, progress=False, max_chunks=1)
    manifest = json.loads((out / "manifest.json").read_text())
    # the keys and fingerprint the code before friction wrote for this spec (commit
    # ba7b13a, the same spec): a folder of that code resumes
    assert set(manifest) == {"sweep", "spec", "fingerprint", "n_runs", "chunk_size",
                             "n_chunks", "format", "format_version", "solver"}
    assert manifest["fingerprint"] == \
        "da7b7957bfe1432d658337882c1c918c96ee9e704fbf391ca976917b35380e55"
    assert manifest["format_version"] == 3
    with_friction = ROCKING_SPEC.replace("[run]", "[friction]\nstatic = 0.6\n[run]")
    with pytest.raises(sweeps.SweepError, match=r"has no \[friction\] \(the rocking model\) "
                                                r"and .* has \[friction\]"):
        sweeps.run_sweep(sweeps.load_spec(write(tmp_path, with_friction, "b.toml")), out,
                         progress=False, resume=True)
    resumed = sweeps.run_sweep(spec, out, progress=False, resume=True)
    assert resumed.complete and resumed.skipped_runs == 10


# --------------------------------------------------------------------------- bad input
FRICTION = "[friction]\nstatic = [0.2, 0.5]\ndynamic_ratio = [1.0, 0.8]\n"


@pytest.mark.parametrize("section, message", [
    ("[friction]\nstatic = [0.2, 0.5]\ndynamic = [0.1, 0.3]\n",
     r"friction.dynamic 0.3 exceeds friction.static 0.2 .*\(line 19\)"),
    ("[friction]\nstatic = [0.2, -0.1]\n", r"friction.static must be a finite number 0 or more"
                                           r" \[-\] or a list of them, got -0.1 \(line 18\)"),
    ("[friction]\nstatic = nan\n", r"friction.static must be a finite number.*got nan"),
    ("[friction]\nstatic = [\"0.3\"]\n", r"friction.static is a friction coefficient, "
                                          r"dimensionless: give a plain number"),
    ("[friction]\nstatic = \"0.3 g\"\n", "dimensionless"),
    ("[friction]\nstatic = 0.3\ndynamic_ratio = 1.2\n",
     r"friction.dynamic_ratio must be a finite number in \[0, 1\].*\(line 19\)"),
    ("[friction]\nstatic = 0.3\ndynamic = 0.2\ndynamic_ratio = 0.5\n",
     "friction.dynamic and friction.dynamic_ratio are both given"),
    ("[friction]\ndynamic = 0.2\n", r"friction.static is missing .*\(line 17\)"),
    ("[friction]\nstatic = []\n", "friction.static must not be an empty list"),
    ("[friction]\nstatic = [0.3, 0.3]\n", "friction.static lists .* a value twice"),
    ("[friction]\nstatic = 0.3\nmu = 0.2\n", r"unknown key 'mu' in \[friction\].*\(line 19\)"),
])
def test_bad_friction_names_the_file_the_key_and_the_line(tmp_path, section, message):
    path = write(tmp_path, SPEC.replace(FRICTION, section))
    with pytest.raises(sweeps.SweepError, match=message) as caught:
        sweeps.load_spec(path)
    assert str(caught.value).startswith(str(path))


@pytest.mark.parametrize("change, message", [
    (("sizes = [\"30x6in\", \"4x1ft\"]", "sizes = [\"30x6in\"]\n[blocks.rods]\n"
      "stiffness = \"0.4 W/in\"\nforce = \"0.4 W\"\nedge_distance = \"3 in\""),
     r"\[blocks.rods\] with \[friction\]: the coupled model refuses prestress rods"),
    (("[run]", "[pitch]\nphases = 2\n[run]"), r"\[pitch\] with \[friction\]: .*no table rotation"),
    (("[run]", "[ensemble]\nmembers = 3\n[run]"), r"\[ensemble\] with \[friction\]"),
    (("duration = \"5 s\"\n[[records]]", "duration = \"5 s\"\nmethod = \"linear\"\n"
      "[[records]]"), r"rocking.method 'linear' with \[friction\]"),
    (("duration = \"5 s\"\n[[records]]", "duration = \"5 s\"\nsubdivisions = 4\n[[records]]"),
     r"rocking.subdivisions with \[friction\]"),
    (("duration = \"5 s\"\n[[records]]", "duration = \"5 s\"\ntheta0 = \"0.1 alpha\"\n"
      "[[records]]"), r"rocking.theta0 with \[friction\]: .*from rest"),
])
def test_what_the_coupled_model_does_not_take_is_refused_by_key(tmp_path, change, message):
    old, new = change
    assert old in SPEC
    path = write(tmp_path, SPEC.replace(old, new, 1))
    with pytest.raises(sweeps.SweepError, match=message) as caught:
        sweeps.load_spec(path)
    assert str(caught.value).startswith(str(path))


def test_a_block_where_a_numeric_cor_is_undefined_is_refused(tmp_path):
    # B/H = sqrt(2): Housner's c_H = 1 - 1.5 sin^2(alpha) = 0 (tan^2 alpha = 2, sin^2 = 2/3)
    text = SPEC.replace("sizes = [\"30x6in\", \"4x1ft\"]",
                        f"height = [\"1 m\"]\naspect = [{1 / math.sqrt(2)!r}]")
    with pytest.raises(sweeps.SweepError, match=r"rocking.cor with \[friction\], block .*c_H"):
        sweeps.load_spec(write(tmp_path, text))


# --------------------------------------------------------------------------- summaries
@pytest.mark.usefixtures("figure_drafts")
def test_sweep_command_prints_verdicts_and_draws_figures_per_friction(tmp_path, capsys):
    # one PGA level: a rocking spectrum (max theta/alpha against p) per record and COR
    text = SPEC.replace("chunk_size = 7", "chunk_size = 64").replace(
        'pga = ["0.3 g", "0.6 g"]', 'pga = ["0.6 g"]')
    out = tmp_path / "out"
    assert main(["sweep", str(write(tmp_path, text)), "--out", str(out), "--no-progress",
                 "--figures"]) == 0
    captured = capsys.readouterr()
    printed = captured.out
    table = pd.read_parquet(out / "results.parquet")
    counts = table["verdict"].value_counts()
    # what runs is said on stderr, the answer on stdout
    assert "[friction]: the coupled planar model" in captured.err
    assert ", ".join(f"{counts[v]} {v}" for v in ("stayed", "slid", "rocked", "slide-rocked",
                                                  "flew", "overturned") if v in counts) \
        in printed
    for mu_s, mu_d in [(0.2, 0.2), (0.2, 0.16), (0.5, 0.5), (0.5, 0.4)]:
        rows = table[np.isclose(table["static friction mu_s [-]"], mu_s)
                     & np.isclose(table["dynamic friction mu_d [-]"], mu_d)]
        standing = rows[~rows["overturned"]]
        assert len(rows) == 8
        line = f"mu_s {mu_s:g}, mu_d {mu_d:g}: "
        assert line in printed
        if len(standing):
            # blocks in in and ft: lengths in m (mm below 1 m), 3 significant digits
            from shaketable.core.units import format_length

            assert (f"largest peak slip {format_length(standing['peak slip [m]'].max(), 'm')}"
                    in printed.split(line)[1].splitlines()[0])
    folders = sorted(p.name for p in (out / "figures").iterdir())
    assert folders == ["friction-mus0.2-mud0.16", "friction-mus0.2-mud0.2",
                       "friction-mus0.5-mud0.4", "friction-mus0.5-mud0.5"]
    for name in folders:   # 2 records x 2 COR, each drawn from its own friction's rows
        assert len(list((out / "figures" / name).glob("spectrum-*.png"))) == 4, name


def test_measure_comparison_refuses_to_pool_frictions(friction_table):
    from shaketable.sweeps.fragility import compare_measures, ida_capacities

    with pytest.raises(ValueError, match="compare_measures: the table holds 4 friction pairs"):
        compare_measures(friction_table)
    # IDA groups by friction pair too: one group per record x block x COR x pair
    capacities, censored = ida_capacities(friction_table, "pga")
    assert len(capacities) + censored == 2 * 2 * 2 * 4
    assert np.all(capacities > 0)


def test_risk_command_fits_each_friction_pair_apart(tmp_path, capsys):
    # one block, two friction pairs, six PGV levels: `shaketable risk` fits per block, COR
    # and friction pair (here, four pairs would be pooled into one fit without it)
    text = SPEC.replace('sizes = ["30x6in", "4x1ft"]', 'sizes = ["30x6in"]').replace(
        "cor = [0.9, 0.8]", "cor = 0.9").replace(
        'pga = ["0.3 g", "0.6 g"]', 'scale = [0.25, 0.5, 0.75, 1.0, 1.5, 2.0]').replace(
        "dynamic_ratio = [1.0, 0.8]\n", "")
    out = tmp_path / "out"
    assert main(["sweep", str(write(tmp_path, text)), "--out", str(out), "--no-progress"]) == 0
    capsys.readouterr()
    # neither pair's outcomes give a fragility here (one never overturns, the other's are
    # separated): each pair is named once, and with no rate at all the exit status is 1
    assert main(["risk", str(out), "--hazard", "example"]) == 1
    printed = capsys.readouterr().err
    assert printed.count("30 x 6 in, COR 0.9, mu_s 0.2, mu_d 0.2:") == 1
    assert printed.count("30 x 6 in, COR 0.9, mu_s 0.5, mu_d 0.5:") == 1


@pytest.fixture
def batch_threads(monkeypatch):
    """The ``threads`` of every planar batch a sweep calls, in order (a spy on
    simulate_many_planar, which still runs)."""
    from shaketable.models.planar import batch as planar_batch

    seen = []
    original = planar_batch.simulate_many_planar

    def spy(*arguments, **options):
        seen.append(options.get("threads"))
        return original(*arguments, **options)

    monkeypatch.setattr(planar_batch, "simulate_many_planar", spy)
    return seen


def test_workers_sets_the_planar_batch_threads_and_not_the_table(tmp_path, friction_table,
                                                                 batch_threads):
    # --workers (run_sweep's workers=) is the planar batch's thread count, as the rocking
    # batch's; the rows do not depend on it
    import numba

    seen = batch_threads
    spec = sweeps.load_spec(write(tmp_path, SPEC))
    for threads in sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)}):
        seen.clear()
        chunk = execute.compute_chunk(spec, 3, threads=threads)
        assert seen and set(seen) == {threads}
        pd.testing.assert_frame_equal(chunk, friction_table.iloc[21:28].reset_index(drop=True),
                                      check_exact=True)
    table = sweeps.run_sweep(spec, tmp_path / "one-thread", workers=1, progress=False).table
    pd.testing.assert_frame_equal(table, friction_table, check_exact=True)


@pytest.mark.parametrize("threads", [0, 1.5, "2", True, 10**6])
def test_planar_batch_threads_out_of_range_is_refused_by_name(threads):
    from shaketable.models.planar.batch import simulate_many_planar

    block, motion = st.Block.parse("30x6in"), records.load("pacoima-dam-s16e")
    with pytest.raises(ValueError, match="threads"):
        simulate_many_planar(block, motion, Friction(0.3, 0.3), 0.9, threads=threads)


@pytest.mark.parametrize("rtol", [0.0, 1e-320, -1e-9, float("nan"), 2.0])
def test_planar_batch_rtol_out_of_range_is_refused_by_name(rtol):
    # rtol 0 gave a zero error scale: a division 0/0 in the DOP853 step (a wrong "stalled"
    # run under numba's numpy error model, not an error)
    from shaketable.models.planar.batch import simulate_many_planar

    block, motion = st.Block.parse("30x6in"), records.load("pacoima-dam-s16e")
    with pytest.raises(ValueError, match="rtol"):
        simulate_many_planar(block, motion, Friction(0.3, 0.3), 0.9, rtol=rtol)


def test_friction_sweep_on_a_local_dask_cluster_gives_the_same_table(tmp_path, friction_table,
                                                                     batch_threads):
    # two tasks at once in one worker process (threads_per_worker=2), each chunk's planar
    # batch on one thread there (workers default to 1 inside a Dask task)
    distributed = pytest.importorskip("distributed")
    seen = batch_threads
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        outcome = sweeps.run_sweep(sweeps.load_spec(write(tmp_path, SPEC)), tmp_path / "out",
                                  scheduler=client, progress=False)
    assert outcome.complete and seen and set(seen) == {1}
    pd.testing.assert_frame_equal(outcome.table, friction_table, check_exact=True)


_CONCURRENT_BATCHES = """
import threading
import pandas as pd
import shaketable as st
from shaketable.models.sliding.result import Friction
from shaketable.ground import records
from shaketable.models.planar.batch import simulate_many_planar

blocks = [st.Block.parse("30x6in"), st.Block.parse("2x1ft")]
motion = records.load("pacoima-dam-s16e")
frictions = [Friction(0.3, 0.3), Friction(0.5, 0.4)]
alone = simulate_many_planar(blocks, motion, frictions, 0.9, duration=4.0, threads=2)
frames = [None] * 3

def batch(k):
    frames[k] = simulate_many_planar(blocks, motion, frictions, 0.9, duration=4.0, threads=2)

threads = [threading.Thread(target=batch, args=(k,)) for k in range(3)]
for thread in threads:
    thread.start()
for thread in threads:
    thread.join()
for frame in frames:
    pd.testing.assert_frame_equal(frame, alone, check_exact=True)
print("ok")
"""


def test_planar_batches_at_once_in_threads_under_numbas_workqueue_layer():
    # Dask runs tasks in threads of one process. numba's workqueue threading layer (used
    # where neither OpenMP nor TBB is found, as on a bare machine) aborts the process on
    # concurrent parallel calls; the planar batch shares its cases among Python threads
    # instead, so three batches of two threads each at once run, with the same rows.
    import os
    import subprocess
    import sys

    environment = dict(os.environ, NUMBA_THREADING_LAYER="workqueue", NUMBA_NUM_THREADS="2")
    done = subprocess.run([sys.executable, "-c", _CONCURRENT_BATCHES], env=environment,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr[-2000:]
