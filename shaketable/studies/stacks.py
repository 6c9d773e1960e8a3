"""Stacks beside single blocks: the report's shielding blocks stacked, uplift thresholds and
pulse overturning amplitudes, each against its closed form (``docs/stack.md``).

The report's shielding blocks are "often stacked as much as 20 feet high" (Section 1);
its Section 4 computes one block at a time. This study sets a column of the report's
blocks beside the block alone:

* :func:`record_runs`: a block of Section 4 alone (the single-block engine at Housner's
  COR 1 - 1.5 sin^2(alpha), the plastic law's one-block case) and stacked two and three
  high (the stack model, plastic impacts) under a record of Section 4 with its vertical;
* :func:`uplift_thresholds`: the table acceleration at which a two-block stack starts to
  rock, from a slowly rising acceleration, against the closed form
  ``(g + v'') min(A1, A2)``, ``A1 = b1 (m1 + m2) / (m1 h1 + m2 (2 h1 + h2))`` (the whole
  stack about a base corner), ``A2 = b2 / h2`` (the top block alone), and the bottom block
  alone ``tan(alpha1)`` (Eq. 2-1);
* :func:`pulse_amplitudes`: the smallest half-sine pulse that overturns a block alone and
  the same block two high (the lowest edge of :func:`column_bands`, the scan of every
  overturn/safe band that ``spectrum --stack`` draws,
  :mod:`shaketable.studies.stack_spectrum`), against the half-sine estimate of Eq. (2-8),
  ``a / (g alpha) = sqrt(1 + (omega / p)^2)``, written for the stack rocking as one rigid
  body with its own ``alpha_eq = atan(b1 / y_c)`` and ``p_eq^2 = M g R_c / I_O``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.api import simulate
from shaketable.models.stack import (
    Stack,
    StackFrictionWarning,
    StackRetryWarning,
    StackTensionWarning,
    simulate_stack,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def housner_cor(block: Block) -> float:
    """Housner's COR 1 - 1.5 sin^2(alpha) [-]: the plastic impact law of one block."""
    return 1.0 - 1.5 * math.sin(block.alpha) ** 2


def quiet_stack_run(stack: Stack, motion: Motion | None, **options):
    """One stack run; its warnings are not shown: the study counts its assumption warnings,
    and a run made again at a tighter tolerance says it in ``statistics["rtol"]``."""
    with warnings.catch_warnings():
        for category in (StackTensionWarning, StackFrictionWarning, StackRetryWarning):
            warnings.simplefilter("ignore", category)
        return simulate_stack(stack, motion, **options)


# ----------------------------------------------------------------------------- closed forms
def centred_only(stack: Stack, what: str) -> None:
    """Refuse a stack with offsets in the closed forms of centred columns (``what`` names
    the function): a ValueError naming ``Stack.offsets``."""
    if stack.offsets is not None and any(stack.offsets):
        raise ValueError(f"{what} is the closed form of a centred column; Stack.offsets = "
                         f"{stack.offsets!r} is not zero (docs/stack.md, Offsets, gives the "
                         "thresholds with offsets)")


def rigid_stack(stack: Stack) -> dict:
    """The stack as one rigid body rocking on a base corner (check 2 of ``docs/stack.md``).

    Returns
    -------
    dict
        ``I_O`` [kg m^2] (about the base corner), ``y_c`` [m] (height of the centre of
        mass), ``R_c`` [m], ``alpha_eq`` = atan(b1 / y_c) [rad], ``p_eq`` =
        sqrt(M g R_c / I_O) [rad/s].
    """
    centred_only(stack, "rigid_stack")
    b, h, m = stack.b, stack.h, stack.m
    y = 2.0 * np.concatenate([[0.0], np.cumsum(h)[:-1]]) + h   # centroid heights
    inertia = float(np.sum(m * ((b ** 2 + h ** 2) / 3.0 + b[0] ** 2 + y ** 2)))
    y_c = float(np.sum(m * y) / m.sum())
    r_c = math.hypot(b[0], y_c)
    return {"I_O": inertia, "y_c": y_c, "R_c": r_c, "alpha_eq": math.atan(b[0] / y_c),
            "p_eq": math.sqrt(m.sum() * G * r_c / inertia)}


