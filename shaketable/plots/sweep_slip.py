"""The slip figure of a friction sweep: peak slip and corner excursion against intensity.

A sweep with ``[friction]`` runs the planar block (:mod:`shaketable.sweeps.friction`);
besides whether it overturns, an engineer sizes the clearance around a block from how
far it slides and how far its corners travel. :func:`slip_against_intensity` draws, per
intensity level, every standing run's peak slip and peak corner excursion, their median
and 84th percentile (the usual "median and median plus one sigma" of a record suite), and
how many runs overturned (their slip is not a clearance: they fell).
"""

from __future__ import annotations

import numpy as np

from shaketable.plots.base import pyplot

#: The columns drawn, with their panel titles.
SLIP_COLUMNS = (("peak slip [m]", "peak slip of the base"),
                ("peak corner excursion [m]", "peak corner excursion (clearance)"))


def _length_unit(block_label: str) -> str:
    """The unit a block label ends with (``"2 x 0.5 m"`` -> ``"m"``), m if none."""
    unit = str(block_label).rsplit(" ", 1)[-1]
    return unit if unit in ("m", "cm", "mm", "in", "ft") else "m"


def slip_against_intensity(rows, *, intensity: str = "pga [g]", fig=None):
    """Peak slip and corner excursion of one block and COR against the intensity.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of a friction sweep's table for one block, COR and friction pair (the
        columns of :data:`SLIP_COLUMNS`, ``overturned`` and ``intensity``).
    intensity : str
        The intensity column (default ``pga [g]``).
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
        Two panels; lengths in the unit of the block's label (mm or in below one m or ft).
    """
    from shaketable.core.constants import LENGTH_UNITS
    from shaketable.core.units import display_length_unit

    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(10, 4.2), layout="constrained")
    axes = fig.subplots(1, 2, sharex=True)
    block = str(rows["block"].iloc[0])
    standing = rows[~rows["overturned"].astype(bool)]
    levels = np.sort(rows[intensity].round(6).unique())
    for axis, (column, title) in zip(axes, SLIP_COLUMNS):
        largest = float(standing[column].max()) if len(standing) else 0.0
        unit = display_length_unit(largest if np.isfinite(largest) else 0.0,
                                   _length_unit(block))
        scale = LENGTH_UNITS[unit]
        axis.plot(standing[intensity], standing[column] / scale, "o", ms=3.5, color="0.6",
                  alpha=0.7, label="each standing run")
        medians, p84s, shown = [], [], []
        for level in levels:
            values = standing.loc[standing[intensity].round(6) == level, column].to_numpy()
            if values.size:
                shown.append(level)
                medians.append(np.median(values) / scale)
                p84s.append(np.percentile(values, 84) / scale)
        axis.plot(shown, medians, "-", color="tab:blue", lw=1.6, label="median")
        axis.plot(shown, p84s, "--", color="tab:red", lw=1.4, label="84th percentile")
        for level in levels:
            at = rows[rows[intensity].round(6) == level]
            fell = int(at["overturned"].astype(bool).sum())
            if fell:
                axis.annotate(f"{fell}/{len(at)}\nfell", (level, 1.0),
                              xycoords=axis.get_xaxis_transform(), ha="center", va="top",
                              fontsize=7, color="tab:red")
        axis.set_ylabel(f"{title} [{unit}]")
        axis.set_xlabel(intensity)
        axis.set_ylim(bottom=0.0)
        axis.grid(True, lw=0.3, alpha=0.5)
        axis.legend(fontsize=7, loc="upper left")
    cor = rows["cor [-]"].iloc[0]
    fig.suptitle(f"{block}, COR {cor:g}: slip and clearance against intensity "
                 f"({rows['record'].nunique()} record(s); overturned runs left out of the "
                 "statistics)", fontsize=10)
    return fig
