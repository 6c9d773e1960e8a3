"""``shaketable run SCENE``: one scene (or study), its outputs and its comparison with the report."""

from __future__ import annotations

from pathlib import Path


def _run(args) -> int:
    from shaketable.commands.common import notice_first_compile
    from shaketable.core.files import prepare_output_folder
    from shaketable.scenes.catalog import is_sweep_spec, read_scene, uses_planar, uses_stack
    from shaketable.scenes.parse import SceneError, Study, load_scene

    sweep = ValueError(f"{args.scene!r} is a sweep spec, not a scene: run it with "
                       f"`shaketable sweep {args.scene}`")
    try:   # the file is read once: the questions below and the parser share the reading
        source = read_scene(args.scene)
    except SceneError:
        if is_sweep_spec(args.scene):   # the name of a bundled sweep spec
            raise sweep from None
        raise
    if is_sweep_spec(args.scene, source.data):
        raise sweep
    scene = load_scene(source.path, read=(source.data, source.text))
    out = prepare_output_folder(args.out or Path("shaketable-out") / scene.name)
    if "stack" in source.data:   # a [stack] scene: the stack engine alone
        engines: tuple = ("stack",)
    else:
        engines = ("engine",) + (("planar",) if uses_planar(source) else ()) + (
            ("stack",) if uses_stack(source) else ())
    notice_first_compile(args.quiet, which=engines)
    if isinstance(scene, Study):
        return _run_study(scene, out)
    from shaketable.scenes.stack import StackScene

    if isinstance(scene, StackScene):   # [stack]: a column of blocks (the stack model)
        return _run_stack(scene, out, args)
    from shaketable.scenes.run import run_scene

    if args.parquet or args.svg:
        outputs = dict(scene.outputs, parquet=args.parquet or scene.outputs["parquet"],
                       svg=args.svg or scene.outputs["svg"])
        scene = type(scene)(**{**scene.__dict__, "outputs": outputs})
    result = run_scene(scene)
    written = result.write(out)
    from shaketable.commands.answers import free_periods_line

    if periods := free_periods_line(result.runs):   # releases from several angles: Eq. 2-5
        print(f"{scene.name}: {periods}")
    if scene.mode() is not None:
        print(f"{scene.name}: {scene.mode()}")
    if result.table is not None:
        for line in result.table.warnings():
            print(f"{scene.name}: table limit exceeded: {line}")
    from shaketable.commands.answers import rocking_heading

    for run in result.runs:
        several = any(len(starts) > 1 for starts in scene.theta0s)
        start = f", from θ/α = {run.theta[0] / run.block.alpha:.3g}" if several else ""
        line = (f"{scene.name}: {run.block.describe()} block{start}, COR {run.cor:g}: "
                f"{rocking_heading(run)}")   # free rocking: when it came to rest
        if run.overturned:
            line += (f" (largest |θ|/α before instability "
                     f"{run.max_theta_ratio_before_instability:.3f})")
        print(line)
    for run in result.planar:   # block.static_friction runs the planar block
        from shaketable.commands.answers import planar_answer

        print(f"{scene.name}: planar {run.block.describe()} block (mu_s "
              f"{run.friction.static:g}, mu_d {run.friction.dynamic:g}), COR {run.cor:g}: "
              f"{run.verdict()}")
        for answer in planar_answer(run):
            print(f"  {answer}")
    for run in result.slides:   # in the one unit of the scene's slips
        from shaketable.scenes.run import length_in

        unit = result.slip_unit
        print(f"{scene.name}: sliding with mu_s {run.friction.static:g}, mu_d "
              f"{run.friction.dynamic:g}: peak slip {length_in(run.peak_slip, unit)}, "
              f"residual {length_in(run.residual_slip, unit, signed=True)}, "
              f"{run.slip_episodes} slip episode(s); Section 2.1: "
              f"{run.mode_choice.get('mode (Section 2.1)', 'n/a')}")
    for line in result.comparisons:
        verdict = "agrees" if line.agrees else "differs"
        print(f"  {line.quantity}: the report gives {_words(line.report, line.unit)}, "
              f"reproduced {_words(line.reproduced, line.unit)}: {verdict}")
    if result.calibrated is not None:          # rocking.cor = "calibration.json"
        print(f"{scene.name}: calibrated {scene.calibrated_cor.describe()}: "
              f"{result.calibrated.describe()}")
    if scene.report.get("note"):
        print(f"  note: {scene.report['note']}")
    _print_scaling(scene)
    if scene.ensemble:
        from shaketable.scenes.ensemble import run_ensembles

        more, lines = run_ensembles(scene, result.motion, out)
        written += more
        print("\n".join(lines))
    print("wrote " + ", ".join(str(path) for path in written))
    from shaketable.commands.checks import report_early_stops

    return report_early_stops([*result.runs, *result.planar], "run", scene.name)


