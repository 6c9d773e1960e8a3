"""Scenes (TOML experiments), the pipeline, ``run`` and ``reproduce``."""

import json

import pytest

from shaketable.cli import main
from shaketable.pipeline import run_scene
from shaketable.scenes import SceneError, load_scene, scene_from_dict, scene_names

GOOD = """
name = "demo"
source = "Fig. 3.4"

[block]
size = "30x6in"

[motion]
kind = "free"

[rocking]
cor = 0.925
theta0 = "0.5 alpha"
duration = "8 s"

[report]
t_rest = "6 s"
"""


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_every_bundled_scene_is_valid():
    names = scene_names()
    assert {"fig-3-4", "fig-3-7", "fig-4-1", "fig-4-17"} <= set(names)
    for name in names:
        from shaketable.scenes import resolve_scene_path

        scene = load_scene(resolve_scene_path(name))
        assert scene.source, name


def test_fig_3_4_scene_reproduces_the_report(tmp_path):
    scene = load_scene(write(tmp_path, GOOD))
    result = run_scene(scene)
    (line,) = result.comparisons
    # Section 3.7 (1): rest after about 6 s; within the report's 10 %.
    assert line.report == 6.0 and line.agrees
    written = result.write(tmp_path / "out")
    assert (tmp_path / "out" / "calcomp.png") in written
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["runs"][0]["cor [-]"] == 0.925


@pytest.mark.parametrize("change, message", [
    (("[block]\nsize = \"30x6in\"", "[block]\nsize = \"30x6in\"\ncolour = \"red\""),
     "unknown key 'colour' in \\[block\\]"),
    (("size = \"30x6in\"", "height = 30\nwidth = \"6 in\""), "block.height: 30 has no unit"),
    (("kind = \"free\"", "kind = \"wobble\""), "motion.kind must be one of"),
    (("cor = 0.925", "cor = 1.5"), "rocking.cor must be a number in \\[0, 1\\]"),
    (("duration = \"8 s\"", "duration = \"8 parsecs\""), "unknown time unit 'parsecs'"),
    (("t_rest = \"6 s\"", "rest = \"6 s\""), "unknown key 'rest' in \\[report\\]"),
    (("theta0 = \"0.5 alpha\"", "theta0 = \"half alpha\""), "rocking.theta0"),
])
def test_scene_errors_name_the_file_and_the_key(tmp_path, change, message):
    path = write(tmp_path, GOOD.replace(*change))
    with pytest.raises(SceneError, match=message) as error:
        load_scene(path)
    assert str(path) in str(error.value)


def test_missing_sections_and_bad_toml(tmp_path):
    with pytest.raises(SceneError, match="missing \\[block\\]"):
        scene_from_dict({"name": "x", "motion": {"kind": "free"}, "rocking": {"cor": 1}}, "s.toml")
    with pytest.raises(SceneError, match="not valid TOML"):
        load_scene(write(tmp_path, "name = "))
    with pytest.raises(SceneError, match="cannot read"):
        load_scene(tmp_path / "absent.toml")


def test_run_command_writes_outputs(tmp_path, capsys):
    path = write(tmp_path, GOOD)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    printed = capsys.readouterr().out
    assert "t rest: report 6.0 s" in printed and "agrees" in printed
    assert (tmp_path / "out" / "history.csv").exists()


def test_run_command_unknown_scene_is_a_clear_error(capsys):
    assert main(["run", "no-such-scene"]) == 2
    assert "no scene 'no-such-scene'" in capsys.readouterr().err


def test_reproduce_writes_a_markdown_report(tmp_path):
    out = tmp_path / "reproduced"
    assert main(["reproduce", "fig-3-4", "fig-3-7", "fig-4-1", "--out", str(out),
                 "--quiet"]) == 0
    text = (out / "report.md").read_text()
    assert "| t rest | 6 |" in text and "![fig-3-7](fig-3-7/calcomp.png)" in text
    assert (out / "fig-4-1" / "calcomp.png").exists()
