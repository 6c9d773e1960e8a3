"""The overturning spectrum of a stack (:mod:`shaketable.studies.stack_spectrum`), drawn as
the single block's (:mod:`shaketable.plots.spectrum`): overturning bands shaded on the
omega/p - amplitude plane, one panel for the stack and one for its bottom block alone,
with Housner's Eq. (2-8) for each as one rigid body."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from matplotlib.patches import Rectangle

from shaketable.plots.base import pyplot
from shaketable.plots.spectrum import DISCRETE_BELOW

#: The colour of the bands in which a block fell: the bottom block (and a block alone),
#: the top one, and the blocks between.
FELL_COLOURS = {"bottom": "#d95f02", "top": "#7570b3", "between": "#1b9e77"}


def _colour(words: str) -> str:
    if "(top)" in words:
        return FELL_COLOURS["top"]
    if "(bottom)" in words or words == "the block":
        return FELL_COLOURS["bottom"]
    return FELL_COLOURS["between"]


def _strips(ratios: np.ndarray) -> tuple[list, tuple, bool]:
    """Each omega/p's strip (a narrow bar when few are computed), the x span, discrete."""
    edges = np.concatenate([[ratios[0] - 0.5 * (ratios[1] - ratios[0]) if ratios.size > 1
                             else ratios[0] - 0.5],
                            0.5 * (ratios[1:] + ratios[:-1]),
                            [ratios[-1] + 0.5 * (ratios[-1] - ratios[-2]) if ratios.size > 1
                             else ratios[0] + 0.5]])
    discrete = ratios.size < DISCRETE_BELOW
    if discrete:
        half = 0.06 * (float(np.min(np.diff(ratios))) if ratios.size > 1 else 1.0)
        return [(r - half, r + half) for r in ratios], (edges[0], edges[-1]), True
    return list(zip(edges[:-1], edges[1:])), (edges[0], edges[-1]), False


def stack_bands_figure(frame, curves: dict | Callable[[np.ndarray], dict], title: str = ""):
    """Overturn (shaded, by the block that fell) and safe (white) bands of a stack and of its
    bottom block alone under half-sine pulses.

    Parameters
    ----------
    frame : DataFrame
        :func:`shaketable.studies.stack_spectrum.stack_spectrum_bands` (amplitudes [g]).
    curves : dict or callable
        ``{"stack": (ratios, [g]), "bottom block alone": (ratios, [g])}``: Eq. (2-8) of
        each as one rigid body (:func:`shaketable.studies.stacks.eq_2_8_curves`), or a
        function of the omega/p values [-] that returns it: then the curves are drawn
        across the whole omega/p axis, whatever ratios were computed.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    columns = list(dict.fromkeys(frame["column"]))
    fig, axes = plt.subplots(1, len(columns), figsize=(4.8 * len(columns), 4.8), sharey=True,
                             squeeze=False)
    top = float(frame["to [g]"].max())
    # headroom above the highest amplitude computed, so that its point is not cut by the
    # frame; nothing is computed there (grey, as above each ratio's own ceiling)
    axis_top = 1.06 * top
    ratios = np.array(sorted(set(frame["omega/p [-]"])))
    strips, span, discrete = _strips(ratios)
    if callable(curves):   # evaluated across the axis: a dashed line cut short misleads
        curves = curves(np.linspace(max(0.0, span[0]), span[1], 200))
    for axis, column in zip(axes[0], columns):
        rows = frame[frame["column"] == column]
        labelled: set = set()
        for k, ratio in enumerate(ratios):
            strip = rows[np.isclose(rows["omega/p [-]"], ratio)]
            ceiling = float(strip["to [g]"].max())
            if ceiling < axis_top:   # above this ratio's ceiling nothing was computed
                label = "above the scan's ceiling (not computed)"
                axis.fill_between(strips[k], ceiling, axis_top, color="0.85", hatch="//",
                                  edgecolor="0.6", lw=0, label=None if label in labelled
                                  else label)
                labelled.add(label)
            for _, row in strip.iterrows():
                if row["flagged"]:   # narrower than the scan: framed, not hidden
                    axis.add_patch(Rectangle((strips[k][0], row["from [g]"]),
                                             strips[k][1] - strips[k][0],
                                             row["to [g]"] - row["from [g]"], fill=False,
                                             edgecolor="red", lw=1.2, ls="--"))
                if row["verdict"] != "overturns":
                    continue
                colour = _colour(row["block that fell"])
                label = ("overturns" if row["block that fell"] == "the block" else
                         f"{row['block that fell']} falls first")
                axis.fill_between(strips[k], row["from [g]"], row["to [g]"], color=colour,
                                  alpha=0.55, lw=0, label=None if label in labelled else label)
                labelled.add(label)
                if discrete:   # the computed band edges as points
                    axis.plot([ratio, ratio], [row["from [g]"], min(row["to [g]"], top)],
                              "o", color=colour, ms=4, clip_on=False)
        x, values = curves[column]
        shown = (x >= max(0.0, span[0])) & (x <= span[1])
        axis.plot(x[shown], values[shown], "k--", lw=1,
                  label="Eq. (2-8) as one rigid body")
        axis.set_xlim(*span)
        if discrete:
            axis.set_xticks(ratios)
        axis.set_ylim(0.0, axis_top)
        axis.set_xlabel("ω / p of the bottom block [-]")
        axis.set_title(f"{column}\n(white: safe"
                       + (f"; computed at ω/p = {', '.join(f'{r:g}' for r in ratios)} only)"
                          if discrete else ")"), fontsize=9)
        axis.grid(True, lw=0.3, alpha=0.6)
        axis.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1,
                    frameon=False)
    axes[0][0].set_ylabel("half-sine amplitude [g]")
    fig.suptitle(title or "half-sine pulses", fontsize=10)
    fig.tight_layout()
    return fig
