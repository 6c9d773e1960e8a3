"""Every overturn/safe band of a stack under half-sine pulses (``spectrum --stack``), checked
against the single block's exact spectrum (another engine and another decision after the
pulse: shaketable.studies.overturning_spectrum)."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from shaketable.cli import main
from shaketable.core.geometry import Block
from shaketable.models.stack import Stack
from shaketable.studies.overturning_spectrum import overturning_spectrum
from shaketable.studies.stack_spectrum import column_bands, uplift_threshold

BLOCK = Block.from_inches(96, 24)     # 8 x 2 ft, tan(alpha) = 0.25


@pytest.fixture(scope="module")
def exact_edge():
    # the single block's lowest overturning amplitude at omega/p = 2 [g], exact decision
    # after the pulse (Housner's COR): a/(g tan alpha) = 1.8015 (one band up to the ceiling)
    spectrum = overturning_spectrum(BLOCK, ratios=[2.0], scan_step=0.02, tolerance=1e-6)
    return spectrum.minimum("half-sine", 2.0) * math.tan(BLOCK.alpha)


def test_a_block_alone_has_the_single_block_spectrum_bands(exact_edge):
    bands, _ = column_bands(Stack((BLOCK,)), 2.0 * BLOCK.p, scan_step=0.05, iterations=8)
    assert [band["verdict"] for band in bands] == ["safe", "overturns"]
    # edge bracket 0.05 / 2**8 relative wide: its middle within 1e-4 of the edge, plus what
    # the 10-s window after the pulse leaves (measured 0.07 %)
    assert bands[1]["from [g]"] == pytest.approx(exact_edge, rel=1e-3)
    # the ceiling: twice Eq. (2-8) and 2 tan(alpha) more, as the single block's
    # 2 sqrt(1 + (omega/p)^2) + 2 in a/(g tan alpha)
    assert bands[1]["to [g]"] == pytest.approx(0.25 * (2 * math.sqrt(5) + 2), rel=1e-12)


def test_a_stack_with_a_weightless_squat_top_falls_as_its_bottom_block(exact_edge):
    # a top block of 1e-6 the mass that cannot tip by itself below b2/h2 = 10 g: the stack
    # engine (plastic multi-contact impacts) must find the single block's edge (Housner's
    # COR, the plastic law of one block)
    stack = Stack((BLOCK, Block.from_inches(2.4, 24)), masses=(1.0, 1e-6))
    assert uplift_threshold(stack) == pytest.approx(0.25, rel=1e-5)
    bands, _ = column_bands(stack, 2.0 * BLOCK.p, scan_step=0.05, iterations=8)
    assert bands[0]["verdict"] == "safe"
    assert bands[1]["verdict"] == "overturns" and bands[1]["block that fell"] == \
        "block 0 (bottom)"
    assert bands[1]["from [g]"] == pytest.approx(exact_edge, rel=1e-3)


def test_uplift_threshold_is_the_closed_form_of_two_blocks():
    # A1 = b1 (m1 + m2) / (m1 h1 + m2 (2 h1 + h2)), A2 = b2 / h2 (docs/stack.md)
    top = Block.from_inches(96, 12)
    stack = Stack((BLOCK, top), masses=(2.0, 1.0))
    b1, h1, b2, h2 = 0.5 * BLOCK.width, 0.5 * BLOCK.height, 0.5 * top.width, 0.5 * top.height
    a1 = b1 * 3.0 / (2.0 * h1 + 1.0 * (2 * h1 + h2))
    assert uplift_threshold(stack) == pytest.approx(min(a1, b2 / h2), rel=1e-14)


def test_spectrum_stack_gives_every_band_and_the_block_that_fell(tmp_path, capsys):
    assert main(["spectrum", "--stack", "8x2ft,8x1ft", "--ratios", "2", "--scan-step", "0.1",
                 "--iterations", "3", "--out", str(tmp_path)]) == 0
    said = capsys.readouterr().out
    table = pd.read_csv(tmp_path / "spectrum.csv")
    stack = table[table["column"] == "stack"]
    # the slender top (b2/h2 = 0.125 < A1) falls first at low amplitudes, the column later
    assert list(stack["verdict"]) == ["safe", "overturns", "overturns"]
    assert list(stack["block that fell"].fillna("")) == ["", "block 1 (top)",
                                                         "block 0 (bottom)"]
    # the bands tile the scanned range
    assert (stack["from [g]"].to_numpy()[1:] == stack["to [g]"].to_numpy()[:-1]).all()
    assert "block 1 (top) first" in said and "block 0 (bottom) first" in said
    assert (tmp_path / "spectrum.png").is_file()
