"""The reproduction report's counting rules and its figures' numbers (report.md)."""

from __future__ import annotations

import pytest

from shaketable.reproduce import reproduce
from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import load_scene
from shaketable.scenes.run import run_scene
from shaketable.studies.comparison import COMPARISON_KINDS, ComparisonTally


def test_tally_counts_every_line_in_its_kind():
    tally = ComparisonTally()
    tally.add("report inputs", True)
    tally.add("report inputs", False)
    tally.add_many("substitute", 2, 5)
    tally.add("by construction", True, 2)
    assert tally.counts == {"report inputs": [1, 1], "substitute": [2, 3],
                            "by construction": [2, 0]}
    assert set(tally.counts) == set(COMPARISON_KINDS)
    with pytest.raises(ValueError, match="kind must be one of"):
        tally.add("recorded", True)


@pytest.mark.usefixtures("figure_drafts")
def test_headline_separates_the_three_kinds(tmp_path):
    # fig-4-15.toml states three report values (overturned, t_unstable, overturn_direction);
    # its realisation (seed 54) was chosen for the last two: they are by construction, the
    # first is a substitute comparison. fig-4-16.toml states one value on a recorded motion.
    path = reproduce(["fig-4-15", "fig-4-16"], out=tmp_path, progress=False)
    text = path.read_text()
    assert "Against the report's own inputs" in text and ": 1 comparisons agree, 0 differ" in text
    assert "Against SUBSTITUTE accelerograms" in text
    assert "not expected to match): 1 agree, 0 differ" in text
    assert "Fig. 4.15; not evidence): 2 agree, 0 differ" in text
    assert "yes (by construction)" in text
    assert "+0 / +0" not in text


def test_fig_4_5_gives_the_number_of_its_table_4_1_cell():
    # Table 4.1, 16 x 4 ft block, COR 1.0, Olive View column (substitute, seed 1 in
    # table-4-1.toml): Fig. 4.5 illustrates that cell, so both read the same realisation.
    from shaketable.studies.report_tables import reproduce_table

    table = load_scene(resolve_scene_path("table-4-1"))
    figure = load_scene(resolve_scene_path("fig-4-5"))
    assert figure.motion["seed"] == table.seed
    frame = reproduce_table("table_4_1", columns=["olive view"], seed=table.seed).to_frame()
    cell = frame[(frame["height [ft]"] == 16) & (frame["width [ft]"] == 4)
                 & (frame["cor [-]"] == 1.0)]["reproduced"].iloc[0]
    assert f"{run_scene(figure).main.max_theta_ratio:.2f}" == cell
