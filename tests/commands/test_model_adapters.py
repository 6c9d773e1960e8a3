"""``animate`` and ``spectrum`` hand a subject given on the command line to its model's
adapter (the one ``simulate`` uses), not to a branch of their own."""

from __future__ import annotations

import pytest

from shaketable.cli import main
from shaketable.commands.simulate_models import RockingCommand, SimulateCommand
from shaketable.commands.stack import StackCommand


@pytest.mark.parametrize("command, argv", [
    (StackCommand, ["spectrum", "--stack", "8x2ft,8x2ft"]),
    (RockingCommand, ["spectrum", "--block", "16x4ft"]),
    (StackCommand, ["animate", "--stack", "30x6in,30x6in", "--duration", "1s"]),
    (RockingCommand, ["animate", "--block", "30x6in", "--cor", "0.9", "--duration", "1s"]),
])
def test_the_command_dispatches_on_the_model(command, argv, monkeypatch, tmp_path):
    called = []
    hook = argv[0]

    def recorded(self, args, *rest):
        called.append((type(self).__name__, args.out))
        return 0

    monkeypatch.setattr(command, hook, recorded)
    assert main([*argv, "--out", str(tmp_path / ("a.gif" if hook == "animate" else "o"))]) == 0
    assert [name for name, _ in called] == [command.__name__]


def test_a_model_without_the_command_says_so():
    with pytest.raises(ValueError, match="spectrum does not offer the planar model"):
        type("Planar", (SimulateCommand,), {"model": "planar"})().spectrum(None)
    with pytest.raises(ValueError, match="animate does not draw the planar model"):
        type("Planar", (SimulateCommand,), {"model": "planar"})().animate(None, (1, 1), None)
