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

from shaketable.models.stack import Stack
from shaketable.studies.stacks import block_words as block_words
from shaketable.studies.stacks import column_bands
from shaketable.studies.stacks import uplift_threshold as uplift_threshold

#: The columns of :func:`stack_spectrum_bands`' table.
BAND_COLUMNS = ["omega/p [-]", "column", "from [g]", "to [g]", "verdict", "block that fell",
                "Eq. (2-8) as one body [g]", "flagged", "note"]

#: The two columns computed at each pulse frequency.
COLUMNS = ("stack", "bottom block alone")


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
