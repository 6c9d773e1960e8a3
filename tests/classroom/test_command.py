"""``shaketable classroom`` without starting a server: its options and a missing Panel."""

from __future__ import annotations

import importlib.util

import pytest

from shaketable.cli import main


def test_without_panel_the_command_says_which_extra_to_install(monkeypatch, capsys):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *args: None if name == "panel" else real(name, *args))
    # a set-up error: exit status 2 (shaketable --help), said as an error, with the install
    # line for the package and for a checkout (the README's pip install ".[classroom]")
    assert main(["classroom", "--no-browser"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("shaketable classroom: error: the classroom page needs Panel"), err
    assert "pip install 'shaketable[classroom]'" in err and "pip install '.[classroom]'" in err
    assert err.count("\n") == 1, err


@pytest.mark.skipif(importlib.util.find_spec("panel") is None,
                    reason="without Panel the command stops before reading --port (above)")
def test_a_port_out_of_range_is_bad_input(capsys):
    assert main(["classroom", "--no-browser", "--port", "70000"]) == 2
    assert "--port must be from 0 to 65535" in capsys.readouterr().err
