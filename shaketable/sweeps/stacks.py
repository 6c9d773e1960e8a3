"""Stacks as a sweep axis: ``[stacks]`` runs every cell with the stack model.

A sweep spec (:mod:`shaketable.sweeps.spec`) with a ``[stacks]`` section (or
``model = "stack"``) runs a column of rigid blocks in each cell instead of one block, with
:func:`shaketable.models.stack.simulate_stack` (the plastic multi-contact impact law by
default; ``docs/stack.md``). The stacks take the place of ``[blocks]`` in the grid::

    model = "stack"               # optional: [stacks] chooses it
    [stacks]
    sizes = ["30x6in", "60x12in"] # every block of a column this size (bottom to top) ...
    blocks = [2, 3]               # ... and this many blocks: an axis of its own (default 2)
    # columns = [["60x12in", "30x6in"]]   # or explicit columns, bottom first
    mass_ratios = [1.0, 0.5]      # optional: each block's mass over the one below's [-]
    #                             #   (default: 2400 kg/m^3 over 1 m of depth)

    [rocking]                     # optional for stacks
    cor = "plastic"               # the default; or numbers [-]: the constant-COR law,
    #                             # or a list mixing both, ["plastic", 0.9]
    # rtol = 1e-10                # the stack engine's relative tolerance (default 1e-12);
    #                             # duration = "30 s"

The grid's order: each size (or column), then the number of blocks, then the mass ratio
(fastest); in the run order the stacks stand where the blocks stand (record, pitch phase,
intensity, stack, COR). Each stack is labelled in the ``block`` column as
:meth:`Stack.describe` writes it, top first (``"2 blocks: 30 x 6 in on 30 x 6 in"``),
with ``", mass ratio 0.5"`` when a ratio is given.

Each row keeps the input columns of a rocking sweep (record, scale, PGA, COR, intensity
measures, ...; ``R [m]`` and the block-normalised measures ``pga/(g tan a)`` and ``pgv
p/(g tan a)`` are those of the BOTTOM block) and gains ``blocks``, ``mass ratio [-]``
(NaN: one density, or a block alone), ``stack height [m]``, ``base width [m]``, ``impact`` (``"plastic"``
or ``"cor"``; ``cor [-]`` is NaN with the plastic law), ``status``, ``overturned`` (some
block fell), ``overturned block`` (the block that fell, numbered from 0 at the bottom;
-1 if none), ``verdict`` (:meth:`StackResult.verdict`), ``t_overturn [s]``,
``max_theta_ratio [-]`` (the largest max |theta_i| / alpha_i over the blocks, NaN when
overturned), ``max |theta| bottom [rad]``, ``max |theta| top [rad]`` (these peaks, and the
top corner's, read at the record's samples: the stack's output times), ``t_start [s]``,
``n_impacts``, ``peak top-corner excursion [m]``, ``max F/N [-]``,
``t_friction_exceeded [s]`` (the first time a contact needs more friction than
:data:`~shaketable.models.stack.PLAUSIBLE_FRICTION`: the no-slip assumption fails there),
``t_tension [s]`` and ``airborne``. The model's warnings are not raised in a sweep: these
columns carry them, and ``rtol [-]`` the tolerance each run was computed at (tighter than
``rocking.rtol`` for a run that stalled at it and was made again; ``sweep``'s summary
counts them: :func:`retried_line`). A run that stalled at every tolerance tried does not
stop the sweep: its row has the status ``"stalled"``, the engine's message in ``verdict``
and NaN results (:mod:`shaketable.models.stack.batch`); it is neither a fall nor a
survival, so the fragility fits, ``risk`` and the summaries leave it out and say how many
they left out (:func:`finished_runs`, :func:`stalled_line`).

What the stack model does not take is refused when the spec is read, naming the key:
``[pitch]``, ``[ensemble]``, ``[friction]``, ``rocking.method`` other than ``"fast"``,
``rocking.subdivisions`` and ``rocking.theta0`` (every run starts from rest). The runs of
a chunk are computed one after the other by the stack batch
(:func:`shaketable.models.stack.batch.simulate_cases`: the compiled engine, the rows
from its arrays, no result objects); ``--workers N`` (``run_sweep(workers=N)``) computes
N chunks at once in processes of their own, so give ``[run] chunk_size`` small enough for
several chunks. The table is the same whatever the number of workers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import product
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core import sections
from shaketable.core.equality import fields_equal
from shaketable.core.validation import check_keys, count
from shaketable.sweeps.base import SweepError
from shaketable.sweeps.models import RockingSweep

if TYPE_CHECKING:
    import pandas as pd

    from shaketable.sweeps.spec import SweepSpec

#: Keys of ``[stacks]``.
STACK_KEYS = {"sizes", "blocks", "columns", "mass_ratios"}

#: The stack engine's relative tolerance in a sweep without ``rocking.rtol`` (its DOP853
#: steps of several moving bodies and its RKN6(4) steps of one, :mod:`~shaketable.models.stack`).
DEFAULT_STACK_RTOL = 1e-12


@dataclass(frozen=True)
class StackCase:
    """One run of a stack sweep: the stack, the unscaled motion, the COR (NaN: the plastic
    law), the scale factor and the labels of the table."""

    __eq__ = fields_equal   # NaN (the plastic law) equal to NaN; equal after a pickle

    stack: Any
    motion: Any
    cor: float
    scale: float = 1.0
    block_label: str = ""
    motion_label: str = ""


def stacks_grid(table: object, where: str) -> tuple[list, list]:
    """The stacks of ``[stacks]`` and, for each, the grid values that made it.

    Returns
    -------
    stacks : list of Stack
    inputs : list of dict
        ``size`` (the size text, or the column's list), ``blocks`` and ``mass ratio``.
    """
    from shaketable.models.stack import Stack
    from shaketable.models.stack.geometry import MAX_BLOCKS, overhang_message

    table = sections.table_of(table, where, "stacks", SweepError)
    check_keys(table, STACK_KEYS, where, "[stacks]", SweepError)
    if ("sizes" in table) == ("columns" in table):
        raise SweepError(f"{where}: [stacks] needs exactly one of stacks.sizes (block sizes, "
                         "each stacked stacks.blocks high) or stacks.columns (explicit "
                         "columns of sizes, bottom first)")
    columns: list[tuple[Any, list]] = []
    if "sizes" in table:
        counts = []
        for value in _as_list(table.get("blocks", 2)):
            number = _checked(count, f"{where}: stacks.blocks", value, 1)
            if number > MAX_BLOCKS:
                raise SweepError(f"{where}: stacks.blocks must be at most {MAX_BLOCKS}, got "
                                 f"{number!r}")
            counts.append(number)
        sizes = _non_empty(table["sizes"], where, "stacks.sizes")
        for text, number in product(sizes, counts):
            block = sections.sized_block(text, where, "stacks.sizes", None, SweepError)
            columns.append((text, [block] * number))
    else:
        if "blocks" in table:
            raise SweepError(f"{where}: stacks.blocks goes with stacks.sizes; a column of "
                             "stacks.columns has its own number of blocks")
        for column in _non_empty(table["columns"], where, "stacks.columns"):
            if not isinstance(column, list) or not column:
                raise SweepError(f"{where}: stacks.columns must be lists of block sizes, "
                                 f"bottom first, such as [\"60x12in\", \"30x6in\"], got "
                                 f"{column!r}")
            blocks = [sections.sized_block(text, where, "stacks.columns", None, SweepError)
                      for text in column]
            overhang = overhang_message(blocks)
            if overhang is not None:   # in the user's units, as simulate --stack says it
                raise SweepError(f"{where}: stacks.columns {', '.join(map(str, column))}: "
                                 f"{overhang}")
            columns.append((list(column), blocks))
    ratios: list = [None]
    if "mass_ratios" in table:
        ratios = []
        for value in _non_empty(table["mass_ratios"], where, "stacks.mass_ratios"):
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not (value > 0 and math.isfinite(value)):
                raise SweepError(f"{where}: stacks.mass_ratios must be positive numbers [-] "
                                 f"(each block's mass over the one below's), got {value!r}")
            ratios.append(float(value))
    stacks, inputs = [], []
    for (size, blocks), ratio in product(columns, ratios):
        masses = None if ratio is None else tuple(ratio ** i for i in range(len(blocks)))
        try:
            stack = Stack(tuple(blocks), masses)
        except ValueError as error:
            raise SweepError(f"{where}: [stacks] {size!r}: {error}") from None
        stacks.append(stack)
        inputs.append({"size": size, "blocks": len(blocks),   # one block: no ratio
                       "mass ratio": math.nan if ratio is None or len(blocks) < 2 else ratio})
    return stacks, inputs


def stack_cors(rocking: dict, where: str) -> tuple:
    """``rocking.cor`` of a stack sweep: NaN for ``"plastic"`` (the default), else the
    constant COR [-] in [0, 1]."""
    values = _as_list(rocking.get("cor", "plastic"))
    if not values:
        raise SweepError(f"{where}: rocking.cor must not be an empty list")
    cors = []
    for value in values:
        if value == "plastic":
            cors.append(math.nan)
        elif isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not 0.0 <= value <= 1.0:
            raise SweepError(f"{where}: rocking.cor of a stack sweep must be \"plastic\" (the "
                             f"plastic multi-contact law) or a number in [0, 1] (the "
                             f"constant-COR law), or a list of them, got {value!r}")
        else:
            cors.append(float(value))
    if len(set(map(str, cors))) != len(cors):
        raise SweepError(f"{where}: rocking.cor lists {values!r}: a value twice")
    return tuple(cors)


@dataclass(frozen=True)
class StackSweep(RockingSweep):
    """A column of rigid blocks (:mod:`shaketable.models.stack`) in each cell."""

    name: str = "stack"
    processes = True   # a chunk's runs on one thread: --workers N runs N chunks at once

    def manifest(self) -> dict:
        return {"model": {"model": "stack (a column of rigid blocks; no sliding, no flight)",
                          "default rtol": DEFAULT_STACK_RTOL}}

    def check(self, spec: SweepSpec, rocking: dict) -> None:
        where = spec.path
        for section, present in (("pitch", spec.pitch is not None),
                                 ("ensemble", spec.ensemble is not None)):
            if present:
                raise SweepError(f"{where}: [{section}] with [stacks] is not offered (the "
                                 "stack model runs one column on a table that translates)")
        if spec.method != "fast":
            raise SweepError(f"{where}: rocking.method {spec.method!r} with [stacks]: the "
                             "stack model has its own engine; give method = \"fast\" or none")
        for key in ("subdivisions", "theta0"):
            if key in rocking:
                raise SweepError(f"{where}: rocking.{key} with [stacks]: the stack model "
                                 "starts every run from rest")
        if not 1e-14 <= spec.options.get("rtol", DEFAULT_STACK_RTOL) <= 1e-3:
            raise SweepError(f"{where}: rocking.rtol with [stacks] must be in [1e-14, 1e-3] "
                             f"(the stack engine's relative tolerance), got "
                             f"{spec.options['rtol']!r}")

    def describe(self) -> str | None:
        return ("[stacks]: the stack model (a column of rigid blocks; plastic or constant-COR "
                "impacts), a chunk's runs one after the other (--workers N: N chunks at once)")

    def case(self, subject: Any, motion: Any, cor: float, scale: float, block_label: str,
             motion_label: str) -> Any:
        return StackCase(subject, motion, cor, scale, block_label, motion_label)

    def lead_block(self, subject: Any) -> Any:
        return subject.blocks[0]

    def label(self, subject: Any) -> str:
        """:meth:`Stack.describe`, and the mass ratio when the masses were given."""
        text = subject.describe()
        if subject.masses is None or subject.n < 2:
            return text
        return f"{text}, mass ratio {subject.masses[1] / subject.masses[0]:g}"

    def simulate(self, spec: SweepSpec, inputs: pd.DataFrame, cases: list,
                 threads: int | None) -> tuple:
        return simulate_stacks(spec, inputs, cases), None


def simulate_stacks(spec: SweepSpec, inputs: pd.DataFrame, cases: list) -> pd.DataFrame:
    """The rows of a chunk of a stack sweep (one per case), in order.

    A row's results are those of ``simulate_stack(stack, extended(motion.scaled(scale),
    duration), impact=..., cor=..., rtol=rtol)`` whatever the chunking (each run is on its
    own), taken from the stack batch (:func:`shaketable.models.stack.batch.simulate_cases`,
    one thread: the engine's arrays, no result objects).
    """
    import warnings

    import pandas as pd

    from shaketable.models.stack import StackRetryWarning, StackStalledWarning
    from shaketable.models.stack.batch import Case, simulate_cases

    rtol = spec.options.get("rtol", DEFAULT_STACK_RTOL)
    with warnings.catch_warnings():   # a retried or stalled run: its row says it (summary)
        warnings.simplefilter("ignore", StackRetryWarning)
        warnings.simplefilter("ignore", StackStalledWarning)
        batch = simulate_cases([Case(case.stack, case.motion,
                                     None if math.isnan(case.cor) else case.cor, case.scale,
                                     case.block_label, case.motion_label) for case in cases],
                               threads=1, rtol=rtol, duration=spec.duration)
    rows = []
    for k, (case, result) in enumerate(zip(cases, batch.to_dict("records"))):
        stack = case.stack
        rows.append({
            "block": case.block_label, "blocks": stack.n,
            "mass ratio [-]": spec.block_inputs[inputs["block_index"].iloc[k]]["mass ratio"],
            "stack height [m]": float(sum(block.height for block in stack.blocks)),
            "base width [m]": float(stack.blocks[0].width),
            "motion": case.motion_label, "scale [-]": float(case.scale),
            "pga [m/s^2]": case.motion.pga * float(case.scale),
            "motion_vertical": case.motion.vertical is not None,
            "duration [s]": result["duration [s]"], "impact": result["impact"],
            "cor [-]": float(case.cor), "method": "stack", "rtol [-]": result["rtol [-]"],
            **{name: result[name] for name in _BATCH_COLUMNS},
            "block_index": int(inputs["block_index"].iloc[k]),
            "motion_index": result["motion_index"],
        })
    table = pd.DataFrame(rows)
    table["n_impacts"] = table["n_impacts"].astype(np.int64)
    return table.set_index(inputs.index)


#: The columns of a stack sweep's rows that the stack batch gives, in the rows' order.
_BATCH_COLUMNS = ("status", "overturned", "overturned block", "verdict", "t_overturn [s]",
                  "max_theta_ratio [-]", "max |theta| bottom [rad]", "max |theta| top [rad]",
                  "t_start [s]", "n_impacts", "peak top-corner excursion [m]", "max F/N [-]",
                  "t_friction_exceeded [s]", "t_tension [s]", "airborne")


#: The status of a stack run that stalled at every tolerance tried (no results).
STALLED = "stalled"


def finished_runs(rows):
    """The rows of a stack sweep without the runs that stalled (:data:`STALLED`: neither a
    fall nor a survival, so no fragility counts them); the rows themselves when none did or
    the table has no ``status``."""
    if "status" not in rows:
        return rows
    stalled = (rows["status"] == STALLED).to_numpy()
    return rows[~stalled] if stalled.any() else rows


def stalled_line(rows) -> str:
    """``"1 of 40 runs stalled (excluded)"``: how many runs of a stack sweep's rows stalled
    and were left out of the counts and fits; "" when none did."""
    if "status" not in rows or not len(rows):
        return ""
    stalled = int((rows["status"] == STALLED).sum())
    return f"{stalled} of {len(rows)} runs stalled (excluded)" if stalled else ""


def overturned_blocks(table) -> str:
    """Which block fell in the overturned runs of a stack sweep's rows, top first:
    ``"block 1 (top) 5, block 0 (bottom) 2"`` (``"a block alone 3"``: the columns of one
    block; "" for another sweep's table). Rows of columns of several heights name each
    column: ``"2 high: block 0 (bottom) 4; 3 high: block 2 (top) 1, block 0 (bottom) 4"``."""
    if "overturned block" not in table or "blocks" not in table:
        return ""
    fell = table[table["overturned"].astype(bool)]
    heights = {int(blocks) for blocks in fell["blocks"] if int(blocks) > 1}
    named = len(heights) > 1
    parts: dict = {}
    for (blocks, index), rows in sorted(fell.groupby(["blocks", "overturned block"]),
                                        key=lambda item: ((item[0][0], -item[0][1]) if named
                                                          else (-item[0][1], item[0][0]))):
        blocks, index = int(blocks), int(index)
        name = "a block alone" if blocks == 1 else f"block {index}" + (
            " (bottom)" if index == 0 else " (top)" if index == blocks - 1 else "")
        parts.setdefault(blocks if named else 0, []).append(f"{name} {len(rows)}")
    if not named:
        return ", ".join(parts.get(0, []))
    return "; ".join(", ".join(words) if blocks == 1 else f"{blocks} high: {', '.join(words)}"
                     for blocks, words in parts.items())


def overturned_line(rows) -> str:
    """How many of one sweep group's runs overturned, and, for a stack, which block fell:
    ``"overturned in 9 of 14 runs (a block alone)"``, ``"overturned in 14 of 20 runs; the
    block that fell: block 1 (top) 1, block 0 (bottom) 13"`` ("" for another sweep's
    rows). A block alone has no "block that fell": its count is said apart. Runs that
    stalled are not counted: ``"...; 1 of 15 runs stalled (excluded)"``."""
    if "overturned block" not in rows or "blocks" not in rows or not len(rows):
        return ""
    stalled = stalled_line(rows)
    finished = finished_runs(rows)
    count = (f"overturned in {int(finished['overturned'].astype(bool).sum())} of "
             f"{len(finished)} runs")
    if (rows["blocks"].astype(int) == 1).all():
        return count + " (a block alone)" + (f"; {stalled}" if stalled else "")
    which = overturned_blocks(finished[finished["blocks"].astype(int) > 1])
    return (count + (f"; the block that fell: {which}" if which else "")
            + (f"; {stalled}" if stalled else ""))


def overturn_answer(table) -> str:
    """How many runs of a stack sweep overturn, the stacks and the blocks alone apart:
    ``"23 of 40 runs overturn: 14 stacks (the block that fell: block 1 (top) 1, block 0
    (bottom) 13) and 9 blocks alone"``; the runs that stalled are left out and said:
    ``"..., 1 of 41 runs stalled (excluded)"``."""
    stalled = stalled_line(table)
    table = finished_runs(table)
    fell = table[table["overturned"].astype(bool)]
    parts = []
    stacks = fell[fell["blocks"].astype(int) > 1] if "blocks" in fell else fell
    if len(stacks):
        which = overturned_blocks(stacks)
        parts.append(f"{len(stacks)} stack{'s' if len(stacks) != 1 else ''}"
                     + (f" (the block that fell: {which})" if which else ""))
    alone = len(fell) - len(stacks)
    if alone:
        parts.append(f"{alone} block{'s' if alone != 1 else ''} alone")
    return (f"{len(fell)} of {len(table)} runs overturn"
            + (": " + " and ".join(parts) if parts else "")
            + (f"; {stalled}" if stalled else ""))


def retried_line(table, rtol: float) -> str:
    """How many runs of a stack sweep were computed at a tighter tolerance than the spec's
    ``rtol`` (a stall in the chatter of a contact at its uplift threshold, run again:
    :func:`~shaketable.models.stack.model.integrate_retrying`), from the rows' ``rtol [-]``:
    ``"2 of 40 runs stalled at the spec's rtol 1e-10 and were computed again at a tighter
    one (1e-11; the rtol [-] column)"``; "" when none was."""
    if "rtol [-]" not in table or not len(table):
        return ""
    used = table["rtol [-]"].astype(float)
    tighter = used[used < rtol]
    if tighter.empty:
        return ""
    values = ", ".join(f"{value:g}" for value in sorted(set(tighter), reverse=True))
    return (f"{len(tighter)} of {len(table)} runs stalled at the spec's rtol {rtol:g} and "
            f"were computed again at a tighter one ({values}; the rtol [-] column)")


