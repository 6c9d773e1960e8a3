"""``shaketable simulate --stack 30x6in,30x6in``: a column of blocks (the stack model).

The answer first (the verdict: which block overturned and when; each block's peak
rotation against its own alpha; the top corner's excursion; the friction the contacts
need against ``--mu``), then the files, as for one block: history.csv, events.csv,
summary.json and the Calcomp figure (one rotation panel per block and the contact
patterns; ``docs/stack.md``): :class:`StackCommand`, the stack model's adapter of
``simulate`` (:mod:`shaketable.commands.simulate_models`).
"""

from __future__ import annotations

from shaketable.commands.simulate_models import Setup, SimulateCommand, on_floor

#: ``simulate``'s options that belong to one block, with their defaults: refused with --stack.
_BLOCK_ONLY = {"--block": None, "--method": "fast", "--subdivisions": 4, "--friction": None,
               "--ensemble": 0, "--perturb": 1e-9, "--perturb-amplitude": None,
               "--perturb-cor": None, "--perturb-size": None, "--perturb-start": None,
               "--seed": 0, "--horizon-threshold": 1e-3}


def stack_motion(args, on_floor):
    """The table motion of ``--record``, ``--harmonic`` or ``--pulse`` (None: free rocking),
    a record cut to ``--duration`` when one is given, on ``--floor`` of ``--building``."""
    from shaketable.commands.common import load_motion, scaled_record
    from shaketable.commands.options import motion_from_options
    from shaketable.models.rocking.run import extended

    motion = motion_from_options(args) or (load_motion(args) if args.record else None)
    motion, note = scaled_record(motion, args)
    motion = on_floor(args, motion)
    if motion is None and args.duration is None:
        raise ValueError("free rocking (no --record, --harmonic or --pulse) needs --duration")
    if motion is not None and args.record and args.duration is not None:
        motion = extended(motion, args.duration)
    return motion, note


class StackCommand(SimulateCommand):
    """``simulate --stack``: a column of blocks (the stack model)."""

    model = "stack"
    selects = ("stack",)

    def compiles(self, args) -> tuple[str, ...]:
        """The stack's compiled engine (the first-compile notice names it)."""
        return ("stack",)

    def prepare(self, args) -> Setup:
        from shaketable.commands.checks import refuse_ignored_options
        from shaketable.core.validation import in_range
        from shaketable.scenes.stack import friction_coefficient, per_block_angles, stack_from_text

        refuse_ignored_options(args, "--stack (a column of blocks)", _BLOCK_ONLY)
        if isinstance(args.cor, str):
            raise ValueError(f"--cor {args.cor}: a calibration file is for one block; with "
                             "--stack give a number (the constant-COR law) or leave --cor out "
                             "(the plastic multi-contact law)")
        stack = stack_from_text(args.stack, args.masses, args.densities)
        theta0 = per_block_angles(args.theta0, stack, where="--theta0")
        mu = friction_coefficient(args.mu, "--mu")
        options: dict = {"theta0": theta0}
        if args.cor is not None:
            options.update(impact="cor", cor=in_range("--cor", args.cor, 0.0, 1.0))
        motion, note = stack_motion(args, on_floor)
        if motion is None:
            options["duration"] = args.duration
        from shaketable.scenes.stack import typed_mass_unit

        return Setup(stack, motion, note, options, stack.describe(),
                     {"mu": mu, "mass_unit": typed_mass_unit(args.masses)})

    def run(self, model, setup: Setup):
        from shaketable.scenes.stack import run_quietly

        return run_quietly(setup.subject, setup.motion, **setup.options)

    def history_frame(self, result, mode: str):
        """Every sample (``full``), or the samples of
        :func:`~shaketable.commands.history.stack_peak_rows` (``peaks``)."""
        frame = result.to_frame()
        if mode == "full":
            return frame
        from shaketable.commands.history import stack_peak_rows

        return frame.iloc[stack_peak_rows(result)].reset_index(drop=True)

    def events_frame(self, result):
        return result.events_frame()

    def summary(self, setup: Setup, result, warnings: list[str]) -> dict:
        from shaketable.models.stops import stop_summary

        summary = dict(stop_summary(result), stack=setup.subject.describe(),
                       verdict=result.verdict(), warnings=warnings)
        mu = setup.extra["mu"]
        if mu is not None:
            summary["mu [-]"] = mu
            summary["t_friction_exceeded(mu) [s]"] = result.t_friction_exceeded(mu)
        return summary

    def heading(self, args, setup: Setup, result) -> str:
        from shaketable.scenes.stack import describe_law

        return f"{setup.subject.describe()}, {describe_law(result)}: {result.verdict()}"

    def answer(self, setup: Setup, result) -> list[str]:
        from shaketable.scenes.stack import stack_answer

        return stack_answer(result, setup.extra["mu"], setup.extra.get("mass_unit", "kg"))

    def animate(self, args, size: tuple, wrote) -> int:
        return animate_stack_options(args, size, wrote)

    def spectrum(self, args) -> int:
        return stack_spectrum_command(args)


def _animation_options(args, size) -> dict:
    return {"out": args.out, "fps": args.fps, "speed": args.speed, "start": args.start,
            "end": args.end, "size": size, "dpi": args.dpi, "unit": args.unit}


def _refuse_runs_and_layout(args, what: str) -> None:
    from shaketable.commands.checks import refuse_ignored_options

    refuse_ignored_options(args, what, {"--run": "all", "--layout": "side"})


