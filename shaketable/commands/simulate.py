"""``shaketable simulate``: one block (or a column of blocks), one motion (or free rocking).

The command chooses the model once (:func:`chosen_command`) and hands the run, its
answer, its files and its ensemble to the model's adapter
(:mod:`shaketable.commands.simulate_models`); what every model shares (the output
folder, the order of the files and of the lines, the early-stop warning) is here."""

from __future__ import annotations

import argparse
import json
import sys

from shaketable.commands.calibrate import cor_argument
from shaketable.commands.common import add_record_arguments, notice_first_compile
from shaketable.commands.options import (
    add_mass_options,
    add_motion_options,
    add_quantity,
    friction_argument,
)
from shaketable.commands.simulate_models import (
    PlanarCommand,
    RockingCommand,
    SimulateCommand,
    resolve_angle,
)
from shaketable.commands.stack import StackCommand
from shaketable.models.base import Model
from shaketable.models.registry import MODELS, model_named
from shaketable.models.rocking.layout import METHODS

__all__ = ["SIMULATE_COMMANDS", "chosen_command", "register", "resolve_angle"]


#: The adapter of each model ``simulate`` runs (:mod:`shaketable.commands.simulate_models`);
#: the one whose options (``selects``) the user gave, the most of them, runs; the first
#: on a tie (``--stack`` with ``--friction``: the stack, which refuses ``--friction``).
SIMULATE_COMMANDS: tuple[SimulateCommand, ...] = (StackCommand(), PlanarCommand(),
                                                  RockingCommand())


def chosen_command(args) -> tuple[SimulateCommand, Model]:
    """The adapter for the user's options and its model of :data:`shaketable.models.registry.MODELS`:
    ``--stack`` the stack model, ``--friction`` the planar model, else the rocking model."""
    chosen, most = SIMULATE_COMMANDS[-1], -1
    for command in SIMULATE_COMMANDS:
        if len(command.selects) > most and all(getattr(args, name, None) is not None
                                               for name in command.selects):
            chosen, most = command, len(command.selects)
    return chosen, MODELS[chosen.model]


