"""Floor motions: the acceleration at a floor of a building from a ground motion.

A linear building's floor at height z moves with the absolute acceleration

    u''_f(t) = u''_g(t) + sum_n Gamma_n phi_n(z) u''_n(t),

where u''_n is the relative acceleration of the n-th modal oscillator
``u''_n + 2 zeta_n omega_n u'_n + omega_n^2 u_n = -u''_g(t)`` (classical modal
superposition, e.g. Chopra [1]_, Sections 13.1-13.2). Each oscillator is solved with
the exact piecewise-linear recurrence of Nigam and Jennings [2]_ that the response
spectra use (:func:`shaketable.ground.signals.oscillator_maps`): the floor
acceleration is exact at every sample for a ground motion linear between samples,
and is itself a :class:`~shaketable.core.motion.Motion` (linear between the same
samples) that ``simulate``, scenes and sweeps take like any record.

Defaults for a regular building of ``N`` storeys of equal mass lumped at the floors
(floor k at ``z_k = k H / N``):

* ``"linear"`` -- the first mode linear in height, ``phi(z) = z / H``; its participation
  factor is ``Gamma = sum phi_k / sum phi_k^2 = 3N / (2N + 1)`` (the same factor as the
  floor amplification of NTC 2018's Circolare and of Eurocode 8's equivalent lateral
  force shape).
* ``"shear-beam"`` -- the exact modes of a uniform shear building: N equal floor masses
  on N storeys of equal lateral stiffness, ``phi_n(k) = sin((2n - 1) pi k / (2N + 1))``
  at floor k and ``T_n = T_1 sin(pi / (2(2N + 1))) / sin((2n - 1) pi / (2(2N + 1)))``
  (the eigenvectors of the tridiagonal stiffness matrix). They are orthogonal with the
  equal masses, so the N modes' ``Gamma_n phi_n`` add up to 1 at every floor, and they
  tend to the continuous shear cantilever's ``sin((2n - 1) pi z / (2H))`` and
  ``T_1 / (2n - 1)`` as N grows (the roof's ``Gamma_1 phi_1`` to 4/pi).

The vertical component passes unchanged (a building is taken as rigid vertically).

References
----------
.. [1] A. K. Chopra, *Dynamics of Structures*, 4th ed., Prentice Hall (2012).
.. [2] N. C. Nigam and P. C. Jennings, "Calculation of response spectra from
   strong-motion earthquake records", Bull. Seismol. Soc. Am. 59(2), 909-922 (1969).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.signal

from shaketable.core.motion import Motion
from shaketable.core.motion import motion_argument as _motion
from shaketable.core.validation import in_range, integer, positive
from shaketable.ground.signals import oscillator_maps, uniform_step

#: Mode shapes a :class:`Building` builds by default.
SHAPES = ("linear", "shear-beam")

#: Most storeys accepted [-].
MAX_STOREYS = 200


@dataclass(frozen=True)
class Mode:
    """One mode of a building.

    Attributes
    ----------
    period : float
        Natural period T_n [s], positive.
    damping : float
        Damping ratio zeta_n [-], in [0, 1).
    participation : tuple of float
        ``Gamma_n phi_n`` at floors 1..N [-] (roof last).
    """

    period: float
    damping: float
    participation: tuple

    def __post_init__(self):
        object.__setattr__(self, "period", positive("mode period", self.period, " [s]"))
        damping = in_range("mode damping", self.damping, 0.0, 1.0)
        if damping >= 1.0:
            raise ValueError(f"mode damping must be below 1 [-], got {damping!r}")
        object.__setattr__(self, "damping", damping)
        try:
            values = tuple(float(v) for v in self.participation)
        except (TypeError, ValueError):
            raise ValueError("mode participation must be numbers (Gamma phi at each floor) "
                             f"[-], got {self.participation!r}") from None
        if not values or not all(math.isfinite(v) for v in values):
            raise ValueError(f"mode participation must be finite numbers, one per floor [-], "
                             f"got {self.participation!r}")
        object.__setattr__(self, "participation", values)


def participation(shape: np.ndarray) -> float:
    """Participation factor of a mode shape with equal floor masses [-].

    ``Gamma = sum_k phi_k / sum_k phi_k^2`` (Chopra [1]_, Eq. 13.2.3 with a diagonal mass
    matrix of equal masses and a unit influence vector).
    """
    shape = np.asarray(shape, dtype=float)
    return float(np.sum(shape) / np.sum(shape**2))


def linear_participation(storeys: int) -> float:
    """``Gamma phi(roof)`` of the linear first mode of ``storeys`` equal storeys: 3N/(2N+1)."""
    n = integer("storeys", storeys, 1, MAX_STOREYS)
    return 3.0 * n / (2.0 * n + 1.0)


@dataclass(frozen=True)
class Building:
    """A regular building whose floors an object may stand on.

    Attributes
    ----------
    period : float
        Fundamental period T_1 [s], positive.
    height : float
        Height of the roof above the ground H [m], positive.
    storeys : int
        Number of storeys N (floors 1..N above the ground; N is the roof).
    damping : float
        Damping ratio of every mode [-] (default 5 %).
    shape : {"linear", "shear-beam"}
        Default mode shapes (see the module's docstring); ignored when ``modes`` is given.
    n_modes : int
        Modes of the ``"shear-beam"`` shape (the ``"linear"`` shape has one).
    modes : tuple of Mode, optional
        The modes given explicitly (each with ``Gamma phi`` at the N floors).
    """

    period: float
    height: float
    storeys: int
    damping: float = 0.05
    shape: str = "linear"
    n_modes: int = 1
    modes: tuple | None = None

    def __post_init__(self):
        object.__setattr__(self, "period", positive("period", self.period, " [s]"))
        object.__setattr__(self, "height", positive("height", self.height, " [m]"))
        object.__setattr__(self, "storeys", integer("storeys", self.storeys, 1, MAX_STOREYS))
        damping = in_range("damping", self.damping, 0.0, 1.0)
        if damping >= 1.0:
            raise ValueError(f"damping must be below 1 [-], got {damping!r}")
        object.__setattr__(self, "damping", damping)
        if self.shape not in SHAPES:
            raise ValueError(f"shape must be one of {', '.join(SHAPES)}, got {self.shape!r}")
        object.__setattr__(self, "n_modes", integer("n_modes", self.n_modes, 1, self.storeys))
        if self.shape == "linear" and self.n_modes != 1 and self.modes is None:
            raise ValueError("n_modes: the 'linear' shape has one mode; use 'shear-beam' or "
                             "give the modes")
        if self.modes is not None:
            modes = tuple(self.modes)
            if not modes or not all(isinstance(mode, Mode) for mode in modes):
                raise ValueError("modes must be a non-empty sequence of Mode")
            for mode in modes:
                if len(mode.participation) != self.storeys:
                    raise ValueError(f"modes: each mode needs Gamma phi at the {self.storeys} "
                                     f"floors, got {len(mode.participation)}")
            object.__setattr__(self, "modes", modes)

    def floor_height(self, floor: int) -> float:
        """Height of floor ``floor`` above the ground [m] (0: the ground, N: the roof)."""
        floor = integer("floor", floor, 0, self.storeys)
        return self.height * floor / self.storeys

    def mode_list(self) -> tuple:
        """The modes used: the given ones, or those of :attr:`shape`."""
        if self.modes is not None:
            return self.modes
        n = self.storeys
        floors = np.arange(1, n + 1)
        if self.shape == "linear":
            shapes = [(self.period, floors / n)]
        else:
            # uniform shear building: omega_m proportional to sin((2m - 1) pi / (2(2N + 1)))
            first = math.sin(math.pi / (2 * (2 * n + 1)))
            shapes = [(self.period * first / math.sin((2 * m - 1) * math.pi / (2 * (2 * n + 1))),
                       np.sin((2 * m - 1) * math.pi * floors / (2 * n + 1)))
                      for m in range(1, self.n_modes + 1)]
        return tuple(Mode(period, self.damping, tuple(participation(phi) * phi))
                     for period, phi in shapes)


def relative_acceleration(ground: np.ndarray, dt: float, period: float,
                          damping: float) -> np.ndarray:
    """Relative acceleration u'' of an oscillator at rest under ``-ground`` [m/s^2].

    ``u'' + 2 zeta omega u' + omega^2 u = -a_g``; at each sample
    ``u'' = -a_g - 2 zeta omega u' - omega^2 u`` with ``(u, u')`` from the exact
    recurrence ``x_{i+1} = A x_i + B0 a_i + B1 a_{i+1}`` (Nigam and Jennings [2]_),
    run as a second-order IIR filter with the free vibration of its start removed.

    Parameters
    ----------
    ground : ndarray
        Ground acceleration at uniform samples [m/s^2], linear between them.
    dt : float
        Sample interval [s].
    period, damping : float
        T [s] and zeta [-] of the oscillator.

    Returns
    -------
    ndarray
        u'' at the samples [m/s^2] (the absolute acceleration is ``ground + u''``).
    """
    omega = 2.0 * math.pi / period
    a, b0, b1 = oscillator_maps(np.array([omega]), damping, dt)
    a, b0, b1 = a[0], b0[0], b1[0]
    # output y = c . x of the absolute acceleration -2 zeta omega u' - omega^2 u
    c = np.array([-omega**2, -2.0 * damping * omega])
    # Y / P = c adj(zI - A) (B0 + B1 z) / det(zI - A)
    adj_const = np.array([[-a[1, 1], a[0, 1]], [a[1, 0], -a[0, 0]]])
    # c (I z + adj_const) (B1 z + B0) = z^2 c B1 + z (c B0 + c adj B1) + c adj B0
    numerator = [c @ b1, c @ b0 + c @ adj_const @ b1, c @ adj_const @ b0]
    trace = a[0, 0] + a[1, 1]
    det = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    denominator = [1.0, -trace, det]
    absolute = scipy.signal.lfilter(numerator, denominator, ground)
    if ground[0] != 0.0:
        # lfilter starts from x_0 = B1 p_0 (p zero before t_0): remove c A^k x_0
        x0 = b1 * ground[0]
        free = np.zeros(ground.size)
        free[0] = c @ x0
        if ground.size > 1:
            free[1] = c @ (a @ x0) - trace * free[0]
        absolute = absolute - scipy.signal.lfilter([1.0], denominator, free)
    return absolute - ground


def floor_motion(motion: Motion, building: Building, floor: int | None = None, *,
                 height: float | None = None) -> Motion:
    """The motion at a floor (or a height) of ``building`` under the ground ``motion``.

    Parameters
    ----------
    motion : Motion
        Uniformly sampled ground motion [m/s^2], without table pitch.
    building : Building
    floor : int, optional
        Floor 0..N (0: the ground itself, N: the roof).
    height : float, optional
        Height above the ground [m], ``0 <= height <= building.height``, instead of
        ``floor``: the mode shapes are interpolated linearly between floors.

    Returns
    -------
    Motion
        ``u''_g + sum_n Gamma_n phi_n(z) u''_n`` at the motion's samples [m/s^2] (exact
        there; between samples it is their linear interpolant, as for any record, so the
        samples should resolve the shortest period used), the vertical unchanged; its
        name says the floor and ``metadata`` the building.

    Raises
    ------
    ValueError
        Neither or both of ``floor`` and ``height``, a floor above the roof or below the
        ground, a height outside the building, a motion not uniformly sampled or pitched.
    """
    motion = _motion("motion", motion)
    if not isinstance(building, Building):
        raise ValueError(f"building must be a Building, got {type(building).__name__}")
    if (floor is None) == (height is None):
        raise ValueError("give one of floor (0..N) and height [m]")
    if motion.pitched:
        raise ValueError("motion: a pitched table motion cannot be filtered by a building")
    if floor is not None:
        if isinstance(floor, bool) or not isinstance(floor, (int, np.integer)) \
                or not 0 <= int(floor) <= building.storeys:
            raise ValueError(f"floor must be an integer from 0 (the ground) to "
                             f"{building.storeys} (the roof), got {floor!r}")
        level = float(floor)
        where = f"floor {int(floor)} of {building.storeys}"
    else:
        z = in_range("height", height, 0.0, building.height)
        level = z / building.height * building.storeys
        where = f"z = {z:g} m of {building.height:g} m"
    dt = uniform_step(motion, "floor_motion")
    ground = motion.horizontal
    total = ground.copy()
    floors = np.arange(0, building.storeys + 1)
    for mode in building.mode_list():
        factor = float(np.interp(level, floors, (0.0,) + mode.participation))
        if factor != 0.0:
            total += factor * relative_acceleration(ground, dt, mode.period, mode.damping)
    metadata = dict(motion.metadata)
    metadata["floor"] = {"where": where, "period [s]": building.period,
                         "height [m]": building.height, "storeys": building.storeys,
                         "damping [-]": building.damping, "shape": building.shape}
    return Motion(motion.t, total, motion.vertical, name=f"{motion.name} at {where}".strip(),
                  metadata=metadata)
