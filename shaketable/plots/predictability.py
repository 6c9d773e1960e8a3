"""The teaching figure of :mod:`shaketable.studies.predictability`: one record, a bundle
of theta(t) trajectories from copies differing by a tiny perturbation, diverging."""

from __future__ import annotations

import math

import numpy as np

from shaketable.plots.base import pyplot


def plot_bundle(runs, ax=None, *, horizon: float = math.nan, threshold: float = 1e-3,
                title: str | None = None, members: int | None = None):
    """theta/alpha against time for every run (the first, nominal, in black).

    Parameters
    ----------
    runs : sequence of RockingResult
        Runs of one record, the nominal first.
    ax : matplotlib.axes.Axes, optional
    horizon : float
        Predictability horizon [s] to mark (NaN: none).
    threshold : float
        Its threshold [-] in units of alpha, for the label.
    members : int, optional
        The size of the ensemble the runs are drawn from, for the title (the runs
        drawn are the nominal one and the horizon's perturbed copies, not all members).

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 4.2))
    colours = plt.get_cmap("viridis")(np.linspace(0.05, 0.9, max(1, len(runs) - 1)))
    for k, run in enumerate(runs):
        ratio = run.theta / run.block.alpha
        if k == 0:
            ax.plot(run.t, ratio, color="black", lw=1.2, zorder=5, label="nominal run")
        else:
            ax.plot(run.t, ratio, color=colours[k - 1], lw=0.7, alpha=0.8,
                    label="perturbed copies" if k == 1 else None)
        if run.overturned:
            # drawn whole even at the top of the axis (clip_on=False): x = overturned
            ax.plot(run.t[-1], float(np.clip(ratio[-1], -2.9, 2.9)), "x", color="crimson",
                    ms=6, zorder=6, clip_on=False)
    for level in (-1, 1):
        ax.axhline(level, color="grey", lw=0.6, ls=":")
    if math.isfinite(horizon):
        ax.axvline(horizon, color="crimson", lw=1, ls="--",
                   label=f"horizon {horizon:.2f} s (|Δθ| > {threshold:g} α)")
    ax.set_ylim(-3, 3)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("θ/α [-]")
    first = runs[0]
    count = (f"{len(runs)} runs" if members is None or members == len(runs) else
             f"\n{len(runs)} of the {members} members drawn (the nominal run and the "
             f"horizon's perturbed copies)")
    ax.set_title(title or f"{first.block.describe()} block, {first.motion.name}, COR "
                          f"{first.cor:g}: {count} (x: overturned)", fontsize=9)
    ax.grid(True, lw=0.3, alpha=0.6)
    ax.legend(fontsize=8, loc="lower left")
    return ax
