"""``shaketable bench``: error against run time of every solver (work-precision study)."""

from __future__ import annotations

from pathlib import Path


def run_study(cases=None, quick=False, repeats=5, out="bench-out", progress=print,
              figure_path=None, speed=True, markdown_figure=None):
    """Run the study and write ``work_precision.csv``, ``work_precision.png``, ``RESULTS.md``.

    Parameters
    ----------
    cases : list of str, optional
        Case names (default: all of :func:`shaketable.studies.benchmark_cases.benchmark_cases`).
    quick : bool
        Fewer settings, 20 s instead of 100 s for the long record, fewer repeats.
    repeats : int
        Timed repetitions of the compiled methods [-].
    out : str or Path
        Output folder (created).
    progress : callable
        Called with a message per step.
    figure_path : Path, optional
        Where to write the figure (default ``out/work_precision.png``).
    speed : bool
        Also measure the Pacoima Dam speed, first-call times and batch throughput.
    markdown_figure : str, optional
        Figure path written into ``RESULTS.md`` (default: the figure's file name).

    Returns
    -------
    list of Path
        The files written.
    """
    from shaketable.plots.bench import save_work_precision_figure
    from shaketable.studies import benchmark_cases, work_precision

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    selected = benchmark_cases.benchmark_cases(quick=quick, names=cases)
    settings = work_precision.method_settings(quick=quick)
    cache = {}
    frame = work_precision.work_precision(selected, settings, repeats=repeats, cache=cache,
                                 progress=lambda name: progress(f"work-precision: {name}"))
    csv = out / "work_precision.csv"
    frame.to_csv(csv, index=False)
    figure = Path(figure_path) if figure_path else out / "work_precision.png"
    figure.parent.mkdir(parents=True, exist_ok=True)
    save_work_precision_figure(frame, figure)
    progress("accuracy: fast against reference at their defaults")
    accuracy = work_precision.accuracy_table(selected, cache=cache)
    orders = work_precision.convergence_orders(frame)
    pacoima = first_call = batch = None
    if speed:
        progress("speed: Pacoima Dam, 16 x 4 ft, COR 0.95")
        pacoima = work_precision.pacoima_timing(repeats=50 if quick else 200,
                                       reference_repeats=1 if quick else 5)
        progress("first call in a fresh process")
        first_call = {"numba cache on disk": work_precision.first_call_seconds(cold=False)}
        if not quick:
            first_call["empty cache (compiles)"] = work_precision.first_call_seconds(cold=True)
        progress("batch throughput")
        batch = work_precision.batch_throughput(repeats=1 if quick else 3)
    text = work_precision.results_markdown(accuracy, orders, frame, pacoima, first_call, batch,
                                  figure=markdown_figure or figure.name,
                                  command="shaketable bench" + (" --quick" if quick else ""))
    results = out / "RESULTS.md"
    results.write_text(text)
    return [csv, figure, results]


def _bench(args) -> int:
    written = run_study(cases=args.cases, quick=args.quick,
                        repeats=args.repeats if args.repeats else (3 if args.quick else 5),
                        out=args.out, speed=not args.no_speed)
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
                    "extreme ones; writes work_precision.csv, work_precision.png and "
                    "RESULTS.md (with the Pacoima Dam speed and first-call times).")
    parser.add_argument("--cases", nargs="+", metavar="NAME",
                        help="only these cases (default: all; an unknown name lists them)")
    parser.add_argument("--quick", action="store_true",
                        help="fewer settings, the long record cut to 20 s, fewer repeats")
    parser.add_argument("--repeats", type=_positive_int, default=None,
                        help="timed repetitions of the compiled methods (default 5, quick 3)")
    parser.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    parser.add_argument("--no-speed", action="store_true",
                        help="skip the Pacoima Dam timing, first-call and batch measurements")
    parser.set_defaults(handler=_bench)
