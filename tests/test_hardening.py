"""Safe to share and to run unattended: each defect the hostile-user audit
found, as a test that failed before the fix.

Classes: output confinement of a scene's and a sweep spec's ``name``; file modes
under the umask; the sweep store (stray and temporary parts, the folder lock); API
contracts of ``Motion`` and pickling of every public input and result object; the
free-rocking record that starts at the release; messages that name the file, key or
option (exit 2); a closed pipe; numba's cache folder when numba is imported first.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers import REPOSITORY
from tests.test_bad_input import HARMONIC, SWEEP, _replace, run_cli

# ----------------------------------------------------------------- output confinement
ESCAPING_NAMES = ["../../../escaped", "/tmp/shaketable-issue-27-absolute-escaped", "a/b", "..",
                  "back\\slash", "bell\x07"]


def _toml_string(text: str) -> str:
    """A TOML basic string holding ``text`` (backslashes and control characters escaped)."""
    escaped = text.replace("\\", "\\\\")
    return '"' + "".join(c if ord(c) >= 32 else f"\\u{ord(c):04x}" for c in escaped) + '"'


@pytest.mark.parametrize("name", ESCAPING_NAMES)
def test_scene_name_cannot_leave_the_output_folder(tmp_path, name):
    work = tmp_path / "deep" / "er" / "work"
    work.mkdir(parents=True)
    (work / "s.toml").write_text(_replace(HARMONIC, 'name = "probe"',
                                          f"name = {_toml_string(name)}"), encoding="utf-8")
    status, _, err = run_cli(["run", "s.toml", "-q"], work)
    assert status == 2, err
    assert "s.toml" in err and "'name'" in err, err
    # nothing written anywhere: not in the work folder, not above it
    assert sorted(path.name for path in tmp_path.rglob("*")) == ["deep", "er", "s.toml", "work"]


@pytest.mark.parametrize("name", ESCAPING_NAMES)
def test_sweep_name_cannot_leave_the_output_folder(tmp_path, name):
    work = tmp_path / "deep" / "er" / "work"
    work.mkdir(parents=True)
    (work / "w.toml").write_text(_replace(SWEEP, 'name = "probe"',
                                          f"name = {_toml_string(name)}"), encoding="utf-8")
    status, _, err = run_cli(["sweep", "w.toml", "-q"], work)
    assert status == 2, err
    assert "w.toml" in err and "'name'" in err, err
    assert sorted(path.name for path in tmp_path.rglob("*")) == ["deep", "er", "w.toml", "work"]


def test_study_name_cannot_leave_the_output_folder(tmp_path):
    (tmp_path / "s.toml").write_text('name = "../up"\n[study]\nkind = "teaching"\n',
                                     encoding="utf-8")
    status, _, err = run_cli(["run", "s.toml", "-q"], tmp_path)
    assert status == 2 and "s.toml" in err and "'name'" in err, err


@pytest.mark.usefixtures("figure_drafts")
def test_plain_names_with_dots_and_spaces_still_run(tmp_path):
    # the refusal is of paths only: a name such as "v1.2 probe" is one folder
    (tmp_path / "s.toml").write_text(_replace(HARMONIC, 'name = "probe"', 'name = "v1.2 probe"'),
                                     encoding="utf-8")
    status, _, err = run_cli(["run", "s.toml", "-q"], tmp_path)
    assert status == 0, err
    assert (tmp_path / "shaketable-out" / "v1.2 probe" / "summary.json").is_file()


# ----------------------------------------------------------------- file modes
_MODES = """
import os, stat, sys
from pathlib import Path
umasks = sys.argv[1].split(",")
os.umask(int(umasks[0], 8))   # the first before the package is imported, the others after
from shaketable.cli import main
for umask in umasks:
    os.umask(int(umask, 8))
    work = Path(sys.argv[2]) / umask
    work.mkdir()
    os.chdir(work)
    (work / "w.toml").write_text(sys.argv[3], encoding="utf-8")
    assert main(["simulate", "--block", "30x6in", "--cor", "0.9", "--theta0", "0.5alpha",
                 "--duration", "1s", "--out", "sim", "-q"]) == 0
    assert main(["sweep", "w.toml", "--out", "swept", "-q", "--no-progress"]) == 0
    for path in sorted(work.rglob("*")):
        if path.is_file() and path.name != "w.toml":
            print(umask, oct(stat.S_IMODE(path.stat().st_mode)), path.relative_to(work))
