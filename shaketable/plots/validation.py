"""Figures of the validation against measured tests, and the asymmetric block's history."""

from __future__ import annotations

import numpy as np

from shaketable.plots.base import pyplot


def asymmetric_history(result, fig=None, title: str | None = None):
    """Table acceleration [g] and theta / alpha_s [-] against time [s] of one asymmetric run."""
    from shaketable.core.constants import G

    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(8, 5))
    top, bottom = fig.subplots(2, 1, sharex=True)
    frame = result.to_frame()
    top.plot(frame["time [s]"], frame["ug [m/s^2]"] / G, lw=0.7)
    top.set_ylabel("table acceleration [g]")
    bottom.plot(frame["time [s]"], frame["theta/alpha_side [-]"], lw=0.8)
    bottom.axhline(1.0, color="0.5", lw=0.5, ls="--")
    bottom.axhline(-1.0, color="0.5", lw=0.5, ls="--")
    bottom.set_ylabel(r"$\theta/\alpha_\pm$ [-]")
    bottom.set_xlabel("time [s]")
    top.set_title(title or result.block.describe())
    return fig



def reliability_figure(table, fig=None, title: str | None = None):
    """Predicted P(overturn) in bins against the measured fraction (a reliability diagram).

    ``table``: :func:`shaketable.validation.score.reliability`'s frame; the bars are the
    binomial spread (2 sd) of the fraction a calibrated model would give in each bin.
    """
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(5.2, 5))
    ax = fig.add_subplot(1, 1, 1)
    ax.plot([0, 1], [0, 1], color="0.6", lw=0.8, ls="--", label="perfectly calibrated")
    ax.errorbar(table["predicted"], table["predicted"], yerr=2 * table["binomial_sd"],
                fmt="none", ecolor="0.5", capsize=3, lw=0.8, label="binomial spread (2 sd)")
    sizes = 12 + 2 * table["n"]
    ax.scatter(table["predicted"], table["measured"], s=sizes, color="C0",
               zorder=3, label="measured (area ~ tests)")
    for size, (_, row) in zip(sizes, table.iterrows()):
        # beside the marker (its radius in points), towards the middle: never on the frame
        radius = 0.5 * np.sqrt(size)
        ax.annotate(f"{int(row['n'])}", (row["predicted"], row["measured"]),
                    textcoords="offset points", xytext=(radius + 2, -4 if row["measured"] > 0.5
                                                        else 4),
                    va="top" if row["measured"] > 0.5 else "bottom", fontsize=8)
    # room for the largest marker at 0 or 1 (a full circle, not one cut by the frame)
    ax.set_xlim(-0.06, 1.06)
    ax.set_ylim(-0.06, 1.06)
    ax.set_xlabel("predicted P(overturn) [-] (mean in the bin)")
    ax.set_ylabel("measured fraction overturned [-]")
    ax.set_title(title or "reliability")
    ax.legend(loc="upper left", fontsize=8)
    return fig


def fragility_figure(table, measure: str, log: bool = True, fig=None, title: str | None = None):
    """Measured (Wilson 95 %) and predicted P(overturn) in bins of an intensity measure."""
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(6.4, 4.4))
    ax = fig.add_subplot(1, 1, 1)
    centre = table["centre"].to_numpy()
    ax.errorbar(centre, table["measured"],
                yerr=[np.maximum(table["measured"] - table["measured_low"], 0.0),
                      np.maximum(table["measured_high"] - table["measured"], 0.0)],
                fmt="o", color="k", ms=4, capsize=3, lw=0.8, label="measured (Wilson 95 %)")
    ax.plot(centre, table["predicted"], "s-", color="C3", ms=4, lw=1.0,
            label="predicted (mean P in the bin)")
    for x, y, n in zip(centre, table["measured"], table["n"]):
        # above the point, or below it near the top (a count above 1 would touch the frame)
        ax.annotate(f"{int(n)}", (x, y), textcoords="offset points",
                    xytext=(4, -4 if y > 0.9 else 4), va="top" if y > 0.9 else "baseline",
                    fontsize=7, color="0.4")
    if log:
        ax.set_xscale("log")
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel(measure)
    ax.set_ylabel("P(overturn) [-]")
    ax.set_title(title or f"fragility against {measure.split(' [')[0]} (tests per bin marked)")
    ax.legend(loc="upper left", fontsize=8)
    return fig
