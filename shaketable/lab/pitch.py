"""The table's pitch disturbance (about 12 Hz, Section 3.7) and the motion a block feels at
its position on a pitching table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.core.motion import motion_argument as _motion
from shaketable.core.validation import nonnegative as _nonnegative
from shaketable.core.validation import number as _number
from shaketable.core.validation import positive as _positive
from shaketable.core.validation import seed as _seed

# ------------------------------------------------------------------ pitch
#: Number of random sinusoids in a drift signal, and their frequency band [Hz].
_DRIFT_TERMS = 4

_DRIFT_BAND = (0.02, 0.2)

#: Largest relative drift accepted: keeps the amplitude and frequency positive
#: (the drift signal never exceeds sqrt(2 * _DRIFT_TERMS) = 2.83 in magnitude).
_MAX_DRIFT = 0.25


@dataclass(frozen=True)
class Pitch:
    """Pitching of the table: a rotation about a horizontal axis.

    The report measured a pitch "at approximately 12 Hz" with an angular
    acceleration "between 0.2 to 0.25 radians/sec^2" (Section 3.7 (2)). The
    angular acceleration is modelled as ``A(t) sin(Psi(t))`` with
    ``Psi' = 2 pi f(t)`` (see :func:`pitch_history`).

    Parameters
    ----------
    frequency : float
        Pitch frequency f0 [Hz], positive (report: about 12 Hz).
    amplitude : float
        Amplitude A0 of the angular acceleration [rad/s^2], zero or positive
        (report: 0.2-0.25; default their middle, 0.22).
    phase : float or None
        Phase psi of the angular acceleration at t = 0 [rad]. ``None``: drawn
        uniformly in [0, 2 pi) from ``seed`` (0 when ``seed`` is ``None``).
    seed : int or None
        Seed of ``numpy.random.default_rng`` for the phase (if not given) and
        the drift. Same seed, same pitch.
    frequency_drift : float
        RMS of the relative drift of the frequency [-], 0 to 0.25 (0: none).
    amplitude_drift : float
        RMS of the relative drift of the amplitude [-], 0 to 0.25 (0: none).

    Notes
    -----
    A drift is a sum of 4 sinusoids with frequencies drawn in 0.02-0.2 Hz
    and random phases, scaled to unit RMS and multiplied by the drift given.
    A drift needs a ``seed``.
    """

    frequency: float = 12.0
    amplitude: float = 0.22
    phase: float | None = None
    seed: int | None = None
    frequency_drift: float = 0.0
    amplitude_drift: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "frequency", _positive("frequency", self.frequency, " [Hz]"))
        object.__setattr__(self, "amplitude",
                           _nonnegative("amplitude", self.amplitude, " [rad/s^2]"))
        if self.phase is not None:
            object.__setattr__(self, "phase", _number("phase", self.phase))
        object.__setattr__(self, "seed", _seed("seed", self.seed))
        for key in ("frequency_drift", "amplitude_drift"):
            value = _nonnegative(key, getattr(self, key), " [-]")
            if value > _MAX_DRIFT:
                raise ValueError(f"{key} must be at most {_MAX_DRIFT}, got {value!r}")
            object.__setattr__(self, key, value)
        if self.seed is None and (self.frequency_drift > 0.0 or self.amplitude_drift > 0.0):
            raise ValueError("seed is required when frequency_drift or amplitude_drift is "
                             "non-zero (the drift is random)")

    @property
    def omega(self) -> float:
        """Mean circular frequency 2 pi f0 [rad/s]."""
        return 2.0 * math.pi * self.frequency

    @property
    def angle_amplitude(self) -> float:
        """Amplitude of the pitch angle without drift, A0 / (2 pi f0)^2 [rad]."""
        return self.amplitude / self.omega**2

    def realised_phase(self) -> float:
        """The phase actually used [rad]: ``phase``, or the one drawn from ``seed``."""
        return _realisation(self)[0]


def _realisation(pitch: Pitch):
    """Phase [rad] and the two drift signals' (frequencies [Hz], phases [rad])."""
    rng = np.random.default_rng(0 if pitch.seed is None else pitch.seed)
    drawn_phase = float(rng.uniform(0.0, 2.0 * math.pi))
    if pitch.phase is not None:
        phase = pitch.phase
    else:
        phase = 0.0 if pitch.seed is None else drawn_phase
    drifts = []
    for _ in range(2):  # frequency, then amplitude: always drawn, so independent
        drifts.append((rng.uniform(*_DRIFT_BAND, _DRIFT_TERMS),
                       rng.uniform(0.0, 2.0 * math.pi, _DRIFT_TERMS)))
    return phase, drifts[0], drifts[1]


