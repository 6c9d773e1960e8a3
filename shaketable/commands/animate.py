"""``shaketable animate SCENE --out FILE.mp4``: the block(s) rocking on the moving table.

Or without a scene, one block on a motion given as ``simulate`` takes it:
``shaketable animate --block 30x6in --cor 0.9 --harmonic 2Hz,0.3g --duration 6s --out a.gif``
(``--pulse``, ``--record``).
"""

from __future__ import annotations

import re


def _runs(text: str, count: int, cors: str) -> list:
    """``--run``: ``all``, or run numbers from 0 separated by commas."""
    if str(text).strip().lower() == "all":
        return list(range(count))
    try:
        chosen = [int(part) for part in str(text).split(",")]
    except ValueError:
        chosen = [-1]
    if not all(0 <= index < count for index in chosen):
        raise ValueError(f"--run must be between 0 and {count - 1} (the scene's runs: "
                         f"{cors}), or numbers separated by commas, or 'all'; got {text}")
    return chosen


def _size(text: str) -> tuple:
    """``--size 1280x720``: width and height in pixels."""
    match = re.fullmatch(r"\s*(\d+)\s*[x×]\s*(\d+)\s*(?:px)?\s*", str(text))
    if not match:
        raise ValueError(f"--size {text!r}: give WIDTHxHEIGHT in pixels, e.g. 1280x720")
    return int(match[1]), int(match[2])


def _animate(args) -> int:
    from shaketable.commands.checks import check_animate_options
    from shaketable.core.files import prepare_output_file
    from shaketable.plots.animation import DEFAULT_FPS, animate
    from shaketable.plots.calcomp import run_labels
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import Study, load_scene
    from shaketable.scenes.run import run_scene

    # neither --fps nor --speed: a short run is slowed (speed None: plots.animation's
    # default_speed); a frame rate given alone keeps real time
    if args.fps is None:
        args.fps = float(DEFAULT_FPS)
    elif args.speed is None:
        args.speed = 1.0
    check_animate_options(args)   # before the scene runs: bounds that protect the memory
    size = _size(args.size)
    prepare_output_file(args.out, "--out", suffixes=(".gif", ".mp4"))
    given = [f"--{name}" for name in ("block", "stack", "masses", "densities", "cor",
                                      "harmonic", "pulse", "record")
             if getattr(args, name) is not None]
    if args.scene is None:   # the model of the options given (--block, --stack) draws it
        from shaketable.commands.simulate import chosen_command

        command, _ = chosen_command(args)
        return command.animate(args, size, _wrote)
    if given:
        raise ValueError(f"give a scene or --block with its motion, not both (got the scene "
                         f"{args.scene!r} and {', '.join(given)})")
    scene = load_scene(resolve_scene_path(args.scene))
    if isinstance(scene, Study):
        raise ValueError(f"{scene.path}: a [study] has no single block to animate; give a "
                         "scene with [block], [motion] and [rocking]")
    from shaketable.commands.common import notice_first_compile
    from shaketable.scenes.stack import StackScene

    if isinstance(scene, StackScene):   # [stack]: one drawing per block
        from shaketable.commands.stack import animate_stack_scene

        return animate_stack_scene(args, scene, size, _wrote)
    notice_first_compile(args.quiet)
    result = run_scene(scene)
    labels = run_labels(result.runs)
    chosen = _runs(args.run, len(result.runs), ", ".join(
        f"{index}: {label}" for index, label in enumerate(labels)))
    runs = [result.runs[index] for index in chosen]
    written = animate(runs if len(runs) > 1 else runs[0], out=args.out, fps=args.fps,
                      speed=args.speed, start=args.start, end=args.end, size=size, dpi=args.dpi,
                      layout=args.layout, unit=args.unit,
                      labels=[labels[index] for index in chosen] if len(runs) > 1 else None)
    from shaketable.commands.answers import free_periods_line
    from shaketable.models.rocking.free_rocking import is_free

    if periods := free_periods_line(runs):   # releases from several angles: Eq. 2-5
        print(f"{scene.name}: {periods}")
    for index in chosen:
        run = result.runs[index]
        verdict = (f"overturns at {run.t_overturn:.2f} s" if run.overturned
                   else run.verdict() if is_free(run)   # the rest time and cycles, as run says
                   else f"max θ/α = {run.max_theta_ratio:.3f}")
        label = labels[index] if len(result.runs) > 1 else f"COR {run.cor:g}"
        if run.block.describe() not in label:
            label = f"{run.block.describe()}, {label}"
        print(f"{scene.name}: {label}: {verdict}")
    _wrote(written)
    from shaketable.commands.checks import report_early_stops

    return report_early_stops(runs, "animate", scene.name)


