"""``shaketable.simulate`` as a module: the first version's import path, kept.

The package's front door is the function :func:`shaketable.simulate` (from
:mod:`shaketable.models.api`); its first version also had a module of that name, so that
``import shaketable.simulate`` and ``from shaketable.simulate import simulate, METHODS``
worked. They still do. Importing this module binds the name ``shaketable.simulate`` to it
(Python's import system sets a package's attribute to each submodule it loads), so the
module is callable as the function it holds: ``shaketable.simulate(block, motion, cor=...)``
runs the same solver whether or not this module was imported.
"""

from __future__ import annotations

import sys
import types

from shaketable.models.api import simulate
from shaketable.models.rocking.layout import METHODS

__all__ = ["simulate", "METHODS"]


class _CallableModule(types.ModuleType):
    """This module, callable as :func:`shaketable.models.api.simulate`."""

    def __call__(self, *arguments, **options):
        return simulate(*arguments, **options)


sys.modules[__name__].__class__ = _CallableModule
