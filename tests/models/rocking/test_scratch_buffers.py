"""``simulate`` borrows per-thread scratch arrays for the impacts: a run's
result must not depend on what an earlier run left in them, nor change after a later run.
"""

import threading

import numpy as np

from shaketable import Block, Motion, simulate


def _motion():
    t = np.linspace(0.0, 4.0, 401)
    return Motion(t, 6.0 * np.sin(9.0 * t) * np.exp(-0.3 * t), name="decaying sine")


def _fields(result):
    return (result.impact_times, result.impact_velocities, result.t, result.theta,
            result.theta_dot, result.theta_ddot)


def test_a_run_is_the_same_after_another_and_keeps_its_impacts():
    many = (Block.from_feet(4, 1), 0.5)   # 10 impacts on this motion
    few = (Block.from_feet(2, 1), 1.0)    # 8, with other times: leftovers would show
    fresh = {}

    def in_a_new_thread():  # a thread's first run: scratch arrays just made
        fresh["few"] = simulate(few[0], _motion(), cor=few[1])

    worker = threading.Thread(target=in_a_new_thread)
    worker.start()
    worker.join()
    first = simulate(many[0], _motion(), cor=many[1])
    kept = [field.copy() for field in _fields(first)]
    assert first.n_impacts > fresh["few"].n_impacts > 0
    after = simulate(few[0], _motion(), cor=few[1])
    for mine, reference in zip(_fields(after), _fields(fresh["few"])):
        assert np.array_equal(mine, reference)
    for field, copy in zip(_fields(first), kept):  # untouched by the later run
        assert np.array_equal(field, copy)
    capped = simulate(many[0], _motion(), cor=many[1], max_recorded_impacts=3)
    assert capped.n_impacts == first.n_impacts and capped.impact_times.size == 3
    assert np.array_equal(capped.impact_times, first.impact_times[:3])
