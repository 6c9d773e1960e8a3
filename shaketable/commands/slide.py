"""``shaketable slide``: the sliding mode -- one run, a sweep over mu_d, or Table 4.4."""

from __future__ import annotations

import json

from shaketable.commands.common import add_record_arguments, load_motion, scaled_record


def _slide(args) -> int:
    from shaketable.commands.checks import check_slide_options
    from shaketable.core.files import prepare_output_folder, write_csv, write_text
    from shaketable.models.sliding.engine import peak_slips, slide
    from shaketable.models.sliding.result import Friction
    from shaketable.plots.base import save

    check_slide_options(args)   # options the chosen mode would ignore: refused
    from shaketable.commands.options import block_option

    block = block_option(args.block) if args.block else None   # before the output folder
    motion = scale_note = None
    if not args.table_4_4:   # the record and the frictions too: a refusal leaves no folder
        if not args.record:
            raise ValueError("--record is required (or give --table-4-4)")
        _check_frictions(args, Friction)
        motion, scale_note = scaled_record(load_motion(args), args)
    out = prepare_output_folder(args.out)
    if args.table_4_4:
        from shaketable.studies.sliding import table_4_4, table_4_4_markdown

        frame = table_4_4(seed=args.seed)
        write_csv(out / "table_4_4.csv", frame)
        write_text(out / "table_4_4.md", table_4_4_markdown(frame))
        print(table_4_4_markdown(frame))
        print(f"wrote {out / 'table_4_4.csv'} and {out / 'table_4_4.md'}")
        return 0
    assert motion is not None   # read above: a run on a record
    if args.sweep:
        frame = peak_slips(motion, args.sweep)
        write_csv(out / "sweep.csv", frame)
        print(frame[["mu_d [-]", "peak slip [in]", "residual slip [m]"]].to_string(index=False))
        if scale_note:
            print(scale_note)
        print(f"wrote {out / 'sweep.csv'}")
        return 0
    static = args.static_friction
    dynamic = args.dynamic_friction if args.dynamic_friction is not None else static
    result = slide(motion, Friction(static, dynamic), block=block)
    write_csv(out / "history.csv", result.to_frame())
    write_text(out / "summary.json", json.dumps(result.summary(), indent=2))
    from shaketable.core.units import format_length, shared_length_unit

    # in the unit the block was given in; SI without a block (no length was typed)
    unit = shared_length_unit((result.peak_slip, result.residual_slip),
                              block.length_unit if block is not None else "m")
    save(result.plot(length_unit=block.length_unit if block is not None else "m"),
         out / f"sliding.{args.format}")
    print(f"{result.status}: peak slip {format_length(result.peak_slip, unit)}, residual "
          f"{format_length(result.residual_slip, unit, signed=True)}, "
          f"{result.slip_episodes} slip episodes")
    if scale_note:
        print(scale_note)
    if block is not None:
        print(f"Section 2.1: {result.mode_choice['mode (Section 2.1)']} "
              f"(B/H = {result.mode_choice['B/H [-]']:.3f}, mu_s = {static:g})")
    print(f"wrote {out / 'history.csv'}, {out / 'summary.json'}, "
          f"{out / f'sliding.{args.format}'}")
    return 0


def _check_frictions(args, friction) -> None:
    """The coefficients of ``--sweep`` or of ``--static-friction`` and
    ``--dynamic-friction``, checked as ``friction`` (the run's class) checks them, the
    option named."""
    if args.sweep:
        for mu in args.sweep:
            try:
                friction(mu, mu)
            except ValueError as error:
                raise ValueError(f"--sweep {mu:g}: {error}") from None
        return
    static = args.static_friction
    dynamic = args.dynamic_friction if args.dynamic_friction is not None else static
    try:
        friction(static, dynamic)
    except ValueError as error:
        raise ValueError(f"--static-friction {static:g}, --dynamic-friction {dynamic:g}: "
                         f"{error}") from None


def register(commands) -> None:
    """Add the ``slide`` subcommand to an argparse subparsers object."""
    sub = commands.add_parser(
        "slide", help="sliding block (Coulomb stick-slip): one run, a mu_d sweep, or Table 4.4",
        description="Sliding mode of Section 2.1 / 4.5: peak and residual slip under a record.")
    add_record_arguments(sub)
    sub.add_argument("--static-friction", type=float, default=0.2, help="mu_s [-]")
    sub.add_argument("--dynamic-friction", type=float, help="mu_d [-] (default mu_s)")
    sub.add_argument("--block", help="HEIGHTxWIDTH with unit: adds the Section 2.1 mode choice")
    sub.add_argument("--sweep", type=float, nargs="+", metavar="MU_D",
                     help="peak slip for each mu_d (mu_s = mu_d)")
    sub.add_argument("--table-4-4", action="store_true", help="recompute Table 4.4")
    sub.add_argument("--seed", type=int, default=1, help="seed of the substitute records")
    sub.add_argument("--format", default="png", choices=["png", "svg", "pdf"])
    sub.add_argument("--out", default="shaketable-out", help="output folder")
    sub.set_defaults(handler=_slide)
