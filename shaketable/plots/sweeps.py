"""Figures of sweep tables: overturning maps, rocking spectra, fragility curves.

Every function takes the tidy table of :func:`shaketable.sweeps.execute.run_sweep` (or of
:func:`shaketable.models.rocking.batch.simulate_many`), an optional matplotlib ``ax`` and returns
the axes. matplotlib is imported inside the plotting functions only;
:func:`fragility_fit` is plain numerics.

* :func:`overturning_map` -- block size against aspect ratio (or B/H), colour =
  max |theta|/alpha, overturned cells black and marked "F" (the report's notation
  in Tables 4.1-4.3).
* :func:`rocking_spectrum` -- max |theta|/alpha against the size R or the
  frequency parameter p for one record, one line per aspect ratio.
* :func:`fragility_curve` -- fraction overturned against PGA over a record set,
  with the lognormal fragility fitted by maximum likelihood
  (:func:`fragility_fit`).
* :func:`pitch_phase_spread` -- the same block, record and PGA run at every phase
  of the table's pitch (Section 3.7 (2)): max |theta|/alpha of each phase and how
  many phases overturn.
* :func:`fragility_by_measure` -- fragility against any intensity measure, one curve per
  block with its confidence band (:func:`fragility_with_band` for one fit);
  :func:`fragility_contours` -- the 2-D P(overturn | PGA, PGV) surface;
  :func:`risk_curves` -- hazard curve, fragility and the risk integrand.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.files import subfolder, write_csv
from shaketable.plots.base import log_axis, place_legend, pyplot, stripe_fractions
from shaketable.sweeps.fragility import (
    MEASURE_LABELS,
    fragility_fit,
    fragility_surface,
    measure_column,
)
from shaketable.sweeps.stacks import impact_law, law_token

_RATIO = "max_theta_ratio [-]"

_AXES = {
    "aspect": ("aspect_ratio [-]", "H/B [-]"),
    "slenderness": ("B/H [-]", "B/H [-]"),
    "alpha": ("alpha [rad]", "α [rad]"),
    "width": ("block_width [m]", "width B [m]"),
    "height": ("block_height [m]", "height H [m]"),
    "R": ("R [m]", "size R [m]"),
    "p": ("p [rad/s]", "p [rad/s]"),
}


def _column(table, key):
    """The column of ``key`` (a short name of :data:`_AXES` or a column) and its label."""
    if key in _AXES:
        column, label = _AXES[key]
    else:
        column, label = key, key
    if column == "B/H [-]":
        return 1.0 / table["aspect_ratio [-]"].to_numpy(), label
    if column == "R [m]" and column not in table:
        return np.hypot(table["block_width [m]"], table["block_height [m]"]).to_numpy() / 2, \
            label
    if column not in table:
        raise ValueError(f"the table has no column {column!r} (for {key!r}); short names: "
                         f"{', '.join(_AXES)}")
    return table[column].to_numpy(), label


def _in_unit(values, label, unit):
    """A length axis converted from metres to ``unit`` (other axes unchanged)."""
    if not label.endswith("[m]") or unit == "m":
        return values, label
    from shaketable.core.constants import LENGTH_UNITS

    if unit not in LENGTH_UNITS:
        raise ValueError(f"length_unit must be one of {', '.join(LENGTH_UNITS)}, got {unit!r}")
    return values / LENGTH_UNITS[unit], label[:-3] + f"[{unit}]"


def _select(table, **conditions):
    """Rows where every given column equals its value (None: no condition)."""
    for column, value in conditions.items():
        if value is None:
            continue
        if column not in table:
            raise ValueError(f"the table has no column {column!r}")
        table = table[table[column] == value]
        if table.empty:
            raise ValueError(f"no rows with {column} == {value!r}")
    return table


def _one(table, column):
    values = table[column].unique()
    if len(values) > 1:
        raise ValueError(f"the rows mix several {column!r} ({', '.join(map(str, values[:5]))}); "
                         f"select one with {column.split(' ')[0]}=...")
    return values[0]


def overturning_map(table, *, x="aspect", y="width", record=None, cor=None, ax=None,
                    vmax=1.0, annotate=True, length_unit="m"):
    """Block size against aspect ratio, coloured by max |theta|/alpha, F = overturned.

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table; the rows selected must hold one run per (x, y) cell.
    x, y : str
        Short names (``"aspect"`` H/B, ``"slenderness"`` B/H, ``"alpha"``,
        ``"width"``, ``"height"``, ``"R"``, ``"p"``) or column names.
    record, cor : optional
        Select the rows of one record (``record`` column, or ``motion`` for a
        batch table) and one COR [-].
    vmax : float
        Top of the colour scale for max |theta|/alpha [-].
    annotate : bool
        Write the value (two decimals, as the report's tables) or F in each cell.
    length_unit : str
        Unit of a length axis (``"m"``, ``"ft"``, ``"in"``, ``"cm"``, ``"mm"``).

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()
    from matplotlib.colors import ListedColormap

    rows = _select(table, record=record, **{"cor [-]": cor})
    _one(rows, "cor [-]")
    _one(rows, "record" if "record" in rows else "motion")
    xs, x_label = _in_unit(*_column(rows, x), length_unit)
    ys, y_label = _in_unit(*_column(rows, y), length_unit)
    x_values = np.unique(np.round(xs, 12))
    y_values = np.unique(np.round(ys, 12))
    grid = np.full((y_values.size, x_values.size), np.nan)
    overturned = np.zeros_like(grid, dtype=bool)
    seen = np.zeros_like(grid, dtype=int)
    for xv, yv, ratio, over in zip(np.round(xs, 12), np.round(ys, 12), rows[_RATIO],
                                   rows["overturned"]):
        i, j = np.searchsorted(y_values, yv), np.searchsorted(x_values, xv)
        grid[i, j] = ratio
        overturned[i, j] = over
        seen[i, j] += 1
    if seen.max() > 1:
        raise ValueError("several runs fall in one cell of the map: select one record, COR, "
                         "scale and pitch phase")
    if ax is None:
        _, ax = plt.subplots(figsize=(7.5, 5.5))
    cmap = plt.get_cmap("viridis").with_extremes(bad="white")
    shown = np.ma.masked_invalid(np.where(overturned, np.nan, grid))
    image = ax.pcolormesh(np.arange(x_values.size + 1) - 0.5, np.arange(y_values.size + 1) - 0.5,
                          shown, cmap=cmap, vmin=0.0, vmax=vmax, shading="flat")
    ax.pcolormesh(np.arange(x_values.size + 1) - 0.5, np.arange(y_values.size + 1) - 0.5,
                  np.ma.masked_where(~overturned, np.ones_like(grid)),
                  cmap=ListedColormap(["#b2182b"]), shading="flat")
    if annotate:
        for i in range(y_values.size):
            for j in range(x_values.size):
                if seen[i, j] == 0:
                    continue
                if overturned[i, j]:
                    ax.text(j, i, "F", ha="center", va="center", color="white",
                            fontsize=8, fontweight="bold")
                else:
                    value = grid[i, j]
                    ax.text(j, i, f"{value:.2f}", ha="center", va="center", fontsize=6.5,
                            color="white" if value < 0.6 * vmax else "black")
    ax.set_xticks(range(x_values.size), [f"{v:.3g}" for v in x_values])
    ax.set_yticks(range(y_values.size), [f"{v:.3g}" for v in y_values])
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    bar = ax.figure.colorbar(image, ax=ax, extend="max")
    bar.set_label("max |θ|/α [-]  (red, F: overturned)")
    label = rows["record"].iloc[0] if "record" in rows else rows["motion"].iloc[0]
    ax.set_title(f"{label}, {impact_law(rows['cor [-]'].iloc[0])}: "
                 f"{int(overturned.sum())} of {int((seen > 0).sum())} overturn")
    return ax


def rocking_spectrum(table, *, x="p", record=None, cor=None, group="aspect", ax=None):
    """max |theta|/alpha against block size (R) or p for one record, a line per aspect ratio.

    Overturned runs are drawn as crosses on the dashed line at the top
    (max |theta|/alpha is not meaningful past pi/2).

    Parameters
    ----------
    table : pandas.DataFrame
    x : str
        ``"p"`` (frequency parameter [rad/s]), ``"R"`` (size [m]) or another
        short name or column.
    record, cor : optional
        Select one record and one COR.
    group : str
        One line per value of this (short name or column), default H/B.

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()

    rows = _select(table, record=record, **{"cor [-]": cor})
    _one(rows, "cor [-]")
    _one(rows, "record" if "record" in rows else "motion")
    xs, x_label = _column(rows, x)
    groups, group_label = _column(rows, group)
    ratios = rows[_RATIO].to_numpy()
    over = rows["overturned"].to_numpy()
    finite_top = max(1.0, float(np.nanmax(np.where(over, np.nan, ratios))) * 1.05
                     if (~over).any() else 1.0)
    top = finite_top * 1.08
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4.5))
    colours = plt.get_cmap("plasma")(np.linspace(0, 0.85, len(np.unique(groups))))
    for colour, value in zip(colours, np.unique(np.round(groups, 12))):
        pick = np.round(groups, 12) == value
        order = np.argsort(xs[pick])
        xv, rv, ov = xs[pick][order], ratios[pick][order], over[pick][order]
        shown = np.where(ov, np.nan, rv)
        name = group_label.replace(" [-]", "")
        ax.plot(xv, shown, "o-", ms=3, color=colour, label=f"{name} = {value:.3g}")
        ax.plot(xv[ov], np.full(ov.sum(), top), "x", color=colour, ms=6)
    ax.axhline(1.0, color="0.4", lw=0.8, ls=":")
    ax.axhline(top, color="0.6", lw=0.8, ls="--")
    ax.set_ylim(0, top * 1.08)
    # the overturned row is named on the axis, as a tick "F", not by a text on the crosses
    ticks = [tick for tick in ax.get_yticks() if 0 <= tick <= finite_top]
    ax.set_yticks(ticks + [top], [f"{tick:g}" for tick in ticks] + ["F (overturned)"])
    if x == "p":
        x_label += "   (larger blocks to the left: p = √(3g/4R))"
    ax.set_xlabel(x_label)
    ax.set_ylabel("max |θ|/α [-]")
    label = rows["record"].iloc[0] if "record" in rows else rows["motion"].iloc[0]
    ax.set_title(f"Rocking spectrum: {label}, {impact_law(rows['cor [-]'].iloc[0])}")
    place_legend(ax, fontsize=7, ncol=2)
    return ax


def fragility_curve(table, *, group="block", cor=None, pga="pga [g]", ax=None):
    """Fraction overturned against PGA over the records of a sweep, with lognormal fits.

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table with several records (or realisations) per PGA level.
    group : str or None
        One curve per value of this column (default per block).
    cor : float, optional
        Select one COR.
    pga : str
        PGA column (``"pga [g]"`` default).

    Returns
    -------
    matplotlib.axes.Axes
        With ``ax.fragility_fits``: a dict group -> :class:`FragilityFit`
        (None where every run, or none, overturned).
    """
    plt = pyplot()

    rows = _select(table, **{"cor [-]": cor})
    _one(rows, "cor [-]")
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4.5))
    groups = [(None, rows)] if group is None else list(rows.groupby(group, sort=False))
    colours = plt.get_cmap("tab10")(np.arange(len(groups)) % 10)
    fits = {}
    grid = np.linspace(max(1e-3, rows[pga].min() * 0.8), rows[pga].max() * 1.1, 300)
    for colour, (name, part) in zip(colours, groups):
        levels = part.groupby(np.round(part[pga], 9))["overturned"].agg(["mean", "size"])
        label = str(name) if name is not None else "all runs"
        ax.plot(levels.index, levels["mean"], "o", color=colour, ms=4,
                label=f"{label}: fraction of {int(levels['size'].median())} records")
        try:
            fit = fragility_fit(part[pga], part["overturned"])
        except ValueError:
            fits[name] = None
            continue
        fits[name] = fit
        ax.plot(grid, fit.probability(grid), "-", color=colour, lw=1.2,
                label=f"{label}: lognormal, median {fit.median:.3g}, β {fit.beta:.2f}")
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel("PGA [g]" if pga == "pga [g]" else pga)
    ax.set_ylabel("P(overturn) [-]")
    records = rows["record"].unique() if "record" in rows else rows["motion"].unique()
    n_motions = rows.groupby(["record", "seed"], dropna=False).ngroups if "record" in rows \
        else len(records)
    ax.set_title(f"Fragility: {', '.join(map(str, records))} ({n_motions} motions), "
                 f"{impact_law(rows['cor [-]'].iloc[0])}")
    ax.grid(alpha=0.3)
    place_legend(ax, fontsize=7)
    ax.fragility_fits = fits
    return ax


def pitch_phase_spread(table, *, record=None, cor=None, ax=None):
    """max |theta|/alpha of every pitch phase against PGA, for one record and COR.

    Section 3.7 (2) of the report: the same table motion repeated gives different
    responses, because the table's 12 Hz pitch starts at a different phase each
    time. Each dot is one phase; a phase that overturns is a cross on the "F" line,
    and the count of overturning phases is written above each PGA level.

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table with a ``pitch_phase [rad]`` column (a ``[pitch]`` sweep).
    record : str, optional
        Select one record (needed when the table has several).
    cor : float, optional
        Select one COR.

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()

    rows = _select(table, record=record, **{"cor [-]": cor})
    rows = rows[rows["pitch_phase [rad]"].notna()]
    if rows.empty:
        raise ValueError("the table has no runs with a pitch phase (a sweep with [pitch])")
    _one(rows, "cor [-]")
    _one(rows, "record")
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4.5))
    levels = np.round(rows["pga [g]"].to_numpy(), 6)
    ratios = rows[_RATIO].to_numpy()
    over = rows["overturned"].to_numpy(dtype=bool)
    standing_top = float(np.nanmax(ratios[~over])) if (~over).any() else 1.0
    top = max(1.2, standing_top * 1.15)
    unique = np.unique(levels)
    width = 0.25 * (np.min(np.diff(unique)) if unique.size > 1 else max(unique[0], 0.1))
    for level in unique:
        pick = levels == level
        phases = int(pick.sum())
        offsets = np.linspace(-width, width, phases) if phases > 1 else np.zeros(1)
        ax.plot(level + offsets[~over[pick]], ratios[pick][~over[pick]], "o", ms=3,
                color="tab:blue")
        ax.plot(level + offsets[over[pick]], np.full(int(over[pick].sum()), top), "x",
                ms=5, color="tab:red")
        ax.text(level, top * 1.04, f"{int(over[pick].sum())}/{phases} F", ha="center",
                va="bottom", fontsize=8, color="tab:red")
    ax.axhline(1.0, color="0.4", lw=0.8, ls=":")
    ax.axhline(top, color="0.6", lw=0.8, ls="--")
    ax.set_yticks([*[tick for tick in ax.get_yticks() if 0 <= tick < top * 0.95], top])
    ax.set_yticklabels([*[f"{tick:g}" for tick in ax.get_yticks()[:-1]], "F"])
    ax.set_ylim(0, top * 1.15)
    ax.set_xticks(unique)
    ax.set_xticklabels([f"{level:g}" for level in unique])
    ax.set_xlabel("PGA [g] (at each level, the pitch phases side by side)")
    ax.set_ylabel("max |θ|/α [-]")
    block = rows["block"].iloc[0] if rows["block"].nunique() == 1 else "several blocks"
    ax.set_title(f"{rows['record'].iloc[0]}: {block}, {impact_law(rows['cor [-]'].iloc[0])}, "
                 f"{int(rows['pitch_phase [rad]'].round(9).nunique())} pitch phases "
                 "(Section 3.7 (2))", fontsize=9)
    ax.grid(alpha=0.3)
    # what the markers and the dotted line are (the same at every level)
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], ls="none", marker="o", ms=3, color="tab:blue",
                      label="one phase, standing: its max |θ|/α"),
               Line2D([], [], ls="none", marker="x", ms=5, color="tab:red",
                      label="one phase, overturned (F; count above)"),
               Line2D([], [], ls=":", lw=0.8, color="0.4", label="|θ| = α")]
    place_legend(ax, handles=handles, fontsize=7)
    return ax


