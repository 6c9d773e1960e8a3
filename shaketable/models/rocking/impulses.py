"""Runs with ground-velocity steps: the run split at each step, the state jumped.

:func:`simulate_impulsive` runs the smooth part of an
:class:`~shaketable.core.impulses.ImpulsiveMotion` piece by piece with
:func:`shaketable.models.api.simulate` (the engine unchanged), from each
step's instant to the next; at a step it adds the exact jump of theta'
(:func:`~shaketable.core.impulses.theta_dot_jump`, the angular-momentum
balance about the pivot) to the state the previous piece ended with and
restarts the engine from it. An impact that falls on the instant of a step
is resolved by the piece that ends there first (the step acts just after
it). A run that overturns stops; the pieces' results are joined into one
:class:`~shaketable.models.rocking.result.RockingResult` whose ``t`` holds each step's
instant twice (the state before and after the jump).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from shaketable.core.impulses import ImpulsiveMotion, theta_dot_jump
from shaketable.core.motion import Motion
from shaketable.core.validation import in_range
from shaketable.models.rocking.result import RockingResult


def _piece(motion: Motion, start: float, end: float) -> Motion:
    """The motion between ``start`` and ``end`` [s], ends interpolated (it is linear between samples)."""
    t = motion.t
    inside = (t > start) & (t < end)
    times = np.concatenate([[start], t[inside], [end]])
    horizontal = np.interp(times, t, motion.horizontal)
    vertical = None if motion.vertical is None else np.interp(times, t, motion.vertical)
    rotation = None if motion.rotation is None else np.interp(times, t, motion.rotation)
    # samples within 1 ns of an end are dropped (Motion's minimum interval)
    keep = np.concatenate([[True], np.diff(times) > 2e-9])
    keep[-1] = True
    if keep.sum() > 2 and times[-1] - times[keep][-2] <= 2e-9:
        keep[np.flatnonzero(keep)[-2]] = False
    return Motion(times[keep], horizontal[keep],
                  None if vertical is None else vertical[keep], name=motion.name,
                  rotation=None if rotation is None else rotation[keep])


def _first(values) -> float:
    finite = [v for v in values if np.isfinite(v)]
    return finite[0] if finite else math.nan


def simulate_impulsive(block, motion: ImpulsiveMotion, *, simulate: Callable[..., RockingResult],
                       cor: float, theta0: float = 0.0, theta_dot0: float = 0.0,
                       method: str = "fast", **options) -> RockingResult:
    """:func:`~shaketable.models.api.simulate` of a motion with velocity steps.

    Parameters are those of :func:`~shaketable.models.api.simulate`; ``duration``
    cuts or pads the smooth part (every step must then still lie inside it).
    ``simulate`` is the function that runs each smooth piece (the caller passes
    :func:`~shaketable.models.api.simulate`, which sits above this module).
    """
    base = motion.motion
    duration = options.pop("duration", None)
    if duration is not None:        # cut or padded with the table at rest, as simulate does
        from shaketable.models.rocking.run import extended

        start = float(base.t[0])
        base = extended(base, in_range("duration", duration, 0.0, low_open=True))
        motion = ImpulsiveMotion(base, tuple(t - start for t in motion.times),
                                 motion.velocity_steps)
    bounds = [float(base.t[0]), *motion.times, float(base.t[-1])]
    theta, rate = float(theta0), float(theta_dot0)
    pieces = []
    for k in range(len(bounds) - 1):
        if k > 0:
            rate += theta_dot_jump(theta, motion.velocity_steps[k - 1], block.alpha, block.R,
                                   linear=method == "linear")
        if bounds[k + 1] == bounds[k]:      # a step at the motion's first sample
            continue
        result = simulate(block, _piece(base, bounds[k], bounds[k + 1]), cor=cor, theta0=theta,
                          theta_dot0=rate, method=method, **options)
        pieces.append((bounds[k], result))
        theta, rate = float(result.theta[-1]), float(result.theta_dot[-1])
        if result.status != "completed":
            break
    return _joined(block, motion, cor, method, pieces)


def _joined(block, motion, cor, method, pieces) -> RockingResult:
    shift = [start - float(r.motion.t[0]) for start, r in pieces]
    results = [r for _, r in pieces]
    last = results[-1]
    peak = int(np.argmax([r.max_abs_theta for r in results]))
    first_unstable = next((k for k, r in enumerate(results) if np.isfinite(r.t_unstable)), None)
    statistics: dict = {}
    for r in results:
        for key, value in r.statistics.items():
            statistics[key] = statistics.get(key, 0) + value
    return RockingResult(
        block=block, motion=motion.motion, cor=cor, method=method,
        t=np.concatenate([r.t + s for r, s in zip(results, shift)]),
        theta=np.concatenate([r.theta for r in results]),
        theta_dot=np.concatenate([r.theta_dot for r in results]),
        theta_ddot=np.concatenate([r.theta_ddot for r in results]),
        impact_times=np.concatenate([r.impact_times + s for r, s in zip(results, shift)]),
        impact_velocities=np.concatenate([r.impact_velocities for r in results]),
        t_start=_first([r.t_start + s for r, s in zip(results, shift)]),
        t_unstable=(math.nan if first_unstable is None
                    else results[first_unstable].t_unstable + shift[first_unstable]),
        unstable_direction=0 if first_unstable is None
        else results[first_unstable].unstable_direction,
        t_overturn=last.t_overturn + shift[-1], overturn_direction=last.overturn_direction,
        t_airborne=last.t_airborne + shift[-1],
        t_rest=last.t_rest + shift[-1],
        max_abs_theta=results[peak].max_abs_theta, t_max=results[peak].t_max + shift[peak],
        n_impacts=sum(r.n_impacts for r in results), cascades=sum(r.cascades for r in results),
        status=last.status, statistics=statistics)
