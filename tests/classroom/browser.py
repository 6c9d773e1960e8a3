"""Driving the classroom page in headless Chromium (Selenium and the distribution's chromedriver).

Shared by the browser test and ``benchmarks/classroom_redraw.py``: start ``shaketable
classroom`` in a subprocess, open its address, find the page's widgets (Bokeh draws each
in a shadow root) by the ``st-*`` classes the page gives them.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from tests.helpers import ctrl_c_reaches_subprocesses

CHROMIUM = ("/usr/bin/chromium", "/usr/bin/chromium-browser")
CHROMEDRIVER = "/usr/bin/chromedriver"

#: Chromium's flags: headless, no sandbox (a container), nothing fetched from the network.
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--window-size=1500,1300")

#: A JavaScript helper: every element matching a selector, through all shadow roots.
DEEP = """
function deepAll(selector, root) {
  root = root || document;
  let found = Array.from(root.querySelectorAll(selector));
  for (const element of root.querySelectorAll('*')) {
    if (element.shadowRoot) { found = found.concat(deepAll(selector, element.shadowRoot)); }
  }
  return found;
}
"""


def browser_missing() -> str:
    """Why the browser test cannot run here ('' when it can)."""
    if not any(Path(path).exists() for path in CHROMIUM) or not Path(CHROMEDRIVER).exists():
        return "no chromium and chromedriver (apt-get install chromium chromium-driver)"
    import importlib.util

    # found, not imported: this runs when every xdist worker collects the tests, and
    # importing panel (bokeh) there cost each worker about 1.3 s of CPU for one test
    for module in ("selenium", "panel"):
        if importlib.util.find_spec(module) is None:
            return f"{module} is not installed (pip install 'shaketable[test,classroom]')"
    return ""


class Server:
    """``shaketable classroom --no-browser`` in a subprocess; ``url`` once it listens."""

    def __init__(self, out: Path, cwd: Path, timeout: float = 120.0):
        import shaketable

        # the package under test, wherever the subprocess starts
        environment = dict(os.environ)
        root = str(Path(shaketable.__file__).resolve().parents[1])
        environment["PYTHONPATH"] = os.pathsep.join(
            [root] + [part for part in environment.get("PYTHONPATH", "").split(os.pathsep) if part])
        # stderr to a file: the server's log must never fill a pipe nobody reads
        self.errors = tempfile.TemporaryFile(mode="w+")
        with ctrl_c_reaches_subprocesses():   # stopped with Ctrl-C, however the tests started
            self.process = subprocess.Popen(
                [sys.executable, "-m", "shaketable", "classroom", "--no-browser",
                 "--out", str(out)], cwd=cwd, stdout=subprocess.PIPE, stderr=self.errors,
                text=True, env=environment)
        assert self.process.stdout is not None
        line = self.process.stdout.readline()
        if "http://" not in line:
            _, rest, errors = self.stop()
            raise RuntimeError(f"the classroom did not start: {line!r} {rest} {errors}")
        self.url = line[line.index("http://"):].split()[0]

    def stop(self) -> tuple:
        """Ctrl-C (SIGINT); (exit status, rest of stdout, stderr)."""
        import signal

        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
        try:
            rest, _ = self.process.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            self.process.kill()
            rest, _ = self.process.communicate()
        self.errors.seek(0)
        errors = self.errors.read()
        self.errors.close()
        return self.process.returncode, rest, errors


def chromium():
    """A headless Chromium under Selenium, with a fresh profile folder."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = next(path for path in CHROMIUM if Path(path).exists())
    profile = tempfile.mkdtemp(prefix="shaketable-chromium-")
    for flag in (*FLAGS, f"--user-data-dir={profile}"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"performance": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.profile_folder = profile
    return driver


def load(driver, url: str) -> None:
    """Open the page (again)."""
    driver.numbers_host = None
    driver.get(url)


def close(driver) -> None:
    driver.quit()
    shutil.rmtree(driver.profile_folder, ignore_errors=True)


def wait(condition, timeout: float = 20.0, what: str = "the page"):
    """Poll ``condition()`` until it is truthy; its value."""
    end = time.perf_counter() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.perf_counter() > end:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.1)


def texts(driver, selector: str) -> list:
    """The text of every element matching ``selector`` (through the shadow roots; a
    widget's own text is in its shadow root)."""
    return driver.execute_script(
        DEEP + "return deepAll(arguments[0]).map(e => Array.from((e.shadowRoot || e).childNodes)"
        ".filter(n => !['STYLE', 'LINK'].includes(n.nodeName)).map(n => n.textContent)"
        ".join(''));",
        selector)


def inner(driver, host: str, selector: str):
    """The element ``selector`` inside the widget of class ``host`` (its shadow root)."""
    return driver.execute_script(
        DEEP + "const hosts = deepAll(arguments[0]);"
        "for (const h of hosts) { const r = h.shadowRoot ? h.shadowRoot.querySelector("
        "arguments[1]) : h.querySelector(arguments[1]); if (r) return r; } return null;",
        host, selector)


def type_into(driver, name: str, text: str) -> None:
    """Type ``text`` into the field ``name`` and press Enter."""
    from selenium.webdriver.common.keys import Keys

    field = wait(lambda: inner(driver, f".st-{name}", "input"), what=f"the field {name}")
    driver.execute_script("arguments[0].value = '';", field)   # then typed as a user does
    field.send_keys(text, Keys.ENTER)


def field_value(driver, name: str) -> str:
    return driver.execute_script("return arguments[0].value;",
                                 inner(driver, f".st-{name}", "input"))


def click_button(driver, host: str, label: str) -> None:
    """Click the button reading ``label`` in the widget of class ``host``."""
    def find():
        return driver.execute_script(
            DEEP + "for (const b of deepAll(arguments[0] + ' button')) {"
            " if (b.textContent.trim() === arguments[1]) return b; }"
            "for (const h of deepAll(arguments[0])) { if (!h.shadowRoot) continue;"
            " for (const b of h.shadowRoot.querySelectorAll('button')) {"
            "  if (b.textContent.trim() === arguments[1]) return b; } } return null;",
            host, label)
    from selenium.common.exceptions import StaleElementReferenceException

    for _ in range(5):   # a button whose label just changed may be drawn anew
        try:
            wait(find, what=f"the button {label!r}").click()
            return
        except StaleElementReferenceException:
            time.sleep(0.2)
    wait(find, what=f"the button {label!r}").click()


def numbers(driver) -> dict:
    """The verdicts and the key numbers under the picture, by run: {run: {key: text}}."""
    host = getattr(driver, "numbers_host", None)
    if host is None:   # found once: the pane's element stays, its content changes
        host = driver.numbers_host = wait(lambda: driver.execute_script(
            DEEP + "return deepAll('.st-numbers')[0];"), what="the numbers")
    found = driver.execute_script(
        "return Array.from(arguments[0].shadowRoot.querySelectorAll("
        "'td.st-verdict, td.st-number')).map(e => [e.dataset.run, e.dataset.key || 'verdict',"
        " e.textContent]);", host)
    table: dict = {}
    for run, key, text in found:
        table.setdefault(int(run), {})[key] = text
    return table