def sweep_figures(table, out) -> list:
    """The figures a sweep's table supports, written to folder ``out`` (PNG); their paths.

    * an overturning map (width against H/B) per record and COR, when the
      blocks vary in both;
    * a rocking spectrum (max |theta|/alpha against p) per record and COR,
      when the blocks vary;
    * fragility curves (fraction overturned against PGA, lognormal fits) per
      COR, when there are at least three PGA levels and several records or
      realisations per level (runs without pitch);
    * the spread over the pitch phases (:func:`pitch_phase_spread`) per record,
      block and COR, for a sweep with ``[pitch]``;
    * for a friction sweep with at least two PGA levels, peak slip and corner
      excursion against PGA, median and 84th percentile, per block and COR
      (:func:`shaketable.plots.sweep_slip.slip_against_intensity`).
    """
    from pathlib import Path

    plt = pyplot()
    import pandas as pd

    from shaketable.plots.base import save

    if "overturned block" in table:   # a stack sweep: its own figures
        from shaketable.plots.sweep_stacks import stack_sweep_figures

        return stack_sweep_figures(table, out)
    out = Path(out)
    out = subfolder(out.parent if str(out.parent) else ".", out.name, "figures folder")
    written = []
    widths = table["block_width [m]"].nunique()
    aspects = table["aspect_ratio [-]"].round(9).nunique()
    pitch_free = table[table["pitch_phase [rad]"].isna()] if "pitch_phase [rad]" in table \
        else table
    for (record, seed, cor), rows in pitch_free.groupby(["record", "seed", "cor [-]"],
                                                        sort=False, dropna=False):
        if rows["scale [-]"].nunique() > 1 or rows["pga [g]"].round(6).nunique() > 1:
            continue  # several intensities: the fragility figure covers them
        if not pd.isna(seed) and rows["record_kind"].iloc[0] == "artificial":
            record = f"{record}-seed{int(seed)}"
        label = f"{record}-{law_token(cor)}"
        if widths > 1 and aspects > 1 and rows.groupby(
                ["block_width [m]", "aspect_ratio [-]"]).size().max() == 1:
            figure, axis = plt.subplots(figsize=(8, 5))
            overturning_map(rows, ax=axis, length_unit="ft")
            axis.set_title(f"{record}, {impact_law(cor)}", fontsize=9)
            written.append(out / f"map-{label}.png")
            save(figure, written[-1])
        if rows["block"].nunique() > 1:
            figure, axis = plt.subplots(figsize=(8, 4))
            rocking_spectrum(rows, ax=axis)
            axis.set_title(f"{record}, {impact_law(cor)}", fontsize=9)
            written.append(out / f"spectrum-{label}.png")
            save(figure, written[-1])
    levels = pitch_free["pga [g]"].round(6).nunique()
    per_level = (pitch_free.groupby([pitch_free["pga [g]"].round(6), "block", "cor [-]"],
                                    dropna=False)
                 .size().min() if len(pitch_free) else 0)
    if levels >= 3 and per_level >= 2:
        for cor, rows in pitch_free.groupby("cor [-]", sort=False, dropna=False):
            figure, axis = plt.subplots(figsize=(7, 4.5))
            fragility_curve(rows, ax=axis)
            axis.set_title(f"fragility, {impact_law(cor)}", fontsize=9)
            written.append(out / f"fragility-{law_token(cor)}.png")
            save(figure, written[-1])
    if "peak corner excursion [m]" in table and levels >= 2:   # a friction sweep
        from shaketable.plots.sweep_slip import slip_against_intensity

        for (block, cor), rows in pitch_free.groupby(["block", "cor [-]"], sort=False,
                                                   dropna=False):
            written.append(out / f"slip-{block.replace(' ', '')}-{law_token(cor)}.png")
            save(slip_against_intensity(rows), written[-1])
    if "target_measure" in table:
        written.extend(measure_figures(table, out))
    if "pitch_phase [rad]" in table:
        pitched = table[table["pitch_phase [rad]"].notna()]
        for (record, seed, block, cor), rows in pitched.groupby(
                ["record", "seed", "block", "cor [-]"], sort=False, dropna=False):
            figure, axis = plt.subplots(figsize=(7, 4.5))
            pitch_phase_spread(rows, ax=axis)
            if not pd.isna(seed) and rows["record_kind"].iloc[0] == "artificial":
                record = f"{record}-seed{int(seed)}"
            name = f"pitch-{record}-{block.replace(' ', '')}-{law_token(cor)}"
            written.append(out / f"{name}.png")
            save(figure, written[-1])
    return written


