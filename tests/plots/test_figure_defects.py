"""Figure defects a newcomer found: every run shown where runs are overlaid, reference
lines across the plotted range, panels not squeezed by their legends, tick labels apart.

Every check measures the drawn figure (artists' data and display extents after a draw),
not the code's own placement arithmetic."""

from __future__ import annotations

import numpy as np
import pandas as pd

import shaketable as st
from shaketable.plots.base import pyplot


def _drawn(fig):
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _texts(fig) -> str:
    return "\n".join(text.get_text() for axis in fig.axes for text in axis.texts)


def test_calcomp_of_two_runs_shows_both_and_says_which_one_ends():
    """A small block that falls early overlaid on a large one that rocks on: the rates
    panel carries the large block's velocity to the end of the axis, and the note at the
    fall names the small block (the other run does not end there)."""
    from shaketable.plots.calcomp import calcomp

    small, large = st.Block.from_feet(4, 0.8), st.Block.from_feet(12, 2.4)
    falls = st.simulate(small, None, cor=0.9, theta0=1.2 * small.alpha, duration=4.0)
    rocks = st.simulate(large, None, cor=0.9, theta0=0.5 * large.alpha, duration=4.0)
    assert falls.overturned and not rocks.overturned and falls.t[-1] < 0.5 * rocks.t[-1]
    fig = calcomp(falls, others=[rocks])
    rates = fig.axes[-2]
    stop = rates.get_xlim()[1]
    reach = max(float(np.nanmax(line.get_xdata())) for line in rates.get_lines())
    assert reach >= 0.99 * stop
    note = _texts(fig)
    assert note.startswith(small.describe()) and "overturned (" in note
    assert "its run ends here" in note and large.describe() not in note
    pyplot().close(fig)


def test_the_stack_spectrums_eq_2_8_line_spans_the_omega_axis():
    """One ratio computed (omega/p = 3, the axis 2.5 to 3.5): the dashed Eq. (2-8) line
    runs across the whole axis in both panels, not to 1.05 x the largest ratio."""
    from shaketable.plots.stack_spectrum import stack_bands_figure

    frame = pd.DataFrame([{"column": column, "omega/p [-]": 3.0, "from [g]": 0.4,
                           "to [g]": 1.3, "verdict": "overturns", "flagged": False,
                           "block that fell": "the block"}
                          for column in ("stack", "bottom block alone")])

    def curves(ratios):
        ratios = np.asarray(ratios, dtype=float)
        return {name: (ratios, 0.2 * ratios) for name in ("stack", "bottom block alone")}

    fig = stack_bands_figure(frame, curves)
    for axis in fig.axes:
        low, high = axis.get_xlim()
        dashed = [line for line in axis.get_lines() if line.get_linestyle() == "--"]
        assert len(dashed) == 1
        x = dashed[0].get_xdata()
        assert x.min() <= low + 0.01 * (high - low) and x.max() >= high - 0.01 * (high - low)
    pyplot().close(fig)


def test_a_single_level_mode_map_keeps_its_width_and_units():
    """One PGA level: the map takes most of the figure's width (its legend, below, no
    longer squeezes it to a quarter) and both axes carry their unit [-]."""
    from shaketable.studies.mode_map import ModeMap

    rows = [{"pga [g]": 0.5, "B/H [-]": ratio, "mu [-]": mu,
             "verdict": "slid" if mu < ratio else "overturned", "rule": "slide",
             "overturned": mu >= ratio, "rocking model overturned": True}
            for ratio in (0.15, 0.2, 0.25, 0.3) for mu in (0.1, 0.2, 0.3, 0.4)]
    mode_map = ModeMap(frame=pd.DataFrame(rows), record="a record", height=2.0, cor=0.95)
    fig = mode_map.plot(block=st.Block(width=0.5, height=2.0))
    renderer = _drawn(fig)
    (axis,) = fig.axes
    panel, legend = axis.get_window_extent(renderer), fig.legends[0].get_window_extent(renderer)
    assert panel.width >= 0.6 * fig.bbox.width
    assert not (legend.x0 < panel.x1 and panel.x0 < legend.x1 and legend.y0 < panel.y1
                and panel.y0 < legend.y1)
    assert axis.get_ylabel().endswith("[-]") and axis.get_xlabel().endswith("[-]")
    pyplot().close(fig)


