"""The report's tables (3.1, 4.1-4.3) recomputed side by side with the printed values.

The printed values are in the repository's ``data/report/*.csv`` (installed as
``shaketable.report_data``), each file citing its table.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from importlib.resources import files
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from shaketable.core import theory
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.ground import generators as motions
from shaketable.ground import records
from shaketable.models.api import simulate
from shaketable.models.rocking.result import RockingResult

if TYPE_CHECKING:
    from shaketable.lab.sensors import Sensors

#: How each column of Tables 4.1-4.3 is made. Pacoima Dam: the bundled NGA-West2
#: records with the recorded vertical (read as in ``records.load``). Olive View,
#: A-1, B-1: the package's SUBSTITUTE accelerograms, horizontal only as in the report.
COLUMNS = {
    "pacoima S16E": ("record", "pacoima-dam-s16e"),
    "pacoima S74W": ("record", "pacoima-dam-s74w"),
    "olive view": ("artificial", "olive-view"),
    "A-1": ("artificial", "A-1"),
    "B-1": ("artificial", "B-1"),
}

SUBSTITUTE_SEED = 1


def printed_table(name: str) -> pd.DataFrame:
    """A printed table (``"table_4_2"``...) as a DataFrame, values as printed (str)."""
    path = files("shaketable.report_data") / f"{name}.csv"
    return pd.read_csv(str(path), comment="#", dtype=str)


#: Readings of the Pacoima Dam vertical (labelled DWN in its file): as written ("up", the
#: package's default, see :func:`shaketable.ground.records.load`), reversed ("down"), left out.
PACOIMA_VERTICAL_READINGS = ("up", "down", "none")


def column_motion(column: str, seed: int = SUBSTITUTE_SEED,
                  pacoima_vertical: str = "up") -> Motion:
    """The ground motion of a column of Tables 4.1-4.3.

    ``pacoima_vertical`` is one of :data:`PACOIMA_VERTICAL_READINGS`.
    """
    if pacoima_vertical not in PACOIMA_VERTICAL_READINGS:
        raise ValueError(f"pacoima_vertical must be one of {PACOIMA_VERTICAL_READINGS}, "
                         f"got {pacoima_vertical!r}")
    kind, name = COLUMNS[column]
    if kind == "record":
        if pacoima_vertical == "none":
            return records.load(name, vertical=False)
        return records.load(name, pacoima_vertical_sign=pacoima_vertical)
    return motions.artificial(name, seed=seed)


@dataclass(frozen=True)
class TableComparison:
    """A recomputed table next to the printed one.

    Attributes
    ----------
    name : str
    frame : pandas.DataFrame
        One row per cell: height [ft], width [ft], cor, column, report (as
        printed, "F" = overturns), reproduced (same format), verdict_agrees,
        difference (reproduced - report where both are numbers).
    """

    name: str
    frame: pd.DataFrame

    def counts(self) -> dict[str, dict[str, Any]]:
        """Agreement counted per column, over the recorded (Pacoima Dam) columns, and in total.

        The substitute columns (artificial motions in place of the unavailable
        records) are counted in "all" but not in "recorded records only".
        """
        frame = self.frame
        result: dict[str, dict[str, Any]] = {}
        groups = list(frame.groupby("column", sort=False))
        recorded = frame[~frame["substitute motion"]]
        if 0 < len(recorded) < len(frame):
            groups.append(("recorded records only", recorded))
        for column, group in groups + [("all", frame)]:
            numbers = group["difference"].dropna()
            result[column] = {
                "cells": int(len(group)),
                "same F / not F": int(group["verdict_agrees"].sum()),
                "both numbers": int(len(numbers)),
                "median |difference|": float(np.median(np.abs(numbers))) if len(numbers) else None,
            }
        return result

    def to_frame(self) -> pd.DataFrame:
        """The cell-by-cell comparison."""
        return self.frame


def _cell(result: RockingResult) -> str:
    return "F" if result.overturned else f"{result.max_theta_ratio:.2f}"


def reproduce_table(name: str, columns: Sequence[str] | None = None, seed: int = SUBSTITUTE_SEED,
                    pacoima_vertical: str = "up") -> TableComparison:
    """Recompute Table 4.1, 4.2 or 4.3 (``name`` = ``"table_4_1"`` ...) with the fast engine.

    ``seed`` picks the realisation of the artificial (substitute) columns;
    ``pacoima_vertical`` the reading of the Pacoima Dam vertical
    (:data:`PACOIMA_VERTICAL_READINGS`).
    """
    printed = printed_table(name)
    fixed_cor = {"table_4_2": 1.0, "table_4_3": 0.90}.get(name)
    available = [c for c in COLUMNS if c in printed.columns]
    columns = available if columns is None else [c for c in columns if c in available]
    motion_of = {column: column_motion(column, seed, pacoima_vertical) for column in columns}
    rows = []
    for _, line in printed.iterrows():
        height, width = float(line["height [ft]"]), float(line["width [ft]"])
        cor = float(line["cor [-]"]) if "cor [-]" in line else fixed_cor
        if cor is None:
            raise ValueError(f"{name} has neither a 'cor [-]' column nor a fixed COR")
        block = Block.from_feet(height, width)
        for column in columns:
            reproduced = _cell(simulate(block, motion_of[column], cor=cor))
            report = line[column].strip()
            both = report != "F" and reproduced != "F"
            rows.append({
                "height [ft]": height, "width [ft]": width, "cor [-]": cor, "column": column,
                "substitute motion": COLUMNS[column][0] == "artificial",
                "report": report, "reproduced": reproduced,
                "verdict_agrees": (report == "F") == (reproduced == "F"),
                "difference": float(reproduced) - float(report) if both else math.nan,
            })
    return TableComparison(name, pd.DataFrame(rows))


def table_3_1() -> pd.DataFrame:
    """Table 3.1: periods of the 36 x 9 in block, printed test and theory against
    Eq. (2-5) and the exact nonlinear period [s]."""
    printed = printed_table("table_3_1").astype(float)
    block = Block.from_inches(36, 9)
    amplitudes = np.radians(printed["amplitude [deg]"].to_numpy())
    frame = printed.copy()
    frame["Eq. 2-5 [s]"] = [theory.housner_period(block, a) for a in amplitudes]
    frame["exact [s]"] = [theory.exact_period(block, a) for a in amplitudes]
    frame["test / exact [-]"] = frame["test period [s]"] / frame["exact [s]"]
    virtual = [virtual_period(block, a, seed=k) for k, a in enumerate(amplitudes)]
    frame["virtual test amplitude [deg]"] = [math.degrees(v[0]) for v in virtual]
    frame["virtual test period [s]"] = [v[1] for v in virtual]
    frame["virtual / exact [-]"] = [v[1] / theory.exact_period(block, v[0]) for v in virtual]
    return frame


def virtual_period(block: Block, amplitude: float, *, cor: float = 0.98, seed: int = 0,
                   sensors: Sensors | None = None) -> tuple[float, float]:
    """Period of free rocking measured the report's way on a virtual 50 samples/s record.

    Section 3.7 (1): the period is four times the time from a maximum of the
    recorded angle to the next zero. The block is released from the angle
    whose next half cycle has ``amplitude`` (energy relation of Eq. 2-6), and
    that half cycle is measured (the period does not depend on the COR, which
    only sets how far above ``amplitude`` the release must be: the report gives
    none for this block; 0.98 lets 9.57 deg be reached from below alpha): its extremum located by a parabola through the
    three samples around it, the zero by linear interpolation. Both instants
    carry the anti-alias filter's delay, which therefore cancels.

    Returns
    -------
    amplitude, period : float
        Measured amplitude of the half cycle [rad] and 4 x (peak to zero) [s].
    """
    from shaketable.lab.sensors import Sensors, measure

    release = _release_for(block, amplitude, cor)
    run = simulate(block, None, cor=cor, theta0=release,
                   duration=2.5 * theory.exact_period(block, release))
    record = measure(run, block, run.motion, sensors if sensors is not None else Sensors(seed=seed))
    t, theta = record.t, record.theta
    if theta is None:
        raise ValueError("sensors must include the potentiometer: the period is measured on "
                         "the recorded angle")
    first_zero = int(np.nonzero(theta < 0.0)[0][0])
    # the extremum of the second half cycle (theta < 0) and its following zero
    after = first_zero + int(np.nonzero(theta[first_zero:] > 0.0)[0][0])
    k = first_zero + int(np.argmin(theta[first_zero:after]))
    y0, y1, y2 = theta[k - 1], theta[k], theta[k + 1]
    shift = 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2)
    t_peak = t[k] + shift * record.dt
    peak = y1 - 0.25 * (y0 - y2) * shift
    t_zero = t[after - 1] - theta[after - 1] * (t[after] - t[after - 1]) / (
        theta[after] - theta[after - 1])
    return abs(float(peak)), 4.0 * float(t_zero - t_peak)


def _release_for(block: Block, amplitude: float, cor: float) -> float:
    """Release angle whose next half cycle has ``amplitude`` [rad] (bisection on Eq. 2-6)."""
    if theory.amplitude_after_impact(block, block.alpha * (1.0 - 1e-6), cor) <= amplitude:
        raise ValueError(f"no release below alpha gives a half cycle of {amplitude:.4g} rad "
                         f"after an impact with COR {cor:g}")
    low, high = amplitude, block.alpha * (1.0 - 1e-9)
    for _ in range(100):
        middle = 0.5 * (low + high)
        if theory.amplitude_after_impact(block, middle, cor) < amplitude:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)
