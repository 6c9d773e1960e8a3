"""Repeatability under the table's pitch (Section 3.7 (2))."""

import math

import numpy as np
import pytest

from shaketable import Block
from shaketable.motions import artificial, harmonic
from shaketable.repeatability import pitch_repeatability
from shaketable.table import Pitch

BLOCK = Block.parse("30x6in")


def test_without_pitch_amplitude_every_phase_is_the_same_run():
    # A pitch of zero amplitude is no pitch: every phase must give the reference
    # run exactly, and runs half a cycle apart do not differ at all.
    motion = harmonic(2.0, 0.3, duration=4.0, dt=0.01, ramp=1.0)
    result = pitch_repeatability(BLOCK, motion, cor=0.925, phases=4,
                                 pitch=Pitch(amplitude=0.0))
    for run in result.runs:
        np.testing.assert_array_equal(run.theta, result.without_pitch.theta)
    assert np.all(result.pair_differences() == 0.0)
    summary = result.summary()
    assert summary["phases"] == 4 and summary["overturned fraction"] == 0.0


def test_phases_are_equally_spaced_and_change_a_small_earthquake_response():
    # Section 3.7 (2): "when the block starts rocking under earthquake motions, the
    # initial amplitude of rocking ... is relatively small, and hence the effect of
    # the rotation component of the table motion becomes more important".
    motion = artificial("olive-view", seed=3, pga_g=0.25, vertical_pga_g=0.1, duration=8.0)
    result = pitch_repeatability(BLOCK, motion, cor=0.925, phases=6)
    np.testing.assert_allclose(np.diff(result.phases), 2 * math.pi / 6)
    peaks = result.to_frame()["max theta/alpha [-]"].to_numpy()
    assert peaks.max() > 1.5 * peaks.min()  # visibly different runs
    assert len(result.to_frame()) == 6


def test_bad_phase_count():
    with pytest.raises(ValueError, match="phases"):
        pitch_repeatability(BLOCK, harmonic(2.0, 0.3, duration=1.0, dt=0.01), cor=0.9,
                            phases=1)
