"""Artificial earthquake accelerograms: filtered, enveloped Gaussian white noise.

:func:`artificial` draws a Kanai-Tajimi/Clough-Penzien filtered white noise
under a Jennings-Housner-Tsai envelope [2]_ [3]_, corrects its baseline and
scales it to a peak acceleration given in m/s^2. The presets in
:data:`PRESETS` ("A-1", "A-2", "B-1", "olive-view") are **substitutes** written
in the spirit of the artificial records used in Section 4.1 of [1]_; they are
*not* those records, which are not available.

:mod:`shaketable.ground.generators` offers these next to the harmonic and pulse
generators (``generators.artificial`` is this module's :func:`artificial`).

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
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.core.sampling import time_grid
from shaketable.core.validation import positive as _positive
from shaketable.core.validation import renamed_to_si


@dataclass(frozen=True)
class ArtificialPreset:
    """Parameters of an artificial accelerogram (see :func:`artificial`).

    Parameters
    ----------
    name : str
        Preset name, also the motion's name.
    description : str
        What the preset stands for and, plainly, that it is a substitute.
    pga : float
        Target peak horizontal acceleration [m/s^2] (the presets give it as a
        multiple of :data:`~shaketable.core.constants.G`).
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
    pga: float
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
        pga=0.5 * G, duration=100.0, t1=4.0, t2=64.0, decay=0.1,
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
        pga=0.5 * G, duration=100.0, t1=4.0, t2=64.0, decay=0.1, seed_offset=1_000_003,
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
        pga=0.4 * G, duration=50.0, t1=3.0, t2=33.0, decay=0.2,
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
            "0.2 g V, pass vertical_pga=0.2 * G). Softer site than A-1/B-1 "
            "(ground frequency 2 Hz). "
            + _SUBSTITUTE
        ),
        pga=0.5 * G, duration=30.0, t1=1.5, t2=12.0, decay=0.3,
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


@renamed_to_si(1, pga_g="pga", vertical_pga_g="vertical_pga")
def artificial(preset: str | ArtificialPreset | None = None, *, seed: int,
               duration: float | None = None, dt: float = 0.01, pga: float | None = None,
               t1: float | None = None, t2: float | None = None, decay: float | None = None,
               omega_g: float | None = None, zeta_g: float | None = None,
               omega_f: float | None = None, zeta_f: float | None = None,
               vertical_pga: float | None = None, baseline: bool = True,
               name: str | None = None) -> Motion:
    """Artificial earthquake accelerogram (filtered, enveloped white noise).

    Stationary Gaussian white noise (``numpy.random.default_rng(seed)``) is
    passed through a Kanai-Tajimi ground filter and a Clough-Penzien high-pass
    filter [3]_ (so the displacement has finite variance and does not drift),
    multiplied by the intensity envelope of Jennings, Housner and Tsai [2]_
    (:func:`jennings_envelope`), baseline-corrected and scaled so that the
    peak horizontal acceleration is exactly ``pga``.

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
        overrides the preset's value. Without a preset ``pga``, ``t1``,
        ``t2`` and ``decay`` are required.
    seed : int
        Seed for ``numpy.random.default_rng``, a non-negative integer. Same
        seed and parameters give an identical motion.
    duration : float, optional
        Length of the record [s]; default the preset's, or without a preset
        ``t2 + ln(100) / decay`` (envelope down to 1 %).
    dt : float, optional
        Sample interval [s], positive.
    pga : float, optional
        Peak horizontal acceleration [m/s^2], positive (``0.5 * G`` for 0.5 g,
        with :data:`~shaketable.core.constants.G`).
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
    vertical_pga : float, optional
        If given, add a vertical component with this peak [m/s^2], positive up:
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
        defaults.update(pga=preset.pga, t1=preset.t1, t2=preset.t2,
                        decay=preset.decay, omega_g=preset.omega_g,
                        zeta_g=preset.zeta_g, omega_f=preset.omega_f,
                        zeta_f=preset.zeta_f, duration=preset.duration)
    given = dict(pga=pga, t1=t1, t2=t2, decay=decay, omega_g=omega_g,
                 zeta_g=zeta_g, omega_f=omega_f, zeta_f=zeta_f, duration=duration)
    values = {key: (value if value is not None else defaults.get(key))
              for key, value in given.items()}
    for key in ("pga", "t1", "t2", "decay"):
        if values[key] is None:
            raise ValueError(f"{key} is required when no preset is given")
    units = dict(pga=" [m/s^2]", t1=" [s]", t2=" [s]", decay=" [1/s]",
                 omega_g=" [rad/s]", zeta_g="", omega_f=" [rad/s]", zeta_f="",
                 duration=" [s]")
    checked = {key: _positive(key, values[key], units[key])
               for key in ("pga", "t1", "t2", "decay", "omega_g", "zeta_g", "omega_f", "zeta_f")}
    if checked["t2"] < checked["t1"]:
        raise ValueError(f"t2 ({checked['t2']!r} s) must not be before t1 ({checked['t1']!r} s)")
    total_asked = values["duration"]
    if total_asked is None:
        total_asked = checked["t2"] + math.log(100.0) / checked["decay"]
    total = _positive("duration", total_asked, " [s]")
    dt = _positive("dt", dt, " [s]")
    if vertical_pga is not None:
        vertical_pga = _positive("vertical_pga", vertical_pga, " [m/s^2]")

    t = time_grid(total, dt)
    n = t.size
    filters = (checked["omega_g"], checked["zeta_g"], checked["omega_f"], checked["zeta_f"])
    envelope = jennings_envelope(t, checked["t1"], checked["t2"], checked["decay"])
    rng = np.random.default_rng(int(seed) + (preset.seed_offset if preset is not None else 0))

    def component(target_peak: float) -> np.ndarray:
        shaped = envelope * _filtered_noise(rng, n, dt, *filters)
        if baseline:
            shaped = _baseline_corrected(shaped, envelope, t, dt)
        peak = np.max(np.abs(shaped))
        if peak == 0.0:  # only if the envelope is zero everywhere
            raise ValueError("the envelope is zero over the whole duration; check t1, duration")
        return shaped * (target_peak / peak)

    horizontal = component(checked["pga"])
    vertical = None if vertical_pga is None else component(vertical_pga)
    if name is None:
        name = preset.name if preset is not None else "artificial"
    return Motion(t, horizontal, vertical, name=f"{name} (seed {int(seed)})")
