"""Short runs are animated slowly enough to see (the speed rule of ``animate --help`` and
docs/teaching.md), and a stack's θ/α curves all show when the blocks move together."""

from __future__ import annotations

import numpy as np
import pytest

from shaketable.cli import main
from shaketable.plots.animation import default_speed, frame_times


def test_a_short_span_is_slowed_to_last_four_seconds():
    # speed = span / 4 s (two significant digits) below 4 s, real time from 4 s on
    assert default_speed(1.0) == 0.25
    assert default_speed(0.6) == 0.15
    assert default_speed(4.0) == 1.0 and default_speed(30.0) == 1.0
    # a 1-s run at 12 fps: 48 frame steps of 1/48 s instead of 12 of 1/12 s
    assert frame_times(0.0, 1.0, fps=12, speed=default_speed(1.0)).size == 49


def test_animate_slows_a_short_run_by_default_and_keeps_real_time_with_fps(tmp_path, capsys):
    assert main(["animate", "--block", "30x6in", "--cor", "0.9", "--theta0", "0.5alpha",
                 "--duration", "0.5s", "--size", "160x90", "--dpi", "20",
                 "--out", str(tmp_path / "a.gif")]) == 0
    # 0.5 s at speed 0.5 / 4 = 0.125, to two digits 0.12, and 12 fps: a frame every
    # 0.12 / 12 = 0.01 s, 51 frames
    assert "(51 frames of 160 x 90 pixels, 12 fps, 0-0.5 s at speed 0.12)" in (
        capsys.readouterr().out)
    assert main(["animate", "--block", "30x6in", "--cor", "0.9", "--theta0", "0.5alpha",
                 "--duration", "0.5s", "--size", "160x90", "--dpi", "20", "--fps", "12",
                 "--out", str(tmp_path / "b.gif")]) == 0
    assert "(7 frames of 160 x 90 pixels, 12 fps, 0-0.5 s at speed 1)" in (
        capsys.readouterr().out)


def test_stack_curves_moving_together_all_show():
    from shaketable.core.constants import G
    from shaketable.core.motion import Motion
    from shaketable.plots.base import pyplot
    from shaketable.plots.stack_animation import _StackStage, trace_width
    from shaketable.scenes.stack import run_quietly, stack_from_text

    # a step that tips the column of three as one body: the three θ/α curves coincide
    t = np.arange(0, 0.3, 0.005)
    result, _ = run_quietly(stack_from_text("1x0.2m,1x0.2m,1x0.2m"),
                            Motion(t, np.full(t.size, 0.1 * G)))
    stage = _StackStage(result, np.array([0.0, 0.2]), 0.1, size=(320, 180), dpi=50,
                        unit=None, title=None)
    try:
        curves = [artist for artist in stage.animated
                  if getattr(artist, "get_label", lambda: "")().startswith("θ")]
        # drawn top block first, bottom block last (on top), each wider than the one below
        assert [curve.get_label()[:5] for curve in curves] == ["θ2/α2", "θ1/α1", "θ0/α0"]
        widths = [curve.get_linewidth() for curve in curves]
        assert widths == [trace_width(2, 3), trace_width(1, 3), trace_width(0, 3)]
        assert widths[0] > widths[1] > widths[2] == pytest.approx(1.0)
    finally:
        pyplot().close(stage.fig)
