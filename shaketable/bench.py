"""The work-precision benchmark as one job: run the study, write its table, figure and report.

Used by ``shaketable bench`` and by ``benchmarks/work_precision.py`` (which
regenerates the committed ``benchmarks/RESULTS.md``); the measurements are in
:mod:`shaketable.studies.work_precision`, the figure in :mod:`shaketable.plots.bench`.
"""

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
    from shaketable.core.files import prepare_output_folder, write_csv, write_text
    from shaketable.plots.bench import save_work_precision_figure
    from shaketable.studies import benchmark_cases, work_precision

    out = prepare_output_folder(out, "out")
    selected = benchmark_cases.benchmark_cases(quick=quick, names=cases)
    settings = work_precision.method_settings(quick=quick)
    cache = {}
    frame = work_precision.work_precision(selected, settings, repeats=repeats, cache=cache,
                                 progress=lambda name: progress(f"work-precision: {name}"))
    csv = out / "work_precision.csv"
    write_csv(csv, frame)
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
    write_text(results, text)
    return [csv, figure, results]
