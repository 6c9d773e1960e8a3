"""The classroom page's Python side, without a browser (Panel objects in this process).

A bad field shows its message and keeps the last good picture; a lesson loads its
settings; the save button's files reproduce the page through ``shaketable run``; the
drawing reveals the traces up to the time shown only.
"""

from __future__ import annotations

import importlib.util
import json

import numpy as np
import pytest

from shaketable.classroom.model import LESSONS, Settings, compute

# Panel (with bokeh) is imported by the page's tests, not when the file is collected: about
# 1 s of CPU that every xdist worker paid at collection. The tests share one xdist group,
# so that one worker imports it. Panel 1.9 announces renamed widget arguments (name ->
# label) that older Panels lack.
pytestmark = [pytest.mark.skipif(importlib.util.find_spec("panel") is None,
                                 reason="the optional extra 'classroom' (panel) is not installed"),
              pytest.mark.filterwarnings("ignore::PendingDeprecationWarning"),
              pytest.mark.xdist_group("tests/classroom/test_page.py")]


def ClassroomPage(*args, **kwargs):
    """``shaketable.classroom.page.ClassroomPage`` (imports Panel on first use)."""
    from shaketable.classroom.page import ClassroomPage as page

    return page(*args, **kwargs)


def free_port():
    """``shaketable.classroom.page.free_port`` (imports Panel on first use)."""
    from shaketable.classroom.page import free_port as port

    return port()


def test_a_bad_field_gets_a_message_and_the_page_keeps_its_picture(tmp_path):
    page = ClassroomPage(tmp_path, Settings(duration="4 s", amplitude="0.3 g"))
    page.layout()
    good = page.picture
    assert good is not None and page.status.object == ""
    page.fields["cor"].text.value = "2"
    assert "[0, 1]" in page.fields["cor"].message.object and page.fields["cor"].message.visible
    assert page.picture is good
    page.fields["cor"].text.value = "0.8"   # fixed: the message goes, the page recomputes
    assert page.fields["cor"].message.object == "" and page.picture is not good
    assert page.picture.runs[0].cor == 0.8
    # the slider follows a typed value, in the unit typed
    page.fields["height"].text.value = "0.9 m"
    assert page.fields["height"].slider.value == pytest.approx(0.9)
    assert page.picture.runs[0].block.height == pytest.approx(0.9)


def test_a_lesson_loads_its_settings_and_the_save_reproduces_it(tmp_path):
    from shaketable.cli import main

    page = ClassroomPage(tmp_path / "saved", Settings())
    page.layout()
    page.lesson.value = LESSONS["lower-cor"].title
    assert page.settings() == LESSONS["lower-cor"].settings
    assert "0.93" in page.look_for.object
    scene, image = page.save()
    assert scene.name == "scene-01.toml" and image.stat().st_size > 10_000
    assert main(["run", str(scene), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    runs = json.loads((tmp_path / "run" / "summary.json").read_text())["runs"]
    assert [run["n_impacts"] for run in runs] == [run.n_impacts for run in page.picture.runs]


def test_the_drawing_shows_the_traces_up_to_the_time_shown(tmp_path):
    page = ClassroomPage(tmp_path, LESSONS["period"].settings, autoplay=False)
    page.layout()
    page.start(0.0)
    page.show(2.5)
    times, ratio = compute(LESSONS["period"].settings).traces[1]
    shown = page.trace_sources[1].data
    assert np.max(shown["t"]) <= 2.5 and len(shown["t"]) == np.count_nonzero(times <= 2.5)
    np.testing.assert_array_equal(shown["r"], ratio[times <= 2.5])
    page.show(4.0)   # streamed on: the points up to 4 s, none twice
    assert len(page.trace_sources[1].data["t"]) == np.count_nonzero(times <= 4.0)


def test_a_free_port_is_free():
    import socket

    port = free_port()
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("localhost", port))
