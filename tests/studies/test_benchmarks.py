"""Smoke tests of shaketable.studies.benchmark_cases on one small case (no timing assertions)."""

import numpy as np
import pytest

import shaketable as st
from shaketable.studies import benchmark_cases, work_precision


@pytest.fixture(scope="module")
def small():
    block = st.Block.parse("16x4ft")
    motion = benchmark_cases._harmonic(2.0, 0.3, duration=3.0)
    case = benchmark_cases.Case("small", "16 x 4 ft, 2 Hz 0.3 g, 3 s", block, motion, 0.95)
    settings = work_precision.method_settings(fast_rtols=(1e-5, 1e-7, 1e-9), subdivisions=(2, 4, 8, 16),
                                     reference_rtols=(1e-8,))
    frame = work_precision.work_precision([case], settings, repeats=1)
    return case, frame


def test_frame_structure(small):
    _, frame = small
    assert list(frame["method"].unique()) == ["fast", "predictor-corrector", "linear",
                                              "reference"]
    for column in ("case", "setting", "time [s]", "error max_theta [-]", "error events [-]",
                   "same verdict", "mean step [s]", "truth rtol"):
        assert column in frame.columns
    assert len(frame) == 3 + 4 + 1 + 1
    assert (frame["time [s]"] > 0).all()


def test_errors_decrease_as_settings_tighten(small):
    _, frame = small
    errors = frame[frame["method"] == "predictor-corrector"]["error max_theta [-]"].to_numpy()
    assert np.all(np.diff(errors) < 0) and errors[-1] < 0.1 * errors[0], errors
    # fast: its steps end on every input sample (0.01 s here), which already keeps it
    # far below its tolerance: every rtol gives errors below 1e-9
    fast = frame[frame["method"] == "fast"]
    assert (fast["error max_theta [-]"] < 1e-9).all() and (fast["error events [-]"] < 1e-9).all()


def test_predictor_corrector_order_is_two(small):
    _, frame = small
    orders = work_precision.convergence_orders(frame).set_index("method")
    # Heun's method (Section 2.8 of the report) is second order
    assert 1.7 < orders.loc["predictor-corrector", "order max_theta"] < 2.3


def test_markdown_and_figure(small, tmp_path):
    _, frame = small
    text = work_precision.results_markdown(frame=frame, orders=work_precision.convergence_orders(frame))
    assert "| case | method |" in text and "orders of convergence" in text
    from shaketable.plots.bench import save_work_precision_figure

    path = tmp_path / "wp.png"
    save_work_precision_figure(frame, path)
    assert path.stat().st_size > 1000


def test_unknown_case_is_named():
    with pytest.raises(ValueError, match="unknown benchmark case"):
        benchmark_cases.benchmark_cases(names=["no-such-case"])


def test_cli_bench_help(capsys):
    from shaketable.cli import main

    with pytest.raises(SystemExit):
        main(["bench", "--help"])
    assert "--quick" in capsys.readouterr().out
