"""Screenshots of the classroom page at each lesson, for docs/teaching.md.

Starts ``shaketable classroom --no-browser``, opens it in headless Chromium (the
distribution's ``chromium`` and ``chromium-driver``, driven by Selenium), and for each
lesson lets it play for a few seconds and saves the page, reduced to a small PNG::

    python docs/tools/classroom_screenshots.py [--out docs/figures]

Writes ``classroom_<lesson>.png`` (about 1000 pixels wide, a 64-colour palette).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from tests.classroom import browser  # noqa: E402

#: Lesson button -> (file stem, seconds of real-time play before the picture).
SHOTS = {"A lower COR can raise the response": ("lower_cor", 9.0),
         "The small block falls first": ("small_falls", 6.0),
         "The period grows with the amplitude": ("period", 2.5)}


def _small(source: Path, target: Path, width: int = 1000) -> None:
    from PIL import Image

    with Image.open(source) as image:
        image = image.convert("RGB")
        box = image.getbbox()
        image = image.crop((0, 0, min(image.width, 1480), box[3] if box else image.height))
        image = image.resize((width, round(image.height * width / image.width)),
                             Image.Resampling.LANCZOS)
        image.quantize(colors=64).save(target, optimize=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "figures")
    args = parser.parse_args()
    missing = browser.browser_missing()
    if missing:
        raise SystemExit(missing)
    with tempfile.TemporaryDirectory() as folder:
        server = browser.Server(Path(folder) / "saved", Path(folder))
        driver = browser.chromium()
        try:
            browser.load(driver, server.url)
            browser.wait(lambda: browser.numbers(driver), timeout=60)
            for title, (stem, seconds) in SHOTS.items():
                browser.click_button(driver, ".st-lesson", title)
                time.sleep(seconds)   # the lesson plays from its start when shown
                raw = Path(folder) / f"{stem}.png"
                driver.save_screenshot(str(raw))
                _small(raw, args.out / f"classroom_{stem}.png")
                print(f"wrote {args.out / f'classroom_{stem}.png'}")
        finally:
            browser.close(driver)
            server.stop()


if __name__ == "__main__":
    main()
