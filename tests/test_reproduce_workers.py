"""``reproduce`` in two processes writes what it writes in one.

Scenes run in worker processes when there are many of them; the report is assembled
in the catalogue's order, so the files must not depend on where a scene ran. Checked
on a quick scene and one unknown name (its failure reported, the others kept).
"""

from __future__ import annotations

from shaketable.reproduce import reproduce

NAMES = ["fig-2-10", "no-such-scene"]


def _outputs(folder):
    return {path.relative_to(folder).as_posix(): path.read_bytes()
            for path in sorted(folder.rglob("*")) if path.is_file()
            and path.suffix in (".md", ".json", ".csv")}


def test_two_processes_write_the_same_report_as_one(tmp_path, monkeypatch):
    outputs, failed = {}, {}
    for workers in ("1", "2"):
        monkeypatch.setenv("SHAKETABLE_REPRODUCE_WORKERS", workers)
        failures: list = []
        reproduce(NAMES, out=tmp_path / workers, progress=False, failures=failures)
        outputs[workers] = _outputs(tmp_path / workers)
        failed[workers] = failures
    assert failed["1"] == failed["2"] == ["no-such-scene"]
    assert outputs["1"].keys() == outputs["2"].keys()
    assert "report.md" in outputs["1"] and "fig-2-10/section.md" in outputs["1"]
    for key in outputs["1"]:
        assert outputs["1"][key] == outputs["2"][key], key


def test_progress_bar_moves_by_expected_cost_and_counts_scenes(capsys, recwarn):
    # The scenes' expected CPU seconds are scenes.catalog.SCENE_CPU (measured); the longest
    # runs first, so a bar counting scenes would extrapolate the time left from it.
    from shaketable.reproduce import _ProgressBar
    from shaketable.scenes.catalog import SCENE_CPU

    bar = _ProgressBar(["table-4-3", "table-3-1", "no-such-scene"])
    # in hundredths of a second; 0.1 s: the floor (an unknown scene costs 0)
    total = round(100 * SCENE_CPU["table-4-3"]) + round(100 * SCENE_CPU["table-3-1"]) + 10
    assert bar.tqdm.total == total
    bar.done("table-4-3")
    assert bar.tqdm.n == round(100 * SCENE_CPU["table-4-3"])
    assert bar.tqdm.desc == "1/3 sections"
    bar.done("table-3-1")
    bar.done("no-such-scene")
    bar.close()
    assert bar.tqdm.n == total
    shown = capsys.readouterr().err.replace("\r", "\n").splitlines()[-1]
    assert shown.startswith("reproducing: 100%") and "3/3 sections" in shown
    assert not [w for w in recwarn if "clamping" in str(w.message)]   # tqdm's, past 100 %


def test_progress_bar_counts_a_repeated_scene_each_time(capsys):
    from shaketable.reproduce import _ProgressBar
    from shaketable.scenes.catalog import SCENE_CPU

    bar = _ProgressBar(["fig-3-7", "fig-3-7"])
    assert bar.tqdm.total == 2 * round(100 * SCENE_CPU["fig-3-7"])
    bar.done("fig-3-7")
    bar.done("fig-3-7")
    bar.close()
    assert bar.tqdm.n == bar.tqdm.total
    assert "100%" in capsys.readouterr().err.replace("\r", "\n").splitlines()[-1]
