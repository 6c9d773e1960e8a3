"""What a reader sees at a glance: no empty panel, no legend on the data, captions that say.

The layout checks measure the saved figure in display coordinates (pixels),
independently of :func:`shaketable.plots.base.place_legend`: every panel holds
a drawn trace inside its time range, and no legend box holds a point of a
drawn line (lines are filled with points every pixel, so a reference line
passing under a legend counts, not only its ends).
"""

from __future__ import annotations

import io

import matplotlib
import numpy as np
import pytest

import shaketable as st
from shaketable.core.motion import Motion
from shaketable.plots.base import place_legend, pyplot
from shaketable.plots.calcomp import calcomp
from shaketable.plots.sliding import sliding_figure
from tests.plots.test_calcomp import svg_text


def drawn(fig):
    """Lay the figure out as it is saved (tight box, the package's dpi) and return it."""
    fig.savefig(io.BytesIO(), format="png", dpi=110, bbox_inches="tight")
    fig.canvas.draw()
    return fig


def line_pixels(axis) -> np.ndarray:
    """Every visible line of ``axis`` as pixel points, one per pixel along it, clipped to it."""
    box = axis.get_window_extent()
    pieces = []
    for line in axis.get_lines():
        if not line.get_visible():
            continue
        xy = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
        for segment_start, segment_end in zip(xy[:-1], xy[1:]):
            if not (np.all(np.isfinite(segment_start)) and np.all(np.isfinite(segment_end))):
                continue
            count = int(np.hypot(*(segment_end - segment_start))) + 2
            pieces.append(np.linspace(segment_start, segment_end, count))
        finite = xy[np.all(np.isfinite(xy), axis=1)]
        if line.get_marker() not in (None, "None", "", " ") and len(finite):
            pieces.append(finite)
    points = np.concatenate(pieces) if pieces else np.empty((0, 2))
    inside = ((points[:, 0] >= box.x0) & (points[:, 0] <= box.x1)
              & (points[:, 1] >= box.y0) & (points[:, 1] <= box.y1))
    return points[inside]


def legends_on_data(fig) -> list[str]:
    """The titles or first labels of the legends whose box covers a point of a line."""
    found = []
    for axis in fig.axes:
        legend = axis.get_legend()
        if legend is None:
            continue
        box = legend.get_window_extent()
        points = line_pixels(axis)
        covered = ((points[:, 0] > box.x0) & (points[:, 0] < box.x1)
                   & (points[:, 1] > box.y0) & (points[:, 1] < box.y1))
        if covered.any():
            found.append(legend.get_texts()[0].get_text())
    return found


def empty_panels(fig) -> list[str]:
    """The y labels of the panels with no line point inside their box (an empty panel)."""
    empty = []
    for axis in fig.axes:
        points = line_pixels(axis)
        # a panel shows data when a line covers more than a sliver of its height or has
        # many points (the +-alpha lines alone do not make a panel non-empty)
        traces = [line for line in axis.get_lines()
                  if len(line.get_xdata()) > 2 and np.ptp(np.nan_to_num(
                      np.asarray(line.get_ydata(), dtype=float))) > 0]
        if len(points) == 0 or not traces:
            empty.append(axis.get_ylabel())
    return empty


def pulse_with_vertical() -> Motion:
    t = np.arange(0.0, 4.0, 0.005)
    horizontal = 0.35 * st.G * np.sin(2 * np.pi * 2.0 * t) * (t < 1.5)
    vertical = 0.1 * st.G * np.sin(2 * np.pi * 3.0 * t) * (t < 1.5)
    return Motion(t=t, horizontal=horizontal, vertical=vertical, name="test pulse")


CALCOMP_CASES = {
    "free rocking": lambda: calcomp(st.simulate(
        st.Block.from_inches(30, 6), None, cor=0.925,
        theta0=0.5 * st.Block.from_inches(30, 6).alpha, duration=4.0)),
    "horizontal and vertical": lambda: calcomp(st.simulate(
        st.Block.from_inches(30, 6), pulse_with_vertical(), cor=0.925)),
    "two CORs on a shared time axis": lambda: calcomp(
        st.simulate(st.Block.from_inches(30, 6), pulse_with_vertical(), cor=0.95),
        others=[st.simulate(st.Block.from_inches(30, 6), pulse_with_vertical(), cor=0.8)],
        time_range=(0.0, 8.0)),
}


@pytest.mark.parametrize("case", sorted(CALCOMP_CASES))
def test_calcomp_has_no_empty_panel_and_no_legend_on_data(case):
    fig = drawn(CALCOMP_CASES[case]())
    try:
        assert empty_panels(fig) == []
        assert legends_on_data(fig) == []
    finally:
        matplotlib.pyplot.close(fig)


