"""The first line of a command is the answer its user came for (free rocking: when the
block came to rest; a scene: its agreement with the report; bench: the numbers)."""

from __future__ import annotations

import json

import pytest

from shaketable.cli import main

#: Section 3.7 (1), Fig. 3.4: the 30 x 6 in block, COR 0.925, "came to rest in
#: approximately 6 seconds, after about 10 vibrations". The report states no tolerance for
#: these; its "approximately" and "about" are taken as 10 % (its stated agreement where
#: it gives none, STYLE #9).
FIG_3_4_REST, FIG_3_4_CYCLES, ABOUT = 6.0, 10.0, 0.10


def _visible_impacts_closed_form(height, width, cor, release_ratio, fraction=0.03):
    """Impacts after a swing above ``fraction`` of the release: free rocking conserves
    energy between impacts and an impact scales it by cor^2 (Eq. 2-6), so each swing's
    amplitude follows cos(alpha - a') = cos(alpha) - cor^2 (cos(alpha) - cos(alpha - a))."""
    import math

    alpha = math.atan(width / height)
    release = amplitude = release_ratio * alpha
    count = 0
    while amplitude > fraction * release:
        count += 1
        value = math.cos(alpha) - cor**2 * (math.cos(alpha) - math.cos(alpha - amplitude))
        amplitude = alpha - math.acos(value)
    return count


