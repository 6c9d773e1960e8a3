"""Rock, slide or anchor? The planar block's mode map against Section 2.1's rule.

Section 2.1 of [1]_ decides between the two modes by friction alone: a block rocks if
mu_s > B/H, slides otherwise; Section 4.5 and Conclusion 6 advise letting shielding
blocks slide. The planar model (:mod:`shaketable.models.planar.physics`, run by
``simulate(..., friction=...)``) has all five modes, so the rule can be checked:

* :func:`mode_map` -- one record at a few PGA levels over a grid of (B/H, mu): the mode
  each block reaches (stayed, slid, rocked, slide-rocked, flew, overturned), beside the
  rule's mode and the rocking model's verdict on a base that cannot slide.
* :func:`sliding_limit` -- the largest mu at which a block only slides (never lifts a
  corner), by bisection: Section 2.1 says B/H.
* :func:`table_4_4_coupled` -- Table 4.4's peak slips recomputed for the report's
  shielding blocks with the planar model, beside the pure-sliding values.
* :func:`knife_edge` -- the verdict at relative offsets from mu = B/H: the rule's line
  is a knife-edge (the block slides just below it and may overturn just above it).

Data only: the figure is :func:`shaketable.plots.mode_map.mode_map_figure`.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
.. [2] K. W. Shenton III, "Criteria for initiation of slide, rock, and slide-rock
   rigid-body modes", Journal of Engineering Mechanics 122(7), 690-693 (1996).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd

from shaketable.core.constants import FOOT, INCH, G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.ground import records
from shaketable.ground.signals import scale_to_pga
from shaketable.models.api import simulate
from shaketable.models.sliding.engine import slide
from shaketable.models.sliding.result import Friction

#: Verdicts of the planar model, from calm to violent (the map's colour order).
VERDICT_ORDER = ("stayed", "slid", "rocked", "slide-rocked", "flew", "overturned")

#: The report's shielding blocks used for the sliding limit and Table 4.4 (height, width
#: [ft]; Tables 4.1-4.3 and Figs. 4.1-4.6).
SHIELDING_BLOCKS_FT = ((15.0, 5.0), (16.0, 4.0), (9.0, 3.0), (12.0, 3.0), (15.0, 3.0),
                       (8.0, 2.0))

#: The record of the mode map and the sliding limit: Pacoima Dam S16E with its vertical.
DEFAULT_RECORD = "pacoima-dam-s16e"


def _only_slides(verdict: str) -> bool:
    return verdict in ("stayed", "slid")


@dataclass(frozen=True)
class ModeMap:
    """The mode each block reaches under one record at a few PGA levels.

    Attributes
    ----------
    frame : pandas.DataFrame
        One row per (PGA, B/H, mu): ``pga [g]``, ``B/H [-]``, ``mu [-]`` (mu_s = mu_d),
        ``verdict`` (planar model), ``rule`` (Section 2.1: ``"slide"`` if mu < B/H else
        ``"rock"``), ``overturned``, ``rocking model overturned`` (the report's model on a
        base that cannot slide), ``max theta/alpha [-]``, ``peak slip [m]`` (the base midpoint's,
        rocking included), ``peak base slip [m]`` (the slide alone), ``peak corner
        excursion [m]`` and the seconds in each mode.
    record : str
        The record's name.
    height : float
        Height of every block of the map [m].
    cor : float
        Coefficient of restitution [-].
    """

    frame: pd.DataFrame
    record: str
    height: float
    cor: float

    def to_frame(self) -> pd.DataFrame:
        """The map's rows (a copy)."""
        return self.frame.copy()

    def counts(self) -> pd.DataFrame:
        """Per PGA level: cells where the planar model agrees with Section 2.1's rule on the
        mode (a block the rule lets slide only slides; a block the rule rocks lifts a corner
        without slipping on it) and, above the rule's line, where the planar model's overturn
        verdict agrees with the rocking model's."""
        rows = []
        for pga, cells in self.frame.groupby("pga [g]", sort=True):
            below = cells[cells["rule"] == "slide"]
            above = cells[cells["rule"] == "rock"]
            rows.append({
                "pga [g]": pga, "cells": len(cells),
                "rule slides: only slid": int(below["verdict"].map(_only_slides).sum()),
                "rule slides": len(below),
                "rule rocks: slide-rocked": int((above["time slide-rock [s]"] > 0).sum()),
                "rule rocks": len(above),
                "rule rocks: same overturn verdict": int(
                    (above["overturned"] == above["rocking model overturned"]).sum()),
            })
        return pd.DataFrame(rows)

    def plot(self, fig=None, block: Block | None = None):
        """The map: :func:`shaketable.plots.mode_map.mode_map_figure` (``block``: the
        user's block, its column outlined)."""
        from shaketable.plots.mode_map import mode_map_figure

        return mode_map_figure(self, fig=fig, block=block)