def impact_law(cor: float) -> str:
    """The impact law of a row's ``cor [-]``, for labels: ``"plastic impacts"`` (NaN: the
    plastic multi-contact law has no COR) or ``"COR 0.9"``."""
    return "plastic impacts" if math.isnan(cor) else f"COR {cor:g}"


def law_token(cor: float) -> str:
    """The impact law in a file name: ``"plastic"`` or ``"cor0.9"``."""
    return "plastic" if math.isnan(cor) else f"cor{cor:g}"


def stack_medians(rows, measure: str) -> dict:
    """The lognormal fit of "some block fell" of each stack (``block`` column) of one
    impact law, and its median as a share of the block alone's.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of a stack sweep's table with one impact law (the runs that stalled are left
        out: :func:`finished_runs`; a stack whose runs all stalled has no entry).
    measure : str
        The intensity measure (:func:`shaketable.sweeps.fragility.measure_column`).

    Returns
    -------
    dict
        Each stack's label to ``{"fit": FragilityFit or None, "why": the reason there is
        no fit ("" with one), "share of alone": median / the median of the one-block
        column of the same bottom block (same ``R [m]`` and ``base width [m]``) [-], NaN
        without one}``.
    """
    from shaketable.sweeps.fragility import fragility_fit, measure_column

    column = measure_column(rows, measure)
    found: dict = {}
    for name, part in finished_runs(rows).groupby("block", sort=False):
        try:
            fit, why = fragility_fit(part[column], part["overturned"].astype(bool).to_numpy(),
                                     measure=column, intervals=False), ""
        except ValueError as error:
            fit, why = None, _short_reason(str(error))
        found[name] = {"fit": fit, "why": why, "bottom": (round(float(part["R [m]"].iloc[0]), 9),
                                                          round(float(part["base width [m]"]
                                                                      .iloc[0]), 9)),
                       "blocks": int(part["blocks"].iloc[0])}
    alone = {entry["bottom"]: entry["fit"] for entry in found.values() if entry["blocks"] == 1}
    for entry in found.values():
        single = alone.get(entry["bottom"])
        entry["share of alone"] = (entry["fit"].median / single.median
                                   if entry["fit"] is not None and single is not None
                                   and entry["blocks"] > 1 else math.nan)
        del entry["bottom"], entry["blocks"]
    return found


