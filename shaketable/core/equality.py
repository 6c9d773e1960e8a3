"""Equality of the package's frozen dataclasses that hold arrays and tables.

A dataclass's generated ``__eq__`` compares its fields as a tuple, which for
NumPy arrays raises ("the truth value of an array ... is ambiguous"). The
objects that hold arrays (:class:`~shaketable.core.motion.Motion`, the result
objects) use :func:`fields_equal` instead: the same fields (those with
``compare=True``), arrays and pandas objects compared by value, NaN equal to
NaN. So an object equals its copy and its pickled-and-loaded round trip. A frozen
dataclass that holds a NaN by design (a sweep spec's COR of the plastic impact law) uses
it too: the generated ``__eq__`` compares tuples, where NaN equals only the same object.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import fields, is_dataclass
from typing import Any

import numpy as np


def values_equal(first: Any, second: Any) -> bool:
    """Whether two field values are equal: arrays, frames, mappings and sequences by value."""
    if first is second:
        return True
    if isinstance(first, np.ndarray) or isinstance(second, np.ndarray):
        if not (isinstance(first, np.ndarray) and isinstance(second, np.ndarray)) \
                or first.shape != second.shape:
            return False
        try:
            return bool(np.array_equal(first, second, equal_nan=True))
        except TypeError:  # strings or objects: NaN has no meaning there
            return bool(np.array_equal(first, second))
    if hasattr(first, "equals") and type(first) is type(second):  # pandas objects
        return bool(first.equals(second))
    if isinstance(first, Mapping) and isinstance(second, Mapping):
        return first.keys() == second.keys() and all(values_equal(first[key], second[key])
                                                     for key in first)
    if isinstance(first, (list, tuple)) and isinstance(second, (list, tuple)):
        return (type(first) is type(second) and len(first) == len(second)
                and all(values_equal(a, b) for a, b in zip(first, second)))
    if is_dataclass(first) and not isinstance(first, type) and type(first) is type(second):
        return all(values_equal(getattr(first, field.name), getattr(second, field.name))
                   for field in fields(first) if field.compare)   # nested results, arrays
    if isinstance(first, float) and isinstance(second, float) \
            and math.isnan(first) and math.isnan(second):
        return True
    result = first == second
    return bool(result) if isinstance(result, (bool, np.bool_)) else result is True


def fields_equal(self, other) -> bool:
    """``__eq__`` of a dataclass holding arrays: same class, every compared field equal."""
    if other.__class__ is not self.__class__:
        return NotImplemented
    return all(values_equal(getattr(self, field.name), getattr(other, field.name))
               for field in fields(self) if field.compare)
