"""The compiled engines' cache does not depend on where the package is installed.

The README's two set-up commands install the same sources twice (``pip install .``, then
``pip install -e ".[test]"``): the second install must load what the first compiled. numba
names a module's cache folder after the folder's absolute path; the package's locator
(``core/numba_cache.py``) names it after the folder's path inside the package.
"""

from __future__ import annotations

import hashlib
import importlib
import os
import shutil
import subprocess
import sys

import shaketable
from shaketable.core import numba_cache

PACKAGE = os.path.dirname(os.path.abspath(shaketable.__file__))

#: The modules that define cached compiled functions.
COMPILED_MODULES = ["shaketable.models.rocking.physics", "shaketable.models.planar.physics",
                    "shaketable.models.rocking.engine", "shaketable.models.rocking.batch",
                    "shaketable.models.planar.engine", "shaketable.models.planar.modes",
                    "shaketable.models.planar.track", "shaketable.models.planar.phases",
                    "shaketable.models.sliding.engine"]


def test_the_cache_subfolder_is_named_from_the_path_inside_the_package():
    expected = "rocking_" + hashlib.sha1(b"shaketable/models/rocking").hexdigest()
    assert numba_cache.cache_subpath(os.path.join(PACKAGE, "models", "rocking")) == expected
    assert numba_cache.cache_subpath(os.path.join(PACKAGE, "core")) == (
        "core_" + hashlib.sha1(b"shaketable/core").hexdigest())


def test_every_cached_function_of_the_package_uses_the_package_locator():
    import numba.core.registry

    seen = 0
    for name in COMPILED_MODULES:
        module = importlib.import_module(name)
        folder = os.path.dirname(os.path.abspath(module.__file__))
        for value in vars(module).values():
            if isinstance(value, numba.core.registry.CPUDispatcher) and value._cache is not None \
                    and value.__module__ == name and hasattr(value._cache, "_impl"):
                locator = value._cache._impl.locator
                assert type(locator).__name__ == "PackageCacheLocator", (name, value)
                assert locator.get_cache_path() == os.path.join(
                    os.environ["NUMBA_CACHE_DIR"], numba_cache.cache_subpath(folder))
                seen += 1
    assert seen >= 8


_PROBE = (
    "import os, numpy as np, shaketable\n"
    "from shaketable.models.rocking import physics as dynamics\n"
    "assert os.path.dirname(shaketable.__file__).startswith(os.getcwd()), shaketable.__file__\n"
    "moment = dynamics.cascade_rest_time(1.0, 2.0, 0.5)\n"
    "stats = dynamics.cascade_rest_time.stats\n"
    "print(os.environ['NUMBA_CACHE_DIR'], sum(stats.cache_hits.values()),\n"
    "      sum(stats.cache_misses.values()), moment)\n"
)


def test_two_copies_of_the_sources_at_different_paths_share_one_compile(tmp_path):
    """The same sources at two paths (a wheel's site-packages, an editable checkout): the
    first process compiles, the second loads the first's machine code (numba's hit counter),
    from the same default cache folder (keyed by the sources, not the path)."""
    environment = {key: value for key, value in os.environ.items()
                   if key not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    environment["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    lines = []
    for install in ("site-packages", "checkout"):
        root = tmp_path / install
        shutil.copytree(PACKAGE, root / "shaketable", symlinks=True,
                        ignore=shutil.ignore_patterns("__pycache__", "data", "*.pyc"))
        done = subprocess.run([sys.executable, "-c", _PROBE], cwd=root, env=environment,
                              capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr
        lines.append(done.stdout.split())
    (first_folder, first_hits, first_misses, _), (second_folder, hits, misses, _) = lines
    assert first_folder == second_folder
    assert first_folder.startswith(str(tmp_path / "cache" / "shaketable" / "numba"))
    assert (first_hits, first_misses) == ("0", "1")   # compiled in the first copy
    assert (hits, misses) == ("1", "0")               # loaded in the second


def test_the_cache_folders_key_covers_every_folder_numba_compiles():
    """numba checks a cached function against its own file only, so the default cache
    folder is keyed by the sources of every package folder whose modules numba compiles
    (``shaketable/__init__.py``): a folder missing there (the shared numerics, inlined
    into the planar and stack engines) would let an upgrade that changes only it run the
    stale machine code."""
    from pathlib import Path

    import shaketable

    package = Path(shaketable.__file__).parent
    compiling = {path.relative_to(package).parts[0] for path in package.rglob("*.py")
                 if "import numba" in path.read_text(encoding="utf-8")
                 or "from numba" in path.read_text(encoding="utf-8")}
    assert compiling and compiling <= set(shaketable._COMPILED_LAYERS), compiling