def animate_stack_scene(args, scene, size, wrote) -> int:
    """``animate SCENE`` for a scene with ``[stack]``: its one run, one drawing per block."""
    from shaketable.commands.checks import report_early_stops
    from shaketable.plots.stack_animation import animate_stack
    from shaketable.scenes.stack import run_stack_scene

    _refuse_runs_and_layout(args, f"a stack scene ({scene.name}: one run)")
    result = run_stack_scene(scene)
    written = animate_stack(result.run, **_animation_options(args, size))
    print(result.lines()[0])
    wrote(written)
    return report_early_stops([result.run], "animate", scene.name)


def animate_stack_options(args, size, wrote) -> int:
    """``animate --stack SIZES`` with a motion given as ``simulate`` takes it."""
    from shaketable.commands.checks import report_early_stops
    from shaketable.core.validation import in_range
    from shaketable.plots.stack_animation import animate_stack
    from shaketable.scenes.stack import describe_law, per_block_angles, run_quietly, stack_from_text

    _refuse_runs_and_layout(args, "--stack (one run)")
    if args.block is not None:
        raise ValueError("give --block or --stack, not both")
    stack = stack_from_text(args.stack, args.masses, args.densities)
    options: dict = {"theta0": per_block_angles(args.theta0, stack, where="--theta0")}
    if args.cor is not None:
        options.update(impact="cor", cor=in_range("--cor", args.cor, 0.0, 1.0))
    motion, note = stack_motion(args, lambda _, motion: motion)
    if motion is None:
        options["duration"] = args.duration
    result, _ = run_quietly(stack, motion, **options)
    written = animate_stack(result, **_animation_options(args, size))
    if note:
        print(note)
    print(f"{stack.describe()}, {describe_law(result)}: {result.verdict()}")
    wrote(written)
    return report_early_stops([result], "animate", stack.describe())


def stack_spectrum_command(args) -> int:
    """``spectrum --stack``: every overturn/safe band of half-sine pulses of a stack and of
    its bottom block alone over omega/p, drawn as the single block's spectrum
    (:func:`shaketable.studies.stack_spectrum.stack_spectrum_bands`)."""
    import functools
    import time

    from shaketable.commands.checks import refuse_ignored_options
    from shaketable.core.files import prepare_output_folder, write_csv, write_parquet
    from shaketable.plots import base as plots
    from shaketable.plots.stack_spectrum import stack_bands_figure
    from shaketable.scenes.spectrum import parse_ratios
    from shaketable.scenes.stack import stack_from_text
    from shaketable.studies.stack_spectrum import COLUMNS, lowest_overturning, stack_spectrum_bands
    from shaketable.studies.stacks import eq_2_8_curves

    refuse_ignored_options(args, "--stack (half-sine pulses, plastic impacts)",
                           {"--block": None, "--alpha": None, "--p": None, "--cor": "housner",
                            "--ceiling": None, "--tolerance": 1e-8, "--method": "fast",
                            "--compare-linear": False})
    if args.pulse and args.pulse != ["half-sine"]:
        raise ValueError(f"--pulse {args.pulse[0]}: with --stack only half-sine pulses are "
                         "offered")
    if not 1 <= args.iterations <= 30:
        raise ValueError(f"--iterations must be from 1 to 30, got {args.iterations}")
    step = STACK_SCAN_STEP if args.scan_step is None else args.scan_step
    if not 0 < step < 1:
        raise ValueError(f"--scan-step must be in (0, 1), got {step!r}")
    stack = stack_from_text(args.stack, args.masses)
    ratios = parse_ratios(args.ratios)
    out = prepare_output_folder(args.out)
    began = time.perf_counter()
    frame = stack_spectrum_bands(stack, ratios, scan_step=step, iterations=args.iterations)
    elapsed = time.perf_counter() - began
    written = [write_csv(out / "spectrum.csv", frame)]
    if args.parquet:
        written.append(write_parquet(out / "spectrum.parquet", frame))
    written.append(out / f"spectrum.{args.format}")
    curves = functools.partial(eq_2_8_curves, stack)   # drawn across the figure's axis
    plots.save(stack_bands_figure(frame, curves, f"half-sine pulses: {stack.describe()}, "
                                                 "plastic impacts"), written[-1])
    print(f"{stack.describe()}, plastic impacts: overturning half-sine pulses [g] over ω/p "
          f"(p = {stack.blocks[0].p:.4g} rad/s of the bottom block); "
          f"{frame.attrs['runs']} runs, {elapsed:.1f} s")
    for ratio in dict.fromkeys(frame["omega/p [-]"]):
        for column in COLUMNS:
            rows = frame[(frame["omega/p [-]"] == ratio) & (frame["column"] == column)]
            lowest = lowest_overturning(frame, ratio, column)
            falls = [f"{row['from [g]']:.3g} to {row['to [g]']:.3g}"
                     + (" (the ceiling)" if row["note"] == "up to the ceiling" else "")
                     + ("" if row["block that fell"] == "the block"
                        else f", {row['block that fell']} first")
                     for _, row in rows.iterrows() if row["verdict"] == "overturns"]
            print(f"  ω/p = {ratio:g}, {column}: "
                  + (f"lowest {lowest:.3g} g" if lowest == lowest else "no overturning")
                  + f" (Eq. 2-8 as one body {rows['Eq. (2-8) as one body [g]'].iloc[0]:.3g} g)"
                  + (f"; overturns {'; '.join(falls)}" if falls else ""))
    print("wrote " + ", ".join(str(path) for path in written))
    return 0


#: ``spectrum --stack``'s default relative scan step (a stack run costs a few single-block
#: runs; the edges are bisected --iterations times after the scan).
STACK_SCAN_STEP = 0.02
