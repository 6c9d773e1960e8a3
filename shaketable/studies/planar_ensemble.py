"""How predictable a sliding-and-rocking block is: an ensemble of the planar model.

The rocking model's ensemble (:func:`shaketable.studies.predictability.ensemble`)
perturbs the input amplitude, the COR, the block's height and width and the record's
start by a small relative spread and runs the copies in the rocking batch engine.
:func:`planar_ensemble` draws the same perturbations (:func:`shaketable.core.ensemble.
perturbed_members`, member 0 the nominal run) and runs each copy in the planar model
(:func:`shaketable.models.api.simulate` with ``friction=``), so that a block that may
slide gets P(overturn) with its Wilson interval and, over the members that stay up, the
spread of its peak slip and corner excursion (the clearance it needs).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from shaketable.core.ensemble import (
    Perturbation,
    perturbed_block,
    perturbed_cor,
    perturbed_members,
    shifted,
    verdict_statistics,
)
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.sliding.result import Friction


@dataclass(frozen=True)
class PlanarEnsemble:
    """Perturbed copies of one planar run.

    Attributes
    ----------
    block : Block
    motion : Motion
    cor : float
        Nominal COR [-].
    friction : Friction
    perturbation : Perturbation
    members : pandas.DataFrame
        One row per member: its factors, verdict, ``overturned``, ``max_theta_ratio [-]``,
        ``peak slip [m]``, ``peak corner excursion [m]``, ``t_overturn [s]``.
    summary : dict
        :func:`~shaketable.core.ensemble.verdict_statistics` plus the median, 84th and
        95th percentiles of the standing members' peak slip and corner excursion [m].
    """

    block: Block
    motion: Motion
    cor: float
    friction: Friction
    perturbation: Perturbation
    members: pd.DataFrame
    summary: dict

    def to_frame(self) -> pd.DataFrame:
        """One row per member (a copy)."""
        return self.members.copy()

    def describe(self) -> str:
        """P(overturn) with its interval, then the standing members' slip and clearance in
        the unit the block was given in."""
        from shaketable.core.units import format_length

        s, unit = self.summary, self.block.length_unit
        text = (f"P(overturn) = {s['P(overturn) [-]']:.3f} (Wilson 95 % {s['P low [-]']:.3f} "
                f"to {s['P high [-]']:.3f}) over {s['members']} members")
        if not s["standing members"]:
            return text + "; every member overturns"
        return (text + f"; over the {s['standing members']} standing members: peak slip "
                f"median {format_length(s['median peak slip [m]'], unit)}, 84th percentile "
                f"{format_length(s['p84 peak slip [m]'], unit)}; corner excursion median "
                f"{format_length(s['median peak corner excursion [m]'], unit)}, 84th "
                f"percentile {format_length(s['p84 peak corner excursion [m]'], unit)}")

    def plot(self, ax: Any = None) -> Any:
        """Peak slip and corner excursion of each member (standing ones; fallen marked)."""
        from shaketable.plots.planar import planar_ensemble_axes

        return planar_ensemble_axes(self, ax=ax)


def planar_ensemble(block: Block, motion: Motion, cor: float, friction: Friction, *,
                    members: int = 200, perturbation: Perturbation | None = None,
                    seed: int = 0, duration: float | None = None) -> PlanarEnsemble:
    """Run ``members`` perturbed copies of one planar run (member 0 the nominal one).

    Parameters
    ----------
    block : Block
        No prestress rods.
    motion : Motion
        Table motion [m/s^2].
    cor : float
        Coefficient of restitution [-].
    friction : Friction
    members : int
        Ensemble size (>= 2).
    perturbation : Perturbation, optional
        Relative spreads of amplitude, COR, size and start (default 1e-9 each).
    seed : int
        Seed of the draws.
    duration : float, optional
        Length of the runs [s].

    Returns
    -------
    PlanarEnsemble
    """
    from shaketable.models.api import simulate

    if not isinstance(friction, Friction):
        raise ValueError(f"friction must be a Friction, got {type(friction).__name__}")
    perturbation = Perturbation() if perturbation is None else perturbation
    drawn = perturbed_members(members, perturbation, seed)
    rows = []
    for k in range(members):
        felt = shifted(motion, drawn.start[k] * motion.dt)
        if drawn.amplitude[k] != 1.0:
            felt = felt.scaled(float(drawn.amplitude[k]))
        run = simulate(perturbed_block(block, drawn, k), felt,
                       cor=perturbed_cor(cor, drawn, k), friction=friction, duration=duration)
        rows.append({"member": k, "amplitude factor [-]": drawn.amplitude[k],
                     "cor factor [-]": drawn.cor[k], "height factor [-]": drawn.height[k],
                     "width factor [-]": drawn.width[k],
                     "start shift [samples]": drawn.start[k], "verdict": run.verdict(),
                     "overturned": run.overturned,
                     "max_theta_ratio [-]": run.max_theta_ratio,
                     "peak slip [m]": run.peak_slip,
                     "peak corner excursion [m]": run.peak_excursion,
                     "t_overturn [s]": run.t_overturn})
    frame = pd.DataFrame(rows)
    summary = verdict_statistics(frame["overturned"].to_numpy(),
                                 frame["max_theta_ratio [-]"].to_numpy())
    standing = frame[~frame["overturned"]]
    for column in ("peak slip [m]", "peak corner excursion [m]"):
        values = standing[column].to_numpy()
        name = column.replace(" [m]", "")
        for label, q in (("median", 50), ("p84", 84), ("p95", 95)):
            summary[f"{label} {name} [m]"] = (float(np.percentile(values, q)) if values.size
                                              else float("nan"))
    summary.update({"cor [-]": cor, "static friction mu_s [-]": friction.static,
                    "dynamic friction mu_d [-]": friction.dynamic, "seed": seed})
    return PlanarEnsemble(block, motion, float(cor), friction, perturbation, frame, summary)
