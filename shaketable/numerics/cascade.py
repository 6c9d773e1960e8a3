"""The closed-form sum of an endless cascade of impacts (plain Python: compiled by the
engines that call it, importable without numba)."""

from __future__ import annotations

import math


def cascade_rest_time(rate_after, deceleration, ratio):
    """Time for an endless cascade of impacts to die out [s].

    Near the position of an impact a body pushed back onto it by a constant deceleration
    ``deceleration`` (a0) [1/s^2 or m/s^2, as ``rate_after``] flies for 2|w| / a0 after an
    impact with velocity w (``rate_after``), and each impact multiplies w by ``ratio``
    [-]. The flights form a geometric series whose sum, 2|w| / (a0 (1 - ratio)), is the
    finite time at which the body comes to rest (infinitely many impacts in finite time).

    Returns ``inf`` when the series does not converge (``ratio >= 1`` or
    ``deceleration <= 0``).
    """
    if deceleration <= 0.0 or ratio >= 1.0:
        return math.inf
    return 2.0 * abs(rate_after) / (deceleration * (1.0 - ratio))
