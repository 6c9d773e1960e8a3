"""Checks of scalar arguments shared by the modules: a clear ValueError naming the parameter."""

from __future__ import annotations

import math
import numbers

import numpy as np

from .motion import Motion


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


def motion_argument(name: str, motion) -> Motion:
    """``motion`` if it is a :class:`~shaketable.motion.Motion`, else a ValueError naming ``name``."""
    if not isinstance(motion, Motion):
        raise ValueError(f"{name} must be a shaketable Motion, got {type(motion).__name__}")
    return motion
