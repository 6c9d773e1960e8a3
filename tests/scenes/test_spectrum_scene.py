"""The ``overturning-spectrum`` study kind: a scene runs the spectrum, writes
its CSV, figure and report section, and compares with published edges.

Reference values: Zhang, J. and Makris, N., "Rocking response of free-standing blocks
under cycloidal pulses", J. Eng. Mech. 127(5), 473-483, 2001: the
one-sine at omega/p = 4 (alpha 0.25 rad, p 2 rad/s, Housner's COR) overturns from
1.78856 to 5.00928 and above 5.32302 (6 significant digits: agreement within 5e-6).
"""

import math

import pandas as pd
import pytest

from shaketable.reproduce import run_study
from shaketable.scenes.parse import SceneError, Study, load_scene
from tests.helpers import REPOSITORY
from tests.test_bad_input import run_cli

SCENE = REPOSITORY / "experiments" / "spectrum-one-sine.toml"
ZHANG_MAKRIS_4 = [1.78856, 5.00928, 5.32302]

SMALL = """
name = "small-spectrum"
source = "test"
[study]
kind = "overturning-spectrum"
pulse = ["half-sine"]
block = "16x4ft"
cor = 0.9
omega_over_p = "2:4:2"
scan_step = 0.02
tolerance = 1e-6
"""


def test_the_bundled_scene_reads_as_the_issue_asks():
    study = load_scene(SCENE)
    assert isinstance(study, Study) and study.kind == "overturning-spectrum"
    settings = study.spectrum
    assert settings.pulses == ("one-sine",) and settings.cor == "housner"
    assert settings.ratios == (2.0, 3.0, 4.0)
    assert settings.block.alpha == pytest.approx(0.25, rel=1e-12)
    assert settings.block.p == pytest.approx(2.0, rel=1e-12)
    (reference,) = settings.references
    assert reference.edges == tuple(ZHANG_MAKRIS_4) and reference.tolerance == 5e-6


def test_the_bundled_scene_reproduces_zhang_makris(tmp_path):
    # through `shaketable run spectrum-one-sine`, with the checks that
    # tests/scenes/test_every_scene_runs.py makes on every other bundled scene (which leaves
    # this one out, so that it runs once in the suite)
    status, out, err = run_cli(["run", SCENE.stem, "--out", str(tmp_path / "out")],
                               cwd=tmp_path)
    assert "Traceback" not in err and "internal error" not in err, err
    assert status == 0, err
    assert "wrote" in out
    text = (tmp_path / "out" / "report.md").read_text()
    assert "![spectrum-one-sine](spectrum.png)" in text
    assert "| Zhang & Makris (2001)" in text and text.rstrip().endswith("| yes |")
    frame = pd.read_csv(tmp_path / "out" / "spectrum.csv", comment="#")
    rows = frame[frame["omega/p [-]"] == 4]
    assert list(rows["verdict"]) == ["safe", "overturns", "safe", "overturns"]
    assert list(rows["how"].fillna("")) == ["", "after 1 impact", "", "without impact"]
    edges = list(rows["from a/(g tan alpha) [-]"])[1:]
    assert edges == pytest.approx(ZHANG_MAKRIS_4, abs=5e-6)
    assert (tmp_path / "out" / "spectrum.png").stat().st_size > 0
    # a markdown table cell with |theta| must not break the table
    assert "(\\|theta\\| > alpha)" in text


def test_a_scene_with_a_block_size_and_a_range(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    study = load_scene(path)
    assert study.spectrum.ratios == (2.0, 4.0) and study.spectrum.cor == 0.9
    status, out, err = run_cli(["run", str(path), "--out", str(tmp_path / "out")],
                               cwd=tmp_path)
    assert status == 0, err
    frame = pd.read_csv(tmp_path / "out" / "spectrum.csv", comment="#")
    assert set(frame["omega/p [-]"]) == {2.0, 4.0}
    # the half-sine: one transition per omega/p, safe below and overturning above
    for _, rows in frame.groupby("omega/p [-]"):
        assert list(rows["verdict"]) == ["safe", "overturns"]
    assert "Published band edges" not in (tmp_path / "out" / "report.md").read_text()


@pytest.mark.parametrize("change, message", [
    (('block = "16x4ft"', ''), "the block is missing: give study.block"),
    (('block = "16x4ft"', 'block = "16x4ft"\nalpha = "0.25 rad"\np = "2 rad/s"'),
     "give study.block or study.alpha and study.p, not both"),
    (('block = "16x4ft"', 'alpha = "0.25 rad"\np = 2'), "study.p must be a frequency parameter"),
    (('pulse = ["half-sine"]', 'pulse = "square"'), "study.pulse: unknown pulse kind 'square'"),
    (('cor = 0.9', 'cor = "soft"'), "study.cor must be a number in \\[0, 1\\] or 'housner'"),
    (('omega_over_p = "2:4:2"', 'omega_over_p = [2, -1]'),
     "study.omega_over_p: omega/p values must be positive"),
    (('tolerance = 1e-6', 'tolerance = 0.5'), "study.tolerance must be a number in"),
    (('tolerance = 1e-6', 'tolerance = 1e-6\nwobble = 1'), "unknown key 'wobble' in \\[study\\]"),
    (('tolerance = 1e-6', 'tolerance = 1e-6\n[[study.reference]]\npulse = "half-sine"\n'
      'omega_over_p = 3\nedges = [1.0]\ntolerance = 1e-3'),
     "study.reference\\[0\\] compares half-sine at omega/p = 3, which the study does not"),
    (('tolerance = 1e-6', 'tolerance = 1e-6\n[[study.reference]]\npulse = "half-sine"\n'
      'omega_over_p = 2\nedges = [2.0, 1.0]\ntolerance = 1e-3'),
     "study.reference\\[0\\].edges must be increasing"),
])
def test_bad_spectrum_scenes_name_the_file_and_the_key(tmp_path, change, message):
    path = tmp_path / "bad.toml"
    text = SMALL.replace(*change)
    assert text != SMALL
    path.write_text(text)
    with pytest.raises(SceneError, match=f"bad.toml: .*{message}"):
        load_scene(path)


def test_a_failed_comparison_says_no(tmp_path):
    """A published edge the engine does not reproduce is reported as **no** (the
    comparison can fail: here the half-sine edge at omega/p = 2 is put 1 % off)."""
    path = tmp_path / "off.toml"
    path.write_text(SMALL + '[[study.reference]]\npulse = "half-sine"\nomega_over_p = 2\n'
                    'edges = [9.99]\ntolerance = 1e-6\nsource = "made up"\n')
    report, _ = run_study(load_scene(path), tmp_path / "out")
    line = [row for row in report.read_text().splitlines() if row.startswith("| made up")][0]
    assert line.endswith("| **no** |")
    assert math.isfinite(float(line.split("|")[6]))
