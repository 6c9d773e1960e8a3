"""Uniform time grids: making them and checking that a motion has one.

Generators sample their motions on :func:`time_grid`; the signal utilities and
the table's command need a constant sample interval and ask
:func:`uniform_step` for it.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from shaketable.core.validation import sample_count

#: Relative tolerance used to decide that a motion is uniformly sampled.
UNIFORM_RTOL = 1e-6


def uniform_step(times: npt.ArrayLike, what: str) -> float:
    """Sample interval of uniformly sampled times [s].

    Parameters
    ----------
    times : array_like
        Sample times [s], increasing.
    what : str
        What needs the uniform sampling (named in the error).

    Raises
    ------
    ValueError
        If the steps differ from their mean by more than :data:`UNIFORM_RTOL`
        of it.
    """
    steps = np.diff(np.asarray(times, dtype=float))
    dt = float(np.mean(steps))
    if np.max(np.abs(steps - dt)) > UNIFORM_RTOL * dt:
        raise ValueError(
            f"{what} needs a uniformly sampled motion; this one has steps from "
            f"{steps.min()!r} to {steps.max()!r} s (use Motion.subdivided or "
            "interpolate onto a uniform grid first)"
        )
    return dt


def time_grid(total: float, dt: float) -> np.ndarray:
    """Times ``0, dt, 2 dt, ...`` up to ``total`` (inclusive within rounding) [s].

    Parameters
    ----------
    total : float
        Length of the grid [s], positive.
    dt : float
        Sample interval [s], positive.

    Raises
    ------
    ValueError
        If the grid would hold fewer than two samples, or too many to allocate.
    """
    n = sample_count(math.floor(total / dt + 1e-9) + 1,
                     f"duration {total:g} s at dt = {dt:g} s")
    if n < 2:
        raise ValueError(
            f"duration {total!r} s is shorter than one sample interval dt = {dt!r} s"
        )
    return dt * np.arange(n)
