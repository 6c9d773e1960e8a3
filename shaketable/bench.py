"""The work-precision benchmark as one job: run the study, write its table, figure and report.

Used by ``shaketable bench`` and by ``benchmarks/work_precision.py`` (which
regenerates the committed ``benchmarks/RESULTS.md``); the measurements are in
:mod:`shaketable.studies.work_precision` (the rocking methods) and
:mod:`shaketable.studies.planar_work_precision` (the coupled planar model), the
figure in :mod:`shaketable.plots.bench`.
"""

from __future__ import annotations

from pathlib import Path


def run_study(cases=None, quick=False, repeats=5, out="bench-out", progress=print,
              figure_path=None, speed=True, markdown_figure=None, planar=True, stack=True,
              measured: dict | None = None):
    """Run the study and write ``work_precision.csv``, ``work_precision.png``, ``RESULTS.md``
    (and ``planar_work_precision.csv``).

    The coupled planar model joins the study (``planar``): the compiled planar engine and
    the SciPy planar reference on the rocking-limit case
    (:data:`~shaketable.studies.planar_work_precision.ROCKING_LIMIT_CASE`, ample friction,
    rows of ``work_precision.csv`` against that case's rocking truth) and on the coupled
    cases of :func:`~shaketable.studies.planar_work_precision.planar_cases` (against the
    planar reference at rtol 1e-13, ``planar_work_precision.csv``), drawn as further panels
    of the figure; on the first seconds of the coupled cases (``quick``: the 3 Hz case only)
    the independent Moreau-Jean time stepping joins them at steps h of
    :func:`~shaketable.studies.planar_work_precision.moreau_steps` (first order, with the
    plastic Newton law, against the planar reference with ``cor="housner"``).

    Parameters
    ----------
    cases : list of str, optional
        Case names (default: all of :func:`shaketable.studies.benchmark_cases.benchmark_cases`
        and, with ``planar``, of :func:`shaketable.studies.planar_work_precision.planar_cases`).
    quick : bool
        Fewer settings, fewer repeats; without ``cases``, the report's four rocking cases
        and the 3 Hz coupled case only (a named long record: 20 s instead of 100 s); a
        truth check in ``RESULTS.md``.
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
    planar : bool
        Also measure the coupled planar model (engine and reference).
    stack : bool
        Also measure the stack model: its compiled engine and its SciPy engine on the cases
        of :func:`shaketable.studies.stack_work_precision.stack_cases`,
        ``stack_work_precision.csv`` and a panel per case (not with ``cases``: those name
        the rocking and planar cases; not with ``quick``: the SciPy engine's runs take
        seconds each, and a first run in an empty numba cache compiles the engine).

    measured : dict, optional
        Filled with ``"pacoima"`` (the speed; None without ``speed``) and ``"accuracy"``
        (fast against reference; None without cases), as ``RESULTS.md`` reports them.

    Returns
    -------
    list of Path
        The files written.
    """
    import pandas as pd

    from shaketable.core.files import prepare_output_folder, write_csv, write_text
    from shaketable.plots.bench import save_work_precision_figure
    from shaketable.studies import (
        benchmark_cases,
        planar_work_precision,
        stack_work_precision,
        work_precision,
    )

    out = prepare_output_folder(out, "out")
    planar_names = planar_work_precision.planar_case_names()
    rocking_names = None if cases is None else [n for n in cases if n not in planar_names]
    coupled_names = None if cases is None else [n for n in cases if n in planar_names]
    if cases is not None and not cases:
        raise ValueError("cases: give at least one case name (or none for all)")
    if coupled_names and not planar:
        raise ValueError(f"cases: {coupled_names} are cases of the planar model, which "
                         "this run leaves out (planar=False, --no-planar)")
    try:
        selected = benchmark_cases.benchmark_cases(quick=quick, names=rocking_names)
    except ValueError as error:  # an unknown name: list the planar cases too
        raise ValueError(f"{error}; planar cases: {sorted(planar_names)}") from None
    settings = work_precision.method_settings(quick=quick)
    cache: dict = {}
    frame = work_precision.work_precision(selected, settings, repeats=repeats, cache=cache,
                                 progress=lambda name: progress(f"work-precision: {name}"))
    rocking_frame = frame
    planar_frame = None
    written = []
    if planar:
        planar_settings = planar_work_precision.method_settings(quick=quick)
        for case in selected:
            if case.name == planar_work_precision.ROCKING_LIMIT_CASE:
                progress(f"work-precision: {case.name}, planar block with ample friction")
                rows = planar_work_precision.rocking_limit_rows(
                    case, work_precision.truth_run(case, cache), planar_settings,
                    repeats=repeats)
                frame = pd.concat([frame, pd.DataFrame(rows)], ignore_index=True)
        coupled = planar_work_precision.planar_cases(names=coupled_names, quick=quick)
        if coupled:
            planar_frame = planar_work_precision.planar_work_precision(
                coupled, planar_settings, repeats=repeats,
                moreau=planar_work_precision.moreau_steps(quick),
                moreau_cases=planar_work_precision.moreau_case_names(quick),
                progress=lambda name: progress(f"work-precision (planar): {name}"))
    stack_frame = None
    if stack and cases is None and not quick:
        stack_frame = stack_work_precision.stack_work_precision(
            stack_work_precision.stack_cases(quick=quick),
            stack_work_precision.method_settings(quick=quick), repeats=repeats,
            progress=lambda name: progress(f"work-precision (stack): {name}"))
    csv = out / "work_precision.csv"
    write_csv(csv, frame)
    written.append(csv)
    if planar_frame is not None:
        planar_csv = out / "planar_work_precision.csv"
        write_csv(planar_csv, planar_frame)
        written.append(planar_csv)
    if stack_frame is not None:
        stack_csv = out / "stack_work_precision.csv"
        write_csv(stack_csv, stack_frame)
        written.append(stack_csv)
    figure = Path(figure_path) if figure_path else out / "work_precision.png"
    figure.parent.mkdir(parents=True, exist_ok=True)
    save_work_precision_figure(frame, figure, planar=planar_frame, stack=stack_frame)
    progress("accuracy: fast against reference at their defaults")
    accuracy = work_precision.accuracy_table(selected, cache=cache) if selected else None
    orders = work_precision.convergence_orders(rocking_frame) if selected else None
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
                                  command="shaketable bench" + (" --quick" if quick else ""),
                                  planar=planar_frame, truth=quick)
    if stack_frame is not None:
        text = text.rstrip("\n") + "\n\n" + "\n".join(
            stack_work_precision.stack_markdown(stack_frame))
    results = out / "RESULTS.md"
    write_text(results, text)
    if measured is not None:
        measured.update(pacoima=pacoima, accuracy=accuracy)
    return written + [figure, results]
