"""Table-motion generators, signal utilities and ground-motion measures.

Every generator returns a :class:`~shaketable.core.motion.Motion` in SI units
(m/s^2, vertical positive **up**); accelerations are *given* in g where the
argument name ends in ``_g`` and converted here with
:data:`shaketable.core.constants.G`.

Generators
----------
* :func:`harmonic` -- steady sinusoidal table motion, horizontal and optionally
  vertical, with an optional raised-cosine ramp-up and a quiet lead-in
  (the harmonic tests of Section 3.6 and Figs. 3.7-3.9 of [1]_).
* :func:`constant_pulse` -- constant acceleration for ``t1`` then constant
  velocity (Section 2.3, Eq. (2-7) of [1]_).
* :func:`half_sine_pulse` -- one half sine wave ``a sin(pi t / t_p)``
  (Section 2.4, Eqs. (2-8)-(2-10) of [1]_; ``t_p = T_s / 2``).
* :func:`artificial` -- filtered, enveloped Gaussian white noise (Kanai-Tajimi
  with a Clough-Penzien high-pass, Jennings-Housner-Tsai envelope). The presets
  in :data:`PRESETS` ("A-1", "B-1", "olive-view") are **substitutes** written in
  the spirit of the artificial records used in Section 4.1 of [1]_; they are
  *not* those records, which are not available.

Utilities (always return a new motion, never change the one given)
------------------------------------------------------------------
:func:`scale_to_pga`, :func:`resample`, :func:`trim`, :func:`pad`.

Measures
--------
:func:`arias_intensity`, :func:`strong_motion_duration`,
:func:`response_spectrum` (exact piecewise-linear recurrence of Nigam and
Jennings), :func:`fourier_amplitude`.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
.. [2] Jennings, P. C., Housner, G. W. and Tsai, N. C., "Simulated Earthquake
   Motions", Earthquake Engineering Research Laboratory, California Institute
   of Technology, April 1968. (Its types A and B match the report's names
   A-1 and B-1; the report's own reference (3) for them is not in the text
   available here.)
.. [3] Clough, R. W. and Penzien, J., *Dynamics of Structures*, McGraw-Hill,
   1975 (Kanai-Tajimi spectrum with a second, high-pass filter).
.. [4] Nigam, N. C. and Jennings, P. C., "Calculation of response spectra from
   strong-motion earthquake records", Bull. Seismol. Soc. Am. 59(2),
   909-922, 1969.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.core.validation import nonnegative as _nonnegative
from shaketable.core.validation import number as _number
from shaketable.core.validation import positive as _positive
from shaketable.core.validation import sample_count

#: Relative tolerance used to decide that a motion is uniformly sampled.
UNIFORM_RTOL = 1e-6


# ------------------------------------------------------------------ validation
def uniform_step(motion: Motion, what: str) -> float:
    """Sample interval of a uniformly sampled motion, else a ValueError."""
    steps = np.diff(motion.t)
    dt = float(np.mean(steps))
    if np.max(np.abs(steps - dt)) > UNIFORM_RTOL * dt:
        raise ValueError(
            f"{what} needs a uniformly sampled motion; this one has steps from "
            f"{steps.min()!r} to {steps.max()!r} s (use Motion.subdivided or "
            "interpolate onto a uniform grid first)"
        )
    return dt


def motion_component(motion: Motion, component: str) -> np.ndarray:
    if component == "horizontal":
        return motion.horizontal
    if component == "vertical":
        return motion.vertical_or_zero
    raise ValueError(
        f"component must be 'horizontal' or 'vertical', got {component!r}"
    )


def _grid(total: float, dt: float) -> np.ndarray:
    """Times 0, dt, ... up to ``total`` (inclusive within rounding) [s]."""
    n = sample_count(math.floor(total / dt + 1e-9) + 1,
                     f"duration {total:g} s at dt = {dt:g} s")
    if n < 2:
        raise ValueError(
            f"duration {total!r} s is shorter than one sample interval dt = {dt!r} s"
        )
    return dt * np.arange(n)


def _fmt(value: float) -> str:
    return f"{value:g}"


# ------------------------------------------------------------------ harmonic
#: Fewest samples per period a harmonic may have. Two or fewer alias (50 Hz at 0.01 s
#: falls on the sine's zeros, 60 Hz reads as 40 Hz); four samples still hold the
#: peaks of a sine in phase with them. A sine drawn linearly between N samples per
#: period can miss its peak by up to 1 - cos(pi / N): use 20 or more for accuracy.
MIN_SAMPLES_PER_PERIOD = 4

#: Samples per period of a harmonic's default step, ``dt = min(0.01 s, 1 / (20 f))``
#: (a peak error of at most 1.2 %; 0.01 s, the report's digitizing, up to 5 Hz).
DEFAULT_SAMPLES_PER_PERIOD = 20


def harmonic(frequency: float, horizontal_g: float, vertical_g: float = 0.0, *,
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
    horizontal_g : float
        Horizontal amplitude a_h [g] (a negative value reverses the sign).
        Fig. 3.7 uses 0.5 g, Fig. 3.8 0.38 g, Fig. 3.9 0.45 g.
    vertical_g : float, optional
        Vertical amplitude a_v [g], positive up. Zero (the default) gives a
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
    horizontal_g = _number("horizontal_g", horizontal_g)
    vertical_g = _number("vertical_g", vertical_g)
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

    t = _grid(start + duration, dt)
    tau = t - start
    shaking = tau >= 0.0
    envelope = shaking.astype(float)
    if ramp > 0.0:
        rising = shaking & (tau < ramp)
        envelope[rising] = 0.5 * (1.0 - np.cos(np.pi * tau[rising] / ramp))
    angle = 2.0 * np.pi * frequency * tau
    horizontal = horizontal_g * G * envelope * np.sin(angle)
    vertical = None
    if vertical_g != 0.0:
        vertical = vertical_g * G * envelope * np.sin(angle + phase)
    name = f"harmonic {_fmt(frequency)} Hz, {_fmt(horizontal_g)} g H"
    if vertical is not None:
        name += f" + {_fmt(vertical_g)} g V"
    return Motion(t, horizontal, vertical, name=name)


# ------------------------------------------------------------------ pulses
def constant_pulse(acceleration_g: float, pulse_duration: float, *, duration: float,
                   dt: float = 0.001) -> Motion:
    """Constant table acceleration ``a`` for ``t1`` seconds, then none.

    After the pulse the table moves on at the constant velocity ``a t1``
    (Section 2.3 of [1]_; Eq. (2-7) gives the ``t1`` that overturns a slender
    block).

    Parameters
    ----------
    acceleration_g : float
        Table acceleration a [g] (sign gives the direction).
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
    acceleration_g = _number("acceleration_g", acceleration_g)
    pulse_duration = _positive("pulse_duration", pulse_duration, " [s]")
    duration = _positive("duration", duration, " [s]")
    dt = _positive("dt", dt, " [s]")
    if pulse_duration >= duration:
        raise ValueError(
            f"pulse_duration ({pulse_duration!r} s) must be shorter than "
            f"duration ({duration!r} s)"
        )
    t = _grid(duration, dt)
    low = np.maximum(t - 0.5 * dt, 0.0)
    high = t + 0.5 * dt
    covered = np.clip(np.minimum(high, pulse_duration) - low, 0.0, None)
    fraction = np.clip(covered / (high - low), 0.0, 1.0)
    horizontal = acceleration_g * G * fraction
    name = f"constant pulse {_fmt(acceleration_g)} g for {_fmt(pulse_duration)} s"
    return Motion(t, horizontal, None, name=name)


