"""How predictable a verdict is: ensembles of perturbed copies of one run.

Rocking under a long record is chaotic: two runs whose inputs differ by one
part in 1e12 can end one standing, one overturned (Yim, Chopra &
Penzien [2]_; Bachmann et al. [3]_, "Is rocking motion predictable?"). Only
the distribution of responses is reproducible, which is what the report's
Section 3.7 (2) and 4.3 (3) discussions of unrepeatable table tests are
about [1]_. :func:`ensemble` runs ``members`` copies of one run, each with

* the input amplitude multiplied by ``1 + amplitude * u1``,
* the COR multiplied by ``1 + cor * u2`` (kept in [0, 1]),
* the block height and width multiplied by ``1 + size * u3``, ``1 + size * u4``,
* the record started ``start * u5`` sample intervals later (the record
  re-sampled, linearly, at t + delta),

with u1 ... u5 independent and uniform in [-1, 1] (a seeded generator); member 0
is the unperturbed run. The spreads are relative (default 1e-9, to expose
chaos; physical spreads such as ``cor=0.01`` for COR +/- 1 % are given the same
way). All members run in one call of the batch engine
(:func:`shaketable.models.rocking.batch.simulate_cases`).

It reports P(overturn) with Wilson's 95 % score interval, the median and the
5-95 % range of max |theta|/alpha, and a **predictability horizon**: the
time after which copies differing by the tiny perturbation ``horizon_spread``
(1e-9 of every input) differ by more than ``threshold`` (1e-3 alpha) in theta,
the median over ``horizon_pairs`` pairs (the nominal run against perturbed
copies, full time histories from :func:`shaketable.models.api.simulate`).

References
----------
.. [1] Aslam, M., Godden, W. G. and Scalise, D. T., "Rocking and overturning
   response of rigid bodies to earthquake motions", LBL-7539, 1978.
.. [2] Yim, C.-S., Chopra, A. K. and Penzien, J., "Rocking response of rigid
   blocks to earthquakes", Earthquake Eng. Struct. Dyn. 8, 565-587, 1980.
.. [3] Bachmann, J. A., Strand, M., Vassiliou, M. F., Broccardo, M. and
   Stojadinovic, B., "Is rocking motion predictable?", Earthquake Eng.
   Struct. Dyn. 47(2), 535-552, 2018.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from shaketable.core.ensemble import (  # the solver-free part, shared with the sweeps
    HORIZON_THRESHOLD,
    TINY,
    Members,
    Perturbation,
    perturbed_block,
    perturbed_cor,
    perturbed_members,
    shifted,
    verdict_statistics,
    wilson_interval,
)
from shaketable.core.equality import fields_equal
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.rocking.batch import Case, simulate_cases

__all__ = ["Perturbation", "EnsembleResult", "ensemble", "wilson_interval",
           "perturbed_members", "horizon", "trajectories", "TINY"]


def member_cases(block: Block, motion: Motion, cor: float, drawn: Members,
                 motions: list | None = None, label: str = "") -> list:
    """The batch :class:`Case` of each member (``motions``: shifted copies to share)."""
    if motions is None:
        motions = [shifted(motion, s * motion.dt) for s in drawn.start]
    cases = []
    for k in range(drawn.amplitude.size):
        cases.append(Case(perturbed_block(block, drawn, k), motions[k],
                          perturbed_cor(cor, drawn, k), scale=float(drawn.amplitude[k]),
                          block_label=label or block.describe(), motion_label=motion.name))
    return cases


def summarize(frame: pd.DataFrame) -> dict:
    """P(overturn), its Wilson interval, and max |theta|/alpha statistics of members' rows
    (:func:`shaketable.core.ensemble.verdict_statistics` of the batch columns)."""
    return verdict_statistics(frame["overturned"].to_numpy(),
                              frame["max_theta_ratio [-]"].to_numpy())


def trajectories(block: Block, motion: Motion, cor: float, *, members: int = 5,
                 spread: float = TINY, seed: int = 1, duration: float | None = None,
                 method: str = "fast"):
    """Full runs of ``members`` copies (the first nominal) perturbed by ``spread``.

    Returns a list of :class:`shaketable.models.rocking.result.RockingResult`.
    """
    from shaketable.models.api import simulate

    drawn = perturbed_members(members, Perturbation.uniform(spread), seed)
    runs = []
    for k in range(members):
        member_block = perturbed_block(block, drawn, k)
        felt = shifted(motion, drawn.start[k] * motion.dt)
        if drawn.amplitude[k] != 1.0:
            felt = felt.scaled(float(drawn.amplitude[k]))
        runs.append(simulate(member_block, felt, cor=perturbed_cor(cor, drawn, k),
                             duration=duration, method=method))
    return runs


def divergence_time(first, second, threshold: float = HORIZON_THRESHOLD) -> float:
    """First time [s] at which |theta_1 - theta_2| > threshold * alpha (inf if never).

    Both runs are compared on the first's time grid (the second interpolated);
    after one of them ends (overturned) the other is compared with its last
    value, so an overturn of one copy only is a divergence.
    """
    t = first.t
    theta1 = first.theta
    theta2 = np.interp(t, second.t, second.theta)
    theta2[t > second.t[-1]] = second.theta[-1]
    difference = np.abs(theta1 - theta2) / first.block.alpha
    over = np.flatnonzero(difference > threshold)
    if over.size:
        return float(t[over[0]])
    if first.t[-1] < second.t[-1]:
        return float(first.t[-1])
    return math.inf


def horizon(runs, threshold: float = HORIZON_THRESHOLD) -> float:
    """Median over ``runs[1:]`` of their divergence time from ``runs[0]`` [s]."""
    times = [divergence_time(runs[0], other, threshold) for other in runs[1:]]
    return float(np.median(times))


@dataclass(frozen=True)
class EnsembleResult:
    """An ensemble of perturbed copies of one run.

    Attributes
    ----------
    block : Block
    motion : Motion
    cor : float
        Nominal COR [-].
    perturbation : Perturbation
    members : pandas.DataFrame
        One row per member (the batch columns plus the factors drawn).
    summary : dict
        :func:`summarize` of the members, plus ``horizon [s]`` (median time
        after which tiny-perturbed copies differ by more than ``threshold``
        alpha; inf when they never do, NaN when not computed).
    threshold : float
        Horizon threshold [-] in units of alpha.
    runs : tuple
        The full runs used for the horizon (nominal first), for :meth:`plot`.
    """

    __eq__ = fields_equal   # arrays compared by value; equal after a pickle round trip

    block: Block
    motion: Motion
    cor: float
    perturbation: Perturbation
    members: pd.DataFrame
    summary: dict
    threshold: float = HORIZON_THRESHOLD
    runs: tuple = field(default=(), repr=False)

    @property
    def p_overturn(self) -> float:
        return self.summary["P(overturn) [-]"]

    @property
    def interval(self) -> tuple[float, float]:
        return self.summary["P low [-]"], self.summary["P high [-]"]

    @property
    def robust(self) -> bool:
        """Every member reached the same verdict."""
        return self.summary["robust"]

    @property
    def horizon(self) -> float:
        return self.summary["horizon [s]"]

    def describe(self) -> str:
        s = self.summary
        verdict = ("robust" if s["robust"] else "fragile") + (
            f": P(overturn) = {s['P(overturn) [-]']:.3f} [{s['P low [-]']:.3f}, "
            f"{s['P high [-]']:.3f}] (Wilson 95 %) over {s['members']} members")
        peaks = ("every member overturns (F)" if not s["standing members"] else
                 f"max θ/α of the {s['standing members']} standing members: median "
                 f"{s['median max theta/alpha [-]']:.3f}, 5-95 % "
                 f"{s['p05 max theta/alpha [-]']:.3f}-{s['p95 max theta/alpha [-]']:.3f}")
        return (f"{verdict}; {peaks}; predictability horizon {s['horizon [s]']:.2f} s "
                f"(|d theta| > {self.threshold:g} alpha)")

    def to_frame(self) -> pd.DataFrame:
        """One row per member (a copy)."""
        return self.members.copy()

    def plot(self, ax=None, **kwargs):
        """The theta(t)/alpha bundle of the horizon runs (:mod:`shaketable.plots.predictability`)."""
        from shaketable.plots.predictability import plot_bundle

        kwargs.setdefault("members", len(self.members))
        return plot_bundle(self.runs, ax=ax, horizon=self.horizon, threshold=self.threshold,
                           **kwargs)


def ensemble(block: Block, motion: Motion, *, cor: float, members: int = 200,
             perturbation: Perturbation | None = None, seed: int = 0,
             horizon_pairs: int = 4, horizon_spread: float = TINY,
             threshold: float = HORIZON_THRESHOLD, duration: float | None = None,
             method: str = "fast", threads: int | None = None) -> EnsembleResult:
    """Run ``members`` perturbed copies of one run (block, motion, COR) and summarise.

    Parameters
    ----------
    block : Block
    motion : Motion
        Ground accelerations [m/s^2].
    cor : float
        Nominal coefficient of restitution [-].
    members : int
        Ensemble size (member 0 is the nominal run).
    perturbation : Perturbation, optional
        Relative spreads (default: :data:`TINY` on every input).
    seed : int
        Seed of the draws.
    horizon_pairs : int
        Perturbed copies compared with the nominal run for the horizon
        (0: no horizon, NaN).
    horizon_spread : float
        Relative perturbation of those copies [-].
    threshold : float
        Horizon threshold [-] in units of alpha.
    duration, method, threads
        As in :func:`shaketable.models.rocking.batch.simulate_cases`.

    Returns
    -------
    EnsembleResult
    """
    perturbation = Perturbation() if perturbation is None else perturbation
    drawn = perturbed_members(members, perturbation, seed)
    cases = member_cases(block, motion, float(cor), drawn)
    frame = simulate_cases(cases, threads=threads, method=method, duration=duration)
    frame["member"] = np.arange(members)
    frame["amplitude factor [-]"] = drawn.amplitude
    frame["height factor [-]"] = drawn.height
    frame["width factor [-]"] = drawn.width
    frame["start shift [samples]"] = drawn.start
    summary = summarize(frame)
    runs = ()
    summary["horizon [s]"] = math.nan
    if horizon_pairs > 0:
        runs = tuple(trajectories(block, motion, float(cor), members=horizon_pairs + 1,
                                  spread=horizon_spread, seed=seed + 1, duration=duration,
                                  method=method))
        summary["horizon [s]"] = horizon(runs, threshold)
    return EnsembleResult(block, motion, float(cor), perturbation, frame, summary, threshold,
                          runs)


# --------------------------------------------------------------------------- report tables
def _mark(summary: dict) -> str:
    if summary["robust"]:
        return "robust"
    return f"fragile P={summary['P(overturn) [-]']:.2f}"


def table_predictability(name: str, *, members: int = 200,
                         perturbation: Perturbation | None = None, columns=None,
                         seed: int = 0, motion_seed: int = 1,
                         threads: int | None = None) -> pd.DataFrame:
    """Table 4.1, 4.2 or 4.3 recomputed with an ensemble per cell and a robust/fragile mark.

    Every cell is run ``members`` times (member 0 nominal, the others
    perturbed as in :func:`ensemble`); all cells of the table in one batch.
    The shifted copies of each record are shared by every cell (member k of
    every cell uses the same start shift). A cell is **robust** when every
    member reaches the nominal verdict (overturns or stands), **fragile**
    otherwise, with its P(overturn) and Wilson interval.

    Returns
    -------
    pandas.DataFrame
        One row per cell: height [ft], width [ft], cor [-], column, report (as
        printed), reproduced (the nominal run, "F" = overturns), verdict_agrees,
        mark ("robust" / "fragile P=0.32"), the :func:`summarize` columns.
    ``motion_seed`` is the realisation of the substitute (artificial) columns.
    """
    from shaketable.studies.report_tables import COLUMNS, column_motion, printed_table

    perturbation = Perturbation() if perturbation is None else perturbation
    printed = printed_table(name)
    fixed_cor = {"table_4_2": 1.0, "table_4_3": 0.90}.get(name)
    available = [c for c in COLUMNS if c in printed.columns]
    columns = available if columns is None else [c for c in columns if c in available]
    drawn = perturbed_members(members, perturbation, seed)
    shared = {}
    for column in columns:
        motion = column_motion(column, motion_seed)
        shared[column] = (motion, [shifted(motion, s * motion.dt) for s in drawn.start])
    cases, cells = [], []
    for _, line in printed.iterrows():
        height, width = float(line["height [ft]"]), float(line["width [ft]"])
        if "cor [-]" in line:
            cor = float(line["cor [-]"])
        elif fixed_cor is not None:
            cor = fixed_cor
        else:
            raise ValueError(f"{name}: the printed table gives no COR and none is fixed for it")
        block = Block.from_feet(height, width)
        for column in columns:
            motion, copies = shared[column]
            cases += member_cases(block, motion, cor, drawn, copies)
            cells.append({"height [ft]": height, "width [ft]": width, "cor [-]": cor,
                          "column": column, "substitute motion": COLUMNS[column][0] ==
                          "artificial", "report": line[column].strip()})
    frame = simulate_cases(cases, threads=threads)
    rows = []
    for k, cell in enumerate(cells):
        part = frame.iloc[k * members:(k + 1) * members]
        summary = summarize(part)
        nominal = part.iloc[0]
        reproduced = "F" if nominal["overturned"] else f"{nominal['max_theta_ratio [-]']:.2f}"
        rows.append({**cell, "reproduced": reproduced,
                     "verdict_agrees": (cell["report"] == "F") == (reproduced == "F"),
                     "mark": _mark(summary), **summary})
    return pd.DataFrame(rows)


def agreement_counts(frame: pd.DataFrame) -> dict:
    """Cells whose verdict (F / not F) agrees with the report, robust and fragile apart.

    For a fragile cell the report's verdict is also called *compatible* when
    some member reaches it (0 < P(overturn) < 1 always is).
    """
    result = {}
    for label, part in (("robust", frame[frame["robust"]]),
                        ("fragile", frame[~frame["robust"]])):
        result[label] = {"cells": int(len(part)),
                         "same F / not F (nominal run)": int(part["verdict_agrees"].sum())}
    return result


def predictability_markdown(name: str, *, columns=None, motion_seed: int = 1,
                            members: int = 200) -> list:
    """Markdown lines for the reproduction report: the marks per cell and the two counts."""
    frame = table_predictability(name, members=members, columns=columns,
                                 motion_seed=motion_seed)
    frame = frame.assign(cell=frame["report"] + " / " + frame["reproduced"] + " ("
                         + frame["mark"] + ")")
    wide = frame.pivot_table(index=["height [ft]", "width [ft]", "cor [-]"], columns="column",
                             values="cell", aggfunc="first", sort=False).reset_index()
    header = "| " + " | ".join(str(c) for c in wide.columns) + " |"
    lines = ["", f"**How predictable each verdict is** ({members} copies per cell, every "
             "input perturbed by 1e-9 relative; shaketable.studies.predictability). "
             "robust: every copy reaches the same verdict; fragile: P(overturn) over the "
             "copies, and the printed verdict is one draw of a chaotic response.", "",
             header, "|" + "---|" * len(wide.columns)]
    for _, row in wide.iterrows():
        lines.append("| " + " | ".join(f"{v:g}" if isinstance(v, float) else str(v)
                                       for v in row) + " |")
    counts = agreement_counts(frame)
    lines += ["", "| cells | count | same F / not F as the report (nominal run) |",
              "|---|---|---|"]
    for label, count in counts.items():
        lines.append(f"| {label} | {count['cells']} | "
                     f"{count['same F / not F (nominal run)']} |")
    return lines
