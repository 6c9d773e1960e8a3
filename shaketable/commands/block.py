"""The rocking model's commands beyond ``simulate``: one block drawn (``animate --block``)
and its overturning spectrum (``spectrum --block``), the bodies of
:class:`shaketable.commands.simulate_models.RockingCommand`'s ``animate`` and ``spectrum``
(as :mod:`shaketable.commands.stack` holds the stack model's), and the readers of one
block's options they share with ``simulate``."""

from __future__ import annotations

import math
import time

from shaketable.core.constants import INCH
from shaketable.core.geometry import Block
from shaketable.core.units import parse_angle_or_ratio
from shaketable.scenes.spectrum import block_from, parse_ratios


def resolve_angle(text: str, block: Block) -> float:
    """``--theta0`` [rad]: rad, deg, a multiple of the block's alpha, or a bare zero
    (:func:`shaketable.core.units.parse_angle_or_ratio`)."""
    try:
        theta0 = parse_angle_or_ratio(text, block.alpha, where="--theta0")
    except ValueError:
        raise ValueError(f"--theta0 {text!r}: give a number with a unit, e.g. 0.05rad, 3deg "
                         "or 0.5alpha") from None
    if not abs(theta0) < math.pi / 2:   # on its side or beyond: no release at all
        raise ValueError(f"--theta0 {text}: the tilt must be below 90 deg (pi/2 rad) either "
                         f"way, got {math.degrees(theta0):.4g} deg")
    if abs(theta0) > block.alpha:   # past the tipping angle: the block falls by statics
        from shaketable.commands.options import note

        note(f"--theta0 {text} is past alpha (theta0/alpha = {theta0 / block.alpha:.3g}, "
             f"alpha = {block.alpha:.4g} rad): released there the block falls at once, by "
             "statics (it rocks back only from |theta0| < alpha)")
    return theta0


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


#: ``spectrum --block``'s default relative scan step.
BLOCK_SCAN_STEP = 0.005

#: The parameters of the spectrum functions and the options that give them.
OPTIONS = {"cor": "--cor", "scan_step": "--scan-step", "tolerance": "--tolerance",
           "ceiling": "--ceiling", "alpha": "--alpha", "p": "--p", "method": "--method",
           "unknown pulse kind": "--pulse: unknown pulse kind"}


