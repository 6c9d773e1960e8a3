"""``shaketable calibrate RECORD --block 30x6in``: the COR of a free-rocking record."""

from __future__ import annotations

from pathlib import Path


def _anti_alias(text: str, record, order):
    """The ``--anti-alias`` value: 'fit', 'none' or a cutoff in Hz (a known filter)."""
    from shaketable.core.units import parse
    from shaketable.lab.digitizer import Digitizer

    key = text.strip().lower()
    if key in ("fit", "none"):
        return key
    try:
        cutoff = parse(text, "frequency", where="--anti-alias")
    except ValueError:
        raise ValueError(f"--anti-alias {text!r}: give 'fit', 'none' or the cutoff with its "
                         "unit, e.g. 20Hz") from None
    return Digitizer(rate=record.rate, cutoff=cutoff, filter_order=4 if order == "auto"
                     else int(order))


def _filter_order(text: str):
    key = text.strip().lower()
    if key == "auto":
        return key
    try:
        return int(key)
    except ValueError:
        raise ValueError(f"--filter-order {text!r}: give 'auto' or a number of poles 1-8") \
            from None


def _column(text: str | None) -> str | int | None:
    """A --column / --time-column value: a 0-based index if it is an integer, else a name."""
    if text is not None and text.strip().lstrip("-").isdigit():
        return int(text)
    return text


def bundled_free_rocking() -> dict:
    """Bundled free-rocking records: name -> path (``shaketable/data/free_rocking``)."""
    from importlib.resources import files

    folder = Path(str(files("shaketable.data.free_rocking")))
    return {path.stem: path for path in sorted(folder.glob("*.csv"))}


def _record_path(text: str) -> Path:
    """A record file, or the name of a bundled free-rocking record."""
    path = Path(text)
    bundled = bundled_free_rocking()
    if not path.exists() and text in bundled:
        return bundled[text]
    return path


def _calibrate(args) -> int:
    from shaketable.calibration.fit import calibrate
    from shaketable.calibration.record import read_record
    from shaketable.commands.options import block_option
    from shaketable.core.files import prepare_output_folder, write_csv
    from shaketable.core.units import parse
    from shaketable.plots.base import save

    block = block_option(args.block)
    height = None
    if args.height is not None:
        height = parse(args.height, "length", where="--height")
    record = read_record(_record_path(args.record), column=_column(args.column),
                         units=args.units, rate=args.rate, height=height,
                         time_column=_column(args.time_column))
    order = _filter_order(args.filter_order)
    from shaketable.commands.common import notice_first_compile

    notice_first_compile(args.quiet)
    anti_alias = _anti_alias(args.anti_alias, record, order)
    # the output folder is checked before the fit (the expensive part), after the inputs
    out = prepare_output_folder(args.out or Path("shaketable-out")
                                / f"calibrate-{Path(args.record).stem}")
    result = calibrate(record, block, anti_alias=anti_alias,
                       filter_order=order if anti_alias == "fit" else "auto",
                       bootstrap=args.bootstrap, seed=args.seed, interval=args.interval)
    figure = result.plot(title=f"COR calibration: {record.name}, {block.describe()} block")
    save(figure, out / "calibration.png", dpi=120)
    result.to_json(out / "calibration.json")
    write_csv(out / "calibration.csv", result.to_frame())
    print(f"{record.name}: {block.describe()} block, {record.t.size} samples at "
          f"{record.rate:.4g} samples/s")
    print(result.text())
    print("wrote " + ", ".join(str(out / name) for name in
                               ("calibration.png", "calibration.json", "calibration.csv")))
    return 0


def cor_argument(text: str) -> float | str:
    """A ``--cor`` value: a number, or the path of a ``calibration.json``."""
    import argparse

    try:
        return float(text)
    except ValueError:
        if text.strip().lower().endswith(".json") or Path(text).is_file():
            return text
        raise argparse.ArgumentTypeError(
            f"{text!r}: give a number in [0, 1] or the path of a calibration.json of "
            "`shaketable calibrate`") from None


