"""Ground-velocity steps (impulses) carried with a motion.

An impulse is a step ``delta_v`` [m/s] of the table's horizontal velocity at
one instant: the Dirac pulse of the rocking literature (Housner 1963's
impulsive limit; the double impulse of Kojima & Takewaki 2015 and Nabeshima,
Taniguchi, Kojima & Takewaki 2016). A :class:`Motion` cannot hold it (its
samples are at least 1 ns apart and linear between), so an
:class:`ImpulsiveMotion` pairs a smooth motion with the steps, and
:func:`shaketable.models.api.simulate` applies each one exactly
(:mod:`shaketable.models.rocking.impulses`).

The jump of theta' (angular-momentum balance about the pivot)
-------------------------------------------------------------
The impulsive reaction acts at the pivot, gravity is finite: the angular
momentum about the pivot is kept through the step. Integrating Eq. (2-13)
over the instant, (I0/M) Delta theta' = delta_v (h cos theta + s b sin theta)
with s = sign(theta) the pivot, i.e.

    Delta theta' = (3 / (4 R)) delta_v cos(alpha - |theta|)   (exact model),
    Delta theta' = (3 / (4 R)) delta_v = p^2 delta_v / g      (linearised Eq. 2-4),

positive ``delta_v`` (along +x) driving theta positive, as a positive
ground acceleration does (the package's sign convention). A block **at rest**
pivots on the corner the step drives it to (s = sign(delta_v)) and takes
theta' = 3 delta_v cos(alpha) / (4 R): an ideal step always lifts it (its
infinite acceleration exceeds g tan alpha); it overturns straight away iff
that kinetic energy clears the barrier (:mod:`shaketable.core.fate`), i.e.
|delta_v| > V1 = sqrt(8 g R (1 - cos alpha) / 3) / cos alpha (exact;
sqrt(4 g R / 3) alpha in the linearised model, where cos alpha -> 1 and
1 - cos alpha -> alpha^2 / 2). The pivot is assumed to stay in contact (no
bouncing), as in the literature.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaketable.core.motion import Motion

__all__ = ["ImpulsiveMotion", "theta_dot_jump", "single_impulse_overturn_velocity"]


@dataclass(frozen=True)
class ImpulsiveMotion:
    """A smooth table motion plus steps of the table's horizontal velocity.

    Parameters
    ----------
    motion : Motion
        The smooth part [m/s^2] (``Motion.at_rest`` for impulses alone); the run
        spans it.
    times : tuple of float
        Instants of the steps [s], strictly increasing, inside the motion
        (from its first sample, before its last: a step at the first sample
        acts on the initial state).
    velocity_steps : tuple of float
        Change of the table's horizontal velocity at each instant [m/s], nonzero.
    """

    motion: Motion
    times: tuple
    velocity_steps: tuple

    def __post_init__(self) -> None:
        if not isinstance(self.motion, Motion):
            raise ValueError(f"ImpulsiveMotion.motion must be a Motion, got "
                             f"{type(self.motion).__name__}")
        times = tuple(float(t) for t in np.atleast_1d(np.asarray(self.times, dtype=float)))
        steps = tuple(float(v) for v in np.atleast_1d(np.asarray(self.velocity_steps,
                                                                  dtype=float)))
        if len(times) != len(steps) or not times:
            raise ValueError("ImpulsiveMotion: give one velocity_steps value [m/s] per time [s] "
                             f"(got {len(times)} times, {len(steps)} steps)")
        if not all(math.isfinite(v) and v != 0.0 for v in steps):
            raise ValueError(f"ImpulsiveMotion.velocity_steps must be finite and nonzero [m/s], "
                             f"got {steps}")
        t = self.motion.t
        if not all(math.isfinite(x) for x in times) or any(b <= a for a, b in zip(times,
                                                                                 times[1:])):
            raise ValueError(f"ImpulsiveMotion.times must be finite and strictly increasing "
                             f"[s], got {times}")
        if times[0] < t[0] or times[-1] >= t[-1]:
            raise ValueError(f"ImpulsiveMotion.times must lie inside the motion [{t[0]:g} s, "
                             f"{t[-1]:g} s), got {times}")
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "velocity_steps", steps)

    @property
    def name(self) -> str:
        steps = ", ".join(f"{v:+.4g} m/s at {t:.4g} s" for t, v in zip(self.times,
                                                                      self.velocity_steps))
        return f"{self.motion.name + ' + ' if self.motion.name else ''}velocity steps {steps}"

    @property
    def t(self) -> np.ndarray:
        return self.motion.t

    def scaled(self, factor: float) -> "ImpulsiveMotion":
        """Accelerations and velocity steps times ``factor``."""
        return ImpulsiveMotion(self.motion.scaled(factor), self.times,
                               tuple(factor * v for v in self.velocity_steps))


def theta_dot_jump(theta: float, velocity_step: float, alpha: float, radius: float,
                   linear: bool = False) -> float:
    """Change of theta' [rad/s] of a rocking block when the table's velocity steps by ``velocity_step``.

    (3 / (4 R)) delta_v cos(alpha - |theta|), or (3 / (4 R)) delta_v in the
    linearised model (module docstring). Valid for a block at rest too (theta = 0).
    """
    factor = 1.0 if linear else math.cos(alpha - abs(theta))
    return 0.75 * velocity_step * factor / radius


def single_impulse_overturn_velocity(alpha: float, radius: float, linear: bool = False) -> float:
    """Smallest velocity step [m/s] that overturns a block at rest at once, V1.

    (1/2)(4 R^2 / 3) theta'^2 = g R (1 - cos alpha) with theta' = 3 V cos(alpha)/(4 R):
    V1 = sqrt(8 g R (1 - cos alpha) / 3) / cos(alpha); linearised: theta' = 3 V/(4 R)
    against the barrier p^2 alpha^2 / 2, V1 = alpha sqrt(4 g R / 3).
    """
    from shaketable.core.constants import G

    if linear:
        return alpha * math.sqrt(4.0 * G * radius / 3.0)
    return math.sqrt(8.0 * G * radius * (1.0 - math.cos(alpha)) / 3.0) / math.cos(alpha)
