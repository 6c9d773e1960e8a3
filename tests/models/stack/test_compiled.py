"""The compiled stack engine against the Python one (SciPy's solve_ivp), and its batch.

The compiled engine integrates the one-DOF patterns with the single block's RKN6(4) stepper
and DOP853 elsewhere; the Python engine takes SciPy's DOP853 steps throughout. Both run at
rtol 1e-12 (``simulate_stack``'s default), and they must agree to the issue's 1e-9 (issue
38's "Reference" bound: histories, event times, forces relative to the weight, the table's
work relative to the weight times the stack's height).
"""

import warnings

import numpy as np
import pytest

import shaketable as st
from shaketable.models.stack import Stack, StackTensionWarning, pattern_name, simulate_stack
from shaketable.models.stack.model import STACK_MODEL

#: Runs that together visit every pattern of two blocks (rest, the stack as one body, the
#: top alone, both the same way, both opposite ways), and a three-block run that opens two
#: interfaces at once (the runs of test_reference.py, checked there against Newton-Euler).
T2 = np.arange(0.0, 1.0, 0.02)
T3 = np.arange(0.0, 1.0, 0.01)
RUNS = [(Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)]),
         st.Motion(T2, 3.5 * np.sin(7 * T2) * np.exp(-0.5 * T2), 1.0 * np.sin(11 * T2))),
        (Stack([st.Block(0.6, 0.6), st.Block(0.9, 0.2)]), st.Motion(T2, 2.6 * np.sin(8 * T2))),
        (Stack([st.Block(0.6, 0.6), st.Block(0.9, 0.3), st.Block(0.6, 0.15)]),
         st.Motion(T3, 3.0 * np.sin(8 * T3)))]


def _both(stack, motion, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StackTensionWarning)
        return (simulate_stack(stack, motion, **options),
                simulate_stack(stack, motion, method="reference", **options))


def _difference(a, b):
    """Largest difference of the histories [rad, rad/s] and of the event times [s]; the
    event kinds and patterns must be the same."""
    assert a.status == b.status and a.t.size == b.t.size
    assert [(e["kind"], e["interface"], e["pattern_after"]) for e in a.events] == \
        [(e["kind"], e["interface"], e["pattern_after"]) for e in b.events]
    assert np.array_equal(a.patterns, b.patterns)
    times = max((abs(x["t"] - y["t"]) for x, y in zip(a.events, b.events)), default=0.0)
    return max(np.abs(a.theta - b.theta).max(), np.abs(a.theta_dot - b.theta_dot).max(),
               times)


def test_the_compiled_engine_agrees_with_the_python_engine_in_every_pattern():
    visited = set()
    for stack, motion in RUNS:
        compiled, python = _both(stack, motion)
        assert _difference(compiled, python) < 1e-9
        # the contact forces and the table's work too (relative to the weight, to the weight
        # times the stack's height)
        assert np.abs(compiled.forces - python.forces).max() < 1e-9 * stack.weight
        height = 2.0 * float(stack.h.sum())
        assert np.abs(compiled.work - python.work).max() < 1e-9 * stack.weight * height
        visited |= {pattern_name(p).split(" (")[0] for p in compiled.patterns}
        if stack.n == 3:
            assert any(sum(s != 0 for s in p) >= 2 for p in compiled.patterns)
    assert visited >= {"rest", "stack as one body", "top alone", "both, same way",
                       "both, opposite ways"}


def test_the_compiled_engine_takes_the_constant_cor_law_and_cascades_alike():
    # a decaying rigid stack (43 plastic impacts, the endless cascade summed in closed form,
    # then rest), and the constant-COR law on the same stack
    stack = Stack([st.Block(1.0, 0.6), st.Block(0.2, 0.5)])
    for options, duration in (({}, 1.9), ({"impact": "cor", "cor": 0.5}, 1.0)):
        compiled, python = _both(stack, None, theta0=[0.3, 0.3], duration=duration,
                                 output_dt=0.01, **options)
        assert _difference(compiled, python) < 1e-9
        assert len(compiled.events) >= 3
        if not options:
            assert compiled.events[-1]["kind"] == "rest"


def test_the_batch_runs_each_motion_as_one_run():
    stack, motion = RUNS[1]
    motions = [motion, motion.scaled(0.8), motion.mirrored()]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StackTensionWarning)
        batch = STACK_MODEL.run_many(stack, motions, threads=2)
        single = [simulate_stack(stack, m) for m in motions]
    for a, b in zip(batch, single):
        assert np.array_equal(a.theta, b.theta) and a.events == b.events
    with pytest.raises(ValueError, match="threads"):
        STACK_MODEL.run_many(stack, motions, threads=0)


def test_a_method_that_does_not_exist_is_refused():
    stack, motion = RUNS[1]
    with pytest.raises(ValueError, match="method"):
        simulate_stack(stack, motion, method="fast")
    with pytest.raises(ValueError, match="method"):
        st.simulate(stack, motion, method="linear")
