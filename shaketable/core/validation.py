"""Checks of scalar arguments shared by the modules: a clear ValueError naming the parameter."""

from __future__ import annotations

import math
import numbers

import numpy as np


def number(name: str, value) -> float:
    """``value`` as a finite float, else a ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, np.floating,
                                                        np.integer)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return value


def positive(name: str, value, unit: str = "") -> float:
    """A finite positive number; ``unit`` (e.g. ``" [Hz]"``) is quoted in the message."""
    value = number(name, value)
    if value <= 0.0:
        raise ValueError(f"{name} must be positive{unit}, got {value!r}")
    return value


def nonnegative(name: str, value, unit: str = "") -> float:
    """A finite number, zero or positive; ``unit`` is quoted in the message."""
    value = number(name, value)
    if value < 0.0:
        raise ValueError(f"{name} must be zero or positive{unit}, got {value!r}")
    return value


def integer(name: str, value, low: int, high: int) -> int:
    """An integer (Python or NumPy, not a bool) from ``low`` to ``high`` inclusive."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)) \
            or not low <= value <= high:
        raise ValueError(f"{name} must be an integer from {low} to {high}, got {value!r}")
    return int(value)


def in_range(name: str, value, low: float = -math.inf, high: float = math.inf,
             low_open: bool = False) -> float:
    """A finite number in ``[low, high]`` (``(low, high]`` if ``low_open``)."""
    value = number(name, value)
    if value < low or value > high or (low_open and value == low):
        bracket = "(" if low_open else "["
        raise ValueError(f"{name} must be in {bracket}{low}, {high}], got {value!r}")
    return value


def seed(name: str, value) -> int | None:
    """A random seed: a non-negative integer, or None for fresh entropy."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)) \
            or value < 0:
        raise ValueError(f"{name} must be a non-negative integer or None, got {value!r}")
    return int(value)