"""

UMASKS = {"022": 0o644, "027": 0o640, "077": 0o600}


def test_outputs_get_the_mode_the_umask_gives(tmp_path):
    # before: every output was 0600 (mkstemp's mode kept by the rename) whatever the umask.
    # The three umasks in one process (one start-up instead of three), one after another.
    result = subprocess.run([sys.executable, "-c", _MODES, ",".join(UMASKS), str(tmp_path),
                             SWEEP], capture_output=True, text=True, cwd=REPOSITORY)
    assert result.returncode == 0, result.stderr
    rows = [line.split() for line in result.stdout.splitlines()]
    assert {umask for umask, _, _ in rows} == set(UMASKS)
    for umask, expected in UMASKS.items():
        lines = [(mode, name) for row_umask, mode, name in rows if row_umask == umask]
        written = {name for _, name in lines}
        # the simulate outputs, the sweep's manifest, part and result table are all there
        assert {"sim/history.csv", "swept/manifest.json",
                "swept/parts/part-000000.parquet"} <= written, umask
        assert any(name.startswith("swept/results.") for name in written), umask
        assert {mode for mode, _ in lines} == {oct(expected)}, (umask, lines)


# ----------------------------------------------------------------- sweep store
def _swept(tmp_path) -> Path:
    """A finished one-run sweep (SWEEP: 1 block, 1 COR, 1 record) in tmp_path/out."""
    (tmp_path / "w.toml").write_text(SWEEP, encoding="utf-8")
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "-q", "--no-progress"],
                             tmp_path)
    assert status == 0, err
    return tmp_path / "out"


def test_a_stray_part_is_not_joined_on_resume(tmp_path):
    import pandas as pd

    out = _swept(tmp_path)
    parts = out / "parts"
    (parts / "part-000999.parquet").write_bytes((parts / "part-000000.parquet").read_bytes())
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "--resume", "-q",
                              "--no-progress"], tmp_path)
    assert status == 0, err
    assert "warning:" in err and "part-000999.parquet" in err and "left out" in err, err
    # before: 2 rows (the copy joined) for the sweep's 1 run
    assert len(pd.read_parquet(out / "results.parquet")) == 1
    # the API reading the folder's parts says so too, as a warning
    from shaketable.sweeps import read_results

    with pytest.warns(UserWarning, match="part-000999"):
        assert len(read_results(out, parts_only=True)) == 1


def test_temporary_files_of_a_killed_writer_are_removed_on_resume(tmp_path):
    out = _swept(tmp_path)
    # the names the atomic writer gives its temporary files (a kill leaves them)
    left = [out / "parts" / ".part-000000.tmp-0a1b2c3d.parquet",
            out / ".results.tmp-4e5f6a7b.parquet", out / ".manifest.tmp-00112233.json"]
    for path in left:
        path.write_bytes(b"half-written")
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "--resume", "-q",
                              "--no-progress"], tmp_path)
    assert status == 0, err
    assert not any(path.exists() for path in left)
    assert (out / "parts" / "part-000000.parquet").is_file()


_HOLD_LOCK = """
import sys
from shaketable.core.files import folder_lock
with folder_lock(sys.argv[1]):
    print("locked", flush=True)
    sys.stdin.read()        # hold the lock until killed
