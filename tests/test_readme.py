"""Every command of the README's "Use" section runs verbatim from an empty folder.

Each ``shaketable ...`` line of the README's bash blocks (the set-up block's pip lines
excepted) runs in a folder of its own outside the repository, empty but for what the
earlier lines of its block wrote that it reads (``risk fragility`` reads the folder the
``sweep ... --out fragility`` line above it writes, so that line runs first there), as a
user would type them, through the console script's function (``shaketable.cli.main``, in
the test's process: a fresh interpreter per line cost 1.7 s of CPU each; the entry point
itself runs a README line in a subprocess below); the Python blocks as scripts (globals
of their own) in the test's process: exit status 0 (no exception), no traceback, files
written. No test needs another to have run, on its worker or before it: a line another
reads is run once per process (a module-scoped memo) and its folder copied.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import traceback

import matplotlib.pyplot as plt
import pytest

from shaketable.scenes.catalog import scene_names
from tests.helpers import REPOSITORY, TEST_MEMBERS, draft_animations, draft_figures

README = (REPOSITORY / "README.md").read_text(encoding="utf-8")


def _blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", README, flags=re.DOTALL)


def _command_blocks() -> list[list[str]]:
    """The ``shaketable`` lines of each bash block (comments dropped), blocks without one left out."""
    blocks = []
    for block in _blocks("bash"):
        lines = [line.split("  #")[0].strip() for line in block.splitlines()]
        lines = [line for line in lines if line.startswith("shaketable ")]
        if lines:
            blocks.append(lines)
    return blocks


BLOCKS = _command_blocks()
COMMANDS = [line for block in BLOCKS for line in block]
#: (block, line) of every command, in the README's order
LINES = [(b, i) for b, block in enumerate(BLOCKS) for i in range(len(block))]
PYTHON_BLOCKS = _blocks("python")

#: The bundled scenes the README runs as plain ``shaketable run NAME``: this file checks
#: them as ``tests/scenes/test_every_scene_runs.py`` checks every other scene (which
#: leaves them out, so that no scene runs twice for the same checks).
README_RUN_SCENES = [command.split()[2] for command in COMMANDS
                     if len(command.split()) == 3 and command.split()[1] == "run"]


def _out(line: str) -> str | None:
    words = shlex.split(line)
    return words[words.index("--out") + 1] if "--out" in words[:-1] else None


def prerequisites(block: int, index: int) -> list[int]:
    """The earlier lines of ``block`` whose output folder line ``index`` reads (a word of its
    arguments, not the name of a bundled scene, is that folder), with theirs, in order."""
    lines = BLOCKS[block]
    bundled = set(scene_names())
    words = [word for word in shlex.split(lines[index])[2:] if word not in bundled]
    needed: set[int] = set()
    for earlier in range(index):
        out = _out(lines[earlier])
        if out is not None and any(word == out or word.startswith(out + "/") for word in words):
            needed.add(earlier)
            needed.update(prerequisites(block, earlier))
    return sorted(needed)


def _environment():
    environment = dict(os.environ, MPLBACKEND="Agg")
    environment["PYTHONPATH"] = os.pathsep.join(
        [str(REPOSITORY)] + [part for part in environment.get("PYTHONPATH", "").split(os.pathsep)
                             if part])
    return environment


def _files(folder):
    return {path: path.stat().st_mtime_ns for path in folder.rglob("*") if path.is_file()}


def test_the_readme_has_commands_and_python():
    assert len(COMMANDS) >= 8 and PYTHON_BLOCKS


def test_the_risk_line_runs_after_the_sweep_it_reads():
    """From an empty folder ``risk fragility`` has no sweep to read: its block must write
    that folder first (the README says so beside it)."""
    (block, index), = [(b, i) for b, i in LINES if BLOCKS[b][i].startswith("shaketable risk ")]
    needed = prerequisites(block, index)
    assert [BLOCKS[block][i].split()[1] for i in needed] == ["sweep"]
    assert _out(BLOCKS[block][needed[0]]) == shlex.split(BLOCKS[block][index])[2]


def _run_in_process(argv: list[str], folder) -> subprocess.CompletedProcess:
    """``shaketable ARGV`` run in ``folder`` by the console script's function, its output
    captured; an exception that escapes it is a traceback on stderr and exit status 1.
    Its PNG figures are drafts (:func:`tests.helpers.draft_figures`: every figure built
    and drawn, at a low dpi without the layout solver), and so are its animations' frames
    (:func:`tests.helpers.draft_animations`: every frame drawn, with fewer pixels): these
    tests check that the line runs and writes its files, tests/plots how its figures
    look."""
    from shaketable.cli import main

    stdout, stderr = io.StringIO(), io.StringIO()
    here = os.getcwd()
    os.chdir(folder)
    try:
        with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr), \
                draft_figures(), draft_animations():
            try:
                status = main(argv)
            except SystemExit as exit_:
                status = exit_.code if isinstance(exit_.code, int) else 1
            except Exception:
                traceback.print_exc()
                status = 1
    finally:
        os.chdir(here)
        plt.close("all")
    return subprocess.CompletedProcess(argv, status, stdout.getvalue(), stderr.getvalue())


def test_the_console_entry_point_runs_a_readme_line(tmp_path):
    """The first README line through ``python -m shaketable`` (what the console script
    calls), in a fresh interpreter, from an empty folder."""
    line = BLOCKS[0][0]
    done = subprocess.run([sys.executable, "-m", "shaketable"] + shlex.split(line)[1:],
                          cwd=tmp_path, env=_environment(), capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
    assert (tmp_path / _out(line)).is_dir() and any((tmp_path / _out(line)).iterdir())


@pytest.fixture(scope="module")
def shared_table_predictability():
    """``run table-4-2`` and ``reproduce fig-3-4 table-4-2`` both end with Table 4.2's
    ensembles (:func:`shaketable.studies.predictability.predictability_markdown`). Here
    they run with :data:`tests.helpers.TEST_MEMBERS` members per cell instead of the
    package's 200 (9,600 distinct batch runs, about 7 s of CPU): the same code path (one
    batch call whatever the size, the nominal member first), as
    ``tests/scenes/test_every_scene_runs.py`` runs the other report tables; these tests
    check that the README's lines run and write their files, not the ensembles'
    statistics (``tests/studies/test_predictability.py`` checks the ensemble machinery). The table is
    computed once per process for the same arguments (the function is deterministic:
    seeded members, fixed records), each caller getting its own copy of the frame."""
    import copy
    import functools

    from shaketable.studies import predictability

    computed: dict = {}
    original = predictability.table_predictability

    def table_predictability(*args, **kwargs):
        key = repr((args, sorted(kwargs.items())))
        if key not in computed:
            computed[key] = original(*args, **kwargs)
        return copy.deepcopy(computed[key])

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(predictability, "table_predictability", table_predictability)
        patch.setattr(predictability, "predictability_markdown", functools.partial(
            predictability.predictability_markdown, members=TEST_MEMBERS))
        yield computed


@pytest.fixture(scope="module")
def coarse_spectrum_scan():
    """The ``spectrum`` lines scan omega/p with a relative step of 0.05 instead of the
    command's 0.005 (``BLOCK_SCAN_STEP``; 2.8 s of CPU for the README's first line): the
    same code runs (scan, edge bisection to the same tolerance, flags, CSV, figure) on a
    tenth of the grid points. The first line then finds 18 bands instead of 20 (one-sine,
    omega/p = 1 loses a band 0.7 % wide, and a narrow band is still flagged): these tests
    check that the lines run and write their files;
    tests/studies/test_overturning_spectrum.py checks the bands against an independent
    solver and the closed forms."""
    from shaketable.commands import block

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(block, "BLOCK_SCAN_STEP", 0.05)
        yield


@pytest.fixture(scope="module")
def first_call_in_process():
    """``bench``'s first-call timing (:func:`shaketable.studies.work_precision.first_call_seconds`)
    runs its script (import, two ``simulate`` calls, the printed times) in the test's process
    instead of a fresh interpreter (1.0 s of CPU in imports): its own code still builds the
    environment and parses the script's output. These tests check that the README's lines
    run and write their files; a fresh interpreter running a README line is
    :func:`test_the_console_entry_point_runs_a_readme_line`'s subject."""
    import types

    from shaketable.studies import work_precision

    def run(argv, **options):
        assert argv[1] == "-c", argv
        stdout = io.StringIO()
        with contextlib.redirect_stdout(stdout):
            exec(compile(argv[2], "<first call>", "exec"), {"__name__": "__main__"})
        return subprocess.CompletedProcess(argv, 0, stdout.getvalue(), "")

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(work_precision, "subprocess", types.SimpleNamespace(run=run))
        yield


