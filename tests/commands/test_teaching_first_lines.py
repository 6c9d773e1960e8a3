"""A teaching scene leads with its lesson's numbers, taken from the run."""

from __future__ import annotations

import math
import re

import pandas as pd
import pytest

from shaketable.cli import main
from shaketable.core.constants import G

INCH = 0.0254


@pytest.mark.usefixtures("figure_drafts")
def test_rocking_onset_leads_with_the_thresholds_of_eq_2_1(tmp_path, capsys):
    assert main(["run", "teaching-rocking-onset", "--out", str(tmp_path / "o")]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    # Eq. 2-1: rocking starts at (B/H)(g + v): 30 x 6 in, v = 0 and v = -0.6 g
    said = re.fullmatch(r"teaching-rocking-onset: rocking starts at (\S+) g on a table at rest "
                        r"vertically and at (\S+) g while it accelerates downward at 0\.6 g "
                        r"\(Eq\. 2-1\)", first)
    assert said, first
    assert float(said[1]) == pytest.approx(6 / 30, abs=5e-4)
    assert float(said[2]) == pytest.approx(6 / 30 * (1 - 0.6), abs=5e-4)


@pytest.mark.usefixtures("figure_drafts")
def test_similar_blocks_leads_with_which_sizes_overturn(tmp_path, capsys):
    out = tmp_path / "s"
    assert main(["run", "teaching-similar-blocks", "--out", str(out)]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    said = re.fullmatch(r"teaching-similar-blocks: similar blocks of H/B = 5: (.+) ft overturn; "
                        r"(.+) ft survive \(max θ/α (.+)\)", first)
    assert said, first

    def heights(words):
        return [float(word) for word in re.split(r", | and ", words)]
    fell, stood = heights(said[1]), heights(said[2])
    # Section 2.4 (1): of similar blocks the larger survives
    assert max(fell) < min(stood)
    # the numbers are the run's (its numbers.csv), not the scene's text
    table = pd.read_csv(out / "numbers.csv")
    assert sorted(fell + stood) == sorted(table["height [ft]"])
    peaks = [float(word) for word in said[3].split(", ")]
    survived = table[~table["overturned"]]["max theta/alpha [-]"]
    assert peaks == pytest.approx(list(survived), abs=0.005)


@pytest.mark.usefixtures("figure_drafts")
def test_period_grows_leads_with_both_periods(tmp_path, capsys):
    assert main(["run", "teaching-period-grows", "--out", str(tmp_path / "p")]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    said = re.fullmatch(r"teaching-period-grows: the period grows with the amplitude: "
                        r"(\S+) s from θ/α = 0\.2, (\S+) s from θ/α = 0\.8 \(.*\)", first)
    assert said, first
    # Eq. 2-5: T = (4/p) arccosh(1/(1 - θ0/α)), p = sqrt(3g/(4R)), 36 x 9 in; within the
    # slender approximation's 0.5 % for this block (alpha 0.245 rad) and the 2 decimals
    radius = 0.5 * math.hypot(36 * INCH, 9 * INCH)
    p = math.sqrt(3 * G / (4 * radius))
    for got, ratio in ((said[1], 0.2), (said[2], 0.8)):
        period = 4 / p * math.acosh(1 / (1 - ratio))
        assert float(got) == pytest.approx(period, rel=0.005, abs=0.006)


def test_cor_sweep_and_period_amplitude_lessons_read_their_tables():
    from shaketable.studies.teaching import teaching_answer

    # a table where COR 0.9 overturns and COR 1 does not: the worst is the overturn
    sweep = pd.DataFrame({"cor [-]": [1.0, 0.95, 0.9],
                          "max theta/alpha [-]": [0.2, 0.5, 1.2],
                          "overturned": [False, False, True]})
    assert teaching_answer("cor-sweep", sweep) == (
        "max θ/α = 0.200 at COR 1 but F (overturns) at COR 0.9: a lower COR can raise the peak")
    periods = pd.DataFrame({"theta0/alpha [-]": [0.1, 0.9], "exact period [s]": [0.5, 2.0],
                            "linear oscillator period [s]": [1.25, 1.25]})
    assert teaching_answer("period-amplitude", periods).startswith(
        "the rocking period grows from 0.500 s at θ0/α = 0.1 to 2.000 s at 0.9 (4.0 times)")
    assert teaching_answer("an-item-of-my-own", periods) == ""


def test_a_lesson_the_numbers_do_not_show_is_not_stated():
    from shaketable.studies.teaching import teaching_answer

    # the highest COR gives the largest peak: no "a lower COR can raise the peak"
    sweep = pd.DataFrame({"cor [-]": [0.9, 1.0, 0.95],
                          "max theta/alpha [-]": [0.2, 0.5, 0.3],
                          "overturned": [False, False, False]})
    assert teaching_answer("cor-sweep", sweep) == (
        "max θ/α = 0.500 at COR 1, 0.300 at COR 0.95, 0.200 at COR 0.9")
    # a period that shrinks with the amplitude: no "grows"
    periods = pd.DataFrame({"theta0/alpha [-]": [0.1, 0.9], "exact period [s]": [2.0, 0.5],
                            "linear oscillator period [s]": [1.25, 1.25]})
    assert teaching_answer("period-amplitude", periods) == (
        "the rocking period is 2.000 s at θ0/α = 0.1 and 0.500 s at 0.9; the linear "
        "oscillator's 1.250 s")
    # no downward vertical acceleration: no "while it accelerates downward"
    onsets = pd.DataFrame({"vertical [g]": [0.0, 0.2], "engine onset [g]": [0.2, 0.24]})
    assert teaching_answer("rocking-onset", onsets) == (
        "rocking starts at 0.200 g at a vertical acceleration of +0 g")
    # downward, and the onset falls: the lesson, with Eq. (2-1)'s numbers,
    # (B/H)(g + v) = 0.2 (1 - 0.3) = 0.14 g
    onsets = pd.DataFrame({"vertical [g]": [0.0, -0.3], "engine onset [g]": [0.2, 0.14]})
    assert teaching_answer("rocking-onset", onsets) == (
        "rocking starts at 0.200 g on a table at rest vertically and at 0.140 g while it "
        "accelerates downward at 0.3 g (Eq. 2-1)")


@pytest.mark.usefixtures("figure_drafts")
def test_animate_period_grows_says_the_periods_not_the_release(tmp_path, capsys):
    assert main(["animate", "teaching-period-grows", "--end", "0.2s", "--fps", "5",
                 "--size", "160x120", "--out", str(tmp_path / "a.gif")]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("teaching-period-grows: the period grows with the amplitude: "), first