def fragility_with_band(fit, *, ax=None, im=None, overturned=None, color="tab:blue",
                        label=None, grid=None):
    """One fragility fit: the lognormal curve, its pointwise confidence band and (given
    ``im`` and ``overturned``) the fraction overturned in bins of the IM.

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4.5))
    if grid is None:
        low = fit.median * np.exp(-3.0 * fit.beta)
        high = fit.median * np.exp(3.0 * fit.beta)
        if im is not None:
            low, high = min(low, float(np.min(im))), max(high, float(np.max(im)))
        grid = np.geomspace(low, high, 300)
    lower, upper = fit.band(grid)
    name = label if label is not None else (fit.measure or "fit")
    ax.fill_between(grid, lower, upper, color=color, alpha=0.18, lw=0)
    ax.plot(grid, fit.probability(grid), "-", color=color, lw=1.3,
            label=f"{name}: median {fit.median:.3g} [{fit.median_interval[0]:.3g}, "
                  f"{fit.median_interval[1]:.3g}], β {fit.beta:.2f} [{fit.beta_interval[0]:.2f}, "
                  f"{fit.beta_interval[1]:.2f}]")
    if im is not None and overturned is not None:
        centres, fractions, _ = stripe_fractions(im, overturned)
        ax.plot(centres, fractions, "o", color=color, ms=4)
    log_axis(ax.xaxis)
    ax.set_ylim(-0.03, 1.03)
    ax.set_ylabel("P(overturn) [-]")
    ax.grid(alpha=0.3, which="both")
    return ax


def fragility_by_measure(table, measure="pgv", *, group="block", cor=None, ax=None,
                         confidence=0.95):
    """Fragility against any intensity measure: one MSA fit per group (block) with its
    profile-likelihood band (shaded) and the fraction overturned in bins of the IM.

    Parameters
    ----------
    table : pandas.DataFrame
        A sweep table with the intensity-measure columns.
    measure : str
        Short name (``pga``, ``pgv``, ``pga*``, ``pgv*``, ``sa(1)``, ``sa_avg``...) or column.
    group : str
        One curve per value of this column.
    cor : float, optional
        Select one COR.

    Returns
    -------
    matplotlib.axes.Axes
        With ``ax.fragility_fits``: group -> FragilityFit (None where not identified).
    """
    plt = pyplot()

    rows = _select(table, **{"cor [-]": cor})
    _one(rows, "cor [-]")
    column = measure_column(rows, measure)
    if ax is None:
        _, ax = plt.subplots(figsize=(7.5, 4.8))
    colours = plt.get_cmap("tab10")(np.arange(10))
    fits = {}
    values = rows[column].to_numpy(dtype=float)
    grid = np.geomspace(values.min() * 0.8, values.max() * 1.25, 300)
    for k, (name, part) in enumerate(rows.groupby(group, sort=False)):
        try:
            fit = fragility_fit(part[column], part["overturned"], confidence=confidence,
                                measure=column)
        except ValueError:
            fits[name] = None
            continue
        fits[name] = fit
        fragility_with_band(fit, ax=ax, im=part[column], overturned=part["overturned"],
                            color=colours[k % 10], label=str(name), grid=grid)
    ax.set_xlabel(MEASURE_LABELS.get(column, column) + "  (log scale)")
    records = rows.groupby(["record", "seed"], dropna=False).ngroups if "record" in rows \
        else rows["motion"].nunique()
    ax.set_title(f"Fragility against {MEASURE_LABELS.get(column, column).split(' [')[0]}: "
                 f"{records} motions, {impact_law(rows['cor [-]'].iloc[0])} (bands: "
                 f"{100 * confidence:g} % profile likelihood)", fontsize=9)
    place_legend(ax, fontsize=7)
    ax.fragility_fits = fits
    return ax


def fragility_contours(surface, *, ax=None, table=None, x_unit=1.0, y_unit=1.0,
                       levels=(0.1, 0.3, 0.5, 0.7, 0.9)):
    """The 2-D fragility ``P(overturn | x, y)`` as contours, with the runs (given a
    ``table``: dots stand, crosses overturn), log axes.

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 5))
    if table is not None:
        x = table[surface.x_measure].to_numpy(dtype=float)
        y = table[surface.y_measure].to_numpy(dtype=float)
        over = table["overturned"].to_numpy(dtype=bool)
        x_range = (x.min() * 0.8, x.max() * 1.25)
        y_range = (y.min() * 0.8, y.max() * 1.25)
    else:
        x_range, y_range = (0.1, 10.0), (0.01, 2.0)
    xs = np.geomspace(*x_range, 200)
    ys = np.geomspace(*y_range, 200)
    grid_x, grid_y = np.meshgrid(xs, ys)
    probability = surface.probability(grid_x, grid_y)
    filled = ax.contourf(grid_x / x_unit, grid_y / y_unit, probability,
                         levels=np.linspace(0, 1, 11), cmap="RdYlBu_r", alpha=0.75)
    lines = ax.contour(grid_x / x_unit, grid_y / y_unit, probability, levels=list(levels),
                       colors="k", linewidths=0.8)
    ax.clabel(lines, fmt="%.1f", fontsize=7)
    if table is not None:
        ax.plot(x[~over] / x_unit, y[~over] / y_unit, "o", ms=2.5, mfc="none", mec="0.15",
                mew=0.6, label="stands")
        ax.plot(x[over] / x_unit, y[over] / y_unit, "x", ms=3, color="k", mew=0.7,
                label="overturns")
        place_legend(ax, fontsize=7)
    log_axis(ax.xaxis)
    log_axis(ax.yaxis)
    ax.figure.colorbar(filled, ax=ax).set_label("P(overturn) [-]")
    ax.set_xlabel(MEASURE_LABELS.get(surface.x_measure, surface.x_measure))
    ax.set_ylabel(MEASURE_LABELS.get(surface.y_measure, surface.y_measure))
    b0, b1, b2 = surface.coefficients
    ax.set_title(f"P(overturn) = Φ({b0:.2f} + {b1:.2f} ln x + {b2:.2f} ln y), "
                 f"{surface.n_runs} runs", fontsize=9)
    return ax