def _drift_signal(t: np.ndarray, terms):
    """Unit-RMS drift r(t), its integral from 0, and r', r''."""
    frequencies, phases = terms
    scale = 1.0 / math.sqrt(_DRIFT_TERMS / 2.0)
    w = 2.0 * np.pi * frequencies[:, None]
    angle = w * t[None, :] + phases[:, None]
    value = scale * np.sin(angle).sum(axis=0)
    integral = scale * ((np.cos(phases[:, None]) - np.cos(angle)) / w).sum(axis=0)
    first = scale * (w * np.cos(angle)).sum(axis=0)
    second = -scale * (w**2 * np.sin(angle)).sum(axis=0)
    return value, integral, first, second


def pitch_history(pitch, t):
    """Pitch angle, angular velocity and angular acceleration of the table.

    The angle is the primary quantity, and the three histories are exact
    derivatives of one another::

        phi(t) = -a(t) sin(Psi(t)),   a = A(t) / Omega(t)^2,
        Psi(t) = psi + 2 pi f0 (t + df * integral_0^t r_f),  Omega = Psi',
        A(t) = A0 (1 + dA r_A(t)),

    so ``phi'' = A sin(Psi) - a'' sin(Psi) - (2 a' Omega + a Omega') cos(Psi)``.
    Without drift this is exactly ``phi'' = A0 sin(2 pi f0 t + psi)`` and
    ``phi = -phi'' / (2 pi f0)^2``; with drift the extra terms are of relative
    size (drift frequency / pitch frequency) x drift, below 0.2 / 12 x 0.25 ~ 4e-3.

    Parameters
    ----------
    pitch : Pitch
    t : array_like
        Times [s].

    Returns
    -------
    angle : ndarray
        phi [rad], positive in the sense of positive theta.
    angular_velocity : ndarray
        phi' [rad/s].
    angular_acceleration : ndarray
        phi'' [rad/s^2].
    """
    if not isinstance(pitch, Pitch):
        raise ValueError(f"pitch must be a Pitch, got {type(pitch).__name__}")
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or not np.all(np.isfinite(t)):
        raise ValueError("t must be a one-dimensional array of finite times [s]")
    phase, frequency_terms, amplitude_terms = _realisation(pitch)
    r_f, r_f_integral, r_f_1, r_f_2 = _drift_signal(t, frequency_terms)
    r_a, _, r_a_1, r_a_2 = _drift_signal(t, amplitude_terms)
    w0, df, da, a0 = pitch.omega, pitch.frequency_drift, pitch.amplitude_drift, pitch.amplitude

    psi = phase + w0 * (t + df * r_f_integral)
    omega, omega_1, omega_2 = w0 * (1.0 + df * r_f), w0 * df * r_f_1, w0 * df * r_f_2
    amp, amp_1, amp_2 = a0 * (1.0 + da * r_a), a0 * da * r_a_1, a0 * da * r_a_2
    a = amp / omega**2
    a_1 = amp_1 / omega**2 - 2.0 * amp * omega_1 / omega**3
    a_2 = (amp_2 / omega**2 - 4.0 * amp_1 * omega_1 / omega**3
           - 2.0 * amp * omega_2 / omega**3 + 6.0 * amp * omega_1**2 / omega**4)
    sine, cosine = np.sin(psi), np.cos(psi)
    angle = -a * sine
    angular_velocity = -a_1 * sine - a * omega * cosine
    angular_acceleration = (a * omega**2 - a_2) * sine - (2.0 * a_1 * omega + a * omega_1) * cosine
    return angle, angular_velocity, angular_acceleration


