"""The table's stroke, velocity and acceleration limits, and where a command exceeds them."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shaketable.core.constants import INCH, G
from shaketable.core.validation import positive as _positive
from shaketable.lab.command import AXES, QUANTITIES, TableCommand


@dataclass(frozen=True)
class TableLimits:
    """Performance limits of the table, per axis (all peak absolute values).

    The defaults are **assumptions** for the 1970s Berkeley 20 ft x 20 ft
    table; the report (Section 3.4) gives none. They are the figures usually
    quoted for that table when it was built: horizontal stroke +-5 in, vertical
    +-2 in, velocity 25 in/s horizontal and 10 in/s vertical, acceleration
    1.5 g horizontal and 1.0 g vertical. Replace them when better data are at
    hand.

    Parameters
    ----------
    horizontal_stroke : float
        Largest horizontal displacement from centre [m] (default 5 in).
    horizontal_velocity : float
        Largest horizontal velocity [m/s] (default 25 in/s).
    horizontal_acceleration : float
        Largest horizontal acceleration [m/s^2] (default 1.5 g).
    vertical_stroke : float
        Largest vertical displacement from centre [m] (default 2 in).
    vertical_velocity : float
        Largest vertical velocity [m/s] (default 10 in/s).
    vertical_acceleration : float
        Largest vertical acceleration [m/s^2] (default 1.0 g).
    """

    horizontal_stroke: float = 5.0 * INCH
    horizontal_velocity: float = 25.0 * INCH
    horizontal_acceleration: float = 1.5 * G
    vertical_stroke: float = 2.0 * INCH
    vertical_velocity: float = 10.0 * INCH
    vertical_acceleration: float = 1.0 * G

    def __post_init__(self):
        for axis in AXES:
            for quantity, (limit, unit) in QUANTITIES.items():
                key = f"{axis}_{limit}"
                object.__setattr__(self, key, _positive(key, getattr(self, key), f" [{unit}]"))

    def limit(self, axis: str, quantity: str) -> float:
        """Limit of ``quantity`` (displacement, velocity, acceleration) on ``axis``."""
        return getattr(self, f"{axis}_{QUANTITIES[quantity][0]}")


@dataclass(frozen=True)
class LimitExceedance:
    """One quantity of one axis of a command that exceeds the table's limit.

    Parameters
    ----------
    axis : str
        ``"horizontal"`` or ``"vertical"``.
    quantity : str
        ``"displacement"``, ``"velocity"`` or ``"acceleration"``.
    unit : str
        Unit of ``limit``, ``peak`` and ``excess`` (``m``, ``m/s``, ``m/s^2``).
    limit : float
        The limit [unit].
    peak : float
        Signed value of largest magnitude [unit].
    t_peak : float
        Time of the peak [s].
    t_first, t_last : float
        First and last sample times at which the limit is exceeded [s].
    excess : float
        ``|peak| - limit`` [unit], positive.
    """

    axis: str
    quantity: str
    unit: str
    limit: float
    peak: float
    t_peak: float
    t_first: float
    t_last: float
    excess: float

    @property
    def ratio(self) -> float:
        """``|peak| / limit`` [-], above 1."""
        return abs(self.peak) / self.limit

    def __str__(self) -> str:
        return (f"{self.axis} {self.quantity}: peak {self.peak:+.4g} {self.unit} at "
                f"{self.t_peak:.3f} s exceeds the limit {self.limit:.4g} {self.unit} by "
                f"{self.excess:.4g} {self.unit} ({100 * (self.ratio - 1):.1f} %), "
                f"from {self.t_first:.3f} s to {self.t_last:.3f} s")


def _exceedance(t, values, axis, quantity, limit) -> LimitExceedance | None:
    over = np.flatnonzero(np.abs(values) > limit)
    if over.size == 0:
        return None
    index = int(np.argmax(np.abs(values)))
    peak = float(values[index])
    return LimitExceedance(axis=axis, quantity=quantity, unit=QUANTITIES[quantity][1],
                           limit=limit, peak=peak, t_peak=float(t[index]),
                           t_first=float(t[over[0]]), t_last=float(t[over[-1]]),
                           excess=abs(peak) - limit)


def check_limits(command, limits=None) -> list[LimitExceedance]:
    """What a command asks of the table beyond its limits.

    Parameters
    ----------
    command : TableCommand
        From :func:`displacement_command`.
    limits : TableLimits, optional
        Default :class:`TableLimits()` (assumed Berkeley limits).

    Returns
    -------
    list of LimitExceedance
        One entry per axis and quantity exceeded, in the order horizontal,
        vertical and displacement, velocity, acceleration; empty when the
        table can run the command.
    """
    if not isinstance(command, TableCommand):
        raise ValueError(f"command must be a TableCommand, got {type(command).__name__}")
    if limits is None:
        limits = TableLimits()
    elif not isinstance(limits, TableLimits):
        raise ValueError(f"limits must be TableLimits or None, got {type(limits).__name__}")
    found = []
    for axis in command.axes:
        for quantity in QUANTITIES:
            entry = _exceedance(command.t, command.quantity(axis, quantity), axis, quantity,
                                limits.limit(axis, quantity))
            if entry is not None:
                found.append(entry)
    return found
