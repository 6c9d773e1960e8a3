"""Overturning spectra in the style of Zhang & Makris (2001): shaded overturning regions
on the omega/p - a/(g tan alpha) plane, with Housner's Eq. (2-8) of the report."""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Rectangle

from shaketable.plots.base import pyplot

#: Fewer omega/p values than this are drawn as bars at the computed values, not strips.
DISCRETE_BELOW = 12


def plot_spectrum(spectrum, ax=None, *, pulse: str | None = None, overlay=None):
    """Overturn (shaded) and safe bands of one pulse of an :class:`OverturningSpectrum`.

    Each omega/p of the spectrum is a vertical strip (half-way to its
    neighbours) when the values are many (:data:`DISCRETE_BELOW` or more); fewer are
    drawn as narrow bars at the computed values with a point at each band edge, so
    that three computed values do not read as a continuous scan. Overturning
    without impact and after impacts are shaded differently. The places the spectrum
    flags (:attr:`OverturningSpectrum.windows`:
    a band narrower than the scan step, a mode change without a safe band, safe but
    unstable scan points) are framed in dashed red with a red marker, not hidden.
    Housner's Eq. (2-8), a/(g tan alpha) = sqrt(1 + (omega/p)^2) (the half-sine
    estimate), is drawn for comparison. ``overlay``, a second spectrum of the same
    pulses (e.g. ``method="linear"``, Housner's linearised model, over the exact
    one), draws its overturning bands as outlined boxes in the middle of each strip.

    Returns
    -------
    matplotlib.axes.Axes (the last one when several pulses make several panels)
    """
    plt = pyplot()
    bands = spectrum.bands
    pulses = [pulse] if pulse else list(dict.fromkeys(bands["pulse"]))
    if ax is None:
        _, axes = plt.subplots(1, len(pulses), figsize=(4.6 * len(pulses), 4.2), squeeze=False)
        axes = list(axes[0])
    else:
        axes = [ax] * len(pulses)
    for axis, kind in zip(axes, pulses):
        rows = bands[bands["pulse"] == kind]
        ratios = np.array(sorted(set(rows["omega/p [-]"])))
        edges = np.concatenate([[ratios[0] - 0.5 * (ratios[1] - ratios[0]) if ratios.size > 1
                                 else ratios[0] - 0.5],
                                0.5 * (ratios[1:] + ratios[:-1]),
                                [ratios[-1] + 0.5 * (ratios[-1] - ratios[-2]) if ratios.size > 1
                                 else ratios[0] + 0.5]])
        labelled = set()
        top = float(rows["to a/(g tan alpha) [-]"].max())
        span = (edges[0], edges[-1])
        discrete = ratios.size < DISCRETE_BELOW
        if discrete:  # a narrow bar around each computed value
            half = 0.06 * (float(np.min(np.diff(ratios))) if ratios.size > 1 else 1.0)
            strips = [(ratio - half, ratio + half) for ratio in ratios]
        else:
            strips = list(zip(edges[:-1], edges[1:]))
        for k, ratio in enumerate(ratios):
            strip = rows[np.isclose(rows["omega/p [-]"], ratio)]
            # above this ratio's ceiling nothing was computed: grey, not the white of "safe"
            ceiling = float(strip["to a/(g tan alpha) [-]"].max())
            if ceiling < top:
                label = "above the scan's ceiling (not computed)"
                axis.fill_between(strips[k], ceiling, top, color="0.85",
                                  hatch="//", edgecolor="0.6", lw=0,
                                  label=None if label in labelled else label)
                labelled.add(label)
            for _, row in strip.iterrows():
                if row["verdict"] != "overturns":
                    continue
                without = row["impacts"] == 0
                label = "overturns without impact" if without else "overturns after impact(s)"
                colour = "#d95f02" if without else "#7570b3"
                axis.fill_between(strips[k], row["from a/(g tan alpha) [-]"],
                                  row["to a/(g tan alpha) [-]"],
                                  color=colour, alpha=0.55,
                                  lw=0, label=None if label in labelled else label)
                labelled.add(label)
                if discrete:  # the computed band edges as points
                    axis.plot([ratio, ratio], [row["from a/(g tan alpha) [-]"],
                                               min(row["to a/(g tan alpha) [-]"], top)],
                              "o", color=colour, ms=4, clip_on=False)
        # flagged places (OverturningSpectrum.windows): where a window narrower than the
        # scan may hide, or a band narrower than the scan was found; a dashed red frame
        # and a marker at the strip's right edge (visible even when very thin)
        windows = spectrum.windows
        for _, window in windows[windows["pulse"] == kind].iterrows():
            k = int(np.argmin(np.abs(ratios - window["omega/p [-]"])))
            low, high = window["from a/(g tan alpha) [-]"], window["to a/(g tan alpha) [-]"]
            label = ("flagged (see the CSV's note): a band or a possible window\n"
                     "narrower than the scan")
            axis.add_patch(Rectangle((strips[k][0], low), strips[k][1] - strips[k][0],
                                     high - low, fill=False, edgecolor="red", lw=1.2, ls="--"))
            # not clipped: on the last strip the marker sits on the axis' right edge
            axis.plot([strips[k][1]], [0.5 * (low + high)], marker="<", color="red", ms=7,
                      ls="none", clip_on=False, label=None if label in labelled else label)
            labelled.add(label)
        if overlay is not None:
            others = overlay.bands[(overlay.bands["pulse"] == kind)
                                   & (overlay.bands["verdict"] == "overturns")]
            label = f"overturns, method {getattr(overlay, 'method', 'fast')} (outlined)"
            for _, row in others.iterrows():
                k = int(np.argmin(np.abs(ratios - row["omega/p [-]"])))
                if not np.isclose(ratios[k], row["omega/p [-]"]):
                    continue
                width = strips[k][1] - strips[k][0]
                low, high = row["from a/(g tan alpha) [-]"], row["to a/(g tan alpha) [-]"]
                axis.add_patch(Rectangle((strips[k][0] + 0.3 * width, low), 0.4 * width,
                                         high - low, fill=False, edgecolor="#1b9e77", lw=1.4,
                                         label=None if label in labelled else label))
                labelled.add(label)
        x = np.linspace(max(0.0, span[0]), span[1], 200)
        axis.plot(x, np.sqrt(1 + x ** 2), "k--", lw=1, label="Eq. (2-8) (Housner): a/(g tan α) = √(1 + (ω/p)²)")
        axis.set_xlim(*span)
        if discrete:
            axis.set_xticks(ratios)
        axis.set_ylim(0, top)
        axis.set_xlabel("ω / p [-]")
        axis.set_ylabel("a / (g tan α) [-]")
        block = spectrum.block
        method = getattr(spectrum, "method", "fast")
        axis.set_title(f"{kind}: α = {block.alpha:.3g} rad, p = {block.p:.3g} rad/s, "
                       f"COR {spectrum.cor:.3g}" + ("" if method == "fast" else f", {method}")
                       + "\n(white: safe"
                       + (f"; computed at ω/p = {', '.join(f'{r:g}' for r in ratios)} only)"
                          if discrete else ")"), fontsize=9)
        axis.grid(True, lw=0.3, alpha=0.6)
        axis.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1,
                    frameon=False)
    return axes[-1]
