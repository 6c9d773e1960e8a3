"""The animated GIF (shaketable.plots.animation) and ``shaketable animate``."""

import math

import numpy as np
import pytest
from PIL import Image

import shaketable as st
from shaketable.cli import main
from shaketable.core.constants import G
from shaketable.ground import generators as motions
from shaketable.plots.animation import (
    animate,
    block_outline,
    ffmpeg_available,
    frame_times,
    snapshot,
    stage_unit,
    table_displacement,
)


def test_frame_times_subsample_by_speed_over_fps():
    # 8 s at 12 frames per GIF second in real time: one frame every 1/12 s, 0 ... 8 s
    times = frame_times(0.0, 8.0, fps=12, speed=1.0)
    assert times.size == 97 and times[-1] == pytest.approx(8.0)
    assert frame_times(0.0, 8.0, fps=12, speed=2.0).size == 49
    with pytest.raises(ValueError, match="fps"):
        frame_times(0.0, 8.0, fps=0, speed=1.0)
    with pytest.raises(ValueError, match="more than 10"):
        frame_times(0.0, 8.0, fps=12, speed=1.0, max_frames=10)


def test_block_outline_rotates_about_the_pivot_corner():
    block = st.Block(1.0, 0.2)
    theta = 0.1
    corners = block_outline(block, theta, base_x=0.5)
    # theta > 0: pivot on the -x corner, which stays put; the top moves toward -x
    # (docs/conventions.md); the top-left corner goes to (-b - H sin, H cos)
    np.testing.assert_allclose(corners[0], [0.5 - 0.1, 0.0], atol=1e-15)
    np.testing.assert_allclose(corners[3], [0.4 - math.sin(theta), math.cos(theta)], atol=1e-12)
    mirrored = block_outline(block, -theta, base_x=0.5)
    np.testing.assert_allclose(mirrored[1], [0.6, 0.0], atol=1e-15)    # +x corner fixed
    np.testing.assert_allclose(mirrored[:, 0] - 0.5, -(corners[[1, 0, 3, 2, 1], 0] - 0.5),
                               atol=1e-12)                             # mirror image
    sides = np.hypot(*np.diff(corners, axis=0).T)
    np.testing.assert_allclose(sides, [0.2, 1.0, 0.2, 1.0], rtol=1e-12)  # drawn to scale


def test_table_displacement_of_a_harmonic():
    # a sin(w t) is the acceleration of the displacement -a/w^2 sin(w t): 0.2 g at 2 Hz
    # -> amplitude 12.4 mm, in phase with -sin. The ramp-up leaves a slow drift of a
    # few mm (partly removed by the 0.1 Hz high-pass), fitted here by a quadratic.
    motion = motions.harmonic(2.0, horizontal=0.2 * G, duration=10.125, dt=0.005, ramp=2.0)
    times = np.linspace(4.0, 6.0, 401)
    omega = 4 * np.pi
    got = table_displacement(motion, times)
    basis = np.column_stack([np.sin(omega * times), np.cos(omega * times),
                             np.ones_like(times), times, times**2])
    sine, cosine = np.linalg.lstsq(basis, got, rcond=None)[0][:2]
    assert sine == pytest.approx(-0.2 * 9.80665 / omega**2, rel=0.01)
    assert abs(cosine) < 0.01 * abs(sine)
    np.testing.assert_array_equal(table_displacement(None, times), 0.0)


def test_table_displacement_of_an_abrupt_harmonic_does_not_drift():
    # a sine acceleration A sin(w t) integrated from rest has the mean velocity A / w
    # and drifts by A t / w (2.1 m in 6 s at 2 Hz, 0.45 g); a shaking table moves by the
    # closed form -A / w^2 sin(w t) (27.9 mm) about where it started
    amplitude, omega = 0.45 * G, 4 * np.pi
    motion = motions.harmonic(2.0, horizontal=amplitude, duration=6.0)
    times = np.linspace(0.0, 6.0, 1201)
    closed = -amplitude / omega**2 * np.sin(omega * times)
    # without the high-pass: the closed form up to the sampling error: samples every
    # 0.01 s, the acceleration linear between them and the displacement interpolated
    # linearly between them, each off by up to (w dt)^2 / 8 = 0.2 % of the amplitude
    exact = table_displacement(motion, times, highpass=None)
    np.testing.assert_allclose(exact, closed, atol=0.005 * amplitude / omega**2)
    # the default 0.1 Hz high-pass changes it by the filter's response at the abrupt ends
    shown = table_displacement(motion, times)
    np.testing.assert_allclose(shown, closed, atol=0.03 * amplitude / omega**2)


