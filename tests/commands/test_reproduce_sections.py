"""``shaketable reproduce``: the report's sections beyond the scenes are named like scenes."""

from __future__ import annotations

from shaketable.cli import main
from shaketable.reproduce import EXTRA_SECTIONS


def test_list_names_the_sections_beyond_the_scenes(capsys):
    from shaketable.scenes.catalog import scene_names

    assert main(["reproduce", "--list"]) == 0
    listed = capsys.readouterr().out.split()
    # every scene, then every extra section: the names `reproduce NAME` accepts
    assert listed == scene_names() + list(EXTRA_SECTIONS)
    assert "validation" in listed


def test_the_validation_section_runs_alone_and_quiet_keeps_the_closing_line(
        tmp_path, capsys, monkeypatch):
    monkeypatch.delenv("SHAKETABLE_PBR", raising=False)
    out = tmp_path / "rv"
    assert main(["reproduce", "validation", "--validation-data", str(tmp_path / "absent"),
                 "--out", str(out), "-q"]) == 0
    printed = capsys.readouterr()
    # -q: no progress and no summary, but the file written is said
    assert printed.out.splitlines() == [f"wrote {out / 'report.md'} (and gallery.md beside it)"]
    assert printed.err == ""
    report = (out / "report.md").read_text()
    assert "1 section: 0 rerun now, 1 skipped (validation" in report
    section = (out / "validation" / "section.md").read_text()
    assert "Skipped: no folder of measured tests at" in section
    assert "--validation-data DIR" in section and "SHAKETABLE_PBR" in section


def test_validation_data_without_its_section_is_refused(tmp_path, capsys):
    assert main(["reproduce", "fig-2-3", "--validation-data", str(tmp_path),
                 "--out", str(tmp_path / "o")]) == 2
    assert "--validation-data is the folder of the 'validation' section" in (
        capsys.readouterr().err)
    assert not (tmp_path / "o").exists()


def test_the_progress_bar_counts_the_report_sections(tmp_path, capsys, monkeypatch):
    # the bar's count and the report's headline count the same sections (the scenes
    # and the extra sections)
    from shaketable.reproduce import reproduce

    monkeypatch.delenv("SHAKETABLE_PBR", raising=False)
    report = reproduce([], out=tmp_path / "out", progress=True,
                       extra={"validation": {"data": tmp_path / "absent"}})
    shown = capsys.readouterr().err.replace("\r", "\n").strip().splitlines()[-1]
    assert "1/1 sections" in shown, shown
    assert "1 section: 0 rerun now, 1 skipped" in report.read_text()


def test_a_run_without_comparisons_prints_no_empty_tallies(tmp_path, capsys, monkeypatch):
    monkeypatch.delenv("SHAKETABLE_PBR", raising=False)
    out = tmp_path / "rv"
    assert main(["reproduce", "validation", "--validation-data", str(tmp_path / "absent"),
                 "--out", str(out)]) == 0
    # the validation section compares nothing with the report: no "0 agree, 0 differ" lines,
    # one line saying so, the same as the report's headline
    nothing = "These sections compare no value with the report's"
    printed = capsys.readouterr().out.splitlines()
    assert len(printed) == 2 and printed[0].startswith(nothing), printed
    assert printed[1] == f"wrote {out / 'report.md'} (and gallery.md beside it)"
    assert f"**{printed[0]}**" in (out / "report.md").read_text()
    assert "0 agree" not in (out / "report.md").read_text()
