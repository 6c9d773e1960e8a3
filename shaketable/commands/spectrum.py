"""``shaketable spectrum``: overturning spectrum of pulses (every overturn/safe band)."""

from __future__ import annotations

# the readers of one block's spectrum options, here as before (commands.block holds them)
from shaketable.commands.block import (  # noqa: F401
    BLOCK_SCAN_STEP,
    OPTIONS,
    block_of,
    cor_of,
)

# one reader of omega/p values and of (alpha, p) for the command and the scene kind
from shaketable.scenes.spectrum import MAX_RATIOS, block_from, parse_ratios  # noqa: F401


def _spectrum(args) -> int:
    # the model of the options given (--block or --alpha and --p, --stack) computes it
    from shaketable.commands.simulate import chosen_command

    command, _ = chosen_command(args)
    return command.spectrum(args)


def register(commands) -> None:
    """Add the ``spectrum`` subcommand to an argparse subparsers object."""
    from shaketable.commands.options import add_quantity

    spec = commands.add_parser(
        "spectrum", help="overturning spectrum of pulses: every overturn/safe band, CSV and figure",
        description="Every overturn/safe band edge in a/(g tan alpha) of a block under pulses, "
                    "over omega/p (shaketable.studies.overturning_spectrum).")
    spec.add_argument("--block", help="HEIGHTxWIDTH with unit, e.g. 16x4ft")
    spec.add_argument("--stack", metavar="SIZE,SIZE[,...]",
                      help="a column of blocks from the bottom up (e.g. 8x2ft,8x2ft; "
                           "--masses as for simulate): every overturn/safe band of "
                           "half-sine pulses of the stack and of its bottom block alone "
                           "(a scan of --scan-step, each edge bisected --iterations times; "
                           "which block falls first in each band), beside Eq. (2-8) for "
                           "each as one rigid body")
    spec.add_argument("--masses", metavar="MASS,MASS[,...]",
                      help="with --stack: each block's mass with its unit, bottom first")
    spec.add_argument("--iterations", type=int, default=5,
                      help="with --stack: bisections of each band edge (default 5)")
    add_quantity(spec, "--alpha", kind="angle", example="0.25rad", positive=True,
                 help="block angle alpha (with --p)")
    add_quantity(spec, "--p", kind="angular frequency", example="2rad/s", positive=True,
                 help="frequency parameter p (with --alpha)")
    spec.add_argument("--cor", default="housner",
                      help="coefficient of restitution [0-1] or 'housner' (1 - 1.5 sin^2 alpha)")
    spec.add_argument("--pulse", action="append",
                      help="half-sine, one-sine, one-cosine, type-A, type-B, type-C1, ..., ricker "
                           "(repeat for several; default half-sine)")
    spec.add_argument("--ratios", default="1,2,3,4,6,8,10",
                      help="omega/p values: 1,2,4 or start:stop:step (default 1,2,3,4,6,8,10)")
    spec.add_argument("--ceiling", type=float, help="largest a/(g tan alpha) examined [-]")
    spec.add_argument("--scan-step", type=float, default=None,
                      help="relative scan step [-] (default 0.005; with --stack 0.02)")
    spec.add_argument("--tolerance", type=float, default=1e-8,
                      help="relative width of each band edge [-]")
    spec.add_argument("--method", default="fast", choices=["fast", "linear", "predictor-corrector"],
                      help="solver: fast (exact Eq. 2-13, default), linear (Housner's linearised "
                           "Eq. 2-4, the closed forms' model) or predictor-corrector")
    spec.add_argument("--compare-linear", action="store_true",
                      help="also compute the linearised spectrum (spectrum-linear.csv) and "
                           "outline its overturning bands on the figure")
    spec.add_argument("--parquet", action="store_true", help="also write spectrum.parquet")
    spec.add_argument("--format", default="png", choices=["png", "svg", "pdf"])
    spec.add_argument("--out", default="shaketable-out", help="output folder")
    spec.set_defaults(handler=_spectrum)