def _scaled(motion: Motion, pga: float | None) -> Motion:
    return motion if pga is None else scale_to_pga(motion, pga=pga)


def mode_map(motion: Motion | None = None, *, pga_levels: Sequence[float | None] = (None,),
             aspect_ratios: Sequence[float] = (0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5),
             frictions: Sequence[float] = tuple(np.round(np.arange(0.05, 0.801, 0.05), 3)),
             height: float = 16 * FOOT, cor: float = 0.95) -> ModeMap:
    """Run the planar block over a grid of aspect ratio and friction.

    Parameters
    ----------
    motion : Motion, optional
        Table motion [m/s^2] (default: Pacoima Dam S16E with its vertical).
    pga_levels : sequence of float or None
        Peak horizontal accelerations to scale the motion to [m/s^2] (both components
        scaled alike); ``None`` keeps the record as it is.
    aspect_ratios : sequence of float
        B/H of the blocks [-] (the width is ``B/H * height``).
    frictions : sequence of float
        Friction coefficients [-], mu_s = mu_d (as Table 4.4).
    height : float
        Height of the blocks [m] (default the 16 ft block of Figs. 4.1-4.6).
    cor : float
        Coefficient of restitution [-] (Section 2.7 (5)).

    Returns
    -------
    ModeMap
    """
    motion = records.load(DEFAULT_RECORD) if motion is None else motion
    rows = []
    for pga in pga_levels:
        scaled = _scaled(motion, pga)
        level = float(np.max(np.abs(scaled.horizontal)) / G)
        for ratio in aspect_ratios:
            block = Block(height=height, width=ratio * height)
            rocking = simulate(block, scaled, cor=cor)
            for mu in frictions:
                result = simulate(block, scaled, cor=cor, friction=Friction(float(mu)))
                rows.append({
                    "pga [g]": round(level, 6), "B/H [-]": ratio, "mu [-]": float(mu),
                    "verdict": result.verdict(),
                    "rule": "slide" if mu < ratio else "rock",
                    "overturned": result.overturned,
                    "rocking model overturned": rocking.overturned,
                    "max theta/alpha [-]": result.max_theta_ratio,
                    "peak slip [m]": result.peak_slip,
                    "peak base slip [m]": result.peak_base_slip,
                    "peak corner excursion [m]": result.peak_excursion,
                    **{f"time {name} [s]": seconds
                       for name, seconds in result.time_in_mode.items()},
                })
    return ModeMap(pd.DataFrame(rows), motion.name, height, cor)


def sliding_limit(block: Block, motion: Motion | None = None, *, cor: float = 0.95,
                  low: float = 0.01, high: float = 1.5, tolerance: float = 1e-4) -> float:
    """The largest friction coefficient (mu_s = mu_d) at which the block only slides.

    Bisection on "the planar block never leaves the rest and slide modes" between ``low``
    (it must only slide there) and ``high`` (it must lift a corner there).

    Parameters
    ----------
    block : Block
    motion : Motion, optional
        Default: Pacoima Dam S16E with its vertical.
    cor : float
        Coefficient of restitution [-].
    low, high : float
        Bracket of the friction coefficient [-].
    tolerance : float
        Width of the final bracket [-].

    Returns
    -------
    float
        The bracket's lower end [-]; NaN when ``high`` still only slides (the record never
        lifts a corner of this block: no limit).

    Raises
    ------
    ValueError
        When the block does more than slide at ``low``.
    """
    motion = records.load(DEFAULT_RECORD) if motion is None else motion

    def slides(mu: float) -> bool:
        return _only_slides(simulate(block, motion, cor=cor, friction=Friction(mu)).verdict())

    if not slides(low):
        raise ValueError(f"sliding_limit: the block does more than slide at mu = {low}")
    if slides(high):
        return math.nan
    while high - low > tolerance:
        middle = 0.5 * (low + high)
        if slides(middle):
            low = middle
        else:
            high = middle
    return low