def _wrote(written) -> None:
    if written.note:
        print(f"note: {written.note}")
    print(f"wrote {written.path} ({written.n_frames} frames of {written.size[0]} x "
          f"{written.size[1]} pixels, {written.fps:g} fps, {round(written.t_first, 2):g}-"
          f"{round(written.t_last, 2):g} s at speed {written.speed:g})")


def register(commands) -> None:
    """Add the ``animate`` subcommand."""
    from shaketable.commands.common import add_record_arguments
    from shaketable.commands.options import add_mass_options, add_motion_options, add_quantity

    parser = commands.add_parser(
        "animate", help="animation (MP4 or GIF): the blocks rocking on the moving table beside θ/α",
        description="Run a scene and write an animation of its blocks (to scale, rocking "
                    "about their corners) on the moving table, beside θ/α with the ±1 lines "
                    "and the ground acceleration. A scene with several runs (cor, theta0 "
                    "or block size given as a list) shows them side by side or overlaid. "
                    "Without a scene, one block on a motion given as `simulate` takes it "
                    "(--block, --cor, --harmonic, --pulse, --record, --duration). Every trace "
                    "is drawn up to the frame's time, never ahead of it. "
                    "MP4 needs ffmpeg; without it a GIF is written.")
    parser.add_argument("scene", nargs="?",
                        help="path to a scene .toml, or the name of a bundled scene; or none, "
                             "with --block and its motion")
    parser.add_argument("--block", help="without a scene: HEIGHTxWIDTH with unit, height "
                                        "first, e.g. 30x6in or 16x4ft")
    parser.add_argument("--stack", metavar="SIZE,SIZE[,...]",
                        help="without a scene: a column of blocks from the bottom up, each "
                             "HEIGHTxWIDTH with unit (e.g. 30x6in,30x6in), as simulate --stack "
                             "(--cor optional: without it plastic impacts)")
    add_mass_options(parser)
    parser.add_argument("--cor", type=float,
                        help="without a scene: coefficient of restitution [0-1]")
    parser.add_argument("--theta0", default="0rad",
                        help="without a scene: initial tilt with unit: 0.05rad, 3deg or "
                             "0.5alpha (default 0rad)")
    add_record_arguments(parser)
    add_motion_options(parser)
    add_quantity(parser, "--duration", kind="time", example="8s", positive=True,
                 help="without a scene: length of the run")
    parser.add_argument("--out", required=True,
                        help="the file to write: FILE.mp4 (with ffmpeg; otherwise FILE.gif "
                             "is written) or FILE.gif")
    parser.add_argument("--fps", type=float, default=None,
                        help="frames per second of the animation (default 12)")
    parser.add_argument("--speed", type=float, default=None,
                        help="simulated seconds per animation second (1: real time). "
                             "Default: real time for 4 s or more shown; a shorter span "
                             "is slowed to last 4 s (speed = span / 4 s: a 1-s run at "
                             "0.25, 48 frames at 12 fps), unless --fps is given (then 1)")
    parser.add_argument("--run", default="all",
                        help="which of the scene's runs to show, counted from 0: 'all' "
                             "(default), one (1) or several (0,1)")
    parser.add_argument("--layout", choices=("side", "overlay"), default="side",
                        help="several runs: each block on its own table side by side "
                             "(default), or all on one table")
    parser.add_argument("--size", default="1024x576",
                        help="frame size WIDTHxHEIGHT in pixels (default 1024x576)")
    parser.add_argument("--dpi", type=float, default=100.0,
                        help="dots per inch: larger makes the fonts larger in the same frame "
                             "(default 100)")
    parser.add_argument("--unit", choices=("mm", "cm", "m", "in", "ft"),
                        help="length unit of the drawing (default: the unit of the block size)")
    add_quantity(parser, "--start", kind="time", example="2s", help="first time shown")
    add_quantity(parser, "--end", kind="time", example="16s", help="last time shown")
    parser.set_defaults(handler=_animate)
