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
import re
from typing import Any

from shaketable.core.units import parse

#: Exit status of bad usage or input (``shaketable.cli.EXIT_BAD_INPUT``).
_BAD_INPUT = 2


class Quantity(argparse.Action):
    """An option holding a quantity of ``kind`` (a key of :data:`shaketable.core.units.UNITS`).

    Use as ``parser.add_argument("--duration", action=Quantity, kind="time")``; the
    namespace receives the value in SI units [s, m, m/s^2, Hz, rad, rad/s...]. With
    ``positive=True`` a value of zero or below is refused as the command line is read
    (``--duration must be positive, got -3 s``), before any output folder is made.
    """

    def __init__(self, option_strings, dest, kind: str, positive: bool = False,
                 **kwargs: Any) -> None:
        self.kind = kind
        self.positive = positive
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        option = option_string or self.dest
        try:
            value = parse(values, self.kind, where=option)
        except ValueError as error:
            parser.exit(_BAD_INPUT, f"{parser.prog}: error: {error}\n")
        if self.positive and not value > 0:
            parser.exit(_BAD_INPUT, f"{parser.prog}: error: {option} must be positive, got "
                                    f"{_as_written(values)}\n")
        setattr(namespace, self.dest, value)


def _as_written(text: str) -> str:
    """A quantity as the user wrote it, its number and unit apart: ``-3s`` -> ``-3 s``."""
    match = re.fullmatch(r"\s*([-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?)\s*(\S.*?)?\s*", str(text))
    if match is None:
        return str(text).strip()
    return " ".join(part for part in match.groups() if part)


#: A command-line word that begins like a negative number: ``-30x6in``, ``-8s``, ``-.5rad``.
_NEGATIVE = re.compile(r"-\.?\d")


def join_negative_values(parser: argparse.ArgumentParser, argv: list[str]) -> list[str]:
    """``argv`` with each negative value of a one-value option joined to it by ``=``.

    argparse reads a word that begins with ``-`` and is not a plain number as an option,
    so ``--block -30x6in`` ended in its usage dump ("expected one argument") instead of
    the option's own answer on the value. Joined (``--block=-30x6in``), the value reaches
    the option's reader, which accepts it (``--theta0 -3deg``) or refuses it naming the
    option (``--block -30x6in: the height and the width must be positive``). Only words
    after an option of the command that takes exactly one value are joined.
    """
    options = _one_value_options(parser)
    for word in argv:   # the subcommand's own options
        subcommand = _subcommands(parser).get(word)
        if subcommand is not None:
            options |= _one_value_options(subcommand)
            break
    joined: list[str] = []
    words = iter(argv)
    for word in words:
        following = next(words, None) if word in options else None
        if following is not None and _NEGATIVE.match(following):
            joined.append(f"{word}={following}")
        else:
            joined += [word] if following is None else [word, following]
    return joined


def _one_value_options(parser: argparse.ArgumentParser) -> set[str]:
    """The option strings of ``parser`` that take exactly one value."""
    return {flag for action in parser._actions if action.nargs is None and action.option_strings
            for flag in action.option_strings if flag.startswith("--")}


