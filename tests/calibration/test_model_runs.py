"""The fit's model reuses an engine run it already made, and only that.

A finite-difference column in the release time, the offset or the filter's u asks
:class:`shaketable.calibration.model.FreeRockingModel` again for the run it has just made
(on the fine grid the run depends on cor, theta0 and the grid's length only): the model
keeps its last runs by their inputs. Reused, a run must be the very array a new model
computes (the engine is deterministic), unchanged by what the caller does with the copy it
got, and ``evaluations`` (the ``engine_runs`` of the fit's diagnostics) counts real runs.
"""

from __future__ import annotations

import numpy as np

import shaketable as st
from shaketable.calibration.free_rocking import virtual_free_rocking_record
from shaketable.calibration.model import FreeRockingModel

BLOCK = st.Block.parse("30x6in")    # the report's test block (Sections 3.2, 3.5)


def _model(record, mode="fit"):
    return FreeRockingModel(record, BLOCK, mode, None, 4, 1e-9)


def test_a_repeated_run_is_reused_bit_for_bit_and_not_counted_twice():
    record, _ = virtual_free_rocking_record(BLOCK, 0.9, 0.5 * BLOCK.alpha, seed=3, before=0.5,
                                            duration=3.0)
    x = np.array([0.9, 0.5 * BLOCK.alpha, 0.5, 0.0, 1e-5])
    model = _model(record)
    first = model(x)
    assert model.evaluations == 1
    # offset, release time and filter moved, cor and theta0 kept: the same engine run
    for index, step in ((3, 1e-4), (2, 1e-7), (4, 1e-9)):
        moved = x.copy()
        moved[index] += step
        assert np.array_equal(model(moved), _model(record)(moved))
    assert model.evaluations == 1
    assert np.array_equal(model(x), first) and model.evaluations == 1
    # the caller's copy changed (as __call__ changes its first sample) leaves the kept run
    grid = model.fine_dt * np.arange(50)
    mine = model.theta(x[0], x[1], 0.0, grid)
    assert model.evaluations == 2
    mine[:] = np.nan
    again = model.theta(x[0], x[1], 0.0, grid)
    assert model.evaluations == 2
    assert np.array_equal(again, _model(record).theta(x[0], x[1], 0.0, grid))
    # the COR or theta0 moved: a new run, counted
    for index in (0, 1):
        moved = x.copy()
        moved[index] *= 1 + 1e-6
        assert np.array_equal(model(moved), _model(record)(moved))
    assert model.evaluations == 4


def test_the_unfiltered_model_reuses_only_an_identical_run():
    record, _ = virtual_free_rocking_record(BLOCK, 0.9, 0.5 * BLOCK.alpha, seed=4, before=0.5,
                                            duration=3.0)
    x = np.array([0.9, 0.5 * BLOCK.alpha, 0.5, 0.0])
    model = _model(record, "none")
    model(x)
    offset = x.copy()
    offset[3] += 1e-4
    assert np.array_equal(model(offset), _model(record, "none")(offset))
    assert model.evaluations == 1
    release = x.copy()
    release[2] += 1e-7     # the record's samples on the run's grid move: a new run
    assert np.array_equal(model(release), _model(record, "none")(release))
    assert model.evaluations == 2
