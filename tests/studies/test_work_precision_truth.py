"""The truth check of ``bench --quick`` and the quick case set (no SciPy run: synthetic rows)."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from shaketable.studies import benchmark_cases, planar_work_precision, work_precision


def _row(case, method, rtol, theta, events, truth_rtol=2.5e-14):
    return {"case": case, "method": method, "rtol": rtol, "error max_theta [-]": theta,
            "error events [-]": events, "truth rtol": truth_rtol}


def test_truth_check_reads_the_truths_own_error_from_the_reference_row():
    frame = pd.DataFrame([
        # the reference at 1e-12 is 3e-13 off the truth: errors from 3e-11 up are resolved
        _row("a", "reference", 1e-12, 1e-13, 3e-13),
        _row("a", "fast", 1e-6, 4e-11, 2e-11),          # one resolved, one not
        _row("a", "predictor-corrector", math.nan, 1e-5, 1e-4),
        _row("a", "planar-reference", 1e-12, 1.0, 1.0),  # another model: not the estimate
        # no reference error above the truth's rtol: the estimate is the truth's rtol
        _row("b", "reference", 1e-12, 0.0, 1e-15),
        _row("b", "fast", 1e-6, 3e-12, 0.0),
        # no reference row: nothing to estimate with, nothing resolved
        _row("c", "fast", 1e-6, 1e-3, 1e-3),
    ])
    check = work_precision.truth_check(frame, None).set_index("case")
    assert check.loc["a", "truth error estimate [-]"] == pytest.approx(3e-13)
    assert check.loc["a", "resolved below [-]"] == pytest.approx(3e-11)
    assert check.loc["a", "errors resolved"] == "3 of 4"
    assert check.loc["a", "smallest resolved [-]"] == pytest.approx(4e-11)
    assert check.loc["a", "largest unresolved [-]"] == pytest.approx(2e-11)
    assert check.loc["b", "truth error estimate [-]"] == pytest.approx(2.5e-14)
    assert check.loc["b", "errors resolved"] == "1 of 2"   # 3e-12 over 100 x 2.5e-14; 0 not
    assert math.isnan(check.loc["c", "truth error estimate [-]"])
    assert check.loc["c", "errors resolved"] == "0 of 2"


def test_truth_check_of_a_coupled_case_uses_the_planar_reference():
    planar = pd.DataFrame([
        _row("slide", "planar-reference", 1e-12, 1e-11, 2e-11, truth_rtol=1e-13),
        _row("slide", "planar-reference", 1e-6, 1e-5, 1e-5, truth_rtol=1e-13),
        _row("slide", "planar", 1e-6, 5e-9, 1e-9, truth_rtol=1e-13),
        _row("slide", "moreau-jean", math.nan, 1e-2, 1e-2, truth_rtol=1e-13),  # not checked
    ])
    check = work_precision.truth_check(planar).set_index("case")
    assert check.loc["slide", "reference rtol"] == 1e-12
    assert check.loc["slide", "truth error estimate [-]"] == pytest.approx(2e-11)
    assert check.loc["slide", "errors resolved"] == "1 of 2"


def test_quick_runs_the_reports_cases_and_still_every_method():
    quick = benchmark_cases.benchmark_cases(quick=True)
    assert [case.name for case in quick] == ["free-rocking", "harmonic-2hz-0.5g",
                                             "harmonic-2hz-vertical", "pacoima-16x4ft"]
    assert not any(case.extreme for case in quick)
    # a named extreme case is still there with quick (its long record cut to 20 s)
    (long,) = benchmark_cases.benchmark_cases(quick=True, names=["long-100s-200hz"])
    assert long.intervals == 4000
    methods = {method for method, *_ in work_precision.method_settings(quick=True)}
    assert methods == {"fast", "predictor-corrector", "linear", "reference"}
    # the coupled planar model: one case, both of its methods, the Moreau-Jean rows on it
    coupled = [case.name for case in planar_work_precision.planar_cases(quick=True)]
    assert coupled == ["slide-rock-3hz"]
    assert set(planar_work_precision.moreau_case_names(quick=True)) <= set(coupled)
    assert {method for method, *_ in planar_work_precision.method_settings(quick=True)} == {
        "planar", "planar-reference"}
    assert planar_work_precision.ROCKING_LIMIT_CASE in [case.name for case in quick]
    assert len(planar_work_precision.planar_cases(quick=True, names=["pacoima-16x4ft-mu0.3"])) == 1


def test_quick_results_carry_the_truth_check_and_the_full_ones_do_not():
    frame = pd.DataFrame([_row("a", "reference", 1e-12, 1e-13, 3e-13),
                          _row("a", "fast", 1e-6, 4e-11, 2e-11)])
    frame = frame.assign(setting="rtol=1e-06", **{"time [s]": 1e-3, "same impacts": True,
                                                   "same verdict": True})
    quick = work_precision.results_markdown(frame=frame, figure="", truth=True)
    assert "## Truth check" in quick and "| a |" in quick
    assert "Truth check" not in work_precision.results_markdown(frame=frame, figure="")
