"""The reproduction report can be navigated, and its figures show what they are about:
a table of contents and the list of the comparisons that differ at the top, run lines that
say which block and starting angle they describe, an overlay figure that runs to the end of
its longest run, a sliding-only planar figure without flat rotation panels, and a package
docstring that starts with an example.
"""

from __future__ import annotations

import doctest
import json

import matplotlib
import pytest

import shaketable as st
from shaketable.ground import records

matplotlib.use("Agg")

SECTION_A = """## Fig. 9.9 — `aaa-scene`

| quantity | report | reproduced | unit | agrees |
|---|---|---|---|---|
| t overturn | 4 | 4.1 | s | yes |
| max theta/alpha | 0.5 | 0.8 | - | **no** |
<!-- differs: report inputs | max theta/alpha: the report gives 0.5, reproduced 0.8 -->
"""

SECTION_B = """## Table 9.9 — `bbb-scene`

| 4 x 1 ft | 0.9 | F / 0.3 |
<!-- differs: substitute | 4 x 1 ft, COR 0.9, A-1: the report gives F, reproduced 0.3 -->
"""


def test_report_has_contents_and_the_differing_comparisons_first(tmp_path):
    from shaketable.reproduce import _assemble

    for name, section, counts in (("aaa-scene", SECTION_A, {"report inputs": [1, 1]}),
                                  ("bbb-scene", SECTION_B, {"substitute": [0, 1]})):
        (tmp_path / name).mkdir()
        (tmp_path / name / "section.md").write_text(section)
        (tmp_path / name / "counts.json").write_text(json.dumps(counts))
    text = _assemble(tmp_path, rerun=["aaa-scene", "bbb-scene"]).read_text()
    differ = text.index("## The 1 comparison against the report's own inputs that differs")
    substitute = text.index("## The 1 comparison against SUBSTITUTE accelerograms")
    contents = text.index("## Contents")
    first_section = text.index("## Fig. 9.9")
    assert differ < substitute < contents < first_section
    assert ("- [`aaa-scene`](#aaa-scene): max theta/alpha: the report gives 0.5, reproduced "
            "0.8") in text
    assert ("- [`bbb-scene`](#bbb-scene): 4 x 1 ft, COR 0.9, A-1: the report gives F, "
            "reproduced 0.3") in text
    assert "- [Fig. 9.9 — `aaa-scene`](#aaa-scene) (1 differ)" in text
    assert '<a id="aaa-scene"></a>' in text and '<a id="bbb-scene"></a>' in text
    assert "<!-- differs" not in text       # the carriers are not left in the report


@pytest.mark.usefixtures("figure_drafts")
def test_a_scene_lists_what_differs_as_many_as_the_headline_counts(tmp_path):
    from shaketable.reproduce import reproduce

    # Fig. 4.2: the report's block stays (max 0.78 alpha); under the NGA-West2 re-processing
    # of its record it overturns: both comparisons differ, against the report's own inputs
    text = reproduce(["fig-4-2"], out=tmp_path, progress=False).read_text()
    # the headline's three lines: "... N agree, M differ.**"
    differ = sum(int(line.rsplit(", ", 1)[1].split(" differ")[0])
                 for line in text.splitlines() if line.startswith(("**Against", "**By")))
    listed = [line for line in text.splitlines() if line.startswith("- [`fig-4-2`]")]
    assert differ == len(listed) == 2
    assert "## The 2 comparisons against the report's own inputs that differ" in text
    assert "- [`fig-4-2`](#fig-4-2): max θ/α (±10 %): the report gives 0.78, reproduced F " \
        "(overturns)" in listed


def test_run_lines_name_the_block_and_the_starting_angle():
    from shaketable.reproduce import run_line

    block = st.Block.parse("30x6in")
    run = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=1.0)
    assert run_line(run).startswith("* 30 x 6 in block, from θ0 = 0.5 α, COR 0.925: ")
    still = st.simulate(block, records.load("pacoima-dam-s16e").scaled(0.05), cor=0.9,
                        duration=1.0)
    assert run_line(still).startswith("* 30 x 6 in block, from rest, COR 0.9: ")


def test_overlay_figure_runs_to_the_end_of_its_longest_run():
    import matplotlib.pyplot as plt

    # the teaching scene: 4 x 0.8 ft overturns, 12 x 2.4 ft survives (Section 2.4 (1))
    motion = records.load("pacoima-dam-s74w")
    small = st.simulate(st.Block.parse("4x0.8ft"), motion, cor=0.9, duration=10.0)
    large = st.simulate(st.Block.parse("12x2.4ft"), motion, cor=0.9, duration=10.0)
    assert small.overturned and not large.overturned
    # the figure runs past where the small block fell (4.28 s): the large block's
    # response after it (the record's strong part lasts to about 9 s) is on the axis
    from shaketable.plots.calcomp import calcomp

    figure = calcomp(small, others=[large])
    assert figure.axes[-1].get_xlim()[1] == pytest.approx(large.t[-1])
    assert large.t[-1] == pytest.approx(10.0) and large.t[-1] > 2 * small.t_overturn
    plt.close(figure)


def test_a_block_that_never_rocks_gets_no_flat_rotation_panels():
    import matplotlib.pyplot as plt

    # mu_s 0.2 < B/H 0.25: the block only slides (Section 2.1)
    motion = records.load("el-centro-chopra").scaled(1.5)
    run = st.simulate(st.Block.parse("2x0.5m"), motion, cor=0.9, friction=st.Friction(0.2),
                      duration=6.0)
    assert run.verdict() == "slid" and run.max_abs_theta == 0.0
    figure = run.plot()
    labels = [axis.get_ylabel() for axis in figure.axes]
    assert "θ [rad]" not in labels and "θ' [rad/s]" not in labels
    assert "slip velocity [mm/s]" in labels and "slip [mm]" in labels
    assert "never rocked" in figure._suptitle.get_text()
    plt.close(figure)


def test_help_starts_with_an_example_that_runs():
    lines = st.__doc__.splitlines()
    assert lines[2].startswith("Example") and lines[4].startswith(">>> import shaketable")
    result = doctest.testmod(st, verbose=False)
    assert result.attempted >= 5 and result.failed == 0
