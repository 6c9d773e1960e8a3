"""The test-vs-theory figure of a virtual shaking-table test (Figs. 3.4, 3.5, 3.7-3.9)."""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G
from shaketable.plots.base import pyplot
from shaketable.plots.calcomp import describe_block


def plot_test_vs_theory(result, fig=None, title: str | None = None):
    """Virtual test and theory overlaid, like Figs. 3.4 and 3.7-3.9.

    ``result`` is a :class:`VirtualTestResult`; see :meth:`VirtualTestResult.plot`.
    The time axis ends a little after the later overturn (test or theory)
    when the block falls, else at the end of the record. Samples where the
    virtual potentiometer is at the end of its stroke (the block has fallen
    onto the catcher and the reading is clipped) are shaded and said so.
    """
    plt = pyplot()

    driven = bool(np.any(result.test.motion.horizontal)
                  or np.any(result.test.motion.vertical_or_zero))
    rows = 2 if result.measurement.table_horizontal is not None and driven else 1
    if fig is None:
        fig = plt.figure(figsize=(9, 2.8 + 2.4 * rows), layout="constrained")
    else:
        fig.set_layout_engine("constrained")
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    t = result.measurement.t
    alpha = result.block.alpha
    legend = dict(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=True,
                  borderaxespad=0.0)
    if rows == 2:
        axes[0].plot(t, result.measurement.table_horizontal / G, lw=0.8, color="k",
                     label="horizontal")
        if result.measurement.table_vertical is not None:
            axes[0].plot(t, result.measurement.table_vertical / G, lw=0.8, color="tab:blue",
                         label="vertical")
        axes[0].set_ylabel("table acc. [g]\n(digitized)")
        axes[0].legend(**legend)
    axis = axes[-1]
    measured = result.measured_theta() / alpha
    axis.plot(t, measured, color="k", lw=1.0,
              label=f"virtual test (simulated potentiometers,\nCOR {result.test.cor:g})")
    axis.plot(t, result.theory_theta() / alpha, color="tab:red", lw=1.0, ls="--",
              label=f"theory (COR {result.theory_cor:.3f})")
    for level in (-1.0, 1.0):
        axis.axhline(level, color="0.4", ls=":", lw=0.8, label="±α" if level > 0 else None)
    limit = max(1.5, min(4.0, 1.1 * float(np.max(np.abs(measured)))))
    axis.set_ylim(-limit, limit)
    clipped = result.measurement.top_clipped
    if clipped is not None and np.any(clipped):
        first = float(t[np.argmax(clipped)])
        axis.axvspan(first, t[-1], color="0.85", zorder=0,
                     label="potentiometer at the end of\nits stroke (block fallen)")
        axis.text(first, 0.97, f" from {first:.2f} s the block lies\n on the catcher: the virtual\n"
                  " potentiometer reads the end\n of its stroke (clipped), not θ",
                  transform=axis.get_xaxis_transform(), fontsize=7, va="top", ha="left")
    axis.set_ylabel("θ/α [-]")
    axis.set_xlabel("time [s]")
    axis.legend(**legend)
    falls = [run.t_overturn for run in (result.test, result.theory) if run.overturned]
    if falls:
        axis.set_xlim(t[0], min(t[-1], max(falls) + max(0.5, 0.25 * max(falls))))
    metrics = result.metrics()
    # the RMS difference is taken before either run first exceeds alpha; a run that never
    # does (free rocking) compares the whole record
    unstable = [value for value in (metrics["t unstable test [s]"],
                                    metrics["t unstable theory [s]"]) if value is not None]
    window = (f"up to {min(unstable):.2f} s, where the first run exceeds α" if unstable
              else "over the whole record")
    axis.set_title(f"peak ratio virtual test/theory {metrics['peak ratio test/theory']}, RMS "
                   f"difference {metrics['RMS difference theta/alpha']} α ({window})",
                   fontsize=8)
    for panel in axes:
        panel.grid(True, lw=0.3, alpha=0.5)
    fig.align_ylabels(axes)
    # the block as the Calcomp caption gives it (B x H with units), under the given title
    block = describe_block(result.block)
    fig.suptitle(f"{title}\n{block}" if title else f"virtual test vs theory: {block}",
                 fontsize=10)
    return fig
