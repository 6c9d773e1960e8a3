"""Packaging hygiene: the Python 3.10 ``tomli`` fallback, ``py.typed``, one version."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import shaketable

ROOT = Path(__file__).resolve().parents[1]


def test_toml_fallback_to_tomli_when_tomllib_is_missing():
    # Python 3.10 has no tomllib; simulate that (None in sys.modules makes the import
    # fail) and hand in a stand-in "tomli" (tomli and tomllib are the same parser) that
    # counts its calls, to prove the fallback path is taken and that a bundled scene and
    # a bundled sweep spec then load through it, and a bad file still gives a clear error.
    code = (
        "import sys, types, tomllib as real\n"
        "calls = []\n"
        "fake = types.ModuleType('tomli')\n"
        "fake.loads = lambda text: calls.append(len(text)) or real.loads(text)\n"
        "fake.TOMLDecodeError = real.TOMLDecodeError\n"
        "sys.modules['tomli'] = fake; sys.modules['tomllib'] = None\n"
        "import shaketable.scenes.parse as parse, shaketable.sweeps.spec as spec\n"
        "from shaketable.scenes.catalog import resolve_scene_path, resolve_sweep_path\n"
        "import shaketable.core.tomlfile as tomlfile\n"
        "print(tomlfile.tomllib is fake)\n"
        "scene = parse.load_scene(resolve_scene_path('fig-3-4'))\n"
        "sweep = spec.load_spec(resolve_sweep_path('artificial-fragility'))\n"
        "print(scene.name, sweep.name, len(calls))\n"
        "import pathlib, tempfile\n"
        "bad = pathlib.Path(tempfile.mkdtemp()) / 'bad.toml'\n"
        "bad.write_text('[block\\n', encoding='utf-8')\n"
        "try:\n"
        "    parse.load_scene(bad)\n"
        "except ValueError as error:\n"
        "    print('refused', 'bad.toml' in str(error), len(calls))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=ROOT)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].split() == ["True"]
    assert lines[1].split() == ["fig-3-4", "artificial-fragility", "2"]
    assert lines[2].split() == ["refused", "True", "3"]


def test_pyproject_declares_tomli_for_python_3_10():
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert re.search(r'requires-python\s*=\s*">=3\.10"', pyproject)
    assert "\"tomli>=2.0; python_version < '3.11'\"" in pyproject


def test_py_typed_license_and_changelog_are_present():
    assert (ROOT / "shaketable" / "py.typed").is_file()
    assert "MIT License" in (ROOT / "LICENSE").read_text()
    assert "## [Unreleased]" in (ROOT / "CHANGELOG.md").read_text()


def test_version_is_written_once():
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert re.search(r'^version\s*=\s*"', pyproject, re.MULTILINE) is None
    assert 'version = { attr = "shaketable.version.__version__" }' in pyproject
    assert re.fullmatch(r"\d+\.\d+\.\d+(\.dev\d+)?", shaketable.__version__)


def test_every_name_of_the_front_door_loads_from_outside_the_repository(tmp_path):
    """``import shaketable`` and ``from shaketable import *`` from a folder outside the
    checkout: every name of ``__all__`` resolves (``simulate`` and ``METHODS`` on first use,
    from ``models.api`` and ``models.rocking.layout``), and the import itself loads no numba.
    ``shaketable.METHODS`` raised AttributeError before (it was looked up in ``api``)."""
    code = (
        "import sys\n"
        "import shaketable\n"
        "light = 'numba' not in sys.modules\n"
        "from shaketable import *\n"
        "missing = [n for n in shaketable.__all__ if getattr(shaketable, n, None) is None]\n"
        "print(light, missing, sorted(shaketable.METHODS), simulate.__module__,\n"
        "      set(shaketable.__all__) <= set(dir(shaketable)))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split("\n")[0] == ("True [] ['fast', 'linear', 'predictor-corrector', "
                                           "'reference'] shaketable.models.api True")


def test_the_package_loads_from_the_folder_that_holds_a_checkout_named_shaketable(tmp_path):
    """A clone is named ``shaketable`` and used from its parent folder: that folder is on
    ``sys.path`` first and the checkout (no ``__init__.py`` at its root) would be taken as a
    namespace package ``shaketable`` with no ``simulate`` if the editable install found the
    package through an import hook, which Python consults after its path search (setuptools
    does so for a flat layout). ``package-dir = {"" = "."}`` in pyproject.toml makes it a
    plain path entry instead, where the search finds the real package. (Installed from the
    wheel or from a path entry this holds too; under a hook-based editable install, as
    setuptools made before, this failed.)"""
    (tmp_path / "shaketable").symlink_to(ROOT, target_is_directory=True)
    code = "from shaketable import simulate, METHODS; print(simulate.__module__)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "shaketable.models.api"


def test_the_first_versions_module_path_shaketable_simulate_still_imports(tmp_path):
    """The first version had a module ``shaketable.simulate`` (``from shaketable.simulate
    import simulate, METHODS``); the project's set-up check imports it from outside the
    checkout. Importing it binds ``shaketable.simulate`` to the module, which is callable as
    the function: a run gives the same result before and after (bit for bit), and a bare
    ``import shaketable`` still loads no numba."""
    code = (
        "import sys\n"
        "import shaketable as st\n"
        "light = 'numba' not in sys.modules\n"
        "block = st.Block.parse('30x6in')\n"
        "before = st.simulate(block, cor=0.925, theta0=0.05, duration=2)\n"
        "import shaketable.simulate\n"
        "after = st.simulate(block, cor=0.925, theta0=0.05, duration=2)\n"
        "from shaketable.simulate import METHODS, simulate\n"
        "from shaketable.models import api\n"
        "print(light, simulate is api.simulate, sorted(METHODS) == sorted(st.METHODS),\n"
        "      bool((before.theta == after.theta).all()), before.n_impacts == after.n_impacts)\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["True"] * 5


def test_a_build_from_a_checkout_writes_nothing_into_it(tmp_path):
    """The build backend (``buildtools/shaketable_build.py``, pyproject's ``build-backend``)
    runs setuptools with its scratch folders outside the source folder: a tiny project's
    sdist built with it leaves the project file for file as it was, and its wheel's build
    folder (``build/lib``, where ``build_py`` copies the modules) is outside it; setuptools'
    own backend, run the same way, writes an egg-info there and builds in ``build/``
    (what ``pip install /path/to/checkout`` did to the checkout)."""
    import tarfile

    pyproject = (ROOT / "pyproject.toml").read_text()
    assert 'build-backend = "shaketable_build"' in pyproject
    assert 'backend-path = ["buildtools"]' in pyproject
    assert "include buildtools/shaketable_build.py" in (ROOT / "MANIFEST.in").read_text()
    found = {}
    for backend in ("shaketable_build", "setuptools.build_meta"):
        project = tmp_path / backend / "project"
        (project / "tiny").mkdir(parents=True)
        (project / "tiny" / "__init__.py").write_text("VALUE = 1\n")
        (project / "setup.cfg").write_text("[metadata]\nname = tiny\nversion = 1.0\n"
                                           "[options]\npackages = tiny\n")
        before = sorted(path.relative_to(project) for path in project.rglob("*"))
        dist = tmp_path / backend / "dist"
        dist.mkdir()
        code = (f"import contextlib, importlib, os, sys\n"
                f"sys.path.insert(0, {str(ROOT / 'buildtools')!r})\n"
                f"backend = importlib.import_module({backend!r})\n"
                f"print(backend.build_sdist({str(dist)!r}))\n"
                "from setuptools.dist import Distribution\n"
                "with getattr(backend, 'outside_the_checkout', contextlib.nullcontext)():\n"
                "    distribution = Distribution()\n"
                "    distribution.parse_config_files()\n"
                "    build = distribution.get_command_obj('build')\n"
                "    build.ensure_finalized()\n"
                "    print(os.path.abspath(build.build_lib))\n")
        result = subprocess.run([sys.executable, "-c", code], cwd=project, capture_output=True,
                                text=True)
        assert result.returncode == 0, result.stderr
        sdist, build_lib = result.stdout.split()[-2:]
        assert "tiny-1.0/tiny/__init__.py" in tarfile.open(dist / sdist).getnames()
        after = sorted(path.relative_to(project) for path in project.rglob("*"))
        found[backend] = (before, after, Path(build_lib))
    before, after, build_lib = found["shaketable_build"]
    assert after == before
    assert not build_lib.is_relative_to(tmp_path / "shaketable_build"), build_lib
    before, after, build_lib = found["setuptools.build_meta"]   # the same checks can fail
    assert Path("tiny.egg-info") in after
    assert build_lib == tmp_path / "setuptools.build_meta" / "project" / "build" / "lib"
