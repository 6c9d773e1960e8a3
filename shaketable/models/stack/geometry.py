"""A column of rigid rectangular blocks, each centred on the one below or offset from it
(input of the stack model)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaketable.core.constants import G
from shaketable.core.geometry import Block, size_words
from shaketable.core.units import format_length
from shaketable.core.validation import number

#: The density a stack's blocks are given when no masses are [kg/m^3]: concrete, as the
#: report's shielding blocks are.
DEFAULT_DENSITY = 2400.0

#: The out-of-plane depth of every block of a stack given no masses [m]: forces and
#: energies are then per metre of depth (the planar model's own measure).
DEFAULT_DEPTH = 1.0

#: Most blocks in one stack (the patterns are enumerated: 3^n candidates at an event).
MAX_BLOCKS = 10


def block_words(index: int, count: int) -> str:
    """``"block 1 (top)"``: a block of a column of ``count`` named as the messages name it
    (counted from 0 at the bottom)."""
    where = " (bottom)" if index == 0 and count > 1 else (
        " (top)" if index == count - 1 and count > 1 else "")
    return f"block {index}{where}"


def overhang_message(blocks) -> str | None:
    """What to say of the first block of ``blocks`` (bottom first) wider than the one below
    it, in the user's units (:meth:`Block.describe`: ``"block 1 (top) (6 x 4 ft) is wider
    than block 0 (bottom) (6 x 2 ft) below it: ..."``); None when no block overhangs."""
    count = len(blocks)
    for index in range(1, count):
        if blocks[index].width > blocks[index - 1].width:
            return (f"{block_words(index, count)} ({blocks[index].describe()}) is wider than "
                    f"{block_words(index - 1, count)} ({blocks[index - 1].describe()}) below "
                    "it: an overhanging block is not offered by the stack model "
                    "(docs/stack.md)")
    return None


