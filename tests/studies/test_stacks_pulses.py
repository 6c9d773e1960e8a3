"""The stacks study's smallest overturning pulse of a block alone against the exact
single-block overturning spectrum (decided after the pulse in closed form)."""

from __future__ import annotations

import math

import pytest

from shaketable import Block
from shaketable.studies.overturning_spectrum import overturning_spectrum
from shaketable.studies.stacks import pulse_amplitudes

BLOCK = Block.parse("8x2ft")   # the block of the reproduce section


def test_the_block_alone_minimum_is_the_exact_spectrum_edge():
    exact = (overturning_spectrum(BLOCK, ratios=[3.0], scan_step=0.02, tolerance=1e-6)
             .minimum("half-sine", 3.0) * math.tan(BLOCK.alpha))
    row = pulse_amplitudes(BLOCK, ratios=(3.0,), heights=(1,)).iloc[0]
    # a bracket 0.02 / 2**5 relative wide holding the edge, to what the 10-s window after
    # the pulse leaves (0.07 %, stack_spectrum's docstring)
    assert row["falls [g]"] / row["stands [g]"] - 1.0 < 7e-4
    assert row["minimum [g]"] == pytest.approx(exact, rel=1e-3)
    assert row["stands [g]"] <= exact * (1 + 7e-4) and row["falls [g]"] >= exact * (1 - 7e-4)
