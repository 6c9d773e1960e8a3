"""The console says what the signs of a stack's pattern mean when two pivots have
opposite signs ("both, opposite ways (+-)" while both θ traces of the figure rise), in the
figure's terms: θ each block's rotation, φ its rotation on the block below."""

from __future__ import annotations

import numpy as np

from shaketable.scenes.stack_patterns import pattern_signs


def test_opposite_pivots_are_said_in_theta_and_phi():
    from shaketable.core.constants import G
    from shaketable.core.motion import Motion
    from shaketable.scenes.stack import run_quietly, stack_answer, stack_from_text

    # stack-step's column (docs/stack.md): two 1 x 0.1 m blocks under a step above
    # u* = 0.664 g start tipping opposite ways at once
    t = np.arange(0, 0.2, 0.005)
    result, _ = run_quietly(stack_from_text("1x0.1m,1x0.1m"), Motion(t, np.full(t.size, 0.7 * G)))
    lines = stack_answer(result)
    k = next(i for i, line in enumerate(lines) if line.startswith("first uplift"))
    assert "both, opposite ways (+-)" in lines[k]
    assert lines[k + 1] == pattern_signs((1, -1))
    assert "φ1 = θ1 − θ0" in lines[k + 1] and "block 1 turns back on block 0 (φ1 < 0)" in lines[k + 1]
    # what the words say, in the run: at the end both θ have grown (+), the top one less
    theta = np.asarray(result.theta)
    assert theta[-1, 0] > 0 and theta[-1, 1] > 0 and theta[-1, 1] - theta[-1, 0] < 0


def test_patterns_whose_signs_read_as_they_look_get_no_note():
    for pattern in ((1, 1), (1, 0), (0, -1), (-1, 0, 0), (0, 1, 1), (0, 0)):
        assert pattern_signs(pattern) == ""
    assert "block 2 turns back on block 1 (φ2 < 0)" in pattern_signs((1, 0, -1))
