"""Dimensional command-line options: one unit rule for every subcommand.

Every option that holds a dimensional value takes it with its unit (``--duration 8s``,
``--dt 0.02s``, ``--alpha 0.25rad``), as scenes do (:mod:`shaketable.core.units`); a bare
number is refused. The value is converted to SI when the command line is read, and a bad
one ends the command with one short line naming the option (exit status 2), without
argparse's usage dump::

    shaketable simulate: error: --duration: '8' has no unit; write the time with its
    unit, e.g. '8 s' (units: min, ms, s)
"""

from __future__ import annotations

import argparse
from typing import Any

from shaketable.core.units import parse

#: Exit status of bad usage or input (``shaketable.cli.EXIT_BAD_INPUT``).
_BAD_INPUT = 2


class Quantity(argparse.Action):
    """An option holding a quantity of ``kind`` (a key of :data:`shaketable.core.units.UNITS`).

    Use as ``parser.add_argument("--duration", action=Quantity, kind="time")``; the
    namespace receives the value in SI units [s, m, m/s^2, Hz, rad, rad/s...].
    """

    def __init__(self, option_strings, dest, kind: str, **kwargs: Any) -> None:
        self.kind = kind
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        try:
            value = parse(values, self.kind, where=option_string or self.dest)
        except ValueError as error:
            parser.exit(_BAD_INPUT, f"{parser.prog}: error: {error}\n")
        setattr(namespace, self.dest, value)


def add_quantity(parser, *flags: str, kind: str, example: str, help: str, **kwargs: Any) -> None:
    """Add a dimensional option: ``help`` gains the unit rule and an example (``8s``)."""
    metavar = kwargs.pop("metavar", None) or kind.upper().replace(" ", "_")
    parser.add_argument(*flags, action=Quantity, kind=kind, metavar=metavar,
                        help=f"{help}, with its unit (e.g. {example})", **kwargs)
