"""``shaketable calibrate RECORD --block 30x6in``: the COR of a free-rocking record (issue 6)."""

from __future__ import annotations

from pathlib import Path


def _calibrate(args) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..calibrate import calibrate, read_record
    from ..constants import length_factor
    from ..geometry import Block
    from ..sensors import Digitizer

    block = Block.parse(args.block)
    height = None
    if args.height is not None:
        number, _, unit = args.height.strip().partition(" ")
        try:
            height = float(number) * length_factor(unit or "m")
        except ValueError:
            raise ValueError(f"--height {args.height!r}: write a length such as '30 in'") from None
    record = read_record(args.record, column=args.column, units=args.units, rate=args.rate,
                         height=height)
    anti_alias = None
    if args.anti_alias is not None:
        anti_alias = Digitizer(rate=record.rate, cutoff=args.anti_alias,
                               filter_order=args.filter_order)
    result = calibrate(record, block, anti_alias=anti_alias, bootstrap=args.bootstrap,
                       seed=args.seed, interval=args.interval)
    out = Path(args.out) if args.out else Path("shaketable-out") / f"calibrate-{record.name}"
    out.mkdir(parents=True, exist_ok=True)
    figure = result.plot(title=f"COR calibration: {record.name}, {block.describe()} block")
    figure.savefig(out / "calibration.png", dpi=120)
    plt.close(figure)
    result.to_json(out / "calibration.json")
    result.to_frame().to_csv(out / "calibration.csv", index=False)
    print(f"{record.name}: {block.describe()} block, {record.t.size} samples at "
          f"{record.rate:.4g} samples/s")
    print(result.text())
    print("wrote " + ", ".join(str(out / name) for name in
                               ("calibration.png", "calibration.json", "calibration.csv")))
    return 0


def register(commands) -> None:
    """Add the ``calibrate`` subcommand."""
    parser = commands.add_parser(
        "calibrate", help="coefficient of restitution of a free-rocking record, with interval",
        description="Identify the COR, release angle, release time and sensor offset of a "
                    "free-rocking record by least squares with the engine in the loop; print "
                    "the COR with its 95 %% interval, write the fit figure, a JSON and a CSV.")
    parser.add_argument("record", help="CSV file with a header (a 'time [s]' column, or --rate)")
    parser.add_argument("--block", required=True, help="block size, height x width, e.g. 30x6in")
    parser.add_argument("--column", help="the measured column (default: the only non-time one)")
    parser.add_argument("--units", help="unit of the column: rad, deg, mrad (angle) or m, cm, "
                                        "mm, in, ft (top displacement); default from '[unit]' "
                                        "in its name")
    parser.add_argument("--rate", type=float, help="samples per second, without a time column")
    parser.add_argument("--height", help="height of the potentiometer wire, e.g. '30 in' "
                                         "(default: the block's height)")
    parser.add_argument("--anti-alias", type=float, metavar="HZ",
                        help="cutoff of the acquisition's Butterworth anti-alias filter, "
                             "modelled in the fit (default: not modelled)")
    parser.add_argument("--filter-order", type=int, default=4,
                        help="poles of that filter (default 4)")
    parser.add_argument("--interval", choices=("hac", "iid"), default="hac",
                        help="covariance of the interval (default hac: Newey-West)")
    parser.add_argument("--bootstrap", type=int, default=0, metavar="N",
                        help="moving-block bootstrap refits for the interval (default 0)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the bootstrap")
    parser.add_argument("--out", help="output folder (default shaketable-out/calibrate-<name>)")
    parser.set_defaults(handler=_calibrate)
