"""``spectrum`` says where a band meets the scan's ceiling, and its CSV where each
omega/p's scan stopped."""

from __future__ import annotations

import math
import re

import pytest

from shaketable.cli import main


@pytest.mark.usefixtures("figure_drafts")
def test_a_band_up_to_the_ceiling_says_so(tmp_path, capsys):
    out = tmp_path / "spectrum"
    assert main(["spectrum", "--block", "16x4ft", "--pulse", "half-sine", "--ratios", "1,2",
                 "--scan-step", "0.05", "--out", str(out)]) == 0
    lines = [line for line in capsys.readouterr().out.splitlines() if "ω/p = " in line]
    assert len(lines) == 2, lines   # one band line per ratio
    # the default ceiling of a/(g tan alpha) is 2 sqrt(1 + (ω/p)^2) + 2, past Eq. 2-8's
    # threshold (the docstring of overturning_spectrum): 4.828 at 1, 6.472 at 2
    for line, ratio in zip(lines, (1, 2)):
        ceiling = 2 * math.sqrt(1 + ratio**2) + 2
        said = re.fullmatch(r"\s+half-sine at ω/p = \d: overturns without impact for "
                            r"a/\(g tan α\) from (\d\.\d{3}) to (\d\.\d{3}) \(the ceiling\)", line)
        assert said, line           # four significant figures, and the ceiling named
        assert float(said[2]) == pytest.approx(ceiling, abs=5e-4)
    header = (out / "spectrum.csv").read_text().splitlines()[0]
    assert "ceiling 4.82843 at omega/p = 1, 6.47214 at 2;" in header


def test_a_flag_is_explained_once_in_the_csv(tmp_path):
    from shaketable.core.constants import G
    from shaketable.core.geometry import Block
    from shaketable.studies.overturning_spectrum import overturning_spectrum

    # the one-sine safe window at omega/p = 4 (5.00928-5.32302, Zhang & Makris 2001, for
    # p^2 = 3g/16, alpha = 0.25) scanned with a 20 % step: flagged as narrower than the scan
    block = Block.from_slenderness(3 * G / 16, 0.25)
    coarse = overturning_spectrum(block, ["one-sine"], [4], scan_step=0.2)
    path = tmp_path / "coarse.csv"
    coarse.to_csv(path)
    text = path.read_text()
    assert text.count("narrower than the scan step") == 1      # in the band's note only
    assert "# flag: one-sine omega/p=4: safe band 5.00928" in text