def uplift_closed_form(stack: Stack) -> tuple[float, float]:
    """``(A1, A2)`` of a two-block stack [-]: the whole stack about a base corner and the
    top block alone (the uplift thresholds over g + v'')."""
    centred_only(stack, "uplift_closed_form")
    (b1, b2), (h1, h2), (m1, m2) = stack.b, stack.h, stack.m
    return b1 * (m1 + m2) / (m1 * h1 + m2 * (2.0 * h1 + h2)), b2 / h2


# ----------------------------------------------------------------------------- records
def record_runs(block: Block, motion: Motion, heights=(1, 2, 3), rtol: float = 1e-10,
                record: str = "") -> pd.DataFrame:
    """``block`` alone and stacked ``heights`` high under ``motion``.

    One block: the single-block engine at Housner's COR (the plastic law's one-block
    case). Two or more: the stack model, plastic impacts, DOP853 at ``rtol``.

    Returns
    -------
    DataFrame
        One row per height: verdict, t_overturn [s] and which block, first uplift [s],
        max theta/alpha of each block (bottom first), when the contacts first needed
        F/N > 1 or pulled [s] (the model's assumptions failing), and the tolerance a
        stack was computed at (``rtol [-]``: ``rtol``, or tighter after a stall at it;
        NaN for the block alone).
    """
    rows = []
    for count in heights:
        row = {"record": record, "block": block.describe(), "blocks high": count,
               "height [ft]": count * block.height / 0.3048}
        if count == 1:
            run = simulate(block, motion, cor=housner_cor(block))
            row.update({"verdict": ("F" if run.overturned else "rocked" if math.isfinite(run.t_start)
                                    else "at rest"),
                        "t_overturn [s]": run.t_overturn if run.overturned else math.nan,
                        "overturned block": 0 if run.overturned else -1,
                        "t_uplift [s]": run.t_start,
                        "max theta/alpha": f"{run.max_theta_ratio:.3g}" if not run.overturned
                        else "F",
                        "F/N > 1 from [s]": math.nan, "tension from [s]": math.nan,
                        "rtol [-]": math.nan})
        else:
            stack = Stack((block,) * count)
            run = quiet_stack_run(stack, motion, rtol=rtol)
            ratios = np.abs(run.theta).max(axis=0) / block.alpha
            words = ["F" if run.status == "overturned" and i >= run.overturned_block
                     else f"{ratio:.3g}" for i, ratio in enumerate(ratios)]
            summary = run.summary()
            verdict = ("F" if run.status == "overturned" else run.status
                       if run.status != "completed" else "rocked"
                       if math.isfinite(summary["t_start [s]"]) else "at rest")
            row.update({"verdict": verdict,
                        "t_overturn [s]": run.t_overturn,
                        "overturned block": run.overturned_block,
                        "t_uplift [s]": summary["t_start [s]"],
                        "max theta/alpha": ", ".join(words),
                        "F/N > 1 from [s]": summary["t_friction_exceeded [s]"],
                        "tension from [s]": summary["t_tension [s]"],
                        "rtol [-]": run.statistics["rtol"]})
        rows.append(row)
    return pd.DataFrame(rows)


# ----------------------------------------------------------------------------- uplift
def ramp(rate: float, duration: float) -> Motion:
    """A table acceleration rising at ``rate`` [m/s^3] from rest for ``duration`` [s]."""
    return Motion(np.array([0.0, duration]), np.array([0.0, rate * duration]), name="ramp")


