"""The old import paths of the modules that moved into :mod:`shaketable.models`.

The rocking, planar and sliding models each live in one folder of
:mod:`shaketable.models` now (their physics, engine, reference, batch and result). Their
old paths under :mod:`shaketable.core` and :mod:`shaketable.solvers` keep working: importing
one gives the module at its new path (the same object, so ``isinstance`` and monkeypatching
see one class and one namespace) with a :class:`DeprecationWarning` naming that path, once
per process. :func:`install` puts the finder that does it on :data:`sys.meta_path`;
``shaketable.core`` and ``shaketable.solvers`` call it when they are imported.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
import warnings

#: Old module path -> new module path.
MOVED = {
    "shaketable.solvers.api": "shaketable.models.api",
    "shaketable.core.stops": "shaketable.models.stops",
    "shaketable.core.dynamics": "shaketable.models.rocking.physics",
    "shaketable.core.results": "shaketable.models.rocking.result",
    "shaketable.core.asymmetric_result": "shaketable.models.rocking.asymmetric_result",
    "shaketable.solvers.layout": "shaketable.models.rocking.layout",
    "shaketable.solvers.steppers": "shaketable.models.rocking.steppers",
    "shaketable.solvers.engine": "shaketable.models.rocking.engine",
    "shaketable.solvers.common": "shaketable.models.rocking.run",
    "shaketable.solvers.reference": "shaketable.models.rocking.reference",
    "shaketable.solvers.batch": "shaketable.models.rocking.batch",
    "shaketable.solvers.impulses": "shaketable.models.rocking.impulses",
    "shaketable.solvers.asymmetric": "shaketable.models.rocking.asymmetric",
    "shaketable.core.planar_dynamics": "shaketable.models.planar.physics",
    "shaketable.core.planar_result": "shaketable.models.planar.result",
    "shaketable.core.planar_reference_result": "shaketable.models.planar.reference_result",
    "shaketable.core.shenton": "shaketable.models.planar.shenton",
    "shaketable.solvers.planar": "shaketable.models.planar.engine",
    "shaketable.solvers.planar_steps": "shaketable.models.planar.steps",
    "shaketable.solvers.planar_modes": "shaketable.models.planar.modes",
    "shaketable.solvers.planar_track": "shaketable.models.planar.track",
    "shaketable.solvers.planar_run": "shaketable.models.planar.run",
    "shaketable.solvers.planar_batch": "shaketable.models.planar.batch",
    "shaketable.solvers.planar_contact": "shaketable.models.planar.contact",
    "shaketable.solvers.planar_reference": "shaketable.models.planar.reference",
    "shaketable.solvers.planar_moreau": "shaketable.models.planar.moreau",
    "shaketable.solvers.sliding": "shaketable.models.sliding.engine",
    "shaketable.core.sliding_result": "shaketable.models.sliding.result",
}


#: The modules whose frames stand between an old import and the warning.
_PASSED_OVER = {__name__, "importlib", "shaketable.core", "shaketable.solvers"}


def moved_warning(old: str) -> None:
    """Warn that the module ``old`` moved, pointing at the line that imported it."""
    # warnings.warn counts the frames outside the import system's own (``_bootstrap``);
    # the frames of this module, importlib.import_module and the packages' __getattr__
    # are passed over too
    level = 1
    frame: types.FrameType | None = sys._getframe(1)
    while frame is not None:
        name = frame.f_code.co_filename
        if not ("importlib" in name and "_bootstrap" in name):
            level += 1
            if frame.f_globals.get("__name__") not in _PASSED_OVER:
                break
        frame = frame.f_back
    warnings.warn(f"{old} has moved to {MOVED[old]}; import it from there (the old path "
                  "will be removed)", DeprecationWarning, stacklevel=level)


class MovedFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds the old path of a moved module and loads it as the module at its new path."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname not in MOVED:
            return None
        return importlib.machinery.ModuleSpec(fullname, self)

    def create_module(self, spec):
        return None   # a placeholder, replaced in sys.modules by exec_module

    def exec_module(self, module) -> None:
        old = module.__spec__.name
        moved_warning(old)
        # the import system returns what sys.modules holds under the old name after this
        sys.modules[old] = importlib.import_module(MOVED[old])


def install() -> None:
    """Put :class:`MovedFinder` on :data:`sys.meta_path` (once)."""
    if not any(isinstance(finder, MovedFinder) for finder in sys.meta_path):
        sys.meta_path.insert(0, MovedFinder())


def moved_attribute(package: str, name: str):
    """``package.name`` for a moved module that was not imported yet (a package's
    ``__getattr__``); AttributeError for any other name."""
    old = f"{package}.{name}"
    if old not in MOVED:
        raise AttributeError(f"module {package!r} has no attribute {name!r}")
    return importlib.import_module(old)
