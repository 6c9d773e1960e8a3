"""Figure details: legends off the data, labels and markers inside the frame,
no curve that measures nothing, captions that say what was compared.

Every check measures the drawn figure (display coordinates after a draw), not the code's
own placement arithmetic."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from shaketable.plots.base import place_legend, pyplot


def _drawn(fig):
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _overlap(a, b) -> bool:
    """Whether two display boxes share more than a pixel."""
    return a.x0 < b.x1 - 1 and b.x0 < a.x1 - 1 and a.y0 < b.y1 - 1 and b.y0 < a.y1 - 1


def test_the_risk_figures_legend_lies_outside_the_panel():
    """The legend goes below the panel: inside, any corner covers the integrand's flank or
    the fitted points."""
    from shaketable.plots.sweeps import risk_curves
    from shaketable.sweeps.fragility import fragility_fit
    from shaketable.sweeps.risk import HazardCurve

    levels = np.repeat([0.1, 0.2, 0.3, 0.4, 0.6, 0.8], 4)
    fell = np.array([0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1],
                    dtype=bool)
    fit = fragility_fit(levels, fell, measure="pgv", intervals=False)
    im = np.geomspace(0.02, 5.0, 20)
    hazard = HazardCurve(im=tuple(im), rate=tuple(1e-3 * (im / 0.1) ** -2.5), measure="pgv",
                         column="pgv [m/s]")
    plt = pyplot()
    fig, axis = plt.subplots(figsize=(7.5, 4.4))
    risk_curves(fit, hazard, ax=axis)
    fig.tight_layout()
    renderer = _drawn(fig)
    legend = axis.get_legend().get_window_extent(renderer)
    assert not _overlap(legend, axis.get_window_extent(renderer))
    assert legend.y1 <= axis.xaxis.label.get_window_extent(renderer).y0 + 1   # under the label
    assert fig.bbox.contains(legend.x0, legend.y0) and fig.bbox.contains(legend.x1, legend.y1)
    plt.close(fig)


def test_a_legend_that_covers_data_in_every_corner_goes_below_the_x_label():
    """``place_legend(outside="below")``, for a panel beside another (the calibration
    figure's COR-per-impact panel would be squeezed to 40 % of its width by a legend at its
    right); the default still puts it at the right."""
    plt = pyplot()
    x = np.linspace(0, 1, 50)
    placed = {}
    for outside in ("below", "right"):
        fig, axis = plt.subplots(figsize=(5, 3.5), layout="constrained")
        axis.plot(x, x, label="rising, a long label as the calibration's are")
        axis.plot(x, 1 - x, label="falling")
        axis.plot(x, np.full_like(x, 0.02), label="floor")
        axis.plot(x, np.full_like(x, 0.98), label="ceiling")
        axis.set_xlabel("x [-]")
        place_legend(axis, outside=outside)
        renderer = _drawn(fig)
        legend = axis.get_legend().get_window_extent(renderer)
        placed[outside] = (legend, axis.get_window_extent(renderer),
                           axis.xaxis.label.get_window_extent(renderer))
        assert fig.bbox.contains(legend.x0, legend.y0) and fig.bbox.contains(legend.x1,
                                                                             legend.y1)
        plt.close(fig)
    legend, panel, label = placed["below"]
    assert legend.y1 <= label.y0 + 1 and panel.x0 - 1 <= legend.x0 and legend.x1 <= panel.x1 + 1
    legend, right_panel, _ = placed["right"]
    assert legend.x0 >= right_panel.x1
    assert panel.width > 1.3 * right_panel.width   # the panel keeps its width
    with pytest.raises(ValueError, match="outside must be 'right' or 'below'"):
        place_legend(axis, outside="above")


def test_the_stack_spectrums_highest_point_is_inside_the_frame():
    """The highest amplitude computed (a point of a band's edge) is drawn below the top
    of the frame, not on it."""
    from shaketable.plots.stack_spectrum import stack_bands_figure

    rows = []
    for column, ceiling in (("stack", 0.99), ("bottom block alone", 2.08)):
        for ratio in (2.0, 3.0):
            rows.append({"column": column, "omega/p [-]": ratio, "from [g]": 0.3,
                         "to [g]": ceiling, "verdict": "overturns", "flagged": False,
                         "block that fell": "the block" if column != "stack"
                         else "block 0 (bottom)"})
    frame = pd.DataFrame(rows)
    curves = {name: (np.array([1.5, 3.5]), np.array([0.3, 0.6])) for name in
              ("stack", "bottom block alone")}
    fig = stack_bands_figure(frame, curves)
    renderer = _drawn(fig)
    for axis in fig.axes:
        frame_box = axis.get_window_extent(renderer)
        for line in axis.get_lines():
            if line.get_marker() == "o":
                for x, y in line.get_transform().transform(line.get_xydata()):
                    radius = 0.5 * line.get_markersize() * fig.dpi / 72.0
                    assert y + radius <= frame_box.y1, (axis.get_title(), y, frame_box.y1)
    pyplot().close(fig)


def test_validation_counts_and_markers_stay_inside_the_frame():
    """Bin counts at P = 1 stay below the top frame, and the reliability diagram's
    largest marker (243 tests at 0) and its count stay inside it."""
    from shaketable.plots.validation import fragility_figure, reliability_figure

    fragility = pd.DataFrame({"centre": [0.05, 0.2, 1.0, 3.0], "measured": [0.0, 0.3, 1.0, 1.0],
                              "measured_low": [0.0, 0.1, 0.8, 0.3],
                              "measured_high": [0.4, 0.6, 1.0, 1.0],
                              "predicted": [0.01, 0.3, 0.97, 1.0], "n": [6, 94, 16, 2]})
    reliability = pd.DataFrame({"predicted": [0.01, 0.4, 0.98], "measured": [0.01, 0.55, 0.97],
                                "binomial_sd": [0.01, 0.08, 0.02], "n": [243, 33, 102]})
    for fig in (fragility_figure(fragility, "PGA [g]"), reliability_figure(reliability)):
        renderer = _drawn(fig)
        axis = fig.axes[0]
        box = axis.get_window_extent(renderer)
        for text in axis.texts:
            extent = text.get_window_extent(renderer)
            assert box.x0 <= extent.x0 and extent.x1 <= box.x1 + 40, text.get_text()
            assert box.y0 <= extent.y0 and extent.y1 <= box.y1, text.get_text()
        from matplotlib.collections import PathCollection

        for collection in axis.collections:   # the markers, sized by the tests in the bin
            if not isinstance(collection, PathCollection):
                continue
            sizes = collection.get_sizes()
            centres = collection.get_offset_transform().transform(collection.get_offsets())
            radii = 0.5 * np.sqrt(sizes) * fig.dpi / 72.0
            assert np.all(centres[:, 1] - radii >= box.y0 - 0.5)
            assert np.all(centres[:, 0] - radii >= box.x0 - 0.5)
        pyplot().close(fig)


def _bench_rows(case: str, status: str, linear_error: float) -> pd.DataFrame:
    rows = [("fast", "rtol=1e-06", 1e-3, 0.0, 1e-10), ("fast", "rtol=1e-12", 2e-3, 0.0, 1e-14),
            ("predictor-corrector", "subdivisions=1", 1e-3, 2e-16, 1e-4),
            ("predictor-corrector", "subdivisions=64", 1e-2, 0.0, 1e-7),
            ("linear", "closed form", 5e-4, linear_error, 1e-2),
            ("reference", "rtol=1e-13", 0.5, 7e-16, 1e-14)]
    return pd.DataFrame([{"case": case, "method": method, "setting": setting, "time [s]": time,
                          "error max_theta [-]": theta, "error events [-]": events,
                          "status truth": status}
                         for method, setting, time, theta, events in rows])


def test_bench_draws_no_max_theta_curve_that_every_method_gets_exactly():
    """On a case whose block overturns every method's max |theta| is alpha (the peak
    before instability), the linear model's too: drawn, its curves would sit at the floor
    and make the linear model look exact. They are not drawn and the panel says why; a case whose
    peak the methods get differently keeps them."""
    from shaketable.plots.bench import fixed_peak, work_precision_panel

    plt = pyplot()
    overturns = _bench_rows("overturns", "overturned", 7.07e-16)
    release = _bench_rows("free", "completed", 0.0)
    informative = _bench_rows("rocks", "completed", 3e-2)
    assert "α" in fixed_peak(overturns) and "overturns" in fixed_peak(overturns)
    assert "release angle" in fixed_peak(release)
    assert fixed_peak(informative) is None
    for rows, solid in ((overturns, 0), (informative, 4)):
        fig, axis = plt.subplots()
        work_precision_panel(rows, rows["case"].iloc[0], ax=axis)
        styles = [line.get_linestyle() for line in axis.get_lines()
                  if len(line.get_xdata()) > 0 and line.get_marker() not in ("None", "")]
        assert styles.count("-") == solid and styles.count("--") == 4, styles
        assert any("not drawn" in text.get_text() for text in axis.texts) == (solid == 0)
        plt.close(fig)


def test_bench_leaves_no_more_empty_slots_than_its_rows_need():
    """Five panels at four per row are drawn 3 + 2 (one empty slot, not 4 + 1 beside
    three), and every column has its x label under its lowest panel."""
    from matplotlib.figure import Figure

    from shaketable.plots.bench import work_precision_figure

    frame = pd.concat([_bench_rows(f"case {k}", "completed", 3e-2) for k in range(5)])
    fig = work_precision_figure(frame, fig=Figure(figsize=(12, 7)))
    drawn = [ax for ax in fig.axes if ax.get_visible() and ax.get_subplotspec() is not None]
    hidden = [ax for ax in fig.axes if not ax.get_visible()]
    assert len(drawn) == 5 and len(hidden) == 1
    columns = {ax.get_subplotspec().colspan.start for ax in drawn}
    labelled = {ax.get_subplotspec().colspan.start for ax in drawn if ax.get_xlabel()}
    assert columns == labelled == {0, 1, 2}


def test_the_test_vs_theory_caption_says_over_what_the_rms_difference_runs():
    """Fig. 3.4's free rocking never exceeds alpha: its RMS difference is over the whole
    record, not "before instability"; a run that falls says up to when."""
    from shaketable import Block
    from shaketable.lab.sensors import Sensors
    from shaketable.scenes.virtual_test import TheorySetup, run_virtual_test

    block = Block.parse("30x6in")
    for theta0, expected in ((0.5, "(over the whole record)"),
                             (1.02, "where the first run exceeds α)")):
        result = run_virtual_test(block, None, cor=0.925, sensors=Sensors(seed=2),
                                  theory=TheorySetup(cor=0.925), theta0=theta0 * block.alpha,
                                  duration=1.0)
        fig = result.plot()
        titles = [axis.get_title() for axis in fig.axes]
        assert any(title.endswith(expected) for title in titles), titles
        assert not any("before instability" in title for title in titles), titles
        pyplot().close(fig)
