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


__all__ = ["asymmetric_history", "np"]