def _assessment(c_s=(0.57, 0.56)):
    """A stand-in for an assessment result: two levels, three frictions; the high
    friction stays put under one record at the first level (a range from 0)."""
    from types import SimpleNamespace

    rows = []
    for case, mu in (("low", 0.3), ("high", 0.5), ("let it slide", 0.15)):
        for level, low in ((0.4, 0.0 if case == "high" else 15e-3), (0.6, 0.2)):
            rows.append({"case": case, "ground pga [g]": level, "mu [-]": mu,
                         "P(overturn) [-]": 0.4, "P low [-]": 0.2, "P high [-]": 0.7,
                         **{f"{what} {stat} [m]": value for what in ("excursion", "slip")
                            for stat, value in (("median", 0.2), ("p84", 0.3), ("min", low),
                                                ("max", 0.5))}})
    names = ("design", "MCE")
    frequencies = np.geomspace(0.2, 30.0, 40)
    spec = SimpleNamespace(name="cabinet", where="on floor 3",
                           criteria=SimpleNamespace(acceptable=0.1, clearance=0.1),
                           demand=SimpleNamespace(level_names=names))
    return SimpleNamespace(
        free=pd.DataFrame(rows), spec=spec, fragility={},
        runs=pd.DataFrame({"record": ["a", "b"]}),
        spectra={k: (frequencies, (1.0 + k) * 9.80665 * np.exp(-np.log(frequencies) ** 2))
                 for k in range(2)},
        codes={name: {"ASCE 43-05 A.1 (sliding)": {"c_s [g]": value, "mu_e [-]": value / 2,
                                             "mu [-]": 0.3}}
               for name, value in zip(names, c_s)})


def test_the_assessments_demand_ranges_are_bars_on_a_linear_scale():
    """Excursion and slip on a linear scale (no symlog "0" tick under 10^0), and each range
    over records a vertical bar at its level: no band is filled between two levels."""
    from shaketable.plots.assess import assessment_figure

    fig = assessment_figure(_assessment(), "demands")
    _drawn(fig)
    for axis in fig.axes[1:]:
        assert axis.get_yscale() == "linear"
        bars = 0
        for collection in axis.collections:
            for path in collection.get_paths():
                x = path.vertices[:, 0]
                assert np.ptp(x) < 0.05, "a range drawn across levels"
                bars += 1
        assert bars == 6   # three frictions at two levels
    pyplot().close(fig)


def test_the_assessments_code_lines_say_what_mu_e_is_and_do_not_overlap_apart():
    """The c_s lines: mu_e defined in the legend; two lines closer than a line's width are
    one black line with one entry naming both levels; far apart, each in its colour."""
    from shaketable.plots.assess import assessment_figure

    for c_s, entries in (((0.57, 0.56), 1), ((0.57, 1.2), 2)):
        fig = assessment_figure(_assessment(c_s), "floor-spectra")
        (axis,) = fig.axes
        legend = axis.get_legend()
        assert "μe = μ (1 − 0.4 A_v/g)" in legend.get_title().get_text()
        dotted = [line for line in axis.get_lines() if line.get_linestyle() == ":"]
        labels = [text.get_text() for text in legend.get_texts() if "c_s" in text.get_text()]
        assert len(labels) == entries and len(dotted) == 2
        colours = {line.get_color() for line in dotted}
        assert len(colours) == (1 if entries == 1 else 2)
        if entries == 1:
            assert "design 0.57 g" in labels[0] and "MCE 0.56 g" in labels[0]
        pyplot().close(fig)


def test_the_calibrations_block_mean_band_is_tall_enough_to_see():
    """A 95 % interval of the block's mean a hundredth of the per-impact spread (the
    bundled virtual test's): its band is drawn at least 3 % of the axis tall, and the
    label gives the interval itself."""
    from shaketable.calibration.peaks import PeakEstimate
    from shaketable.calibration.scatter import CorScatter
    from shaketable.plots.calibration import plot_cor_per_impact

    velocity = np.linspace(0.2, 0.7, 15)
    cors = 0.925 + 0.01 * np.sin(7 * velocity)
    peaks = PeakEstimate(cor=0.9254, cor_interval=(0.9249, 0.9258), peak_times=velocity,
                         amplitudes=velocity, cor_per_impact=cors,
                         cor_per_impact_se=np.full(15, 0.01), impact_velocity=velocity,
                         slope=np.nan, slope_se=np.nan, intercept=np.nan)
    scatter = CorScatter(mean=0.9253, mean_se=0.00025, mean_interval=(0.9248, 0.9258),
                         sigma=0.0, sigma_interval=(0.0, 0.0023), impacts=15,
                         measurement_se=0.01)
    fig, axis = pyplot().subplots(figsize=(6.0, 4.0))
    plot_cor_per_impact(peaks, ax=axis, scatter=scatter)
    renderer = _drawn(fig)
    (band,) = [patch for patch in axis.patches + axis.collections
               if "block mean" in str(patch.get_label())]
    box, panel = band.get_window_extent(renderer), axis.get_window_extent(renderer)
    assert box.height >= 0.03 * panel.height
    assert "0.9248 to 0.9258" in band.get_label()
    pyplot().close(fig)


