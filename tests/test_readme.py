"""Every command of the README's "Use" section runs verbatim from an empty folder.

The ``shaketable ...`` lines of the README's bash blocks (the set-up block's pip lines
excepted) are run in order in one temporary folder outside the repository, as a user
would type them (so a folder an earlier command wrote is there for the later ones),
through ``python -m shaketable`` (the same entry point as the console script); the
Python blocks in a fresh interpreter: exit status 0, no traceback, files written.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys

import pytest

from tests.helpers import REPOSITORY

README = (REPOSITORY / "README.md").read_text(encoding="utf-8")


def _blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", README, flags=re.DOTALL)


def _commands() -> list[str]:
    lines = []
    for block in _blocks("bash"):
        for line in block.splitlines():
            line = line.split("  #")[0].strip()
            if line.startswith("shaketable "):
                lines.append(line)
    return lines


COMMANDS = _commands()
PYTHON_BLOCKS = _blocks("python")

#: The bundled scenes the README runs as plain ``shaketable run NAME``: this file checks
#: them as ``tests/scenes/test_every_scene_runs.py`` checks every other scene (which
#: leaves them out, so that no scene runs twice for the same checks).
README_RUN_SCENES = [command.split()[2] for command in COMMANDS
                     if len(command.split()) == 3 and command.split()[1] == "run"]


def _environment():
    environment = dict(os.environ, MPLBACKEND="Agg")
    environment["PYTHONPATH"] = os.pathsep.join(
        [str(REPOSITORY)] + [part for part in environment.get("PYTHONPATH", "").split(os.pathsep)
                             if part])
    return environment


def test_the_readme_has_commands_and_python():
    assert len(COMMANDS) >= 8 and PYTHON_BLOCKS


@pytest.fixture(scope="module")
def user_folder(tmp_path_factory):
    """The one folder, empty at first, where the README's commands run one after another."""
    return tmp_path_factory.mktemp("readme-user")


def _files(folder):
    return {path: path.stat().st_mtime_ns for path in folder.rglob("*") if path.is_file()}


@pytest.mark.slow
@pytest.mark.parametrize("command", COMMANDS)
def test_readme_command_runs_verbatim_from_an_empty_folder(command, user_folder):
    before = _files(user_folder)
    argv = [sys.executable, "-m", "shaketable"] + shlex.split(command)[1:]
    done = subprocess.run(argv, cwd=user_folder, env=_environment(), capture_output=True,
                          text=True, timeout=600)
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
    done = subprocess.run([sys.executable, "-c", PYTHON_BLOCKS[index]], cwd=tmp_path,
                          env=_environment(), capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    # run as a script, a block shows something and keeps something
    assert done.stdout.strip(), "the block prints nothing"
    assert any(tmp_path.iterdir()), "the block writes nothing"
