"""Checks of scalar arguments shared by the modules: a clear ValueError naming the parameter."""

from __future__ import annotations

import functools
import math
import numbers
from collections.abc import Callable, Iterable
from typing import ParamSpec, TypeVar

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


def unknown_keys(table: Iterable[str], allowed: Iterable[str]) -> list[str]:
    """The keys of an input section ``table`` that it does not take (``allowed``), sorted:
    the first, named in the caller's message, is the same whatever the order written."""
    return sorted(set(table) - set(allowed))


def check_keys(table: Iterable[str], allowed: Iterable[str], where: str, section: str,
               error: type = ValueError) -> None:
    """Refuse a key of an input section that it does not take, the one message of every
    input file: ``"WHERE: unknown key 'x' in SECTION; expected one of a, b"``.

    Parameters
    ----------
    table : iterable of str
        The keys written (a dict of the section).
    allowed : iterable of str
        The keys the section takes.
    where : str
        The file (the message's start).
    section : str
        The section as the message names it (``"[block]"``, ``"records[0] (file)"``).
    error : type
        The exception class (a ValueError subclass of the caller's layer).
    """
    unknown = unknown_keys(table, allowed)
    if unknown:
        raise error(f"{where}: unknown key {unknown[0]!r} in {section}; expected one of "
                    f"{', '.join(sorted(allowed)) or '(none)'}")


def flag(name: str, value: object) -> bool:
    """``value`` if it is a bool (TOML's true or false), else a ValueError naming ``name``."""
    if not isinstance(value, bool):
        raise ValueError(f"{name} must be true or false, got {value!r}")
    return value


def count(name: str, value: object, low: int = 0) -> int:
    """An integer (not a bool) of at least ``low``, else a ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        expected = ("a non-negative integer" if low == 0 else "a positive integer" if low == 1
                    else f"an integer of at least {low}")
        raise ValueError(f"{name} must be {expected}, got {value!r}")
    return int(value)


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


_Parameters = ParamSpec("_Parameters")
_Returned = TypeVar("_Returned")


def renamed_to_si(positional: int, **renamed: str) -> Callable[
        [Callable[_Parameters, _Returned]], Callable[_Parameters, _Returned]]:
    """Decorator: a call in a generator's old g-based form raises a ``TypeError`` saying what to pass.

    Version 0.1's generators took accelerations in g, some positionally; a call
    written for them would otherwise either fail with Python's bare message or,
    worse, pass a value in g where m/s^2 is now expected.

    Parameters
    ----------
    positional : int
        How many positional arguments the decorated function takes; more is an
        old-form call.
    **renamed : str
        Each removed ``*_g`` keyword [g] mapped to its SI replacement [m/s^2].
    """
    def decorate(function: Callable[_Parameters, _Returned]) -> Callable[
            _Parameters, _Returned]:
        name = function.__name__
        hint = ", ".join(f"{new}=<value in g> * G" for new in renamed.values())

        @functools.wraps(function)
        def checked(*args: _Parameters.args, **kwargs: _Parameters.kwargs) -> _Returned:
            for old, new in renamed.items():
                if old in kwargs:
                    raise TypeError(
                        f"{name}() takes accelerations in m/s^2 now: pass "
                        f"{new}={kwargs[old]!r} * G (G from shaketable.core.constants) "
                        f"instead of {old}={kwargs[old]!r}")
            if len(args) > positional:
                takes = ("no positional arguments" if positional == 0 else
                         f"{positional} positional argument{'s' if positional > 1 else ''}")
                raise TypeError(
                    f"{name}() takes {takes} (got {len(args)}); pass its accelerations "
                    f"as keywords in m/s^2: {hint}")
            return function(*args, **kwargs)

        return checked

    return decorate
