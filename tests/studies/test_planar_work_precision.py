"""The coupled planar model in the work-precision study.

Truths: the rocking-limit rows are measured against the rocking ``reference`` at rtol
2.5e-14 (a different model and solver: the report's Eq. 2-13 by SciPy), the coupled rows
against the SciPy planar reference at rtol 1e-13 (a different formulation from the
compiled engine: Newton-Euler linear solves per mode). No timing is asserted.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaketable.core.geometry import Block
from shaketable.models.sliding.result import Friction
from shaketable.studies import benchmark_cases, planar_work_precision, work_precision


@pytest.fixture(scope="module")
def coupled():
    """The slide-rock case at two settings of each method (plus its truth)."""
    case = planar_work_precision.planar_cases(names=["slide-rock-3hz"])[0]
    settings = [("planar", "rtol=1e-12", {"rtol": 1e-12}),
                ("planar-reference", "rtol=1e-08", {"rtol": 1e-8}),
                ("planar-reference", "rtol=1e-12", {"rtol": 1e-12})]
    cache: dict = {}
    frame = planar_work_precision.planar_work_precision([case], settings, repeats=1,
                                                        cache=cache)
    return case, frame, cache[(case.name, "planar truth")]


def test_coupled_case_visits_slide_rock_and_engine_meets_1e_8(coupled):
    case, frame, truth = coupled
    # the case is what it claims: rock and slide-rock with impacts (on the truth's run)
    assert truth.time_in_mode["slide-rock"] > 0 and truth.time_in_mode["rock"] > 0
    assert len(truth.impact_times) >= 10
    engine = frame[frame["method"] == "planar"].iloc[0]
    # the compiled engine agrees with the independent reference to 1e-8
    assert engine["same events"] and engine["same verdict"]
    for column in ("error max_theta [-]", "error events [-]", "error peak slip [-]"):
        assert engine[column] < 1e-8, column
    assert engine["truth"] == "planar-reference" and engine["truth rtol"] == 1e-13


def test_reference_converges_toward_its_tight_tolerance(coupled):
    _, frame, _ = coupled
    reference = frame[frame["method"] == "planar-reference"].set_index("setting")
    # the coarse (0.05 s) samples let DOP853's tolerance set its steps: tightening rtol
    # from 1e-8 to 1e-12 brings max |theta| at least ten times closer to rtol 1e-13's
    assert (reference.loc["rtol=1e-12", "error max_theta [-]"]
            < 0.1 * reference.loc["rtol=1e-08", "error max_theta [-]"])
    assert reference["same events"].all()


def test_frame_has_the_rocking_study_columns(coupled):
    _, frame, _ = coupled
    for column in ("case", "method", "setting", "rtol", "time [s]", "error max_theta [-]",
                   "error events [-]", "same verdict", "status", "truth rtol"):
        assert column in frame.columns
    assert (frame["time [s]"] > 0).all()


def test_transitions_agree_between_the_two_result_types(coupled):
    case, _, truth = coupled
    engine = case.run("planar")
    times, modes = planar_work_precision.transitions(engine)
    truth_times, truth_modes = planar_work_precision.transitions(truth)
    np.testing.assert_array_equal(modes, truth_modes)
    np.testing.assert_allclose(times, truth_times, rtol=0, atol=1e-8)


def test_a_different_run_is_seen_as_different(coupled):
    case, _, truth = coupled
    # more friction (mu 0.5 > the critical friction of this drive): no slide-rock, so the
    # mode sequence differs from the truth's: the event error is infinite, not small
    other = planar_work_precision.run_planar("planar", case.block, case.motion, cor=case.cor,
                                             friction=Friction(0.5))
    errors = planar_work_precision.compare_planar(other, truth)
    assert not errors["same events"] and math.isinf(errors["error events [-]"])
    assert errors["error peak slip [-]"] > 0.1


def test_rocking_limit_rows_meet_check_1():
    block = Block.parse("30x6in")
    case = benchmark_cases.Case("free-short", "30 x 6 in released at 0.5 alpha, 3 s", block,
                                None, 0.925, theta0=0.5 * block.alpha, duration=3.0)
    truth = work_precision.truth_run(case, {})
    settings = [("planar", "rtol=1e-12", {"rtol": 1e-12}),
                ("planar-reference", "rtol=1e-12", {"rtol": 1e-12})]
    rows = planar_work_precision.rocking_limit_rows(case, truth, settings, repeats=1)
    assert [row["method"] for row in rows] == ["planar", "planar-reference"]
    for row in rows:
        # the rocking limit: with friction that cannot be exceeded the planar block is the
        # rocking block: impact times and max theta to 1e-9 of the rocking truth
        assert row["impacts"] == row["impacts truth"] >= 8
        assert row["error max_theta [-]"] < 1e-9 and row["error events [-]"] < 1e-9
        assert row["same verdict"]
        assert "truth" not in row  # the rocking frame's columns only


def test_moreau_jean_rows_converge_at_first_order():
    """Moreau-Jean (independent: time stepping, no modes or events) against the planar
    reference with its plastic Newton law (cor "housner") on the 3 Hz case's first 1.2 s.

    First order: a step four times smaller divides the peak-slip error by about 4
    (measured 3.95 from h = 1e-3 to 2.5e-4, 3.98 from 2.5e-4 to 6.25e-5). The bound on the
    observed order, 1 +- 0.25 (a ratio in [2.83, 5.66]), leaves room for the O(h^2)
    remainder at h = 1e-3 and fails a zeroth- or second-order scheme (ratio 1 or 16).
    Max |theta| is the largest of the sampled steps: its O(h) error changes sign between
    impacts (measured ratio 1.96), so it is only asserted to fall and stay below 1 %.
    """
    case = planar_work_precision.planar_cases(names=["slide-rock-3hz"])[0]
    rows = planar_work_precision.moreau_jean_rows(case, (1e-3, 2.5e-4))
    coarse, fine = rows
    assert coarse["steps"] == 1200 and fine["steps"] == 4800
    assert coarse["truth"] == "planar-reference cor=housner"
    assert coarse["same verdict"] and fine["same verdict"]
    ratio = coarse["error peak slip [-]"] / fine["error peak slip [-]"]
    assert 4.0 ** 0.75 < ratio < 4.0 ** 1.25, ratio
    assert fine["error max_theta [-]"] < coarse["error max_theta [-]"] < 0.01
    assert math.isnan(coarse["error events [-]"])  # neither overturns: no event error


def test_unknown_planar_case_is_named():
    with pytest.raises(ValueError, match="no-such"):
        planar_work_precision.planar_cases(names=["no-such"])
    with pytest.raises(ValueError, match="method"):
        planar_work_precision.run_planar("fast", Block.parse("30x6in"), None, cor=0.9,
                                         friction=Friction(0.3), duration=1.0)
    assert set(planar_work_precision.planar_case_names()) == {
        case.name for case in planar_work_precision.planar_cases()}


def test_bench_draws_the_coupled_panel(tmp_path):
    """``run_study`` with only a coupled case: its CSV, a figure with its panel, RESULTS.md."""
    import pandas as pd

    from shaketable.bench import run_study

    written = run_study(cases=["slide-rock-3hz"], quick=True, repeats=1, out=tmp_path,
                        progress=lambda message: None, speed=False)
    names = [path.name for path in written]
    assert names == ["work_precision.csv", "planar_work_precision.csv", "work_precision.png",
                     "RESULTS.md"]
    frame = pd.read_csv(tmp_path / "planar_work_precision.csv")
    assert set(frame["method"]) == {"planar", "planar-reference", "moreau-jean"}
    # the Moreau-Jean rows come after the others, one per quick step, with their own truth
    moreau = frame[frame["method"] == "moreau-jean"]
    assert list(moreau["setting"]) == [f"h={step:g}" for step in
                                       planar_work_precision.QUICK_MOREAU_STEPS]
    assert moreau.index.min() > frame[frame["method"] != "moreau-jean"].index.max()
    assert (moreau["truth"] == "planar-reference cor=housner").all()
    assert "slide-rock-3hz" in (tmp_path / "RESULTS.md").read_text()


def test_bench_unknown_name_lists_the_planar_cases(tmp_path):
    from shaketable.bench import run_study

    with pytest.raises(ValueError, match="slide-rock-3hz"):
        run_study(cases=["nothing"], quick=True, out=tmp_path, speed=False)


def test_figure_has_a_panel_per_case_and_the_planar_lines(coupled):
    import pandas as pd

    from shaketable.plots.base import pyplot
    from shaketable.plots.bench import STYLE, work_precision_figure

    _, frame, _ = coupled
    rocking = pd.DataFrame([{"case": "free-rocking", "method": "fast", "setting": "rtol=1e-08",
                             "time [s]": 1e-3, "error max_theta [-]": 1e-12,
                             "error events [-]": 1e-11},
                            {"case": "free-rocking", "method": "planar",
                             "setting": "rtol=1e-08", "time [s]": 2e-2,
                             "error max_theta [-]": 1e-13, "error events [-]": 1e-13}])
    fig = work_precision_figure(rocking, planar=frame)
    try:
        visible = [ax for ax in fig.axes if ax.get_visible()]
        assert len(visible) == 2
        assert visible[0].get_title() == "free-rocking\n(planar: μs = μd = 10)"
        assert visible[1].get_title().startswith("slide-rock-3hz\n(vs planar-reference")
        # the coupled panel: per method, max |theta|, event and peak-slip lines with the
        # frame's numbers (floored at 1e-16)
        colours = {line.get_color() for line in visible[1].get_lines()}
        assert {STYLE["planar"][0], STYLE["planar-reference"][0]} <= colours
        slip = [line for line in visible[1].get_lines() if line.get_linestyle() == "-."
                and line.get_color() == STYLE["planar-reference"][0]]
        assert len(slip) == 1
        expected = frame[frame["method"] == "planar-reference"].sort_values("time [s]")
        np.testing.assert_allclose(slip[0].get_ydata(),
                                   np.maximum(expected["error peak slip [-]"], 1e-16))
    finally:
        pyplot().close(fig)


def test_cli_bench_offers_no_planar(capsys):
    from shaketable.cli import main

    with pytest.raises(SystemExit):
        main(["bench", "--help"])
    assert "--no-planar" in capsys.readouterr().out


def test_bench_refuses_a_planar_case_without_the_planar_model(tmp_path):
    from shaketable.bench import run_study

    with pytest.raises(ValueError, match="no-planar"):
        run_study(cases=["slide-rock-3hz"], out=tmp_path, speed=False, planar=False)