@dataclass(frozen=True)
class Stack:
    """A planar column of rigid blocks on the table, block 0 at the bottom.

    Parameters
    ----------
    blocks : sequence of Block or (height, width) pairs
        The blocks from the bottom up [m]. Each rests centred on the one below (or offset
        from it by ``offsets``) and its base must lie on the lower block's top (an
        overhanging upper block would pivot on the lower block's top corner, which this
        model does not describe). Prestress rods are not offered.
    masses : sequence of float, optional
        Mass of each block [kg] (only the ratios enter the motion). By default
        :data:`DEFAULT_DENSITY` (2400 kg/m^3, concrete) over :data:`DEFAULT_DEPTH` (1 m)
        times the block's area B H: forces [N] and energies [J] per metre of depth.
    offsets : sequence of float, optional
        ``n - 1`` values [m], one per block above the bottom one: ``offsets[i - 1]`` is
        ``e_i``, the horizontal distance from the centre of block i - 1 to the centre of
        block i (positive toward +x), at rest. The bottom block's place on the table does
        not enter the model, so it has no offset. Each upper block's base must lie on the
        lower block's top, ``|e_i| + b_i <= b_{i-1}`` (to rounding, 1e-12 of ``b_{i-1}``),
        so that every block above block j lies within ``b_j - b_i`` of its centre and the
        centre of mass of the blocks on each interface lies within its base: the column
        stands at rest. None (the default) or zeros: every block centred on the one below.

    Notes
    -----
    Half sizes ``b_i = B_i / 2``, ``h_i = H_i / 2``; the moment of inertia of block i about
    its centroid is ``m_i (b_i^2 + h_i^2) / 3``. The chain vector from the pivot of block k
    to that of block k + 1 is ``D_k = (s_k b_k - s_{k+1} b_{k+1} + e_{k+1}, 2 h_k)`` in
    block k's frame (``docs/stack.md``). The stack model assumes no sliding and no
    flight (as the report's Section 2.7 does for one block); the result reports the
    friction each contact needs and any tensile contact force.
    """

    blocks: tuple[Block, ...]
    masses: tuple[float, ...] | None = None
    offsets: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        try:
            given = list(self.blocks)
        except TypeError:
            raise TypeError(f"Stack.blocks must be a sequence of Block, got "
                            f"{type(self.blocks).__name__}")
        if not given:
            raise ValueError("Stack.blocks must hold at least one block, got none")
        if len(given) > MAX_BLOCKS:
            raise ValueError(f"Stack.blocks holds {len(given)} blocks; at most {MAX_BLOCKS}")
        blocks: list[Block] = []
        for index, item in enumerate(given):
            name = f"Stack.blocks[{index}]"
            if isinstance(item, Block):
                block = item
            elif isinstance(item, (tuple, list)) and len(item) == 2:
                height = number(f"{name} height", item[0])
                width = number(f"{name} width", item[1])
                for what, value in (("height", height), ("width", width)):
                    if not value > 0:
                        raise ValueError(f"{name} {what} must be positive [m], got {value!r}")
                try:
                    block = Block(height, width)
                except ValueError as error:
                    raise ValueError(f"{name}: {error}") from None
            else:
                raise TypeError(f"{name} must be a Block or a (height, width) pair [m], "
                                f"got {item!r}")
            if block.rods is not None:
                raise ValueError(f"{name}.rods: prestress rods are not offered in a stack")
            if blocks and block.width > blocks[-1].width and self.offsets is None:
                raise ValueError(
                    f"{name}.width ({block.width!r} m) is wider than the block below "
                    f"(Stack.blocks[{index - 1}].width = {blocks[-1].width!r} m): an "
                    "overhanging block is not offered by the stack model")
            blocks.append(block)
        object.__setattr__(self, "blocks", tuple(blocks))
        if self.masses is not None:
            self._check_masses()
        if self.offsets is not None:
            self._check_offsets()

    def _check_masses(self) -> None:
        """Validate and store :attr:`masses` (see the class's docstring)."""
        blocks = self.blocks
        try:
            masses = [number(f"Stack.masses[{i}]", m)
                      for i, m in enumerate(self.masses)]   # type: ignore[arg-type]
        except TypeError:
            raise TypeError(f"Stack.masses must be a sequence of numbers [kg], got "
                            f"{self.masses!r}")
        if len(masses) != len(blocks):
            raise ValueError(f"Stack.masses has {len(masses)} values for {len(blocks)} blocks")
        for index, mass in enumerate(masses):
            if not (mass > 0 and math.isfinite(mass)):
                raise ValueError(f"Stack.masses[{index}] must be a positive finite mass [kg], "
                                 f"got {mass!r}")
        object.__setattr__(self, "masses", tuple(masses))

    def _check_offsets(self) -> None:
        """Validate and store :attr:`offsets` (see the class's docstring)."""
        blocks, count = self.blocks, len(self.blocks)
        try:
            given = list(self.offsets)   # type: ignore[arg-type]
        except TypeError:
            raise TypeError(f"Stack.offsets must be a sequence of numbers [m], got "
                            f"{self.offsets!r}") from None
        if len(given) != count - 1:
            raise ValueError(f"Stack.offsets has {len(given)} values for {count} blocks: give "
                             f"{count - 1}, one per block above the bottom one (offsets[i - 1] "
                             "is block i's offset from the centre of block i - 1) [m]")
        offsets = []
        for index, value in enumerate(given):
            name = f"Stack.offsets[{index}] ({block_words(index + 1, count)})"
            offset = number(name, value)   # a finite real, else a ValueError naming it
            lower, upper = blocks[index].b, blocks[index + 1].b
            if abs(offset) + upper > lower * (1.0 + 1e-12):
                raise ValueError(
                    f"{name} = {offset!r} m puts the base of {block_words(index + 1, count)} "
                    f"(half width {upper!r} m) past the top of {block_words(index, count)} "
                    f"(half width {lower!r} m): |offset| + b_{index + 1} must be at most "
                    f"b_{index}, an overhanging block is not offered by the stack model")
            offsets.append(offset)
        object.__setattr__(self, "offsets", tuple(offsets))

    @property
    def e(self) -> np.ndarray:
        """Each block's offset from the centre of the block below [m], bottom first (0 for
        the bottom block; zeros without :attr:`offsets`)."""
        if self.offsets is None:
            return np.zeros(self.n)
        return np.concatenate([[0.0], np.array(self.offsets, dtype=float)])

    @property
    def centres(self) -> np.ndarray:
        """Each block's centre at rest from the bottom block's centre, horizontally [m]
        (the running sums of :attr:`e`)."""
        return np.cumsum(self.e)

    @property
    def n(self) -> int:
        """Number of blocks."""
        return len(self.blocks)

    @property
    def b(self) -> np.ndarray:
        """Half widths [m], bottom first."""
        return np.array([block.b for block in self.blocks])

    @property
    def h(self) -> np.ndarray:
        """Half heights [m], bottom first."""
        return np.array([block.h for block in self.blocks])

    @property
    def m(self) -> np.ndarray:
        """The masses the equations of motion use: the given ones [kg], or the areas B H
        [m^2] when none were given (only their ratios enter the motion; times
        :attr:`mass_scale` they are the masses in kg, :attr:`mass`)."""
        if self.masses is None:
            return np.array([block.width * block.height for block in self.blocks])
        return np.array(self.masses, dtype=float)

    @property
    def mass_scale(self) -> float:
        """:attr:`mass` over :attr:`m` [kg per unit of m]: 1 for given masses, else
        :data:`DEFAULT_DENSITY` times :data:`DEFAULT_DEPTH` [kg/m^2] (forces, work and
        energies of a run are scaled by it; the motion is not)."""
        return 1.0 if self.masses is not None else DEFAULT_DENSITY * DEFAULT_DEPTH

    @property
    def mass(self) -> np.ndarray:
        """Each block's mass [kg], bottom first: the given masses, else
        :data:`DEFAULT_DENSITY` x :data:`DEFAULT_DEPTH` x B H."""
        return self.m * self.mass_scale

    def describe_masses(self) -> str:
        """Which masses the run used, in words: ``"masses: uniform density, assumed 2400
        kg/m^3 (concrete) over 1 m of depth: 0.279, 0.279 kg (forces and energies per metre
        of depth)"`` or ``"masses: 400, 200 kg (given)"``."""
        values = ", ".join(f"{mass:.4g}" for mass in self.mass)
        if self.masses is not None:
            return f"masses: {values} kg (given, bottom first)"
        return (f"masses: uniform density, assumed {DEFAULT_DENSITY:g} kg/m^3 (concrete) over "
                f"{DEFAULT_DEPTH:g} m of depth: {values} kg, bottom first (forces and "
                "energies per metre of depth; give masses or densities for yours)")

    @property
    def p_max(self) -> float:
        """Largest frequency parameter sqrt(3 g / 4 R_i) of the blocks [rad/s]."""
        return max(block.p for block in self.blocks)

    @property
    def alpha_min(self) -> float:
        """Smallest block angle atan(b_i / h_i) [rad]."""
        return min(block.alpha for block in self.blocks)

    @property
    def weight(self) -> float:
        """Total weight [N] (g times the sum of the masses, :attr:`mass`)."""
        return float(G * self.mass.sum())

    def describe(self) -> str:
        """``"2 blocks: 30 x 6 in on 30 x 6 in"``-like text, top first; with non-zero
        offsets, ``"2 blocks: 30 x 6 in offset +2.00 in on 30 x 6 in"`` (each block's
        offset from the centre of the one below, in the bottom block's length unit)."""
        sizes = [size_words(block) for block in self.blocks]
        if self.offsets is not None and any(self.offsets):
            unit = self.blocks[0].length_unit
            for index, offset in enumerate(self.offsets, start=1):
                if offset:
                    sizes[index] += f" offset {format_length(offset, unit, signed=True)}"
        return f"{self.n} block{'s' if self.n > 1 else ''}: " + " on ".join(reversed(sizes))
