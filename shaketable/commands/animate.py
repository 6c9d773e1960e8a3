"""``shaketable animate SCENE.toml --out FILE.gif``: the block rocking on the moving table."""

from __future__ import annotations


def _animate(args) -> int:
    from shaketable.core.files import prepare_output_file
    from shaketable.plots.animation import animate
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import Study, load_scene
    from shaketable.scenes.run import build_motion, run_scene

    prepare_output_file(args.out, "--out", suffixes=(".gif",))
    scene = load_scene(resolve_scene_path(args.scene))
    if isinstance(scene, Study):
        raise ValueError(f"{scene.path}: a [study] has no single block to animate; give a "
                         "scene with [block], [motion] and [rocking]")
    from shaketable.commands.common import notice_first_compile

    notice_first_compile(args.quiet)
    result = run_scene(scene)
    if not 0 <= args.run < len(result.runs):
        raise ValueError(f"--run must be between 0 and {len(result.runs) - 1} (the scene's "
                         f"CORs {', '.join(f'{run.cor:g}' for run in result.runs)}), "
                         f"got {args.run}")
    run = result.runs[args.run]
    written = animate(run, motion=build_motion(scene), out=args.out, fps=args.fps,
                      speed=args.speed, start=args.start, end=args.end)
    verdict = (f"overturns at {run.t_overturn:.2f} s" if run.overturned
               else f"max theta/alpha = {run.max_theta_ratio:.3f}")
    print(f"{scene.name}: {scene.block.describe()}, COR {run.cor:g}: {verdict}")
    print(f"wrote {written.path} ({written.n_frames} frames, {written.fps:g} fps, "
          f"{written.t_first:g}-{written.t_last:g} s at speed {written.speed:g})")
    return 0


def register(commands) -> None:
    """Add the ``animate`` subcommand."""
    from shaketable.commands.options import add_quantity

    parser = commands.add_parser(
        "animate", help="animated GIF: the block rocking on the moving table beside θ/α",
        description="Run a scene and write an animated GIF of the block (to scale, rocking "
                    "about its corner) on the moving table, beside θ/α with the ±1 lines "
                    "and the ground acceleration.")
    parser.add_argument("scene", help="path to a scene .toml, or the name of a bundled scene")
    parser.add_argument("--out", required=True, help="the GIF to write (FILE.gif)")
    parser.add_argument("--fps", type=float, default=12.0,
                        help="frames per second of the GIF (default 12)")
    parser.add_argument("--speed", type=float, default=1.0,
                        help="simulated seconds per GIF second (default 1: real time)")
    parser.add_argument("--run", type=int, default=0,
                        help="which of the scene's CORs to show, counted from 0 (default 0)")
    add_quantity(parser, "--start", kind="time", example="2s", help="first time shown")
    add_quantity(parser, "--end", kind="time", example="16s", help="last time shown")
    parser.set_defaults(handler=_animate)
