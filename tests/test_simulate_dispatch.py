"""``shaketable simulate`` chooses its model once, from the options the user gave, and
each model's adapter names a model of the registry that takes what the adapter reads."""

from __future__ import annotations

import pytest

from shaketable.cli import build_parser
from shaketable.commands.simulate import SIMULATE_COMMANDS, chosen_command
from shaketable.commands.simulate_models import SimulateCommand
from shaketable.models.registry import MODELS


def _args(*options: str):
    return build_parser().parse_args(["simulate", *options])


@pytest.mark.parametrize(("options", "model"), [
    (("--block", "30x6in", "--cor", "0.9"), "rocking"),
    (("--block", "30x6in", "--cor", "0.9", "--friction", "0.3"), "planar"),
    (("--stack", "30x6in,30x6in"), "stack"),
    # both: the stack, whose adapter then refuses --friction (a one-block option)
    (("--stack", "30x6in,30x6in", "--friction", "0.3"), "stack"),
])
def test_the_options_choose_the_model(options, model):
    command, chosen = chosen_command(_args(*options))
    assert chosen is MODELS[model]
    assert command.model == model


def test_every_adapter_runs_a_model_of_the_registry_that_takes_its_subject():
    cases = {"rocking": ("--block", "30x6in", "--cor", "0.9", "--duration", "1s"),
             "planar": ("--block", "30x6in", "--cor", "0.9", "--friction", "0.3",
                        "--duration", "1s"),
             "stack": ("--stack", "30x6in,30x6in", "--duration", "1s")}
    assert sorted(command.model for command in SIMULATE_COMMANDS) == sorted(cases)
    for command in SIMULATE_COMMANDS:
        args = _args(*cases[command.model])
        setup = command.prepare(args)      # reads the inputs only: no run, no folder
        assert MODELS[command.model].accepts(setup.subject)


def test_a_new_adapter_is_chosen_by_its_own_option(monkeypatch):
    """Adding a model to the command is adding an adapter to the table: its option
    (here ``--mu``, the stack's) chooses it over the ones that select fewer options."""

    class TwoOptions(SimulateCommand):
        model = "sliding"
        selects = ("stack", "mu")

    import shaketable.commands.simulate as simulate

    monkeypatch.setattr(simulate, "SIMULATE_COMMANDS", (*SIMULATE_COMMANDS, TwoOptions()))
    command, model = simulate.chosen_command(_args("--stack", "30x6in,30x6in", "--mu", "0.5"))
    assert isinstance(command, TwoOptions) and model is MODELS["sliding"]
    command, model = simulate.chosen_command(_args("--stack", "30x6in,30x6in"))
    assert model is MODELS["stack"]