def _merged_stripes(stripes, rtol: float = 1e-9):
    """(levels, runs, overturned runs) of a fit's stripes, levels within ``rtol`` of each
    other merged: motions scaled to one target measure reach it only to a few ulps, and
    each distinct value is a stripe of the fit (whose likelihood does not depend on how
    the runs are grouped), but one level of the analysis on a figure."""
    levels, runs, failures = (np.asarray(part, dtype=float) for part in stripes)
    order = np.argsort(levels)
    levels, runs, failures = levels[order], runs[order], failures[order]
    starts = np.flatnonzero(np.r_[True, levels[1:] > levels[:-1] * (1.0 + rtol)])
    return (np.add.reduceat(levels * runs, starts) / np.add.reduceat(runs, starts),
            np.add.reduceat(runs, starts), np.add.reduceat(failures, starts))


def risk_curves(fragility, hazard, result=None, *, ax=None, legend=True):
    """Hazard curve (annual rate of exceedance, log-log), the fragility on a second axis
    (with its confidence band and the fraction overturned at each level of a
    multiple-stripe fit), and the risk integrand ``P(overturn | im) |d lambda / d ln im|``
    (shaded: where the rate of overturning comes from; a rate [1/yr], drawn on the rate
    axis, which its legend entry says).

    Parameters
    ----------
    legend : bool
        Draw the legend below the panel. Without it (a figure of several panels with one
        legend, :func:`shared_risk_legend`), the fragility's median and beta go into the
        title instead of the legend.

    Returns
    -------
    matplotlib.axes.Axes
        The hazard axis (the fragility's is ``ax.fragility_axis``). The rate axis shows the
        whole hazard curve.
    """
    plt = pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(7.5, 4.8))
    x = np.geomspace(hazard.im[0], hazard.im[-1], 400)
    rate = hazard.rate_at(x)
    ax.loglog(hazard.im, hazard.rate, "o", ms=3, color="tab:blue")
    ax.loglog(x, rate, "-", color="tab:blue",
              label="hazard: annual rate of exceedance [1/yr] (left axis)")
    density = -np.gradient(rate, np.log(x)) * fragility.probability(x)
    ax.fill_between(x, np.maximum(density, 1e-30), 1e-30, color="tab:red", alpha=0.3,
                    label="integrand P(overturn | im) |dλ/d ln im| [1/yr]: a rate, "
                          "on the left axis")
    # the whole hazard curve (the input) stays in view; the integrand is cut below it
    ax.set_ylim(min(hazard.rate) * 0.5, max(max(hazard.rate), density.max()) * 2)
    ax.set_xlabel(MEASURE_LABELS.get(hazard.column, hazard.column))
    ax.set_ylabel("annual rate [1/yr]")
    ax.grid(alpha=0.3, which="both")
    other = ax.twinx()
    unit = hazard.column.partition("[")[2].rstrip("]")
    median = f"median {fragility.median:.3g}{' ' + unit if unit else ''}, β {fragility.beta:.2f}"
    other.plot(x, fragility.probability(x), "-", color="k", lw=1.2,
               label=f"fragility: {median} (right axis)" if legend
               else "fragility (right axis; median and β in the title)")
    if getattr(fragility, "stripes", ()):
        lower, upper = fragility.band(x)
        other.fill_between(x, lower, upper, color="0.5", alpha=0.2, lw=0,
                           label=f"{fragility.confidence:.0%} band (profile likelihood)")
        levels, runs, failures = _merged_stripes(fragility.stripes)
        single = bool(np.all(runs <= 1))   # every run at an IM of its own: 0 or 1 each
        other.plot(levels, failures / runs, "s", ms=3.5, mfc="white", mec="k", mew=0.8,
                   label="each run: 1 overturned, 0 standing (the data fitted)" if single
                   else "fraction overturned at each level (the data fitted)")
    other.set_ylim(-0.02, 1.02)
    other.set_ylabel("P(overturn) [-]")
    ax.fragility_axis = other
    if legend:   # below the axes: inside, any corner would cover the integrand or the points
        handles, labels = risk_legend_entries([ax])
        ax.legend(handles, labels, fontsize=7, ncol=2, loc="upper center",
                  bbox_to_anchor=(0.5, -0.2), frameon=False)
    title = "" if legend else f"fragility {median}\n"
    if result is not None:   # the interval the fit's uncertainty gives, when it is known
        low, high = getattr(result, "rate_interval", (math.nan, math.nan))
        known = math.isfinite(low) and math.isfinite(high)
        p_low, p_high = getattr(result, "probability_interval", (math.nan, math.nan))
        title += (f"λ = {result.rate:.2g} /yr"
                  + (f" ({100 * result.confidence:g} %: {low:.2g} to {high:.2g})" if known
                     else f" (±{result.error:.1g})")
                  + f", P(overturn in {result.years:g} yr) = {result.probability:.2g}"
                  + (f" ({p_low:.2g} to {p_high:.2g})" if known else ""))
    if title:
        ax.set_title(title.rstrip("\n"), fontsize=9)
    return ax


