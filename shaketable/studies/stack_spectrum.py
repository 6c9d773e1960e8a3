"""The overturning spectrum of a stack under half-sine pulses: every overturn/safe band.

As :func:`shaketable.studies.overturning_spectrum.overturning_spectrum` does for one block,
for a column of blocks and for its bottom block alone, at each pulse frequency omega (as
omega / p of the bottom block): the amplitudes are scanned on a geometric grid from half the
lowest uplift threshold (nothing moves below it) to a ceiling above twice Housner's
Eq. (2-8) for the column as one rigid body, each scan point is run (the stack model with
plastic impacts; the block alone with the single-block engine at Housner's COR, the plastic
law's one-block case), and every change of verdict between neighbouring points (safe, or
which block fell) is bisected. The result is every band, the safe bands above the lowest
overturning amplitude included, with the block that fell in each.

A run overturns when a block falls within ``after`` seconds of the pulse's end (a stack
has no closed-form decision after the pulse, as the single block has). Near an edge the
column hangs near its balance and falls late: with 10 s (the default) the edges of a block
alone are those of the exact single-block spectrum to 0.07 % (omega/p 1 to 6, 8 x 2 ft),
and the lowest edge of two 8 x 2 ft blocks is the same with 10, 20 and 40 s; 2.5 s put
them 0.3-1.7 % (block) and 13 % (stack, omega/p = 3) too high. A band narrower than the
scan step between two points of the same verdict is not seen; the bands found narrower
than the step are flagged.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from shaketable.core.constants import G
from shaketable.models.api import simulate
from shaketable.models.stack import Stack
from shaketable.studies.overturning_spectrum import housner_cor
from shaketable.studies.stacks import (
    centred_only,
    eq_2_8,
    half_sine_pulse,
    quiet_stack_run,
    rigid_stack,
)

#: The columns of :func:`stack_spectrum_bands`' table.
BAND_COLUMNS = ["omega/p [-]", "column", "from [g]", "to [g]", "verdict", "block that fell",
                "Eq. (2-8) as one body [g]", "flagged", "note"]

#: The two columns computed at each pulse frequency.
COLUMNS = ("stack", "bottom block alone")


def block_words(index: int, count: int) -> str:
    """``"block 1 (top)"``; ``"the block"`` for a column of one."""
    if count == 1:
        return "the block"
    return f"block {index}" + (" (bottom)" if index == 0 else
                               " (top)" if index == count - 1 else "")


def uplift_threshold(stack: Stack) -> float:
    """The lowest table acceleration [g] (over g + v'') at which a part of ``stack`` tips as
    one rigid body about a corner of the block below it (the table for j = 0):
    min over j of ``b_j M_j / sum_k>=j m_k (y_k - z_j)``, M_j the mass from block j up, y_k
    a centroid's height and z_j the bottom of block j (``A1``, ``A2`` of two blocks; tan(alpha)
    of one)."""
    centred_only(stack, "uplift_threshold")
    b, h, m = stack.b, stack.h, stack.m
    bottoms = 2.0 * np.concatenate([[0.0], np.cumsum(h)[:-1]])
    centroids = bottoms + h
    return float(min(b[j] * m[j:].sum() / np.sum(m[j:] * (centroids[j:] - bottoms[j]))
                     for j in range(stack.n)))


def _fallen(stack: Stack, amplitude: float, length: float, after: float, rtol: float) -> int:
    """The block that fell under a half-sine of ``amplitude`` [m/s^2] lasting ``length``
    [s] and ``after`` seconds of rest (-1: none fell)."""
    motion = half_sine_pulse(amplitude, length, after)
    if stack.n == 1:
        block = stack.blocks[0]
        return 0 if simulate(block, motion, cor=housner_cor(block)).overturned else -1
    run = quiet_stack_run(stack, motion, rtol=rtol)
    return int(run.overturned_block) if run.status == "overturned" else -1


def column_bands(stack: Stack, omega: float, *, scan_step: float = 0.02, iterations: int = 5,
                 after: float = 10.0, rtol: float = 1e-9) -> tuple[list, int]:
    """Every overturn/safe band of ``stack`` under half-sines of angular frequency ``omega``
    [rad/s] (lasting pi / omega).

    Returns
    -------
    list of dict, int
        The bands, from half the uplift threshold to the ceiling ([g], the block that fell,
        a note for a band narrower than the scan), and the number of runs made.
    """
    length = math.pi / omega
    low = 0.5 * uplift_threshold(stack)
    estimate = eq_2_8(stack, omega)
    top = 2.0 * estimate + 2.0 * math.tan(rigid_stack(stack)["alpha_eq"])
    count = int(math.ceil(math.log(top / low) / math.log1p(scan_step)))
    grid = np.exp(np.linspace(math.log(low), math.log(top), count + 1))
    verdicts = [_fallen(stack, a * G, length, after, rtol) for a in grid]
    runs = grid.size
    edges = []     # (low amplitude, high amplitude, verdict above) of each change, bisected
    brackets = [[grid[k], grid[k + 1], verdicts[k], verdicts[k + 1]]
                for k in range(grid.size - 1) if verdicts[k] != verdicts[k + 1]]
    for _ in range(iterations):
        narrowed = []
        for lo, hi, below, above in brackets:
            middle = math.sqrt(lo * hi)
            verdict = _fallen(stack, middle * G, length, after, rtol)
            runs += 1
            if verdict == below:
                narrowed.append([middle, hi, below, above])
            elif verdict == above:
                narrowed.append([lo, middle, below, above])
            else:   # a third verdict inside: both halves hold a change
                narrowed += [[lo, middle, below, verdict], [middle, hi, verdict, above]]
        brackets = narrowed
    edges = sorted(brackets)
    points = [low] + [0.5 * (lo + hi) for lo, hi, _, _ in edges] + [top]
    classes = [verdicts[0]] + [above for _, _, _, above in edges]
    bands = []
    for k, verdict in enumerate(classes):
        narrow = (0 < k < len(classes) - 1
                  and math.log(points[k + 1] / points[k]) < math.log1p(scan_step))
        bands.append({"from [g]": points[k], "to [g]": points[k + 1],
                      "verdict": "overturns" if verdict >= 0 else "safe",
                      "block that fell": block_words(verdict, stack.n) if verdict >= 0 else "",
                      "Eq. (2-8) as one body [g]": estimate, "flagged": narrow,
                      "note": (f"band narrower than the scan step ({scan_step:g} relative): "
                               "one as narrow between scan points of the same verdict "
                               "would not be seen" if narrow else
                               "up to the ceiling" if k == len(classes) - 1 else "")})
    return bands, runs


def stack_spectrum_bands(stack: Stack, ratios, *, scan_step: float = 0.02,
                         iterations: int = 5, after: float = 10.0,
                         rtol: float = 1e-9) -> pd.DataFrame:
    """Every overturn/safe band of ``stack`` and of its bottom block alone under half-sine
    pulses, at each ``omega / p`` of ``ratios`` (p of the bottom block).

    Parameters
    ----------
    stack : Stack
    ratios : sequence of float
        omega / p of the bottom block [-].
    scan_step : float
        Relative step of the amplitude scan [-] (0.02: about 100 runs per factor 7).
    iterations : int
        Bisections of each change of verdict (its bracket ends ``scan_step / 2**iterations``
        relative wide).
    after : float
        Seconds after the pulse within which a fall counts [s] (default 10).
    rtol : float
        Relative tolerance of the stack engine.

    Returns
    -------
    DataFrame
        One row per band, :data:`BAND_COLUMNS` (amplitudes in g); ``attrs["runs"]`` the
        number of runs.
    """
    if not 0 < scan_step < 1:
        raise ValueError(f"scan_step must be in (0, 1), got {scan_step!r}")
    bottom = Stack((stack.blocks[0],))
    rows, runs = [], 0
    for ratio in ratios:
        omega = float(ratio) * stack.blocks[0].p
        for label, column in zip(COLUMNS, (stack, bottom)):
            bands, count = column_bands(column, omega, scan_step=scan_step,
                                        iterations=iterations, after=after, rtol=rtol)
            runs += count
            rows += [{"omega/p [-]": float(ratio), "column": label, **band} for band in bands]
    frame = pd.DataFrame(rows, columns=BAND_COLUMNS)
    frame.attrs["runs"] = runs
    return frame


def lowest_overturning(frame: pd.DataFrame, ratio: float, column: str) -> float:
    """The lowest overturning amplitude [g] of one column at one omega/p of a band table
    (NaN when none overturns up to the ceiling)."""
    rows = frame[np.isclose(frame["omega/p [-]"], ratio) & (frame["column"] == column)
                 & (frame["verdict"] == "overturns")]
    return float(rows["from [g]"].min()) if len(rows) else math.nan
