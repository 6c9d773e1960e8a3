"""``shaketable assess OBJECT.toml --out FOLDER``: rock, slide or anchor? One assessment of
an object at grade or on a floor of a building, with the codes' checks beside the dynamics."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import argparse


def _assess(args: argparse.Namespace) -> int:
    import time

    from shaketable.assessment import FIGURES, assess
    from shaketable.commands.common import notice_first_compile
    from shaketable.core.files import prepare_output_folder
    from shaketable.scenes.assess import load_assessment
    from shaketable.scenes.catalog import resolve_object_path

    spec = load_assessment(resolve_object_path(args.object))
    out = prepare_output_folder(args.out if args.out is not None
                                else Path("shaketable-out") / spec.name)
    notice_first_compile(args.quiet, which=("engine", "planar"))
    start = time.perf_counter()
    result = assess(spec, out, figures=not args.no_figures)
    if getattr(args, "quiet", False):
        return 0
    print(f"{spec.name} {spec.where}: {result.recommendation['choice']}")
    for reason in result.recommendation["reasons"]:
        print(f"  - {reason}")
    beside = ["summary.json", "runs.csv"] + ([] if args.no_figures
                                             else [file for _, file, _ in FIGURES])
    print(f"wrote {out / 'report.md'} and, beside it, {', '.join(beside)} "
          f"({time.perf_counter() - start:.1f} s)")
    return 0


def register(subparsers) -> None:
    """Add ``assess`` to the command line."""
    parser = subparsers.add_parser(
        "assess", help="rock, slide or anchor: assess an object (at grade or on a floor)",
        description="Assess a free-standing object described in a TOML file (size, mass, "
                    "friction range, COR; ground or a floor of a building; records and "
                    "levels or S_DS; clearance, hazard): the mode map, P(overturn), corner "
                    "excursion and slip, let it slide, the anchor forces beside ASCE 7-16 "
                    "Fp, the codes' checks and a recommendation, as report.md with figures "
                    "and summary.json.")
    from shaketable.scenes.catalog import object_names

    parser.add_argument("object", help="object file (.toml) or a bundled example: "
                                       f"{', '.join(object_names())}")
    parser.add_argument("--out", help="output folder (default shaketable-out/NAME)")
    parser.add_argument("--no-figures", action="store_true", help="write no figures")
    parser.set_defaults(handler=_assess)
