"""The figures of a stack sweep: how likely some block falls, and which block falls first.

A sweep with ``[stacks]`` (:mod:`shaketable.sweeps.stacks`) runs columns of blocks over
records and intensities. An engineer asks of it how much more fragile a block becomes
when it stands on (or under) another, and which block goes: the top one (it can be
secured alone) or the bottom one (the whole column comes down). Two figures answer:

* :func:`stack_fragility` -- P(some block overturns) against PGA and PGV, one curve per
  stack (height, sizes, mass ratio) with its lognormal fit, the block alone beside the
  stacks of it, each stack's median as a share of the block alone's;
* :func:`first_to_fall` -- at each intensity, the share of runs in which each block was
  the first to fall (a run stops there), and of runs that stood, one panel per stack.

:func:`stack_sweep_figures` writes them per impact law: the plastic law has no COR (NaN
in ``cor [-]``), so the rows are grouped by :func:`~shaketable.sweeps.stacks.impact_law`
("plastic impacts", "COR 0.9"), not by the COR's value (a NaN group would be dropped).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from shaketable.core.files import subfolder, write_csv
from shaketable.plots.base import log_axis, pyplot, save, stripe_fractions
from shaketable.sweeps.stacks import impact_law, law_token, stack_medians

#: The measures of :func:`stack_fragility`'s panels: column, axis label, log axis.
STACK_MEASURES = (("pga [g]", "PGA [g]", False), ("pgv [m/s]", "PGV [m/s]", True))


def _stacks(rows) -> list:
    """The rows of each stack (``block`` column), the single blocks first, in sweep order."""
    groups = list(rows.groupby("block", sort=False))
    return sorted(groups, key=lambda item: int(item[1]["blocks"].iloc[0]) != 1)


def _colours(groups) -> list:
    """Black for a block alone, tab10 colours for the stacks."""
    plt = pyplot()
    cycle = plt.get_cmap("tab10")
    colours, k = [], 0
    for _, part in groups:
        if int(part["blocks"].iloc[0]) == 1:
            colours.append("black")
        else:
            colours.append(cycle(k % 10))
            k += 1
    return colours


def stack_fragility(rows, *, fig=None):
    """P(some block overturns) against PGA and PGV for one impact law, one curve per stack.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of a stack sweep's table with one impact law (``blocks``, ``overturned``,
        ``pga [g]``, ``pgv [m/s]``).
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
        Two panels (PGA, PGV on a log axis): each stack's fraction of runs in which some
        block fell (points: per PGA level, or per bin of PGV) and its lognormal fit
        (:func:`~shaketable.sweeps.fragility.fragility_fit`; dashed for a block alone).
        The legend gives each median and, for a stack, the median as a share of the
        block alone's (the same bottom block); a stack whose outcomes cannot be fitted
        (none or all fell, or separated by the measure) says so.
    """
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(12, 5.4), layout="constrained")
    axes = fig.subplots(1, len(STACK_MEASURES), sharey=True)
    groups = _stacks(rows)
    colours = _colours(groups)
    for axis, (column, label, log) in zip(axes, STACK_MEASURES):
        medians = stack_medians(rows, column)
        unit = label.split("[")[1].rstrip("]")
        grid = (np.geomspace(rows[column].min() * 0.7, rows[column].max() * 1.3, 300) if log
                else np.linspace(max(1e-3, rows[column].min() * 0.8),
                                 rows[column].max() * 1.1, 300))
        for colour, (name, part) in zip(colours, groups):
            fell = part["overturned"].astype(bool).to_numpy()
            if log:
                centres, fractions, _ = stripe_fractions(part[column], fell, bins=8)
            else:
                levels = part.groupby(part[column].round(6))["overturned"].mean()
                centres, fractions = levels.index.to_numpy(), levels.to_numpy()
            alone = int(part["blocks"].iloc[0]) == 1
            axis.plot(centres, fractions, "o", color=colour, ms=4.5 if alone else 4)
            entry = medians[name]
            if entry["fit"] is None:
                axis.plot([], [], "-", color=colour,
                          label=f"{name}: no fit ({entry['why']})")
                continue
            fit = entry["fit"]
            share = entry["share of alone"]
            axis.plot(grid, fit.probability(grid), "--" if alone else "-", color=colour,
                      lw=1.4, label=f"{name}: median {fit.median:.3g} {unit}"
                      + ("" if np.isnan(share) else f" ({share:.2f} x alone)")
                      + f", β {fit.beta:.2f}")
        if log:
            log_axis(axis.xaxis)
        axis.set_xlabel(label)
        axis.set_ylim(-0.03, 1.03)
        axis.grid(alpha=0.3, which="both")
        axis.legend(fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.13),
                    frameon=False)   # below: the points reach both 0 and 1
    axes[0].set_ylabel("P(some block overturns) [-]")
    motions = rows.groupby(["record", "seed"], dropna=False).ngroups
    fig.suptitle(f"Stacks against the block alone, {impact_law(rows['cor [-]'].iloc[0])}: "
                 f"P(some block overturns) ({motions} motions; points: fraction of runs, "
                 "lines: lognormal fits)", fontsize=10)
    return fig


def first_to_fall(rows, *, intensity: str = "pga [g]", fig=None):
    """Which block falls first, as a share of the runs at each intensity, per stack.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of a stack sweep's table with one impact law (``blocks``, ``overturned
        block``, ``intensity``); the columns of one block are left out (the block alone
        is the only one that can fall).
    intensity : str
        The intensity column of the bars (default ``pga [g]``).
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure or None
        One panel per stack of two blocks or more: at each intensity level, stacked bars
        of the share of runs whose first block to fall was the top one, a middle one, the
        bottom one, and of runs in which every block stood (a run stops at the first
        block that falls); the number of runs above each bar. None if no stack has two
        blocks.
    """
    plt = pyplot()
    groups = [(name, part) for name, part in rows.groupby("block", sort=False)
              if int(part["blocks"].iloc[0]) > 1]
    if not groups:
        return None
    columns = min(len(groups), 3)
    lines = -(-len(groups) // columns)
    if fig is None:
        fig = plt.figure(figsize=(4.6 * columns + 0.8, 4.3 * lines), layout="constrained")
    axes = np.atleast_1d(fig.subplots(lines, columns, sharey=True, squeeze=False)).ravel()
    for axis in axes[len(groups):]:
        axis.set_axis_off()
    for axis, (name, part) in zip(axes, groups):
        n = int(part["blocks"].iloc[0])
        levels = np.sort(part[intensity].round(6).unique())
        width = 0.7 * (np.min(np.diff(levels)) if levels.size > 1 else 1.0)
        at = part[intensity].round(6).to_numpy()
        counts = np.array([(at == level).sum() for level in levels])
        bottom = np.zeros(levels.size)
        shades = plt.get_cmap("coolwarm")(np.linspace(1.0, 0.0, n)) if n > 1 else ["tab:red"]
        for index, shade in zip(range(n - 1, -1, -1), shades):
            share = np.array([((at == level) & (part["overturned block"] == index)).sum()
                              for level in levels]) / counts
            label = f"block {index}" + (" (top)" if index == n - 1 else
                                        " (bottom)" if index == 0 else "")
            axis.bar(levels, share, width, bottom=bottom, color=shade,
                     label=f"{label} fell first", edgecolor="white", lw=0.5)
            bottom += share
        axis.bar(levels, 1.0 - bottom, width, bottom=bottom, color="0.88",
                 label="every block stood", edgecolor="white", lw=0.5)
        for level, count in zip(levels, counts):
            axis.annotate(f"{count}", (level, 1.0), xytext=(0, 2), textcoords="offset points",
                          ha="center", va="bottom", fontsize=7, color="0.3")
        axis.set_title(name, fontsize=8.5)
        axis.set_xlabel("PGA [g]" if intensity == "pga [g]" else intensity)
        axis.set_ylim(0.0, 1.1)
        axis.set_yticks(np.linspace(0.0, 1.0, 6))
        axis.grid(alpha=0.3, axis="y")
        axis.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2,
                    frameon=False)
    axes[0].set_ylabel("share of runs [-]")
    fig.suptitle(f"Which block falls first, {impact_law(rows['cor [-]'].iloc[0])} (numbers: "
                 "runs at each level; a run stops at the first block that falls)",
                 fontsize=10)
    return fig


def stack_sweep_figures(table, out) -> list:
    """The figures of a stack sweep's table, written to folder ``out``, per impact law:
    ``stacks-fragility-<law>.png`` (:func:`stack_fragility`, with at least two intensity
    levels), ``stacks-first-to-fall-<law>.png`` (:func:`first_to_fall`, with a stack of
    two blocks or more) and ``stacks-fragility-<law>.csv`` (each stack's runs, how many
    fell, which block, and its PGA and PGV medians against the block alone's). ``<law>``
    is ``plastic`` or ``cor0.9``. Their paths. The runs that stalled (no results) are
    left out of the figures and counted apart in the CSV."""
    from shaketable.sweeps.stacks import finished_runs

    out = Path(out)
    out = subfolder(out.parent if str(out.parent) else ".", out.name, "figures folder")
    written: list = []
    for cor, every in table.groupby("cor [-]", sort=False, dropna=False):
        token = law_token(cor)
        rows = finished_runs(every)
        if len(rows) and rows["pga [g]"].round(6).nunique() >= 2:
            written.append(out / f"stacks-fragility-{token}.png")
            save(stack_fragility(rows), written[-1])
        figure = first_to_fall(rows) if len(rows) else None
        if figure is not None:
            written.append(out / f"stacks-first-to-fall-{token}.png")
            save(figure, written[-1])
        written.append(out / f"stacks-fragility-{token}.csv")
        write_csv(written[-1], stack_summary(every))
    return written


def stack_summary(rows):
    """One line per stack of one impact law: runs, how many stalled (left out of the rest),
    how many fell (and which block), and the PGA [g] and PGV [m/s] medians and betas, with
    the median as a share of the block alone's (NaN where there is no fit or no block
    alone)."""
    import pandas as pd

    from shaketable.sweeps.stacks import finished_runs, overturned_blocks

    lines = []
    fits = {column: stack_medians(rows, column) for column, _, _ in STACK_MEASURES}
    for name, every in _stacks(rows):
        part = finished_runs(every)
        line = {"stack": name, "blocks": int(every["blocks"].iloc[0]),
                "stack height [m]": float(every["stack height [m]"].iloc[0]),
                "impact law": impact_law(every["cor [-]"].iloc[0]), "runs": len(every),
                "stalled (excluded)": len(every) - len(part),
                "overturned": int(part["overturned"].astype(bool).sum()),
                "the block that fell": overturned_blocks(part)}
        for column, label, _ in STACK_MEASURES:
            entry = fits[column].get(name, {"fit": None, "share of alone": math.nan})
            fit = entry["fit"]
            short = label.split(" ")[0]
            unit = label.split(" ")[1]
            line[f"median {short} {unit}"] = math.nan if fit is None else fit.median
            line[f"beta {short} [-]"] = math.nan if fit is None else fit.beta
            line[f"median {short} / alone [-]"] = entry["share of alone"]
        lines.append(line)
    return pd.DataFrame(lines)
