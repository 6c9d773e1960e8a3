"""Figures of the table-motion generators (:mod:`shaketable.ground.generators`).

A plotting module (matplotlib is imported only when a function is called).

:func:`plot_artificial_presets` shows what the artificial presets ("A-1",
"B-1", "olive-view") contain: for a few seeds, the acceleration history with
its strong-motion window, the 5 %-damped pseudo-acceleration response
spectrum and the Fourier amplitude spectrum, with the PGA and the 5-95 %
Arias duration of every realisation. The presets are SUBSTITUTES in the
spirit of the report's records, not the originals (which are not available);
the figure says so in its title.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from shaketable.core.constants import G
from shaketable.ground import generators, signals
from shaketable.plots.base import pyplot

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

__all__ = ["plot_artificial_presets", "preset_measures"]

#: Default natural periods of the response spectrum [s], 0.02 to 5 s.
DEFAULT_PERIODS = np.geomspace(0.02, 5.0, 90)


def _check_presets(presets) -> list[str]:
    if isinstance(presets, str):
        presets = [presets]
    names = list(presets)
    if not names:
        raise ValueError("presets is empty; give names from "
                         f"{sorted(generators.PRESETS)}")
    for name in names:
        if name not in generators.PRESETS:
            raise ValueError(f"unknown preset {name!r} in presets; expected names from "
                             f"{sorted(generators.PRESETS)}")
    return names


def _check_seeds(seeds) -> list[int]:
    if isinstance(seeds, (numbers.Integral, np.integer)) and not isinstance(seeds, bool):
        seeds = [seeds]
    values = list(seeds)
    if not values:
        raise ValueError("seeds is empty; give one or more non-negative integers")
    for seed in values:
        if isinstance(seed, bool) or not isinstance(seed, (numbers.Integral, np.integer)) \
                or seed < 0:
            raise ValueError(f"seeds must be non-negative integers, got {seed!r}")
    return [int(seed) for seed in values]


def _arias_window(motion, low=0.05, high=0.95) -> tuple[float, float]:
    """Times [s] at which the cumulative Arias intensity reaches ``low`` and ``high``."""
    arias = signals.arias_intensity(motion)
    fraction = arias / arias[-1]
    start, end = (float(np.interp(level, fraction, motion.t)) for level in (low, high))
    return start, end


def preset_measures(presets: str | Sequence[str] = ("A-1", "B-1", "olive-view"),
                    seeds: int | Sequence[int] = (0, 1, 2), *,
                    dt: float = 0.01) -> pd.DataFrame:
    """PGA, strong-motion duration and predominant frequency of preset realisations.

    Parameters
    ----------
    presets : sequence of str
        Names from :data:`shaketable.ground.generators.PRESETS`.
    seeds : sequence of int
        Seeds of the realisations (non-negative integers).
    dt : float, optional
        Sample interval of the realisations [s].

    Returns
    -------
    pandas.DataFrame
        One row per preset and seed: ``preset``, ``seed``, ``pga [g]``,
        ``target pga [g]``, ``D5-95 [s]`` (5-95 % Arias duration),
        ``t5 [s]``, ``t95 [s]``, ``predominant frequency [Hz]`` (peak of the
        Fourier amplitude smoothed over 0.5 Hz) and ``duration [s]``.

    Raises
    ------
    ValueError
        Unknown preset, bad seed or ``dt``; the message names it.
    """
    import pandas as pd

    rows = []
    for name in _check_presets(presets):
        for seed in _check_seeds(seeds):
            motion = generators.artificial(name, seed=seed, dt=dt)
            t5, t95 = _arias_window(motion)
            frequency, amplitude = signals.fourier_amplitude(motion)
            smooth = _smoothed(frequency, amplitude, 0.5)
            rows.append({
                "preset": name, "seed": seed, "pga [g]": motion.pga / G,
                "target pga [g]": generators.PRESETS[name].pga / G,
                "D5-95 [s]": t95 - t5, "t5 [s]": t5, "t95 [s]": t95,
                "predominant frequency [Hz]": float(frequency[np.argmax(smooth)]),
                "duration [s]": motion.duration,
            })
    return pd.DataFrame(rows)


def _smoothed(frequency: np.ndarray, amplitude: np.ndarray, width: float) -> np.ndarray:
    """Running mean of ``amplitude`` over ``width`` Hz (a boxcar of whole bins)."""
    step = frequency[1] - frequency[0]
    bins = max(1, int(round(width / step)))
    kernel = np.ones(bins) / bins
    return np.convolve(amplitude, kernel, mode="same")


def plot_artificial_presets(presets: str | Sequence[str] = ("A-1", "B-1", "olive-view"),
                            seeds: int | Sequence[int] = (0, 1, 2), *, dt: float = 0.01,
                            damping: float = 0.05, periods: ArrayLike | None = None,
                            smoothing: float = 0.25) -> Figure:
    """Frequency content, PGA and strong-motion duration of the artificial presets.

    One row per preset, three panels each:

    1. acceleration [g] of the first seed against time [s], the 5-95 %
       Arias window shaded, the other seeds faint behind it;
    2. pseudo-acceleration response spectrum S_a [g] against period [s],
       ``damping`` of critical, every seed and their mean, the preset's PGA
       as the zero-period limit;
    3. Fourier amplitude [m/s] against frequency [Hz] (log-log, smoothed
       over ``smoothing`` Hz), every seed, with the Kanai-Tajimi ground
       frequency of the preset marked.

    The legend of each row gives the PGA [g] and the 5-95 % Arias duration
    [s] of every seed.

    Parameters
    ----------
    presets : sequence of str, optional
        Names from :data:`shaketable.ground.generators.PRESETS`.
    seeds : sequence of int, optional
        Seeds of the realisations (non-negative integers).
    dt : float, optional
        Sample interval of the realisations [s].
    damping : float, optional
        Damping ratio of the response spectrum [-], ``0 <= damping < 1``.
    periods : array_like, optional
        Natural periods of the response spectrum [s]; default 90 periods
        from 0.02 to 5 s.
    smoothing : float, optional
        Width of the running mean applied to the Fourier amplitude [Hz],
        positive.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        Unknown preset, bad seed, ``dt``, ``damping``, ``periods`` or
        ``smoothing``; the message names it.

    Notes
    -----
    The presets are **substitutes** for the report's artificial records
    (Section 4.1), not the originals, which are not available; they share
    only the stated PGA and length of strong motion (``docs/motions.md``).
    """
    names = _check_presets(presets)
    seed_list = _check_seeds(seeds)
    if periods is None:
        periods = DEFAULT_PERIODS
    if isinstance(smoothing, bool) or not isinstance(smoothing, (numbers.Real, np.floating)) \
            or not math.isfinite(smoothing) or smoothing <= 0:
        raise ValueError(f"smoothing must be a positive number [Hz], got {smoothing!r}")
    plt = pyplot()
    fig, axes = plt.subplots(len(names), 3, figsize=(14.0, 3.4 * len(names) + 0.8),
                             layout="constrained", squeeze=False,
                             gridspec_kw={"width_ratios": [1.45, 1.0, 1.0]})
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for row, name in zip(axes, names):
        preset = generators.PRESETS[name]
        history, spectrum, fourier = row
        spectra = []
        for index, seed in enumerate(seed_list):
            colour = colours[index % len(colours)]
            motion = generators.artificial(name, seed=seed, dt=dt)
            t5, t95 = _arias_window(motion)
            label = (f"seed {seed}: PGA {motion.pga / G:.2f} g, "
                     f"D5-95 {t95 - t5:.1f} s")
            if index == 0:
                history.plot(motion.t, motion.horizontal / G, color=colour, lw=0.5,
                             label=label, zorder=3)
                history.axvspan(t5, t95, color=colour, alpha=0.12, lw=0,
                                label=f"5-95 % Arias, seed {seed}: {t5:.1f}-{t95:.1f} s")
            else:
                history.plot(motion.t, motion.horizontal / G, color=colour, lw=0.3,
                             alpha=0.35, label=label, zorder=2)
            sa = signals.response_spectrum(motion, periods, damping=damping) / G
            spectra.append(sa)
            spectrum.plot(periods, sa, color=colour, lw=0.9, alpha=0.8)
            frequency, amplitude = signals.fourier_amplitude(motion)
            keep = (frequency > 0.05) & (frequency <= 0.5 / dt)
            fourier.loglog(frequency[keep], _smoothed(frequency, amplitude, smoothing)[keep],
                           color=colour, lw=0.8, alpha=0.8)
        spectrum.plot(periods, np.mean(spectra, axis=0), color="k", lw=1.6,
                      label=f"mean of {len(seed_list)} seeds")
        spectrum.axhline(preset.pga / G, color="0.4", ls=":", lw=1.0,
                         label=f"PGA {preset.pga / G:g} g (T → 0 limit)")
        spectrum.set_xscale("log")
        spectrum.set_xlabel("period T [s]")
        spectrum.set_ylabel(f"S_a [g], ζ = {damping:g}")
        spectrum.legend(fontsize=7, loc="upper right", frameon=False)
        ground = preset.omega_g / (2.0 * math.pi)
        fourier.axvline(ground, color="0.3", ls="--", lw=0.9,
                        label=f"Kanai-Tajimi f_g = {ground:.1f} Hz")
        fourier.set_xlim(0.05, 0.5 / dt)
        fourier.set_xlabel("frequency [Hz]")
        fourier.set_ylabel(f"Fourier amplitude [m/s]\n({smoothing:g} Hz running mean)")
        fourier.legend(fontsize=7, loc="lower left", frameon=False)
        history.set_xlim(0.0, preset.duration)
        history.set_xlabel("time [s]")
        history.set_ylabel("horizontal [g]")
        history.set_title(f"{name} (substitute): target PGA {preset.pga / G:g} g, "
                          f"{preset.duration:g} s record", loc="left", fontsize=9)
        legend = history.legend(fontsize=7, loc="upper right", frameon=True, framealpha=0.85)
        for handle in getattr(legend, "legend_handles", []):
            if hasattr(handle, "get_xdata"):   # lines at full strength, the span as drawn
                handle.set_alpha(1.0)
        for axis in row:
            axis.grid(True, which="both", lw=0.3, alpha=0.5)
    fig.suptitle("Artificial presets — SUBSTITUTES in the spirit of the report's records "
                 "(Section 4.1), not the originals (not available)", fontsize=10)
    return fig
