"""Safe to share and to run unattended (issue 27): each defect the hostile-user audit
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
os.umask(int(sys.argv[1], 8))
from shaketable.cli import main
work = Path(sys.argv[2])
os.chdir(work)
(work / "w.toml").write_text(sys.argv[3], encoding="utf-8")
assert main(["simulate", "--block", "30x6in", "--cor", "0.9", "--theta0", "0.5alpha",
             "--duration", "1", "--out", "sim", "-q"]) == 0
assert main(["sweep", "w.toml", "--out", "swept", "-q", "--no-progress"]) == 0
for path in sorted(work.rglob("*")):
    if path.is_file() and path.name != "w.toml":
        print(oct(stat.S_IMODE(path.stat().st_mode)), path.relative_to(work))
"""


@pytest.mark.parametrize("umask, expected", [("022", 0o644), ("027", 0o640), ("077", 0o600)])
def test_outputs_get_the_mode_the_umask_gives(tmp_path, umask, expected):
    # before: every output was 0600 (mkstemp's mode kept by the rename) whatever the umask
    result = subprocess.run([sys.executable, "-c", _MODES, umask, str(tmp_path), SWEEP],
                            capture_output=True, text=True, cwd=REPOSITORY)
    assert result.returncode == 0, result.stderr
    lines = [line.split() for line in result.stdout.splitlines()]
    written = {name for _, name in lines}
    # the simulate outputs, the sweep's manifest, part and result table are all there
    assert {"sim/history.csv", "swept/manifest.json", "swept/parts/part-000000.parquet"} <= written
    assert any(name.startswith("swept/results.") for name in written)
    assert {mode for mode, _ in lines} == {oct(expected)}, lines
