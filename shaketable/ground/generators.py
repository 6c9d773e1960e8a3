"""Table-motion generators: harmonic shaking, pulses and artificial accelerograms.

Every generator returns a :class:`~shaketable.core.motion.Motion` and takes
its accelerations in SI units, m/s^2 (vertical positive **up**), as keyword
arguments: ``harmonic(2.0, horizontal=0.5 * G, duration=10.0)`` with
:data:`shaketable.core.constants.G` for an amplitude of 0.5 g. Scenes and the
command line accept "0.5 g" and convert it once, at the edge.

Generators
----------
* :func:`harmonic` -- steady sinusoidal table motion, horizontal and optionally
  vertical, with an optional raised-cosine ramp-up and a quiet lead-in
  (the harmonic tests of Section 3.6 and Figs. 3.7-3.9 of [1]_).
* :func:`constant_pulse` -- constant acceleration for ``t1`` then constant
  velocity (Section 2.3, Eq. (2-7) of [1]_).
* :func:`half_sine_pulse` -- one half sine wave ``a sin(pi t / t_p)``
  (Section 2.4, Eqs. (2-8)-(2-10) of [1]_; ``t_p = T_s / 2``).
* :func:`artificial` -- filtered, enveloped Gaussian white noise, with the
  substitute presets :data:`PRESETS` of the report's artificial records
  (written in :mod:`shaketable.ground.artificial`, offered here with the
  other generators).

More pulse shapes (one-sine, one-cosine, Makris-Roussos type-Cn, Ricker) are in
:mod:`shaketable.ground.pulses`; resampling, trimming, scaling and the
ground-motion measures in :mod:`shaketable.ground.signals`.

In version 0.1 the amplitudes were given in g, as ``horizontal_g``,
``acceleration_g``, ``amplitude_g``, ``pga_g`` and ``vertical_pga_g``; those
names now raise a ``TypeError`` that says what to pass instead.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
"""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G
from shaketable.core.impulses import ImpulsiveMotion
from shaketable.core.motion import Motion
from shaketable.core.sampling import time_grid
from shaketable.core.validation import nonnegative as _nonnegative
from shaketable.core.validation import number as _number
from shaketable.core.validation import positive as _positive
from shaketable.core.validation import renamed_to_si
from shaketable.ground.artificial import PRESETS, ArtificialPreset, artificial

__all__ = ["PRESETS", "ArtificialPreset", "artificial", "constant_pulse", "double_impulse",
           "half_sine_pulse", "harmonic", "velocity_steps"]

# ------------------------------------------------------------------ harmonic
#: Fewest samples per period a harmonic may have. Two or fewer alias (50 Hz at 0.01 s
#: falls on the sine's zeros, 60 Hz reads as 40 Hz); four samples still hold the
#: peaks of a sine in phase with them. A sine drawn linearly between N samples per
#: period can miss its peak by up to 1 - cos(pi / N): use 20 or more for accuracy.
MIN_SAMPLES_PER_PERIOD = 4

#: Samples per period of a harmonic's default step, ``dt = min(0.01 s, 1 / (20 f))``
#: (a peak error of at most 1.2 %; 0.01 s, the report's digitizing, up to 5 Hz).
DEFAULT_SAMPLES_PER_PERIOD = 20


