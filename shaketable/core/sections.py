"""The input sections that scene files and sweep specs share, each parsed here once.

A scene's ``[block]`` and a sweep spec's ``[blocks]`` (and the sweep's ``[stacks]``)
give block sizes and prestress rods the same way; this module reads them for both:
:func:`table_of` (a section must be a table), :func:`quantity` (a value with its unit,
in SI), :func:`rods` (``[block.rods]`` / ``[blocks.rods]``) and :func:`sized_block`
(``"30x6in"``), and the label of a block of a grid in the user's unit
(:func:`length_unit`, :func:`labelled`). Every error is raised as the caller's class (``error``: the scenes'
``SceneError``, the sweeps' ``SweepError``), its message beginning with the file and
naming the key, as ``"scene.toml: block.rods.force: ..."``; the unknown-key check is
:func:`shaketable.core.validation.check_keys`.
"""

from __future__ import annotations

from dataclasses import replace

from shaketable.core.constants import LENGTH_UNITS, length_factor
from shaketable.core.geometry import Block, PrestressRods
from shaketable.core.units import parse
from shaketable.core.validation import check_keys

#: The keys of ``[block.rods]`` (and ``[blocks.rods]``) and the kind of quantity of each.
ROD_KEYS = {"stiffness": "stiffness", "force": "weight", "edge_distance": "length"}


def table_of(value: object, where: str, key: str, error: type = ValueError) -> dict:
    """``value`` if it is a TOML table, else ``error`` naming ``[key]``."""
    if not isinstance(value, dict):
        raise error(f"{where}: [{key}] must be a table, got {value!r}")
    return value


def quantity(value: object, kind: str, where: str, key: str, error: type = ValueError,
             positive: bool = False) -> float:
    """A value with its unit (``"30 in"``) as a number of SI units of ``kind``.

    Parameters
    ----------
    value : str or number
    kind : str
        A kind of :func:`shaketable.core.units.parse` (``"length"``, ``"time"``, ...).
    where, key : str
        The file and the dotted key, for the message.
    error : type
    positive : bool
        Refuse zero and negative values.
    """
    try:
        number = parse(value, kind, where=f"{where}: {key}")
    except ValueError as problem:
        raise error(str(problem)) from None
    if positive and not number > 0:
        raise error(f"{where}: {key} must be positive, got {value!r}")
    return number


def rods(value: object, where: str, key: str, error: type = ValueError) -> PrestressRods:
    """The prestress rods of ``[key]`` (``block.rods`` of a scene, ``blocks.rods`` of a
    sweep): ``stiffness`` [N/m], ``force`` [N] and ``edge_distance`` [m], each with its
    unit (``"0.4 W/in"``, ``"0.4 W"``: W the block's weight)."""
    section = table_of(value, where, key, error)
    check_keys(section, ROD_KEYS, where, f"[{key}]", error)
    missing = set(ROD_KEYS) - set(section)
    if missing:
        raise error(f"{where}: {key} needs {', '.join(sorted(missing))}")
    values = [quantity(section[name], kind, where, f"{key}.{name}", error)
              for name, kind in ROD_KEYS.items()]
    try:
        return PrestressRods(*values)
    except ValueError as problem:
        raise error(f"{where}: {key}: {problem}") from None


def sized_block(text: object, where: str, key: str, rods: PrestressRods | None = None,
                error: type = ValueError) -> Block:
    """The block of a size text such as ``"30x6in"`` (:meth:`Block.parse`), labelled in its
    unit; an error message names ``key`` (``"WHERE: block.size '0x6in': the height must be
    positive"``)."""
    try:
        return Block.parse(text, rods=rods)   # type: ignore[arg-type]
    except (ValueError, TypeError) as problem:
        message = str(problem)
        if message.startswith("block size"):
            message = key + message[len("block size"):]
        else:
            message = f"{key}: {message}"
        raise error(f"{where}: {message}") from None


def length_unit(value: object) -> str | None:
    """The unit of the first length of a grid key (``"2 m"`` or ``["2 m", "3 m"]`` ->
    ``"m"``), None if unknown: the unit a grid's blocks are labelled in."""
    values = value if isinstance(value, list) else [value]
    first = values[0] if values else None
    if not isinstance(first, str):
        return None
    unit = first.strip().lstrip("+-0123456789.eE").strip().lower()
    return unit if unit in LENGTH_UNITS else None


def labelled(block: Block, unit: str | None) -> Block:
    """The block labelled ``H x B unit`` in the user's unit (as :meth:`Block.parse` does);
    as it is for ``unit=None``."""
    if unit is None:
        return block
    factor = length_factor(unit)
    return replace(block, label=f"{block.height / factor:.6g} x {block.width / factor:.6g} "
                                f"{unit}")