def _subcommands(parser: argparse.ArgumentParser) -> dict:
    """The subcommands of ``parser`` by name (none: empty)."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def block_option(text: str, option: str = "--block"):
    """The :class:`~shaketable.core.geometry.Block` of ``--block HEIGHTxWIDTH<unit>``.

    Raises
    ------
    ValueError
        Naming the option and its text: ``--block 0x6in: the height must be positive``.
    """
    from shaketable.core.geometry import Block

    text = str(text)
    try:
        block = Block.parse(text)
    except ValueError as error:
        reason, prefix = str(error), f"block size {text!r}"
        reason = reason[len(prefix):].lstrip(":; ") if reason.startswith(prefix) else reason
        raise ValueError(f"{option} {text}: {reason}") from None
    if block.width > block.height:
        note(wider_than_tall(text, block, option))
    return block


def note(text: str) -> None:
    """One line on stderr about an input that is accepted but looks like a slip."""
    import sys

    print(f"shaketable: note: {text}", file=sys.stderr, flush=True)


def wider_than_tall(text: str, block, option: str = "--block") -> str:
    """What to say of a block given wider than tall (``6x30in``): the order is height x
    width (as the report writes blocks), so the user may have meant the other order."""
    import math

    ratio = f"B/H = {block.width / block.height:.3g}, alpha = {math.degrees(block.alpha):.1f} deg"
    # the parsed block's label: "6 x 30 in", or "6 ft x 30 in" with a unit each
    height, _, width = block.describe().partition(" x ")
    width, _, unit = width.partition(" ")
    height, _, height_unit = height.partition(" ")
    if not (height and width and unit):
        return f"{option} {text} is wider than tall ({ratio}); the order is height x width"
    swapped = (f"{width}{unit} x {height}{height_unit}" if height_unit
               else f"{width}x{height}{unit}")
    return (f"{option} {text} is {height} {height_unit or unit} tall and {width} {unit} "
            f"wide ({ratio}); the order is height x width: did you mean {swapped}?")


def add_quantity(parser, *flags: str, kind: str, example: str, help: str, **kwargs: Any) -> None:
    """Add a dimensional option: ``help`` gains the unit rule and an example (``8s``);
    ``positive=True`` refuses a value of zero or below (:class:`Quantity`)."""
    metavar = kwargs.pop("metavar", None) or kind.upper().replace(" ", "_")
    parser.add_argument(*flags, action=Quantity, kind=kind, metavar=metavar,
                        help=f"{help}, with its unit (e.g. {example})", **kwargs)


#: ``--pulse`` shapes: the two of :mod:`shaketable.ground.generators` (as scenes write them)
#: and those of :mod:`shaketable.ground.pulses` (as ``shaketable spectrum`` names them).
GENERATED_PULSES = ("half-sine", "constant")


def add_motion_options(parser) -> None:
    """``--harmonic`` and ``--pulse``: a table motion given on the command line."""
    parser.add_argument("--harmonic", metavar="FREQUENCY,AMPLITUDE[,VERTICAL]",
                        help="harmonic table motion, each value with its unit: 2Hz,0.5g "
                             "(horizontal), or 2Hz,0.5g,0.3g with a vertical amplitude in "
                             "phase; it lasts --duration")
    parser.add_argument("--pulse", metavar="SHAPE,AMPLITUDE,LENGTH",
                        help="one pulse of table acceleration, then none: half-sine,0.5g,0.2s "
                             "(a half sine lasting 0.2 s), constant,0.3g,0.5s, or one-sine, "
                             "one-cosine, ricker, type-C1... with their whole length; the run "
                             "lasts --duration")


def friction_argument(text: str) -> float:
    """A ``--mu`` value: a bare number [-] (the range is checked with the other inputs)."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{text!r}: give the friction coefficient as a number [-], e.g. 0.6 (not a "
            "percentage, no unit)") from None


def add_mass_options(parser) -> None:
    """``--masses`` and ``--densities``: the masses of a column of blocks (``--stack``), as
    ``simulate`` and ``animate`` take them
    (:func:`shaketable.scenes.stack.stack_from_text` reads them)."""
    parser.add_argument("--masses", metavar="MASS,MASS[,...]",
                        help="each block's mass with its unit, bottom first (e.g. 400kg,200kg); "
                             "default: concrete, 2400 kg/m^3 over 1 m of depth (forces and "
                             "energies per metre of depth)")
    parser.add_argument("--densities", metavar="DENSITY,...",
                        help="each block's density with its unit, bottom first (e.g. "
                             "2400kg/m3,7800kg/m3; over 1 m of depth each); default: "
                             "concrete, 2400 kg/m^3 over 1 m of depth")


