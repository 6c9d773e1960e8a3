"""A stack's contact pattern in words, for any number of blocks (docs/stack.md, "Coordinates,
interfaces, patterns").

Two blocks keep the names of the results (:func:`shaketable.models.stack.pattern_name`:
"stack as one body (+)", "top alone (−)", ...). With three or more, the results name a
pattern by its open (pivoting) interfaces (``open 0+ 2-``); here each group of blocks that
moves as one body is named, from the bottom up, with the support it pivots on and the sign
of the pivot, the results' code after it in brackets, said once:
``"blocks 0-1 rocking as one on the table (+), block 2 rocking on block 1 (-) ["open 0+ 2-" in
the CSV files: the open (pivoting) interfaces, from 0 at the base, with their signs]"``.
"""

from __future__ import annotations

from shaketable.models.stack import pattern_name

#: The results' code of a pattern of three blocks or more, said where the console prints it
#: (once: the first uplift): the CSV files name the pattern so.
CODE_WORDS = ("\"{}\" in the CSV files: the open (pivoting) interfaces, from 0 at the base, "
              "with their signs")


def _blocks(first: int, last: int) -> str:
    return f"block {first}" if first == last else f"blocks {first}-{last}"


def pattern_words(pattern, *, code: bool = True) -> str:
    """A contact pattern in words.

    Parameters
    ----------
    pattern : sequence of int
        Each interface's state, bottom first (interface j below block j): 0 flat, +1 or -1
        pivoting on the upper block's -x or +x corner.
    code : bool
        Append the results' code in brackets (three blocks or more), with what it means
        (:data:`CODE_WORDS`).

    Returns
    -------
    str
        For one or two blocks the results' name; for more, every group of blocks moving as
        one body (an open interface and the flat ones above it) with its support and sign,
        the blocks below the lowest open interface said at rest on the table, and the results'
        code in brackets (``"rest"`` when no interface is open).
    """
    pattern = tuple(int(s) for s in pattern)
    if len(pattern) <= 2 or not any(pattern):
        return pattern_name(pattern)
    opened = [j for j, s in enumerate(pattern) if s != 0]
    parts = [] if opened[0] == 0 else [f"{_blocks(0, opened[0] - 1)} at rest on the table"]
    for index, j in enumerate(opened):
        last = opened[index + 1] - 1 if index + 1 < len(opened) else len(pattern) - 1
        support = "the table" if j == 0 else f"block {j - 1}"
        sign = "+" if pattern[j] > 0 else "-"
        parts.append(f"{_blocks(j, last)} rocking{' as one' if last > j else ''} on "
                     f"{support} ({sign})")
    return ", ".join(parts) + (f" [{CODE_WORDS.format(pattern_name(pattern))}]" if code
                               else "")


def pattern_signs(pattern) -> str:
    """What the signs of a pattern with open interfaces of opposite signs mean, in the
    figure's terms (θⱼ each block's absolute rotation, φⱼ = θⱼ − θⱼ₋₁ its rotation on the
    block below, φ₀ = θ₀); "" for any other pattern, whose signs read as they look.

    A block whose pivot's sign is opposite to the one below turns back relative to that
    block: its φ has the other sign, while its θ (what the figure plots) may still grow
    the same way as the block's below."""
    pattern = tuple(int(s) for s in pattern)
    opened = [(j, s) for j, s in enumerate(pattern) if s != 0]
    turned = [j for (i, s), (j, t) in zip(opened, opened[1:]) if s != t]
    if not turned:
        return ""
    relative = ", ".join(f"φ{j} = θ{j} − θ{j - 1}" for j in turned)
    back = ", ".join(f"block {j} turns back on block {j - 1} (φ{j} {'<' if pattern[j] < 0 else '>'}"
                     f" 0) while θ{j} may still grow the same way as θ{j - 1}" for j in turned)
    return ("the signs are the pivots': + on the upper block's corner at −x (φ > 0), − at +x "
            f"(φ < 0), φ a block's rotation on the one below (φ0 = θ0, {relative}): {back}")
