"""The planar figure's "slip of the base" panel draws the base's slide, not its midpoint's.

A block that rocks on a pivot that never slips (ample friction) has not slid at all: its
pivot corner stands where it stood (the base's slip is 0 to rounding), while the midpoint
of its base moves by b (1 - cos theta) + h sin(theta) - b sin... with the rotation. The
panel must show 0 there, and for a block that slide-rocks the displacement of the corner it
turns on, x + h sin(theta) + sign(theta) b (1 - cos(theta)) (docs/planar.md), with its
peak marked at the result's peak_base_slip.
"""

from __future__ import annotations

import numpy as np
import pytest

from shaketable.core.constants import LENGTH_UNITS, G
from shaketable.core.geometry import Block
from shaketable.ground.generators import harmonic
from shaketable.models.planar.run import simulate_planar
from shaketable.models.sliding.result import Friction
from shaketable.plots.base import pyplot


def _slip_panel(result):
    fig = result.plot()
    try:
        for axis in fig.axes:
            for line in axis.get_lines():
                if line.get_label() == "slip of the base":
                    unit = axis.get_ylabel().split("[")[1].rstrip("]")
                    markers = [other for other in axis.get_lines()
                               if other.get_label().startswith("peak")]
                    return (np.asarray(line.get_ydata()) * LENGTH_UNITS[unit],
                            markers[0].get_xydata()[0] * (1.0, LENGTH_UNITS[unit])
                            if markers else None)
    finally:
        pyplot().close(fig)
    raise AssertionError("no 'slip of the base' line")


@pytest.fixture(scope="module")
def motion():
    return harmonic(3.0, horizontal=0.6 * G, duration=2.0, dt=0.005, ramp=0.25)


def test_a_block_rocking_on_a_pivot_that_sticks_shows_no_slip(motion):
    block = Block(0.762, 0.1524)   # 30 x 6 in
    result = simulate_planar(block, motion, cor=0.9, friction=Friction(2.0))
    assert set(result.modes_visited) == {"rest", "rock"}
    midpoint = np.max(np.abs(result.slip))
    assert midpoint > 1e-4   # [m]: the rotation moves the midpoint (0.24 mm here)
    drawn, _ = _slip_panel(result)
    assert np.max(np.abs(drawn)) <= 1e-12 * block.height


def test_a_slide_rocking_block_shows_its_pivot_corner_and_the_peak_base_slip(motion):
    block = Block(0.762, 0.1524)
    result = simulate_planar(block, motion, cor=0.9, friction=Friction(0.25, 0.22))
    assert "slide-rock" in result.modes_visited
    drawn, marker = _slip_panel(result)
    h, b = 0.5 * block.height, 0.5 * block.width
    corner = result.x + h * np.sin(result.theta) \
        + np.sign(result.theta) * b * (1.0 - np.cos(result.theta))
    np.testing.assert_allclose(drawn, corner, rtol=0, atol=1e-12)
    assert marker[0] == result.t_peak_base_slip
    assert abs(marker[1]) == pytest.approx(result.peak_base_slip, rel=1e-12)
    # the located peak is at least every sample's, and differs from the midpoint's
    assert result.peak_base_slip >= np.max(np.abs(corner)) - 1e-15
    assert result.peak_base_slip != result.peak_slip
