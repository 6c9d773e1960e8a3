"""The classroom page's speed: a slider move's recompute-and-redraw, and the page's load.

1. Recompute and redraw (no browser): a page (:class:`shaketable.classroom.page.ClassroomPage`)
   with a 20 s harmonic motion (36 x 9 in block, COR 0.9, 2 Hz, 0.28-0.36 g: it rocks and
   survives), a 20 s stretch of Pacoima Dam S74W (6 x 2 ft block) and the same harmonic
   with friction (mu_s 0.5, mu_d 0.4: the planar block); the amplitude (the record's
   scale) is changed as a slider does, which runs the scene
   (:func:`shaketable.classroom.model.compute`) and updates every figure's data (the
   drawing's first frame, the traces and the band cleared, the numbers). Printed: the
   median and the largest of the repeats, and :func:`compute` alone. Target: < 100 ms.
   Also the server's part of a page load: building one visitor's page and its Bokeh
   document (no browser).
2. Page load (headless Chromium, when installed): ``shaketable classroom --no-browser``
   started in a subprocess (the engine compiled before), the time from asking for the
   page to its numbers drawn, first and second visit; then the time from typing a value
   in a field to the new numbers drawn in the browser. Target: < 3 s.

The load average is printed: on a shared 2-core machine the times scale with it.

    python3 benchmarks/classroom_redraw.py [--repeats 20] [--no-browser]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from shaketable.classroom.model import Settings, compute  # noqa: E402


def _redraw(repeats: int) -> None:
    from shaketable.classroom.page import ClassroomPage

    cases = {
        "harmonic 20 s": (Settings(duration="20 s", amplitude="0.28 g", height="36 in",
                                   width="9 in", cor="0.9"), "amplitude",
                          [f"{0.28 + 0.004 * k:.3f} g" for k in range(repeats)]),
        "record 20 s": (Settings(motion="record", duration="20 s", height="6 ft",
                                 width="2 ft", cor="0.93"), "record_scale",
                        [f"{0.8 + 0.01 * k:.2f}" for k in range(repeats)]),
        "harmonic 20 s, friction": (Settings(duration="20 s", amplitude="0.28 g",
                                             height="36 in", width="9 in", cor="0.9",
                                             friction=True), "amplitude",
                                    [f"{0.28 + 0.004 * k:.3f} g" for k in range(repeats)]),
    }
    with tempfile.TemporaryDirectory() as folder:
        for name, (settings, field, values) in cases.items():
            page = ClassroomPage(Path(folder), settings)
            page.layout()
            redraws, computes, cpu = [], [], []
            for value in values:
                start, start_cpu = time.perf_counter(), time.process_time()
                page.fields[field].text.value = value   # as a slider or a typed value does
                redraws.append(time.perf_counter() - start)
                cpu.append(time.process_time() - start_cpu)
                assert page.status.object == "", page.status.object
                start = time.perf_counter()
                compute(replace(settings, **{field: value}))
                computes.append(time.perf_counter() - start)
            samples = min(run.t.size for run in page.picture.runs)
            print(f"{name} (>= {samples} samples): recompute and redraw median "
                  f"{1e3 * statistics.median(redraws):.1f} ms, largest "
                  f"{1e3 * max(redraws):.1f} ms (CPU median {1e3 * statistics.median(cpu):.1f} "
                  f"ms); compute alone median "
                  f"{1e3 * statistics.median(computes):.1f} ms")


def _session() -> None:
    from bokeh.document import Document

    from shaketable.classroom.page import ClassroomPage

    with tempfile.TemporaryDirectory() as folder:
        times, cpu = [], []
        for _ in range(3):
            start, start_cpu = time.perf_counter(), time.process_time()
            ClassroomPage(Path(folder)).layout().get_root(Document())
            times.append(time.perf_counter() - start)
            cpu.append(time.process_time() - start_cpu)
    print(f"the server's part of a page load (the page and its document built): "
          f"{', '.join(f'{value:.2f}' for value in times)} s "
          f"({', '.join(f'{value:.2f}' for value in cpu)} s of CPU)")


def _page_load() -> None:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from tests.classroom import browser

    missing = browser.browser_missing()
    if missing:
        print(f"page load: skipped ({missing})")
        return
    with tempfile.TemporaryDirectory() as folder:
        server = browser.Server(Path(folder) / "out", Path(folder))
        driver = browser.chromium()
        try:
            for visit in ("first", "second"):
                start = time.perf_counter()
                browser.load(driver, server.url)
                browser.wait(lambda: browser.numbers(driver), timeout=60)
                print(f"page load ({visit} visit): {time.perf_counter() - start:.2f} s")
            browser.click_button(driver, ".st-lesson", "your block")
            browser.wait(lambda: browser.numbers(driver))
            before = browser.numbers(driver)
            start = time.perf_counter()
            browser.type_into(driver, "cor", "0.5")
            browser.wait(lambda: browser.numbers(driver) != before, timeout=30)
            print(f"a typed value to the new numbers in the browser: "
                  f"{time.perf_counter() - start:.2f} s")
        finally:
            browser.close(driver)
            server.stop()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20)
    parser.add_argument("--no-browser", action="store_true")
    args = parser.parse_args()
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    compute(Settings())   # the engines compiled or loaded from the cache first
    compute(replace(Settings(), friction=True))
    _redraw(args.repeats)
    _session()
    if not args.no_browser:
        _page_load()
    print(f"load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
