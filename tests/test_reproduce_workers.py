"""``reproduce`` in two processes writes what it writes in one (issue 28).

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