@pytest.mark.usefixtures("figure_drafts")
def test_free_rocking_leads_with_the_rest_time(tmp_path, capsys):
    import re

    # Fig. 3.4's specimen, 30 x 6 in, COR 0.925, released at 0.5 alpha on a still table
    out = tmp_path / "fig-3-4"
    assert main(["simulate", "--block", "30x6in", "--cor", "0.925", "--theta0", "0.5alpha",
                 "--duration", "8s", "--out", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    # the rest time and the cycles a reader counts, both in the first line
    said = re.fullmatch(r"30 x 6 in block, COR 0\.925: came to rest at t = (\d+\.\d\d) s "
                        r"after (\d+\.?\d*) cycles: (\d+) impacts of swings over 3 % of the "
                        r"release, then ever smaller ones accumulating there \(released at "
                        r"θ/α = 0\.50\)", lines[0])
    assert said, lines[0]
    rest, visible = float(said[1]), int(said[3])
    assert float(said[2]) == visible / 2
    assert abs(rest - FIG_3_4_REST) <= ABOUT * FIG_3_4_REST
    # the impacts a reader counts on the figure: the closed form's, about 10 cycles
    assert visible == _visible_impacts_closed_form(30, 6, 0.925, 0.5) == 21
    assert abs(visible / 2 - FIG_3_4_CYCLES) <= ABOUT * FIG_3_4_CYCLES
    assert lines[1] == f"  came to rest at t = {rest:.2f} s"
    summary = json.loads((out / "summary.json").read_text())
    assert f"{summary['t_rest [s]']:.2f}" == said[1]   # the file says the same
    assert lines[2] == (f"  21 impacts of swings over 3 % of the release (10.5 cycles), then "
                        f"{summary['n_impacts'] - 21} smaller ones accumulating at "
                        f"t = {rest:.2f} s ({summary['n_impacts']} impacts computed one by "
                        f"one, then 1 summed cascade)")
    assert lines[3] == "  max θ/α 0.5 at the release (t = 0.00 s); did not overturn"


@pytest.mark.usefixtures("figure_drafts")
def test_free_rocking_cut_short_says_it_still_rocks(tmp_path, capsys):
    # the same release cut at 2 s: Housner's first impact alone comes at
    # arccosh(1 / (1 - 0.5)) / p = 0.30 s, and the block rocks until about 6 s
    assert main(["simulate", "--block", "30x6in", "--cor", "0.925", "--theta0", "0.5alpha",
                 "--duration", "2s", "--out", str(tmp_path / "short")]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("30 x 6 in block, COR 0.925: still rocking at the end "
                            "(t = 2.00 s) after ")
    swing = first.split("last swing θ/α = ")[1].split(":")[0]
    assert len(swing.split(".")[1]) == 2       # two decimals, as the release is said
    assert 0.0 < float(swing) < 0.5        # each impact takes energy: below the release
    assert first.endswith("(released at θ/α = 0.50)")


@pytest.mark.usefixtures("figure_drafts")
def test_a_table_motion_keeps_its_verdict_first(tmp_path, capsys):
    # Section 4: the 16 x 4 ft block under Pacoima Dam S16E overturns (Fig. 4.1)
    assert main(["simulate", "--block", "16x4ft", "--cor", "0.95", "--record",
                 "pacoima-dam-s16e", "--out", str(tmp_path / "p")]) == 0
    assert capsys.readouterr().out.splitlines()[0].startswith(
        "16 x 4 ft block, COR 0.95: overturned (")


@pytest.mark.usefixtures("figure_drafts")
def test_a_study_leads_with_its_comparison_with_the_report(tmp_path, capsys):
    # Section 4.3 (4): the report's 4.6 g for a 0.1 s pulse, Eq. (2-9), one comparison
    out = tmp_path / "s"
    assert main(["run", "section-4-3-4", "--out", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == (f"section-4-3-4: against the report's own inputs 1 agrees, 0 differ "
                        f"(see {out / 'report.md'})")
    assert lines[1].startswith("section-4-3-4: Section 4.3 (4): ")   # the description after
    assert lines[-1].startswith("wrote ")


def test_the_stacks_study_says_its_conclusions():
    # tables shaped as the stacks study writes them: a 2 x 0.5 m block that stands alone
    # and falls two high; thresholds against the closed form (Eq. 2-1 for the block alone)
    import pandas as pd

    from shaketable.studies.stacks import stacks_answer

    records = pd.DataFrame({"record": ["r", "r"], "block": ["2 x 0.5 m"] * 2,
                            "blocks high": [1, 2], "verdict": ["0.4", "F"],
                            "t_overturn [s]": [float("nan"), 3.456],
                            "overturned block": [0, 1], "max theta/alpha": ["0.4", "0.9, F"]})
    uplift = pd.DataFrame({"pattern entered": ["a", "b"], "pattern of the closed form": ["a", "a"],
                           "relative difference [-]": [1e-12, -3e-12],
                           "computed [g]": [0.125, 0.3],
                           "bottom block alone tan(alpha1) [g]": [0.25, 0.25]})
    pulses = pd.DataFrame({"omega/p [-]": [3.0, 3.0], "blocks high": [1, 2],
                           "minimum [g]": [0.5621, 0.3579]})
    assert stacks_answer(records, uplift, pulses) == [
        "2 x 0.5 m block under r: alone stands (max θ/α 0.4); two high overturns at 3.46 s "
        "(block 1)",
        "uplift thresholds agree with the closed form g min(A1, A2) in 1 of 2 stacks "
        "(largest relative difference 3.0e-12); stacking lowers the threshold in 1 of 2 "
        "(0.125-0.3 g against tan α1 = 0.25 g alone)",
        "smallest half-sine pulse that overturns it at ω/p = 3: 0.562 g alone, 0.358 g two "
        "high"]


def test_bench_says_its_numbers():
    # a measurement shaped as pacoima_timing and accuracy_table give it: 0.25 ms against
    # 0.125 s is 500 times; the largest errors are the largest of the cases
    import pandas as pd

    from shaketable.commands.bench import bench_answer

    pacoima = {"fast median [ms]": 0.25, "reference median [s]": 0.125, "speed-up [-]": 500.0,
               "same as reference": {"same verdict": True, "same impacts": True,
                                     "impacts": 27, "impacts truth": 27}}
    accuracy = pd.DataFrame({"error max_theta [-]": [1e-15, 3e-12],
                             "error events [-]": [2e-13, 1e-14], "meets 1e-8": [True, True]})
    assert bench_answer(pacoima, accuracy) == [
        "speed (Pacoima Dam S16E + vertical, 16 x 4 ft, COR 0.95): fast 0.25 ms per run, 500x "
        "the reference (0.125 s); same verdict and impacts (27)",
        "accuracy (fast against the reference at their defaults, 2 cases): largest relative "
        "error of max |θ| 3e-12, of the event times 2e-13; 2 of 2 within 1e-8 (details in "
        "RESULTS.md)"]
    assert bench_answer(None, None) == []          # --no-speed and no case: nothing measured
    # a table without one of the error columns says the other alone
    assert bench_answer(None, accuracy.drop(columns="error events [-]")) == [
        "accuracy (fast against the reference at their defaults, 2 cases): largest relative "
        "error of max |θ| 3e-12; 2 of 2 within 1e-8 (details in RESULTS.md)"]


def test_one_length_unit_per_output():
    from shaketable.core.units import shared_length_unit

    # a 16 x 4 ft block: a 1.79 in slip (under a foot) puts the 2.53 ft excursion in
    # inches too; without a slip the excursion keeps the block's feet
    inch, foot = 0.0254, 0.3048
    assert shared_length_unit((1.79 * inch, 2.53 * foot), "ft") == "in"
    assert shared_length_unit((0.0, 2.53 * foot), "ft") == "ft"
    assert shared_length_unit((float("nan"),), "m") == "m"
    assert shared_length_unit((0.004, 2.47), "m") == "mm"


def test_planar_run_says_its_lengths_in_one_unit_and_one_rounding():
    # the 16 x 4 ft block of Section 4 on friction 0.3/0.25 under Pacoima Dam S16E
    import shaketable as st
    from shaketable.commands.answers import planar_answer
    from shaketable.ground import records
    from shaketable.plots.planar import planar_caption

    result = st.simulate(st.Block.parse("16x4ft"), records.load("pacoima-dam-s16e"),
                         cor=0.95, friction=st.Friction(0.3, 0.25))
    inch = 0.0254
    slip, excursion = result.peak_base_slip / inch, result.peak_excursion / inch
    assert slip < 12.0 < excursion          # under a foot and over one: inches for both
    answer = planar_answer(result)
    assert answer[1].startswith(f"peak slip of the base {slip:#.3g} in at t = ")
    assert answer[2] == f"corner excursion (the clearance it needs) {excursion:#.3g} in"
    # the caption: the same slip (the base's, not the midpoint's), one rounding, one unit
    caption = planar_caption(result)[-1]
    assert caption.endswith(f"peak slip {slip:#.3g} in, corner excursion {excursion:#.3g} in")


@pytest.mark.usefixtures("figure_drafts")
def test_spectrum_names_the_block_by_the_users_alpha_and_p(tmp_path, capsys):
    # Eq. (2-13): p^2 = 3 g / (4 R), so p = 2 rad/s gives R = 3 g / 16 = 1.8387 m, and
    # H = 2 R cos(0.1) = 144.1 in, B = 2 R sin(0.1) = 14.45 in
    import math

    radius = 3 * 9.80665 / 16
    height, width = 2 * radius * math.cos(0.1) / 0.0254, 2 * radius * math.sin(0.1) / 0.0254
    assert main(["spectrum", "--alpha", "0.1rad", "--p", "2rad/s", "--pulse", "one-sine",
                 "--ratios", "4", "--method", "linear", "--ceiling", "2",
                 "--out", str(tmp_path / "s")]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith(f"block of alpha 0.1 rad, p 2 rad/s (H x B = {height:.4g} x "
                            f"{width:.4g} in), COR ")
    assert f"{height:.4g} x {width:.4g}" == "144.1 x 14.45"


@pytest.mark.usefixtures("figure_drafts")
def test_a_free_rocking_scene_leads_with_the_rest_time(tmp_path, capsys):
    # Fig. 3.4's scene: Section 3.7 (1), "came to rest in approximately 6 seconds"
    out = tmp_path / "fig-3-4"
    assert main(["run", "fig-3-4", "--out", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    first = lines[0]
    # Section 3.7 (2): test and theory overturn "in the same direction"; a block released
    # at 0.5 alpha on a still table never passes alpha: said as a sentence
    assert ("  test vs theory: direction of instability: the report gives the same, "
            "reproduced the same (neither becomes unstable): agrees") in lines
    rest = json.loads((out / "summary.json").read_text())["runs"][0]["t_rest [s]"]
    assert abs(rest - FIG_3_4_REST) <= ABOUT * FIG_3_4_REST
    assert first.startswith(f"fig-3-4: 30 x 6 in block, COR 0.925: came to rest at "
                            f"t = {rest:.2f} s after 10.5 cycles: 21 impacts of swings over 3 % ")
    # "about 10 vibrations" (Section 3.7 (1)): the closed form's 21 impacts, two a cycle
    assert _visible_impacts_closed_form(30, 6, 0.925, 0.5) / 2 == 10.5


def test_the_reproduction_report_says_free_rocking_as_the_console_does():
    import shaketable as st
    from shaketable.reproduce import run_line

    # Fig. 3.4's run: report.md's line leads with the rest time and the countable impacts
    block = st.Block.parse("30x6in")
    run = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=8.0)
    line = run_line(run)
    assert line.startswith("* 30 x 6 in block, from θ0 = 0.5 α, COR 0.925: came to rest at t = ")
    rest = float(line.split("came to rest at t = ")[1].split(" s")[0])
    assert abs(rest - FIG_3_4_REST) <= ABOUT * FIG_3_4_REST
    assert "after 10.5 cycles: 21 impacts of swings over 3 % of the release" in line


def test_a_small_release_is_said_as_given_and_a_last_swing_in_two_decimals():
    import shaketable as st
    from shaketable.studies.free_rocking import free_rocking_verdict

    # released at 0.001 alpha (below the two decimals of a larger release), and the same
    # block cut while it still rocks with a swing under 0.01 alpha
    block = st.Block.parse("36x9in")
    small = st.simulate(block, None, cor=0.925, theta0=0.001 * block.alpha, duration=3.0)
    assert free_rocking_verdict(small).endswith("(released at θ/α = 0.001)")
    late = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=5.0)
    verdict = free_rocking_verdict(late)
    assert verdict.startswith("still rocking at the end (t = 5.00 s) after ")
    swing = verdict.split("last swing θ/α = ")[1].split(":")[0]
    assert len(swing.split(".")[1]) == 2 and 0 < float(swing) < 0.5, verdict
    # Fig. 3.4's block just before its rest (5.76 s): its last swing is below 0.01 alpha
    block = st.Block.parse("30x6in")
    end = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=5.7)
    assert "after 10.5 cycles, last swing θ/α < 0.01: 21 impacts of swings over 3 % of the " \
        "release and " \
        in free_rocking_verdict(end)


def test_a_block_kicked_from_upright_is_said_by_its_initial_rate():
    import shaketable as st
    from shaketable.studies.free_rocking import free_rocking_verdict

    # theta0 = 0, theta_dot0 = 0.3 rad/s: no "released at θ/α = 0"; the swings are counted
    # against the largest one (there is no release amplitude)
    block = st.Block.parse("30x6in")
    kicked = st.simulate(block, None, cor=0.925, theta_dot0=0.3, duration=4.0)
    verdict = free_rocking_verdict(kicked)
    assert verdict.endswith("(started from θ = 0 at θ' = 0.3 rad/s)"), verdict
    assert "released" not in verdict and "of the release" not in verdict, verdict
    assert "% of the largest swing" in verdict, verdict


def test_the_api_verdict_of_free_rocking_is_the_commands_verdict():
    import re

    import shaketable as st

    # Fig. 3.4's block released at 0.5 alpha: Section 3.7 (1), about 6 s and about 10
    # vibrations, both in result.verdict() itself (not only in the commands)
    block = st.Block.parse("30x6in")
    run = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=8.0)
    said = re.match(r"came to rest at t = (\d+\.\d\d) s after (\d+\.?\d*) cycles", run.verdict())
    assert said, run.verdict()
    assert abs(float(said[1]) - FIG_3_4_REST) <= ABOUT * FIG_3_4_REST
    assert abs(float(said[2]) - FIG_3_4_CYCLES) <= ABOUT * FIG_3_4_CYCLES


@pytest.mark.usefixtures("figure_drafts")
def test_animate_fig_3_4_leads_with_the_rest_time(tmp_path, capsys):
    # the animation's line is the run's verdict, not the release angle (Section 3.7 (1))
    assert main(["animate", "fig-3-4", "--end", "0.2s", "--fps", "5", "--size", "160x120",
                 "--out", str(tmp_path / "a.gif")]) == 0
    out = capsys.readouterr().out
    assert "fig-3-4: 30 x 6 in, COR 0.925: came to rest at t = " in out, out
    assert "after 10.5 cycles: " in out


def test_run_of_a_study_counts_the_substitutes_apart(tmp_path, capsys, monkeypatch):
    import shaketable.reproduce as reproduce
    from shaketable.commands.run import _run_study
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.studies.comparison import ComparisonTally

    # Table 4.2's counts as reproduce gave them (trial 4): 29 agree and 1 differs on the
    # report's own inputs, 21 and 3 on the SUBSTITUTES; the run is replaced by that tally
    tally = ComparisonTally()
    tally.add_many("report inputs", 29, 30)
    tally.add_many("substitute", 21, 24)
    monkeypatch.setattr(reproduce, "run_study_tally",
                        lambda study, out: (tmp_path / "report.md", tally))
    assert _run_study(load_scene(resolve_scene_path("table-4-2")), tmp_path) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first == ("table-4-2: against the report's own inputs 29 agree, 1 differs; against "
                     "SUBSTITUTE accelerograms (not expected to match) 21 agree, 3 differ "
                     f"(see {tmp_path / 'report.md'})")


def test_the_counts_line_says_one_in_the_singular():
    from shaketable.studies.comparison import ComparisonTally

    tally = ComparisonTally()
    tally.add_many("report inputs", 29, 30)
    tally.add_many("substitute", 1, 4)
    assert tally.console_line() == (
        "against the report's own inputs 29 agree, 1 differs; against SUBSTITUTE "
        "accelerograms (not expected to match) 1 agrees, 3 differ")