@renamed_to_si(1, horizontal_g="horizontal", vertical_g="vertical")
def harmonic(frequency: float, *, horizontal: float, vertical: float = 0.0,
             duration: float, dt: float | None = None, phase: float = 0.0, ramp: float = 0.0,
             start: float = 0.0) -> Motion:
    """Sinusoidal table motion, horizontal and optionally vertical.

    The horizontal acceleration is ``a_h sin(2 pi f tau)`` and the vertical
    ``a_v sin(2 pi f tau + phase)`` with ``tau = t - start`` the time since the
    shaking began; both are multiplied by the same ramp envelope and are zero
    during the quiet lead-in ``0 <= t < start``.

    Parameters
    ----------
    frequency : float
        Frequency of the shaking f [Hz], positive. The harmonic tests of the
        report (Figs. 3.7-3.9 of [1]_) use 2 Hz.
    horizontal : float
        Horizontal amplitude a_h [m/s^2] (a negative value reverses the sign).
        Fig. 3.7 uses 0.5 g (``0.5 * G``), Fig. 3.8 0.38 g, Fig. 3.9 0.45 g.
    vertical : float, optional
        Vertical amplitude a_v [m/s^2], positive up. Zero (the default) gives a
        motion without a vertical component (``vertical is None``).
        Fig. 3.8 uses 0.33 g, Fig. 3.9 0.26 g.
    duration : float
        Length of the shaking [s], positive; the motion ends at
        ``start + duration``.
    dt : float, optional
        Sample interval [s], positive, with at least :data:`MIN_SAMPLES_PER_PERIOD`
        samples per period (a coarser step would alias or flatten the sine).
        Default ``min(0.01, 1 / (20 frequency))``: 0.01 s up to 5 Hz.
    phase : float, optional
        Phase of the vertical component relative to the horizontal one [rad].
        The report does not give it; 0 means both cross zero upward together.
    ramp : float, optional
        Length of a smooth ramp-up [s], ``0 <= ramp <= duration``. The envelope
        is the raised cosine ``(1 - cos(pi tau / ramp)) / 2`` for
        ``tau < ramp`` and 1 after, so the acceleration and its slope start at
        zero. Zero (default) starts the sine abruptly.
    start : float, optional
        Quiet lead-in before the shaking starts [s], zero or positive.

    Returns
    -------
    Motion
        Sampled every ``dt`` from 0 to ``start + duration`` [s], [m/s^2].

    Raises
    ------
    ValueError
        If a parameter is not finite, ``frequency``, ``duration`` or ``dt`` is
        not positive, ``ramp`` or ``start`` is negative, or ``ramp`` exceeds
        ``duration``.
    """
    frequency = _positive("frequency", frequency, " [Hz]")
    horizontal = _number("horizontal", horizontal)
    vertical = _number("vertical", vertical)
    duration = _positive("duration", duration, " [s]")
    if dt is None:
        dt = min(0.01, 1.0 / (DEFAULT_SAMPLES_PER_PERIOD * frequency))
    dt = _positive("dt", dt, " [s]")
    if frequency * dt > 1.0 / MIN_SAMPLES_PER_PERIOD:
        raise ValueError(
            f"dt = {dt!r} s gives {1.0 / (frequency * dt):.3g} samples per period of the "
            f"{frequency!r} Hz harmonic; at least {MIN_SAMPLES_PER_PERIOD} are needed (a "
            f"coarser step aliases or flattens the sine): use dt <= "
            f"{1.0 / (MIN_SAMPLES_PER_PERIOD * frequency):.3g} s, or leave dt out")
    phase = _number("phase", phase)
    ramp = _nonnegative("ramp", ramp, " [s]")
    start = _nonnegative("start", start, " [s]")
    if ramp > duration:
        raise ValueError(f"ramp ({ramp!r} s) must not exceed duration ({duration!r} s)")

    t = time_grid(start + duration, dt)
    tau = t - start
    shaking = tau >= 0.0
    envelope = shaking.astype(float)
    if ramp > 0.0:
        rising = shaking & (tau < ramp)
        envelope[rising] = 0.5 * (1.0 - np.cos(np.pi * tau[rising] / ramp))
    angle = 2.0 * np.pi * frequency * tau
    horizontal_samples = horizontal * envelope * np.sin(angle)
    vertical_samples = None
    name = f"harmonic {frequency:g} Hz, {horizontal / G:g} g H"
    if vertical != 0.0:
        vertical_samples = vertical * envelope * np.sin(angle + phase)
        name += f" + {vertical / G:g} g V"
    return Motion(t, horizontal_samples, vertical_samples, name=name)


# ------------------------------------------------------------------ pulses
@renamed_to_si(0, acceleration_g="acceleration")
def constant_pulse(*, acceleration: float, pulse_duration: float, duration: float,
                   dt: float = 0.001) -> Motion:
    """Constant table acceleration ``a`` for ``t1`` seconds, then none.

    After the pulse the table moves on at the constant velocity ``a t1``
    (Section 2.3 of [1]_; Eq. (2-7) gives the ``t1`` that overturns a slender
    block).

    Parameters
    ----------
    acceleration : float
        Table acceleration a [m/s^2] (sign gives the direction).
    pulse_duration : float
        Duration of the pulse t1 [s], positive and less than ``duration``.
    duration : float
        Length of the motion [s], positive.
    dt : float, optional
        Sample interval [s], positive.

    Returns
    -------
    Motion
        Horizontal only, sampled every ``dt`` from 0 [s], [m/s^2].

    Notes
    -----
    A :class:`~shaketable.core.motion.Motion` is linear between samples, so the
    step at ``t1`` occupies one sample interval. Every sample carries the
    average of the exact step over its trapezoidal-rule cell
    (``[t_k - dt/2, t_k + dt/2]``, ``[0, dt/2]`` for the first): samples
    inside the pulse are exactly ``a``, those after it exactly 0, and the one
    or two samples at the step take the intermediate value that makes the
    table velocity after the pulse exactly ``a t1`` whether or not ``t1`` is a
    multiple of ``dt`` (``a / 2`` at ``t1`` when it is).
    """
    acceleration = _number("acceleration", acceleration)
    pulse_duration = _positive("pulse_duration", pulse_duration, " [s]")
    duration = _positive("duration", duration, " [s]")
    dt = _positive("dt", dt, " [s]")
    if pulse_duration >= duration:
        raise ValueError(
            f"pulse_duration ({pulse_duration!r} s) must be shorter than "
            f"duration ({duration!r} s)"
        )
    t = time_grid(duration, dt)
    low = np.maximum(t - 0.5 * dt, 0.0)
    high = t + 0.5 * dt
    covered = np.clip(np.minimum(high, pulse_duration) - low, 0.0, None)
    fraction = np.clip(covered / (high - low), 0.0, 1.0)
    horizontal = acceleration * fraction
    name = f"constant pulse {acceleration / G:g} g for {pulse_duration:g} s"
    return Motion(t, horizontal, None, name=name)


