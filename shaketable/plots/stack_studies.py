"""The figure of the stacks study (:mod:`shaketable.studies.stacks`): uplift thresholds and
pulse overturning amplitudes of stacks beside their closed forms, and the report's blocks
stacked under the Section 4 records."""

from __future__ import annotations

import math

import numpy as np

from shaketable.plots.base import pyplot


def _uplift_panel(axis, frame) -> None:
    """Uplift threshold against m2/m1: closed forms (lines) and computed (markers)."""
    ratios = np.geomspace(0.1, 10.0, 200)
    colours = ("tab:blue", "tab:orange", "tab:green", "tab:red")
    for (label, rows), colour in zip(frame.groupby("stack", sort=False), colours):
        first = rows.iloc[0]
        b1, h1, b2, h2 = (first[key] for key in ("b1 [m]", "h1 [m]", "b2 [m]", "h2 [m]"))
        a1 = b1 * (1 + ratios) / (h1 + ratios * (2 * h1 + h2))
        a2 = np.full_like(ratios, b2 / h2)
        axis.plot(ratios, np.minimum(a1, a2), color=colour, lw=1.6,
                  label=f"{label}: (g + v̈) min(A1, A2)")
        axis.plot(ratios, a1, color=colour, lw=0.8, ls=":", label="A1: the whole stack")
        axis.plot(ratios, a2, color=colour, lw=0.8, ls="--", label="A2: the top block alone")
        axis.plot(rows["m2/m1 [-]"], rows["computed [g]"], "o", mfc="none", color=colour,
                  ms=8, label="computed (first uplift)")
    tan_alpha = float(frame["bottom block alone tan(alpha1) [g]"].iloc[0])
    axis.axhline(tan_alpha, color="k", lw=1.0, label="bottom block alone: tan α1 (Eq. 2-1)")
    axis.set_xscale("log")
    axis.set_xlabel("mass ratio m2/m1 (top over bottom) [-]")
    axis.set_ylabel("uplift threshold |ü| / (g + v̈) [-]")
    axis.set_title("(a) when a stack starts to rock", fontsize=10)
    axis.set_ylim(0.0, 1.15 * tan_alpha)
    axis.legend(fontsize=6.5, loc="lower left")


def _pulse_panel(axis, frame, block) -> None:
    """Smallest overturning half-sine pulse: bracket (bar), middle, Eq. (2-8) as one body."""
    for k, (_, row) in enumerate(frame.iterrows()):
        x = k
        label = f"{int(row['blocks high'])} high, ω/p = {row['omega/p [-]']:g}"
        if math.isfinite(row["minimum [g]"]):
            axis.plot([x, x], [row["stands [g]"], row["falls [g]"]], color="k", lw=3)
            axis.plot(x, row["minimum [g]"], "o", color="k",
                      label="computed: the lowest overturning edge (spectrum --stack)" if k == 0 else None)
        axis.plot(x, row["Eq. (2-8) as one body [g]"], "s", mfc="none", color="tab:red", ms=9,
                  label="Eq. (2-8) for the column as one body" if k == 0 else None)
        axis.annotate(label, (x, 0), xytext=(0, 4), textcoords="offset points", ha="center",
                      fontsize=7)
    axis.set_xlim(-0.6, len(frame) - 0.4)
    axis.set_ylim(0.0, 1.2 * float(np.nanmax(frame[["falls [g]",
                                                     "Eq. (2-8) as one body [g]"]].to_numpy())))
    axis.set_xticks([])
    axis.set_ylabel("half-sine amplitude [g]")
    axis.set_title(f"(b) the smallest pulse that overturns {block.describe()} blocks",
                   fontsize=10)
    axis.legend(fontsize=7, loc="upper right")


def _record_panel(axis, frame) -> None:
    """Each record (a row) against the number of blocks high (a column): the cell red when
    the column fell (when, and the lowest block that fell), else the largest theta/alpha."""
    records = list(dict.fromkeys(frame["record"]))
    heights = sorted(int(count) for count in frame["blocks high"].unique())
    for _, row in frame.iterrows():
        x = heights.index(int(row["blocks high"]))
        y = records.index(row["record"])
        fell = row["verdict"] == "F"
        if fell:
            text = f"falls at {float(row['t_overturn [s]']):.2f} s\nblock {int(row['overturned block'])}"
        else:
            peak = max(float(value) for value in str(row["max theta/alpha"]).split(", "))
            text = f"{row['verdict']}\nmax θ/α {peak:.2f}"
        axis.add_patch(_cell((x - 0.5, y - 0.5), "#f4b6b0" if fell else "#cfe8cf"))
        axis.text(x, y, text, ha="center", va="center", fontsize=7.5)
    axis.set_xlim(-0.5, len(heights) - 0.5)
    axis.set_ylim(len(records) - 0.5, -0.5)
    axis.set_xticks(range(len(heights)),
                    [("alone" if count == 1 else f"{count} high") for count in heights])
    axis.set_yticks(range(len(records)), records)
    axis.set_xlabel("blocks high (alone: the single-block engine, COR 1 − 1.5 sin²α)")
    block = frame["block"].iloc[0]
    axis.set_title(f"(c) {block} blocks stacked under the Section 4 records", fontsize=10)


def _cell(corner, colour):
    """A unit cell of :func:`_record_panel`."""
    from matplotlib.patches import Rectangle

    return Rectangle(corner, 1.0, 1.0, facecolor=colour, edgecolor="white", lw=2)


def stacks_study_figure(study):
    """The stacks study in three panels (the closed forms drawn beside the computed points).

    Parameters
    ----------
    study : shaketable.studies.stacks.StacksStudy

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(15.0, 5.2))
    _uplift_panel(axes[0], study.uplift)
    _pulse_panel(axes[1], study.pulses, study.block)
    _record_panel(axes[2], study.records)
    for axis in axes[:2]:
        axis.grid(True, lw=0.3, alpha=0.5)
    fig.suptitle("Stacks beside single blocks (plastic impacts; shaketable.studies.stacks, "
                 "docs/stack.md)", fontsize=11)
    fig.tight_layout()
    return fig
