"""The test-vs-theory figure of a virtual shaking-table test (Figs. 3.4, 3.5, 3.7-3.9)."""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G
from shaketable.plots.base import pyplot


def plot_test_vs_theory(result, fig=None, title: str | None=None):
    """Test and theory overlaid, like Figs. 3.4 and 3.7-3.9.

    ``result`` is a :class:`VirtualTestResult`; see :meth:`VirtualTestResult.plot`.
    """
    plt = pyplot()

    driven = bool(np.any(result.test.motion.horizontal) or np.any(result.test.motion.vertical_or_zero))
    rows = 2 if result.measurement.table_horizontal is not None and driven else 1
    if fig is None:
        fig = plt.figure(figsize=(8, 2.6 + 2.4 * rows))
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    t = result.measurement.t
    alpha = result.block.alpha
    if rows == 2:
        axes[0].plot(t, result.measurement.table_horizontal / G, lw=0.8, color="k",
                     label="horizontal")
        if result.measurement.table_vertical is not None:
            axes[0].plot(t, result.measurement.table_vertical / G, lw=0.8, color="tab:blue",
                         label="vertical")
        axes[0].set_ylabel("table acc. [g]\n(digitized)")
        axes[0].legend(loc="upper right", fontsize=7, frameon=False)
    axis = axes[-1]
    axis.plot(t, result.measured_theta() / alpha, color="k", lw=1.0,
              label=f"test (measured, true COR {result.test.cor:g})")
    axis.plot(t, result.theory_theta() / alpha, color="tab:red", lw=1.0, ls="--",
              label=f"theory (COR {result.theory_cor:.3f})")
    for level in (-1.0, 1.0):
        axis.axhline(level, color="0.4", ls=":", lw=0.8)
    limit = max(1.5, min(4.0, 1.1 * float(np.max(np.abs(result.measured_theta()))) / alpha))
    axis.set_ylim(-limit, limit)
    axis.set_ylabel("θ/α [-]")
    axis.set_xlabel("time [s]")
    axis.legend(loc="upper right", fontsize=7, frameon=False)
    metrics = result.metrics()
    axis.set_title(f"peak ratio {metrics['peak ratio test/theory']}, RMS difference "
                   f"{metrics['RMS difference theta/alpha']} α", fontsize=8)
    fig.suptitle(title or f"test vs theory: {result.block.describe()}", fontsize=10)
    fig.tight_layout()
    return fig