def _values(option: str, text: str, kinds: tuple, example: str) -> list:
    """The comma-separated values of ``option``, each read with its unit."""
    parts = [part.strip() for part in str(text).split(",")]
    required = sum(1 for kind in kinds if not kind.endswith("?"))
    if not required <= len(parts) <= len(kinds):
        raise ValueError(f"{option} {text!r}: give {required}"
                         f"{'' if required == len(kinds) else f' or {len(kinds)}'} values "
                         f"separated by commas, e.g. {example}")
    return [parse(part, kind.rstrip("?"), where=f"{option} {text!r}")
            for part, kind in zip(parts, kinds)]


def motion_from_options(args):
    """The table motion of ``--harmonic`` or ``--pulse`` [m/s^2], or ``None`` for neither.

    Raises
    ------
    ValueError
        Both options, one with ``--record``, a missing ``--duration``, a value without
        its unit or out of range; the message names the option.
    """
    given = [name for name in ("record", "harmonic", "pulse") if getattr(args, name, None)]
    if len(given) > 1:
        raise ValueError(f"give one table motion: --{given[0]} or --{given[1]}, not both")
    if not given or given[0] == "record":
        return None
    option = f"--{given[0]}"
    if getattr(args, "duration", None) is None:
        raise ValueError(f"{option} needs --duration, the length of the run (e.g. 8s)")
    from shaketable.ground import generators

    duration = args.duration
    if option == "--harmonic":
        frequency, horizontal, *vertical = _values(
            option, args.harmonic, ("frequency", "acceleration", "acceleration?"), "2Hz,0.5g")
        try:
            return generators.harmonic(frequency, horizontal=horizontal,
                                       vertical=vertical[0] if vertical else 0.0,
                                       duration=duration)
        except ValueError as error:
            raise ValueError(f"{option} {args.harmonic!r}: {error}") from None
    shape, _, rest = str(args.pulse).partition(",")
    shape = shape.strip()
    try:
        amplitude, length = _values(option, rest, ("acceleration", "time"),
                                    "half-sine,0.5g,0.2s")
    except ValueError as error:
        raise ValueError(str(error).replace(f"{option} {rest!r}", f"{option} {args.pulse!r}")) \
            from None
    try:
        if shape.lower() == "half-sine":
            return generators.half_sine_pulse(amplitude=abs(amplitude), pulse_duration=length,
                                              duration=duration, sign=-1 if amplitude < 0 else 1)
        if shape.lower() == "constant":
            return generators.constant_pulse(acceleration=amplitude, pulse_duration=length,
                                             duration=duration)
        from shaketable.core.validation import positive
        from shaketable.ground.pulses import Pulse, pulse_motion

        length = positive("the pulse length", length, " [s]")
        unit = Pulse(shape, 1.0)  # its length at omega = 1 rad/s: omega from the length
        form = Pulse(shape, unit.duration / length)
        if length > duration:
            raise ValueError(f"the pulse ({length:g} s) is longer than --duration "
                             f"({duration:g} s)")
        import numpy as np

        from shaketable.core.motion import Motion

        shaped = pulse_motion(form, amplitude, samples_per_cycle=2048)
        # then the table at rest: a drop to zero within a millionth of the pulse (a pulse
        # ending at a nonzero value, one-cosine or type-Cn) and samples every 10 ms
        tail = np.unique(np.concatenate([[form.duration * (1 + 1e-6)],
                                         np.arange(form.duration + 0.01, duration, 0.01),
                                         [duration]]))
        tail = tail[tail > form.duration * (1 + 1e-7)]
        words = ", ".join(part.strip() for part in rest.split(","))
        return Motion(np.concatenate([shaped.t, tail]),
                      np.concatenate([shaped.horizontal, np.zeros(tail.size)]),
                      name=f"{shape} pulse {words}")
    except ValueError as error:
        raise ValueError(f"{option} {args.pulse!r}: {error}") from None
