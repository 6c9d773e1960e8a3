"""How a stack names its blocks: in the units they were given in, as far as known."""

from __future__ import annotations

from shaketable import Block
from shaketable.models.stack import Stack


def test_blocks_given_in_metres_are_described_in_metres():
    assert Stack([Block(1.0, 0.4)] * 2).describe() == "2 blocks: 1 x 0.4 m on 1 x 0.4 m"


def test_parsed_and_whole_inch_blocks_keep_their_units():
    # 0.762 x 0.1524 m is 30 x 6 in exactly (1 in = 0.0254 m); a parsed block keeps its text
    stack = Stack([Block.parse("4x1ft"), Block(0.762, 0.1524), Block.parse("300x60mm")])
    assert stack.describe() == "3 blocks: 300 x 60 mm on 30 x 6 in on 4 x 1 ft"
