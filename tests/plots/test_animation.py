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
    frame_times,
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


def test_animate_writes_a_gif_with_the_expected_frames_and_size(tmp_path):
    block = st.Block.from_inches(30, 6)
    result = st.simulate(block, cor=0.925, theta0=0.5 * block.alpha, duration=1.0)
    written = animate(result, block, out=tmp_path / "rock.gif", fps=6, speed=1.0, dpi=40)
    # 1 s at 6 frames per second: frames at 0, 1/6, ..., 1 s
    assert written.n_frames == 7
    with Image.open(written.path) as gif:
        assert gif.n_frames == 7
        assert gif.size == (320, 144)  # 8 x 3.6 in at 40 dpi
    assert written.path.stat().st_size < 2_000_000
    with pytest.raises(ValueError, match="out must be a .gif"):
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
