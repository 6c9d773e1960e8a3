"""Pulse studies: the overturning threshold by bisection and Section 4.3 (4) (the 16 x 4 ft
block under short half-sine pulses, Eq. 2-9).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from shaketable.core import theory
from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.solvers.api import simulate


def bisect_threshold(predicate, low, high, iterations=30):
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


def _half_sine_then_rest(amplitude_g, pulse, tail, points=200, dt_after=0.005):
    """A half-sine pulse finely sampled, then the table at rest (coarse samples)."""
    from shaketable.core.motion import Motion

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
    (:func:`shaketable.core.theory.half_sine_impulse_overturn_amplitude`) and the
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

        engine = bisect_threshold(overturns, 0.5 * impulse, 2.0 * impulse, iterations=16)
        rows.append({"pulse duration [s]": pulse, "omega/p [-]": math.pi / pulse / block.p,
                     "Eq. 2-9 [g]": theory.half_sine_overturn_amplitude_large_frequency(
                         block, period) / G,
                     "Eq. 2-8 [g]": theory.half_sine_overturn_amplitude(block, period) / G,
                     "impulse limit [g]": impulse, "engine [g]": engine,
                     "engine / impulse limit [-]": engine / impulse})
    return pd.DataFrame(rows)