def risk_legend_entries(axes) -> tuple:
    """(handles, labels) of the rate and fragility axes of :func:`risk_curves` panels, each
    label once, in the order first drawn."""
    entries: dict = {}
    for axis in axes:
        for part in (axis, axis.fragility_axis):
            for handle, label in zip(*part.get_legend_handles_labels()):
                entries.setdefault(label, handle)
    return list(entries.values()), list(entries)


def shared_risk_legend(axes) -> None:
    """One legend for several :func:`risk_curves` panels (drawn with ``legend=False``),
    below the last, and one range of annual rates on every panel (the hazard curve is the
    same; the integrands differ)."""
    low = min(axis.get_ylim()[0] for axis in axes)
    high = max(axis.get_ylim()[1] for axis in axes)
    for axis in axes:
        axis.set_ylim(low, high)
    handles, labels = risk_legend_entries(axes)
    axes[-1].legend(handles, labels, fontsize=7, ncol=2, loc="upper center",
                    bbox_to_anchor=(0.5, -0.2), frameon=False)


def measure_figures(table, out) -> list:
    """The intensity-measure figures of a sweep scaled to a measure (``target_measure``
    column), written to folder ``out``: fragility against the target measure, PGA and
    PGV p/(g tan alpha) with bands, the 2-D PGA-PGV surface as contours, and the
    comparison of the measures (``im-comparison.csv``). Their paths."""
    from pathlib import Path

    plt = pyplot()
    from shaketable.plots.base import save
    from shaketable.sweeps.fragility import compare_measures

    out = Path(out)
    written = []
    target = str(table["target_measure"].iloc[0])
    rows = table[table["pitch_phase [rad]"].isna()] if "pitch_phase [rad]" in table else table
    for cor, part in rows.groupby("cor [-]", sort=False, dropna=False):
        for measure in dict.fromkeys([target, "pga", "pgv*"]):
            figure, axis = plt.subplots(figsize=(7.5, 4.8))
            fragility_by_measure(part, measure, ax=axis)
            name = measure.replace("*", "-star")
            written.append(out / f"fragility-{name}-{law_token(cor)}.png")
            save(figure, written[-1])
        blocks = list(part.groupby("block", sort=False))
        if len(blocks) > 4:
            blocks = [("all blocks", part)]
        figure, axes = plt.subplots(1, len(blocks), figsize=(5.2 * len(blocks), 4.6),
                                    squeeze=False)
        drawn = 0
        for axis, (block, rows_of_block) in zip(axes[0], blocks):
            try:
                surface = fragility_surface(rows_of_block["pga [m/s^2]"],
                                            rows_of_block["pgv [m/s]"],
                                            rows_of_block["overturned"])
            except ValueError:
                axis.set_axis_off()
                axis.set_title(f"{block}: outcomes separated, no surface", fontsize=9)
                continue
            fragility_contours(surface, ax=axis, table=rows_of_block)
            axis.set_title(f"{block}\n" + axis.get_title(), fontsize=8)
            drawn += 1
        if drawn:
            figure.tight_layout()
            written.append(out / f"fragility-pga-pgv-{law_token(cor)}.png")
            save(figure, written[-1])
        else:
            plt.close(figure)
        if part["block"].nunique() > 1:
            comparison = compare_measures(part, [m for m in ("pga", "pgv", "sa(1)", "sa_avg",
                                                              "pga*", "pgv*")
                                                 if _has_measure(part, m)])
            written.append(out / f"im-comparison-{law_token(cor)}.csv")
            write_csv(written[-1], comparison)
    return written


def _has_measure(table, measure) -> bool:
    try:
        measure_column(table, measure)
    except ValueError:
        return False
    return True