def uplift_thresholds(cases, rate: float = 0.5 * G, duration: float = 0.8) -> pd.DataFrame:
    """The uplift threshold of each two-block stack of ``cases`` from a slowly rising
    table acceleration, beside the closed form.

    Parameters
    ----------
    cases : iterable of (str, Stack)
        A label and a two-block stack.
    rate : float
        Rate of the rising acceleration [m/s^3]: the first uplift at time t is the
        threshold ``rate t`` (the resting stack's corner forces are linear in time and
        their zero is found exactly).
    duration : float
        Length of each ramp [s] (``rate duration`` must pass every threshold).

    Returns
    -------
    DataFrame
        label, mass ratio m2/m1, A1, A2, closed form min(A1, A2), computed [g], relative
        difference, the pattern entered and the one the closed form names, the bottom
        block alone tan(alpha1) (Eq. 2-1).
    """
    from shaketable.models.stack import pattern_name

    rows = []
    motion = ramp(rate, duration)
    for label, stack in cases:
        a1, a2 = uplift_closed_form(stack)
        run = quiet_stack_run(stack, motion)
        uplift = next((event for event in run.events if event["kind"] == "uplift"), None)
        computed = math.nan if uplift is None else rate * uplift["t"] / G
        expected = "stack as one body (+)" if a1 < a2 else "top alone (+)"
        rows.append({"stack": label, "m2/m1 [-]": float(stack.m[1] / stack.m[0]),
                     "b1 [m]": stack.b[0], "h1 [m]": stack.h[0], "b2 [m]": stack.b[1],
                     "h2 [m]": stack.h[1],
                     "A1 [-]": a1, "A2 [-]": a2, "closed form min(A1, A2) [g]": min(a1, a2),
                     "computed [g]": computed,
                     "relative difference [-]": computed / min(a1, a2) - 1.0,
                     "pattern entered": "none" if uplift is None
                     else pattern_name(uplift["pattern_after"]),
                     "pattern of the closed form": expected,
                     "bottom block alone tan(alpha1) [g]": math.tan(stack.blocks[0].alpha)})
    return pd.DataFrame(rows)


# ----------------------------------------------------------------------------- pulses
def half_sine_pulse(amplitude: float, length: float, after: float, samples: int = 40) -> Motion:
    """A half sine of ``amplitude`` [m/s^2] lasting ``length`` [s], then the table at rest
    for ``after`` [s] (sampled every 0.05 s: nothing to resolve)."""
    t = np.linspace(0.0, length, samples + 1)
    tail = np.arange(length + 0.05, length + after + 1e-9, 0.05)
    return Motion(np.concatenate([t, tail]),
                  np.concatenate([amplitude * np.sin(math.pi * t / length),
                                  np.zeros(tail.size)]), name="half-sine pulse")


def eq_2_8(stack: Stack, omega: float) -> float:
    """Housner's half-sine estimate Eq. (2-8) for the column as one rigid body [g]:
    tan(alpha_eq) sqrt(1 + (omega / p_eq)^2) (one block: the report's own)."""
    rigid = rigid_stack(stack)
    return math.tan(rigid["alpha_eq"]) * math.sqrt(1.0 + (omega / rigid["p_eq"]) ** 2)


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
        a note for a band narrower than the scan; ``bracket [g]``: the last bracket of the
        bisection of its lower edge, whose middle is ``from [g]``; NaN, NaN for the first),
        and the number of runs made.
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
    ends = [(math.nan, math.nan)] + [(lo, hi) for lo, hi, _, _ in edges]
    classes = [verdicts[0]] + [above for _, _, _, above in edges]
    bands = []
    for k, verdict in enumerate(classes):
        narrow = (0 < k < len(classes) - 1
                  and math.log(points[k + 1] / points[k]) < math.log1p(scan_step))
        bands.append({"from [g]": points[k], "to [g]": points[k + 1],
                      "verdict": "overturns" if verdict >= 0 else "safe",
                      "block that fell": block_words(verdict, stack.n) if verdict >= 0 else "",
                      "Eq. (2-8) as one body [g]": estimate, "flagged": narrow,
                      "bracket [g]": ends[k],
                      "note": (f"band narrower than the scan step ({scan_step:g} relative): "
                               "one as narrow between scan points of the same verdict "
                               "would not be seen" if narrow else
                               "up to the ceiling" if k == len(classes) - 1 else "")})
    return bands, runs


