"""``shaketable run SCENE.toml``: one scene, its outputs and its comparison with the report."""

from __future__ import annotations

from pathlib import Path


def _run(args) -> int:
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import run_scene

    scene = load_scene(resolve_scene_path(args.scene))
    if args.parquet or args.svg:
        outputs = dict(scene.outputs, parquet=args.parquet or scene.outputs["parquet"],
                       svg=args.svg or scene.outputs["svg"])
        scene = type(scene)(**{**scene.__dict__, "outputs": outputs})
    result = run_scene(scene)
    out = Path(args.out) if args.out else Path("shaketable-out") / scene.name
    written = result.write(out)
    if scene.mode() is not None:
        print(f"{scene.name}: {scene.mode()}")
    if result.table is not None:
        for line in result.table.warnings():
            print(f"{scene.name}: table limit exceeded: {line}")
    for run in result.runs:
        verdict = (f"overturns ({run.overturn_direction:+d}) at {run.t_overturn:.2f} s"
                   if run.overturned else f"max theta/alpha = {run.max_theta_ratio:.3f}")
        print(f"{scene.name}: {scene.block.describe()}, COR {run.cor:g}: {verdict}")
    for line in result.comparisons:
        mark = "agrees" if line.agrees else "differs"
        print(f"  {line.quantity}: report {line.report} {line.unit}, reproduced "
              f"{line.reproduced} {line.unit} ({mark})")
    if scene.ensemble:
        from shaketable.scenes.ensemble import run_ensembles

        more, lines = run_ensembles(scene, result.motion, out)
        written += more
        print("\n".join(lines))
    print("wrote " + ", ".join(str(path) for path in written))
    return 0


def register(commands) -> None:
    """Add the ``run`` subcommand."""
    parser = commands.add_parser(
        "run", help="run one scene (TOML): CSV, Calcomp figure, summary.json",
        description="Run a scene file, or a scene of the experiments folder by name "
                    "(e.g. fig-3-4).")
    parser.add_argument("scene", help="path to a scene .toml, or the name of a bundled scene")
    parser.add_argument("--out", help="output folder (default shaketable-out/<scene name>)")
    parser.add_argument("--parquet", action="store_true", help="also write history.parquet")
    parser.add_argument("--svg", action="store_true", help="also write the figure as SVG")
    parser.set_defaults(handler=_run)
