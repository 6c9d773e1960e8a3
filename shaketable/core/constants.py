"""Physical constants and unit conversion factors.

Everything inside :mod:`shaketable` is SI (metres, seconds, radians, m/s^2).
Inches, feet, g and gal are accepted only at the edges (scenes, the CLI and the
record readers), which convert with the factors defined here and nowhere else.
"""

from __future__ import annotations

#: Standard acceleration of gravity [m/s^2].
G = 9.80665

#: The largest friction coefficient an input takes [-] (assess's object.friction, a
#: stack's mu): measured coefficients of dry contacts stay below about 1.
MAX_FRICTION = 1.5

#: One inch [m].
INCH = 0.0254

#: One foot [m].
FOOT = 0.3048

#: One centimetre [m].
CENTIMETRE = 0.01

#: One millimetre [m].
MILLIMETRE = 0.001

#: One gal = 1 cm/s^2 [m/s^2].
GAL = 0.01

#: Length units accepted at the edges, name -> metres.
LENGTH_UNITS = {
    "m": 1.0,
    "cm": CENTIMETRE,
    "mm": MILLIMETRE,
    "in": INCH,
    "ft": FOOT,
}

#: Acceleration units accepted at the edges, name -> m/s^2.
ACCELERATION_UNITS = {
    "m/s2": 1.0,
    "m/s^2": 1.0,
    "g": G,
    "gal": GAL,
    "cm/s2": GAL,
    "cm/s^2": GAL,
}


def length_factor(unit: str) -> float:
    """Return the factor converting ``unit`` to metres.

    Parameters
    ----------
    unit : str
        One of ``m, cm, mm, in, ft``.

    Raises
    ------
    ValueError
        If the unit is unknown; the message lists the accepted units.
    """
    try:
        return LENGTH_UNITS[str(unit).strip().lower()]
    except KeyError:
        raise ValueError(
            f"unknown length unit {unit!r}; expected one of {sorted(LENGTH_UNITS)}"
        ) from None


def acceleration_factor(unit: str) -> float:
    """Return the factor converting ``unit`` to m/s^2.

    Parameters
    ----------
    unit : str
        One of ``g, m/s2, m/s^2, gal, cm/s2, cm/s^2``.

    Raises
    ------
    ValueError
        If the unit is unknown; the message lists the accepted units.
    """
    try:
        return ACCELERATION_UNITS[str(unit).strip().lower()]
    except KeyError:
        raise ValueError(
            f"unknown acceleration unit {unit!r}; expected one of "
            f"{sorted(ACCELERATION_UNITS)}"
        ) from None