def column_minimum(stack: Stack, omega: float, iterations: int = 5, after: float = 10.0,
                   rtol: float = 1e-9, scan_step: float = 0.02) -> dict:
    """The smallest half-sine pulse of angular frequency ``omega`` [rad/s] (lasting
    pi / omega) that overturns ``stack`` (one block: the single-block engine at Housner's
    COR): the lowest overturning edge of its overturning spectrum
    (:func:`column_bands`, what ``spectrum --stack``
    gives: a geometric scan of relative step ``scan_step`` from half the uplift threshold,
    each change of verdict bisected ``iterations`` times, so that the bracket is
    ``scan_step / 2**iterations`` relative wide: 0.06 % by default). A run overturns when
    the column falls within ``after`` seconds of the pulse's end (near the minimum a column
    falls late: 2.5 s put the two-high minimum 13 % high; 10 s gives the answer of 20 s and
    40 s).

    Returns
    -------
    dict
        ``stands [g]`` and ``falls [g]`` (the bracket), ``minimum [g]`` (its middle, the
        spectrum's edge; NaN when nothing overturns up to the spectrum's ceiling) and
        ``Eq. (2-8) as one body [g]``.
    """
    bands, _ = column_bands(stack, omega, scan_step=scan_step, iterations=iterations,
                            after=after, rtol=rtol)
    edge = next((band for band in bands if band["verdict"] == "overturns"), None)
    stands, falls = (math.nan, math.nan) if edge is None else edge["bracket [g]"]
    return {"stands [g]": stands, "falls [g]": falls,
            "minimum [g]": math.nan if edge is None else edge["from [g]"],
            "Eq. (2-8) as one body [g]": eq_2_8(stack, omega)}


def eq_2_8_curves(stack: Stack, ratios) -> dict:
    """:func:`eq_2_8` of ``stack`` and of its bottom block alone over ``ratios`` (omega/p
    of the bottom block): ``{"stack": (ratios, [g]), "bottom block alone": (ratios, [g])}``."""
    ratios = np.asarray(ratios, dtype=float)
    p = stack.blocks[0].p
    return {label: (ratios, np.array([eq_2_8(column, ratio * p) for ratio in ratios]))
            for label, column in (("stack", stack), ("bottom block alone",
                                                     Stack((stack.blocks[0],))))}


def pulse_amplitudes(block: Block, ratios=(3.0,), heights=(1, 2), iterations: int = 5,
                     after: float = 10.0, rtol: float = 1e-9) -> pd.DataFrame:
    """The smallest half-sine pulse that overturns ``block`` alone and stacked
    ``heights`` high, for each ``omega / p`` of ``ratios`` (p of the block alone)
    (:func:`column_minimum`).

    Returns
    -------
    DataFrame
        omega/p, blocks high, the bracket found [g] (stands, falls), its middle, and
        Eq. (2-8) for the column as one body [g].
    """
    rows = []
    for ratio in ratios:
        for count in heights:
            rows.append({"omega/p [-]": ratio, "blocks high": count,
                         **column_minimum(Stack((block,) * count), ratio * block.p,
                                          iterations, after, rtol)})
    return pd.DataFrame(rows)


# ----------------------------------------------------------------------------- the study
@dataclass(frozen=True)
class StacksStudy:
    """The three parts of the study (:func:`stacks_study`); ``plot()`` draws them."""

    records: pd.DataFrame
    uplift: pd.DataFrame
    pulses: pd.DataFrame
    block: Block

    def plot(self) -> "Figure":
        from shaketable.plots.stack_studies import stacks_study_figure

        return stacks_study_figure(self)


