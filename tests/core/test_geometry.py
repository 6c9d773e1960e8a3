"""Block geometry: the derived quantities of Sections 2.2 and 2.6, worked by hand.

The 16 x 4 ft block (height x width, the report's order; Section 4 uses it) with
1 ft = 0.3048 m exactly (international foot) and g = 9.80665 m/s^2 (standard
gravity, ``shaketable.core.constants.G``):

* H = 16 ft = 4.8768 m, B = 4 ft = 1.2192 m (exact decimals);
* h = H/2 = 2.4384 m, b = B/2 = 0.6096 m (exact);
* R = sqrt(b^2 + h^2) = b sqrt(1 + 4^2) = 0.6096 sqrt(17) = 2.513445189376526 m
  (sqrt(17) = 4.123105625617661);
* alpha = arctan(b/h) = arctan(1/4) = 0.2449786631268641 rad = 14.036243 deg;
* p = sqrt(3 g / 4R) = sqrt(29.41995 / 10.05378075750610) = 1.710630692527962 rad/s;
* I0 / M = 4 R^2 / 3 = 4 (17 x 0.37161216) / 3 = 25.26962688 / 3 = 8.42320896 m^2 (exact);
* aspect ratio H/B = 4.
"""

from __future__ import annotations

import math

import pytest

from shaketable import Block
from shaketable.core.constants import G


@pytest.mark.parametrize("text", ["16x4ft", "16 x 4 ft", "16ft x 4ft", "16X4FT", "16×4ft"])
def test_parse_16x4ft_derived_quantities_by_hand(text):
    block = Block.parse(text)
    assert block.height == pytest.approx(4.8768, rel=1e-15)
    assert block.width == pytest.approx(1.2192, rel=1e-15)
    assert block.h == pytest.approx(2.4384, rel=1e-15)
    assert block.b == pytest.approx(0.6096, rel=1e-15)
    assert block.R == pytest.approx(2.513445189376526, rel=1e-14)
    assert block.alpha == pytest.approx(0.2449786631268641, rel=1e-14)
    assert math.degrees(block.alpha) == pytest.approx(14.036243, abs=1e-6)
    assert block.p == pytest.approx(1.710630692527962, rel=1e-13)
    assert block.I0_per_mass == pytest.approx(8.42320896, rel=1e-14)
    assert block.aspect_ratio == pytest.approx(4.0, rel=1e-15)
    assert block.describe() == "16 x 4 ft" and block.describe(unit="in") == "192 x 48 in"
    assert Block.parse("30x6in").describe() == "30 x 6 in"
    assert Block.parse("36x9in").describe() == "36 x 9 in"  # 3 x 0.75 ft: inches


@pytest.mark.parametrize("text, label", [
    ("30x6in", "30 x 6 in"), ("4x0.8ft", "4 x 0.8 ft"), ("16x4ft", "16 x 4 ft"),
    ("36in x 9in", "36 x 9 in"), ("30in x 0.5ft", "30 in x 0.5 ft"), ("0.5x0.1m", "0.5 x 0.1 m"),
])
def test_a_parsed_block_is_echoed_in_the_users_order_and_units(text, label):
    # `--block 4x0.8ft` is echoed as the user wrote it, not as 48 x 9.6 in
    block = Block.parse(text)
    assert block.label == label and block.describe() == label
    # the label is not part of equality: the same block built in SI is equal, and the
    # sweep tables' inch labels do not change
    assert block == Block(block.height, block.width) and hash(block) == hash(
        Block(block.height, block.width))
    assert block.describe(unit="in") == Block(block.height, block.width).describe(unit="in")
    assert Block.parse("4x0.8ft").height == pytest.approx(4 * 0.3048, rel=1e-15)


def test_derived_quantities_are_consistent_with_each_other():
    # identities that hold for any block: b = R sin(alpha), h = R cos(alpha),
    # p^2 = g / (I0 / R) (= 3 g / 4R), and Eq. (2-1) threshold g b/h = g tan(alpha)
    block = Block.parse("16x4ft")
    assert block.R * math.sin(block.alpha) == pytest.approx(block.b, rel=1e-14)
    assert block.R * math.cos(block.alpha) == pytest.approx(block.h, rel=1e-14)
    assert block.p ** 2 == pytest.approx(G * block.R / block.I0_per_mass, rel=1e-14)
    assert block.rocking_threshold() == pytest.approx(G * 0.25, rel=1e-14)


def test_parse_is_height_by_width_and_units_agree_with_the_explicit_constructors():
    # the report writes blocks height x width ("30 in. x 6 in."); 16 x 4 ft = 192 x 48 in
    assert Block.parse("16x4ft") == Block.from_feet(16, 4)
    assert Block.parse("192x48in").height == pytest.approx(Block.from_feet(16, 4).height,
                                                            rel=1e-15)
    tall = Block.parse("16x4ft")
    assert tall.height > tall.width
    assert Block.parse("4x16ft").alpha == pytest.approx(math.atan(4.0), rel=1e-14)


@pytest.mark.parametrize("text, match", [
    ("16x4", "no unit"),
    ("16 by 4 ft", "not understood"),
    ("16x4 furlongs", "unit"),
    ("0x4ft", "'0x4ft': the height must be positive"),
    ("16x0ft", "'16x0ft': the width must be positive"),
    ("-16x4ft", "'-16x4ft': the height and the width must be positive"),
])
def test_parse_rejects_bad_sizes_naming_the_problem(text, match):
    with pytest.raises(ValueError, match=match):
        Block.parse(text)
