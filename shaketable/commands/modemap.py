"""``shaketable modemap --block 2x0.5m --record NAME``: rock, slide or anchor, for your block.

The planar block's mode map (:func:`shaketable.studies.mode_map.mode_map`, the study of
the bundled ``mode-map-pacoima`` scene) at the user's block height, over B/H (the user's
block among them) and friction, under the user's record; and the largest friction at
which the user's block only slides (:func:`~shaketable.studies.mode_map.sliding_limit`)
beside Section 2.1's rule mu_s = B/H.
"""

from __future__ import annotations

import json
import math

from shaketable.commands.common import add_record_arguments, load_motion, scaled_record

#: The map's B/H columns when none are given (those of the bundled scene).
DEFAULT_RATIOS = (0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5)


def _numbers(option: str, text: str) -> tuple[float, ...]:
    """A list ``0.1,0.2`` or ``start:stop:step`` (stop included) of positive numbers."""
    from shaketable.scenes.mode_map import grid_numbers

    value: object = text if text.count(":") == 2 else []
    if text.count(":") != 2:
        try:
            value = [float(part) for part in text.split(",")]
        except ValueError:
            raise ValueError(f"{option} {text!r}: give numbers separated by commas or "
                             "start:stop:step") from None
    try:
        return grid_numbers(value, "command line", option.lstrip("-"), 0.0, 10.0)
    except ValueError as error:
        raise ValueError(f"{option}: {error}") from None


def _cropped(motion, duration):
    """The motion up to ``duration`` [s] (None: all of it)."""
    if duration is None:
        return motion
    from shaketable.core.motion import Motion

    keep = motion.t <= motion.t[0] + duration + 1e-12
    return Motion(motion.t[keep], motion.horizontal[keep],
                  None if motion.vertical is None else motion.vertical[keep],
                  name=motion.name)


def _modemap(args) -> int:
    from shaketable.commands.common import notice_first_compile
    from shaketable.commands.options import block_option
    from shaketable.core.constants import G
    from shaketable.core.files import prepare_output_folder, write_csv, write_text
    from shaketable.core.units import format_length
    from shaketable.core.validation import number
    from shaketable.plots.base import save
    from shaketable.studies.mode_map import mode_map, sliding_limit

    block = block_option(args.block)
    if block.rods is not None:
        raise ValueError("--block: the planar model has no prestress rods")
    cor = number("--cor", args.cor)
    if not 0 <= cor <= 1:
        raise ValueError(f"--cor must be in [0, 1], got {args.cor!r}")
    if not args.record:
        raise ValueError("--record is required: a bundled name (shaketable records) or a file")
    motion, scale_note = scaled_record(load_motion(args), args)
    motion = _cropped(motion, args.duration)
    ratio = block.width / block.height
    ratios = _numbers("--aspect-ratios", args.aspect_ratios) if args.aspect_ratios \
        else DEFAULT_RATIOS
    ratios = tuple(sorted(set(ratios) | {round(ratio, 12)}))
    frictions = _numbers("--frictions", args.frictions)
    out = prepare_output_folder(args.out)
    notice_first_compile(args.quiet, which=("planar", "engine"))
    result = mode_map(motion, aspect_ratios=ratios, frictions=frictions, height=block.height,
                      cor=cor)
    limit = sliding_limit(block, motion, cor=cor, tolerance=args.tolerance)
    frame = result.to_frame()
    mine = frame[(frame["B/H [-]"] - round(ratio, 12)).abs() < 1e-12]
    pga = float(frame["pga [g]"].iloc[0])
    # the answer: the user's block, its sliding limit and its mode at each friction
    print(f"{block.describe()} block (B/H {ratio:.4g}) under {motion.name}, PGA {pga:.3g} g, "
          f"COR {cor:g}:")
    if math.isnan(limit):
        print("  it only slides at every friction up to 1.5: this record never lifts a "
              "corner (it never rocks)")
    else:
        print(f"  only slides up to mu = {limit:.4f} (bisection to {args.tolerance:g}); "
              f"Section 2.1's rule says mu_s = B/H = {ratio:.4f} "
              f"(difference {limit - ratio:+.1e})")
    print("  at mu_s = mu_d: " + ", ".join(f"{row['mu [-]']:g} {row['verdict']}"
                                            for _, row in mine.iterrows()))
    counts = result.counts().iloc[0]
    print(f"map: {len(ratios)} B/H x {len(frictions)} mu = {len(frame)} planar runs at "
          f"H = {format_length(block.height, block.length_unit)}; below the rule's "
          f"line {int(counts['rule slides: only slid'])} of {int(counts['rule slides'])} "
          f"blocks only slid; above it {int(counts['rule rocks: slide-rocked'])} of "
          f"{int(counts['rule rocks'])} slide-rocked")
    if scale_note:
        print(scale_note)
    write_csv(out / "mode_map.csv", frame)
    summary = {"block": block.describe(), "B/H [-]": ratio, "record": motion.name,
               "pga [g]": pga, "record pga [g]": motion.pga / G, "cor [-]": cor,
               "largest mu that only slides [-]": None if math.isnan(limit) else limit,
               "verdicts": {f"{row['mu [-]']:g}": row["verdict"] for _, row in mine.iterrows()}}
    write_text(out / "summary.json", json.dumps(summary, indent=2) + "\n")
    save(result.plot(block=block), out / f"mode_map.{args.format}")
    print(f"wrote {out / 'mode_map.csv'}, {out / 'summary.json'}, "
          f"{out / ('mode_map.' + args.format)}")
    return 0


def register(commands) -> None:
    """Add the ``modemap`` subcommand."""
    from shaketable.commands.options import add_quantity

    parser = commands.add_parser(
        "modemap", help="rock, slide or anchor: the planar block's mode map for your block "
                        "and record",
        description="Run the planar block (rest, slide, rock, slide-rock, flight) at your "
                    "block's height over B/H (yours among them) and friction mu_s = mu_d under "
                    "your record; print the largest friction at which your block only slides "
                    "beside Section 2.1's rule mu_s = B/H, and its mode at each friction; "
                    "write the map (CSV, figure) and a summary.json.")
    parser.add_argument("--block", required=True, help="block size, height x width, e.g. 2x0.5m")
    add_record_arguments(parser)
    parser.add_argument("--cor", default=0.95, type=float,
                        help="coefficient of restitution [0-1] (default 0.95)")
    parser.add_argument("--frictions", default="0.05:0.8:0.05", metavar="LIST|START:STOP:STEP",
                        help="mu_s = mu_d of the map (default 0.05:0.8:0.05)")
    parser.add_argument("--aspect-ratios", metavar="LIST|START:STOP:STEP",
                        help="B/H of the map's columns (default 0.15,0.2,0.25,0.3,0.35,0.4,0.5; "
                             "your block's is always added)")
    add_quantity(parser, "--duration", kind="time", example="10s", positive=True,
                 help="use the record up to this time (default all of it)")
    parser.add_argument("--tolerance", type=float, default=1e-4,
                        help="width of the sliding limit's bisection bracket [-] (default 1e-4)")
    parser.add_argument("--format", default="png", choices=["png", "svg", "pdf"])
    parser.add_argument("--out", default="shaketable-out/modemap", help="output folder")
    parser.set_defaults(handler=_modemap)
