"""``shaketable bench``: error against run time of every solver (work-precision study)."""

from __future__ import annotations

from shaketable.bench import run_study


def bench_answer(pacoima: dict | None, accuracy) -> list[str]:
    """The numbers a user runs ``bench`` for, as ``RESULTS.md`` gives them: the fast
    engine's time per run and its speed-up over the reference (``pacoima``, of
    :func:`~shaketable.studies.work_precision.pacoima_timing`), and its largest errors
    against the reference (``accuracy``, of
    :func:`~shaketable.studies.work_precision.accuracy_table`); None: not measured."""
    lines = []
    if pacoima is not None:
        same = pacoima["same as reference"]
        lines.append(
            f"speed (Pacoima Dam S16E + vertical, 16 x 4 ft, COR 0.95): fast "
            f"{pacoima['fast median [ms]']:.3g} ms per run, {pacoima['speed-up [-]']:.0f}x the "
            f"reference ({pacoima['reference median [s]']:.3g} s); "
            + ("same verdict" if same["same verdict"] else "verdicts differ")
            + (f" and impacts ({same['impacts']})" if same["same impacts"]
               else f", impacts {same['impacts']} against {same['impacts truth']}"))
    if accuracy is not None and len(accuracy):
        meets = int(accuracy["meets 1e-8"].sum())
        errors = [f"of {what} {accuracy[column].max():.2g}"
                  for what, column in (("max |θ|", "error max_theta [-]"),
                                       ("the event times", "error events [-]"))
                  if column in accuracy]
        largest = f": largest relative error {', '.join(errors)}" if errors else ""
        lines.append(f"accuracy (fast against the reference at their defaults, "
                     f"{len(accuracy)} cases){largest}; {meets} of {len(accuracy)} within 1e-8 "
                     "(details in RESULTS.md)")
    return lines


def _bench(args) -> int:
    measured: dict = {}
    written = run_study(cases=args.cases, quick=args.quick,
                        repeats=args.repeats if args.repeats else (3 if args.quick else 5),
                        out=args.out, speed=not args.no_speed, planar=not args.no_planar,
                        stack=not args.no_stack, measured=measured)
    for line in bench_answer(measured.get("pacoima"), measured.get("accuracy")):
        print(line)
    print("wrote " + ", ".join(str(path) for path in written))
    return 0


def _positive_int(text):
    import argparse

    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--repeats must be a positive integer, got {text!r}")
    if value < 1:
        raise argparse.ArgumentTypeError(f"--repeats must be a positive integer, got {text!r}")
    return value


def register(commands) -> None:
    """Add the ``bench`` subcommand."""
    parser = commands.add_parser(
        "bench", help="error against run time of every solver: CSV, figure, RESULTS.md",
        description="Work-precision study: each method (fast at several rtol, the report's "
                    "predictor-corrector at 1..64 subdivisions, linear, reference at several "
                    "rtol) against reference at rtol 2.5e-14, on the report's cases and the "
                    "extreme ones; the coupled planar model (engine and SciPy reference at "
                    "several rtol) on the rocking-limit case (free-rocking, ample friction) "
                    "and on coupled cases against the planar reference at rtol 1e-13; the "
                    "stack model (compiled and SciPy engines; not with --quick) on two- and "
                    "three-block cases against its SciPy engine at rtol 1e-14; writes work_precision.csv, "
                    "planar_work_precision.csv, stack_work_precision.csv, work_precision.png "
                    "and "
                    "RESULTS.md (with the Pacoima Dam speed and first-call times).")
    parser.add_argument("--cases", nargs="+", metavar="NAME",
                        help="only these cases (default: all; an unknown name lists them)")
    parser.add_argument("--quick", action="store_true",
                        help="fewer settings (the SciPy references at their default rtol only), "
                             "the report's four rocking cases and the 3 Hz coupled case (with "
                             "--cases: any, the long record cut to 20 s), fewer repeats, a "
                             "truth check in RESULTS.md, no stack model (its rows are in the "
                             "full run only)")
    parser.add_argument("--repeats", type=_positive_int, default=None,
                        help="timed repetitions of the compiled methods (default 5, quick 3)")
    parser.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    parser.add_argument("--no-speed", action="store_true",
                        help="skip the Pacoima Dam timing, first-call and batch measurements")
    parser.add_argument("--no-planar", action="store_true",
                        help="skip the coupled planar model (its rows, CSV and panels)")
    parser.add_argument("--no-stack", action="store_true",
                        help="skip the stack model (its rows, CSV and panels; --quick "
                             "skips it too)")
    parser.set_defaults(handler=_bench)