def block_spectrum(args) -> int:
    """``spectrum --block`` (or ``--alpha`` and ``--p``): every overturn/safe band of one
    block (the rocking model's ``spectrum``:
    :meth:`shaketable.commands.simulate_models.RockingCommand.spectrum`)."""
    from shaketable.commands.checks import with_option_names
    from shaketable.commands.common import notice_first_compile
    from shaketable.core.files import atomic_write, prepare_output_folder, write_parquet
    from shaketable.ground.pulses import Pulse
    from shaketable.plots import base as plots
    from shaketable.studies.overturning_spectrum import check_scan, overturning_spectrum

    if args.compare_linear and args.method == "linear":
        raise ValueError("--compare-linear cannot be used with --method linear: the spectrum "
                         "is the linearised one already; leave out --compare-linear")
    try:
        block = block_of(args.block, args.alpha, args.p)
    except ValueError as error:
        raise with_option_names(error, OPTIONS) from None
    cor_of(args.cor)
    parse_ratios(args.ratios)
    try:   # the pulse names too, before the output folder
        for kind in args.pulse or ["half-sine"]:
            Pulse(kind, 1.0)
    except ValueError as error:
        raise with_option_names(error, OPTIONS) from None
    scan_step = BLOCK_SCAN_STEP if args.scan_step is None else args.scan_step
    try:   # the scan's parameters too, before the output folder
        check_scan(parse_ratios(args.ratios), scan_step, args.tolerance, args.ceiling)
    except ValueError as error:
        raise with_option_names(error, OPTIONS) from None
    out = prepare_output_folder(args.out)
    notice_first_compile(args.quiet, which=("batch",))
    start = time.perf_counter()
    try:   # the parameters are checked before the first run: name the options
        result = overturning_spectrum(block, pulses=args.pulse or ["half-sine"],
                                      ratios=parse_ratios(args.ratios), cor=cor_of(args.cor),
                                      ceiling=args.ceiling, scan_step=scan_step,
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
                                       ceiling=args.ceiling, scan_step=scan_step,
                                       tolerance=args.tolerance, method="linear")
        written.append(out / "spectrum-linear.csv")
        atomic_write(written[-1], overlay.to_csv)
    ax = result.plot(overlay=overlay)
    written.append(out / f"spectrum.{args.format}")
    plots.save(ax.figure, written[-1])
    bands = result.to_frame()
    # the block as the user gave it: its size, or its alpha and p (the size it implies
    # to 4 significant digits, in inches as Block.describe gives it)
    named = (f"{block.describe()} block (alpha {block.alpha:.6g} rad, p {block.p:.6g} rad/s)"
             if args.block is not None else
             f"block of alpha {block.alpha:.6g} rad, p {block.p:.6g} rad/s (H x B = "
             f"{block.height / INCH:.4g} x {block.width / INCH:.4g} in)")
    print(f"{named}, "
          f"COR {result.cor:.6g}" + ("" if args.method == "fast" else f", method {args.method}")
          + f": {len(bands)} bands, {result.runs} runs, {elapsed:.1f} s")
    for _, row in bands[bands["verdict"] == "overturns"].iterrows():
        print(f"  {row['pulse']:>10} at ω/p = {row['omega/p [-]']:g}: overturns "
              f"{row['how']} for a/(g tan α) from {row['from a/(g tan alpha) [-]']:#.4g} to "
              f"{row['to a/(g tan alpha) [-]']:#.4g}"
              + (" (the ceiling)" if str(row["note"]).endswith("up to the ceiling") else ""))
    if result.flags:
        print(f"  {len(result.flags)} flag(s): windows narrower than the scan cannot be "
              f"excluded there (see {written[0]})")
    print("wrote " + ", ".join(str(path) for path in written))
    return 0


def animate_block(args, size: tuple, wrote) -> int:
    """No scene: one block (``--block``, ``--cor``, ``--theta0``) on the motion of
    ``--harmonic``, ``--pulse`` or ``--record`` (or free rocking), as ``simulate`` reads them
    (the rocking model's ``animate``:
    :meth:`shaketable.commands.simulate_models.RockingCommand.animate`)."""
    from shaketable.commands.checks import refuse_stack_options, report_early_stops
    from shaketable.commands.common import load_motion, notice_first_compile, scaled_record
    from shaketable.commands.options import block_option, motion_from_options
    from shaketable.core.validation import in_range
    from shaketable.models.api import simulate
    from shaketable.plots.animation import animate

    refuse_stack_options(args)
    if args.block is None or args.cor is None:
        raise ValueError("give a scene, or --block and --cor (with --harmonic, --pulse or "
                         "--record, or --theta0 and --duration for free rocking)")
    block = block_option(args.block)
    cor = in_range("--cor", args.cor, 0.0, 1.0)
    motion = motion_from_options(args) or (load_motion(args) if args.record else None)
    motion, scale_note = scaled_record(motion, args)
    if motion is None and args.duration is None:
        raise ValueError("free rocking (no --harmonic, --pulse or --record) needs --duration")
    theta0 = resolve_angle(args.theta0, block)
    notice_first_compile(args.quiet)
    result = simulate(block, motion, cor=cor, theta0=theta0, duration=args.duration)
    written = animate(result, out=args.out, fps=args.fps, speed=args.speed, start=args.start,
                      end=args.end, size=size, dpi=args.dpi, unit=args.unit)
    if scale_note:
        print(scale_note)
    from shaketable.commands.answers import rocking_heading

    print(f"{block.describe()} block, COR {cor:g}: {rocking_heading(result)}")
    wrote(written)
    return report_early_stops([result], "animate", block.describe())
