"""What ``shaketable simulate`` does per model: one adapter per model of :mod:`shaketable.models`.

``simulate`` chooses the model once (:func:`shaketable.commands.simulate.chosen_command`)
and hands the rest to the model's adapter, a :class:`SimulateCommand`:

* :meth:`~SimulateCommand.prepare`: every input read and checked (before the output
  folder is made): the subject (a block, a column of blocks), the motion and the run's
  options, as a :class:`Setup` (a one-block model: :func:`one_block_setup`, with the
  adapter's :meth:`~SimulateCommand.refuse` of the options its model does not take and
  its :meth:`~SimulateCommand.run_options`);
* :meth:`~SimulateCommand.ensemble`: the model's ensemble (``--ensemble``, a calibrated
  COR), or None for one run;
* :meth:`~SimulateCommand.run`: the one run, and the warnings it gave as text;
* :meth:`~SimulateCommand.heading` and :meth:`~SimulateCommand.answer`: the answer lines;
* :meth:`~SimulateCommand.history`, :meth:`~SimulateCommand.history_frame`,
  :meth:`~SimulateCommand.events_frame`, :meth:`~SimulateCommand.summary`,
  :meth:`~SimulateCommand.figure`: the files (history.csv, events.csv, summary.json,
  the Calcomp figure).

The same adapter serves the model in the other commands that take a subject from the
command line: :meth:`~SimulateCommand.animate` (``animate`` without a scene) and
:meth:`~SimulateCommand.spectrum` (``spectrum``); each command chooses the adapter as
``simulate`` does (:func:`shaketable.commands.simulate.chosen_command`).

Adding a model to ``simulate`` means adding one adapter (a subclass here or beside the
model's other commands, e.g. :class:`shaketable.commands.stack.StackCommand`) and one entry
in :data:`shaketable.commands.simulate.SIMULATE_COMMANDS`.
"""

from __future__ import annotations

import dataclasses
import json
from typing import Any

from shaketable.commands.block import resolve_angle  # noqa: F401  (its home before)


@dataclasses.dataclass(frozen=True)
class Setup:
    """One ``simulate`` run's inputs, read and checked.

    Attributes
    ----------
    subject : Block or Stack
        What the model moves.
    motion : Motion or None
        The table's motion; None: free rocking.
    note : str or None
        What scaling the record said (``--scale``, ``--pga``), printed with the answer.
    options : dict
        The options of the model's run (``cor``, ``theta0``, ``duration``, ...).
    label : str
        What the run is, for the early-stop warning (``30x6in block``).
    extra : dict
        The adapter's own inputs that are not run options (the stack's ``mu``).
    """

    subject: Any
    motion: Any
    note: str | None
    options: dict
    label: str
    extra: dict = dataclasses.field(default_factory=dict)


class SimulateCommand:
    """The hooks of one model in ``shaketable simulate``; the defaults suit one block.

    Attributes
    ----------
    model : str
        The model's name in :data:`shaketable.models.registry.MODELS`.
    selects : tuple of str
        The options (argparse names) that choose this model: the adapter whose options
        are all given, the most of them, wins; the first on a tie.
    """

    model: str = ""
    selects: tuple[str, ...] = ()

    def prepare(self, args) -> Setup:
        raise NotImplementedError

    def refuse(self, args) -> None:
        """Refuse the options this model does not take (ValueError naming them)."""

    def run_options(self, args) -> dict:
        """This model's own options of the run (a one-block model: beside ``cor``,
        ``theta0`` and ``duration``)."""
        return {}

    def compiles(self, args) -> tuple[str, ...]:
        """The compiled engines the run needs (the first-compile notice names them)."""
        return ()

    def ensemble(self, args, setup: Setup, out) -> int | None:
        """Run the model's ensemble and say it; its exit status, or None: one run."""
        return None

    def run(self, model, setup: Setup) -> tuple[Any, list[str]]:
        """The run of ``model`` (the registry's), and the warnings it gave as text."""
        return model.run(setup.subject, setup.motion, **setup.options), []

    def history(self, args, result) -> str:
        """What history.csv holds: ``full``, ``peaks`` or ``none``."""
        from shaketable.commands.history import history_mode

        return history_mode(args.history, result.t.size)

    def history_frame(self, result, mode: str):
        from shaketable.commands.history import history_frame

        return history_frame(result, mode)

    def events_frame(self, result):
        """The events.csv table, or None: no such file."""
        return None

    def summary(self, setup: Setup, result, warnings: list[str]) -> dict:
        from shaketable.models.stops import stop_summary

        return stop_summary(result)

    def figure(self, result):
        return result.plot()

    def heading(self, args, setup: Setup, result) -> str:
        return f"{setup.subject.describe()} block, COR {args.cor}: {result.verdict()}"

    def answer(self, setup: Setup, result) -> list[str]:
        raise NotImplementedError

    def animate(self, args, size: tuple, wrote) -> int:
        """``animate`` without a scene: this model's run on the motion given as ``simulate``
        takes it, drawn to ``args.out`` (``size`` in pixels; ``wrote`` says the file)."""
        raise ValueError(f"animate does not draw the {self.model} model; give a scene, "
                         "--block or --stack")

    def spectrum(self, args) -> int:
        """``spectrum``: this model's overturning spectrum of pulses, written to ``args.out``."""
        raise ValueError(f"spectrum does not offer the {self.model} model; give --block "
                         "(or --alpha and --p) or --stack")


def on_floor(args, motion):
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


def friction_option(text: str | None):
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


