"""The old import paths of the moved model modules keep working, deprecated.

Every old path of :data:`shaketable._moved.MOVED` imports as the very module at its new
path (one object: one class, one namespace to monkeypatch), with a DeprecationWarning that
names the new path; the warning comes once, as the module is then held under its old name
too. A pickle written before the move (class paths under ``shaketable.core``) loads.
"""

from __future__ import annotations

import importlib
import pickle
import sys
import warnings

import pytest

import shaketable.core
import shaketable.solvers
from shaketable._moved import MOVED


@pytest.mark.parametrize("old", sorted(MOVED))
def test_an_old_path_imports_the_new_module_with_a_warning_naming_it(old, monkeypatch):
    new = importlib.import_module(MOVED[old])
    monkeypatch.delitem(sys.modules, old, raising=False)
    with pytest.warns(DeprecationWarning, match=rf"{old} has moved to {MOVED[old]};") as caught:
        module = importlib.import_module(old)
    assert module is new
    assert len(caught) == 1
    # this test's own line, not the import system's, is what the warning points at
    assert caught[0].filename == __file__
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert importlib.import_module(old) is new     # once: no second warning


def test_from_imports_of_the_old_paths_give_the_new_objects():
    from shaketable.models.planar import engine
    from shaketable.models.sliding.result import Friction as NewFriction

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from shaketable.core.sliding_result import Friction

        from shaketable.solvers import planar
    assert Friction is NewFriction
    assert planar is engine


def test_a_moved_module_is_an_attribute_of_its_old_package():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        assert shaketable.solvers.batch is importlib.import_module("shaketable.models.rocking.batch")
        assert shaketable.core.dynamics is importlib.import_module("shaketable.models.rocking.physics")
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        shaketable.solvers.nothing  # noqa: B018


def test_a_pickle_written_under_the_old_path_loads():
    from shaketable.models.sliding.result import Friction

    friction = Friction(0.3)
    data = pickle.dumps(friction, protocol=0)
    assert b"shaketable.models.sliding.result" in data
    old = data.replace(b"shaketable.models.sliding.result", b"shaketable.core.sliding_result")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        assert pickle.loads(old) == friction
