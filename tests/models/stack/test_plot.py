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
    # blocks numbered from 0 at the bottom, as docs/stack.md and the verdict number them
    assert labels[0].startswith("horizontal") and "θ1 [rad]\nblock 1 (top)" in labels
    assert "θ0 [rad]\nblock 0 (bottom)" in labels and labels[-1] == "contact"
    assert "30 × 6 in on 30 × 6 in" in fig._suptitle.get_text()
    pyplot().close(fig)


def test_the_docs_number_the_blocks_as_the_figure_and_the_verdict_do():
    from pathlib import Path

    text = (Path(__file__).parents[3] / "docs" / "stack.md").read_text(encoding="utf-8")
    assert '"block 0 (bottom)"' in text and '"block 1 (top)"' in text
    assert '"block 0 (bottom) overturned at 3.99 s"' in text
