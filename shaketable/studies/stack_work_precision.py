"""Work-precision of the stack model: error against run time of its two engines.

The compiled stack engine (method ``"stack"``, ``simulate_stack(..., method="compiled")``)
and the Python one on SciPy's ``solve_ivp`` (``"stack-reference"``,
``method="reference"``) at several rtol, each against the Python engine at
:data:`STACK_TRUTH_RTOL` (the tightest tolerance the model accepts; the compiled engine at
that setting is never its own truth). Errors (:func:`compare_stack`): the relative error of
max |theta| over the blocks, and the largest relative error of the event times (uplifts,
impacts, rests, overturn) while the two runs' events are the same kinds in the same order
(inf when they part before the end). ``shaketable bench`` draws the rows as panels beside
the single-block methods.

Nothing here is a pass/fail test; the functions measure and return pandas frames.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.studies.planar_work_precision import timed

if TYPE_CHECKING:
    import pandas as pd

#: Methods of this study, as written in the frames' ``method`` column.
STACK_METHODS = ("stack", "stack-reference")
#: Tolerances of the compiled engine and of the Python engine.
STACK_RTOLS = (1e-6, 1e-8, 1e-10, 1e-12, 1e-13)
STACK_REFERENCE_RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)
QUICK_STACK_RTOLS = (1e-6, 1e-10, 1e-12)
QUICK_STACK_REFERENCE_RTOLS = (1e-8, 1e-12)
#: The truth: the Python engine at the tightest rtol the model accepts.
STACK_TRUTH_RTOL = 1e-14
#: Seconds of each record the cases run (``quick``: fewer).
WINDOW, QUICK_WINDOW = 8.0, 4.0


@dataclass(frozen=True)
class StackCase:
    """One work-precision case of the stack model: blocks (bottom first) under a record."""

    name: str
    blocks: tuple[Block, ...]
    record: str
    scale: float
    window: float

    def motion(self) -> Motion:
        from shaketable.ground import records
        from shaketable.ground.signals import trim

        motion = records.load(self.record).scaled(self.scale)
        return trim(motion, float(motion.t[0]), float(motion.t[0]) + self.window)

    def run(self, method: str, rtol: float):
        from shaketable.models.stack import Stack, simulate_stack

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")   # the assumption warnings: not measured here
            return simulate_stack(Stack(self.blocks), self.motion(), rtol=rtol,
                                  method="compiled" if method == "stack" else "reference")


def stack_cases(quick: bool = False) -> list[StackCase]:
    """Two of the report's 30 x 6 in blocks stacked under El Centro 1940 (180 and up) at
    half scale, and three 4 x 1 ft blocks under Pacoima Dam S16E (with its vertical) at
    half scale: rocking with impacts and uplifts of the upper interfaces."""
    window = QUICK_WINDOW if quick else WINDOW
    slender, tall = Block.parse("30x6in"), Block.parse("4x1ft")
    return [StackCase("stack 2 x 30x6in el-centro x0.5", (slender, slender),
                      "el-centro-1940-180", 0.5, window),
            StackCase("stack 3 x 4x1ft pacoima x0.5", (tall, tall, tall),
                      "pacoima-dam-s16e", 0.5, window)]


def compare_stack(result, truth) -> dict[str, float]:
    """Relative error of max |theta| and the largest relative error of the event times."""
    peak, peak_truth = float(np.abs(result.theta).max()), float(np.abs(truth.theta).max())
    theta_error = abs(peak - peak_truth) / peak_truth if peak_truth > 0 else math.nan
    events_error = 0.0
    for event, reference in zip(result.events, truth.events):
        if (event["kind"], event["interface"]) != (reference["kind"], reference["interface"]):
            events_error = math.inf
            break
        scale = max(abs(reference["t"]), 1e-300)
        events_error = max(events_error, abs(event["t"] - reference["t"]) / scale)
    if len(result.events) != len(truth.events):
        events_error = math.inf
    return {"error max_theta [-]": theta_error, "error events [-]": events_error}


def method_settings(quick: bool = False) -> list[tuple[str, str, dict[str, Any]]]:
    """(method, label, options) of the stack rows."""
    engine = QUICK_STACK_RTOLS if quick else STACK_RTOLS
    reference = QUICK_STACK_REFERENCE_RTOLS if quick else STACK_REFERENCE_RTOLS
    return ([("stack", f"rtol={r:g}", {"rtol": r}) for r in engine]
            + [("stack-reference", f"rtol={r:g}", {"rtol": r}) for r in reference])


def stack_work_precision(cases: Sequence[StackCase] | None = None,
                         settings: Sequence[tuple[str, str, dict[str, Any]]] | None = None,
                         repeats: int = 5,
                         progress: Callable[[str], object] | None = None) -> pd.DataFrame:
    """Error against run time, one row per (case, method, setting).

    Parameters
    ----------
    cases : list of StackCase, optional
        Default :func:`stack_cases`.
    settings : list, optional
        Default :func:`method_settings`.
    repeats : int
        Timed repetitions of the compiled engine (median reported) [-].
    progress : callable, optional
        Called with each case's name.

    Returns
    -------
    pandas.DataFrame
        Columns: case, method, setting, rtol, subdivisions (NaN), time [s], the errors of
        :func:`compare_stack`, steps, evaluations, events, status, status truth, truth
        ("stack-reference"), truth rtol.
    """
    import pandas as pd

    cases = stack_cases() if cases is None else cases
    settings = method_settings() if settings is None else settings
    rows = []
    for case in cases:
        if progress:
            progress(case.name)
        truth = case.run("stack-reference", STACK_TRUTH_RTOL)
        for method, label, options in settings:
            result, seconds = timed(lambda: case.run(method, options["rtol"]), method == "stack",
                                    repeats)
            rows.append({"case": case.name, "method": method, "setting": label,
                         # the tolerance computed at: tighter after a stall at the asked
                         "rtol": result.statistics["rtol"], "subdivisions": math.nan,
                         "time [s]": seconds, **compare_stack(result, truth),
                         "steps": result.statistics["steps"],
                         "evaluations": result.statistics["evaluations"],
                         "events": result.n_events, "status": result.status,
                         "status truth": truth.status, "truth": "stack-reference",
                         "truth rtol": STACK_TRUTH_RTOL})
    return pd.DataFrame(rows)


def stack_markdown(frame: pd.DataFrame) -> list[str]:
    """The stack's section of ``RESULTS.md``: each case's rows (error and time)."""
    lines = ["## The stack model (two and three blocks)", "",
             "`stack`: the compiled stack engine; `stack-reference`: the same algorithm on "
             f"SciPy's `solve_ivp`; errors against `stack-reference` at rtol "
             f"{STACK_TRUTH_RTOL:g} (relative error of max |θ| over the blocks; largest "
             "relative error of the event times, inf when the events part).", "",
             "| case | method | rtol | time [s] | error max θ | error events | events |",
             "|---|---|---|---|---|---|---|"]
    for values in frame.to_dict("records"):
        lines.append(f"| {values['case']} | {values['method']} | {values['rtol']:g} | "
                     f"{values['time [s]']:.3g} | {values['error max_theta [-]']:.2g} | "
                     f"{values['error events [-]']:.2g} | {values['events']} |")
    return lines + [""]
