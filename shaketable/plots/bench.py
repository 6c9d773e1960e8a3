"""Work-precision figure of :mod:`shaketable.studies.benchmark_cases` (matplotlib is imported only here).

One log-log panel per benchmark case: the error of every method against the
truth (``reference`` at the tightest tolerance) versus the median run time.
Solid lines with filled markers: relative error of max |theta|; dashed lines
with open markers: largest relative error of the event times (impacts before
20 s, start, unstable, overturn, rest, airborne). Each line is one method
swept over its setting; the first and last settings are written at the ends
of the max |theta| line (rtol for ``fast`` and ``reference``, subdivisions
for ``predictor-corrector``).

The coupled planar model joins it: its compiled engine (``planar``) and its
SciPy reference (``planar-reference``) are lines on the rocking-limit case's panel (ample
friction, against that case's rocking truth), and each coupled case of
:mod:`shaketable.studies.planar_work_precision` gets a panel of its own (against the planar
reference at rtol 1e-13), where a dash-dotted line adds the error of the peak slip. The
Moreau-Jean time stepping (``moreau-jean``, grey, labelled by its step h) is drawn on the
coupled panels: first order in h, against the planar reference with the plastic Newton law
(``cor="housner"``) on each case's first seconds (``MOREAU_WINDOW``).
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.plots.base import pyplot
from shaketable.studies.planar_work_precision import (
    AMPLE_FRICTION,
    MOREAU_WINDOW,
    PLANAR_TRUTH_RTOL,
)

#: Colour and marker of each method.
STYLE = {
    "fast": ("tab:blue", "o"),
    "predictor-corrector": ("tab:orange", "s"),
    "linear": ("tab:green", "D"),
    "reference": ("tab:red", "^"),
    "planar": ("tab:purple", "P"),
    "planar-reference": ("tab:brown", "v"),
    "moreau-jean": ("tab:gray", "X"),
    "stack": ("tab:olive", "*"),
    "stack-reference": ("tab:cyan", "h"),
}

#: Title of a coupled case's panel: its truth is not the rocking one.
PLANAR_TRUTH_NOTE = f"vs planar-reference {PLANAR_TRUTH_RTOL:g}"

#: Title of the rocking-limit panel's second line.
PLANAR_LIMIT_NOTE = (f"planar: μs = μd = {AMPLE_FRICTION.static:g}"
                     if AMPLE_FRICTION.static == AMPLE_FRICTION.dynamic
                     else f"planar: μs = {AMPLE_FRICTION.static:g}, "
                          f"μd = {AMPLE_FRICTION.dynamic:g}")

#: Errors below this are drawn on it (an error of exactly 0 has no logarithm) [-].
ERROR_FLOOR = 1e-16


def _short(label: str) -> str:
    """``rtol=1e-08`` -> ``1e-8``; ``subdivisions=4`` -> ``n=4``; ``h=0.00025`` -> ``h=2.5e-4``."""
    if label.startswith("rtol="):
        value = float(label[5:])
        exponent = math.log10(value)
        return f"1e{round(exponent)}" if abs(exponent - round(exponent)) < 1e-9 else f"{value:g}"
    if label.startswith("subdivisions="):
        return "n=" + label.split("=", 1)[1]
    if label.startswith("h="):   # a time step: h=0.00025 -> h=2.5e-4
        digits, power = f"{float(label[2:]):e}".split("e")
        return f"h={float(digits):g}e{int(power)}"
    return ""


#: Height of a row of end labels [points] and their size [points].
_ROW, _FONT = 8.0, 6.5


def _annotate_ends(ax, ends):
    """Write the end labels, each a row higher than an earlier one it would run into.

    Labels of different methods often fall on one spot (every method at the error floor,
    or two lines starting at the same time and error): a label is lifted by a row while
    it shares the height of an earlier label within about a label's width of it
    (positions in points on the panel as laid out when this is called). The time axis is
    widened until every label lies inside the panel.
    """
    box = ax.get_window_extent()
    points_per_pixel = 72.0 / ax.figure.dpi
    height_points = box.height * points_per_pixel
    width_points = box.width * points_per_pixel
    (y0, y1) = np.log10(ax.get_ylim())
    for _ in range(5):
        x0, x1 = np.log10(ax.get_xlim())
        placed = []  # (left, right, bottom, lift) in points from the panel's lower left
        for time, error, text, align, _color in ends:
            x = (math.log10(time) - x0) / (x1 - x0) * width_points
            y = (math.log10(error) - y0) / (y1 - y0) * height_points
            width = 0.62 * _FONT * len(text) + 3.0  # DejaVu Sans digits, the 3-point gap
            left, right = (x - width, x) if align == "right" else (x, x + width)
            lift = 3.0
            while any(left < other_right and other_left < right
                      and abs(y + lift - other_bottom) < _ROW
                      for other_left, other_right, other_bottom, _ in placed):
                lift += _ROW
            placed.append((left, right, y + lift, lift))
        over_left = max(0.0, -min(left for left, *_ in placed))
        over_right = max(0.0, max(right for _, right, *_ in placed) - width_points)
        if over_left == 0.0 and over_right == 0.0:
            break
        decades = (x1 - x0) / width_points  # per point
        ax.set_xlim(10 ** (x0 - (over_left + 2.0) * decades),
                    10 ** (x1 + (over_right + 2.0) * decades))
    for (time, error, text, align, color), (*_, lift) in zip(ends, placed):
        ax.annotate(text, (time, error), textcoords="offset points",
                    xytext=(-3 if align == "right" else 3, lift), ha=align, fontsize=_FONT,
                    color=color)

#: A max |theta| error below this for every method, the linear model included, means the
#: case fixes the peak (a different model gets it too): it measures no method [-].
FIXED_PEAK_ERROR = 1e-12


def fixed_peak(rows) -> str | None:
    """Why the max |theta| of a case's rows carries no information, or None when it does.

    When every method, the linear (closed-form) model included, gets the truth's max
    |theta| to :data:`FIXED_PEAK_ERROR`, the case fixes it: a block that overturns peaks
    at alpha before instability (the peak the errors are measured on) whatever the
    method, and a block released from rest in free rocking peaks at its release angle.
    """
    if "linear" not in set(rows["method"]):
        return None
    errors = rows["error max_theta [-]"].to_numpy(dtype=float)
    if not (errors.size and np.all(np.isfinite(errors)) and np.all(errors <= FIXED_PEAK_ERROR)):
        return None
    overturns = "status truth" in rows and (rows["status truth"] == "overturned").all()
    return ("max |θ| = α for every method\n(the block overturns): not drawn" if overturns
            else "max |θ| = the release angle\nfor every method: not drawn")


def work_precision_panel(frame, case: str, ax=None, annotate: bool = True):
    """Draw one case of a :func:`shaketable.studies.work_precision.work_precision` frame.

    Parameters
    ----------
    frame : pandas.DataFrame
        Output of :func:`shaketable.studies.work_precision.work_precision`.
    case : str
        The case to draw (``frame["case"]``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (a new figure otherwise).
    annotate : bool
        Write the first and last setting of each line next to it.

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 4))
    rows = frame[frame["case"] == case]
    # a max |theta| every method gets exactly (the case fixes it) is not drawn: its line
    # would sit at the floor and make the linear model look exact; the end labels then go
    # on the event-time lines
    fixed = fixed_peak(rows)
    labelled = "error events [-]" if fixed else "error max_theta [-]"
    # room at both ends of the time axis for the labels written beside the end points
    ax.margins(x=0.12)
    ends = []  # (time, error, text, align, colour) of the labelled end points
    for method, (color, marker) in STYLE.items():
        group = rows[rows["method"] == method]
        if group.empty:
            continue
        time = group["time [s]"].to_numpy(dtype=float)
        order = np.argsort(time) if method != "linear" else np.arange(time.size)
        lines = [("error max_theta [-]", "-", color)] if not fixed else []
        lines.append(("error events [-]", "--", "none"))
        if "error peak slip [-]" in group and group["error peak slip [-]"].notna().any():
            lines.append(("error peak slip [-]", "-.", "white"))
        for column, style, face in lines:
            error = np.maximum(group[column].to_numpy(dtype=float), ERROR_FLOOR)
            error = np.where(np.isfinite(error), error, np.nan)
            ax.loglog(time[order], error[order], style, color=color, marker=marker,
                      markerfacecolor=face, markersize=4, linewidth=1.2)
        if annotate and method != "linear" and len(group) > 1:
            error = np.maximum(group[labelled].to_numpy(dtype=float), ERROR_FLOOR)
            labels = list(group["setting"])
            # the labels at the two ends of the line in time, written away from each other
            # (the first setting is not always the fastest: "1e-81e-12" ran together)
            for index, align in ((int(order[0]), "right"), (int(order[-1]), "left")):
                if np.isfinite(error[index]):
                    ends.append((time[index], error[index], _short(labels[index]), align, color))
    ax.set_ylim(ERROR_FLOOR / 3, 10.0)
    if ends:
        _annotate_ends(ax, ends)
    ax.axhline(1e-8, color="0.6", linewidth=0.8, linestyle=":")
    if fixed:
        ax.text(0.97, 0.96, fixed, transform=ax.transAxes, ha="right", va="top", fontsize=6.5,
                color="0.25")
    coupled = "truth" in rows and (rows["truth"] == "planar-reference").any()
    stacked = "truth" in rows and (rows["truth"] == "stack-reference").any()
    limit = not coupled and rows["method"].isin(["planar", "planar-reference"]).any()
    title = (f"{case}\n({PLANAR_TRUTH_NOTE})" if coupled
             else f"{case}\n(vs stack-reference {rows['truth rtol'].iloc[0]:g})" if stacked
             else f"{case}\n({PLANAR_LIMIT_NOTE})" if limit else case)
    ax.set_title(title, fontsize=9)
    # minor ticks unlabelled: on a panel spanning about one decade matplotlib labels
    # them (2 x 10^-4, 4 x 10^-4, ...) and the labels overrun each other
    from matplotlib.ticker import NullFormatter

    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.tick_params(labelsize=7)
    ax.grid(True, which="major", linewidth=0.3, alpha=0.6)
    return ax


