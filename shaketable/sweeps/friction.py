"""Friction as a sweep axis: ``[friction]`` runs every cell with the coupled planar model.

A sweep spec (:mod:`shaketable.sweeps.spec`) with a ``[friction]`` section runs each
cell with the coupled model of the whole planar block -- rest, slide, rock, slide-rock
and free flight with Coulomb friction (``docs/planar.md``) -- compiled, through
:func:`shaketable.models.planar.batch.simulate_many_planar`, instead of the rocking
batch. Friction coefficients are dimensionless: plain numbers, no unit::

    [friction]
    static = [0.2, 0.3, 0.5]      # mu_s [-]: a number or a list
    # and at most one of (default: mu_d = mu_s, "same as static"):
    # dynamic_ratio = 0.8         #   mu_d = 0.8 mu_s; a number or a list in [0, 1]
    # dynamic = [0.15, 0.2]       #   mu_d [-], an axis of its own: every (mu_s, mu_d)
    #                             #   combination, each with mu_d <= mu_s

The friction pairs (mu_s, mu_d) are an axis of the grid between the block and the COR:
the run order is record realisation, pitch phase, intensity, block, friction, COR (the
last varying fastest), mu_s slower than mu_d (or than the ratio). A sweep without
``[friction]`` is untouched: same runs, same rows, same store.

What the coupled model does not take is refused when the spec is read, naming the key:
``[blocks.rods]`` (a rod hinged to the ground ties the block to the table),
``[pitch]`` (the model has no table rotation), ``[ensemble]``, ``rocking.method`` other
than ``"fast"`` (the model has its own engine), ``rocking.subdivisions`` and
``rocking.theta0`` (every run starts from rest), and a numeric COR on a block with
B/H = sqrt(2) (where Housner's c_H is 0). ``rocking.rtol`` is the planar engine's DOP853
tolerance (default 1e-12, :data:`shaketable.models.planar.run.DEFAULT_PLANAR_RTOL`).

Each row keeps the input columns of a rocking sweep (record, scale, PGA, block, COR,
intensity measures, ...) and gains ``static friction mu_s [-]``, ``dynamic friction mu_d
[-]``, ``verdict`` (stayed, slid, rocked, slide-rocked, flew, overturned: the largest mode
visited), ``peak slip [m]``, ``residual slip [m]`` (of the base's midpoint, relative to
the table), ``peak corner excursion [m]`` (the clearance the block needs), ``time rest
[s]`` ... ``time flight [s]``; ``status``, ``overturned``, ``max_theta_ratio [-]`` (NaN
when overturned), ``t_overturn [s]`` and ``n_impacts`` mean what they mean in a rocking
sweep. The rocking engine's diagnostics (``airborne``, ``t_start``, solver work ...)
are not written. The manifest records the friction grid, so a resume with other
friction (or with none) is refused by name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from shaketable.core.validation import check_keys
from shaketable.sweeps.base import SweepError

if TYPE_CHECKING:
    import pandas as pd

    from shaketable.sweeps.spec import SweepSpec

#: Keys of ``[friction]``.
FRICTION_KEYS = {"static", "dynamic", "dynamic_ratio"}

#: Table columns of the two coefficients (the names of
#: :func:`~shaketable.models.planar.batch.simulate_many_planar` and ``PlanarResult.summary``).
STATIC_COLUMN, DYNAMIC_COLUMN = "static friction mu_s [-]", "dynamic friction mu_d [-]"

#: Columns of the planar batch copied into a sweep row, in this order.
PLANAR_COLUMNS = ("status", "verdict", "max_theta_ratio [-]", "peak slip [m]",
                  "residual slip [m]", "peak corner excursion [m]", "t_overturn [s]",
                  "n_impacts", "time rest [s]", "time slide [s]", "time rock [s]",
                  "time slide-rock [s]", "time flight [s]")

#: Verdicts in the order of the modes (as :data:`shaketable.models.planar.result.VERDICTS`),
#: overturned last.
VERDICT_ORDER = ("stayed", "slid", "rocked", "slide-rocked", "flew", "overturned")


@dataclass(frozen=True)
class FrictionGrid:
    """The ``[friction]`` section: the (mu_s, mu_d) pairs of the axis, in run order.

    Attributes
    ----------
    pairs : tuple of (float, float)
        Static and dynamic coefficients [-], mu_s slower.
    rule : str
        How mu_d was given: ``"same"`` (mu_d = mu_s), ``"ratio"`` or ``"explicit"``.
    """

    pairs: tuple
    rule: str = "same"

    def manifest(self) -> dict:
        """What a sweep folder records (a resume with another grid is refused)."""
        from shaketable.models.planar.run import DEFAULT_PLANAR_RTOL

        return {"model": "planar (rest, slide, rock, slide-rock, flight)",
                "pairs (mu_s, mu_d)": [list(pair) for pair in self.pairs],
                "rule": self.rule, "default rtol": DEFAULT_PLANAR_RTOL}


def _coefficients(value, where: str, key: str, high: float = math.inf) -> list:
    """Plain numbers in [0, high]: a number or a non-empty list; the message names the key."""
    values = value if isinstance(value, list) else [value]
    if not values:
        raise SweepError(f"{where}: {key} must not be an empty list")
    result = []
    for item in values:
        if isinstance(item, str):
            raise SweepError(f"{where}: {key} is a friction coefficient, dimensionless: give "
                             f"a plain number such as 0.3 (no unit, not text), got {item!r}")
        if isinstance(item, bool) or not isinstance(item, (int, float)) \
                or not math.isfinite(item) or not 0.0 <= item <= high:
            interval = "0 or more" if high == math.inf else f"in [0, {high:g}]"
            raise SweepError(f"{where}: {key} must be a finite number {interval} [-] or a list "
                             f"of them, got {item!r}")
        result.append(float(item))
    if len(set(result)) != len(result):
        raise SweepError(f"{where}: {key} lists {result!r}: a value twice (one run per value)")
    return result


def friction_grid(table, where: str) -> FrictionGrid | None:
    """Read ``[friction]`` (``None`` when absent); SweepError naming the file and the key."""
    if table is None:
        return None
    if not isinstance(table, dict):
        raise SweepError(f"{where}: [friction] must be a table with friction.static, got "
                         f"{table!r}")
    check_keys(table, FRICTION_KEYS, where, "[friction]", SweepError)
    if "static" not in table:
        raise SweepError(f"{where}: friction.static is missing (the static coefficient mu_s "
                         "[-], a number or a list)")
    statics = _coefficients(table["static"], where, "friction.static")
    if "dynamic" in table and "dynamic_ratio" in table:
        raise SweepError(f"{where}: friction.dynamic and friction.dynamic_ratio are both "
                         "given; give one (or neither: mu_d = mu_s)")
    if "dynamic_ratio" in table:
        ratios = _coefficients(table["dynamic_ratio"], where, "friction.dynamic_ratio", 1.0)
        # mu_s = 0 gives the pair (0, 0) for every ratio: each pair is run once
        return FrictionGrid(tuple(dict.fromkeys((mu_s, ratio * mu_s) for mu_s in statics
                                                for ratio in ratios)), "ratio")
    if "dynamic" not in table:
        return FrictionGrid(tuple((mu_s, mu_s) for mu_s in statics), "same")
    dynamics = _coefficients(table["dynamic"], where, "friction.dynamic")
    for mu_s in statics:
        for mu_d in dynamics:
            if mu_d > mu_s:
                raise SweepError(
                    f"{where}: friction.dynamic {mu_d:g} exceeds friction.static {mu_s:g} "
                    "(every combination is run, and mu_d must not exceed mu_s); use "
                    "friction.dynamic_ratio for a mu_d tied to each mu_s")
    return FrictionGrid(tuple((mu_s, mu_d) for mu_s in statics for mu_d in dynamics),
                        "explicit")


def check_friction_spec(spec: SweepSpec, rocking: dict) -> None:
    """Refuse, by key, what the coupled model does not take (the module docstring); a
    spec without ``[friction]`` passes."""
    from shaketable.models.planar.run import impact_ratios

    if spec.friction is None:
        return
    where = spec.path
    if any(block.rods is not None for block in spec.blocks):
        raise SweepError(f"{where}: [blocks.rods] with [friction]: the coupled model refuses "
                         "prestress rods (a rod hinged to the ground ties the block to the "
                         "table, so it cannot slide); drop one of them")
    if spec.pitch is not None:
        raise SweepError(f"{where}: [pitch] with [friction]: the coupled model has no table "
                         "rotation; drop one of them")
    if spec.ensemble is not None:
        raise SweepError(f"{where}: [ensemble] with [friction] is not offered (the ensembles "
                         "run the rocking batch); drop one of them")
    if spec.method != "fast":
        raise SweepError(f"{where}: rocking.method {spec.method!r} with [friction]: the "
                         "coupled model has its own engine; give method = \"fast\" or none")
    for key in ("subdivisions", "theta0"):
        if key in rocking:
            raise SweepError(f"{where}: rocking.{key} with [friction]: the coupled model "
                             "starts every run from rest and takes no "
                             f"{'subdivisions' if key == 'subdivisions' else 'initial tilt'}")
    for block in spec.blocks:
        for cor in spec.cors:
            try:
                impact_ratios(block, cor)
            except ValueError as error:
                raise SweepError(f"{where}: rocking.cor with [friction], block "
                                 f"{block.describe()}: {error}") from None


def simulate_friction(spec: SweepSpec, inputs: pd.DataFrame, cases: list,
                      threads: int | None = None) -> pd.DataFrame:
    """The rows of a chunk of a friction sweep (one per row of ``inputs``), in order.

    Parameters
    ----------
    spec : SweepSpec
        With ``spec.friction``.
    inputs : pandas.DataFrame
        :func:`shaketable.sweeps.execute.runs_table` of the chunk (``friction_index``).
    cases : list of shaketable.models.rocking.batch.Case
        The chunk's runs: block, unscaled motion, COR and scale factor.
    threads : int, optional
        Threads of the planar batch (:func:`~shaketable.models.planar.batch.simulate_many_planar`).

    Returns
    -------
    pandas.DataFrame
        The columns of a rocking batch's frame that describe the run (block, motion,
        scale, PGA, COR, ...), the friction pair and :data:`PLANAR_COLUMNS`, plus
        ``block_index`` and ``motion_index`` (dropped by the caller).

    Notes
    -----
    The runs of one motion (and scale) are one call of
    :func:`~shaketable.models.planar.batch.simulate_many_planar` over the blocks,
    friction pairs and CORs the chunk holds for it (its product; the few extra runs at a
    chunk's edges are discarded). A run does not depend on the others of its call, so a
    row equals ``simulate(block, motion.scaled(scale), cor=cor, friction=Friction(mu_s,
    mu_d), duration=duration)`` whatever the chunking. The batch shares its runs among
    ``threads`` threads (``--workers``; default all cores).
    """
    import pandas as pd

    from shaketable.models.planar.batch import simulate_many_planar
    from shaketable.models.planar.run import DEFAULT_PLANAR_RTOL
    from shaketable.models.sliding.result import Friction

    assert spec.friction is not None   # called for a sweep with [friction] only
    rtol = spec.options.get("rtol", DEFAULT_PLANAR_RTOL)
    pairs = spec.friction.pairs
    block_of = inputs["block_index"].to_numpy()
    friction_of = inputs["friction_index"].to_numpy()
    groups: dict[tuple, list[int]] = {}
    for k, case in enumerate(cases):
        groups.setdefault((id(case.motion), case.scale), []).append(k)
    rows: list[dict | None] = [None] * len(cases)
    for motion_index, members in enumerate(groups.values()):
        first = cases[members[0]]
        motion = first.motion if first.scale == 1.0 else first.motion.scaled(first.scale)
        blocks = sorted({int(block_of[k]) for k in members})
        frictions = sorted({int(friction_of[k]) for k in members})
        cors = sorted({float(cases[k].cor) for k in members})
        frame = simulate_many_planar([spec.blocks[b] for b in blocks], motion,
                                     [Friction(*pairs[f]) for f in frictions], cors,
                                     rtol=rtol, duration=spec.duration, threads=threads)
        columns = frame.to_dict("records")
        duration = spec.duration if spec.duration is not None else motion.duration
        for k in members:
            case = cases[k]
            position = ((blocks.index(int(block_of[k])) * len(frictions)
                         + frictions.index(int(friction_of[k]))) * len(cors)
                        + cors.index(float(case.cor)))
            result = columns[position]
            block = case.block
            rows[k] = {
                "block": case.block_label, "block_height [m]": block.height,
                "block_width [m]": block.width, "aspect_ratio [-]": block.height / block.width,
                "alpha [rad]": block.alpha, "p [rad/s]": block.p, "rods": False,
                "motion": case.motion_label, "scale [-]": float(case.scale),
                "pga [m/s^2]": case.motion.pga * float(case.scale),
                "motion_vertical": case.motion.vertical is not None,
                "duration [s]": float(duration), "cor [-]": float(case.cor),
                STATIC_COLUMN: result[STATIC_COLUMN], DYNAMIC_COLUMN: result[DYNAMIC_COLUMN],
                "method": "planar", "rtol [-]": float(rtol),
                "overturned": result["status"] == "overturned",
                **{name: result[name] for name in PLANAR_COLUMNS},
                "block_index": int(block_of[k]), "motion_index": motion_index,
            }
    table = pd.DataFrame(rows)
    table["n_impacts"] = table["n_impacts"].astype(np.int64)
    return table.set_index(inputs.index)


def verdict_counts(table) -> str:
    """``"12 stayed, 3 slid, ..."``: the verdicts of a friction sweep's table, in mode order."""
    counts = table["verdict"].value_counts()
    return ", ".join(f"{int(counts[name])} {name}" for name in VERDICT_ORDER if name in counts)


def friction_summary(table) -> list:
    """One line per friction pair of a friction sweep's table: its verdicts and, over its
    runs that stay standing (a toppled block's slip and corner are no clearance), the
    largest peak slip and peak corner excursion (in the unit of the blocks' labels when
    they share one, else m)."""
    from shaketable.core.units import format_length

    # lengths in the unit of the blocks' labels when they share one (2 x 0.5 m: mm or m)
    units = {str(label).rsplit(" ", 1)[-1] for label in table["block"].unique()}
    unit = units.pop() if len(units) == 1 and units <= {"m", "cm", "mm", "in", "ft"} else "m"
    lines = []
    for mu_s, mu_d in friction_pairs(table):
        rows = friction_rows(table, mu_s, mu_d)
        standing = rows[~rows["overturned"].astype(bool)]
        extent = "no run stands" if standing.empty else (
            "standing runs: largest peak slip "
            f"{format_length(standing['peak slip [m]'].max(), unit)}, largest peak corner "
            f"excursion {format_length(standing['peak corner excursion [m]'].max(), unit)}")
        lines.append(f"mu_s {mu_s:g}, mu_d {mu_d:g}: {verdict_counts(rows)}; {extent}")
    return lines


def friction_pairs(table) -> list:
    """The distinct (mu_s, mu_d) of a table, in order of first appearance (none: [])."""
    if STATIC_COLUMN not in table:
        return []
    pairs = table[[STATIC_COLUMN, DYNAMIC_COLUMN]].drop_duplicates()
    return [(float(s), float(d)) for s, d in pairs.itertuples(index=False)]


def friction_rows(table, mu_s: float, mu_d: float):
    """The rows of ``table`` with friction (mu_s, mu_d)."""
    return table[(table[STATIC_COLUMN] == mu_s) & (table[DYNAMIC_COLUMN] == mu_d)]


def refuse_mixed_friction(table, what: str) -> None:
    """ValueError when ``table`` mixes friction pairs that ``what`` would pool."""
    pairs = friction_pairs(table)
    if len(pairs) > 1:
        raise ValueError(f"{what}: the table holds {len(pairs)} friction pairs (mu_s, mu_d) "
                         f"{pairs[:4]}{' ...' if len(pairs) > 4 else ''}; select one first "
                         f"(shaketable.sweeps.friction.friction_rows), they are not pooled")


def friction_figure_sets(table, out: Path) -> list:
    """(rows, folder) of each figure set of a sweep: the whole table into ``out``, or for a
    friction sweep each (mu_s, mu_d) pair's rows into ``out/friction-mus<mu_s>-mud<mu_d>``
    (the overturning maps, spectra and fragility curves of one friction each; the
    figures pool no frictions)."""
    pairs = friction_pairs(table)
    if not pairs:
        return [(table, out)]
    return [(friction_rows(table, mu_s, mu_d), out / f"friction-mus{mu_s:g}-mud{mu_d:g}")
            for mu_s, mu_d in pairs]