def uplift_cases(block: Block, slender_top: Block, mass_ratios=(0.25, 1.0, 4.0)) -> list:
    """Two-block stacks of the study: ``block`` on ``block`` and ``slender_top`` on
    ``block``, at each mass ratio m2/m1 (the closed form's two branches)."""
    cases = []
    for top in (block, slender_top):
        for ratio in mass_ratios:
            label = f"{top.describe()} on {block.describe()}"
            cases.append((label, Stack((block, top), masses=(1.0, ratio))))
    return cases


def stacks_study(block: Block, records: dict, slender_top: Block, window: float,
                 heights=(1, 2, 3), ratios=(3.0,), iterations: int = 5,
                 rtol: float = 1e-10, rest: float = 0.0) -> StacksStudy:
    """The three parts for ``block`` under ``records`` (name -> Motion), each cut to
    ``window`` seconds [s] and followed by ``rest`` seconds of the table at rest [s] (a
    column still falling when the record is cut falls within it)."""
    from shaketable.models.rocking.run import extended

    frames = [record_runs(block, extended(extended(motion, window), window + rest), heights,
                          rtol=rtol, record=name)
              for name, motion in records.items()]
    return StacksStudy(records=pd.concat(frames, ignore_index=True),
                       uplift=uplift_thresholds(uplift_cases(block, slender_top)),
                       pulses=pulse_amplitudes(block, ratios=ratios, iterations=iterations),
                       block=block)


def retried_runs(records: pd.DataFrame, rtol: float) -> str:
    """The runs of :func:`record_runs`' rows computed at a tighter tolerance than ``rtol``
    (a stall at it, run again), for the text that states ``rtol``: ``"; three high under
    pacoima-dam-s16e at rtol 1e-08 (a stall at 1e-07)"``; "" when none was."""
    tighter = records[records["rtol [-]"] < rtol]
    return "".join(f"; {_heights_words(int(row['blocks high']))} under {row['record']} at "
                   f"rtol {row['rtol [-]']:g} (a stall at {rtol:g})"
                   for _, row in tighter.iterrows())


def _heights_words(count: int) -> str:
    return {1: "alone", 2: "two high", 3: "three high"}.get(count, f"{count} high")


def stacks_answer(records: pd.DataFrame, uplift: pd.DataFrame,
                  pulses: pd.DataFrame) -> list[str]:
    """What the study concludes, in a line per part (the tables of
    :func:`stacks_study`, as its CSVs hold them): which columns overturned under each
    record, how the uplift thresholds compare with their closed form, and the smallest
    overturning pulse alone and stacked."""
    lines = []
    for (record, block), rows in records.groupby(["record", "block"], sort=False):
        said = []
        for _, row in rows.iterrows():
            high = _heights_words(int(row["blocks high"]))
            if row["verdict"] == "F":
                said.append(f"{high} overturns at {float(row['t_overturn [s]']):.2f} s "
                            f"(block {int(row['overturned block'])})")
            else:
                said.append(f"{high} stands (max θ/α {row['max theta/alpha']})")
        lines.append(f"{block} block under {record}: " + "; ".join(said))
    agree = int((uplift["pattern entered"] == uplift["pattern of the closed form"]).sum())
    worst = float(np.nanmax(np.abs(uplift["relative difference [-]"])))
    computed = uplift["computed [g]"]
    alone = uplift["bottom block alone tan(alpha1) [g]"]
    lower = int((computed < alone).sum())
    lines.append(f"uplift thresholds agree with the closed form g min(A1, A2) in {agree} of "
                 f"{len(uplift)} stacks (largest relative difference {worst:.1e}); stacking "
                 f"lowers the threshold in {lower} of {len(uplift)} "
                 f"({computed.min():.3g}-{computed.max():.3g} g against tan α1 = "
                 f"{alone.max():.3g} g alone)")
    for ratio, rows in pulses.groupby("omega/p [-]", sort=False):
        minima = ", ".join(f"{row['minimum [g]']:.3g} g "
                           f"{_heights_words(int(row['blocks high']))}"
                           for _, row in rows.iterrows())
        lines.append(f"smallest half-sine pulse that overturns it at ω/p = {ratio:g}: {minima}")
    return lines
