"""shaketable: virtual shaking-table tests of free-standing rigid blocks.

Example: does a 30 x 6 in block overturn under Pacoima Dam S16E, at 0.3 and 0.5 of it?

>>> import shaketable as st
>>> from shaketable.ground import records
>>> block = st.Block.parse("30x6in")               # height x width, with its unit
>>> motion = records.load("pacoima-dam-s16e")      # a bundled record (`shaketable records`)
>>> st.simulate(block, motion.scaled(0.3), cor=0.9).verdict()   # peak rotation / alpha
'max θ/α = 0.20'
>>> st.simulate(block, motion.scaled(0.5), cor=0.9).verdict()
'overturned (−) at 4.16 s'

A run's ``plot()`` draws the report's Calcomp figure, ``to_frame()`` its time
history; ``st.simulate(..., friction=st.Friction(0.3))`` lets the base slide too. From
a shell: ``shaketable simulate --block 30x6in --record pacoima-dam-s16e --scale 0.3
--cor 0.9``.

Reproduces Aslam, Godden & Scalise, *Rocking and overturning response of rigid
bodies to earthquake motions* (LBL / UC Berkeley; program BLOKROC).

The names below are the package's front door; the layers behind them are
described in ``docs/architecture.md``. :func:`simulate` and :data:`METHODS`
are loaded on first use, so that ``import shaketable`` (and a reader or a
generator) does not compile or load the numba engine or SciPy's integrators.
"""

import os as _os

# numba's on-disk cache of the compiled engine goes to the user's cache folder, not
# next to the modules: a cache written inside site-packages outlives `pip uninstall`
# and its leftover folder then shadows a later editable install. Set
# NUMBA_CACHE_DIR yourself to put it elsewhere. The default folder is keyed by the compiled
# modules' source (below), so that an edit of an inlined helper cannot leave stale code.


#: The package folders whose modules numba compiles (the engines and the numerics they share).
_COMPILED_LAYERS = ("core", "models", "numerics")


def _compiled_sources_fingerprint() -> str:
    """A short hash of the source of every module numba compiles (:data:`_COMPILED_LAYERS`).

    numba's cache checks only the file that defines a cached function, not the helpers it
    inlines from other files (``models/rocking/steppers.py`` into ``models/rocking/engine.py``,
    ``models/planar/modes.py`` into ``models/planar/engine.py``): after an edit or an upgrade
    that changes only a helper's file, the stale machine code would still run. One cache
    folder per version of these sources makes such a change compile afresh (about 1 ms
    to hash the files at import).
    """
    import hashlib

    digest = hashlib.sha256()
    here = _os.path.dirname(_os.path.abspath(__file__))
    try:
        for layer in _COMPILED_LAYERS:
            for folder, folders, names in sorted(_os.walk(_os.path.join(here, layer))):
                folders.sort()
                for name in sorted(names):
                    if name.endswith(".py"):
                        digest.update(_os.path.relpath(_os.path.join(folder, name), here).encode())
                        with open(_os.path.join(folder, name), "rb") as source:
                            digest.update(source.read())
    except OSError:   # sources not readable as files (a zipped or frozen install)
        from shaketable.version import __version__

        return "version-" + __version__
    return digest.hexdigest()[:16]


if "NUMBA_CACHE_DIR" not in _os.environ:
    _os.environ["NUMBA_CACHE_DIR"] = _os.path.join(
        _os.environ.get("XDG_CACHE_HOME") or _os.path.join(_os.path.expanduser("~"), ".cache"),
        "shaketable", "numba", _compiled_sources_fingerprint())

# While numba types the engine it tries many overloads for every operation and formats
# the message of each one it rejects, in bold through colorama, although it shows none of
# them unless the compile fails. Plain messages make the engine's first compile
# shorter; numba's error messages lose only their bold. Set
# the variable to an empty string to keep it. (Read when numba is imported: no effect if
# numba was imported first.)
_os.environ.setdefault("NUMBA_DISABLE_ERROR_MESSAGE_HIGHLIGHTING", "1")


def _numba_sees_the_cache_folder() -> None:
    """numba reads ``NUMBA_CACHE_DIR`` when it is imported: if it was imported before us (a
    notebook that used numba first), have it read the environment again now, before the
    engine's cached functions are defined, or it would compile into the package's
    ``__pycache__``. numba itself is not imported here (only ``models`` imports it)."""
    import sys

    config = sys.modules.get("numba.core.config")
    if config is not None and hasattr(config, "reload_config"):
        config.reload_config()


_numba_sees_the_cache_folder()

from shaketable.core.constants import FOOT, INCH, G  # noqa: E402
from shaketable.core.geometry import AsymmetricBlock, Block, PrestressRods  # noqa: E402
from shaketable.core.motion import Motion  # noqa: E402
from shaketable.models.planar.result import PlanarResult  # noqa: E402
from shaketable.models.rocking.result import RockingResult  # noqa: E402
from shaketable.models.sliding.result import Friction  # noqa: E402
from shaketable.version import __version__  # noqa: E402

__all__ = ["Block", "AsymmetricBlock", "PrestressRods", "Motion", "RockingResult", "Friction",
           "PlanarResult", "simulate", "METHODS", "assess", "G", "INCH", "FOOT", "__version__"]

#: The names loaded on first use, and the module each comes from.
_LAZY = {"simulate": "shaketable.models.api", "METHODS": "shaketable.models.rocking.layout",
         "assess": "shaketable.assessment"}


def __getattr__(name):
    if name in _LAZY:
        from importlib import import_module

        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'shaketable' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
