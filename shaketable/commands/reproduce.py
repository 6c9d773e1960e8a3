"""``shaketable reproduce``: rerun the report's experiments and write a Markdown report."""

from __future__ import annotations

import sys

from shaketable.commands.common import compiled_before, notice_first_compile


def _reproduce(args) -> int:
    from shaketable.reproduce import EXTRA_SECTIONS, reproduce
    from shaketable.scenes.catalog import scene_names

    available = scene_names()
    extras = list(EXTRA_SECTIONS)   # the report's sections beyond the scenes
    if args.list:
        print("\n".join(available + extras))
        return 0
    every = args.all or not args.names
    names = available + extras if every else args.names
    unknown = [name for name in names if name not in available and name not in extras]
    if unknown:  # checked before anything is written
        from shaketable.scenes.catalog import did_you_mean

        said = ", ".join(f"{name!r}" + did_you_mean(name, available + extras).replace(
            ": ", " (", 1).replace("?", "?)") for name in unknown)
        raise ValueError(f"no scene {said}; "
                         f"`shaketable reproduce --list` lists the {len(available)} scenes "
                         f"and the {len(extras)} section{'s' if len(extras) != 1 else ''} "
                         f"beyond them ({', '.join(extras)})")
    chosen = [name for name in names if name in extras]
    if args.validation_data is not None and "validation" not in chosen:
        raise ValueError("--validation-data is the folder of the 'validation' section: "
                         "name it (`shaketable reproduce validation --validation-data DIR`) "
                         "or give --all")
    scenes = [name for name in names if name in available]
    from shaketable.core.files import prepare_output_folder

    out = prepare_output_folder(args.out)
    from shaketable.scenes.catalog import uses_planar, uses_stack

    planar = any(uses_planar(name) for name in scenes)
    engines = ("engine",) + (("planar",) if planar else ()) + (
        ("stack",) if any(uses_stack(name) for name in scenes) else ())
    notice_first_compile(args.no_progress, which=engines)
    failed: list = []
    # each extra section skips itself, saying how to give what it needs, when it cannot run
    options = {"validation": {"data": args.validation_data}}
    report = reproduce(scenes, out=out, progress=not args.no_progress, failures=failed,
                       compile_planar_first=planar and not compiled_before("planar"),
                       extra={name: options.get(name, {}) for name in chosen})
    if not args.no_progress:
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
    parser.add_argument("names", nargs="*",
                        help="scene names, and the sections beyond the scenes by name "
                             "(validation; default: all of them)")
    parser.add_argument("--all", action="store_true",
                        help="every scene and every section beyond them")
    parser.add_argument("--list", action="store_true",
                        help="list the scenes, then the sections beyond them, and stop")
    parser.add_argument("--out", default="reproduce-out", help="output folder")
    parser.add_argument("--validation-data", metavar="DIR",
                        help="the folder of measured tests of the 'validation' section "
                             "(with --all, or naming validation; default $SHAKETABLE_PBR, else "
                             "../shared/data/pbr beside the source checkout when run from "
                             "one; skipped, saying how to give it, when absent)")
    # its own dest: the global --quiet silences all output, this one keeps the last line
    parser.add_argument("-q", "--quiet", action="store_true", dest="no_progress",
                        help="no progress bar and no summary: only the closing "
                             "'wrote ...' line (and errors)")
    parser.set_defaults(handler=_reproduce)
