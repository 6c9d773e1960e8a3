"""Command line: ``shaketable SUBCOMMAND ...``, a thin layer over the library.

Each subcommand lives in ``shaketable/commands/<name>.py`` and exposes
``register(subparsers)``; :data:`SUBCOMMANDS` lists them in help order.
"""

from __future__ import annotations

import argparse
import importlib
import sys

#: Subcommand modules in ``shaketable.commands``, in the order ``--help`` shows them.
SUBCOMMANDS = ["simulate", "run", "reproduce", "calibrate", "sweep", "bench", "animate",
               "slide", "spectrum"]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every subcommand registered."""
    parser = argparse.ArgumentParser(
        prog="shaketable",
        description="Virtual shaking-table tests of rocking rigid blocks "
                    "(Aslam, Godden & Scalise; BLOKROC).")
    commands = parser.add_subparsers(dest="command", required=True)
    for name in SUBCOMMANDS:
        importlib.import_module(f"shaketable.commands.{name}").register(commands)
    return parser


def main(argv=None) -> int:
    """Entry point of the ``shaketable`` console script; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.handler(args)
    except (ValueError, FileNotFoundError) as error:
        print(f"shaketable {args.command}: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
