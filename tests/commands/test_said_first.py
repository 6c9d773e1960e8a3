"""The helpful part of a message comes first: a sweep refused for a folder that already
holds one says so before anything else; a run whose sections compared no values of a kind
prints no empty tally for it (tests/test_cli.py); ``classroom --help`` gives the install
line that works from a checkout too."""

from __future__ import annotations

import json

import pytest

from shaketable.cli import main


def test_a_folder_that_holds_a_sweep_is_refused_first(tmp_path, capsys):
    out = tmp_path / "fragility"
    out.mkdir()
    (out / "manifest.json").write_text(json.dumps({"sweep": "im-fragility-collapse"}))
    assert main(["sweep", "im-fragility-collapse", "--out", str(out)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("shaketable sweep: error: ") and "already holds a sweep" in err[0]
    assert sorted(path.name for path in out.iterdir()) == ["manifest.json"]


def test_classroom_help_gives_the_install_line_of_a_checkout(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["classroom", "--help"])
    assert stop.value.code == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "pip install 'shaketable[classroom]'" in text and "pip install '.[classroom]'" in text
