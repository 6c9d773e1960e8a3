"""The stack work-precision study's error measures and settings (no runs)."""

import math
from types import SimpleNamespace

import numpy as np

from shaketable.studies.stack_work_precision import (
    STACK_TRUTH_RTOL,
    compare_stack,
    method_settings,
    stack_cases,
)


def _result(peak, times, kinds=None):
    kinds = kinds or ["impact"] * len(times)
    return SimpleNamespace(theta=np.array([[0.0, -peak], [0.5 * peak, 0.0]]),
                           events=[{"t": t, "kind": k, "interface": 0}
                                   for t, k in zip(times, kinds)])


def test_the_errors_are_relative_and_part_when_the_events_do():
    truth = _result(0.2, [1.0, 2.0])
    errors = compare_stack(_result(0.202, [1.001, 2.0]), truth)
    assert math.isclose(errors["error max_theta [-]"], 0.01, rel_tol=1e-12)
    assert math.isclose(errors["error events [-]"], 1e-3, rel_tol=1e-9)
    assert compare_stack(_result(0.2, [1.0]), truth)["error events [-]"] == math.inf
    assert compare_stack(_result(0.2, [1.0, 2.0], ["impact", "uplift"]),
                         truth)["error events [-]"] == math.inf


def test_the_truth_is_tighter_than_every_setting():
    settings = method_settings() + method_settings(quick=True)
    assert {method for method, _, _ in settings} == {"stack", "stack-reference"}
    assert all(options["rtol"] > STACK_TRUTH_RTOL for _, _, options in settings)
    assert [len(case.blocks) for case in stack_cases(quick=True)] == [2, 3]
