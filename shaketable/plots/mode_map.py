"""The mode map of the planar block against Section 2.1's rule."""

from __future__ import annotations

import numpy as np

from shaketable.plots.base import pyplot
from shaketable.studies.mode_map import KNIFE_EDGE_MARGIN, VERDICT_ORDER

#: One colour per verdict, calm to violent.
VERDICT_COLOURS = {"stayed": "#f0f0f0", "slid": "#9ecae1", "rocked": "#fdd49e",
                   "slide-rocked": "#fc8d59", "flew": "#c994c7", "overturned": "#b30000"}


def mode_map_figure(mode_map, fig=None, block=None):
    """One panel per PGA level: the verdict of each (B/H, mu) cell, the rule mu = B/H (a
    knife-edge: drawn solid) and the margin below it that a friction known to +-5 % needs.

    Cells where the planar block overturns and the rocking model (a base that cannot slide)
    does not, or the other way round, carry a cross.

    Parameters
    ----------
    mode_map : shaketable.studies.mode_map.ModeMap
    fig : matplotlib.figure.Figure, optional
    block : Block, optional
        The user's block: its B/H column is outlined, and the title gives its size in the
        unit it was given in.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    plt = pyplot()
    frame = mode_map.frame
    levels = sorted(frame["pga [g]"].unique())
    if fig is None:
        # the legend goes below the panels: at their right it took half the width of a
        # single-level map and squeezed the panel to a quarter
        fig = plt.figure(figsize=(max(3.6 * len(levels), 6.4), 6.0), layout="constrained")
    axes = fig.subplots(1, len(levels), sharey=True, squeeze=False)[0]
    cmap = ListedColormap([VERDICT_COLOURS[name] for name in VERDICT_ORDER])
    for axis, level in zip(axes, levels):
        cells = frame[frame["pga [g]"] == level]
        ratios = np.sort(cells["B/H [-]"].unique())
        mus = np.sort(cells["mu [-]"].unique())
        codes = np.full((len(mus), len(ratios)), np.nan)
        for row in cells.itertuples(index=False):
            codes[np.searchsorted(mus, row[2]), np.searchsorted(ratios, row[1])] = \
                VERDICT_ORDER.index(row[3])
        axis.pcolormesh(_edges(ratios), _edges(mus), codes, cmap=cmap, vmin=-0.5,
                        vmax=len(VERDICT_ORDER) - 0.5, edgecolors="white", linewidth=0.4)
        differ = cells[cells["overturned"] != cells["rocking model overturned"]]
        axis.plot(differ["B/H [-]"], differ["mu [-]"], "x", color="black", markersize=5)
        line = np.array([min(ratios[0], mus[0]), max(ratios[-1], mus[-1])])
        axis.plot(line, line, color="black", linewidth=1.8)   # the knife-edge
        axis.plot(line, (1.0 - KNIFE_EDGE_MARGIN) * line, ":", color="black", linewidth=1.2)
        axis.set_xlim(_edges(ratios)[[0, -1]])
        axis.set_ylim(_edges(mus)[[0, -1]])
        if block is not None:
            ratio = block.width / block.height
            axis.axvline(ratio, color="tab:blue", linewidth=1.6,
                         label=f"{block.describe()} (B/H {ratio:.3g})")
        axis.set_title(f"PGA {level:.2f} g")
        axis.set_xlabel("B / H [-]")
    axes[0].set_ylabel("μs = μd [-]")
    handles = [Patch(facecolor=VERDICT_COLOURS[name], edgecolor="grey", label=name)
               for name in VERDICT_ORDER if name in set(frame["verdict"])]
    handles += [plt.Line2D([], [], color="k", linewidth=1.8,
                           label="μs = B/H (Section 2.1): a knife-edge,\nslides below, may "
                                 "overturn above"),
                plt.Line2D([], [], color="k", linestyle=":",
                           label=f"μs = {1 - KNIFE_EDGE_MARGIN:g} B/H: slides for a μs\n"
                                 f"known to ±{KNIFE_EDGE_MARGIN:.0%}"),
                plt.Line2D([], [], color="k", marker="x", linestyle="",
                           label="overturn verdict differs\nfrom the rocking model")]
    if block is not None:
        handles.append(plt.Line2D([], [], color="tab:blue", linewidth=1.6,
                                  label=f"{block.describe()} block"))
    fig.legend(handles=handles, loc="outside lower center", ncol=2, frameon=False,
               fontsize=8)
    if block is not None:
        from shaketable.core.units import format_length

        height = format_length(mode_map.height, block.length_unit)
    else:
        height = f"{mode_map.height:.3g} m"
    fig.suptitle(f"Planar block under {mode_map.record}:\nH = {height}, COR {mode_map.cor:g}",
                 fontsize=10)
    return fig


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges halfway between sorted centres (the ends mirrored)."""
    centres = np.asarray(centres, dtype=float)
    if len(centres) == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    middle = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - middle[0]], middle, [2 * centres[-1] - middle[-1]]])
