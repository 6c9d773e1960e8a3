"""Checks of scalar arguments shared by the modules: a clear ValueError naming the parameter."""

from __future__ import annotations

import math
import numbers

import numpy as np


def number(name: str, value: object) -> float:
    """``value`` as a finite float, else a ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, np.floating,
                                                        np.integer)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return value


def positive(name: str, value: object, unit: str = "") -> float:
    """A finite positive number; ``unit`` (e.g. ``" [Hz]"``) is quoted in the message."""
    value = number(name, value)
    if value <= 0.0:
        raise ValueError(f"{name} must be positive{unit}, got {value!r}")
    return value


def nonnegative(name: str, value: object, unit: str = "") -> float:
    """A finite number, zero or positive; ``unit`` is quoted in the message."""
    value = number(name, value)
    if value < 0.0:
        raise ValueError(f"{name} must be zero or positive{unit}, got {value!r}")
    return value


def integer(name: str, value: object, low: int, high: int) -> int:
    """An integer (Python or NumPy, not a bool) from ``low`` to ``high`` inclusive."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)) \
            or not low <= int(value) <= high:
        raise ValueError(f"{name} must be an integer from {low} to {high}, got {value!r}")
    return int(value)


def in_range(name: str, value: object, low: float = -math.inf, high: float = math.inf,
             low_open: bool = False) -> float:
    """A finite number in ``[low, high]`` (``(low, high]`` if ``low_open``)."""
    value = number(name, value)
    if value < low or value > high or (low_open and value == low):
        bracket = "(" if low_open else "["
        raise ValueError(f"{name} must be in {bracket}{low}, {high}], got {value!r}")
    return value


def seed(name: str, value: object) -> int | None:
    """A random seed: a non-negative integer, or None for fresh entropy."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)) \
            or int(value) < 0:
        raise ValueError(f"{name} must be a non-negative integer or None, got {value!r}")
    return int(value)


#: Most samples a motion or a run may have: 10 million samples (a day of record at
#: 0.01 s is 8.6 million); the arrays of one run then take about 0.6 GB.
MAX_SAMPLES = 10_000_000

#: Most fixed steps (samples x subdivisions) a fixed-step method may take in one run
#: (about a minute of the predictor-corrector on one core).
MAX_FIXED_STEPS = 2_000_000_000


def sample_count(count: float, what: str) -> int:
    """A number of samples checked against :data:`MAX_SAMPLES` before anything is allocated.

    Parameters
    ----------
    count : float
        The number of samples asked for (may be huge or not finite).
    what : str
        How it was asked for, for the message, e.g. ``"duration 1e9 s at dt 0.005 s"``.
    """
    if not math.isfinite(count) or count > MAX_SAMPLES:
        shown = f"{count:.3g}" if math.isfinite(count) else "infinitely many"
        raise ValueError(f"{what} asks for {shown} samples; the limit is {MAX_SAMPLES:,} "
                         f"samples per motion or run (shorten the run or use a longer "
                         f"sample interval)")
    return int(count)