def _print_scaling(scene) -> None:
    """The record's own PGA and the factor that scaled it to ``motion.pga``, as
    ``simulate --pga`` says them."""
    from shaketable.scenes.run import record_scaling_note

    note = record_scaling_note(scene)
    if note:
        print(note)


def _run_stack(scene, out: Path, args) -> int:
    """A scene with ``[stack]``: its verdict and answer, then the files."""
    import sys

    from shaketable.commands.checks import report_early_stops
    from shaketable.scenes.stack import run_stack_scene, with_outputs

    if args.parquet:
        raise ValueError(f"--parquet: a stack scene ({scene.name}) writes history.csv only")
    result = run_stack_scene(with_outputs(scene, svg=args.svg) if args.svg else scene)
    written = result.write(out)
    print("\n".join(result.lines()))
    _print_scaling(scene.base)
    from shaketable.scenes.stack import fall_note

    note, warned = fall_note(result.warnings)   # those after the fall: one note line
    if note:
        print(note)   # on the answer's stream: --quiet silences it
    for line in warned:
        print(f"shaketable run: warning: {scene.name}: {line}", file=sys.stderr)
    print("wrote " + ", ".join(str(path) for path in written))
    return report_early_stops([result.run], "run", scene.name)


def _run_study(study, out: Path) -> int:
    """A ``[study]`` scene: the report's table or figure it recomputes, as ``reproduce`` does."""
    from shaketable.reproduce import run_study_tally

    report, tally = run_study_tally(study, out)
    # the answer first: the comparison with the report (its own inputs apart from the
    # substitutes, as reproduce counts them), or what the study concludes
    if counts := tally.console_line():
        print(f"{study.name}: {counts} (see {report})")
    for line in _study_answer(study, out):
        print(f"{study.name}: {line}")
    print(f"{study.name}: {study.source or study.kind}: {study.description}")
    print(f"wrote {out}/ ({', '.join(sorted(path.name for path in out.iterdir() if not path.name.startswith('.')))})")
    return 0


def _study_answer(study, out: Path) -> list[str]:
    """What a study without comparisons with the report concludes (its report.md's
    conclusions), from the tables it wrote into ``out``; [] for the others."""
    import pandas as pd

    if study.kind == "teaching":   # the lesson's numbers, from the table the run wrote
        from shaketable.studies.teaching import teaching_answer

        lesson = teaching_answer(study.item, pd.read_csv(out / "numbers.csv"))
        return [lesson] if lesson else []
    if study.kind != "stacks":
        return []

    from shaketable.studies.stacks import stacks_answer

    return stacks_answer(*(pd.read_csv(out / f"{name}.csv")
                           for name in ("records", "uplift", "pulses")))


def _words(value, unit: str) -> str:
    """A compared value in words with its unit ("yes", "6.42 s", "0.78")."""
    if isinstance(value, bool):
        text = "yes" if value else "no"
    elif value is None:
        text = "none"
    else:
        text = f"{value:g}" if isinstance(value, float) else \
            "the same" if value == "same" else str(value)
    return f"{text} {unit}".strip() if unit not in ("", "-") else text


def register(commands) -> None:
    """Add the ``run`` subcommand."""
    parser = commands.add_parser(
        "run", help="run one scene (TOML): CSV, Calcomp figure, summary.json",
        description="Run a scene file, or a scene of the experiments folder by name "
                    "(e.g. fig-3-4). A [study] scene (e.g. table-4-2, fig-2-6, "
                    "teaching-lower-cor) writes its table, figure and report.md.")
    parser.add_argument("scene", help="path to a scene .toml, or the name of a bundled scene")
    parser.add_argument("--out", help="output folder (default shaketable-out/<scene name>)")
    parser.add_argument("--parquet", action="store_true", help="also write history.parquet")
    parser.add_argument("--svg", action="store_true", help="also write the figure as SVG")
    parser.set_defaults(handler=_run)
