"""Packaging hygiene: the Python 3.10 ``tomli`` fallback, ``py.typed``, one version."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import shaketable

ROOT = Path(__file__).resolve().parents[1]


def test_toml_fallback_to_tomli_when_tomllib_is_missing():
    # Python 3.10 has no tomllib; simulate that and hand in a stand-in "tomli"
    # (tomli and tomllib are the same parser) to prove the fallback path is taken.
    code = (
        "import sys, types, tomllib as real\n"
        "fake = types.ModuleType('tomli'); fake.loads = real.loads\n"
        "fake.TOMLDecodeError = real.TOMLDecodeError\n"
        "sys.modules['tomli'] = fake; sys.modules['tomllib'] = None\n"
        "import shaketable.scenes.parse as parse, shaketable.sweeps.spec as spec\n"
        "print(parse.tomllib is fake, spec.tomllib is fake)\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True, cwd=ROOT)
    assert result.stdout.split() == ["True", "True"]


def test_py_typed_license_and_changelog_are_present():
    assert (ROOT / "shaketable" / "py.typed").is_file()
    assert "MIT License" in (ROOT / "LICENSE").read_text()
    assert "## [Unreleased]" in (ROOT / "CHANGELOG.md").read_text()


def test_version_is_written_once():
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert re.search(r'^version\s*=\s*"', pyproject, re.MULTILINE) is None
    assert 'version = { attr = "shaketable.version.__version__" }' in pyproject
    assert re.fullmatch(r"\d+\.\d+\.\d+(\.dev\d+)?", shaketable.__version__)
