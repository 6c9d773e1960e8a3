"""A scene's ``[sliding]`` section: the same block and motion, sliding.

The sliding solver itself is checked against closed forms and Table 4.4 in
``tests/models/sliding``; here: the section is parsed strictly, the scene runs the
solver on the scene's own motion (the same numbers as a direct call), and the
outputs are written.
"""

from __future__ import annotations

import pytest

from shaketable.ground import records
from shaketable.models.sliding.engine import slide
from shaketable.models.sliding.result import Friction
from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import SceneError, load_scene, scene_from_dict
from shaketable.scenes.run import run_scene

BASE = {"name": "probe", "block": {"size": "8x2ft"},
        "motion": {"kind": "record", "name": "pacoima-dam-s16e"}, "rocking": {"cor": 0.95}}


@pytest.mark.usefixtures("figure_drafts")
def test_the_teaching_scene_runs_both_modes_and_matches_a_direct_call(tmp_path):
    scene = load_scene(resolve_scene_path("teaching-slide-or-rock"))
    assert scene.sliding == ((0.2, 0.15), (0.2, 0.1))
    result = run_scene(scene)
    assert len(result.runs) == 1 and len(result.slides) == 2
    direct = slide(records.load("pacoima-dam-s16e"), Friction(0.2, 0.15))
    assert result.slides[0].peak_slip == direct.peak_slip
    # a lower dynamic friction slides further (Table 4.4's trend over mu_d)
    assert result.slides[1].peak_slip > result.slides[0].peak_slip
    written = {path.name for path in result.write(tmp_path)}
    assert {"sliding-1.csv", "sliding-2.csv", "sliding-1.png"} <= written
    assert result.summary()["sliding"][0]["mode (Section 2.1)"] == "sliding"


@pytest.mark.parametrize("section, message", [
    ({"dynamic_friction": 0.1}, "static_friction is missing"),
    ({"static_friction": 0.2, "dynamic_friction": 0.3}, "must not exceed"),
    ({"static_friction": -0.2}, ">= 0"),
    ({"static_friction": "0.2"}, ">= 0"),
    ({"static_friction": 0.2, "dynamic_friction": []}, "empty"),
    ({"static_friction": 0.2, "colour": 1}, "colour"),
])
def test_a_bad_sliding_section_names_the_key(section, message):
    with pytest.raises(SceneError, match=message):
        scene_from_dict({**BASE, "sliding": section}, where="probe.toml")


def test_sliding_needs_a_table_motion():
    data = {**BASE, "motion": {"kind": "free"}, "rocking": {"cor": 0.9, "duration": "2 s",
                                                             "theta0": "0.1 rad"},
            "sliding": {"static_friction": 0.2}}
    with pytest.raises(SceneError, match="needs a table motion"):
        scene_from_dict(data, where="probe.toml")