def test_animate_prints_rounded_times(capsys):
    from types import SimpleNamespace

    from shaketable.commands.animate import _wrote

    _wrote(SimpleNamespace(note=None, path="a.gif", n_frames=53, size=(640, 360), fps=12.0,
                           t_first=0.0, t_last=4.333333333, speed=1.0))
    assert "0-4.33 s at speed 1" in capsys.readouterr().out


def test_animate_writes_a_gif_with_the_expected_frames_and_size(tmp_path):
    block = st.Block.from_inches(30, 6)
    result = st.simulate(block, cor=0.925, theta0=0.5 * block.alpha, duration=1.0)
    written = animate(result, block, out=tmp_path / "rock.gif", fps=6, speed=1.0,
                      size=(320, 180), dpi=40)
    # 1 s at 6 frames per second: frames at 0, 1/6, ..., 1 s
    assert written.n_frames == 7
    with Image.open(written.path) as gif:
        assert gif.n_frames == 7
        assert gif.size == (320, 180)  # the size asked for, in pixels
    assert written.path.stat().st_size < 2_000_000
    with Image.open(animate(result, out=tmp_path / "big.gif", fps=2, end=0.5).path) as gif:
        assert gif.size == (1024, 576)  # the default: readable on a projector
    with pytest.raises(ValueError, match="out must be a .gif or .mp4"):
        animate(result, out=tmp_path / "rock.png")
    with pytest.raises(ValueError, match="block .* is not the block of the result"):
        animate(result, st.Block.from_inches(36, 9), out=tmp_path / "x.gif")


def test_cli_animate_help_and_smoke_run(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["animate", "--help"])
    assert exit_info.value.code == 0
    assert "--speed" in capsys.readouterr().out
    # a free-rocking scene of its own (Fig. 3.4's block), independent of other stages
    scene = tmp_path / "free.toml"
    scene.write_text('name = "free"\nsource = "Fig. 3.4"\n[block]\nsize = "30x6in"\n'
                     '[motion]\nkind = "free"\n[rocking]\ncor = 0.925\n'
                     'theta0 = "0.5 alpha"\nduration = "2 s"\n')
    out = tmp_path / "fig.gif"
    assert main(["animate", str(scene), "--out", str(out), "--fps", "4", "--end", "1s"]) == 0
    with Image.open(out) as gif:
        assert gif.n_frames == 5  # 0, 0.25, ..., 1 s
    assert "free: 30 x 6 in, COR 0.925" in capsys.readouterr().out
    assert main(["animate", str(scene), "--out", str(out), "--run", "3"]) == 2
    assert "--run must be between 0 and 0" in capsys.readouterr().err
    assert main(["animate", "table-4-2", "--out", str(out)]) == 2
    assert "[study]" in capsys.readouterr().err


def _two_cors():
    # free rocking of Fig. 3.4's block from 0.5 alpha at two CORs: two runs to compare
    block = st.Block.parse("30x6in")
    return [st.simulate(block, cor=cor, theta0=0.5 * block.alpha, duration=1.0)
            for cor in (0.925, 0.7)]


def test_blitted_frames_are_the_fully_drawn_frames(tmp_path):
    # the frames are drawn by blitting (the still parts once); each must look like the
    # same frame drawn whole (snapshot), up to the GIF's 255-colour palette: no artist
    # left behind from the previous frame, none missing
    runs = _two_cors()
    written = animate(runs, out=tmp_path / "two.gif", fps=4, size=(640, 360), dpi=60)
    assert written.n_frames == 5 and written.size == (640, 360)
    with Image.open(written.path) as gif:
        gif.seek(3)                                   # t = 0.75 s
        blitted = np.asarray(gif.convert("RGB"), dtype=float)
    whole = snapshot(runs, 0.75, out=tmp_path / "whole.png", span=(0.0, 1.0),
                     size=(640, 360), dpi=60)
    with Image.open(whole) as image:
        drawn = np.asarray(image.convert("RGB"), dtype=float)
    assert blitted.shape == drawn.shape
    differ = np.abs(blitted - drawn).max(axis=2) > 40  # beyond palette rounding
    assert differ.mean() < 0.002, differ.mean()


def test_several_runs_side_by_side_or_overlaid_in_one_unit(tmp_path):
    runs = _two_cors()
    for layout in ("side", "overlay"):
        written = animate(runs, out=tmp_path / f"{layout}.gif", fps=2, end=0.5, layout=layout,
                          size=(480, 270), dpi=50)
        assert written.n_frames == 2
    with pytest.raises(ValueError, match="layout"):
        animate(runs, out=tmp_path / "x.gif", layout="stacked")
    with pytest.raises(ValueError, match="one label per result"):
        animate(runs, out=tmp_path / "x.gif", labels=["one"])
    with pytest.raises(ValueError, match="block and motion are for one result"):
        animate(runs, st.Block.parse("30x6in"), out=tmp_path / "x.gif")
    # the drawing's length unit is the one the block was written in
    assert stage_unit([st.Block.parse("6x2ft")]) == "ft"
    assert stage_unit([st.Block.parse("30x6in")]) == "in"
    assert stage_unit([st.Block(1.0, 0.2)]) == "m"


