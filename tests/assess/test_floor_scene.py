"""A scene's [floor]: the block feels the floor motion of the modal filter."""

import numpy as np
import pytest

import shaketable.scenes  # noqa: F401  (registers the [floor] parser)
from shaketable.ground import generators
from shaketable.ground.floor import Building, floor_motion
from shaketable.scenes.parse import SceneError, load_scene
from shaketable.scenes.run import build_motion

SCENE = """name = "on-a-floor"
[block]
size = "30x6in"
[motion]
kind = "harmonic"
frequency = "2 Hz"
horizontal = "0.1 g"
duration = "3 s"
dt = "0.01 s"
[rocking]
cor = 0.9
[floor]
floor = 2
period = "0.5 s"
height = "9 m"
storeys = 3
"""


def test_floor_scene_motion_is_the_floor_motion(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE, encoding="utf-8")
    scene = load_scene(path)
    ground = generators.harmonic(2.0, horizontal=0.1 * 9.80665, duration=3.0, dt=0.01)
    expected = floor_motion(ground, Building(0.5, 9.0, 3), floor=2)
    np.testing.assert_array_equal(build_motion(scene).horizontal, expected.horizontal)


@pytest.mark.parametrize("old, new, match", [
    ("floor = 2", "floor = 4", r"floor\.floor: floor 4 is above the roof.*\(line 13\)"),
    ('period = "0.5 s"', 'period = "0 s"', r"floor\.period: must be positive.*\(line 14\)"),
    ('height = "9 m"', "height = 9", r"floor\.height: .*no unit.*\(line 15\)"),
])
def test_bad_floor_names_the_key_and_line(tmp_path, old, new, match):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE.replace(old, new), encoding="utf-8")
    with pytest.raises(SceneError, match=match):
        load_scene(path)


def test_simulate_on_a_floor_from_the_command_line(tmp_path, capsys):
    import argparse

    from shaketable.cli import main
    from shaketable.commands.simulate_models import on_floor as _on_floor
    from shaketable.ground import records

    ground = records.load("el-centro-chopra")
    args = argparse.Namespace(floor=3, building="0.6s,17.5m,5")
    expected = floor_motion(ground, Building(0.6, 17.5, 5), floor=3)
    np.testing.assert_array_equal(_on_floor(args, ground).horizontal, expected.horizontal)
    assert main(["simulate", "--block", "2x0.5m", "--cor", "0.9", "--record",
                 "el-centro-chopra", "--floor", "6", "--building", "0.6s,17.5m,5",
                 "--out", str(tmp_path / "bad")]) == 2
    assert "--floor 6" in capsys.readouterr().err
    assert main(["simulate", "--block", "2x0.5m", "--cor", "0.9", "--record",
                 "el-centro-chopra", "--floor", "2", "--out", str(tmp_path / "bad")]) == 2
    assert "go together" in capsys.readouterr().err
