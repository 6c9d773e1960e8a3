"""``shaketable reproduce``: rerun the report's experiments and write a Markdown report."""

from __future__ import annotations

import sys

from shaketable.commands.common import compiled_before, notice_first_compile


def _reproduce(args) -> int:
    from shaketable.reproduce import reproduce
    from shaketable.scenes.catalog import scene_names

    available = scene_names()
    if args.list:
        print("\n".join(available))
        return 0
    names = available if args.all or not args.names else args.names
    unknown = [name for name in names if name not in available]
    if unknown:  # checked before anything is written
        raise ValueError(f"no scene {', '.join(repr(name) for name in unknown)}; "
                         f"`shaketable reproduce --list` lists the {len(available)} scenes")
    from shaketable.core.files import prepare_output_folder

    out = prepare_output_folder(args.out)
    from shaketable.scenes.catalog import uses_planar

    planar = any(uses_planar(name) for name in names)
    notice_first_compile(args.quiet, which=("engine", "planar") if planar else ("engine",))
    failed: list = []
    # with every scene, the sections beyond them (each skips itself when it cannot run)
    extra = {"validation": {"data": args.validation_data}} if names == available else None
    report = reproduce(names, out=out, progress=not args.quiet, failures=failed,
                       compile_planar_first=planar and not compiled_before("planar"),
                       extra=extra)
    for line in _summary(out):
        print(line)
    print(f"wrote {report} (and gallery.md beside it)")
    if failed:
        print(f"shaketable reproduce: {len(failed)} scene(s) could not be reproduced: "
              f"{', '.join(failed)} (their sections in {report} say why)", file=sys.stderr)
        return 1
    return 0


def _summary(out) -> list:
    """The report's headline on the console: agree/differ counts of every section in ``out``."""
    import json

    from shaketable.studies.comparison import ComparisonTally

    tally = ComparisonTally()
    for path in sorted(out.glob("*/counts.json")):
        for kind, (agree, differ) in json.loads(path.read_text()).items():
            if kind in tally.counts:
                tally.add_many(kind, agree, agree + differ)
    return [line.strip("*") for line in tally.headline()]


def register(commands) -> None:
    """Add the ``reproduce`` subcommand."""
    parser = commands.add_parser(
        "reproduce", help="rerun the report's figures and tables; write a Markdown report",
        description="Run the report's experiments (the scenes of the experiments folder) "
                    "and write report.md with every figure and a 'report value vs "
                    "reproduced value' table for each.")
    parser.add_argument("names", nargs="*", help="scene names (default: all)")
    parser.add_argument("--all", action="store_true", help="every scene")
    parser.add_argument("--list", action="store_true", help="list the scenes and stop")
    parser.add_argument("--out", default="reproduce-out", help="output folder")
    parser.add_argument("--validation-data", metavar="DIR",
                        help="with every scene: the folder of measured tests of the "
                             "'validation' section (default $SHAKETABLE_PBR, else "
                             "../shared/data/pbr beside the source checkout when run from "
                             "one; skipped, saying how to give it, when absent)")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    parser.set_defaults(handler=_reproduce)
