"""The stack's Calcomp figure: a panel per ground channel, one per block, the pattern band."""

import numpy as np

import shaketable as st
from shaketable.models.stack import Stack, simulate_stack
from shaketable.plots.base import pyplot


def test_the_figure_has_one_rotation_panel_per_block_and_a_pattern_band():
    stack = Stack([st.Block.parse("30x6in"), st.Block.parse("30x6in")])
    t = np.arange(0.0, 0.6, 0.005)
    result = simulate_stack(stack, st.Motion(t, 2.5 * np.sin(12.0 * t), name="sine"))
    fig = result.plot(title="two 30 x 6 in blocks")
    labels = [axis.get_ylabel() for axis in fig.axes]
    assert labels[0].startswith("horizontal") and "θ1 [rad]\n(top)" in labels
    assert "θ0 [rad]\n(bottom)" in labels and labels[-1] == "contact"
    assert "30 × 6 in on 30 × 6 in" in fig._suptitle.get_text()
    pyplot().close(fig)