# ------------------------------------------------------------------ at the block
def motion_at_block(table_motion, *, pitch=None, block_position=0.0,
                    axis_depth=0.0) -> Motion:
    """The motion a block feels on a table that translates and pitches.

    Derivation (also in ``docs/table.md``). The table translates with the
    accelerations of ``table_motion`` (those of its pitch axis, in the fixed
    frame) and rotates by phi(t) about a horizontal axis, phi in the same
    sense as theta: phi > 0 lowers the table's -x side (counterclockwise with
    +x to the right and up up). theta is measured relative to the table, so
    the block's absolute rotation is theta + phi. Take moments about the
    pivot corner P, which moves with the table while the block rocks:
    ``I0 (theta'' + phi'') = M_P(gravity) - M_P(m a_P)``, written in the
    table's axes (x along the table, y normal to it):

    (a) Gravity, (0, -g) in the fixed frame, has components
        (-g sin(phi), -g cos(phi)) in the table's axes: a pull toward -x for
        phi > 0, downhill. That is exactly the inertial force per mass of an
        extra horizontal ground acceleration +g sin(phi) (a positive ``u``
        pushes the block toward -x and drives theta positive,
        ``docs/conventions.md``), so tilt adds ``g sin(phi)`` to the
        horizontal and positive phi drives theta positive, as a positive
        horizontal acceleration does. (g cos(phi) = g to 1e-9.)
    (b) A table point at (x, d) from the pitch axis (x along the table,
        d = ``axis_depth`` above the axis) has the rigid-body acceleration
        ``a_axis + phi'' k x r - phi'^2 r``, i.e. tangential components
        (-d phi'', x phi''): ``-axis_depth phi''`` is added to the horizontal
        and ``block_position phi''`` to the vertical.
    (c) Dividing by I0 = 4R^2/3 gives theta'' = (Eq. 2-13 with the
        accelerations of (a), (b)) / I0 - phi''. The ``-phi''`` is the
        inertia of the base rotation; it is the ``rotation`` channel of
        :class:`Motion`, which the engine subtracts.

    At theta = 0, rocking onto the corner of side s (+1: the corner at -x)
    starts when
    ``s (u + g phi - d phi'') h > (g + v + x phi'') b + s I0 phi''``: the
    rotational term I0 phi'' dominates (for a 30 x 6 in block at 12 Hz it is
    300 times the tilt term g phi h).

    Neglected (all below 3e-4 m/s^2 = 3e-5 g for the report's pitch, 0.25
    rad/s^2 at 12 Hz, and table accelerations up to 1 g): the rotation of the
    table's own accelerations into its tilted axes (``v sin(phi)`` in the
    horizontal, ``-u sin(phi)`` in the vertical), ``g (1 - cos(phi))``, and
    the centripetal terms ``-phi'^2 r``. ``g sin(phi)`` itself (3.8e-4 m/s^2)
    is of the same order; it is kept because it is the tilt term. The
    vertical acceleration is taken at ``block_position``; the pivot corners
    are +-b from it (use ``block_position -+ b`` for the exact value on one
    side).

    Do not apply this to accelerations *measured on the table*: an
    accelerometer fixed to a tilting table already reads ``g sin(phi)`` and
    the tangential terms at its own location.

    Parameters
    ----------
    table_motion : Motion
        Translation of the table (its pitch axis) [m/s^2]; typically
        :func:`achieved`. Its own ``rotation``, if any, is replaced.
    pitch : Pitch, optional
        The pitching; ``None`` returns ``table_motion`` unchanged.
    block_position : float, optional
        Horizontal distance x of the block's centre from the pitch axis [m],
        positive along +x.
    axis_depth : float, optional
        Height d of the table surface above the pitch axis [m] (negative if
        the axis is above the surface).

    Returns
    -------
    Motion
        ``horizontal = u + g sin(phi) - d phi''``,
        ``vertical = v + x phi''`` (``None`` if ``table_motion`` has no
        vertical and x = 0), ``rotation = phi''``; ``None`` rotation without
        pitch.
    """
    table_motion = _motion("table_motion", table_motion)
    block_position = _number("block_position", block_position)
    axis_depth = _number("axis_depth", axis_depth)
    if pitch is None:
        return table_motion
    if not isinstance(pitch, Pitch):
        raise ValueError(f"pitch must be a Pitch or None, got {type(pitch).__name__}")
    angle, _, angular_acceleration = pitch_history(pitch, table_motion.t)
    horizontal = (table_motion.horizontal + G * np.sin(angle)
                  - axis_depth * angular_acceleration)
    vertical = table_motion.vertical
    if block_position != 0.0:
        vertical = table_motion.vertical_or_zero + block_position * angular_acceleration
    name = f"{table_motion.name} + pitch" if table_motion.name else "pitch"
    return Motion(table_motion.t, horizontal, vertical, name=name,
                  rotation=angular_acceleration)
