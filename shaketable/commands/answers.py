"""The answer of a run in the user's units, first: what the commands print before details.

An engineer deciding about a block reads the verdict, max θ/α, the overturn time,
the peak slip, the corner excursion (the clearance the block needs) and when it came to
rest; these lines give them, lengths in the unit the block was given in
(:attr:`shaketable.core.geometry.Block.length_unit`, :func:`shaketable.core.units.format_length`).
Time spent in each mode is a detail and comes last.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.units import format_length, shared_length_unit
from shaketable.studies.free_rocking import (
    impacts_words,
    is_free,
    rocking_rest_time,
)


def _seconds(value: float) -> str:
    return f"{value:.2f} s"


def planar_rest_time(result) -> float:
    """When a planar block (:class:`~shaketable.models.planar.result.PlanarResult`) came to
    rest for good [s]: the start of the rest it ends the run in; NaN when it overturned
    or is still moving at the end, 0 when it never moved."""
    from shaketable.models.planar.result import MODES

    rest = MODES.index("rest")
    if result.overturned or int(result.mode[-1]) != rest:
        return math.nan
    if not math.isfinite(result.t_start):
        return 0.0
    events = result.events
    if result.n_events <= events.shape[0]:     # every event recorded: the exact instant
        into_rest = events[(events[:, 3] == rest) & (events[:, 2] != rest), 0]
        if into_rest.size:
            return float(into_rest[-1])
    moving = np.flatnonzero(result.mode != rest)
    return float(result.t[moving[-1] + 1]) if moving.size else 0.0


def _rest_line(rest: float, result) -> str:
    if result.overturned:
        return "came to rest: no, it overturned"
    if math.isnan(rest):
        return f"came to rest: no, still moving at the end of the run (t = {result.t[-1]:.2f} s)"
    if rest == 0.0:
        return "came to rest: it never moved"
    return f"came to rest at t = {_seconds(rest)}"


def _ratio_line(result) -> str:
    if result.overturned:
        return (f"max θ/α: F (overturned); overturn time {_seconds(result.t_overturn)}"
                f" ({'+' if result.overturn_direction > 0 else '-'}x side)")
    if not result.max_theta_ratio > 1e-9:   # below rounding: the block only slid or stood
        return "max θ/α 0: did not rock; did not overturn"
    when = (f"at the release (t = {_seconds(result.t_max)})"
            if result.t_max == result.t[0] and result.theta[0] != 0.0
            else f"at t = {_seconds(result.t_max)}")
    return f"max θ/α {result.max_theta_ratio:.3g} {when}; did not overturn"


def planar_answer(result) -> list[str]:
    """The answer lines of a planar (friction) run, in the block's units."""
    # the base's slip on the table (not the midpoint's motion, which rocking moves too)
    base, when = result.peak_base_slip, result.t_peak_base_slip
    if math.isnan(base):
        base, when = result.peak_slip, result.t_peak_slip
    slid = base > 1e-9 * result.block.height   # below: rounding of a corner that did not slide
    # one unit for the answer's lengths: the block's, or the smaller one a length needs
    unit = shared_length_unit((base if slid else 0.0, result.peak_excursion),
                              result.block.length_unit)
    residual = format_length(result.residual_slip, unit, signed=True)
    lines = [_ratio_line(result),
             f"peak slip of the base {format_length(base, unit)} at t = {_seconds(when)}, "
             f"base midpoint at the end {residual}"
             if slid else "peak slip 0: the base never slid",
             f"corner excursion (the clearance it needs) "
             f"{format_length(result.peak_excursion, unit)}",
             _rest_line(planar_rest_time(result), result)]
    in_mode = ", ".join(f"{name} {_seconds(seconds)}" for name, seconds in
                        result.time_in_mode.items() if seconds > 0)
    lines.append(f"time in each mode: {in_mode}")
    return lines


def rocking_answer(result) -> list[str]:
    """The answer lines of a rocking run (after its verdict)."""
    if result.status == "airborne":
        return [f"the block leaves the ground at t = {_seconds(result.t_airborne)}: "
                "outside the model, the run stops there"]
    rest = _rest_line(rocking_rest_time(result), result)
    if is_free(result) and result.status == "completed" and math.isfinite(result.t_start):
        # released on a still table: when it came to rest first, its max is the release
        return [rest, impacts_words(result), _ratio_line(result)]
    return [_ratio_line(result), rest]


def rocking_heading(result) -> str:
    """What a rocking run's first line says after the block: its verdict (for free
    rocking, when it came to rest and after how many cycles)."""
    return result.verdict()


def free_periods_line(runs) -> str:
    """``"the period grows with the amplitude: 0.70 s from θ/α = 0.2, 2.30 s from 0.8
    (4 x the time to the first impact)"``: runs released from several angles on a still
    table (Eq. 2-5); "" for any other set of runs."""
    from shaketable.models.rocking.free_rocking import first_period

    if len(runs) < 2 or not all(is_free(run) and run.theta[0] != 0.0 for run in runs):
        return ""
    pairs = sorted((abs(run.theta[0]) / run.block.alpha, first_period(run)) for run in runs)
    if any(math.isnan(period) for _, period in pairs):
        return ""
    grows = all(b[1] > a[1] for a, b in zip(pairs, pairs[1:]))
    said = ", ".join(f"{period:.2f} s from θ/α = {ratio:.3g}" for ratio, period in pairs)
    return (f"the period {'grows with' if grows else 'changes with'} the amplitude: {said} "
            "(4 x the time from the release to the first impact)")