@pytest.fixture(scope="module")
def run_line(tmp_path_factory, shared_table_predictability, coarse_spectrum_scan,
             first_call_in_process):
    """Run a README line in a fresh folder holding the outputs of its prerequisites; each
    line runs once per process (its folder, the files before it ran, and its process)."""
    done: dict = {}

    def run(block: int, index: int):
        if (block, index) not in done:
            folder = tmp_path_factory.mktemp(f"readme-{block}-{index}")
            for earlier in prerequisites(block, index):
                shutil.copytree(run(block, earlier)[0], folder, dirs_exist_ok=True)
            before = _files(folder)
            done[(block, index)] = (folder, before,
                                    _run_in_process(shlex.split(BLOCKS[block][index])[1:], folder))
        return done[(block, index)]

    return run


@pytest.mark.slow
@pytest.mark.parametrize("block, index", LINES, ids=COMMANDS)
def test_readme_command_runs_verbatim_from_an_empty_folder(block, index, run_line):
    user_folder, before, done = run_line(block, index)
    command = BLOCKS[block][index]
    assert "Traceback" not in done.stderr, done.stderr
    assert done.returncode == 0, done.stderr
    assert _files(user_folder) != before, "the command wrote nothing"
    words = command.split()
    if words[1] == "run" and words[2] in README_RUN_SCENES:
        # the checks of tests/scenes/test_every_scene_runs.py on this bundled scene
        assert "internal error" not in done.stderr, done.stderr
        assert "wrote" in done.stdout
        assert any((user_folder / "shaketable-out" / words[2]).iterdir())


@pytest.mark.parametrize("index", range(len(PYTHON_BLOCKS)))
def test_readme_python_block_runs(index, tmp_path):
    """Each Python block run as a script (``__main__``, globals of its own, so it must import
    what it uses) in an empty folder, in the test's process (a fresh interpreter per block
    cost 1.7 s of CPU in imports; the console entry point's test above starts one)."""
    stdout = io.StringIO()
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        with contextlib.redirect_stdout(stdout):
            exec(compile(PYTHON_BLOCKS[index], f"<README python block {index}>", "exec"),
                 {"__name__": "__main__"})
    finally:
        os.chdir(here)
        plt.close("all")
    # run as a script, a block shows something and keeps something
    assert stdout.getvalue().strip(), "the block prints nothing"
    assert any(tmp_path.iterdir()), "the block writes nothing"
