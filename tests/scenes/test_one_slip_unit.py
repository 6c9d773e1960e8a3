"""One length unit for a scene's slips: its figures, its report lines and its console lines
(the block's own unit, or the next smaller one when a slip is under one of it)."""

from __future__ import annotations

import re
from types import SimpleNamespace

from shaketable.scenes.run import SceneResult, length_in


def _result(unit, slides, planar=()):
    scene = SimpleNamespace(block=SimpleNamespace(length_unit=unit))
    return SceneResult(scene=scene, motion=None, runs=(),
                       slides=tuple(SimpleNamespace(peak_slip=peak) for peak in slides),
                       planar=tuple(SimpleNamespace(summary=lambda peak=peak: {
                           "peak slip [m]": peak}) for peak in planar))


def test_the_scene_slip_unit_is_the_smallest_its_runs_need():
    # 1 ft = 0.3048 m: 0.394 m is 1.29 ft, 0.233 m is 0.76 ft (shown in inches)
    assert _result("ft", [0.394], [0.233]).slip_unit == "in"
    assert _result("ft", [0.394, 0.5]).slip_unit == "ft"
    assert _result("m", [0.3]).slip_unit == "mm"
    assert _result("in", [2.0]).slip_unit == "in"
    assert _result("ft", []).slip_unit == "ft"


def test_length_in_keeps_the_unit_it_is_given():
    assert length_in(0.394, "in") == "15.5 in"            # 0.394 / 0.0254 = 15.51
    assert length_in(-0.1181, "in", signed=True) == "-4.65 in"
    assert length_in(0.1, "ft") == "0.328 ft"             # not switched to inches
    assert length_in(float("nan"), "m") == "n/a"


SLIDING_SCENE = """name = "two-slips"
description = "an 8 x 2 ft block sliding on a 2-s harmonic table, two dynamic frictions"

[block]
size = "8x2ft"

[motion]
kind = "harmonic"
frequency = "1 Hz"
horizontal = "0.5 g"
duration = "2 s"

[rocking]
cor = 0.95

[sliding]
static_friction = 0.2
dynamic_friction = [0.15, 0.05]

[outputs]
figure = false
"""


def test_a_scene_section_says_every_slip_in_one_unit(tmp_path):
    from shaketable.reproduce import _scene_section
    from shaketable.studies.comparison import ComparisonTally

    path = tmp_path / "two-slips.toml"
    path.write_text(SLIDING_SCENE, encoding="utf-8")
    section = _scene_section(str(path), tmp_path / "out", ComparisonTally())
    lines = [line for line in section.splitlines() if line.startswith("* sliding")]
    assert len(lines) == 2
    units = {unit for line in lines
             for unit in re.findall(r"[-+]?\d[\d.]*(?:e[-+]?\d+)? (m|mm|in|ft)\b", line)}
    assert len(units) == 1, lines