def simulate_calibrated(args, block, motion, theta0: float, out: Path) -> int:
    """``shaketable simulate --cor calibration.json``: the run over the calibrated COR.

    With a ``--record``: an ensemble of ``--ensemble`` members (default 200), each with
    a COR drawn from the calibration (:func:`shaketable.calibration.uncertainty.calibrated_ensemble`),
    reporting P(overturn) and max theta/alpha with their intervals. Free rocking (no
    record) cannot overturn from theta0 < alpha: one run with the calibrated COR.
    """
    import json

    from shaketable.calibration.uncertainty import CalibratedCor, calibrated_ensemble
    from shaketable.core.files import json_ready_dict, write_csv, write_text
    from shaketable.plots import base as plots

    try:
        cor = CalibratedCor.from_json(args.cor)
    except (OSError, ValueError) as error:
        raise ValueError(f"--cor {args.cor}: {error}") from None
    print(f"{block.describe()} block, calibrated {cor.describe()}")
    mismatch = cor.size_mismatch(block)
    if mismatch is not None:   # said once here, not again as a Python warning
        import sys

        print(f"shaketable simulate: warning: {mismatch}", file=sys.stderr)
    if motion is None:
        from shaketable.models.api import simulate
        from shaketable.models.stops import stop_summary

        run = simulate(block, None, cor=cor.mean, theta0=theta0, duration=args.duration,
                          method=args.method, subdivisions=args.subdivisions)
        write_csv(out / "history.csv", run.to_frame())
        write_text(out / "summary.json", json.dumps(json_ready_dict(stop_summary(run)),
                                                    indent=2))
        from shaketable.commands.answers import rocking_answer, rocking_heading

        print(f"free rocking with the mean COR {cor.mean:.4f}: {rocking_heading(run)}")
        for line in rocking_answer(run):
            print("  " + line)
        print(f"wrote {out / 'history.csv'}, {out / 'summary.json'}")
        return 0
    members = args.ensemble if args.ensemble else 200
    import warnings

    from shaketable.calibration.uncertainty import CalibrationMismatchWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CalibrationMismatchWarning)
        ensemble = calibrated_ensemble(block, motion, cor, members=members, seed=args.seed,
                                       duration=args.duration, method=args.method)
    write_csv(out / "ensemble.csv", ensemble.to_frame())
    write_text(out / "ensemble.json", json.dumps(json_ready_dict(ensemble.summary), indent=2,
                                                 default=float))
    plots.save(ensemble.plot().figure, out / f"ensemble.{args.format}")
    print(ensemble.describe())
    print(f"wrote {out / 'ensemble.csv'}, {out / 'ensemble.json'}, "
          f"{out / ('ensemble.' + args.format)}")
    from shaketable.commands.checks import report_stopped_rows

    return report_stopped_rows(ensemble.to_frame(), f"{block.describe()} block", "simulate")


def register(commands) -> None:
    """Add the ``calibrate`` subcommand."""
    from shaketable.commands.options import add_quantity

    # argparse %-formats the help= strings of arguments (a literal percent is written %%
    # there) but prints description= as it is
    parser = commands.add_parser(
        "calibrate", help="coefficient of restitution of a free-rocking record, with interval",
        description="Identify the COR, release angle, release time and sensor offset of a "
                    "free-rocking record by least squares with the engine in the loop; print "
                    "the COR with its 95 % interval, write the fit figure, a JSON (with the "
                    "interval) and a CSV.")
    parser.add_argument("record", help="CSV file with a header (a 'time [s]' column, or "
                                       "--rate), or a plain-text table, headerless or "
                                       "whitespace-separated (then give --units); or "
                                       "the name of a bundled free-rocking record: "
                                       "virtual-fig-3-4 (a virtual Fig. 3.4 test, true "
                                       "COR 0.925)")
    parser.add_argument("--block", required=True, help="block size, height x width, e.g. 30x6in")
    parser.add_argument("--column", help="the measured column, by name or 0-based index "
                                         "(default: the only non-time one)")
    parser.add_argument("--time-column", help="the time column, by name or 0-based index "
                                              "(default: the column named time, t, Zeit... "
                                              "in s, ms or us as its header says)")
    parser.add_argument("--units", help="unit of the column: rad, deg, mrad (angle) or m, cm, "
                                        "mm, in, ft (top displacement); default from '[unit]' "
                                        "in its name (a contradicting --units is refused)")
    add_quantity(parser, "--rate", kind="frequency", example="50Hz", positive=True,
                 help="sampling rate (samples per second), without a time column")
    parser.add_argument("--height", help="height of the potentiometer wire, e.g. '30 in' "
                                         "(default: the block's height)")
    parser.add_argument("--anti-alias", default="fit", metavar="fit|none|FREQUENCY",
                        help="the acquisition's anti-alias filter in the model: 'fit' "
                             "(default: a Butterworth low-pass whose cutoff is fitted), "
                             "'none' (a record known to be unfiltered) or the known cutoff "
                             "of a Butterworth filter of --filter-order poles, with its unit (e.g. 20Hz)")
    parser.add_argument("--filter-order", default="auto", metavar="auto|N",
                        help="poles of that filter (default auto: 1, 2, 4 and 8 are fitted "
                             "and the best kept; 4 for a known cutoff)")
    parser.add_argument("--interval", choices=("acf", "hac", "iid"), default="acf",
                        help="covariance of the 95 %% interval (default acf: the residuals' "
                             "autocovariance, stationary noise; hac: Newey-West; iid)")
    parser.add_argument("--bootstrap", type=int, default=0, metavar="N",
                        help="moving-block bootstrap refits for the interval (default 0)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the bootstrap")
    parser.add_argument("--out", help="output folder (default shaketable-out/calibrate-<name>)")
    parser.set_defaults(handler=_calibrate)
