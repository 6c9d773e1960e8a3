"""The package's build backend: setuptools' own, with its scratch files outside the checkout.

setuptools builds a wheel in ``build/`` and writes ``shaketable.egg-info/`` inside the source
folder, so ``pip install /path/to/checkout`` would leave them in the checkout (and a stale
``build/lib`` can carry a module deleted since into a later wheel). Here every hook of
:mod:`setuptools.build_meta` runs with an extra distutils configuration
(``DIST_EXTRA_CONFIG``) that puts the build folder and the egg-info in a temporary folder,
removed afterwards. The wheels are the same; the sdist no longer holds an ``egg-info/``
folder (its ``PKG-INFO`` stays). Not covered: setuptools makes and removes a temporary
``shaketable-<version>/`` folder in the checkout while it writes an sdist, and a strict
editable install writes its link tree under ``build/``.
"""

from __future__ import annotations

import contextlib
import os
import tempfile

from setuptools import build_meta as _setuptools
from setuptools.build_meta import *  # noqa: F403 -- the hooks not wrapped below


@contextlib.contextmanager
def outside_the_checkout():
    """Point setuptools' build folder and egg-info at a temporary folder for the block."""
    with tempfile.TemporaryDirectory(prefix="shaketable-build-") as scratch:
        config = os.path.join(scratch, "build.cfg")
        with open(config, "w", encoding="utf-8") as file:
            file.write(f"[build]\nbuild_base = {os.path.join(scratch, 'build')}\n"
                       f"[egg_info]\negg_base = {scratch}\n")
        before = os.environ.get("DIST_EXTRA_CONFIG")
        os.environ["DIST_EXTRA_CONFIG"] = config
        try:
            yield scratch
        finally:
            if before is None:
                del os.environ["DIST_EXTRA_CONFIG"]
            else:
                os.environ["DIST_EXTRA_CONFIG"] = before


def _wrapped(hook):
    def run(*args, **kwargs):
        with outside_the_checkout():
            return hook(*args, **kwargs)

    run.__name__, run.__doc__ = hook.__name__, hook.__doc__
    return run


build_wheel = _wrapped(_setuptools.build_wheel)
build_sdist = _wrapped(_setuptools.build_sdist)
get_requires_for_build_wheel = _wrapped(_setuptools.get_requires_for_build_wheel)
get_requires_for_build_sdist = _wrapped(_setuptools.get_requires_for_build_sdist)
prepare_metadata_for_build_wheel = _wrapped(_setuptools.prepare_metadata_for_build_wheel)
if hasattr(_setuptools, "build_editable"):   # PEP 660 (setuptools >= 64)
    build_editable = _wrapped(_setuptools.build_editable)
    get_requires_for_build_editable = _wrapped(_setuptools.get_requires_for_build_editable)
    prepare_metadata_for_build_editable = _wrapped(
        _setuptools.prepare_metadata_for_build_editable)
