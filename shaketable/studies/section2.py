"""Figs. 2.3-2.6 of the report and the pulse of Section 4.3 (4): closed forms against the engine.

Each function returns a table (pandas DataFrame) with the report's analytic
curve and the exact answer computed by the engine, so the figure shows where
the slender-block approximations of Sections 2.2-2.4 fail.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from shaketable.core import theory
from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.ground import generators as motions
from shaketable.ground.pulses import Pulse
from shaketable.models.api import simulate
from shaketable.studies.overturning_spectrum import threshold
from shaketable.studies.pulses import bisect_threshold


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
    Eq. (2-7) against the engine (bisection on t1, its single switch checked on a scan
    of the bracket: :func:`shaketable.studies.pulses.bisect_threshold`) [s]."""
    block = block or Block.from_feet(16, 4)
    ratios = np.array([1.1, 1.25, 1.5, 2.0, 3.0, 4.0]) if ratios is None else np.asarray(ratios)
    rows = []
    for ratio in ratios:
        acceleration_g = ratio * block.alpha  # a / g = ratio * alpha (a/(g alpha) = ratio)
        closed = theory.constant_pulse_overturn_duration(block, acceleration_g * G)

        def overturns(duration, acceleration_g=acceleration_g):
            motion = motions.constant_pulse(acceleration=acceleration_g * G,
                                            pulse_duration=duration,
                                            duration=duration + 6.0 / block.p * 3,
                                            dt=min(duration / 200, 0.002))
            return simulate(block, motion, cor=1.0).overturned

        engine = bisect_threshold(overturns, 0.02 * closed, 3.0 * closed)
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
    (:func:`shaketable.core.theory.constant_pulse_unstable_time`, ``inf`` when the
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
            motion = motions.constant_pulse(acceleration=acceleration_g * G,
                                            pulse_duration=pulse_duration, duration=duration,
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
    Eq. (2-8), Eq. (2-9) and the engine (bisection on the amplitude, its single transition
    checked on a 1 % scan: :func:`shaketable.studies.overturning_spectrum.threshold`) [g]."""
    block = block or Block.from_feet(16, 4)
    frequency_ratios = (np.array([1.0, 2.0, 3.0, 5.0, 10.0, 18.0])
                        if frequency_ratios is None else np.asarray(frequency_ratios))
    rows = []
    for ratio in frequency_ratios:
        omega = ratio * block.p
        period = 2 * math.pi / omega
        pulse = period / 2

        # exact pulse (8192 samples per cycle), verdict after it decided by energy,
        # and a check that no lower band is skipped (overturning_spectrum.threshold)
        engine = math.tan(block.alpha) * threshold(
            block, Pulse("half-sine", omega), cor=1.0, low=0.2 * block.alpha / math.tan(block.alpha),
            high=40 * block.alpha * max(ratio, 1.0) / math.tan(block.alpha))
        rows.append({"omega/p [-]": ratio, "pulse duration [s]": pulse,
                     "Eq. 2-8 [g]": theory.half_sine_overturn_amplitude(block, period) / G,
                     "Eq. 2-9 [g]": theory.half_sine_overturn_amplitude_large_frequency(
                         block, period) / G,
                     "engine [g]": engine})
    return pd.DataFrame(rows)
