"""``shaketable spectrum``: overturning spectrum of pulses (every overturn/safe band)."""

from __future__ import annotations

import time

from shaketable.core.geometry import Block

# one reader of omega/p values and of (alpha, p) for the command and the scene kind
from shaketable.scenes.spectrum import MAX_RATIOS, block_from, parse_ratios  # noqa: F401


def block_of(block: str | None, alpha: float | None, p: float | None) -> Block:
    """The block from ``HxW`` with a unit, or from alpha [rad] and p [rad/s]."""
    if block is not None:
        if alpha is not None or p is not None:
            raise ValueError("give either --block or --alpha and --p, not both")
        from shaketable.commands.options import block_option

        return block_option(block)
    if alpha is None or p is None:
        raise ValueError("give --block HxW (e.g. 16x4ft) or both --alpha [rad] and --p [rad/s]")
    if p <= 0:
        raise ValueError(f"--p must be positive [rad/s], got {p!r}")
    return block_from(alpha, p)


def cor_of(text: str):
    """A number or ``housner``."""
    if str(text).lower() == "housner":
        return "housner"
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"--cor {text!r}: give a number in [0, 1] or 'housner'") from None
    if not 0.0 <= value <= 1.0:   # checked here, before the output folder is made
        raise ValueError(f"--cor must be a number in [0, 1] or 'housner', got {text}")
    return value


#: The parameters of the spectrum functions and the options that give them.
OPTIONS = {"cor": "--cor", "scan_step": "--scan-step", "tolerance": "--tolerance",
           "ceiling": "--ceiling", "alpha": "--alpha", "p": "--p", "method": "--method",
           "unknown pulse kind": "--pulse: unknown pulse kind"}


def _spectrum(args) -> int:
    # the model of the options given (--block or --alpha and --p, --stack) computes it
    from shaketable.commands.simulate import chosen_command

    command, _ = chosen_command(args)
    return command.spectrum(args)


def block_spectrum(args) -> int:
    """``spectrum --block`` (or ``--alpha`` and ``--p``): every overturn/safe band of one
    block (the rocking model's ``spectrum``:
    :meth:`shaketable.commands.simulate_models.RockingCommand.spectrum`)."""
    from shaketable.commands.checks import with_option_names
    from shaketable.commands.common import notice_first_compile
    from shaketable.core.files import atomic_write, prepare_output_folder, write_parquet
    from shaketable.plots import base as plots
    from shaketable.studies.overturning_spectrum import overturning_spectrum

    if args.compare_linear and args.method == "linear":
        raise ValueError("--compare-linear cannot be used with --method linear: the spectrum "
                         "is the linearised one already; leave out --compare-linear")
    try:
        block = block_of(args.block, args.alpha, args.p)
    except ValueError as error:
        raise with_option_names(error, OPTIONS) from None
    cor_of(args.cor)
    out = prepare_output_folder(args.out)
    notice_first_compile(args.quiet, which=("batch",))
    start = time.perf_counter()
    try:   # the parameters are checked before the first run: name the options
        result = overturning_spectrum(block, pulses=args.pulse or ["half-sine"],
                                      ratios=parse_ratios(args.ratios), cor=cor_of(args.cor),
                                      ceiling=args.ceiling, scan_step=args.scan_step,
                                      tolerance=args.tolerance, method=args.method)
    except ValueError as error:
        raise with_option_names(error, OPTIONS) from None
    elapsed = time.perf_counter() - start
    written = [out / "spectrum.csv"]
    atomic_write(written[0], result.to_csv)
    if args.parquet:
        written.append(out / "spectrum.parquet")
        write_parquet(written[-1], result.to_frame())
    overlay = None
    if args.compare_linear and args.method != "linear":
        overlay = overturning_spectrum(block, pulses=args.pulse or ["half-sine"],
                                       ratios=parse_ratios(args.ratios), cor=cor_of(args.cor),
                                       ceiling=args.ceiling, scan_step=args.scan_step,
                                       tolerance=args.tolerance, method="linear")
        written.append(out / "spectrum-linear.csv")
        atomic_write(written[-1], overlay.to_csv)
    ax = result.plot(overlay=overlay)
    written.append(out / f"spectrum.{args.format}")
    plots.save(ax.figure, written[-1])
    bands = result.to_frame()
    print(f"{block.describe()} block (alpha {block.alpha:.6g} rad, p {block.p:.6g} rad/s), "
          f"COR {result.cor:.6g}" + ("" if args.method == "fast" else f", method {args.method}")
          + f": {len(bands)} bands, {result.runs} runs, {elapsed:.1f} s")
    for _, row in bands[bands["verdict"] == "overturns"].iterrows():
        print(f"  {row['pulse']:>10} at ω/p = {row['omega/p [-]']:g}: overturns "
              f"{row['how']} for a/(g tan α) from {row['from a/(g tan alpha) [-]']:.7g} to "
              f"{row['to a/(g tan alpha) [-]']:.7g}")
    if result.flags:
        print(f"  {len(result.flags)} flag(s): windows narrower than the scan cannot be "
              f"excluded there (see {written[0]})")
    print("wrote " + ", ".join(str(path) for path in written))
    return 0


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
                           "--masses as for simulate): the smallest overturning half-sine "
                           "of the stack and of its bottom block alone, bisected "
                           "(--iterations), beside Eq. (2-8) for each as one rigid body")
    spec.add_argument("--masses", metavar="MASS,MASS[,...]",
                      help="with --stack: each block's mass with its unit, bottom first")
    spec.add_argument("--iterations", type=int, default=5,
                      help="with --stack: bisections of each amplitude (default 5)")
    add_quantity(spec, "--alpha", kind="angle", example="0.25rad",
                 help="block angle alpha (with --p)")
    add_quantity(spec, "--p", kind="angular frequency", example="2rad/s",
                 help="frequency parameter p (with --alpha)")
    spec.add_argument("--cor", default="housner",
                      help="coefficient of restitution [0-1] or 'housner' (1 - 1.5 sin^2 alpha)")
    spec.add_argument("--pulse", action="append",
                      help="half-sine, one-sine, one-cosine, type-A, type-B, type-C1, ..., ricker "
                           "(repeat for several; default half-sine)")
    spec.add_argument("--ratios", default="1,2,3,4,6,8,10",
                      help="omega/p values: 1,2,4 or start:stop:step (default 1,2,3,4,6,8,10)")
    spec.add_argument("--ceiling", type=float, help="largest a/(g tan alpha) examined [-]")
    spec.add_argument("--scan-step", type=float, default=0.005, help="relative scan step [-]")
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
