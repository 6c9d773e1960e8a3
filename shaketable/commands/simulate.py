"""``shaketable simulate``: one block, one motion (or free rocking)."""

from __future__ import annotations

import argparse
import dataclasses
import json
import math

from shaketable.commands.calibrate import cor_argument
from shaketable.commands.common import (
    add_record_arguments,
    load_motion,
    notice_first_compile,
    scaled_record,
)
from shaketable.commands.options import (
    add_motion_options,
    add_quantity,
    block_option,
    motion_from_options,
)
from shaketable.core.geometry import Block
from shaketable.models.rocking.layout import METHODS


def resolve_angle(text: str, block: Block) -> float:
    value = str(text).strip().lower()
    for suffix, factor in (("alpha", block.alpha), ("deg", math.pi / 180), ("rad", 1.0)):
        if value.endswith(suffix):
            try:
                return float(value[: -len(suffix)]) * factor
            except ValueError:
                break
    raise ValueError(f"--theta0 {text!r}: give a number with a unit, e.g. 0.05rad, 3deg or 0.5alpha")


def _on_floor(args, motion):
    """``--floor K --building PERIOD,HEIGHT,STOREYS``: the motion at floor K of the building."""
    if args.floor is None and args.building is None:
        return motion
    if args.floor is None or args.building is None:
        raise ValueError("--floor and --building go together (e.g. --floor 3 --building "
                         "0.6s,17.5m,5)")
    if motion is None:
        raise ValueError("--floor needs a ground motion (--record, --harmonic or --pulse)")
    from shaketable.core.units import parse
    from shaketable.ground.floor import Building, floor_motion

    parts = [part.strip() for part in args.building.split(",")]
    if len(parts) != 3 or not parts[2].isdigit():
        raise ValueError(f"--building {args.building!r}: give PERIOD,HEIGHT,STOREYS with the "
                         f"units, e.g. 0.6s,17.5m,5")
    where = f"--building {args.building!r}"
    building = Building(parse(parts[0], "time", where=where),
                        parse(parts[1], "length", where=where), int(parts[2]))
    if not 0 <= args.floor <= building.storeys:
        raise ValueError(f"--floor {args.floor}: the building has floors 0 (the ground) to "
                         f"{building.storeys} (the roof)")
    return floor_motion(motion, building, floor=args.floor)


def _simulate(args) -> int:
    from shaketable.commands.checks import check_simulate_options, report_early_stops
    from shaketable.core.files import json_ready_dict, prepare_output_folder, write_csv, write_text
    from shaketable.models.api import simulate
    from shaketable.models.stops import stop_summary
    from shaketable.plots import base as plots

    if args.stack is not None:   # a column of blocks: the stack model (commands/stack.py)
        from shaketable.commands.stack import simulate_stack_command

        return simulate_stack_command(args, _on_floor)
    from shaketable.commands.stack import refuse_stack_options

    refuse_stack_options(args)
    if args.block is None or args.cor is None:
        raise ValueError("give --block and --cor (one block), or --stack (a column of blocks, "
                         "e.g. --stack 30x6in,30x6in)")
    check_simulate_options(args)   # options the chosen model would ignore: refused
    block = block_option(args.block)
    motion = motion_from_options(args) or (load_motion(args) if args.record else None)
    motion, scale_note = scaled_record(motion, args)
    motion = _on_floor(args, motion)
    theta0 = resolve_angle(args.theta0, block)
    friction = _friction(args.friction)      # every input checked before the output folder
    if not isinstance(args.cor, str):
        from shaketable.core.validation import in_range

        in_range("--cor", args.cor, 0.0, 1.0)
    out = prepare_output_folder(args.out)  # before the run: a bad path loses no work
    notice_first_compile(args.quiet, which=("planar",) if args.friction is not None else
                         ("engine", "batch") if args.ensemble else ("engine",))
    if isinstance(args.cor, str):           # a calibration.json: the calibrated COR's spread
        from shaketable.commands.calibrate import simulate_calibrated

        status = simulate_calibrated(args, block, motion, theta0, out)
        if scale_note:
            print(scale_note)
        return status
    if friction is not None and args.ensemble:   # the planar model's ensemble
        from shaketable.commands.friction_ensemble import friction_ensemble

        status = friction_ensemble(args, block, motion, friction, out)
        if scale_note:
            print(scale_note)
        return status
    if args.ensemble:
        status = _ensemble(args, block, motion, out)
        if scale_note:
            print(scale_note)
        return status
    if friction is not None:   # the planar block (rest, slide, rock, slide-rock, flight)
        result = simulate(block, motion, cor=args.cor, theta0=theta0, duration=args.duration,
                          friction=friction)
    else:
        result = simulate(block, motion, cor=args.cor, theta0=theta0, duration=args.duration,
                          method=args.method, subdivisions=args.subdivisions)
    from shaketable.commands.history import for_figure, history_frame, history_mode

    history = history_mode(args.history, result.t.size)   # --history
    if friction is not None and history == "peaks":
        history = "full"   # the planar block's history has no peaks selection: all of it
    if history != "none":
        write_csv(out / "history.csv", history_frame(result, history))
    write_text(out / "summary.json", json.dumps(json_ready_dict(stop_summary(result)), indent=2))
    plots.save((result if friction is not None else for_figure(result)).plot(),
               out / f"calcomp.{args.format}")
    from shaketable.commands.answers import planar_answer, rocking_answer

    # the answer first, in the block's units; then the files
    print(f"{block.describe()} block, COR {args.cor}: {result.verdict()}")
    for line in (planar_answer(result) if friction is not None else rocking_answer(result)):
        print("  " + line)
    if scale_note:
        print(scale_note)
    if args.history == "auto" and history != "full":
        print(f"history.csv: {history} ({result.t.size} samples; --history full writes all)")
    written = ([out / "history.csv"] if history != "none" else []) + [
        out / "summary.json", out / f"calcomp.{args.format}"]
    print("wrote " + ", ".join(str(path) for path in written))
    return report_early_stops([result], "simulate", f"{block.describe()} block")


