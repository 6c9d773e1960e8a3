"""Repeatability under the table's pitch (Section 3.7 (2))."""

import math

import numpy as np
import pytest

from shaketable import Block
from shaketable.core.constants import G
from shaketable.ground.generators import artificial, harmonic
from shaketable.lab.pitch import Pitch
from shaketable.lab.stage import TableSetup, run_table
from shaketable.models.api import simulate
from shaketable.scenes.studies import section_3_7_cases
from shaketable.studies.repeatability import (
    is_final,
    pitch_repeatability,
    run_to_the_end,
    section_3_7_contrast,
)

BLOCK = Block.parse("30x6in")


def test_without_pitch_amplitude_every_phase_is_the_same_run():
    # A pitch of zero amplitude is no pitch: every phase must give the reference
    # run exactly, and runs half a cycle apart do not differ at all.
    motion = harmonic(2.0, horizontal=0.3 * G, duration=4.0, dt=0.01, ramp=1.0)
    result = pitch_repeatability(BLOCK, motion, cor=0.925, phases=4,
                                 pitch=Pitch(amplitude=0.0))
    for run in result.runs:
        np.testing.assert_array_equal(run.theta, result.without_pitch.theta)
    assert np.all(result.pair_differences() == 0.0)
    summary = result.summary()
    assert summary["phases"] == 4 and summary["verdicts final"] == 4
    assert summary["overturned fraction"] == float(result.without_pitch.overturned)


def test_phases_are_equally_spaced_and_change_a_small_earthquake_response():
    # Section 3.7 (2): "when the block starts rocking under earthquake motions, the
    # initial amplitude of rocking ... is relatively small, and hence the effect of
    # the rotation component of the table motion becomes more important".
    motion = artificial("olive-view", seed=3, pga=0.25 * G, vertical_pga=0.1 * G, duration=8.0)
    result = pitch_repeatability(BLOCK, motion, cor=0.925, phases=6)
    np.testing.assert_allclose(np.diff(result.phases), 2 * math.pi / 6)
    peaks = result.to_frame()["max theta/alpha [-]"].to_numpy()
    assert peaks.max() > 1.5 * peaks.min()  # visibly different runs
    assert len(result.to_frame()) == 6


def test_bad_phase_count():
    with pytest.raises(ValueError, match="phases"):
        pitch_repeatability(BLOCK, harmonic(2.0, horizontal=0.3 * G, duration=1.0, dt=0.01), cor=0.9,
                            phases=1)


def test_a_run_continues_past_the_record_until_its_verdict_is_final():
    # Fig. 3.9's motion started abruptly (0.45 g H + 0.26 g V at 2 Hz, 10 s) on a
    # table pitching with phase 4 pi / 3: cut at the end of the record the block is
    # still falling (|theta| > alpha), which was listed as "not overturned". On a table
    # at rest a block beyond its block angle cannot come back (gravity's moment about
    # the pivot changes sign at |theta| = alpha, Eq. 2-13 without ground motion): it
    # must overturn, the way it leans.
    motion = harmonic(2.0, horizontal=0.45 * G, vertical=0.26 * G, duration=10.0, dt=0.01)
    felt = run_table(motion, TableSetup(pitch=Pitch(phase=4 * math.pi / 3))).felt
    cut = simulate(BLOCK, felt, cor=0.925)
    assert not cut.overturned and abs(cut.theta[-1]) > BLOCK.alpha and not is_final(cut)
    final = run_to_the_end(BLOCK, felt, cor=0.925)
    assert is_final(final) and final.overturned
    assert final.overturn_direction == np.sign(cut.theta[-1])
    assert final.t_overturn > motion.t[-1]
    # a run that comes to rest is final too: at rest on a table at rest (0.22 g is
    # above Eq. 2-1's B/H g = 0.2 g: the block rocks)
    small = run_to_the_end(BLOCK, harmonic(2.0, horizontal=0.22 * G, duration=2.0, dt=0.01, ramp=0.25),
                           cor=0.925)
    assert not small.overturned and small.max_theta_ratio > 0.1
    assert is_final(small) and small.theta[-1] == 0.0
    with pytest.raises(ValueError, match="tail"):
        run_to_the_end(BLOCK, felt, cor=0.925, tail=0.0)


def test_section_3_7_harmonic_tests_repeat_and_an_earthquake_test_does_not():
    # Section 3.7 (2): under the 2 Hz harmonic tests "the effect of the pitch was
    # relatively small", while an earthquake test "was not repeatable using the same
    # horizontal and vertical command displacements because the pitch of the shaking
    # table was different in each case". Same commands, 12 pitch phases each: the
    # harmonic scenes (Figs. 3.7-3.9) give one verdict, one direction and times of
    # instability within half a 2 Hz period; the earthquake-type motion that rocks the
    # block substantially (the Fig. 3.5 substitute at 0.27 g) gives different verdicts
    # or directions, and its runs differ visibly more (median RMS difference of
    # theta/alpha between runs half a pitch cycle apart) than any harmonic test's.
    cases = section_3_7_cases(phases=12)
    harmonic_cases = [case for case in cases if case.kind == "harmonic"]
    assert len(harmonic_cases) == 3
    for case in cases:
        assert all(is_final(run) for run in case.runs), case.name
    for case in harmonic_cases:
        assert case.repeatable(), case.name
        assert case.t_unstable_spread() <= 0.25 and case.summary()["agrees"], case.name
    rocking = cases[3]
    assert rocking.kind == "earthquake-type" and "0.27 g" in rocking.name
    verdicts = {(run.overturned, run.unstable_direction) for run in rocking.runs}
    assert len(verdicts) > 1 and not rocking.repeatable()
    assert rocking.spread() > 5 * max(case.spread() for case in harmonic_cases)
    contrast = section_3_7_contrast(cases)
    assert contrast[0].report is True and contrast[0].agrees
