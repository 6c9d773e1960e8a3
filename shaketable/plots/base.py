"""The one way the package reaches pyplot, and saving a figure.

Every figure of the package is drawn in :mod:`shaketable.plots`, the only
folder that imports matplotlib (``tests/test_layering.py``). The package never
sets a global backend: :func:`pyplot` imports pyplot under the user's backend,
and falls back to the file-only Agg backend only where the configured
interactive backend cannot be imported (a machine without a display).
"""

from __future__ import annotations


def pyplot():
    """matplotlib.pyplot, imported on first use (Agg if the configured backend cannot load)."""
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "module://matplotlib_inline.backend_inline"):
        try:
            import matplotlib.pyplot as plt  # noqa: F401
        except ImportError:  # pragma: no cover
            matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig, path, dpi: int = 110) -> None:
    """Save a figure to ``path`` (format from the suffix, written atomically) and close it."""
    from shaketable.core.files import atomic_write

    plt = pyplot()
    try:
        atomic_write(path, lambda temporary: save_tight(fig, temporary, dpi))
    finally:
        plt.close(fig)


def save_tight(fig, target, dpi: int = 110) -> None:
    """``fig.savefig(target, dpi=dpi, bbox_inches="tight")``, the same file drawn once.

    For ``bbox_inches="tight"`` matplotlib draws the whole figure once without
    rendering (laying it out when it has a layout engine) to find the box, then
    again to render it. For a PNG on the Agg canvas the first draw is not needed:
    the figure is laid out as that draw would lay it out, its box measured at the
    same dpi with the same padding, and the file is byte-identical
    (``tests/plots/test_save_tight.py``; every figure of ``shaketable reproduce
    --all`` checked): ~10 % of the time of a Calcomp figure. Any other
    format or canvas goes through ``savefig`` unchanged.
    """
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    engine = fig.get_layout_engine()
    if (type(fig.canvas) is not FigureCanvasAgg or not str(target).lower().endswith(".png")
            or (engine is not None and not hasattr(fig, "_layout_engine"))):
        fig.savefig(target, dpi=dpi, bbox_inches="tight")
        return
    fig.dpi = dpi   # as savefig sets it while it measures and draws
    renderer = fig.canvas.get_renderer()
    if engine is not None:
        if fig.axes:
            try:   # what Figure.draw does first
                engine.execute(fig)
            except ValueError:   # matplotlib's draw goes on without the layout too
                pass
        # laid out: savefig must neither lay it out again nor draw it to measure it
        # (it does both whenever the figure has an engine; set_layout_engine("none")
        # leaves a placeholder engine, hence matplotlib's attribute)
        fig._layout_engine = None
    try:
        box = fig.get_tightbbox(renderer)
        fig.savefig(target, dpi=dpi,
                    bbox_inches=box.padded(matplotlib.rcParams["savefig.pad_inches"]))
    finally:
        fig._layout_engine = engine   # the figure keeps its engine (None if it had none)


#: Where :func:`place_legend` tries a legend inside the axes, in this order.
LEGEND_CORNERS = ("upper right", "upper left", "lower left", "lower right")


def plotted_points(axis, spacing: float = 0.004):
    """Every drawn line, line collection and marker of ``axis`` as points in axes fractions.

    Straight segments are filled with points every ``spacing`` (axes
    fraction), so a long horizontal reference line counts where it runs, not
    only at its two ends. Returns an ``(n, 2)`` array.
    """
    import numpy as np
    from matplotlib.collections import LineCollection, PathCollection

    to_axes = axis.transAxes.inverted()
    pieces = []

    def add(path_display):
        points = to_axes.transform(path_display)
        points = points[np.all(np.isfinite(points), axis=1)]
        if len(points) < 2:
            pieces.append(points)
            return
        steps = np.hypot(*np.diff(points, axis=0).T)
        arc = np.concatenate([[0.0], np.cumsum(steps)])
        count = int(min(200_000, max(len(points), arc[-1] / spacing)))
        samples = np.linspace(0.0, arc[-1], count)
        pieces.append(np.column_stack([np.interp(samples, arc, points[:, 0]),
                                       np.interp(samples, arc, points[:, 1])]))
        pieces.append(points)

    for line in axis.get_lines():
        if line.get_visible() and len(line.get_xydata()):
            xy = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
            # a NaN breaks a line: each run of finite points is its own path
            finite = np.all(np.isfinite(xy), axis=1)
            for run in np.split(np.arange(len(xy)), np.flatnonzero(np.diff(finite)) + 1):
                if finite[run[0]]:
                    add(xy[run])
    for collection in axis.collections:
        if not collection.get_visible():
            continue
        if isinstance(collection, LineCollection):
            for segment in collection.get_segments():
                add(collection.get_transform().transform(np.asarray(segment, dtype=float)))
        elif isinstance(collection, PathCollection):
            offsets = np.asarray(collection.get_offsets(), dtype=float)
            if offsets.size:
                pieces.append(to_axes.transform(
                    collection.get_offset_transform().transform(offsets)))
    return np.concatenate(pieces) if pieces else np.empty((0, 2))