def half_sine_pulse(amplitude_g: float, pulse_duration: float, *, duration: float,
                    dt: float = 0.001, sign: int = 1) -> Motion:
    """One half sine wave of table acceleration, then none.

    ``a_g(t) = sign * a * sin(pi t / t_p)`` for ``0 <= t <= t_p`` and zero
    after. In the notation of Section 2.4 of [1]_ the pulse is half a sine
    wave of period ``T_s``, so ``t_p = T_s / 2`` and Eq. (2-10) reads
    ``a t_p = 2 pi alpha sqrt(R g / 3)``.

    Parameters
    ----------
    amplitude_g : float
        Amplitude a [g], positive.
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
    amplitude_g = _positive("amplitude_g", amplitude_g, " [g]")
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
    t = _grid(duration, dt)
    inside = t <= pulse_duration
    horizontal = np.zeros_like(t)
    horizontal[inside] = sign * amplitude_g * G * np.sin(np.pi * t[inside] / pulse_duration)
    name = f"half-sine pulse {_fmt(sign * amplitude_g)} g, {_fmt(pulse_duration)} s"
    return Motion(t, horizontal, None, name=name)


@dataclass(frozen=True)
class ArtificialPreset:
    """Parameters of an artificial accelerogram (see :func:`artificial`).

    Parameters
    ----------
    name : str
        Preset name, also the motion's name.
    description : str
        What the preset stands for and, plainly, that it is a substitute.
    pga_g : float
        Target peak horizontal acceleration [g].
    duration : float
        Total length of the record [s].
    t1 : float
        End of the quadratic rise of the intensity envelope [s].
    t2 : float
        End of the constant part of the envelope [s].
    decay : float
        Exponential decay rate c of the envelope after ``t2`` [1/s].
    omega_g : float
        Kanai-Tajimi ground frequency [rad/s].
    zeta_g : float
        Kanai-Tajimi ground damping ratio [-].
    omega_f : float
        Clough-Penzien high-pass corner frequency [rad/s].
    zeta_f : float
        Clough-Penzien high-pass damping ratio [-].
    source : str
        Where in the report the preset's intent comes from.
    seed_offset : int
        Added to the ``seed`` given to :func:`artificial`, so that two presets
        with the same parameters (A-1, A-2: two realisations of one type) give
        different records for the same seed.
    """

    name: str
    description: str
    pga_g: float
    duration: float
    t1: float
    t2: float
    decay: float
    omega_g: float = 15.6
    zeta_g: float = 0.6
    omega_f: float = 1.5
    zeta_f: float = 0.6
    source: str = "Section 4.1 of the report"
    seed_offset: int = 0


_SUBSTITUTE = (
    "SUBSTITUTE, not the original record (the original is not available): "
    "seeded Kanai-Tajimi/Clough-Penzien filtered white noise under a "
    "Jennings-Housner-Tsai envelope, with parameters chosen here so that the "
    "PGA and the length of strong motion match what the report states."
)

#: Named artificial-record presets, name -> :class:`ArtificialPreset`.
#: All three are substitutes in the spirit of the report's records, NOT the
#: originals. Envelope times are chosen so that the expected 5-95 % Arias
#: duration of the envelope alone equals the report's "length of strong
#: motion" (59.6 s, 30.0 s and 11.8 s respectively).
PRESETS: dict[str, ArtificialPreset] = {
    "A-1": ArtificialPreset(
        name="A-1",
        description=(
            "Substitute for the artificial accelerogram A-1 (the report's "
            "reference 3, apparently Jennings, Housner & Tsai 1968, type A) as "
            "used in Section 4.1 of the report: magnitude-8 type "
            "shaking, about 60 s of strong motion, PGA 0.5 g, horizontal only. "
            + _SUBSTITUTE
        ),
        pga_g=0.5, duration=100.0, t1=4.0, t2=64.0, decay=0.1,
        source="Section 4.1 of the report (A-1: 0.5 g, 60 s of strong motion)",
    ),
    "A-2": ArtificialPreset(
        name="A-2",
        description=(
            "Substitute for the artificial accelerogram A-2 of Table 4.4 of the report "
            "(Section 4.5; the report gives no characteristics of A-2 beyond its name, "
            "apparently a second type-A record of Jennings, Housner & Tsai 1968): "
            "A-1's parameters (0.5 g, about 60 s of strong motion, horizontal only) "
            "with another realisation of the noise. " + _SUBSTITUTE
        ),
        pga_g=0.5, duration=100.0, t1=4.0, t2=64.0, decay=0.1, seed_offset=1_000_003,
        source="Section 4.5 / Table 4.4 of the report (A-2: a second type-A record)",
    ),
    "B-1": ArtificialPreset(
        name="B-1",
        description=(
            "Substitute for the artificial accelerogram B-1 (the report's "
            "reference 3, apparently Jennings, Housner & Tsai 1968, type B) as "
            "used in Section 4.1 of the report: magnitude-7 type "
            "shaking, about 30 s of strong motion, PGA 0.4 g, horizontal only. "
            + _SUBSTITUTE
        ),
        pga_g=0.4, duration=50.0, t1=3.0, t2=33.0, decay=0.2,
        source="Section 4.1 of the report (B-1: 0.4 g, 30 s of strong motion)",
    ),
    "olive-view": ArtificialPreset(
        name="olive-view",
        description=(
            "Substitute for the artificial accelerogram with the characteristics "
            "of the 1971 San Fernando earthquake at Olive View Hospital used in "
            "Section 4.1 of the report: about 12 s of strong motion, PGA 0.5 g, "
            "horizontal only (the report's vertical was not generated; for the "
            "San Fernando-like table test of Section 3.6, 0.5 g H and about "
            "0.2 g V, pass vertical_pga_g=0.2). Softer site than A-1/B-1 "
            "(ground frequency 2 Hz). "
            + _SUBSTITUTE
        ),
        pga_g=0.5, duration=30.0, t1=1.5, t2=12.0, decay=0.3,
        omega_g=4.0 * np.pi, zeta_g=0.4, omega_f=1.0, zeta_f=0.6,
        source="Section 4.1 of the report (Olive View: 0.5 g, about 12 s)",
    ),
}


def jennings_envelope(t: npt.ArrayLike, t1: float, t2: float, decay: float) -> np.ndarray:
    """Intensity envelope of Jennings, Housner and Tsai [2]_.

    ``(t / t1)^2`` for ``t < t1``, 1 for ``t1 <= t <= t2`` and
    ``exp(-decay (t - t2))`` after ``t2``; zero for ``t < 0``.

    Parameters
    ----------
    t : array_like
        Time [s].
    t1, t2 : float
        End of the rise and of the constant part [s], ``0 < t1 <= t2``.
    decay : float
        Decay rate c [1/s], positive.
    """
    t = np.asarray(t, dtype=float)
    return np.where(
        t < 0.0, 0.0,
        np.where(t < t1, (t / t1) ** 2,
                 np.where(t <= t2, 1.0, np.exp(-decay * (t - t2)))),
    )


def _ground_filter(omega: np.ndarray, omega_g: float, zeta_g: float, omega_f: float,
                   zeta_f: float) -> np.ndarray:
    """Kanai-Tajimi times Clough-Penzien transfer function at ``i omega``."""
    s = 1j * omega
    kanai_tajimi = (2.0 * zeta_g * omega_g * s + omega_g**2) / (
        s**2 + 2.0 * zeta_g * omega_g * s + omega_g**2)
    clough_penzien = s**2 / (s**2 + 2.0 * zeta_f * omega_f * s + omega_f**2)
    return kanai_tajimi * clough_penzien


def _filtered_noise(rng: np.random.Generator, n: int, dt: float, omega_g: float, zeta_g: float,
                    omega_f: float, zeta_f: float) -> np.ndarray:
    """Stationary Gaussian noise with the Kanai-Tajimi/Clough-Penzien PSD."""
    noise = rng.standard_normal(n)
    spectrum = np.fft.rfft(noise)
    omega = 2.0 * np.pi * np.fft.rfftfreq(n, dt)
    return np.fft.irfft(spectrum * _ground_filter(omega, omega_g, zeta_g, omega_f, zeta_f),
                        n)


def _velocity_displacement(acceleration: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocity [m/s] and displacement [m] of a piecewise-linear acceleration.

    Exact integrals from rest at the first sample, uniform step ``dt``.
    """
    a0, a1 = acceleration[:-1], acceleration[1:]
    velocity = np.concatenate([[0.0], np.cumsum(0.5 * dt * (a0 + a1))])
    displacement = np.concatenate(
        [[0.0], np.cumsum(velocity[:-1] * dt + dt * dt * (2.0 * a0 + a1) / 6.0)])
    return velocity, displacement