def work_precision_figure(frame, cases=None, columns: int = 4, fig=None, planar=None,
                          stack=None):
    """The work-precision grid: one panel per case, shared legend.

    Parameters
    ----------
    frame : pandas.DataFrame
        Output of :func:`shaketable.studies.work_precision.work_precision` (with the
        planar rows of the rocking-limit case, if any).
    cases : list of str, optional
        Cases in panel order (default: as they appear in ``frame``).
    columns : int
        Panels per row at most (fewer when that leaves fewer empty slots on the last
        row: 5 panels at 4 per row are drawn 3 + 2).
    fig : matplotlib.figure.Figure, optional
        Figure to draw into (a new one, sized to the grid, otherwise).
    planar : pandas.DataFrame, optional
        Output of :func:`shaketable.studies.planar_work_precision.planar_work_precision`:
        a panel per coupled case after the rocking ones.
    stack : pandas.DataFrame, optional
        Output of :func:`shaketable.studies.stack_work_precision.stack_work_precision`: a
        panel per stack case, last.

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    from matplotlib.lines import Line2D

    if cases is None:
        cases = list(dict.fromkeys(frame["case"])) if "case" in frame else []
    panels = [(frame, case) for case in cases]
    if planar is not None and not planar.empty:
        panels += [(planar, case) for case in dict.fromkeys(planar["case"])]
    if stack is not None and not stack.empty:
        panels += [(stack, case) for case in dict.fromkeys(stack["case"])]
    if not panels:
        raise ValueError("frame has no cases to draw")
    columns = max(1, min(int(columns), len(panels)))
    rows = int(math.ceil(len(panels) / columns))
    columns = int(math.ceil(len(panels) / rows))   # as few empty slots as the rows allow
    if fig is None:
        fig = plt.figure(figsize=(3.3 * columns + 0.6, 2.75 * rows + 1.1))
    axes = fig.subplots(rows, columns, squeeze=False)
    _fixed_layout(fig)
    for ax, (source, case) in zip(axes.flat, panels):
        work_precision_panel(source, case, ax=ax)
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    for ax in axes[:, 0]:
        ax.set_ylabel("error vs truth [-]", fontsize=8)
    for column in range(columns):   # under the lowest panel drawn in each column
        drawn = [ax for ax in axes[:, column] if ax.get_visible()]
        drawn[-1].set_xlabel("median run time [s]", fontsize=8)
    methods = set(frame["method"]) if "method" in frame else set()
    if planar is not None and not planar.empty:
        methods |= set(planar["method"])
    if stack is not None and not stack.empty:
        methods |= set(stack["method"])
    handles = [Line2D([], [], color=color, marker=marker, label=method)
               for method, (color, marker) in STYLE.items() if method in methods]
    handles += [Line2D([], [], color="k", marker="o",
                       label="max |θ| (solid; not drawn where the case fixes it)"),
                Line2D([], [], color="k", marker="o", markerfacecolor="none", linestyle="--",
                       label="event times (dashed)")]
    caption = ("Work-precision: error against the reference at rtol 2.5e-14 "
               "(labels: rtol of fast/reference, n = predictor-corrector subdivisions; "
               f"errors below {ERROR_FLOOR:g} drawn at it)")
    if planar is not None and not planar.empty:
        handles.append(Line2D([], [], color="k", marker="o", markerfacecolor="white",
                              linestyle="-.", label="peak slip (dash-dot)"))
        caption = ("Work-precision: error against the rocking reference at rtol 2.5e-14 "
                   f"({PLANAR_LIMIT_NOTE} on the rocking-limit panel); the coupled "
                   "panels (planar block with friction)\nagainst the planar reference at rtol "
                   f"{PLANAR_TRUTH_RTOL:g} (labels: rtol, n = predictor-corrector subdivisions; "
                   f"errors below {ERROR_FLOOR:g} drawn at it)")
        if (planar["method"] == "moreau-jean").any():
            moreau = dict.fromkeys(planar.loc[planar["method"] == "moreau-jean", "case"])
            windows = ", ".join(f"{MOREAU_WINDOW[name]:g} s of {name}" if name in MOREAU_WINDOW
                                else name for name in moreau)
            caption += ("\nmoreau-jean (labels: step h): plastic Newton law, against "
                        f"planar-reference with cor = housner on the first {windows}")
    if stack is not None and not stack.empty:
        caption += ("\nstack panels (columns of blocks, plastic impacts): the compiled stack "
                    "engine and its SciPy engine against the SciPy engine at rtol "
                    f"{stack['truth rtol'].iloc[0]:g} (labels: rtol)")
    handles.append(Line2D([], [], color="0.6", linestyle=":", label="1e-8 target"))
    legend_columns = len(handles) if len(handles) <= 9 else int(math.ceil(len(handles) / 2))
    fig.legend(handles=handles, loc="upper center", ncol=legend_columns, fontsize=8,
               frameon=False)
    fig.suptitle(caption, fontsize=8.5, y=0.005, va="bottom")
    _fixed_layout(fig, legend_rows=1 if len(handles) == legend_columns else 2,
                  caption_rows=caption.count("\n") + 1)
    return fig


def _fixed_layout(fig, legend_rows: int = 2, caption_rows: int = 3) -> None:
    """Place the grid of panels by fixed margins [inches] around it.

    The room for the tick labels, axis labels and the two-line panel titles is the same
    on every grid, so it is set once instead of measured (``tight_layout`` drew every
    text of the figure to measure it: a second of CPU on a few panels, several on the
    full grid); the shared legend above and the caption below get their rows' height.
    Called before the panels are drawn (the end labels are placed on the panel as laid
    out) and again with the legend's and the caption's rows.
    """
    width, height = fig.get_size_inches()
    grid = fig.axes[0].get_subplotspec().get_gridspec() if fig.axes else None
    rows, columns = (grid.nrows, grid.ncols) if grid is not None else (1, 1)
    left, right, between_x = 0.62, 0.12, 0.5
    top = (0.3 if legend_rows == 1 else 0.45) + 0.4
    bottom = 0.45 + 0.16 * caption_rows
    between_y = 0.72
    panel_width = (width - left - right - between_x * (columns - 1)) / columns
    panel_height = (height - top - bottom - between_y * (rows - 1)) / rows
    fig.subplots_adjust(left=left / width, right=1 - right / width,
                        bottom=bottom / height, top=1 - top / height,
                        wspace=between_x / panel_width, hspace=between_y / panel_height)


def save_work_precision_figure(frame, path, cases=None, dpi: int = 110, planar=None,
                               stack=None) -> None:
    """Draw :func:`work_precision_figure` and write it to ``path`` (PNG, SVG... by suffix)."""
    plt = pyplot()
    fig = work_precision_figure(frame, cases=cases, planar=planar, stack=stack)
    from shaketable.core.files import atomic_write

    try:
        atomic_write(path, lambda temporary: fig.savefig(temporary, dpi=dpi))
    finally:
        plt.close(fig)
