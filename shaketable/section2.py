"""Figs. 2.3-2.6 of the report and the pulse of Section 4.3 (4): closed forms against the engine.

Each function returns a table (pandas DataFrame) with the report's analytic
curve and the exact answer computed by the engine, so the figure shows where
the slender-block approximations of Sections 2.2-2.4 fail.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from . import motions, theory
from .constants import G
from .geometry import Block
from .simulate import simulate


def _bisect(predicate, low, high, iterations=30):
    """Smallest x in [low, high] with predicate(x) true (predicate monotone).

    Raises ValueError when the bracket does not hold the switch (predicate(low)
    already true, or predicate(high) false), instead of returning its edge.
    """
    if predicate(low) or not predicate(high):
        raise ValueError(f"the bracket [{low:.6g}, {high:.6g}] does not hold the threshold")
    for _ in range(iterations):
        middle = 0.5 * (low + high)
        low, high = (low, middle) if predicate(middle) else (middle, high)
    return 0.5 * (low + high)


def figure_2_3(blocks=None, ratios=None) -> pd.DataFrame:
    """Period vs amplitude (Fig. 2.3): Eq. (2-5), the exact period, and the engine's
    time between impacts (x 2) at COR 1 [s]."""
    blocks = blocks or [Block.from_inches(30, 6), Block.from_inches(36, 9),
                        Block.from_feet(16, 4), Block.from_feet(6, 3)]
    ratios = np.linspace(0.05, 0.95, 19) if ratios is None else np.asarray(ratios)
    rows = []
    for block in blocks:
        for ratio in ratios:
            amplitude = ratio * block.alpha
            exact = theory.exact_period(block, amplitude)
            run = simulate(block, cor=1.0, theta0=amplitude, duration=1.6 * exact,
                           output_dt=exact / 50)
            rows.append({"block": block.describe(), "R [m]": block.R, "alpha [rad]": block.alpha,
                         "theta0/alpha [-]": ratio,
                         "Eq. 2-5 [s]": theory.housner_period(block, amplitude),
                         "exact [s]": exact,
                         "engine [s]": 2 * float(np.diff(run.impact_times[:2])[0])})
    return pd.DataFrame(rows)


def figure_2_4(block=None, ratios=None) -> pd.DataFrame:
    """Duration t1 of a constant acceleration a that overturns the block (Fig. 2.4):
    Eq. (2-7) against the engine (bisection on t1) [s]."""
    block = block or Block.from_feet(16, 4)
    ratios = np.array([1.1, 1.25, 1.5, 2.0, 3.0, 4.0]) if ratios is None else np.asarray(ratios)
    rows = []
    for ratio in ratios:
        acceleration_g = ratio * block.alpha  # a / g = ratio * alpha (a/(g alpha) = ratio)
        closed = theory.constant_pulse_overturn_duration(block, acceleration_g * G)

        def overturns(duration, acceleration_g=acceleration_g):
            motion = motions.constant_pulse(acceleration_g, duration, duration=duration + 6.0 /
                                            block.p * 3, dt=min(duration / 200, 0.002))
            return simulate(block, motion, cor=1.0).overturned

        engine = _bisect(overturns, 0.02 * closed, 3.0 * closed)
        rows.append({"a/(g alpha) [-]": ratio, "a [g]": acceleration_g,
                     "Eq. 2-7 t1 [s]": closed, "engine t1 [s]": engine})
    return pd.DataFrame(rows)


def figure_2_5(heights=None, aspect_ratio: float = 4.0, accelerations_g=(0.5, 1.0, 2.0),
               pulse_duration: float = 0.1) -> pd.DataFrame:
    """Time at which blocks of various size overturn under a constant acceleration a
    lasting 0.1 s (Fig. 2.5): the slender-block closed form against the engine.

    The report's text gives the pulse (0.1 s) but not the blocks it plotted;
    here geometrically similar blocks of height/width ``aspect_ratio`` (4, the
    30 x 6 in test block's shape, alpha = 0.245 rad) and several a.

    Returns one row per (a, height): the closed form's time to theta = alpha
    (:func:`shaketable.theory.constant_pulse_unstable_time`, ``inf`` when the
    block falls back) and the engine's time to |theta| = alpha and to
    |theta| = pi/2 (exact Eq. 2-13, COR 1) [s], NaN when it does not get there.
    """
    heights = (np.geomspace(0.1, 3.0, 12) if heights is None else np.asarray(heights))
    rows = []
    for acceleration_g in accelerations_g:
        for height in heights:
            block = Block(float(height), float(height) / aspect_ratio)
            closed = theory.constant_pulse_unstable_time(block, acceleration_g * G,
                                                         pulse_duration)
            duration = pulse_duration + 12.0 / block.p
            motion = motions.constant_pulse(acceleration_g, pulse_duration, duration=duration,
                                            dt=min(pulse_duration / 100, 0.25 / block.p / 20))
            run = simulate(block, motion, cor=1.0)
            rows.append({"a [g]": acceleration_g, "height [m]": float(height),
                         "R [m]": block.R, "p [rad/s]": block.p,
                         "closed form t(alpha) [s]": closed,
                         "engine t(alpha) [s]": run.t_unstable,
                         "engine t(pi/2) [s]": run.t_overturn,
                         "engine overturns": run.overturned})
    return pd.DataFrame(rows)


def figure_2_6(block=None, frequency_ratios=None) -> pd.DataFrame:
    """Amplitude of a single half-sine pulse that overturns the block vs omega/p (Fig. 2.6):
    Eq. (2-8), Eq. (2-9) and the engine (bisection on the amplitude) [g]."""
    block = block or Block.from_feet(16, 4)
    frequency_ratios = (np.array([1.0, 2.0, 3.0, 5.0, 10.0, 18.0])
                        if frequency_ratios is None else np.asarray(frequency_ratios))
    rows = []
    for ratio in frequency_ratios:
        omega = ratio * block.p
        period = 2 * math.pi / omega
        pulse = period / 2

        def overturns(amplitude_g, pulse=pulse):
            motion = motions.half_sine_pulse(amplitude_g, pulse, duration=pulse + 20.0 / block.p,
                                             dt=pulse / 200)
            return simulate(block, motion, cor=1.0).overturned

        rows.append({"omega/p [-]": ratio, "pulse duration [s]": pulse,
                     "Eq. 2-8 [g]": theory.half_sine_overturn_amplitude(block, period) / G,
                     "Eq. 2-9 [g]": theory.half_sine_overturn_amplitude_large_frequency(
                         block, period) / G,
                     "engine [g]": _bisect(overturns, 0.2 * block.alpha, 40 * block.alpha *
                                           max(ratio, 1.0))})
    return pd.DataFrame(rows)


def _half_sine_then_rest(amplitude_g, pulse, tail, points=200, dt_after=0.005):
    """A half-sine pulse finely sampled, then the table at rest (coarse samples)."""
    from .motion import Motion

    during = np.linspace(0.0, pulse, points + 1)
    after = pulse + dt_after * np.arange(1, int(math.ceil(tail / dt_after)) + 1)
    t = np.concatenate([during, after])
    horizontal = np.concatenate([amplitude_g * G * np.sin(math.pi * during / pulse),
                                 np.zeros(after.size)])
    horizontal[points] = 0.0  # sin(pi) rounding
    return Motion(t, horizontal, name=f"half-sine {amplitude_g:.4g} g, {pulse:g} s")


def section_4_3_4(block=None, pulse_durations=(0.1, 0.05, 0.02, 0.01)) -> pd.DataFrame:
    """Section 4.3 (4): a single half-sine pulse that overturns the 16 x 4 ft block [g].

    The report: "using Eq. (2-9) ... the amplitude ... of a single sine wave of
    duration 0.1 second has to be at least 4.6 g". Per pulse duration: Eq. (2-9),
    Eq. (2-8), the exact impulsive limit
    (:func:`shaketable.theory.half_sine_impulse_overturn_amplitude`) and the
    engine (exact Eq. 2-13, bisection on the amplitude to 1e-4 relative). The
    engine's amplitude tends to the impulsive limit as the pulse shortens;
    both are about half of Eq. (2-9), whose slender derivation asks theta to
    reach alpha with the pulse still acting. Either way the report's point
    stands: a single pulse needs several g, the earthquakes that overturn the
    block peak near 0.5 g (Table 4.1).
    """
    block = block or Block.from_feet(16, 4)
    rows = []
    for pulse in pulse_durations:
        period = 2.0 * pulse
        impulse = theory.half_sine_impulse_overturn_amplitude(block, pulse) / G

        def overturns(amplitude_g, pulse=pulse):
            motion = _half_sine_then_rest(amplitude_g, pulse, tail=12.0 / block.p)
            return simulate(block, motion, cor=1.0).overturned

        engine = _bisect(overturns, 0.5 * impulse, 2.0 * impulse, iterations=16)
        rows.append({"pulse duration [s]": pulse, "omega/p [-]": math.pi / pulse / block.p,
                     "Eq. 2-9 [g]": theory.half_sine_overturn_amplitude_large_frequency(
                         block, period) / G,
                     "Eq. 2-8 [g]": theory.half_sine_overturn_amplitude(block, period) / G,
                     "impulse limit [g]": impulse, "engine [g]": engine,
                     "engine / impulse limit [-]": engine / impulse})
    return pd.DataFrame(rows)