def _short_reason(message: str) -> str:
    """The reason of a fit's ValueError in a few words, for a legend."""
    lowered = message.lower()
    if "no run overturned" in lowered:
        return "none fell"
    if "every run overturned" in lowered:
        return "all fell"
    if "separated" in lowered:
        return "outcomes separated by the measure"
    return message.split(";")[0][:60]


def first_to_fall_fits(rows, measure: str, *, intervals: bool = True) -> dict:
    """Lognormal fragilities of one stack's rows (one stack and impact law): of "some
    block fell" (the ``overturned`` column) and of each block that was the one to fall
    (``overturned block == j``: the run stops at the first block that falls), by name.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of a stack sweep's table for one stack (the runs that stalled are left out:
        :func:`finished_runs`).
    measure : str
        The intensity measure (:func:`shaketable.sweeps.fragility.measure_column`).
    intervals : bool
        Profile-likelihood intervals too (:func:`~shaketable.sweeps.fragility.fragility_fit`).

    Returns
    -------
    dict
        ``"any block"`` and ``"block j ..."`` to a
        :class:`~shaketable.sweeps.fragility.FragilityFit`, or to the ValueError's message
        when that outcome cannot be fitted (it never or always happened, or it is
        separated by the measure).
    """
    from shaketable.sweeps.fragility import fragility_fit, measure_column

    rows = finished_runs(rows)
    column = measure_column(rows, measure)
    blocks = rows["blocks"].unique()
    if len(blocks) != 1:
        raise ValueError(f"first_to_fall_fits: the rows hold stacks of {sorted(blocks)} "
                         "blocks; select one stack first")
    n = int(blocks[0])
    outcomes = {"any block": rows["overturned"].astype(bool)}
    for index in range(n - 1, -1, -1):
        name = f"block {index}" + (" (bottom)" if index == 0 and n > 1 else
                                   " (top)" if index == n - 1 and n > 1 else "")
        outcomes[name] = rows["overturned block"] == index
    fits: dict = {}
    for name, outcome in outcomes.items():
        try:
            fits[name] = fragility_fit(rows[column], outcome.to_numpy(), measure=column,
                                       intervals=intervals)
        except ValueError as error:
            fits[name] = str(error)
    return fits


def _as_list(value) -> list:
    return value if isinstance(value, list) else [value]


def _non_empty(value, where: str, key: str) -> list:
    values = _as_list(value)
    if not values:
        raise SweepError(f"{where}: {key} must not be an empty list")
    return values


def _checked(check, name: str, *args):
    try:
        return check(name, *args)
    except ValueError as error:
        raise SweepError(str(error)) from None
