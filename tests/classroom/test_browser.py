"""The classroom page in a real browser: headless Chromium driven by Selenium.

``shaketable classroom --no-browser`` runs in a subprocess; the test loads its page,
switches lessons, types into fields, moves a slider with the keyboard, and checks that
the verdicts and numbers drawn equal those of ``simulate`` called here with the inputs
the page shows; a bad field gets its message while the page keeps working; the save
button writes a scene that ``shaketable run`` reproduces; Ctrl-C stops the server.
Skipped where Chromium, chromedriver, Selenium or Panel are missing (``.ci/run`` installs
them).
"""

from __future__ import annotations

import json
import math

import pytest

from tests.classroom import browser

pytestmark = pytest.mark.skipif(bool(browser.browser_missing()),
                                reason=browser.browser_missing() or "browser present")


def _direct(driver):
    """simulate() with the inputs the page's fields show (harmonic motion, one block)."""
    from shaketable import Block, simulate
    from shaketable.classroom.model import key_numbers
    from shaketable.core.units import parse
    from shaketable.ground import generators

    value = lambda name, kind: parse(browser.field_value(driver, name), kind)  # noqa: E731
    block = Block(value("height", "length"), value("width", "length"))
    motion = generators.harmonic(value("frequency", "frequency"),
                                 horizontal=value("amplitude", "acceleration"),
                                 vertical=value("vertical", "acceleration"),
                                 duration=value("duration", "time"))
    result = simulate(block, motion, cor=float(browser.field_value(driver, "cor")))
    return dict(verdict=result.verdict(), **key_numbers(result, "in"))


def test_the_page_in_chromium(tmp_path):
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.support.select import Select

    server = browser.Server(tmp_path / "saved", tmp_path)
    driver = browser.chromium()
    try:
        browser.load(driver, server.url + "?play=0")   # the lessons shown, not played
        # the first lesson is shown: two blocks, their verdicts under the picture
        first = browser.wait(lambda: browser.numbers(driver), timeout=60)
        assert set(first) == {0, 1}
        browser.click_button(driver, ".st-lesson", "The small block falls first")
        browser.wait(lambda: browser.numbers(driver).get(0, {}).get("max |θ|/α") == "F",
                     what="the small block's verdict")
        assert browser.numbers(driver)[0]["overturns at"] == "4.28 s"
        assert "small one overturns" in " ".join(browser.texts(driver, ".st-look-for"))

        # your block: the lesson's block alone on a harmonic motion
        browser.click_button(driver, ".st-lesson", "your block")
        Select(browser.inner(driver, ".st-compare", "select")).select_by_visible_text("none")
        browser.click_button(driver, ".st-motion", "harmonic")
        browser.type_into(driver, "duration", "8 s")
        expected = _direct(driver)
        browser.wait(lambda: browser.numbers(driver) == {0: expected},
                     what=f"the numbers of simulate: {expected}")

        # a slider moved with the keyboard: its field follows, the numbers are simulate's
        handle = browser.inner(driver, ".st-amplitude-slider", ".noUi-handle")
        handle.click()
        for _ in range(5):   # five steps of 0.01 g from 0.25 g
            handle.send_keys(Keys.ARROW_RIGHT)
        browser.wait(lambda: browser.field_value(driver, "amplitude") == "0.3 g",
                     what="the amplitude field to follow the slider to 0.3 g")
        moved = _direct(driver)
        browser.wait(lambda: browser.numbers(driver) == {0: moved},
                     what=f"the numbers after the slider: {moved}")

        # save: the scene file that `shaketable run` reproduces, and the figure
        browser.click_button(driver, ".st-save", "save figure and scene")
        browser.wait(lambda: "scene-01.toml" in " ".join(browser.texts(driver, ".st-status")),
                     what="the saved scene's name")
        scene = tmp_path / "saved" / "scene-01.toml"
        assert (tmp_path / "saved" / "figure-01.png").stat().st_size > 10_000
        from shaketable.cli import main

        assert main(["run", str(scene), "--out", str(tmp_path / "run"), "--quiet"]) == 0
        summary = json.loads((tmp_path / "run" / "summary.json").read_text())
        (run,) = summary["runs"]
        assert run["verdict"] == moved["verdict"]
        assert (f"{run['max_abs_theta [rad]'] / math.atan2(run['block_width [m]'], run['block_height [m]']):.3f}"
                if not run["overturned"] else "F") == moved["max |θ|/α"]
        assert str(run["n_impacts"]) == moved["impacts"]

        # bad input: a message next to the field; the page keeps the last good numbers
        for name, text, words in (("frequency", "2", "no unit"),
                                  ("height", "-3 in", "positive"), ("cor", "2", "[0, 1]")):
            browser.type_into(driver, name, text)
            browser.wait(lambda: words in " ".join(browser.texts(
                driver, f".st-{name}-message")), what=f"the message next to {name}")
        assert browser.numbers(driver) == {0: moved}
    finally:
        browser.close(driver)
        status, rest, _ = server.stop()
    assert status == 0 and "stopped" in rest   # Ctrl-C stops it cleanly
