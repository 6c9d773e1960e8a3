"""A stack's contact pattern in words for three blocks and more (docs/stack.md's table)."""

from __future__ import annotations

import numpy as np

from shaketable.scenes.stack_patterns import pattern_words


def test_patterns_of_three_and_more_blocks_are_named_in_words():
    # interface j lies below block j; +1 pivots on the upper block's -x corner (docs/stack.md)
    assert pattern_words((1, 0, 0), code=False) == "blocks 0-2 rocking as one on the table (+)"
    assert pattern_words((1, 0, -1)) == ("blocks 0-1 rocking as one on the table (+), block 2 "
                                         "rocking on block 1 (-) [\"open 0+ 2-\" in the CSV "
                                         "files: the open (pivoting) interfaces, from 0 at the "
                                         "base, with their signs]")
    assert pattern_words((0, -1, 0)) == ("block 0 at rest on the table, blocks 1-2 rocking as "
                                         "one on block 0 (-) [\"open 1-\" in the CSV files: "
                                         "the open (pivoting) interfaces, from 0 at the base, "
                                         "with their signs]")
    assert pattern_words((0, 1, 0, 1, 0), code=False) == (
        "block 0 at rest on the table, blocks 1-2 rocking as one on block 0 (+), blocks 3-4 "
        "rocking as one on block 2 (+)")
    assert pattern_words((0, 0, 0)) == "rest"
    # one and two blocks keep the results' names (docs/stack.md's two-block table)
    assert pattern_words((1, 0)) == "stack as one body (+)"
    assert pattern_words((0, -1)) == "top alone (-)"


def test_the_stack_answer_names_a_three_block_uplift_in_words():
    from shaketable.core.constants import G
    from shaketable.core.motion import Motion
    from shaketable.models.stack import Stack
    from shaketable.scenes.stack import run_quietly, stack_answer, stack_from_text

    # three equal blocks 1 x 0.2 m (b/h = 0.2 each): the whole column uplifts first at
    # A1 = b1 sum(m) / sum(m y_c) = 0.1 * 3 / (0.5 + 1.5 + 2.5) = 0.0667 < A2 = 0.2
    # (docs/stack.md, uplift thresholds): a step of 0.1 g opens the base only, and a positive
    # table acceleration drives theta positive (docs/conventions.md): the pivot is +
    stack = stack_from_text("1x0.2m,1x0.2m,1x0.2m")
    assert isinstance(stack, Stack)
    t = np.arange(0, 0.3, 0.005)
    motion = Motion(t, np.full(t.size, 0.1 * G))
    result, _ = run_quietly(stack, motion)
    uplift = next(line for line in stack_answer(result) if line.startswith("first uplift"))
    # the results' code explained where the console prints it (the CSV files name it so)
    assert ('blocks 0-2 rocking as one on the table (+) ["open 0+" in the CSV files: the open '
            '(pivoting) interfaces, from 0 at the base, with their signs]') in uplift, uplift