def one_block_setup(args, command: SimulateCommand) -> Setup:
    """The inputs of a one-block run (``--block``, ``--cor``, the motion, ``--theta0``),
    checked in the order the user reads the options; ``command`` refuses the options its
    model does not take and reads its own run options (after ``--theta0``, before the
    ``--cor`` range)."""
    from shaketable.commands.checks import check_simulate_options, refuse_stack_options
    from shaketable.commands.common import load_motion, scaled_record
    from shaketable.commands.options import block_option, motion_from_options

    refuse_stack_options(args)
    if args.block is None or args.cor is None:
        raise ValueError("give --block and --cor (one block), or --stack (a column of blocks, "
                         "e.g. --stack 30x6in,30x6in)")
    check_simulate_options(args, command.refuse)   # options the model would ignore: refused
    block = block_option(args.block)
    motion = motion_from_options(args) or (load_motion(args) if args.record else None)
    motion, scale_note = scaled_record(motion, args)
    motion = on_floor(args, motion)
    theta0 = resolve_angle(args.theta0, block)
    own = command.run_options(args)   # every input checked before the output folder
    if not isinstance(args.cor, str):
        from shaketable.core.validation import in_range

        in_range("--cor", args.cor, 0.0, 1.0)
    options = dict(cor=args.cor, theta0=theta0, duration=args.duration, **own)
    return Setup(block, motion, scale_note, options, f"{block.describe()} block")


class RockingCommand(SimulateCommand):
    """``simulate --block --cor``: the rocking block of the report."""

    model = "rocking"

    def prepare(self, args) -> Setup:
        return one_block_setup(args, self)

    def run_options(self, args) -> dict:
        if isinstance(args.subdivisions, int) and args.subdivisions < 1:
            raise ValueError(f"--subdivisions must be an integer >= 1 (steps per sample), "
                             f"got {args.subdivisions}")
        return {"method": args.method, "subdivisions": args.subdivisions}

    def compiles(self, args) -> tuple[str, ...]:
        return ("engine", "batch") if args.ensemble else ("engine",)

    def ensemble(self, args, setup: Setup, out) -> int | None:
        if isinstance(args.cor, str):           # a calibration.json: the calibrated COR's spread
            from shaketable.commands.calibrate import simulate_calibrated

            return simulate_calibrated(args, setup.subject, setup.motion,
                                       setup.options["theta0"], out)
        return rocking_ensemble(args, setup.subject, setup.motion, out) if args.ensemble \
            else None

    def figure(self, result):
        from shaketable.commands.history import for_figure

        return for_figure(result).plot()

    def heading(self, args, setup: Setup, result) -> str:
        from shaketable.commands.answers import rocking_heading

        return f"{setup.subject.describe()} block, COR {args.cor}: {rocking_heading(result)}"

    def answer(self, setup: Setup, result) -> list[str]:
        from shaketable.commands.answers import rocking_answer

        return rocking_answer(result)

    def animate(self, args, size: tuple, wrote) -> int:
        from shaketable.commands.block import animate_block

        return animate_block(args, size, wrote)

    def spectrum(self, args) -> int:
        from shaketable.commands.block import block_spectrum

        return block_spectrum(args)


class PlanarCommand(SimulateCommand):
    """``simulate --friction``: the planar block (rest, slide, rock, slide-rock, flight)."""

    model = "planar"
    selects = ("friction",)

    def prepare(self, args) -> Setup:
        return one_block_setup(args, self)

    def refuse(self, args) -> None:
        """No calibration file as ``--cor``, no ``--method`` or ``--subdivisions``."""
        from shaketable.commands.checks import refuse_ignored_options

        if isinstance(args.cor, str):
            raise ValueError(f"--friction cannot be used with --cor {args.cor} (a calibration "
                             "file): the calibrated COR ensemble runs the rocking model; "
                             "give --cor a number to run the planar block with --friction")
        refuse_ignored_options(args, "--friction", {"--method": "fast", "--subdivisions": 4})

    def run_options(self, args) -> dict:
        return {"friction": friction_option(args.friction)}

    def compiles(self, args) -> tuple[str, ...]:
        return ("planar",)

    def ensemble(self, args, setup: Setup, out) -> int | None:
        if not args.ensemble:
            return None
        from shaketable.commands.friction_ensemble import friction_ensemble

        return friction_ensemble(args, setup.subject, setup.motion,
                                 setup.options["friction"], out)

    def history(self, args, result) -> str:
        mode = super().history(args, result)
        # the planar block's history has no peaks selection: all of it
        return "full" if mode == "peaks" else mode

    def answer(self, setup: Setup, result) -> list[str]:
        from shaketable.commands.answers import planar_answer

        return planar_answer(result)


def rocking_ensemble(args, block, motion, out) -> int:
    """``simulate --ensemble N``: the rocking model's perturbed copies of one run."""
    from shaketable.commands.checks import report_stopped_rows
    from shaketable.commands.friction_ensemble import ensemble_perturbation, perturbation_line
    from shaketable.core.files import json_ready_dict, write_csv, write_text
    from shaketable.plots import base as plots
    from shaketable.studies.predictability import ensemble

    perturbation = ensemble_perturbation(args, motion)
    result = ensemble(block, motion, cor=args.cor, members=args.ensemble,
                      perturbation=perturbation, seed=args.seed, duration=args.duration,
                      method=args.method, threshold=args.horizon_threshold)
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
    return report_stopped_rows(result.to_frame(), f"{block.describe()} block", "simulate")