#: Relative offsets delta of the friction from the knife-edge, mu = (1 - delta) B/H, that
#: :func:`knife_edge` tries by default [-].
KNIFE_EDGE_OFFSETS = (-1e-3, -1e-6, 1e-6, 1e-3, 5e-2)

#: The margin below B/H the mode map draws [-]: a friction coefficient known to +-5 %
#: slides for certain only when its upper bound is below B/H (docs/planar.md, "The
#: knife-edge at mu = B/H"; the model itself slides at any mu below (1 - 1e-6) B/H).
KNIFE_EDGE_MARGIN = 0.05


def knife_edge(block: Block, motion: Motion | None = None, *, cor: float = 0.95,
               offsets: Sequence[float] = KNIFE_EDGE_OFFSETS) -> pd.DataFrame:
    """The verdict of the planar block at mu_s = mu_d = (1 - delta) B/H for each delta.

    Parameters
    ----------
    block : Block
    motion : Motion, optional
        Default: Pacoima Dam S16E with its vertical.
    cor : float
        Coefficient of restitution [-].
    offsets : sequence of float
        Relative offsets delta [-]: positive below B/H.

    Returns
    -------
    pandas.DataFrame
        ``delta [-]``, ``mu [-]``, ``verdict``, ``peak base slip [m]``.
    """
    motion = records.load(DEFAULT_RECORD) if motion is None else motion
    ratio = block.width / block.height
    rows = []
    for delta in offsets:
        mu = ratio * (1.0 - float(delta))
        result = simulate(block, motion, cor=cor, friction=Friction(mu))
        rows.append({"delta [-]": float(delta), "mu [-]": mu, "verdict": result.verdict(),
                     "peak base slip [m]": result.peak_base_slip})
    return pd.DataFrame(rows)


def sliding_limits(blocks_ft: Sequence[tuple[float, float]] = SHIELDING_BLOCKS_FT,
                   motion: Motion | None = None, *, cor: float = 0.95,
                   tolerance: float = 1e-4) -> pd.DataFrame:
    """:func:`sliding_limit` of the report's shielding blocks beside Section 2.1's B/H.

    Returns
    -------
    pandas.DataFrame
        ``height [ft]``, ``width [ft]``, ``B/H [-]``, ``largest mu that only slides [-]``,
        ``difference from B/H [-]``.
    """
    motion = records.load(DEFAULT_RECORD) if motion is None else motion
    rows = []
    for height, width in blocks_ft:
        limit = sliding_limit(Block.from_feet(height, width), motion, cor=cor,
                              tolerance=tolerance)
        rows.append({"height [ft]": height, "width [ft]": width, "B/H [-]": width / height,
                     "largest mu that only slides [-]": limit,
                     "difference from B/H [-]": limit - width / height})
    return pd.DataFrame(rows)


def table_4_4_coupled(blocks_ft: Sequence[tuple[float, float]] = ((15.0, 5.0), (16.0, 4.0)),
                      columns: Sequence[str] = ("pacoima-dam-s16e", "pacoima-dam-s74w"),
                      frictions: Sequence[float] = (0.1, 0.2, 0.3), *,
                      cor: float = 0.95) -> pd.DataFrame:
    """Table 4.4's peak slips [in] with the planar model beside the pure-sliding model.

    The pure-sliding model (:func:`shaketable.models.sliding.engine.slide`, Table 4.4's model)
    cannot rock, so it is the same for every block; the planar block slides exactly the
    same while mu < B/H and rocks or slide-rocks above.

    Returns
    -------
    pandas.DataFrame
        One row per (record, mu, block): ``record``, ``mu [-]`` (mu_s = mu_d),
        ``block [ft]``, ``B/H [-]``, ``sliding model peak slip [in]``, ``planar verdict``,
        ``planar peak slip [in]``, ``planar residual slip [in]``, ``planar peak corner
        excursion [in]``.
    """
    rows = []
    for name in columns:
        motion = records.load(name)
        for mu in frictions:
            sliding = slide(motion, Friction(mu))
            for height, width in blocks_ft:
                block = Block.from_feet(height, width)
                planar = simulate(block, motion, cor=cor, friction=Friction(mu))
                rows.append({
                    "record": name, "mu [-]": mu, "block [ft]": f"{height:g} x {width:g}",
                    "B/H [-]": width / height,
                    "sliding model peak slip [in]": sliding.peak_slip / INCH,
                    "planar verdict": planar.verdict(),
                    "planar peak slip [in]": planar.peak_slip / INCH,
                    "planar residual slip [in]": planar.residual_slip / INCH,
                    "planar peak corner excursion [in]": planar.peak_excursion / INCH,
                })
    return pd.DataFrame(rows)