def _friction(text: str | None):
    """``--friction MU_S[,MU_D]``: a :class:`~shaketable.models.sliding.result.Friction` or None."""
    if text is None:
        return None
    from shaketable.models.sliding.result import Friction

    parts = text.split(",")
    try:
        values = [float(part) for part in parts]
    except ValueError:
        raise ValueError(f"--friction: {text!r} is not MU_S or MU_S,MU_D (numbers, e.g. 0.3 "
                         "or 0.3,0.25)") from None
    if len(values) not in (1, 2):
        raise ValueError(f"--friction: {text!r} is not MU_S or MU_S,MU_D")
    try:
        return Friction(*values)
    except ValueError as error:
        raise ValueError(f"--friction: {error}") from None


def _ensemble(args, block, motion, out) -> int:
    from shaketable.commands.friction_ensemble import ensemble_perturbation, perturbation_line
    from shaketable.plots import base as plots
    from shaketable.studies.predictability import ensemble

    perturbation = ensemble_perturbation(args, motion)
    result = ensemble(block, motion, cor=args.cor, members=args.ensemble,
                      perturbation=perturbation, seed=args.seed, duration=args.duration,
                      method=args.method, threshold=args.horizon_threshold)
    from shaketable.core.files import json_ready_dict, write_csv, write_text

    write_csv(out / "ensemble.csv", result.to_frame())
    summary = json_ready_dict(result.summary)
    summary["perturbation [-]"] = dataclasses.asdict(perturbation)
    write_text(out / "ensemble.json", json.dumps(summary, indent=2, default=float))
    plots.save(result.plot().figure, out / f"ensemble.{args.format}")
    print(f"{block.describe()} block, COR {args.cor}, {args.ensemble} members: "
          f"{result.describe()}")
    print(perturbation_line(perturbation))
    print(f"wrote {out / 'ensemble.csv'}, {out / 'ensemble.json'}, "
          f"{out / ('ensemble.' + args.format)}")
    from shaketable.commands.checks import report_stopped_rows

    return report_stopped_rows(result.to_frame(), f"{block.describe()} block", "simulate")


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
    stack.add_argument("--masses", metavar="MASS,MASS[,...]",
                       help="each block's mass with its unit, bottom first (e.g. 400kg,200kg); "
                            "default: one density, masses in proportion to the areas")
    stack.add_argument("--densities", metavar="DENSITY,...",
                       help="each block's density with its unit, bottom first (e.g. "
                            "2400kg/m3,7800kg/m3; equal depths)")
    stack.add_argument("--mu", type=float,
                       help="the friction coefficient the contacts offer [-]: said beside the "
                            "friction they need (F/N) and when it would be exceeded")
    sim.add_argument("--theta0", default="0rad",
                     help="initial tilt with unit: 0.05rad, 3deg or 0.5alpha (default 0rad); "
                          "with --stack one value (every block's) or one per block, bottom "
                          "first, alpha being each block's own")
    add_record_arguments(sim)
    add_motion_options(sim)
    add_quantity(sim, "--duration", kind="time", example="8s", help="length of the run")
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
                          "samples, impacts and turning points (peaks), or no file (none); "
                          "default auto: full up to 1,000,000 samples, peaks beyond")
    sim.set_defaults(handler=_simulate)