def test_the_checks_see_a_legend_on_data_and_an_empty_panel():
    # the checks above must be able to fail: a legend put on the traces and an empty panel
    fig = CALCOMP_CASES["horizontal and vertical"]()
    fig.axes[-1].legend(loc="center")  # theta crosses the middle of its panel
    blank = fig.add_subplot(5, 1, 5)
    blank.set_ylabel("nothing")
    drawn(fig)
    try:
        assert legends_on_data(fig) != []
        assert "nothing" in empty_panels(fig)
    finally:
        matplotlib.pyplot.close(fig)


def test_place_legend_takes_a_free_corner_else_goes_outside():
    plt = pyplot()
    fig, axis = plt.subplots(layout="constrained")
    x = np.linspace(0.0, 1.0, 200)
    axis.plot(x, x, label="rising")  # through the lower-left and upper-right corners
    axis.plot(x, np.full_like(x, 1.0), label="a line across the top")  # and the upper left
    legend = place_legend(axis)
    drawn(fig)
    assert legend._loc == 4  # lower right, the one free corner
    assert legends_on_data(fig) == []
    axis.plot(x, 1.0 - x, label="falling")  # now every corner holds data
    legend = place_legend(axis)
    drawn(fig)
    assert legend.get_window_extent().x0 > axis.get_window_extent().x1  # outside, right
    assert legends_on_data(fig) == []
    plt.close(fig)


def test_overturn_marked_where_a_shared_time_axis_goes_on():
    block = st.Block.from_feet(8, 2)
    t = np.arange(0.0, 3.0, 0.005)
    motion = Motion(t=t, horizontal=0.6 * st.G * np.sin(2 * np.pi * 1.0 * t) * (t < 1.0),
                    name="one strong cycle")
    run = st.simulate(block, motion, cor=0.9)
    assert run.overturned
    text = svg_text(calcomp(run, time_range=(0.0, 10.0)))
    assert "the run ends here" in text
    # the axis ending with the run: the caption alone gives the time
    assert "the run ends here" not in svg_text(calcomp(run))


def test_test_vs_theory_names_the_block_as_the_calcomp_caption():
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import run_scene

    result = run_scene(load_scene(resolve_scene_path("fig-3-4")))
    text = svg_text(result.tests[0].plot(title="Fig. 3.4: virtual test vs theory"))
    # the scene's size = "30x6in" in its order and units, as the Calcomp caption gives it
    assert "H × B = 30 × 6 in" in text and "B × H" not in text
    assert "virtual test (simulated potentiometers" in text


def test_sliding_figure_zooms_on_the_slipping_and_says_so():
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import run_scene

    result = run_scene(load_scene(resolve_scene_path("teaching-slide-or-rock")))
    slide = result.slides[0]
    fig = drawn(sliding_figure(slide))
    last_slip = float(slide.t[np.flatnonzero(slide.state != 0)[-1]])
    assert fig.axes[-1].get_xlim()[1] < float(slide.t[-1])
    assert f"no slip after {last_slip:.2f} s" in fig.axes[-1].get_xlabel()
    assert legends_on_data(fig) == []
    text = svg_text(fig)
    assert "μs = 0.2" in text and "(shaded: sliding)" in text


def test_work_precision_labels_stay_inside_their_panel_and_apart():
    # the setting labels written at the ends of each line (rtol, n = subdivisions): on the
    # committed bench data, none may cross its panel's frame or run into another label
    # (before: "n=1" and "1e-9" printed over each other, "1e-7" over the y axis)
    from pathlib import Path

    import pandas as pd

    from shaketable.plots.bench import work_precision_figure

    frame = pd.read_csv(Path(__file__).resolve().parents[2] / "benchmarks" / "work_precision.csv")
    fig = work_precision_figure(frame)
    # drawn once as save_work_precision_figure writes it (fixed margins, 110 dpi, no
    # tight box): a tight box changes no position inside the figure, and costs two draws
    fig.set_dpi(110)
    fig.canvas.draw()
    try:
        renderer = fig.canvas.get_renderer()
        problems = []
        for axis in fig.axes:
            if not axis.get_visible():
                continue
            frame_box = axis.get_window_extent(renderer)
            boxes = [(text.get_text(), text.get_window_extent(renderer)) for text in axis.texts]
            assert len(boxes) >= 2, axis.get_title()
            for label, box in boxes:
                if (box.x0 < frame_box.x0 - 0.5 or box.x1 > frame_box.x1 + 0.5
                        or box.y0 < frame_box.y0 - 0.5 or box.y1 > frame_box.y1 + 0.5):
                    problems.append(f"{axis.get_title()}: {label} outside")
            for k, (label, box) in enumerate(boxes):
                for other, other_box in boxes[:k]:
                    if box.overlaps(other_box):
                        problems.append(f"{axis.get_title()}: {label} on {other}")
        assert problems == []
    finally:
        matplotlib.pyplot.close(fig)