def _table(frame: pd.DataFrame) -> list[str]:
    lines = ["| " + " | ".join(frame.columns) + " |", "|" + "---|" * len(frame.columns)]
    for row in frame.itertuples(index=False):
        lines.append("| " + " | ".join(f"{value:.4g}" if isinstance(value, float) else str(value)
                                       for value in row) + " |")
    return lines


def mode_map_markdown(result: ModeMap, limits: pd.DataFrame) -> str:
    """The mode map's section of the reproduction report: what Section 2.1's rule and
    Conclusion 6 get right and where the planar model disagrees, with the counts."""
    counts = result.counts()
    top = counts.iloc[-1]
    worst = limits["difference from B/H [-]"].abs().max()
    frame = result.frame
    strongest = frame[frame["pga [g]"] == frame["pga [g]"].max()]
    below = strongest[strongest["rule"] == "slide"]
    saved = int((below["rocking model overturned"] & ~below["overturned"]).sum())
    holds = bool(worst <= 1e-3)
    limit_text = ("is B/H itself (bisection to 1e-4; largest difference "
                  f"{worst:.1e}): Conclusion 6's advice, lower mu below B/H and the block "
                  "slides, holds in the planar model" if holds else
                  f"differs from B/H by up to {worst:.3g}")
    lines = [
        f"The planar block (rest, slide, rock, slide-rock, flight; `simulate(..., "
        f"friction=...)`, see docs/planar.md) under {result.record} at each PGA level, "
        f"{len(frame)} runs, blocks {result.height:.3g} m high, COR {result.cor:g}, "
        "mu_s = mu_d. Section 2.1's rule: the block slides if mu_s < B/H, rocks otherwise "
        "(dashed line).", "",
        *_table(counts), "",
        "**Where Section 2.1's rule holds.** Below the line "
        f"{int(counts['rule slides: only slid'].sum())} of {int(counts['rule slides'].sum())} "
        "blocks only slid (or stayed): a flat block whose mu_s < B/H = tan(alpha) slips "
        "before Eq. (2-1) is reached, and a flat sliding block's centre of pressure sits at "
        "mu_d h from the middle of its base, inside it, so it never tips. The largest "
        "friction at which each of the report's shielding blocks only slides under the full "
        f"record {limit_text}.", "",
        *_table(limits), "",
        "**Where it does not.** Above the line the rule says *rocks*; the planar block rocks "
        "on a corner that may slip: at the strongest level "
        f"{int(top['rule rocks: slide-rocked'])} of {int(top['rule rocks'])} such cells "
        "slide-rocked (Shenton 1996: between B/H and a critical friction that grows with the "
        "ground acceleration the pivot cannot hold), and the planar block's overturn verdict "
        f"agreed with the rocking model's in {int(top['rule rocks: same overturn verdict'])} "
        f"of {int(top['rule rocks'])}. Below the line the rocking model (a base that cannot "
        f"slide) overturns {saved} of {len(below)} blocks that in fact only slide.",
    ]
    return "\n".join(lines)


def table_4_4_coupled_markdown(frame: pd.DataFrame) -> str:
    """Table 4.4 with the planar model, for the reproduction report."""
    shown = frame[["record", "mu [-]", "block [ft]", "B/H [-]", "sliding model peak slip [in]",
                   "planar verdict", "planar peak slip [in]",
                   "planar peak corner excursion [in]"]]
    same = frame[frame["planar verdict"].map(_only_slides)]
    difference = (same["planar peak slip [in]"] - same["sliding model peak slip [in]"]).abs()
    return "\n".join([
        "", "### Table 4.4 with the planar block", "",
        "The same records and frictions (mu_s = mu_d), the planar model run for two of the "
        "report's shielding blocks beside the sliding model of Table 4.4 (which cannot rock, "
        "so it is the same for every block):", "", *_table(shown), "",
        f"Where the planar block only slides ({len(same)} of {len(frame)} rows, mu < B/H) its "
        f"peak slip equals the sliding model's (largest difference {difference.max():.1e} in). "
        "Where mu >= B/H the 16 x 4 ft block (B/H = 0.25) does not slide as Table 4.4 "
        "assumes: it rocks or slide-rocks, and its corners move further than the table's "
        "slip (peak corner excursion); an overturned block's excursion is that of its fall.",
    ])
