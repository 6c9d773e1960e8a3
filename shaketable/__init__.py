"""shaketable: virtual shaking-table tests of free-standing rigid blocks.

Reproduces Aslam, Godden & Scalise, *Rocking and overturning response of rigid
bodies to earthquake motions* (LBL / UC Berkeley; program BLOKROC).

The names below are the package's front door; the layers behind them are
described in ``docs/architecture.md``. :func:`simulate` and :data:`METHODS`
are loaded on first use, so that ``import shaketable`` (and a reader or a
generator) does not compile or load the numba engine or SciPy's integrators.
"""

from shaketable.core.constants import FOOT, INCH, G
from shaketable.core.geometry import Block, PrestressRods
from shaketable.core.motion import Motion
from shaketable.core.results import RockingResult
from shaketable.version import __version__

__all__ = ["Block", "PrestressRods", "Motion", "RockingResult", "simulate", "METHODS", "G",
           "INCH", "FOOT", "__version__"]

_LAZY = {"simulate", "METHODS"}


def __getattr__(name):
    if name in _LAZY:
        from shaketable.solvers import api

        return getattr(api, name)
    raise AttributeError(f"module 'shaketable' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | _LAZY)
