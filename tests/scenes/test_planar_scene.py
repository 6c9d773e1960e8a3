"""The planar block from a scene (``block.static_friction``) and from ``simulate --friction``.

Reference: the sliding model of Table 4.4 (:func:`shaketable.models.sliding.engine.slide`, exact
piecewise integration). A block with mu_s < B/H only slides (Section 2.1, Eqs. 2-1/2-2: slip
comes first, and a flat sliding block with mu_d <= B/H never tips), so its planar run must
give the sliding model's peak slip.
"""

from __future__ import annotations

import json

import pytest

from shaketable.models.sliding.engine import slide
from shaketable.models.sliding.result import Friction
from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import SceneError, load_scene
from shaketable.scenes.run import run_scene
from tests.test_bad_input import run_cli


def test_teaching_slide_or_rock_runs_the_planar_block_that_only_slides():
    scene = load_scene(resolve_scene_path("teaching-slide-or-rock"))
    assert (scene.static_friction, scene.dynamic_friction) == (0.2, 0.15)
    result = run_scene(scene)
    (planar,) = result.planar
    assert planar.verdict() == "slid"   # mu_s 0.2 < B/H 0.25
    sliding = slide(result.motion, Friction(0.2, 0.15))
    assert planar.peak_slip == pytest.approx(sliding.peak_slip, rel=1e-9)
    assert result.summary()["planar"][0]["verdict"] == "slid"


def _scene(tmp_path, block_lines: str):
    path = tmp_path / "s.toml"
    path.write_text('name = "s"\n[block]\nsize = "8x2ft"\n' + block_lines
                    + '[motion]\nkind = "harmonic"\nfrequency = "2 Hz"\nhorizontal = "0.4 g"\n'
                    'duration = "3 s"\n[rocking]\ncor = 0.9\n')
    return path


@pytest.mark.parametrize("lines, message", [
    ("dynamic_friction = 0.2\n", "needs block.static_friction"),
    ("static_friction = 0.3\ndynamic_friction = 0.4\n", "block.dynamic_friction"),
    ("static_friction = 0.3\ndynamic_friction = -0.1\n", "block.dynamic_friction"),
])
def test_scene_friction_errors_name_the_key(tmp_path, lines, message):
    with pytest.raises(SceneError, match=message):
        load_scene(_scene(tmp_path, lines))


def test_scene_with_rods_and_friction_is_refused(tmp_path):
    path = _scene(tmp_path, "static_friction = 0.6\n[block.rods]\nstiffness = \"0.4 W/in\"\n"
                            "force = \"0.3 W\"\nedge_distance = \"3 in\"\n")
    with pytest.raises(SceneError, match="prestress rods"):
        run_scene(load_scene(path))


@pytest.mark.usefixtures("figure_drafts")
def test_simulate_friction_writes_the_planar_run(tmp_path):
    status, out, err = run_cli(["simulate", "--block", "16x4ft", "--cor", "0.95", "--record",
                                "pacoima-dam-s16e", "--friction", "0.3,0.25", "--out",
                                tmp_path / "run"], cwd=tmp_path)
    assert status == 0, err
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["static friction mu_s [-]"] == 0.3
    assert summary["dynamic friction mu_d [-]"] == 0.25
    assert summary["verdict"] in out
    for bad, message in [("0.2,0.3", "must not exceed"), ("a", "--friction"),
                         ("0.1,0.1,0.1", "--friction")]:
        status, _, err = run_cli(["simulate", "--block", "16x4ft", "--cor", "0.95", "--record",
                                  "pacoima-dam-s16e", "--friction", bad, "--out",
                                  tmp_path / "bad"], cwd=tmp_path)
        assert status == 2 and message in err and "Traceback" not in err