def test_the_stack_animations_x_tick_labels_stand_apart():
    """The stage of a tall two-block column (the stack-kick scene's 0.8 x 0.2 m on
    1 x 0.3 m) at the default frame size: its x tick labels do not touch."""
    from types import SimpleNamespace

    from shaketable.core.geometry import Block
    from shaketable.models.stack import Stack
    from shaketable.plots.animation import DEFAULT_DPI, DEFAULT_SIZE
    from shaketable.plots.stack_animation import _StackStage

    t = np.linspace(0.0, 1.0, 11)
    theta = np.column_stack([np.zeros_like(t), 0.02 * np.cos(3 * t)])
    result = SimpleNamespace(
        stack=Stack((Block(1.0, 0.3), Block(0.8, 0.2))), t=t, theta=theta,
        theta_dot=np.zeros_like(theta), patterns=np.zeros((t.size, 2), dtype=int),
        motion=SimpleNamespace(t=t, horizontal=np.zeros_like(t),
                               vertical_or_zero=np.zeros_like(t), name=None),
        impact="plastic", cor=None, block_name=lambda i: f"block {i}")
    stage = _StackStage(result, t, None, size=DEFAULT_SIZE, dpi=DEFAULT_DPI, unit="m",
                        title="a column")
    renderer = _drawn(stage.fig)
    axis = stage.fig.axes[0]
    boxes = sorted((label.get_window_extent(renderer) for label in axis.get_xticklabels()
                    if label.get_visible() and label.get_text()), key=lambda box: box.x0)
    assert len(boxes) >= 3
    for left, right in zip(boxes, boxes[1:]):
        assert right.x0 - left.x1 >= 4.0   # a gap of a few pixels between labels
    pyplot().close(stage.fig)


def test_a_stacks_overturn_cross_at_the_right_edge_clears_the_legend():
    """A three-block column whose middle block overturns at the run's last instant: the
    cross, drawn on the frame's right edge, does not touch the contact band's legend."""
    from types import SimpleNamespace

    from shaketable.core.geometry import Block
    from shaketable.models.stack import Stack
    from shaketable.plots.stack import stack_calcomp

    t = np.linspace(0.0, 4.85, 50)
    stack = Stack((Block(8 * 0.3048, 2 * 0.3048), Block(8 * 0.3048, 2 * 0.3048),
                   Block(4 * 0.3048, 2 * 0.3048)))
    theta = np.outer(t / t[-1], [0.1, 1.5, 1.0]) ** 2
    patterns = np.zeros((t.size, 3), dtype=int)
    patterns[25:] = 1
    result = SimpleNamespace(
        stack=stack, t=t, theta=theta, patterns=patterns,
        events=[{"kind": "overturn", "t": t[-1], "interface": 1}],
        motion=SimpleNamespace(t=t, horizontal=np.sin(t), vertical_or_zero=np.zeros_like(t),
                               name="a record"),
        impact="plastic", cor=None, status="overturned", overturned_block=1,
        t_overturn=t[-1], block_name=lambda i: f"block {i}")
    fig = stack_calcomp(result)
    renderer = _drawn(fig)
    band = fig.axes[-1]
    (cross,) = [line for line in band.get_lines() if line.get_marker() == "x"]
    x, _ = cross.get_transform().transform(cross.get_xydata())[0]
    half = 0.5 * cross.get_markersize() * fig.dpi / 72.0 + 1.0
    legend = band.get_legend().get_window_extent(renderer)
    assert x + half <= legend.x0   # the legend starts right of the cross
    pyplot().close(fig)
