"""Idealised acceleration pulses: analytic shapes and finely sampled Motions.

Section 2.4 of [1]_ reduces an earthquake's strongest pulse to a half sine
wave; the exact rocking model distinguishes more shapes (Zhang & Makris [2]_,
Makris & Roussos [3]_). Every pulse here is a unit-amplitude shape ``f(t)``
(peak |f| = 1) of circular frequency ``omega`` [rad/s]; the table
acceleration is ``a f(t)`` [m/s^2] during the pulse and zero after it.

================  ==========================================================  ======================
name              f(t)                                                        duration
================  ==========================================================  ======================
``half-sine``     sin(omega t)                                                pi / omega
``one-sine``      sin(omega t)  (Zhang & Makris type-A, forward pulse)        2 pi / omega
``one-cosine``    cos(omega t)  (type-B; table at rest at t = 0, f jumps)     2 pi / omega
``type-A``        same as ``one-sine``                                        2 pi / omega
``type-B``        same as ``one-cosine``                                      2 pi / omega
``type-C1`` ...   cos(omega t + phi), phi from zero final displacement        (n + 1/2 - phi/pi) T
``ricker``        (1 - 2 u^2) exp(-u^2), u = omega (t - t0) / 2                  2 t0 = 4 sqrt(6)/omega
================  ==========================================================  ======================

For ``type-Cn`` the velocity is ``v_p (sin(omega t + phi) - sin phi)``
and phi solves ``2 cos phi = sin phi ((2n + 1) pi - 2 phi)``: velocity and
displacement of the table are zero when the pulse ends [3]_. For ``ricker``,
omega = 2 pi f_p with f_p its peak (Fourier) frequency [Hz].

The engine treats a motion as linear between samples. A straight chord over
an interval h of a sinusoid of frequency omega carries (omega h)^2 / 12 less
area than the arc; :func:`pulse_motion` samples ``samples_per_cycle`` points
per 2 pi / omega (default 8192: area error 4.9e-8, far below the 1e-6 asked
of a band edge).

References
----------
.. [1] Aslam, M., Godden, W. G. and Scalise, D. T., "Rocking and overturning
   response of rigid bodies to earthquake motions", LBL-7539, 1978.
.. [2] Zhang, J. and Makris, N., "Rocking response of free-standing blocks
   under cycloidal pulses", J. Eng. Mech. 127(5), 473-483, 2001.
.. [3] Makris, N. and Roussos, Y., "Rocking response of rigid blocks under
   near-source ground motions", Geotechnique 50(3), 243-262, 2000.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from shaketable.core.motion import Motion, whole_number

__all__ = ["PULSES", "Pulse", "pulse", "pulse_motion", "cycloidal_phase"]

#: Pulse shapes by name (``type-Cn`` for any n >= 1 too).
PULSES = {
    "half-sine": "sin(omega t), 0 <= t <= pi/omega",
    "one-sine": "sin(omega t), one full cycle (Zhang & Makris type-A)",
    "one-cosine": "cos(omega t), one full cycle, block at rest at t = 0 (type-B)",
    "type-A": "alias of one-sine",
    "type-B": "alias of one-cosine",
    "type-Cn": "cos(omega t + phi), n + 1/2 - phi/pi cycles, zero final displacement",
    "ricker": "Ricker wavelet of peak frequency omega / (2 pi)",
}

_ALIASES = {"type-A": "one-sine", "type-a": "one-sine", "type-B": "one-cosine",
            "type-b": "one-cosine"}


def cycloidal_phase(n: int) -> float:
    """Phase phi [rad] of the Makris & Roussos type-Cn pulse: 2 cos phi = sin phi ((2n+1) pi - 2 phi)."""
    n = whole_number("n", n)
    low, high = 0.0, math.pi / 2
    g = lambda phi: 2.0 * math.cos(phi) - math.sin(phi) * ((2 * n + 1) * math.pi - 2 * phi)  # noqa: E731
    for _ in range(200):                         # g(0) = 2 > 0 > g(pi/2): bisection to rounding
        middle = 0.5 * (low + high)
        if g(middle) > 0.0:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


@dataclass(frozen=True)
class Pulse:
    """A unit-amplitude pulse shape.

    Parameters
    ----------
    kind : str
        Name, one of :data:`PULSES` (``type-C2`` etc. for the n-th C pulse).
    omega : float
        Circular frequency of the pulse [rad/s].
    """

    kind: str
    omega: float

    def __post_init__(self):
        kind = _ALIASES.get(self.kind, self.kind)
        if not (kind in PULSES and kind != "type-Cn") and not re.fullmatch(r"type-C\d+", kind):
            raise ValueError(f"unknown pulse kind {self.kind!r}; expected one of "
                             f"{', '.join(sorted(PULSES))} (type-Cn as type-C1, type-C2, ...)")
        object.__setattr__(self, "kind", kind)
        if not (isinstance(self.omega, (int, float, np.floating)) and math.isfinite(self.omega)
                and self.omega > 0):
            raise ValueError(f"omega must be a positive number [rad/s], got {self.omega!r}")
        object.__setattr__(self, "omega", float(self.omega))

    @property
    def phase(self) -> float:
        """Phase phi [rad] (type-Cn; 0 otherwise)."""
        if self.kind.startswith("type-C"):
            return cycloidal_phase(int(self.kind[6:]))
        return 0.0

    @property
    def duration(self) -> float:
        """Length of the pulse [s]; the table is at rest after it."""
        period = 2 * math.pi / self.omega
        if self.kind == "half-sine":
            return period / 2
        if self.kind in ("one-sine", "one-cosine"):
            return period
        if self.kind == "ricker":
            return 4 * math.sqrt(6.0) / self.omega
        n = int(self.kind[6:])
        return (n + 0.5 - self.phase / math.pi) * period

    def __call__(self, t) -> np.ndarray:
        """f(t) [-], zero outside [0, duration]."""
        t = np.asarray(t, dtype=float)
        w = self.omega
        if self.kind in ("half-sine", "one-sine"):
            value = np.sin(w * t)
        elif self.kind == "one-cosine":
            value = np.cos(w * t)
        elif self.kind == "ricker":
            u = 0.5 * w * (t - 2 * math.sqrt(6.0) / w)
            value = (1 - 2 * u ** 2) * np.exp(-u ** 2)
        else:
            value = np.cos(w * t + self.phase)
        return np.where((t >= 0) & (t <= self.duration), value, 0.0)

    def describe(self) -> str:
        return f"{self.kind}, omega {self.omega:.6g} rad/s"


def pulse(kind: str, omega: float) -> Pulse:
    """A :class:`Pulse` by name (validated)."""
    return Pulse(kind, omega)


def pulse_motion(shape: Pulse, amplitude: float = 1.0, *, samples_per_cycle: int = 8192,
                 after: float = 0.0) -> Motion:
    """The pulse ``amplitude * f(t)`` sampled for the engine [m/s^2].

    Parameters
    ----------
    shape : Pulse
        The shape.
    amplitude : float
        Peak table acceleration a [m/s^2] (use ``Case.scale`` to vary it cheaply).
    samples_per_cycle : int
        Samples per 2 pi / omega; the chord-area error is (2 pi / n)^2 / 12.
    after : float
        Time [s] with the table at rest added after the pulse (sampled coarsely).

    Returns
    -------
    Motion
        Horizontal only, from t = 0 to ``duration + after`` [s]; a discontinuity
        of f (one-cosine at t = 0 and at the end) is represented by the first
        and last samples: the table acceleration jumps to a at t = 0+.
    """
    n = whole_number("samples_per_cycle", samples_per_cycle, minimum=16)
    duration = shape.duration
    count = int(math.ceil(n * duration * shape.omega / (2 * math.pi)))
    t = np.linspace(0.0, duration, count + 1)
    values = amplitude * shape(t)
    if shape.kind in ("half-sine", "one-sine"):
        values[-1] = 0.0                         # sin(pi), sin(2 pi): exact zero
    if after > 0.0:
        dt = max(0.01 / shape.omega * 2 * math.pi, 1e-3)
        extra = int(math.ceil(after / dt))
        tail = duration + np.linspace(0.0, after, extra + 1)[1:]
        t = np.concatenate([t, tail])
        values = np.concatenate([values, np.zeros(extra)])
        # a pulse ending at a nonzero value (one-cosine, type-Cn) drops to 0 within 1e-9 s
        if abs(values[count]) > 0.0:
            t = np.insert(t, count + 1, duration + 1e-9 * duration)
            values = np.insert(values, count + 1, 0.0)
    return Motion(t, values, name=f"{shape.kind} a={amplitude:.6g} m/s^2 "
                                  f"omega={shape.omega:.6g} rad/s")