@renamed_to_si(0, amplitude_g="amplitude")
def half_sine_pulse(*, amplitude: float, pulse_duration: float, duration: float,
                    dt: float = 0.001, sign: int = 1) -> Motion:
    """One half sine wave of table acceleration, then none.

    ``a_g(t) = sign * a * sin(pi t / t_p)`` for ``0 <= t <= t_p`` and zero
    after. In the notation of Section 2.4 of [1]_ the pulse is half a sine
    wave of period ``T_s``, so ``t_p = T_s / 2`` and Eq. (2-10) reads
    ``a t_p = 2 pi alpha sqrt(R g / 3)``.

    Parameters
    ----------
    amplitude : float
        Amplitude a [m/s^2], positive.
    pulse_duration : float
        Duration of the half sine t_p = T_s / 2 [s], positive and at most
        ``duration``.
    duration : float
        Length of the motion [s], positive.
    dt : float, optional
        Sample interval [s], positive.
    sign : {1, -1}, optional
        Direction of the pulse.

    Returns
    -------
    Motion
        Horizontal only, sampled every ``dt`` from 0 [s], [m/s^2]; the samples
        are the exact half sine (continuous, so no cell averaging is needed).
    """
    amplitude = _positive("amplitude", amplitude, " [m/s^2]")
    pulse_duration = _positive("pulse_duration", pulse_duration, " [s]")
    duration = _positive("duration", duration, " [s]")
    dt = _positive("dt", dt, " [s]")
    if isinstance(sign, bool) or sign not in (1, -1):
        raise ValueError(f"sign must be 1 or -1, got {sign!r}")
    if pulse_duration > duration:
        raise ValueError(
            f"pulse_duration ({pulse_duration!r} s) must not exceed "
            f"duration ({duration!r} s)"
        )
    t = time_grid(duration, dt)
    inside = t <= pulse_duration
    horizontal = np.zeros_like(t)
    horizontal[inside] = sign * amplitude * np.sin(np.pi * t[inside] / pulse_duration)
    name = f"half-sine pulse {sign * amplitude / G:g} g, {pulse_duration:g} s"
    return Motion(t, horizontal, None, name=name)


# ------------------------------------------------------------------ impulses
def velocity_steps(times, steps, *, duration: float, dt: float = 0.01) -> ImpulsiveMotion:
    """Steps of the table's horizontal velocity (ideal impulses) on a table otherwise at rest.

    Parameters
    ----------
    times : sequence of float
        Instants of the steps [s], strictly increasing, in [0, duration).
    steps : sequence of float
        Velocity change at each instant [m/s] (positive along +x), nonzero.
    duration : float
        Length of the run [s].
    dt : float
        Output interval of the smooth part (the table at rest) [s].

    Returns
    -------
    ImpulsiveMotion
        Applied exactly by :func:`shaketable.models.api.simulate`
        (:mod:`shaketable.core.impulses` derives the jump of theta').
    """
    rest = Motion.at_rest(_positive("duration", duration), _positive("dt", dt))
    return ImpulsiveMotion(Motion(rest.t, rest.horizontal, name="velocity steps"), tuple(times),
                           tuple(steps))


def double_impulse(velocity: float, interval: float, *, duration: float, start: float = 0.1,
                   dt: float = 0.01) -> ImpulsiveMotion:
    """The double impulse of Kojima & Takewaki (2015): +V at ``start``, -V ``interval`` later [m/s, s].

    The idealised near-fault fling: the table's velocity steps by +V and back by
    -V (Nabeshima, Taniguchi, Kojima & Takewaki 2016 give its critical
    amplitude for a rocking block, V1 / (1 + cor) with the second step at the
    first impact; ``tests/studies/test_linearised_model.py`` checks it).
    """
    velocity = _number("velocity", velocity)
    if velocity == 0.0:
        raise ValueError("velocity must be nonzero [m/s]")
    start = _positive("start", start)
    interval = _positive("interval", interval)
    return velocity_steps((start, start + interval), (velocity, -velocity), duration=duration,
                          dt=dt)