"""


def test_a_second_process_on_a_sweep_folder_refuses_and_a_dead_owner_is_taken_over(tmp_path):
    (tmp_path / "w.toml").write_text(SWEEP, encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    holder = subprocess.Popen([sys.executable, "-c", _HOLD_LOCK, str(out)], cwd=REPOSITORY,
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "locked"
        status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "-q", "--no-progress"],
                                 tmp_path)
        assert status == 2, err
        assert "error: out: " in err and f"pid {holder.pid}" in err, err   # folder as given
        assert not (out / "manifest.json").exists()     # refused before anything was written
    finally:
        holder.kill()           # SIGKILL: no clean-up; the lock file stays behind
        holder.wait()
    assert (out / ".shaketable.lock").exists()
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "-q", "--no-progress"],
                             tmp_path)
    assert status == 0, err
    assert (out / "results.parquet").is_file()


def test_two_real_sweeps_on_one_folder_one_refuses(tmp_path):
    # two `shaketable sweep` processes started together on one folder: one writes the
    # sweep, the other either refuses (the folder is busy) or, if it came second, finds
    # the finished sweep and refuses without --resume; never two writers at once
    (tmp_path / "w.toml").write_text(SWEEP, encoding="utf-8")
    command = [sys.executable, "-m", "shaketable", "sweep", "w.toml", "--out", "out", "-q",
               "--no-progress"]
    runs = [subprocess.Popen(command, cwd=tmp_path, stderr=subprocess.PIPE, text=True,
                             env=dict(os.environ, PYTHONPATH=str(REPOSITORY)))
            for _ in range(2)]
    results = [(run.wait(), run.stderr.read()) for run in runs]
    for run in runs:
        run.stderr.close()
    assert sorted(status for status, _ in results) == [0, 2], results
    refusal = next(err for status, err in results if status == 2)
    assert "in use by another shaketable process" in refusal or "already holds" in refusal
    assert "Traceback" not in refusal


def test_a_manifest_that_is_not_an_object_is_bad_input_naming_it(tmp_path):
    out = _swept(tmp_path)
    (out / "manifest.json").write_text("[]", encoding="utf-8")
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "--resume", "-q",
                              "--no-progress"], tmp_path)
    assert status == 2, err                    # before: "internal error (AttributeError)", 1
    assert "manifest.json" in err and "internal error" not in err, err


# ----------------------------------------------------------------- API contracts
def test_motion_never_changes_the_callers_arrays():
    import numpy as np

    import shaketable as st

    t, horizontal, vertical = np.arange(5.0) * 0.01, np.ones(5), np.zeros(5)
    motion = st.Motion(t, horizontal, vertical)
    assert motion.horizontal is not horizontal and motion.t is not t
    horizontal *= 2.0          # before: "assignment destination is read-only"
    t += 1.0
    vertical[0] = 5.0
    assert horizontal.flags.writeable and t.flags.writeable
    assert np.array_equal(motion.horizontal, np.ones(5))      # the motion kept its copy
    assert motion.t[0] == 0.0 and motion.vertical[0] == 0.0
    assert not motion.horizontal.flags.writeable              # and stays immutable


@pytest.mark.parametrize("field", ["t", "horizontal", "vertical", "rotation"])
def test_motion_refuses_datetime64_naming_the_field(field):
    import numpy as np

    import shaketable as st

    values = {"t": np.arange(4.0) * 0.01, "horizontal": np.zeros(4), "vertical": None,
              "rotation": None}
    values[field] = np.datetime64("2024-01-01") + np.arange(4) * np.timedelta64(10, "ms")
    with pytest.raises(ValueError, match=f"Motion.{field} .*datetime64"):
        st.Motion(**values)


@pytest.mark.parametrize("field", ["t", "horizontal", "vertical"])
def test_motion_refuses_complex_values_naming_the_field(field):
    import numpy as np

    import shaketable as st

    values = {"t": np.arange(4.0) * 0.01, "horizontal": np.zeros(4), "vertical": np.zeros(4)}
    values[field] = values[field] + 1j    # before: the imaginary part silently dropped
    with pytest.raises(ValueError, match=f"Motion.{field} .*complex"):
        st.Motion(**values)
    with pytest.raises(ValueError, match="Motion.horizontal .*complex"):
        st.Motion([0.0, 0.01], [1 + 2j, 0.0])                  # a plain list too


def _public_objects():
    """One of each public input and result object, made through the public API."""
    import numpy as np

    import shaketable as st
    from shaketable.calibration.fit import calibrate
    from shaketable.calibration.free_rocking import virtual_free_rocking_record
    from shaketable.core.ensemble import Perturbation
    from shaketable.ground import records
    from shaketable.lab.pitch import Pitch
    from shaketable.models.sliding.engine import slide
    from shaketable.models.sliding.result import Friction
    from shaketable.scenes.catalog import resolve_scene_path, resolve_sweep_path
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import run_scene
    from shaketable.studies.predictability import ensemble
    from shaketable.sweeps.spec import load_spec

    block = st.Block.parse("30x6in")
    motion = records.load("pacoima-dam-s16e")
    record, _ = virtual_free_rocking_record(block, 0.92, 0.5 * block.alpha, seed=1,
                                            before=1.3, duration=6.0)
    scene = load_scene(resolve_scene_path("fig-3-4"))
    return {
        "Block": block,
        "Block with rods": st.Block.parse("30x6in", rods=st.PrestressRods.from_inches(
            0.4, 0.4, 2)),
        "Motion": motion,
        "Motion with metadata": st.Motion(np.arange(3.0), np.zeros(3),
                                          metadata={"horizontal": {"station": "PAC"}}),
        "Record": records.read(REPOSITORY / "shaketable" / "data" / "records"
                               / "RSN77_SFERN_PUL164-hor1.AT2"),
        "RockingResult": st.simulate(block, motion, cor=0.9),
        "Friction": Friction(0.3, 0.2),
        "SlidingResult": slide(motion, Friction(0.3, 0.2)),
        "FreeRockingRecord": record,
        "Calibration": calibrate(record, block),
        "Perturbation": Perturbation(),
        "EnsembleResult": ensemble(block, motion, cor=0.9, members=4),
        "Pitch": Pitch(),
        "Scene": scene,
        "SceneResult": run_scene(scene),
        # a virtual test: TableRun (the table's command, servo, pitch) and VirtualTestResult
        "SceneResult with table and sensors": run_scene(load_scene(resolve_scene_path(
            "fig-3-7"))),
        "SceneResult with sliding": run_scene(load_scene(resolve_scene_path(
            "teaching-slide-or-rock"))),
        "SweepSpec": load_spec(resolve_sweep_path("artificial-fragility")),
    }


def test_every_public_object_pickles_and_compares_equal(tmp_path):
    import pickle

    from shaketable.sweeps.execute import run_sweep
    from shaketable.sweeps.spec import spec_from_dict

    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib

    objects = _public_objects()
    objects["SweepOutcome"] = run_sweep(spec_from_dict(tomllib.loads(SWEEP)), tmp_path / "out",
                                        progress=False)
    for name, value in objects.items():
        # before: "cannot pickle 'mappingproxy' object" for every object holding a Motion,
        # and `==` raised "truth value of an array is ambiguous" for those holding arrays
        back = pickle.loads(pickle.dumps(value))
        assert type(back) is type(value), name
        assert back == value, name
        assert not (back != value), name


# ----------------------------------------------------------------- the release-instant record
@pytest.mark.usefixtures("figure_drafts")
def test_a_clean_record_that_starts_at_the_release_calibrates(tmp_path):
    # A clean free-rocking record of the report's 30x6in test block (Sections 3.2, 3.5),
    # 50 samples/s, t = 0 at the release: made with the reference solver (SciPy's DOP853
    # at rtol 1e-12), not the engine the fit uses, at the true COR 0.925 (Fig. 3.4's).
    # Before: "Motion.t: the sample interval t[1] - t[0] = 9e-10 s is below ...", exit 2.
    import numpy as np

    import shaketable as st

    block = st.Block.parse("30x6in")
    run = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=5.0,
                      method="reference", rtol=1e-12)
    t = np.arange(250) * 0.02
    theta = np.interp(t, run.t, run.theta)
    (tmp_path / "release.csv").write_text(
        "time [s],angle [rad]\n" + "".join(f"{a:.4f},{b:.9e}\n" for a, b in zip(t, theta)),
        encoding="utf-8")
    status, out, err = run_cli(["calibrate", "release.csv", "--block", "30x6in", "--out",
                                "cal"], tmp_path)
    assert status == 0, err
    import json

    cor = json.loads((tmp_path / "cal" / "calibration.json").read_text())["cor [-]"]
    # the truth, to the accuracy the interpolation of the reference run allows
    assert abs(cor - 0.925) < 1e-3, cor


# ----------------------------------------------------------------- messages that name things
FREE = ["simulate", "--block", "30x6in", "--cor", "0.9", "--theta0", "0.5alpha", "--duration",
        "1s"]


def test_a_full_disk_names_the_file(tmp_path, monkeypatch):
    import errno

    import pandas as pd

    def full(self, *args, **kwargs):   # what a full disk gives: no file name in the error
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(pd.DataFrame, "to_csv", full)
    status, _, err = run_cli(FREE + ["--out", "out", "-q"], tmp_path)
    assert status == 1, err
    # before: "cannot read or write: No space left on device" (no file, no folder)
    assert "No space left on device" in err and "history.csv" in err and "out" in err, err
    assert "internal error" not in err
    assert [path.name for path in (tmp_path / "out").iterdir()] == []   # no temporary left


DEEP_TOML = "x = " + "[" * 3000 + "]" * 3000 + "\n"


@pytest.mark.parametrize("kind", ["scene", "sweep"])
def test_a_toml_nested_thousands_deep_is_bad_input_naming_the_file(tmp_path, kind):
    (tmp_path / "deep.toml").write_text(DEEP_TOML, encoding="utf-8")
    status, _, err = run_cli(["run" if kind == "scene" else "sweep", "deep.toml", "-q"],
                             tmp_path)
    assert status == 2, err            # before: "maximum recursion depth exceeded", exit 1
    assert "deep.toml" in err and "nested too deeply" in err, err


@pytest.mark.parametrize("argv", [FREE + ["--out", "a" * 300],
                                  FREE + ["--out", "ok/" + "b" * 256 + "/c"],
                                  ["animate", "fig-3-4", "--out", "c" * 250 + ".gif"]])
def test_an_output_name_too_long_is_refused_before_any_work(tmp_path, argv, monkeypatch):
    import shaketable.models.api as api

    def no_work(*args, **kwargs):
        raise AssertionError("the run started before --out was checked")

    monkeypatch.setattr(api, "simulate", no_work)
    status, _, err = run_cli(argv, tmp_path)
    assert status == 2, err            # before: exit 1 after the run, naming no option
    assert "--out" in err and "Traceback" not in err, err


# ----------------------------------------------------------------- a closed pipe
def test_a_closed_pipe_ends_quietly():
    # `shaketable reproduce --list | head -1`: the reader is gone before the writer
    # writes; made deterministic by closing the pipe's reading end before the child starts
    # printing. Before: "cannot read or write: Broken pipe", exit 1 (and Python's
    # "Exception ignored ... BrokenPipeError" at exit).
    child = subprocess.Popen([sys.executable, "-m", "shaketable", "reproduce", "--list"],
                             cwd=REPOSITORY, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    child.stdout.close()
    err = child.stderr.read().decode()
    child.stderr.close()
    assert child.wait() == 141, err     # 128 + SIGPIPE, the status of a Unix tool cut off so
    assert err == ""


# ----------------------------------------------------------------- numba's cache folder
def test_the_cache_folder_holds_when_numba_is_imported_first(tmp_path):
    # A notebook that used numba before shaketable: before, numba had read an empty
    # NUMBA_CACHE_DIR, the engine compiled into the package's own __pycache__
    # (the package's own __pycache__/*.nbi) and the user's cache stayed empty.
    import time

    started = time.time()
    env = {key: value for key, value in os.environ.items() if not key.startswith("NUMBA_")}
    env.update(HOME=str(tmp_path / "home"), XDG_CACHE_HOME=str(tmp_path / "cache"))
    # Compiled here: Eq. (2-13)'s theta'' (models/rocking/physics.py), a function the package caches
    # as it caches the engine (the same locator and folder), at 0.3 s of compile instead of
    # the engine's 3 s: the test is about where numba writes, not what it compiles.
    code = ("import numba, numpy as np\n"
            "import shaketable as st\n"
            "from shaketable.models.rocking.physics import angular_acceleration, block_parameters\n"
            "block = st.Block.parse('30x6in')\n"
            "print(angular_acceleration(0.5 * block.alpha, 1.0, 0.0, 0.0, 0.0, "
            "block_parameters(block)))\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=REPOSITORY, env=env)
    assert result.returncode == 0, result.stderr
    cache = tmp_path / "cache" / "shaketable" / "numba"
    assert any(cache.rglob("*.nbi")), "the user's cache folder stayed empty"
    in_package = [path for path in (REPOSITORY / "shaketable").rglob("*.nbi")
                  if path.stat().st_mtime >= started - 1]
    assert in_package == [], in_package


# ----------------------------------------------------------------- large inputs through the CLI
def _big_table(path: Path, rows: int, layout: str) -> None:
    import numpy as np

    rng = np.random.default_rng(7)
    t = np.arange(rows) * 0.005
    values = rng.standard_normal(rows) * 10.0 ** rng.integers(-6, 1, rows)
    if layout == "comma":
        text = "time [s],acc [g]\n" + "".join(f"{float(a)!r},{float(b)!r}\n"
                                               for a, b in zip(t, values))
    elif layout == "whitespace":
        text = "".join(f"  {a:.3f}\t {b:.6e} \n" for a, b in zip(t, values))
    elif layout == "one":   # one column, CRLF
        text = "".join(f"{b:.17g}\r\n" for b in values)
    else:   # a header of comments and names, CRLF, blank lines at the end
        text = ("# station XYZ\r\n% units g\r\n\r\ntime  acc\r\n"
                + "".join(f"{a:.3f} {b:.9f}\r\n" for a, b in zip(t, values)) + "\r\n\r\n")
    path.write_bytes(text.encode())


def _split_as_read_text(path: Path):
    from shaketable.ground.readers import text

    content = text.read_text_file(path)
    lines = content.splitlines()
    return content, lines[:text.count_header_lines(lines, None, None)]


@pytest.mark.parametrize("layout", ["comma", "whitespace", "one", "header"])
def test_the_fast_text_path_reads_the_same_bits(tmp_path, layout, monkeypatch):
    import numpy as np

    from shaketable.ground.readers import text

    path = tmp_path / "big.txt"
    _big_table(path, 2 * text.FAST_PATH_LINES, layout)
    options = {"units": "g"} | ({"dt": 0.005} if layout == "one" else {})
    fast = text.read_text(path, **options)
    assert text._fast_body(*_split_as_read_text(path), delimiter=None, european=False) \
        is not None                                       # the compiled parser did read it
    monkeypatch.setattr(text, "FAST_PATH_LINES", 10 ** 9)      # the line-by-line parser
    exact = text.read_text(path, **options)
    assert np.array_equal(fast.acceleration, exact.acceleration)   # bit for bit
    assert (fast.dt, fast.t0, fast.component) == (exact.dt, exact.t0, exact.component)


@pytest.mark.parametrize("fault, message", [
    ("-inf", "line 79: '-inf' is not a finite number"),
    ("nan", "line 79: 'nan' is not a finite number"),
    ("0.1 0.2", "line 79: 3 column(s), but the data start with 2"),
    ("1.5D-3", None),           # a Fortran exponent: read (by the exact parser)
    ("# a comment", None),      # skipped
    ("", None),                 # a blank line: skipped
])
def test_a_fault_in_a_long_record_is_reported_on_its_line(tmp_path, fault, message):
    # -inf on line 79 of a long CSV: before, "line 1001: no numeric data found" was reported
    from shaketable.ground.readers import text

    path = tmp_path / "big.csv"
    _big_table(path, 2 * text.FAST_PATH_LINES, "comma")
    lines = path.read_text().splitlines()
    if fault in ("", "# a comment"):
        lines.insert(78, fault)      # line 79 is not data; the samples go on after it
    elif fault == "0.1 0.2":
        lines[78] = "0.385,0.1,0.2"
    else:
        lines[78] = f"{lines[78].split(',')[0]},{fault}"
    path.write_text("\n".join(lines) + "\n")
    if message is None:
        record = text.read_text(path, units="g")
        data = 2 * text.FAST_PATH_LINES
        assert record.acceleration.size == data
        if fault == "1.5D-3":
            assert record.acceleration[77] == 1.5e-3 * 9.80665
    else:
        with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
            text.read_text(path, units="g")


@pytest.mark.usefixtures("figure_drafts")
def test_history_choices_of_simulate(tmp_path):
    import numpy as np
    import pandas as pd

    import shaketable as st

    base = FREE[:-1] + ["4s"]
    runs = {}
    for choice in ("auto", "full", "peaks", "none"):
        status, out, err = run_cli(base + ["--history", choice, "--out", choice], tmp_path)
        assert status == 0, err
        runs[choice] = tmp_path / choice / "history.csv"
    # a short run: auto is full, byte for byte what simulate wrote before --history existed
    assert runs["auto"].read_bytes() == runs["full"].read_bytes()
    assert not runs["none"].exists() and (tmp_path / "none" / "summary.json").is_file()
    full, peaks = pd.read_csv(runs["full"]), pd.read_csv(runs["peaks"])
    # peaks: a subset of the full rows, holding the first and last rows, every largest
    # |theta| between impacts and every impact (the sign changes of theta, both sides)
    assert 2 < len(peaks) < len(full) / 4
    assert peaks.merge(full, how="left", indicator=True)["_merge"].eq("both").all()
    theta = full["theta [rad]"].to_numpy()
    assert full["time [s]"].iloc[[0, -1]].isin(peaks["time [s]"]).all()
    crossings = np.flatnonzero(np.signbit(theta[1:]) != np.signbit(theta[:-1]))
    assert len(crossings) > 3      # free rocking from 0.5 alpha: several impacts in 4 s
    assert full["time [s]"].iloc[np.r_[crossings, crossings + 1]].isin(peaks["time [s]"]).all()
    for start, stop in zip(crossings[:-1], crossings[1:]):   # each half-cycle's peak
        peak = start + 1 + int(np.argmax(np.abs(theta[start + 1:stop + 1])))
        assert full["time [s]"].iloc[peak] in set(peaks["time [s]"])
    del st


def test_a_long_run_is_drawn_from_its_envelope(monkeypatch):
    import numpy as np

    import shaketable as st
    from shaketable.commands import history

    block = st.Block.parse("30x6in")
    t = np.arange(60_001) * 0.005
    motion = st.Motion(t, 0.25 * st.G * np.sin(2 * np.pi * 4.0 * t) * (t < 30.0))
    result = st.simulate(block, motion, cor=0.9)
    assert history.for_figure(result) is result          # short: every sample drawn
    monkeypatch.setattr(history, "FULL_HISTORY_ROWS", 10_000)
    drawn = history.for_figure(result)
    assert drawn.t.size < result.t.size and drawn.motion.t.size < motion.t.size
    # every extreme the figure shows is kept: the same extent on every curve
    for name in ("theta", "theta_dot", "theta_ddot"):
        assert getattr(drawn, name).max() == getattr(result, name).max()
        assert getattr(drawn, name).min() == getattr(result, name).min()
    assert drawn.motion.horizontal.max() == motion.horizontal.max()
    assert drawn.summary() == result.summary()           # scalars untouched


# ----------------------------------------------------------------- European CSV
EURO_ROWS = [(0.005 * k, 0.1 * ((-1) ** k) * (k % 7) / 7) for k in range(400)]


def _euro(values, header: str = "") -> str:
    return header + "".join(f"{t:.3f};{a:.4f}\n".replace(".", ",") for t, a in values)


@pytest.mark.usefixtures("figure_drafts")
@pytest.mark.parametrize("header", ["", "time [s];acc [g]\n"])
def test_a_european_csv_is_recognised(tmp_path, header):
    # semicolons between fields and a decimal comma, as a spreadsheet in a European locale
    # exports; before: "has 4 columns; choose ... value_column=" (an API-only keyword)
    import numpy as np

    from shaketable.core.constants import G
    from shaketable.ground import records

    (tmp_path / "euro.csv").write_text(_euro(EURO_ROWS, header), encoding="utf-8")
    record = records.read(tmp_path / "euro.csv", units="g")
    assert record.dt == pytest.approx(0.005)
    expected = np.array([float(f"{a:.4f}") for _, a in EURO_ROWS]) * G
    assert np.array_equal(record.acceleration, expected)
    status, out, err = run_cli(["simulate", "--block", "30x6in", "--cor", "0.9", "--record",
                                "euro.csv", "--units", "g", "--out", "o", "-q"], tmp_path)
    assert status == 0, err


@pytest.mark.usefixtures("figure_drafts")
def test_several_columns_name_the_cli_option(tmp_path):
    text = "t;a;b\n" + "".join(f"{t:.3f};{a:.4f};{-a:.4f}\n".replace(".", ",")
                                for t, a in EURO_ROWS)
    (tmp_path / "three.csv").write_text(text, encoding="utf-8")
    argv = ["simulate", "--block", "30x6in", "--cor", "0.9", "--record", "three.csv",
            "--units", "g", "--out", "o", "-q"]
    status, _, err = run_cli(argv, tmp_path)
    assert status == 2 and "three.csv has 3 columns" in err and "--column" in err, err
    status, _, err = run_cli(argv + ["--column", "b"], tmp_path)
    assert status == 0, err


def test_a_full_disk_under_calibrate_names_the_file(tmp_path, monkeypatch):
    import errno

    import matplotlib.figure

    def full(self, *args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", full)
    status, _, err = run_cli(["calibrate", "virtual-fig-3-4", "--block", "30x6in", "--out",
                              "cal", "-q"], tmp_path)
    assert status == 1, err
    assert "calibration.png" in err and "No space left on device" in err, err


def test_an_edit_of_an_inlined_helper_moves_the_default_cache_folder(tmp_path):
    # numba's cache index checks only the file that defines a cached function: an edit of
    # models/rocking/steppers.py (inlined into engine.py's integrators) would leave stale machine
    # code in the cache. The default folder is keyed by the compiled modules' source.
    import shutil

    copy = tmp_path / "copy"
    shutil.copytree(REPOSITORY / "shaketable", copy / "shaketable",
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = {key: value for key, value in os.environ.items() if not key.startswith("NUMBA_")}
    env.update(XDG_CACHE_HOME=str(tmp_path / "cache"), PYTHONPATH=str(copy))
    code = "import os, shaketable; print(os.environ['NUMBA_CACHE_DIR'])"

    def folder() -> str:
        result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                cwd=tmp_path, env=env, check=True)
        return result.stdout.strip()

    before = folder()
    assert before.startswith(str(tmp_path / "cache" / "shaketable" / "numba"))
    assert folder() == before                       # the same sources, the same folder
    with open(copy / "shaketable" / "models" / "rocking" / "steppers.py", "a") as source:
        source.write("\n# an edit\n")
    assert folder() != before
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "mine")  # a folder the user chose stays as it is
    assert folder() == str(tmp_path / "mine")
