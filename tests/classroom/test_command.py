"""``shaketable classroom`` without starting a server: its options and a missing Panel."""

from __future__ import annotations

import importlib.util

import pytest

from shaketable.cli import main


def test_without_panel_the_command_says_which_extra_to_install(monkeypatch, capsys):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *args: None if name == "panel" else real(name, *args))
    assert main(["classroom", "--no-browser"]) == 1
    assert "pip install 'shaketable[classroom]'" in capsys.readouterr().err


@pytest.mark.skipif(importlib.util.find_spec("panel") is None,
                    reason="without Panel the command stops before reading --port (above)")
def test_a_port_out_of_range_is_bad_input(capsys):
    assert main(["classroom", "--no-browser", "--port", "70000"]) == 2
    assert "--port must be from 0 to 65535" in capsys.readouterr().err