def _simulate(args) -> int:
    from shaketable.commands.checks import report_early_stops
    from shaketable.core.files import (
        json_ready_dict,
        prepare_output_folder,
        write_csv,
        write_parquet,
        write_text,
    )
    from shaketable.plots import base as plots

    command, model = chosen_command(args)
    if args.parquet and (args.history == "none" or getattr(args, "ensemble", 0)
                         or isinstance(args.cor, str)):
        raise ValueError("--parquet writes the history table (history.csv) as Parquet too: "
                         "it cannot be used with --history none, --ensemble or a calibrated "
                         "--cor (no history is written)")
    setup = command.prepare(args)              # every input checked before the output folder
    model_named(model.name, setup.subject)
    out = prepare_output_folder(args.out)      # before the run: a bad path loses no work
    notice_first_compile(args.quiet, which=command.compiles(args))
    status = command.ensemble(args, setup, out)
    if status is not None:
        if setup.note:
            print(setup.note)
        return status
    result, warnings = command.run(model, setup)
    history = command.history(args, result)   # --history
    written = []
    if history != "none":
        frame = command.history_frame(result, history)
        written.append(write_csv(out / "history.csv", frame))
        if args.parquet:   # the same table
            written.append(write_parquet(out / "history.parquet", frame))
    events = command.events_frame(result)
    if events is not None:
        written.append(write_csv(out / "events.csv", events))
    written.append(write_text(out / "summary.json", json.dumps(
        json_ready_dict(command.summary(setup, result, warnings)), indent=2)))
    written.append(out / f"calcomp.{args.format}")
    plots.save(command.figure(result), written[-1])
    # the answer first, in the subject's units; then the files
    print(command.heading(args, setup, result))
    if getattr(args, "floor", None) is not None and setup.motion is not None:
        print(f"  motion: {setup.motion.name}")   # the record and the floor it reached
    for line in command.answer(setup, result):
        print("  " + line)
    if setup.note:
        print(setup.note)
    if args.history == "auto" and history != "full":
        print(f"history.csv: {history} ({result.t.size} samples; --history full writes all)")
    if warnings:   # a stack: those after the column began to fall, as one note line
        from shaketable.scenes.stack import fall_note

        note, warnings = fall_note(warnings)
        if note:
            print(note)   # on the answer's stream: --quiet silences it
    for line in warnings:
        print(f"shaketable simulate: warning: {line}", file=sys.stderr)
    print("wrote " + ", ".join(str(path) for path in written))
    return report_early_stops([result], "simulate", setup.label)


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``simulate`` subcommand to an argparse subparsers object."""
    sim = commands.add_parser(
        "simulate", help="one block (or a --stack of blocks), one motion (or free rocking): "
                         "CSV, JSON and Calcomp figure",
        description="Simulate one block under a record (--record), a harmonic motion "
                    "(--harmonic 2Hz,0.5g) or a pulse (--pulse half-sine,0.5g,0.2s). Without "
                    "any, the block rocks freely from --theta0.")
    sim.add_argument("--block",
                     help="HEIGHTxWIDTH with unit, height first, e.g. 30x6in or 16x4ft")
    sim.add_argument("--cor", type=cor_argument,
                     help="coefficient of restitution [0-1], or a calibration.json of "
                          "`shaketable calibrate` (an ensemble over the calibrated COR); "
                          "needed for --block; with --stack optional (the constant-COR law; "
                          "without it the plastic multi-contact law)")
    stack = sim.add_argument_group(
        "stack", "a column of blocks instead of --block (the stack model: no sliding, no "
        "flight; docs/stack.md)")
    stack.add_argument("--stack", metavar="SIZE,SIZE[,...]",
                       help="the blocks from the bottom up, each HEIGHTxWIDTH with unit, e.g. "
                            "30x6in,30x6in; each centred on the one below, none wider than it")
    add_mass_options(stack)
    stack.add_argument("--mu", type=friction_argument,
                       help="the friction coefficient the contacts offer [-], 0 to 1.5: said "
                            "beside the friction they need (F/N) and when it would be "
                            "exceeded")
    sim.add_argument("--theta0", default="0rad",
                     help="initial tilt with unit: 0.05rad, 3deg or 0.5alpha (default 0rad); "
                          "with --stack one value (every block's) or one per block, bottom "
                          "first, alpha being each block's own")
    add_record_arguments(sim)
    add_motion_options(sim)
    add_quantity(sim, "--duration", kind="time", example="8s", positive=True,
                 help="length of the run")
    sim.add_argument("--floor", type=int, metavar="K",
                     help="the block stands on floor K of --building (0: the ground): the "
                          "motion is the ground's, filtered by the building's first mode")
    sim.add_argument("--building", metavar="PERIOD,HEIGHT,STOREYS",
                     help="a regular building for --floor, e.g. 0.6s,17.5m,5 (first mode "
                          "linear in height, 5 %% damping; shaketable.ground.floor)")
    sim.add_argument("--friction", metavar="MU_S[,MU_D]",
                     help="Coulomb friction between block and table (dimensionless): runs the "
                          "planar block, which may rest, slide, rock, slide-rock and fly "
                          "(docs/planar.md); without it the block rocks on a base that cannot "
                          "slide, as in the report")
    sim.add_argument("--method", default="fast",
                     choices=list(METHODS))
    sim.add_argument("--subdivisions", type=int, default=4,
                     help="steps per sample for predictor-corrector")
    ens = sim.add_argument_group(
        "ensemble", "how predictable the verdict is: perturbed copies of the run "
        "(shaketable.studies.predictability)")
    ens.add_argument("--ensemble", type=int, default=0, metavar="N",
                     help="run N perturbed copies (member 0 nominal) and report P(overturn)")
    ens.add_argument("--perturb", type=float, default=1e-9,
                     help="relative spread of every input (amplitude, COR, size, start) "
                          "[-] (default 1e-9)")
    for name in ("amplitude", "cor", "size", "start"):
        ens.add_argument(f"--perturb-{name}", type=float,
                         help=f"relative spread of the {name} [-] (default --perturb)")
    ens.add_argument("--seed", type=int, default=0, help="seed of the draws")
    ens.add_argument("--horizon-threshold", type=float, default=1e-3,
                     help="horizon: |d theta| above this many alpha (default 1e-3)")
    sim.add_argument("--format", default="png", choices=["png", "svg", "pdf"])
    sim.add_argument("--out", default="shaketable-out", help="output folder")
    sim.add_argument("--history", choices=("auto", "full", "peaks", "none"), default="auto",
                     help="what history.csv holds: every sample (full), the first and last "
                          "samples, impacts and turning points (peaks; with --stack also "
                          "every change of contact pattern), or no file (none); "
                          "default auto: full up to 1,000,000 samples, peaks beyond")
    sim.add_argument("--parquet", action="store_true",
                     help="also write the history table as history.parquet (needs pyarrow)")
    sim.set_defaults(handler=_simulate)
