"""Look at the built site as a reader would: empty sidebars, code cut at the right edge.

Run by hand after a build (CI has no browser)::

    python -m sphinx -W -b html docs docs/_build/html
    python docs/tools/check_site.py [--screenshots DIR] [--width 1280]

Three checks, each page of ``docs/_build/html``:

* **empty sidebar** (no browser needed): a primary sidebar ("Section Navigation")
  drawn without a single link in it;
* **cut API summaries** (no browser needed): a summary cell of the API reference ending
  at an abbreviation ("..., Eqs.") or holding a builtin's docstring (``float``'s);
* **clipped code** (headless Chromium, when one is found): in a window ``--width``
  pixels wide, a code block or output (``pre``) wider than its box, whose end the reader
  would have to scroll to. Chromium loads a small page that frames each page of the
  site in turn and measures ``scrollWidth`` against ``clientWidth`` of every ``pre``.

``--screenshots DIR`` also saves a screenshot of every top-level page, to look at.
Exit status 0 when nothing is found, 1 otherwise (each finding printed).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser
from pathlib import Path

SITE = Path(__file__).resolve().parents[1] / "_build" / "html"
CHROMIUM = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


class _Sidebar(HTMLParser):
    """Counts the links of the primary sidebar's "Section Navigation" (``bd-docs-nav``)."""

    VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta",
            "source", "track", "wbr"}

    def __init__(self) -> None:
        super().__init__()
        self.depth = 0          # > 0 inside the section navigation
        self.present = False
        self.links = 0

    def handle_starttag(self, tag, attrs):
        if tag in self.VOID:
            return
        if self.depth:
            self.depth += 1
            self.links += tag == "a" and bool(dict(attrs).get("href"))
        elif "bd-docs-nav" in (dict(attrs).get("class") or "").split():
            self.present, self.depth = True, 1

    def handle_endtag(self, tag):
        if self.depth and tag not in self.VOID:
            self.depth -= 1


def empty_sidebars(site: Path) -> list[str]:
    """Pages whose primary sidebar is drawn with no navigation link in it."""
    found = []
    for page in sorted(site.rglob("*.html")):
        if page.name in ("search.html", "genindex.html") or "_modules" in page.parts:
            continue
        parser = _Sidebar()
        parser.feed(page.read_text(encoding="utf-8", errors="replace"))
        if parser.present and parser.links == 0:
            found.append(str(page.relative_to(site)))
    return found


_PROBE = """<!doctype html><html><body><pre id="result">running</pre>
<iframe id="frame" style="width:{width}px;height:900px;border:0"></iframe>
<script>
const pages = {pages};
const found = [];
const frame = document.getElementById("frame");
let index = 0;
function next() {{
  if (index >= pages.length) {{
    document.getElementById("result").textContent = "RESULT " + JSON.stringify(found);
    return;
  }}
  frame.onload = () => {{
    const doc = frame.contentDocument;
    for (const pre of doc.querySelectorAll("article pre, main pre")) {{
      if (pre.offsetParent !== null && pre.scrollWidth > pre.clientWidth + 1) {{
        found.push([pages[index], pre.textContent.trim().slice(0, 70)]);
      }}
    }}
    index += 1;
    next();
  }};
  frame.src = pages[index];
}}
next();
</script></body></html>"""


def clipped_code(site: Path, pages: list[Path], browser: str, width: int) -> list:
    """(page, start of the block) for every code block wider than its box."""
    with tempfile.TemporaryDirectory() as scratch:
        probe = Path(scratch) / "probe.html"
        probe.write_text(_PROBE.format(width=width, pages=json.dumps(
            [page.as_uri() for page in pages])))
        done = subprocess.run([browser, *FLAGS, "--allow-file-access-from-files",
                               "--virtual-time-budget=120000", "--dump-dom", probe.as_uri()],
                              capture_output=True, text=True, timeout=600)
    match = re.search(r"RESULT (\[.*?\])</pre>", done.stdout, flags=re.DOTALL)
    if not match:
        raise RuntimeError(f"{browser} did not report (stderr: {done.stderr.strip()[-300:]})")
    import html

    return [(str(Path(page[len("file://"):]).relative_to(site)), text)
            for page, text in json.loads(html.unescape(match.group(1)))]


def cut_summaries(site: Path) -> list[str]:
    """API summary cells cut at an abbreviation ("Rocking response ..., Eqs.") or holding a
    builtin's docstring (a constant such as ``shaketable.G`` summarised as ``float``)."""
    found = []
    cell = re.compile(r"<td><p>(.*?)</p></td>", flags=re.DOTALL)
    for page in sorted((site / "api").rglob("*.html")):
        for text in cell.findall(page.read_text(encoding="utf-8", errors="replace")):
            plain = re.sub(r"<[^>]+>", "", text).strip()
            if re.search(r"\b(Eqs?|Figs?|Secs?)\.$", plain) or plain.startswith(
                    ("Convert a string or number to a floating", "int([x]) -> integer")):
                found.append(f"{page.relative_to(site)}: {plain[:70]!r}")
    return found


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--site", type=Path, default=SITE, help="the built site")
    parser.add_argument("--width", type=int, default=1280, help="window width [pixels]")
    parser.add_argument("--screenshots", type=Path, help="save screenshots of the top pages")
    args = parser.parse_args(argv)
    if not (args.site / "index.html").is_file():
        print(f"no built site in {args.site}; build it first", file=sys.stderr)
        return 2
    problems = [f"empty sidebar: {page}" for page in empty_sidebars(args.site)]
    problems += [f"API summary cut or borrowed: {where}" for where in cut_summaries(args.site)]
    browser = next((shutil.which(name) for name in CHROMIUM if shutil.which(name)), None)
    pages = sorted(args.site.glob("*.html")) + sorted(args.site.glob("auto_examples/*.html"))
    pages = [page for page in pages if page.name not in ("search.html", "genindex.html",
                                                         "py-modindex.html")]
    if browser is None:
        print("no Chromium found: the clipped-code check and the screenshots are skipped")
    else:
        problems += [f"code cut at the right edge: {page}: {text!r}"
                     for page, text in clipped_code(args.site, pages, browser, args.width)]
        if args.screenshots:
            args.screenshots.mkdir(parents=True, exist_ok=True)
            for page in sorted(args.site.glob("*.html")):
                subprocess.run([browser, *FLAGS, f"--window-size={args.width},900",
                                f"--screenshot={args.screenshots / (page.stem + '.png')}",
                                page.as_uri()], capture_output=True, timeout=120)
            print(f"screenshots in {args.screenshots}")
    for line in problems:
        print(line)
    print(f"{len(problems)} problem(s) in {len(pages)} pages checked in a browser, "
          f"every page for its sidebar")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
