"""Signal utilities on a :class:`~shaketable.core.motion.Motion`: scaling to a PGA,
resampling, trimming and padding, Arias intensity, strong-motion duration,
response and Fourier spectra.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import scipy.fft
import scipy.linalg
import scipy.signal

from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.core.motion import motion_argument as _motion
from shaketable.core.sampling import UNIFORM_RTOL
from shaketable.core.sampling import uniform_step as _uniform_times
from shaketable.core.validation import nonnegative as _nonnegative
from shaketable.core.validation import number as _number
from shaketable.core.validation import positive as _positive
from shaketable.core.validation import renamed_to_si, sample_count


def uniform_step(motion: Motion, what: str) -> float:
    """Sample interval of a uniformly sampled motion [s], else a ValueError naming ``what``."""
    return _uniform_times(motion.t, what)


def motion_component(motion: Motion, component: str) -> np.ndarray:
    """The ``"horizontal"`` or ``"vertical"`` acceleration of a motion [m/s^2] (zeros if absent)."""
    if component == "horizontal":
        return motion.horizontal
    if component == "vertical":
        return motion.vertical_or_zero
    raise ValueError(
        f"component must be 'horizontal' or 'vertical', got {component!r}"
    )


# ------------------------------------------------------------------ utilities
@renamed_to_si(1, pga_g="pga")
def scale_to_pga(motion: Motion, *, pga: float) -> Motion:
    """Scale a motion so that its peak horizontal acceleration is ``pga``.

    Both components are multiplied by the same factor (their ratio is kept).

    Parameters
    ----------
    motion : Motion
        Motion to scale (unchanged), without table pitch.
    pga : float
        Target peak horizontal acceleration [m/s^2], positive (``0.3 * G`` for
        0.3 g, with :data:`~shaketable.core.constants.G`).

    Returns
    -------
    Motion
        New motion [m/s^2].

    Raises
    ------
    ValueError
        ``pga`` not positive, a zero horizontal component, or a motion that
        carries a table pitch (non-zero ``rotation``).

    Notes
    -----
    The pitch is a disturbance of the table, not part of the earthquake, and
    :func:`shaketable.lab.pitch.motion_at_block` has folded its tilt and
    tangential accelerations into ``horizontal`` and ``vertical``, where they
    would both be scaled and distort the PGA. A pitched motion is therefore
    refused (see :meth:`Motion.scaled`): scale the record first, then put it
    on the pitching table.
    """
    motion = _motion("motion", motion)
    pga = _positive("pga", pga, " [m/s^2]")
    if motion.pga == 0.0:
        raise ValueError("motion has a zero horizontal component; it cannot be scaled to a PGA")
    return motion.scaled(pga / motion.pga)


def _decimate_fft(values: np.ndarray, dt_old: float, dt_new: float,
                  t_old: np.ndarray, t_new: np.ndarray) -> np.ndarray:
    """Low-pass below the new Nyquist in the frequency domain, then interpolate."""
    n = values.size
    size = scipy.fft.next_fast_len(2 * n)  # zero padding: no wrap-around
    frequency = np.fft.rfftfreq(size, dt_old)
    nyquist = 0.5 / dt_new
    # cosine taper from 0.8 to 1.0 of the new Nyquist (limits Gibbs ringing)
    gain = np.clip((nyquist - frequency) / (0.2 * nyquist), 0.0, 1.0)
    gain = 0.5 * (1.0 - np.cos(np.pi * gain))
    filtered = np.fft.irfft(np.fft.rfft(values, size) * gain, size)[:n]
    return np.interp(t_new, t_old, filtered)


def resample(motion, dt) -> Motion:
    """Resample a uniformly sampled motion to the sample interval ``dt``.

    Parameters
    ----------
    motion : Motion
        Uniformly sampled motion (unchanged).
    dt : float
        New sample interval [s], positive.

    Returns
    -------
    Motion
        New motion from ``motion.t[0]`` to at most ``motion.t[-1]`` [m/s^2];
        every channel present (horizontal, vertical, rotation [rad/s^2]) is
        resampled the same way.

    Notes
    -----
    * Coarser ``dt`` (decimation): the signal is first low-passed below the
      new Nyquist frequency ``1 / (2 dt)`` so that nothing aliases. When the
      ratio of the two intervals is a fraction with numerator and denominator
      up to 1000, :func:`scipy.signal.resample_poly` does both (polyphase FIR
      with a Kaiser window, zero padding at the ends); otherwise the signal is
      low-passed by FFT (cosine taper from 0.8 to 1.0 of the new Nyquist) and
      interpolated linearly.
    * Finer ``dt``: linear interpolation, which is exactly the motion as the
      package defines it (linear between samples, Section 2.8 of [1]_); a
      band-limited interpolation would change it.
    """
    motion = _motion("motion", motion)
    dt = _positive("dt", dt, " [s]")
    dt_old = uniform_step(motion, "resample")
    t_old = motion.t
    span = motion.duration
    n_new = sample_count(math.floor(span / dt + 1e-9) + 1,
                         f"resampling {span:g} s at dt = {dt:g} s")
    if n_new < 2:
        raise ValueError(f"dt = {dt!r} s is longer than the motion ({span!r} s)")
    t_new = t_old[0] + dt * np.arange(n_new)

    if abs(dt - dt_old) <= UNIFORM_RTOL * dt_old:
        return Motion(t_old, motion.horizontal, motion.vertical, name=motion.name,
                      rotation=motion.rotation)

    if dt < dt_old:
        def convert(values):
            return np.interp(t_new, t_old, values)
    else:
        ratio = Fraction(dt_old / dt).limit_denominator(1000)  # = up / down
        if ratio > 0 and abs(float(ratio) - dt_old / dt) <= 1e-9 * dt_old / dt:
            up, down = ratio.numerator, ratio.denominator

            def convert(values):
                return scipy.signal.resample_poly(values, up, down)[:n_new]
        else:
            def convert(values):
                return _decimate_fft(values, dt_old, dt, t_old, t_new)

    def optional(values):
        return None if values is None else convert(values)

    return Motion(t_new, convert(motion.horizontal), optional(motion.vertical), name=motion.name,
                  rotation=optional(motion.rotation))


def trim(motion, start, end, *, rezero=False) -> Motion:
    """Keep the samples with ``start <= t <= end``.

    Parameters
    ----------
    motion : Motion
        Motion to cut (unchanged).
    start, end : float
        Window on the motion's own time axis [s], ``start < end``.
    rezero : bool, optional
        If true, shift the times so that the result starts at t = 0;
        by default the original times are kept.

    Returns
    -------
    Motion
        New motion with at least two samples [m/s^2]; vertical and rotation
        [rad/s^2] are cut with the horizontal.
    """
    motion = _motion("motion", motion)
    start = _number("start", start)
    end = _number("end", end)
    if end <= start:
        raise ValueError(f"end ({end!r} s) must be after start ({start!r} s)")
    tolerance = 1e-9 * max(motion.dt, 1e-300)
    keep = (motion.t >= start - tolerance) & (motion.t <= end + tolerance)
    if np.count_nonzero(keep) < 2:
        raise ValueError(
            f"the window [{start!r}, {end!r}] s holds fewer than two samples of a motion "
            f"spanning [{motion.t[0]!r}, {motion.t[-1]!r}] s"
        )
    t = motion.t[keep]
    if rezero:
        t = t - t[0]

    def kept(values):
        return None if values is None else values[keep]

    return Motion(t, motion.horizontal[keep], kept(motion.vertical), name=motion.name,
                  rotation=kept(motion.rotation))


def pad(motion, before=0.0, after=0.0) -> Motion:
    """Add quiet (zero-acceleration) time before and after a motion.

    Parameters
    ----------
    motion : Motion
        Uniformly sampled motion (unchanged).
    before, after : float, optional
        Quiet time to add [s], zero or positive, rounded to whole samples.

    Returns
    -------
    Motion
        New motion starting at the original ``t[0]``; the original samples
        are delayed by the padding added before [m/s^2]. Vertical and
        rotation (when present) are padded with zeros too: the table is at
        rest and does not pitch during the padding.
    """
    motion = _motion("motion", motion)
    before = _nonnegative("before", before, " [s]")
    after = _nonnegative("after", after, " [s]")
    dt = uniform_step(motion, "pad")
    n_before = sample_count(round(before / dt), f"padding {before:g} s before at dt = {dt:g} s")
    n_after = sample_count(round(after / dt), f"padding {after:g} s after at dt = {dt:g} s")
    sample_count(motion.t.size + n_before + n_after, "the padded motion")
    n = motion.t.size + n_before + n_after
    t = motion.t[0] + dt * np.arange(n)

    def padded(values):
        if values is None:
            return None
        return np.concatenate([np.zeros(n_before), values, np.zeros(n_after)])

    return Motion(t, padded(motion.horizontal), padded(motion.vertical), name=motion.name,
                  rotation=padded(motion.rotation))


# ------------------------------------------------------------------ measures
def arias_intensity(motion, component="horizontal") -> np.ndarray:
    """Cumulative Arias intensity ``I_A(t) = pi / (2 g) int_0^t a^2 dt``.

    The integral is exact for the piecewise-linear acceleration that a
    :class:`~shaketable.core.motion.Motion` stands for:
    ``dt (a_k^2 + a_k a_{k+1} + a_{k+1}^2) / 3`` per interval.

    Parameters
    ----------
    motion : Motion
        Ground motion.
    component : {"horizontal", "vertical"}, optional
        Which component to integrate.

    Returns
    -------
    ndarray
        Cumulative Arias intensity at ``motion.t`` [m/s]; the last value is
        the total.
    """
    motion = _motion("motion", motion)
    a = motion_component(motion, component)
    pieces = np.diff(motion.t) * (a[:-1] ** 2 + a[:-1] * a[1:] + a[1:] ** 2) / 3.0
    return np.pi / (2.0 * G) * np.concatenate([[0.0], np.cumsum(pieces)])


def strong_motion_duration(motion, low=0.05, high=0.95, component="horizontal") -> float:
    """Significant duration: time between ``low`` and ``high`` Arias fractions.

    Parameters
    ----------
    motion : Motion
        Ground motion.
    low, high : float, optional
        Fractions of the total Arias intensity, ``0 <= low < high <= 1``;
        default the 5-95 % duration.
    component : {"horizontal", "vertical"}, optional
        Which component to measure.

    Returns
    -------
    float
        Duration [s]; crossing times interpolated linearly in the cumulative
        intensity.
    """
    low = _number("low", low)
    high = _number("high", high)
    if not 0.0 <= low < high <= 1.0:
        raise ValueError(f"need 0 <= low < high <= 1, got low={low!r}, high={high!r}")
    arias = arias_intensity(motion, component)
    total = arias[-1]
    if total <= 0.0:
        raise ValueError(f"the {component} component is zero: no Arias intensity")
    fraction = arias / total

    def crossing(level):
        k = int(np.searchsorted(fraction, level, side="left"))
        if k == 0:
            return float(motion.t[0])
        f0, f1 = fraction[k - 1], fraction[k]
        return float(motion.t[k - 1] + (level - f0) / (f1 - f0) * (motion.t[k] - motion.t[k - 1]))

    return crossing(high) - crossing(low)


def oscillator_maps(omega: np.ndarray, damping: float, dt: float):
    """Exact one-step maps of u'' + 2 z w u' + w^2 u = -p, p linear in the step.

    Returns ``A`` (n, 2, 2), ``B0`` and ``B1`` (n, 2) such that
    ``x_{i+1} = A x_i + B0 p_i + B1 p_{i+1}`` with ``x = (u, u')``: the
    recurrence of Nigam and Jennings [4]_, computed from the matrix exponential
    of the system augmented with ``p`` and its slope (no cancellation at long
    periods).
    """
    n = omega.size
    system = np.zeros((n, 4, 4))
    system[:, 0, 1] = 1.0
    system[:, 1, 0] = -omega**2
    system[:, 1, 1] = -2.0 * damping * omega
    system[:, 1, 2] = -1.0  # forcing -p
    system[:, 2, 3] = 1.0   # p' = slope, slope' = 0
    step = scipy.linalg.expm(system * dt)
    a = step[:, :2, :2]
    b_slope = step[:, :2, 3] / dt
    b0 = step[:, :2, 2] - b_slope
    return a, b0, b_slope


def response_spectrum(motion, periods, damping=0.05, component="horizontal"):
    """Pseudo-acceleration response spectrum ``S_a = omega^2 max|u|``.

    The relative displacement ``u`` of a linear oscillator
    ``u'' + 2 zeta omega u' + omega^2 u = -a_g(t)``, starting at rest, is
    computed with the exact piecewise-linear recurrence of Nigam and Jennings
    [4]_ (exact for a Motion, which is linear between samples). The one-step
    coefficients are computed for all periods at once; the recurrence runs as
    a second-order IIR filter (:func:`scipy.signal.lfilter`) per period.

    Parameters
    ----------
    motion : Motion
        Uniformly sampled ground motion.
    periods : float or array_like
        Natural periods T [s], positive.
    damping : float, optional
        Damping ratio zeta [-], ``0 <= damping < 1``.
    component : {"horizontal", "vertical"}, optional
        Which component excites the oscillator.

    Returns
    -------
    float or ndarray
        Pseudo-acceleration [m/s^2], same shape as ``periods``. For
        ``T -> 0`` it tends to the peak ground acceleration; at resonance with
        a long harmonic input of amplitude a it tends to ``a / (2 zeta)``.
    """
    motion = _motion("motion", motion)
    damping = _number("damping", damping)
    if not 0.0 <= damping < 1.0:
        raise ValueError(f"damping must satisfy 0 <= damping < 1, got {damping!r}")
    try:
        period_array = np.asarray(periods, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"periods must be numbers [s], got {periods!r}") from None
    flat = period_array.ravel()
    if flat.size == 0:
        raise ValueError("periods is empty")
    if not np.all(np.isfinite(flat)) or np.any(flat <= 0.0):
        raise ValueError(f"periods must be positive and finite [s], got {periods!r}")
    dt = uniform_step(motion, "response_spectrum")
    p = motion_component(motion, component)
    omega = 2.0 * np.pi / flat
    a, b0, b1 = oscillator_maps(omega, damping, dt)

    # u as output of x_{i+1} = A x_i + B0 p_i + B1 p_{i+1}:
    # U(z) / P(z) = [(z - a22)(B0u + B1u z) + a12 (B0v + B1v z)] / det(zI - A)
    a11, a12, a21, a22 = a[:, 0, 0], a[:, 0, 1], a[:, 1, 0], a[:, 1, 1]
    numerator = np.stack([
        b1[:, 0],
        b0[:, 0] - a22 * b1[:, 0] + a12 * b1[:, 1],
        -a22 * b0[:, 0] + a12 * b0[:, 1],
    ], axis=1)
    denominator = np.stack([np.ones_like(a11), -(a11 + a22), a11 * a22 - a12 * a21], axis=1)
    # The filter starts from x_0 = B1 p_0 (as if p were 0 before t_0); subtract
    # the free vibration from that state so that the oscillator starts at rest.
    result = np.empty(flat.size)
    for j in range(flat.size):
        u = scipy.signal.lfilter(numerator[j], denominator[j], p)
        if p[0] != 0.0:
            u = u - _free_u(a[j], b1[j] * p[0], p.size)
        result[j] = omega[j] ** 2 * np.max(np.abs(u))
    if period_array.ndim == 0:
        return float(result[0])
    return result.reshape(period_array.shape)


def _free_u(a: np.ndarray, x0: np.ndarray, n: int) -> np.ndarray:
    """First component of x_k = A^k x0, k = 0..n-1 (two-term recurrence)."""
    trace = a[0, 0] + a[1, 1]
    det = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    first = a[0] @ x0  # u_1
    # u_{k+2} = trace u_{k+1} - det u_k (Cayley-Hamilton)
    forcing = np.zeros(n)
    forcing[0] = x0[0]
    forcing[1] = first - trace * x0[0] if n > 1 else 0.0
    return scipy.signal.lfilter([1.0], [1.0, -trace, det], forcing)


def fourier_amplitude(motion, component="horizontal"):
    """Fourier amplitude spectrum of a uniformly sampled motion.

    ``|A(f)| = dt |sum_k a_k exp(-2 pi i f t_k)|``, the discrete estimate of
    the continuous Fourier transform's modulus.

    Parameters
    ----------
    motion : Motion
        Uniformly sampled ground motion.
    component : {"horizontal", "vertical"}, optional
        Which component to transform.

    Returns
    -------
    frequency : ndarray
        Frequencies from 0 to the Nyquist frequency [Hz].
    amplitude : ndarray
        Fourier amplitude [m/s].
    """
    motion = _motion("motion", motion)
    dt = uniform_step(motion, "fourier_amplitude")
    values = motion_component(motion, component)
    frequency = np.fft.rfftfreq(values.size, dt)
    amplitude = dt * np.abs(np.fft.rfft(values))
    return frequency, amplitude