def _baseline_corrected(acceleration: np.ndarray, envelope: np.ndarray, t: np.ndarray,
                        dt: float) -> np.ndarray:
    """Subtract ``envelope (c0 + c1 t/T)`` so final velocity and displacement vanish."""
    shapes = (envelope, envelope * (t - t[0]) / (t[-1] - t[0]))
    ends = np.array([_velocity_displacement(shape, dt) for shape in shapes])[:, :, -1]
    velocity, displacement = _velocity_displacement(acceleration, dt)
    c0, c1 = np.linalg.solve(ends.T, [velocity[-1], displacement[-1]])
    return acceleration - c0 * shapes[0] - c1 * shapes[1]


def artificial(preset: str | ArtificialPreset | None = None, *, seed: int,
               duration: float | None = None, dt: float = 0.01, pga_g: float | None = None,
               t1: float | None = None, t2: float | None = None, decay: float | None = None,
               omega_g: float | None = None, zeta_g: float | None = None,
               omega_f: float | None = None, zeta_f: float | None = None,
               vertical_pga_g: float | None = None, baseline: bool = True,
               name: str | None = None) -> Motion:
    """Artificial earthquake accelerogram (filtered, enveloped white noise).

    Stationary Gaussian white noise (``numpy.random.default_rng(seed)``) is
    passed through a Kanai-Tajimi ground filter and a Clough-Penzien high-pass
    filter [3]_ (so the displacement has finite variance and does not drift),
    multiplied by the intensity envelope of Jennings, Housner and Tsai [2]_
    (:func:`jennings_envelope`), baseline-corrected and scaled so that the
    peak horizontal acceleration is exactly ``pga_g``.

    The high-pass filter alone leaves the modulated record with a random
    final velocity (for A-1 up to about 0.2 m/s, i.e. metres of displacement
    drift at the end). The baseline correction therefore subtracts
    ``envelope(t) (c0 + c1 t / T)`` with ``c0, c1`` chosen so that the table
    velocity and displacement at the end of the record are exactly zero (for
    the piecewise-linear motion). The correction keeps the quiet start and is
    small: below 1 % of the PGA for the A-1 and B-1 presets, a few per cent
    for olive-view.

    The presets (:data:`PRESETS`) are **SUBSTITUTES** in the spirit of the
    artificial records A-1, B-1 and the Olive View record of Section 4.1 of
    [1]_; they are NOT the originals, which are not available. They share the
    report's stated PGA and length of strong motion, nothing else.

    Parameters
    ----------
    preset : str or ArtificialPreset, optional
        ``"A-1"``, ``"B-1"`` or ``"olive-view"`` (or an
        :class:`ArtificialPreset`). Any keyword below given explicitly
        overrides the preset's value. Without a preset ``pga_g``, ``t1``,
        ``t2`` and ``decay`` are required.
    seed : int
        Seed for ``numpy.random.default_rng``, a non-negative integer. Same
        seed and parameters give an identical motion.
    duration : float, optional
        Length of the record [s]; default the preset's, or without a preset
        ``t2 + ln(100) / decay`` (envelope down to 1 %).
    dt : float, optional
        Sample interval [s], positive.
    pga_g : float, optional
        Peak horizontal acceleration [g], positive.
    t1, t2 : float, optional
        End of the envelope's quadratic rise and of its constant part [s].
    decay : float, optional
        Envelope decay rate c after ``t2`` [1/s].
    omega_g, zeta_g : float, optional
        Kanai-Tajimi frequency [rad/s] and damping [-]; default 15.6 rad/s and
        0.6 (firm ground, [3]_) without a preset.
    omega_f, zeta_f : float, optional
        Clough-Penzien high-pass frequency [rad/s] and damping [-]; default
        1.5 rad/s and 0.6 without a preset.
    vertical_pga_g : float, optional
        If given, add a vertical component with this peak [g], positive up:
        independent noise (drawn after the horizontal one from the same
        generator, so the horizontal does not depend on this choice), same
        filter and envelope. This is a simplification; none of the presets
        has a vertical component (the report had none for them).
    baseline : bool, optional
        Apply the baseline correction described above (default). Without it
        the final velocity and displacement are random.
    name : str, optional
        Motion name; default the preset name or ``"artificial"``.

    Returns
    -------
    Motion
        Sampled every ``dt`` from 0 [s], [m/s^2].

    Raises
    ------
    ValueError
        Unknown preset (the message lists :data:`PRESETS`), missing or bad
        parameter (the message names it).
    """
    if isinstance(preset, str):
        if preset not in PRESETS:
            raise ValueError(
                f"unknown preset {preset!r}; expected one of {sorted(PRESETS)}"
            )
        preset = PRESETS[preset]
    elif preset is not None and not isinstance(preset, ArtificialPreset):
        raise ValueError(
            f"preset must be a name from {sorted(PRESETS)}, an ArtificialPreset or "
            f"None, got {preset!r}"
        )

    if isinstance(seed, bool) or not isinstance(seed, (numbers.Integral, np.integer)) \
            or int(seed) < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")

    defaults = dict(omega_g=15.6, zeta_g=0.6, omega_f=1.5, zeta_f=0.6)
    if preset is not None:
        defaults.update(pga_g=preset.pga_g, t1=preset.t1, t2=preset.t2,
                        decay=preset.decay, omega_g=preset.omega_g,
                        zeta_g=preset.zeta_g, omega_f=preset.omega_f,
                        zeta_f=preset.zeta_f, duration=preset.duration)
    given = dict(pga_g=pga_g, t1=t1, t2=t2, decay=decay, omega_g=omega_g,
                 zeta_g=zeta_g, omega_f=omega_f, zeta_f=zeta_f, duration=duration)
    values = {key: (value if value is not None else defaults.get(key))
              for key, value in given.items()}
    for key in ("pga_g", "t1", "t2", "decay"):
        if values[key] is None:
            raise ValueError(f"{key} is required when no preset is given")
    units = dict(pga_g=" [g]", t1=" [s]", t2=" [s]", decay=" [1/s]",
                 omega_g=" [rad/s]", zeta_g="", omega_f=" [rad/s]", zeta_f="",
                 duration=" [s]")
    checked = {key: _positive(key, values[key], units[key])
               for key in ("pga_g", "t1", "t2", "decay", "omega_g", "zeta_g", "omega_f", "zeta_f")}
    if checked["t2"] < checked["t1"]:
        raise ValueError(f"t2 ({checked['t2']!r} s) must not be before t1 ({checked['t1']!r} s)")
    total_asked = values["duration"]
    if total_asked is None:
        total_asked = checked["t2"] + math.log(100.0) / checked["decay"]
    total = _positive("duration", total_asked, " [s]")
    dt = _positive("dt", dt, " [s]")
    if vertical_pga_g is not None:
        vertical_pga_g = _positive("vertical_pga_g", vertical_pga_g, " [g]")

    t = _grid(total, dt)
    n = t.size
    filters = (checked["omega_g"], checked["zeta_g"], checked["omega_f"], checked["zeta_f"])
    envelope = jennings_envelope(t, checked["t1"], checked["t2"], checked["decay"])
    rng = np.random.default_rng(int(seed) + (preset.seed_offset if preset is not None else 0))

    def component(peak_g: float) -> np.ndarray:
        shaped = envelope * _filtered_noise(rng, n, dt, *filters)
        if baseline:
            shaped = _baseline_corrected(shaped, envelope, t, dt)
        peak = np.max(np.abs(shaped))
        if peak == 0.0:  # only if the envelope is zero everywhere
            raise ValueError("the envelope is zero over the whole duration; check t1, duration")
        return shaped * (peak_g * G / peak)

    horizontal = component(checked["pga_g"])
    vertical = None if vertical_pga_g is None else component(vertical_pga_g)
    if name is None:
        name = preset.name if preset is not None else "artificial"
    return Motion(t, horizontal, vertical, name=f"{name} (seed {int(seed)})")
