"""The Calcomp figure carries its own caption: a reader can trust it at a glance."""

from __future__ import annotations

import io
import math

import matplotlib
import numpy as np
import pytest

import shaketable as st
from shaketable.plots.calcomp import broken_at_sign_changes, calcomp
from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import SceneError, load_scene, scene_from_dict
from shaketable.scenes.run import run_scene


def svg_text(fig) -> str:
    """The figure as SVG with its text kept as text (not glyph paths)."""
    buffer = io.StringIO()
    with matplotlib.rc_context({"svg.fonttype": "none"}):
        fig.savefig(buffer, format="svg")
    matplotlib.pyplot.close(fig)
    return buffer.getvalue()


def test_free_rocking_caption_and_no_empty_ground_panels():
    # Fig. 3.4's specimen: the 30 x 6 in block, COR 0.925, released at 0.5 alpha
    block = st.Block.from_inches(30, 6)
    result = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=4.0)
    fig = calcomp(result, title="Fig. 3.4")
    assert len(fig.axes) == 2  # no ground panel: free rocking has no ground motion
    text = svg_text(fig)
    for expected in ("Fig. 3.4", "B × H = 6 × 30 in", "COR 0.925", "free rocking",
                     "still rocking at the end (t = 4.00 s)", "(released at θ/α = 0.50)"):
        assert expected in text


def test_overturned_run_reads_as_overturned_never_as_a_peak():
    # Fig. 4.1 of the report: the 16 x 4 ft block overturns under Pacoima Dam S16E, COR 1.0
    scene = load_scene(resolve_scene_path("fig-4-1"))
    result = run_scene(scene)
    run = result.main
    assert run.overturned
    assert math.isnan(run.max_theta_ratio)  # the report writes F, not a number
    summary = run.summary()
    assert summary["overturned"] is True and summary["max_theta_ratio [-]"] is None
    assert summary["verdict"].startswith("overturned (")
    assert 0.0 <= summary["max_theta_ratio_before_instability [-]"] <= 1.0
    text = svg_text(result.plot())
    assert "overturned (" in text and "max θ/α" not in text
    # the scene's size = "16x4ft", echoed in its order and units
    assert "H × B = 16 × 4 ft" in text and "COR 1" in text and "Pacoima Dam S16E" in text
    # Figs. 4.1 and 4.2 share one time axis (their scenes' [outputs] time_range)
    other = load_scene(resolve_scene_path("fig-4-2"))
    assert scene.outputs["time_range"] == other.outputs["time_range"] == (0.0, 7.0)


def test_rods_in_the_caption():
    # Fig. 4.17 caption: total stiffness 0.4 W/in, total prestressing force 0.4 W
    rods = st.PrestressRods.from_inches(0.4, 0.4, 12.0)
    block = st.Block.from_feet(8, 2, rods=rods)
    result = st.simulate(block, None, cor=0.95, theta0=0.5 * block.alpha, duration=1.0)
    text = svg_text(calcomp(result))
    assert "K = 0.4 W/in" in text and "F0 = 0.4 W" in text


def test_angular_acceleration_broken_at_impacts():
    t = np.arange(6.0)
    theta = np.array([0.1, 0.05, -0.05, -0.1, 0.02, 0.03])
    t_broken, values = broken_at_sign_changes(t, theta, -theta)
    # two changes of sign of theta: two gaps, so no line crosses an impact
    assert np.isnan(values).sum() == 2
    assert list(np.flatnonzero(np.isnan(values))) == [2, 5]


def test_time_range_is_checked():
    base = {"name": "x", "block": {"size": "30x6in"}, "motion": {"kind": "free"},
            "rocking": {"cor": 0.9, "duration": "2 s"}}
    assert scene_from_dict(dict(base, outputs={"time_range": ["1 s", "2 s"]})) \
        .outputs["time_range"] == (1.0, 2.0)
    for bad in (["2 s", "1 s"], ["1 s"], "0-2 s", ["1", "2 s"]):
        with pytest.raises(SceneError, match="time_range"):
            scene_from_dict(dict(base, outputs={"time_range": bad}))
