"""The stack's Calcomp figure: a panel per ground channel, one per block, the pattern band."""

import numpy as np
import pytest

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
    # the band's colours are read by phi (docs/stack.md): each row says what its phi is,
    # and the legend names every mark drawn on it
    band = fig.axes[-1]
    assert [tick.get_text() for tick in band.get_yticklabels()] == \
        ["base\nφ = θ0", "0|1\nφ = θ1 − θ0"]
    assert [text.get_text() for text in band.get_legend().get_texts()] == \
        ["flat", "pivot on -x corner (φ > 0)", "pivot on +x corner (φ < 0)", "impact",
         "overturn"]
    pyplot().close(fig)


def test_the_docs_number_the_blocks_as_the_figure_and_the_verdict_do():
    from pathlib import Path

    text = (Path(__file__).parents[3] / "docs" / "stack.md").read_text(encoding="utf-8")
    assert '"block 0 (bottom)"' in text and '"block 1 (top)"' in text
    assert '"block 0 (bottom) overturned at 3.99 s"' in text


def test_a_small_kick_is_drawn_on_its_own_scale():
    # the top block (0.8 x 0.2 m) released at 0.1 rad lands at 0.265 s and kicks the
    # bottom one (1 x 0.3 m, alpha = atan(0.15 / 0.5) = 0.2915 rad) by a few mrad: on the
    # +-1.3 alpha scale that is a flat line, so its panel takes its own range
    from shaketable.plots.stack import magnification
    from shaketable.plots.stack_animation import _StackStage

    stack = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)], masses=(1000.0, 1000.0))
    result = simulate_stack(stack, theta0=(0.0, 0.1), duration=0.5)
    peak = float(np.abs(result.theta[:, 0]).max())
    alpha = np.arctan(0.15 / 0.5)
    assert 0.0 < peak < 0.05 * alpha
    fig = result.plot()
    bottom = next(a for a in fig.axes if a.get_ylabel().startswith("θ0 [rad]"))
    top = next(a for a in fig.axes if a.get_ylabel().startswith("θ1 [rad]"))
    assert bottom.get_ylim()[1] == pytest.approx(1.3 * peak)     # its own range
    assert "off scale" in " ".join(text.get_text() for text in bottom.texts)
    assert top.get_ylim()[1] == pytest.approx(1.3 * np.arctan(0.1 / 0.4))   # +-1.3 alpha
    pyplot().close(fig)
    # the animation's shared theta/alpha axis: a 1-2-5 factor, on the +-1.2 axis a peak of
    # 0.02 alpha wants 0.6 / 0.02 = 30, i.e. 20; one factor for the column, from its
    # largest peak (the top block's 0.1 rad / alpha1 = 0.41: none)
    assert magnification(0.02, 1.2) == 20.0 and magnification(0.5, 1.2) == 1.0
    assert magnification(0.0, 1.2) == 1.0
    stage = _StackStage(result, np.array([0.0, 0.25, 0.5]), 0.1, size=(1000, 500), dpi=100,
                        unit=None, title=None)
    labels = [line.get_label() for axis in stage.fig.axes for line in axis.get_lines()]
    assert "θ0/α0: block 0 (bottom)" in labels and "θ1/α1: block 1 (top)" in labels
    assert stage.traces[0][2].max() == pytest.approx(result.theta[:, 0].max() / alpha)
    pyplot().close(stage.fig)


def test_blocks_rocking_together_are_drawn_at_one_magnification():
    # an 8 x 4 ft block under a 6 x 4 ft one, released together from 0.06 rad: one body,
    # theta/alpha 0.06 / atan(1/2) = 0.129 (bottom) and 0.06 / atan(2/3) = 0.102 (top),
    # either side of a tenth of the +-1.2 axis; the top block must not be drawn magnified
    # (x 5) beside the bottom one unmagnified, as if it rocked 4 times more
    from shaketable.plots.stack_animation import _StackStage

    stack = Stack([st.Block.parse("8x4ft"), st.Block.parse("6x4ft")])
    result = simulate_stack(stack, theta0=(0.06, 0.06), duration=0.2)
    peaks = np.abs(result.theta).max(axis=0) / [np.arctan(0.5), np.arctan(2.0 / 3.0)]
    assert peaks[0] > 0.12 > peaks[1] > 0.1
    stage = _StackStage(result, np.array([0.0, 0.1, 0.2]), 0.1, size=(800, 450), dpi=100,
                        unit=None, title=None)
    drawn = [trace[2] for trace in stage.traces[:2]]
    assert [np.abs(ratio).max() for ratio in drawn] == pytest.approx(peaks, rel=1e-12)
    assert not any("magnified" in line.get_label()
                   for axis in stage.fig.axes for line in axis.get_lines())
    pyplot().close(stage.fig)


def test_the_title_gives_the_excursion_in_the_unit_family_of_the_blocks():
    # ft blocks: the console's ft/in, not mm; blocks given in m: m (mm under 1 m)
    import re

    for sizes, to_unit in ((("8x4ft", "6x4ft"), {"in": 0.0254, "ft": 0.3048}),
                           (("2x1m", "1.5x1m"), {"mm": 0.001, "m": 1.0})):
        stack = Stack([st.Block.parse(size) for size in sizes])
        result = simulate_stack(stack, theta0=(0.05, 0.05), duration=0.1)
        fig = result.plot()
        found = re.search(r"peak top-corner excursion ([0-9.]+) (\w+)", fig._suptitle.get_text())
        pyplot().close(fig)
        assert found is not None and found[2] in to_unit
        assert float(found[1]) * to_unit[found[2]] == pytest.approx(result.peak_excursion,
                                                                    rel=5e-3)
