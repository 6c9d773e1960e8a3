"""Every bundled scene runs with ``shaketable run NAME``: studies included.

The audit found `run` crashing on every ``[study]`` scene; this runs the command
on each bundled name, in-process, and fails on any traceback or non-zero exit. The scenes
the README runs as ``shaketable run NAME`` are checked the same way, on that run, by
``tests/test_readme.py``, and ``spectrum-one-sine`` by ``tests/scenes/test_spectrum_scene.py``
(each scene runs once in the suite).

The report-table scenes (``table-4-1``, ``table-4-3``) end with an ensemble per cell
(:func:`shaketable.studies.predictability.predictability_markdown`, 200 members by default:
9,600 batch runs, 7-9 s of CPU each scene). Here they run with :data:`MEMBERS` members, the
same code path (one batch call whatever the size) at a tenth of the cost: this test checks
that the command runs and writes its report, not the ensemble's statistics (``reproduce
--all`` writes them with 200; ``tests/studies/test_predictability.py`` checks the
ensembles). In the same way the report-figure scenes (Figs. 2.3, 2.4, 2.6, Section 4.3 (4)),
the pitch study and the mode map run on smaller grids (:func:`_smaller_studies`: the same
code, fewer points; tests/studies checks their values). Its PNG figures are drafts
(:func:`tests.helpers.draft_figures`: every figure built and drawn, at a low dpi without
the layout solver): tests/plots checks how they look.
"""

from __future__ import annotations

import pytest

from shaketable.scenes.catalog import scene_names, sweep_names
from tests.helpers import TEST_MEMBERS, draft_figures
from tests.scenes.test_spectrum_scene import SCENE as SPECTRUM_SCENE
from tests.test_bad_input import run_cli
from tests.test_readme import README_RUN_SCENES

#: Bundled scenes that another test runs with ``shaketable run NAME`` and checks as below,
#: on that run (tests/scenes/test_spectrum_scene.py, with the published band edges).
CHECKED_ELSEWHERE = [SPECTRUM_SCENE.stem]


def test_the_readme_runs_bundled_scenes():
    # the scenes left out below are bundled ones, so test_readme.py checks them
    assert README_RUN_SCENES and set(README_RUN_SCENES) <= set(scene_names())
    assert set(CHECKED_ELSEWHERE) <= set(scene_names())


#: Members of each cell's ensemble in the report-table scenes here (the package's default
#: is 200; see the module docstring).
MEMBERS = TEST_MEMBERS

#: The points of the report-figure scenes' curves here (``[study] kind = "report-figure"``:
#: one engine run, or one bisection, per point), fewer than the package's: the smallest
#: and largest of its own, so each curve still spans its range; the values are checked at
#: points of their own by ``tests/studies/test_section_2.py`` and
#: ``tests/studies/test_overturning_spectrum.py``. Section 4.3 (4) keeps its 0.1 s pulse
#: (the report's 4.6 g, which the scene compares) and its shortest.
REPORT_FIGURE_POINTS = {
    ("section2", "figure_2_3"): dict(ratios=[0.05, 0.95]),   # package: 19 amplitudes x 4 blocks
    ("section2", "figure_2_4"): dict(ratios=[1.1, 4.0]),     # package: 6 accelerations
    ("section2", "figure_2_6"): dict(frequency_ratios=[1.0, 18.0]),   # package: 6 pulses
    ("pulses", "section_4_3_4"): dict(pulse_durations=(0.1, 0.01)),   # package: 4 pulses
}

#: Pitch phases of ``section-3-7-pitch`` here (the scene asks for 24): an even number, so
#: that runs half a pitch cycle apart, which the scene compares, still exist.
PITCH_PHASES = 4


def _smaller_studies(monkeypatch):
    """The report-figure curves at :data:`REPORT_FIGURE_POINTS`, the pitch study at
    :data:`PITCH_PHASES`, the mode map on every third B/H and every fifth mu of its grid
    (both ends kept: 3 x 4 blocks per PGA level, against 7 x 16), the stacks study under
    the first and last of its five records."""
    import functools
    import importlib

    from shaketable.scenes import studies as scene_studies
    from shaketable.studies import mode_map, stacks

    for (module, function), points in REPORT_FIGURE_POINTS.items():
        studies = importlib.import_module(f"shaketable.studies.{module}")
        monkeypatch.setattr(studies, function,
                            functools.partial(getattr(studies, function), **points))
    cases = scene_studies.section_3_7_cases
    monkeypatch.setattr(scene_studies, "section_3_7_cases",
                        lambda phases: cases(phases=min(phases, PITCH_PHASES)))
    whole_map = mode_map.mode_map

    def thinned_map(motion=None, *, aspect_ratios, frictions, **options):
        return whole_map(motion, aspect_ratios=aspect_ratios[::3], frictions=frictions[::5],
                         **options)

    monkeypatch.setattr(mode_map, "mode_map", thinned_map)
    whole_stacks = stacks.stacks_study

    def fewer_records(block, records, *args, **options):
        # the first and last of the scene's records (package: 5): every height still runs
        # under a named record and a substitute, through the same table, text and figure
        kept = dict([list(records.items())[0], list(records.items())[-1]])
        return whole_stacks(block, kept, *args, **options)

    monkeypatch.setattr(stacks, "stacks_study", fewer_records)


@pytest.mark.slow
@pytest.mark.parametrize("name", [name for name in scene_names()
                                  if name not in README_RUN_SCENES + CHECKED_ELSEWHERE])
def test_run_succeeds_on_every_bundled_scene(name, tmp_path, monkeypatch):
    import functools

    from shaketable.studies import predictability

    monkeypatch.setattr(predictability, "predictability_markdown", functools.partial(
        predictability.predictability_markdown, members=MEMBERS))
    _smaller_studies(monkeypatch)
    with draft_figures():
        status, out, err = run_cli(["run", name, "--out", tmp_path / name], cwd=tmp_path)
    assert "Traceback" not in err and "internal error" not in err, err
    assert status == 0, err
    assert "wrote" in out
    assert any((tmp_path / name).iterdir())
    if name in ("table-4-1", "table-4-3"):   # the ensembles ran, at MEMBERS copies per cell
        assert f"({MEMBERS} copies per cell" in (tmp_path / name / "report.md").read_text()


@pytest.mark.parametrize("name", sweep_names())
def test_run_on_a_sweep_spec_says_to_use_sweep(name, tmp_path):
    status, _, err = run_cli(["run", name], cwd=tmp_path)
    assert status == 2 and f"shaketable sweep {name}" in err


def test_sweep_accepts_a_bundled_name(tmp_path):
    status, out, err = run_cli(["sweep", "artificial-fragility", "--max-chunks", "0",
                                "--no-progress", "--out", tmp_path / "sweep"], cwd=tmp_path)
    assert status == 0, err
    assert "artificial-fragility" in out and "--resume" in out


@pytest.mark.usefixtures("figure_drafts")
def test_a_bundled_name_wins_over_a_folder_of_that_name(tmp_path):
    """The README's commands in one folder: `simulate --out fig-3-4` leaves a folder named
    fig-3-4, and `reproduce fig-3-4` must still mean the bundled scene (a newcomer trial
    found it read as "is a folder")."""
    (tmp_path / "fig-2-10").mkdir()
    status, _, err = run_cli(["run", "fig-2-10", "--out", tmp_path / "out"], cwd=tmp_path)
    assert status == 0, err
    status, _, err = run_cli(["reproduce", "fig-2-10", "--out", tmp_path / "rep"], cwd=tmp_path)
    assert status == 0, err