def place_legend(axis, corners=LEGEND_CORNERS, outside: str = "right", **options):
    """A legend in the first corner of ``axis`` where it covers no plotted point, else outside.

    Each corner of ``corners`` is tried in turn; the legend stays in the first
    one whose box (with a small margin) holds none of :func:`plotted_points`
    (measured on the laid-out axes when the figure has a layout engine; call it
    after ``tight_layout`` otherwise).
    When every corner covers data the legend goes outside: to the right of the
    axes (``outside="right"``), or centred below the x label (``"below"``: for a
    panel beside another, whose width a legend at its right would take).
    ``options`` go to :meth:`matplotlib.axes.Axes.legend`.

    Returns
    -------
    matplotlib.legend.Legend
    """
    if outside not in ("right", "below"):
        raise ValueError(f"outside must be 'right' or 'below', got {outside!r}")
    figure = axis.figure
    engine = figure.get_layout_engine()
    if engine is not None and figure.axes:
        engine.execute(figure)  # the layout first: corners of the final axes
    renderer = figure.canvas.get_renderer()
    points = plotted_points(axis)
    to_axes = axis.transAxes.inverted()
    margin = 0.01
    for corner in corners:
        legend = axis.legend(loc=corner, **options)
        box = legend.get_window_extent(renderer).transformed(to_axes)
        inside = ((points[:, 0] > box.x0 - margin) & (points[:, 0] < box.x1 + margin)
                  & (points[:, 1] > box.y0 - margin) & (points[:, 1] < box.y1 + margin))
        if not inside.any():
            return legend
    options.setdefault("frameon", True)
    if outside == "below":
        legend = axis.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), **options)
        # the gap under the axes in the legend's font sizes (points: it keeps when the
        # layout resizes the axes): the tick labels and the x label, and half a line more
        axis.get_legend().remove()
        below = axis.bbox.y0 - axis.get_tightbbox(renderer).y0
        size = legend.prop.get_size_in_points()
        return axis.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0),
                           borderaxespad=below * 72.0 / figure.dpi / size + 0.5, **options)
    return axis.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                       **options)


def stripe_fractions(im, overturned, bins: int = 12):
    """Fraction overturned in log-spaced bins of the IM (the points of a fragility figure):
    bin centres, fractions and counts."""
    import numpy as np

    im = np.asarray(im, dtype=float)
    overturned = np.asarray(overturned, dtype=bool)
    levels = np.unique(np.round(im, 12))
    if levels.size <= bins:
        groups = [np.round(im, 12) == level for level in levels]
        centres = levels
    else:
        edges = np.geomspace(im.min(), im.max() * (1 + 1e-12), bins + 1)
        index = np.clip(np.searchsorted(edges, im, side="right") - 1, 0, bins - 1)
        groups = [index == k for k in range(bins)]
        centres = np.sqrt(edges[:-1] * edges[1:])
    keep = [k for k, pick in enumerate(groups) if pick.any()]
    fractions = np.array([overturned[groups[k]].mean() for k in keep])
    counts = np.array([int(groups[k].sum()) for k in keep])
    return np.asarray(centres)[keep], fractions, counts


def log_axis(axis):
    """A log axis labelled at 1, 2, 5 x 10^n in plain numbers (no crowded minor labels)."""
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

    axis.axes.set_xscale("log") if axis is axis.axes.xaxis else axis.axes.set_yscale("log")
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FormatStrFormatter("%g"))
    axis.set_minor_formatter(NullFormatter())
