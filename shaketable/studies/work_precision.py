"""The work-precision study: every method's error against its run time on the benchmark
cases, convergence orders, the Pacoima Dam timing, first-call and batch throughput.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core.geometry import Block
from shaketable.models.api import simulate
from shaketable.models.rocking.reference import ReferenceSolverError
from shaketable.models.rocking.result import RockingResult
from shaketable.models.rocking.run import DEFAULT_RTOL
from shaketable.studies.benchmark_cases import (
    ACCEPT_ABSOLUTE_THETA,
    ACCEPT_RELATIVE,
    FAST_RTOLS,
    ORDER_ERROR_FLOOR,
    PC_SUBDIVISIONS,
    QUICK_FAST_RTOLS,
    QUICK_PC_SUBDIVISIONS,
    QUICK_REFERENCE_RTOLS,
    REFERENCE_DEFAULT_RTOL,
    REFERENCE_RTOLS,
    TARGET_FAST_MS,
    TARGET_SPEED_UP,
    TRUTH_RTOL,
    Case,
    benchmark_cases,
    compare,
)

if TYPE_CHECKING:
    import pandas as pd

#: Called with each case's name as the study reaches it.
Progress = Callable[[str], object]


def _timed(case: Case, method: str, repeats: int, **options: Any) -> tuple[RockingResult, float]:
    """Run ``case`` ``repeats`` times; the result and the median wall time [s].

    The compiled methods get one untimed call first (numba compilation or cache
    load); ``reference`` has nothing to warm up and is too slow to run twice.
    """
    if method != "reference":
        case.run(method, **options)
    times = []
    result = None
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        result = case.run(method, **options)
        times.append(time.perf_counter() - start)
    assert result is not None, "the loop runs at least once"
    return result, float(np.median(times))


def method_settings(fast_rtols: Sequence[float] = FAST_RTOLS,
                    subdivisions: Sequence[int] = PC_SUBDIVISIONS,
                    reference_rtols: Sequence[float] = REFERENCE_RTOLS, quick: bool = False
                    ) -> list[tuple[str, str, dict[str, Any]]]:
    """(method, label, options) of the work-precision study.

    ``quick=True`` takes :data:`QUICK_FAST_RTOLS`, :data:`QUICK_PC_SUBDIVISIONS`
    and :data:`QUICK_REFERENCE_RTOLS` instead of the defaults.
    """
    if quick:
        fast_rtols, subdivisions, reference_rtols = (QUICK_FAST_RTOLS, QUICK_PC_SUBDIVISIONS,
                                                     QUICK_REFERENCE_RTOLS)
    settings = [("fast", f"rtol={r:g}", {"rtol": r}) for r in fast_rtols]
    settings += [("predictor-corrector", f"subdivisions={s}", {"subdivisions": s})
                 for s in subdivisions]
    settings += [("linear", "closed form", {})]
    settings += [("reference", f"rtol={r:g}", {"rtol": r}) for r in reference_rtols]
    return settings


#: Truth tolerances tried in turn when SciPy fails at the tighter one.
TRUTH_FALLBACK_RTOLS = (TRUTH_RTOL, 1e-13, REFERENCE_DEFAULT_RTOL)

#: SciPy's DOP853 gave up inside an interval (``solve_ivp`` status -1), seen at rtol
#: 2.5e-14 on a flight that starts at theta ~ 1e-16 beside the switch of corner:
#: :func:`truth_run` then falls back to a looser truth.
ReferenceStepFailure = ReferenceSolverError


def truth_run(case: Case, cache: dict | None = None) -> RockingResult:
    """The truth for ``case``: ``reference`` at :data:`TRUTH_RTOL` (memoised in ``cache``).

    If SciPy fails at that tolerance (:class:`ReferenceStepFailure`), the next
    of :data:`TRUTH_FALLBACK_RTOLS` is used; the tolerance used is stored in
    the result's ``statistics["truth rtol"]``.
    """
    if cache is not None and (case.name, "truth") in cache:
        return cache[(case.name, "truth")]
    failure: ReferenceSolverError | None = None
    for rtol in TRUTH_FALLBACK_RTOLS:
        try:
            result = reference_run(case, rtol, cache)
        except ReferenceStepFailure as error:
            failure = error
            continue
        result.statistics["truth rtol"] = rtol
        if cache is not None:
            cache[(case.name, "truth")] = result
        return result
    assert failure is not None, "TRUTH_FALLBACK_RTOLS is not empty"
    raise failure


def reference_run(case: Case, rtol: float, cache: dict | None = None) -> RockingResult:
    """``reference`` at ``rtol`` for ``case``, memoised in ``cache`` by (case name, rtol).

    Raises :class:`ReferenceStepFailure` where SciPy gives up.
    """
    key = (case.name, float(rtol))
    if cache is not None and key in cache:
        return cache[key]
    result = case.run("reference", rtol=rtol)
    if cache is not None:
        cache[key] = result
    return result


def work_precision(cases: Sequence[Case] | None = None,
                   settings: Sequence[tuple[str, str, dict[str, Any]]] | None = None,
                   repeats: int = 5, reference_repeats: int = 1, progress: Progress | None = None,
                   cache: dict | None = None) -> pd.DataFrame:
    """Error against run time, one row per (case, method, setting).

    Parameters
    ----------
    cases : list of Case, optional
        Default :func:`benchmark_cases`.
    settings : list, optional
        Default :func:`method_settings`.
    repeats : int
        Timed repetitions of the compiled methods (median reported) [-].
    reference_repeats : int
        Timed repetitions of the slow ``reference`` method [-].
    progress : callable, optional
        Called with a message before each case.
    cache : dict, optional
        Memo of ``reference`` runs by (case name, rtol), filled here and reused
        by :func:`accuracy_table` (each SciPy run of a long record is slow).

    Returns
    -------
    pandas.DataFrame
        Columns: case, method, setting, rtol, subdivisions, time [s], the
        errors of :func:`compare`, steps, rejected, evaluations, mean step [s]
        (flight time over accepted steps), status, status truth.
    """
    import pandas as pd

    cases = benchmark_cases() if cases is None else cases
    settings = method_settings() if settings is None else settings
    rows = []
    for case in cases:
        if progress:
            progress(case.name)
        truth = truth_run(case, cache)
        for method, label, options in settings:
            if (method == "reference" and case.reference_rtols is not None
                    and options.get("rtol") not in case.reference_rtols):
                continue
            if method == "reference" and reference_repeats <= 1:
                start = time.perf_counter()
                try:
                    result = reference_run(case, options["rtol"], None)
                except ReferenceStepFailure:
                    continue  # SciPy gave up at this tolerance: no point on the figure
                seconds = time.perf_counter() - start
                if cache is not None:
                    cache.setdefault((case.name, float(options["rtol"])), result)
            else:
                count = reference_repeats if method == "reference" else repeats
                result, seconds = _timed(case, method, count, **options)
            row = {"case": case.name, "method": method, "setting": label,
                   "rtol": options.get("rtol", math.nan),
                   "subdivisions": options.get("subdivisions", math.nan),
                   "time [s]": seconds, **compare(result, truth),
                   "steps": result.statistics.get("steps", 0),
                   "rejected": result.statistics.get("rejected", 0),
                   "evaluations": result.statistics.get("evaluations", 0),
                   "status": result.status, "status truth": truth.status,
                   "truth rtol": truth.statistics["truth rtol"]}
            row["mean step [s]"] = _mean_step(case, result, method, options)
            rows.append(row)
    return pd.DataFrame(rows)


def _mean_step(case: Case, result: RockingResult, method: str, options: dict[str, Any]) -> float:
    """Mean step of a run [s]: the fixed substep, or time in flight over accepted steps."""
    dt = 0.005 if case.motion is None else case.motion.dt
    if method == "predictor-corrector":
        return dt / options.get("subdivisions", 4)
    if method == "linear":
        return dt
    steps = result.statistics.get("steps", 0)
    if not steps:
        return math.nan
    flying = _time_in_flight(result)
    return flying / steps if flying > 0 else math.nan


def _time_in_flight(result: RockingResult) -> float:
    """Time the block was not at rest [s] (from the sampled history; rest is theta = omega = 0)."""
    t = result.t
    moving = (result.theta != 0.0) | (result.theta_dot != 0.0)
    inside = moving[:-1] | moving[1:]
    return float(np.sum(np.diff(t)[inside]))


def convergence_orders(frame: pd.DataFrame) -> pd.DataFrame:
    """Measured order of convergence per (case, method): slope of log error vs log step.

    Least-squares slope of log10(error) against log10(mean step) over the
    settings whose errors lie in [1e-10, 1e-2] (below, the truth's own error,
    up to 5e-11 on these cases, dominates; above, a changed sequence of
    events) and whose impact count and
    verdict agree with the truth. Separate columns for max |theta| and for the
    event times.
    """
    import pandas as pd

    rows = []
    for (case, method), group in frame.groupby(["case", "method"], sort=False):
        if method == "linear":
            continue
        row = {"case": case, "method": method}
        for column, key in (("error max_theta [-]", "order max_theta"),
                            ("error events [-]", "order events")):
            ok = group[group["same impacts"] & group["same verdict"]]
            x = np.log10(ok["mean step [s]"].to_numpy(dtype=float))
            y = ok[column].to_numpy(dtype=float)
            keep = np.isfinite(x) & (y >= ORDER_ERROR_FLOOR) & (y <= 1e-2)
            # a slope needs 3 distinct steps spanning 0.3 decades at least: fast's steps
            # end on every input sample, so at loose tolerances the sample interval, not
            # rtol, sets them and the points pile up at one step size
            spread = np.ptp(x[keep]) if keep.any() else 0.0
            row[key] = (float(np.polyfit(x[keep], np.log10(y[keep]), 1)[0])
                        if np.unique(x[keep]).size >= 3 and spread >= 0.3 else math.nan)
        rows.append(row)
    return pd.DataFrame(rows)


def accuracy_table(cases: Sequence[Case] | None = None, progress: Progress | None = None,
                   cache: dict | None = None) -> pd.DataFrame:
    """``fast`` at its default against ``reference`` at its default, per case.

    Parameters
    ----------
    cases : list of Case, optional
        Default :func:`benchmark_cases`.
    progress : callable, optional
        Called with each case's name.
    cache : dict, optional
        ``reference`` runs by (case name, rtol), as filled by
        :func:`work_precision`; the truth (:data:`TRUTH_RTOL`) is taken from it
        when present, otherwise not computed.

    Returns
    -------
    pandas.DataFrame
        The errors of :func:`compare` (fast against reference), whether they
        meet 1e-8 relative (1e-10 rad for max |theta| of tiny responses) with
        the same verdict and impact count, max theta/alpha, the statuses and,
        when the truth is known, the reference's own errors against it
        ("reference error ... vs truth"): where those are as large as fast's,
        the case itself is ill-conditioned (chaotic rocking), not the engine.
    """
    import pandas as pd

    cases = benchmark_cases() if cases is None else cases
    rows = []
    for case in cases:
        if progress:
            progress(case.name)
        fast = case.run("fast")
        try:
            reference = reference_run(case, REFERENCE_DEFAULT_RTOL, cache)
        except ReferenceStepFailure as error:
            rows.append({"case": case.name, "status": fast.status, "meets 1e-8": False,
                         "status reference": f"failed: {error}"})
            continue
        row = {"case": case.name, "max theta/alpha": fast.max_theta_ratio,
               "status": fast.status, "status reference": reference.status,
               **compare(fast, reference)}
        row["meets 1e-8"] = bool(
            (row["error max_theta [-]"] <= ACCEPT_RELATIVE
             or row["error max_theta [rad]"] <= ACCEPT_ABSOLUTE_THETA)
            and row["error events [-]"] <= ACCEPT_RELATIVE
            and row["same verdict"] and row["same impacts"])
        truth = None if cache is None else cache.get((case.name, "truth"))
        if truth is not None:
            own = compare(reference, truth)
            row["reference error max_theta vs truth [-]"] = own["error max_theta [-]"]
            row["reference error events vs truth [-]"] = own["error events [-]"]
        rows.append(row)
    return pd.DataFrame(rows)


#: A measured error is resolved when it is at least this many times the truth's own error.
TRUTH_MARGIN = 100.0

#: The methods whose error the truth check reads (the SciPy references and the Moreau-Jean
#: rows, whose truth is another run, are not checked).
_CHECKED_METHODS = ("fast", "predictor-corrector", "linear", "planar")

_REFERENCE_METHODS = ("reference", "planar-reference")


def truth_check(*frames: pd.DataFrame | None) -> pd.DataFrame:
    """How far each case's truth can be trusted: its own error and what it resolves.

    The truth's own error is estimated from the case's SciPy reference (``reference``, or
    ``planar-reference`` on a coupled case) at its tightest tolerance looser than the
    truth's: the larger of its two errors against the truth (max |theta| and event times),
    the error of the looser run and so, the tighter run being the more accurate, at least
    the truth's (floored at the truth's rtol; NaN when the case has no reference row).
    A compiled method's error is *resolved* when it is at least :data:`TRUTH_MARGIN` times
    that estimate: the truth is then 100 times more accurate
    than the error it measures. An unresolved error only says that the method is within
    ``TRUTH_MARGIN x`` the estimate of the exact solution.

    Parameters
    ----------
    *frames : pandas.DataFrame or None
        Frames of :func:`work_precision` (with planar rows) or of
        :func:`shaketable.studies.planar_work_precision.planar_work_precision`.

    Returns
    -------
    pandas.DataFrame
        One row per case: truth rtol, reference rtol, truth error estimate [-],
        resolved below [-] (the margin times the estimate), errors resolved (of the
        compiled methods' max |theta| and event-time errors: "k of n"), smallest
        resolved error [-] and largest unresolved error [-].
    """
    import pandas as pd

    rows = []
    for frame in frames:
        if frame is None or frame.empty or "method" not in frame:
            continue
        for case, group in frame.groupby("case", sort=False):
            # the case's own reference: on the rocking-limit case the planar reference's
            # rows are errors of another model against the rocking truth
            method = next((name for name in _REFERENCE_METHODS
                           if (group["method"] == name).any()), _REFERENCE_METHODS[0])
            references = group[group["method"] == method]
            references = references[references["rtol"] > group["truth rtol"].min()]
            errors = ["error max_theta [-]", "error events [-]"]
            if references.empty:
                estimate = math.nan
                reference_rtol = math.nan
            else:
                tightest = references[references["rtol"] == references["rtol"].min()]
                reference_rtol = float(tightest["rtol"].iloc[0])
                estimate = max(float(np.nanmax(tightest[errors].to_numpy(dtype=float))),
                               float(group["truth rtol"].min()))
            checked = group[group["method"].isin(_CHECKED_METHODS)][errors]
            measured = checked.to_numpy(dtype=float).ravel()
            measured = measured[np.isfinite(measured)]
            resolved = measured >= TRUTH_MARGIN * estimate
            rows.append({
                "case": case, "truth rtol": float(group["truth rtol"].min()),
                "reference rtol": reference_rtol, "truth error estimate [-]": estimate,
                "resolved below [-]": TRUTH_MARGIN * estimate,
                "errors resolved": f"{int(resolved.sum())} of {measured.size}",
                "smallest resolved [-]": (float(measured[resolved].min()) if resolved.any()
                                          else math.nan),
                "largest unresolved [-]": (float(measured[~resolved].max())
                                           if (~resolved).any() else math.nan)})
    return pd.DataFrame(rows)


def _truth_check_markdown(check: pd.DataFrame) -> list[str]:
    """The section of :func:`truth_check`'s table."""
    return ["## Truth check", "",
            "Each case's truth against its own error, estimated by the SciPy reference at "
            "its tightest rtol against it (the error of the looser run, so at least the "
            "truth's, the tighter run being the more accurate). An error of a compiled "
            f"method is resolved when it is at least {TRUTH_MARGIN:g} times that estimate; "
            "an unresolved one (the fast engine's, mostly) only says the method is as "
            "accurate as this truth can tell: within "
            "'resolved below' of the exact solution.", "",
            markdown_table(check), ""]


# --------------------------------------------------------------------------- speed
def pacoima_timing(repeats: int = 200, reference_repeats: int = 3,
                   cor: float = 0.95) -> dict[str, Any]:
    """Pacoima Dam S16E with its vertical, 16 x 4 ft block: fast (warm) and reference times.

    Returns the median and best fast time per run [ms], the median reference
    time [s] measured in the same process, the speed-up and the run's status.
    """
    from shaketable.ground import records

    block = Block.parse("16x4ft")
    motion = records.load("pacoima-dam-s16e")
    fast = simulate(block, motion, cor=cor)  # warm
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fast = simulate(block, motion, cor=cor)
        times.append(time.perf_counter() - start)
    reference_times = []
    for _ in range(max(1, reference_repeats)):
        start = time.perf_counter()
        reference = simulate(block, motion, cor=cor, method="reference")
        reference_times.append(time.perf_counter() - start)
    median = float(np.median(times))
    reference_median = float(np.median(reference_times))
    return {"fast median [ms]": 1e3 * median, "fast best [ms]": 1e3 * float(np.min(times)),
            "reference median [s]": reference_median, "speed-up [-]": reference_median / median,
            "status": fast.status, "t_end [s]": float(fast.t[-1]),
            "steps": fast.statistics["steps"], "rejected": fast.statistics["rejected"],
            "evaluations": fast.statistics["evaluations"],
            "same as reference": compare(fast, reference)}


_FIRST_CALL = """
import time
start = time.perf_counter()
import shaketable as st
from shaketable.ground import records
imported = time.perf_counter()
block = st.Block.parse("16x4ft")
motion = records.load("pacoima-dam-s16e")
loaded = time.perf_counter()
st.simulate(block, motion, cor=0.95)
first = time.perf_counter()
st.simulate(block, motion, cor=0.95)
second = time.perf_counter()
print(imported - start, first - loaded, second - first)
"""


def first_call_seconds(cold: bool = False) -> dict[str, float]:
    """A fresh Python process: import time and first ``simulate`` call [s].

    ``cold=False`` uses numba's on-disk cache (the usual case after the first
    run on a machine); ``cold=True`` points ``NUMBA_CACHE_DIR`` at an empty
    folder, so the engine is compiled from scratch.
    """
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as folder:
        if cold:
            env["NUMBA_CACHE_DIR"] = folder
        output = subprocess.run([sys.executable, "-c", _FIRST_CALL], capture_output=True,
                                text=True, env=env, check=True).stdout.split()
    imported, first, second = (float(x) for x in output[-3:])
    return {"import [s]": imported, "first call [s]": first, "second call [s]": second}


def batch_throughput(threads: int = 2, n_cors: int = 8, repeats: int = 3) -> dict[str, Any]:
    """Runs per second of :func:`shaketable.models.rocking.batch.simulate_many` on ``threads`` threads.

    The sweep: Table 4.2's nine block sizes x the two Pacoima Dam records x
    ``n_cors`` values of COR in [0.7, 1.0], fast method.

    Returns
    -------
    dict
        runs, threads, median seconds per sweep, runs/s with ``threads``
        threads, with one thread and for a Python loop over
        :func:`shaketable.models.api`, and the number overturned; or, when
        :mod:`shaketable.models.rocking.batch` is not installed yet, ``{"skipped": reason}``.
    """
    from shaketable.ground import records

    try:
        from shaketable.models.rocking.batch import simulate_many
    except ImportError as error:
        return {"skipped": f"shaketable.models.rocking.batch.simulate_many is not available ({error})"}

    blocks = [Block.from_feet(h, w) for h, w in
              ((2, 1), (3, 1), (4, 1), (5, 1), (4, 2), (6, 2), (8, 2), (6, 3), (9, 3))]
    motions = [records.load("pacoima-dam-s16e"), records.load("pacoima-dam-s74w")]
    cors = list(np.linspace(0.7, 1.0, n_cors))
    runs = len(blocks) * len(motions) * len(cors)
    simulate_many(blocks[:1], motions[:1], cors[:1], threads=threads)  # compile / load
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        frame = simulate_many(blocks, motions, cors, threads=threads)
        times.append(time.perf_counter() - start)
    serial = []
    for _ in range(repeats):
        start = time.perf_counter()
        simulate_many(blocks, motions, cors, threads=1)
        serial.append(time.perf_counter() - start)
    loop = time.perf_counter()
    for block in blocks:
        for motion in motions:
            for cor in cors:
                simulate(block, motion, cor=cor)
    loop = time.perf_counter() - loop
    best = float(np.median(times))
    return {"runs": runs, "threads": threads, "seconds": best, "runs/s": runs / best,
            "runs/s 1 thread": runs / float(np.median(serial)),
            "runs/s simulate loop": runs / loop,
            "overturned": int(frame["overturned"].sum())}


# --------------------------------------------------------------------------- report
def _fmt(value: Any, digits: int = 2) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(value)
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–" if value is None or math.isnan(value) else "inf"
    if value == 0:
        return "0"
    if abs(value) < 1e-3 or abs(value) >= 1e5:
        return f"{value:.{digits}e}"
    return f"{value:.{digits + 2}g}"


def markdown_table(frame: pd.DataFrame, columns: Sequence[str] | None = None) -> str:
    """A pandas frame as a GitHub Markdown table (numbers in short scientific form)."""
    columns = list(frame.columns) if columns is None else columns
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for _, row in frame[columns].iterrows():
        lines.append("| " + " | ".join(_fmt(row[c]) if not isinstance(row[c], str) else row[c]
                                       for c in columns) + " |")
    return "\n".join(lines)


def results_markdown(accuracy: pd.DataFrame | None = None, orders: pd.DataFrame | None = None,
                     frame: pd.DataFrame | None = None, pacoima: dict[str, Any] | None = None,
                     first_call: dict[str, dict[str, float]] | None = None,
                     batch: dict[str, Any] | None = None, figure: str = "docs/figures/work_precision.png",
                     command: str = "python3 benchmarks/work_precision.py",
                     planar: pd.DataFrame | None = None, truth: bool = False) -> str:
    """The README-ready Markdown of the benchmark results.

    Every argument is optional; the sections present are written: the figure
    path, the work-precision summary (best fast and predictor-corrector
    settings per case), the acceptance table (:func:`accuracy_table`), the
    measured orders (:func:`convergence_orders`), the Pacoima Dam speed
    (:func:`pacoima_timing`), the first-call times (:func:`first_call_seconds`),
    the batch throughput (:func:`batch_throughput`) and the coupled planar model's rows
    (``frame``'s planar methods on the rocking-limit case, and ``planar``, the frame of
    :func:`shaketable.studies.planar_work_precision.planar_work_precision`); with ``truth``,
    the truth check of ``frame`` and ``planar`` (:func:`truth_check`) after the figure.
    """
    lines = ["# Benchmarks: accuracy against run time", "",
             f"Made by `{command}` (shaketable.studies.benchmark_cases); machine: {os.cpu_count()} cores "
             "shared with other work, so times are indicative.", ""]
    if figure:
        lines += ["## Work-precision figure", "", f"![work-precision]({figure})", "",
                  "Error against `reference` at rtol 2.5e-14 (the truth) versus median run "
                  "time, one panel per case. Solid: relative error of max |θ|; dashed: "
                  "largest relative error of the event times (impacts before 20 s, start, "
                  "unstable, overturn, airborne).", ""]
        if planar is not None and not planar.empty:
            lines[-1:-1] = ["", "The coupled planar model (`planar`: the compiled engine; "
                            "`planar-reference`: its SciPy reference) is on the free-rocking "
                            "panel with friction that cannot be exceeded (against the same "
                            "rocking truth) and has a panel per coupled case, against the "
                            "planar reference at rtol 1e-13 (dash-dotted: the peak slip's "
                            "relative error)."]
    if truth and frame is not None:
        lines += _truth_check_markdown(truth_check(frame, planar))
    if pacoima is not None:
        lines += ["## Speed: Pacoima Dam S16E + vertical, 16 x 4 ft, COR 0.95", "",
                  "| quantity | value |", "|---|---|"]
        for key, value in pacoima.items():
            if isinstance(value, dict):
                for inner, item in value.items():
                    lines.append(f"| fast vs reference: {inner} | {_fmt(item)} |")
            else:
                lines.append(f"| {key} | {value if isinstance(value, str) else _fmt(value)} |")
        milliseconds = pacoima["fast median [ms]"]
        ratio = pacoima["speed-up [-]"]
        lines += ["", f"The project's speed targets: fast at most {TARGET_FAST_MS:g} ms per run "
                  f"warm: {'met' if milliseconds <= TARGET_FAST_MS else 'NOT met'} "
                  f"({milliseconds:.3g} ms); at least {TARGET_SPEED_UP:g} times faster than "
                  f"`reference` in the same process: "
                  f"{'met' if ratio >= TARGET_SPEED_UP else 'NOT met'} ({ratio:.0f}x in this "
                  f"measurement). Both timings are medians, but the ratio still follows the "
                  f"machine's load: the reference's ~{1e3 * pacoima['reference median [s]']:.0f} ms "
                  f"runs are interrupted by other processes, the median of many "
                  f"~{milliseconds:.2g} ms fast runs is not, so a busy machine raises the ratio "
                  f"(the README gives the range over several measurements)."]
        lines.append("")
    if first_call is not None:
        lines += ["## First call in a fresh process", "", "| | import [s] | first simulate [s] "
                  "| second simulate [s] |", "|---|---|---|---|"]
        for label, values in first_call.items():
            lines.append(f"| {label} | {_fmt(values['import [s]'])} | "
                         f"{_fmt(values['first call [s]'])} | {_fmt(values['second call [s]'])} |")
        lines.append("")
    if batch is not None:
        lines += ["## Batch throughput (`shaketable.models.rocking.batch.simulate_many`)", ""]
        if "skipped" in batch:
            lines += [f"Skipped: {batch['skipped']}.", ""]
        else:
            lines += ["| quantity | value |", "|---|---|"]
            lines += [f"| {key} | {_fmt(value)} |" for key, value in batch.items()]
            lines.append("")
        lines += ["The stack model's cost against the single block's (a two-block run about 5 "
                  "times a single-block run on the Pacoima Dam and El Centro record grid, "
                  "because the stack moves longer) is measured by "
                  "`benchmarks/stack_speed.py`: `benchmarks/STACK.md`.", ""]
    if accuracy is not None:
        lines += [f"## Acceptance: fast (default rtol {DEFAULT_RTOL['fast']:g}) against reference "
                  f"(default rtol {DEFAULT_RTOL['reference']:g})", "",
                  "Target: 1e-8 relative in max |θ| (or 1e-10 rad) and in the event "
                  "times, same impact count before 20 s and same verdict.", "",
                  markdown_table(accuracy, [c for c in accuracy.columns if c not in
                                            ("impacts truth",)]), ""]
    if frame is not None and "method" in frame:
        best = frame[frame["method"].isin(["fast", "predictor-corrector", "linear"])]
        lines += ["## Work-precision table (every setting; the CSV has all columns)", "",
                  markdown_table(best, ["case", "method", "setting", "time [s]",
                                        "error max_theta [-]", "error events [-]",
                                        "same impacts", "same verdict"]), ""]
    planar_limit = (None if frame is None or "method" not in frame
                    else frame[frame["method"].isin(["planar", "planar-reference"])])
    if planar is not None or (planar_limit is not None and not planar_limit.empty):
        lines += _planar_markdown(planar_limit, planar)
    if orders is not None:
        lines += ["## Measured orders of convergence", "",
                  "Least-squares slope of log10(error) against log10(mean step), over the "
                  "settings with the truth's impact count and verdict and errors in "
                  f"[{ORDER_ERROR_FLOOR:g}, 1e-2]; '–' where fewer than three settings qualify "
                  "(the fast engine's errors are at the truth's own level, or its steps are "
                  "set by the input's samples). The fast stepper's order at fixed steps is "
                  "tested in tests/test_engine.py (measured 5.99, 6.01, 6.18).", "",
                  markdown_table(orders), ""]
    return "\n".join(lines) + "\n"


def _planar_markdown(limit: pd.DataFrame | None, coupled: pd.DataFrame | None) -> list[str]:
    """The section of the coupled planar model: rocking limit and coupled cases."""
    lines = ["## Coupled planar model: engine and independent reference", "",
             "`planar`: the compiled engine (`simulate(..., friction=...)`) at its rtol; "
             "`planar-reference`: the SciPy reference (`models.planar.reference`, Newton-Euler "
             "linear solves per mode, DOP853 with event location) at its rtol.", ""]
    if limit is not None and not limit.empty:
        lines += ["Rocking limit (mu_s = mu_d = 10, friction never reached): against the case's "
                  "rocking truth (`reference` at rtol 2.5e-14), the rocking study's errors.", "",
                  markdown_table(limit, ["case", "method", "setting", "time [s]",
                                         "error max_theta [-]", "error events [-]",
                                         "impacts", "impacts truth", "same verdict"]), ""]
    if coupled is not None and not coupled.empty:
        lines += ["Coupled cases (rock, slide-rock, impacts): against the planar reference at "
                  "rtol 1e-13; event times are the mode changes and impacts, compared while "
                  "their modes agree (a missing or extra event: inf)."
                  + (" `moreau-jean`: the independent Moreau-Jean time stepping "
                     "(`models.planar.moreau`, plastic Newton law) at step h on the first "
                     "seconds of the case (1.2 s, 3.5 s), against the planar reference with "
                     "`cor=\"housner\"` on the same window; first order in h (no event "
                     "times)."
                     if (coupled["method"] == "moreau-jean").any() else ""), "",
                  markdown_table(coupled, ["case", "method", "setting", "time [s]",
                                           "error max_theta [-]", "error events [-]",
                                           "error peak slip [-]", "events", "events truth",
                                           "same events", "same verdict"]), ""]
    return lines