def test_mp4_with_ffmpeg_and_gif_without(tmp_path, monkeypatch):
    import shaketable.plots.animation as animation

    (run,) = _two_cors()[:1]
    if ffmpeg_available():
        written = animate(run, out=tmp_path / "rock.mp4", fps=4, end=0.5, size=(320, 180))
        head = written.path.read_bytes()[:12]
        assert written.path.suffix == ".mp4" and head[4:8] == b"ftyp" and not written.note
    monkeypatch.setattr(animation, "ffmpeg_available", lambda: False)
    written = animate(run, out=tmp_path / "rock2.mp4", fps=4, end=0.5, size=(320, 180))
    assert written.path == tmp_path / "rock2.gif" and "ffmpeg" in written.note
    with Image.open(written.path) as gif:
        assert gif.n_frames == 3


def test_cli_animate_two_runs_of_a_scene(tmp_path, capsys):
    # the classroom scenes: one command animates both runs side by side
    out = tmp_path / "small.gif"
    assert main(["animate", "teaching-period-grows", "--end", "0.5s", "--fps", "4",
                 "--size", "480x270", "--dpi", "50", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "36 x 9 in, θ0/α 0.2" in printed and "36 x 9 in, θ0/α 0.8" in printed
    with Image.open(out) as gif:
        assert gif.size == (480, 270) and gif.n_frames == 3
    assert main(["animate", "teaching-period-grows", "--size", "big", "--out", str(out)]) == 2
    assert "--size 'big'" in capsys.readouterr().err


def test_the_small_block_falls_first_scene_does_what_it_says():
    # Teaching gallery (c) (docs/teaching.md): under Pacoima Dam S74W with the vertical at
    # COR 0.9, the 4 ft block of H/B = 5 overturns and the 12 ft block peaks at 0.56 alpha
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import run_scene

    small, large = run_scene(load_scene(resolve_scene_path("teaching-small-block-falls"))).runs
    assert small.overturned and not large.overturned
    assert large.max_theta_ratio == pytest.approx(0.56, abs=0.005)


def test_every_trace_is_revealed_up_to_the_frame_time_only():
    # the theta/alpha traces and the ground acceleration are drawn up to each frame's time:
    # the future (the small block's fall) is not on the picture before it happens
    from shaketable.plots.animation import _Stage
    from shaketable.plots.base import pyplot

    block = st.Block.parse("30x6in")
    run = st.simulate(block, motions.harmonic(2.0, horizontal=0.3 * G, duration=3.0), cor=0.9)
    times = frame_times(0.0, 3.0, fps=4, speed=1.0)
    stage = _Stage([run], [run.motion], times, 0.1)
    try:
        assert len(stage.traces) == 2   # theta/alpha and the ground acceleration
        for index, t in enumerate(times):
            stage.draw(index)
            for trace, trace_times, _ in stage.traces:
                shown = np.asarray(trace.get_xdata())
                assert shown.size == np.count_nonzero(trace_times <= t)
                assert shown.size == 0 or shown.max() <= t
        for trace, trace_times, _ in stage.traces:   # the last frame: all of it
            assert np.asarray(trace.get_xdata()).size == trace_times.size
    finally:
        pyplot().close(stage.fig)


def test_cli_animate_takes_the_motion_options_of_simulate(tmp_path, capsys):
    out = tmp_path / "harmonic.gif"
    assert main(["animate", "--block", "30x6in", "--cor", "0.9", "--harmonic", "2Hz,0.3g",
                 "--duration", "2s", "--fps", "2", "--size", "320x180", "--out", str(out)]) == 0
    with Image.open(out) as gif:
        assert gif.n_frames == 5   # 0, 0.5, ..., 2 s
    direct = st.simulate(st.Block.parse("30x6in"),
                         motions.harmonic(2.0, horizontal=0.3 * G, duration=2.0), cor=0.9)
    assert f"30 x 6 in block, COR 0.9: {direct.verdict()}" in capsys.readouterr().out
    assert main(["animate", "fig-3-4", "--block", "30x6in", "--out", str(out)]) == 2
    assert "not both" in capsys.readouterr().err
    assert main(["animate", "--block", "30x6in", "--out", str(out)]) == 2
    assert "--cor" in capsys.readouterr().err
