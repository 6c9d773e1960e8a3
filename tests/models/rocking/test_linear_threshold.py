"""Where each method starts rocking (README "Solvers").

Eq. (2-1): the block lifts when |ug| exceeds g tan(alpha) (1 + vg/g). Housner's
linearised equation (Eq. 2-4) replaces tan(alpha) by alpha, so the ``linear``
method lifts at g alpha: for the 30 x 6 in block (tan(alpha) = 0.2, alpha =
0.19740) a 2 Hz sine of amplitude between 0.1974 g and 0.2 g rocks the block
under ``linear`` and not under the exact methods.
"""

from __future__ import annotations

import math

import pytest

import shaketable as st
from shaketable.core.constants import G
from shaketable.ground import generators

BLOCK = st.Block.parse("30x6in")


@pytest.mark.parametrize("amplitude, exact_rocks, linear_rocks", [
    (0.199, False, True),     # between g alpha and g tan(alpha)
    (0.1970, False, False),   # below both
    (0.2010, True, True),     # above both
])
def test_linear_lifts_at_g_alpha_the_exact_methods_at_g_tan_alpha(amplitude, exact_rocks,
                                                                  linear_rocks):
    motion = generators.harmonic(2.0, horizontal=amplitude * G, duration=2.0)
    for method, rocks in (("fast", exact_rocks), ("predictor-corrector", exact_rocks),
                          ("linear", linear_rocks)):
        result = st.simulate(BLOCK, motion, cor=0.9, method=method)
        assert math.isfinite(result.t_start) == rocks, method


def test_linear_start_time_is_the_crossing_of_g_alpha():
    """The linear method's lift-off is where the table acceleration (linear between its
    samples, the package's definition of a motion) first reaches g alpha."""
    import numpy as np

    motion = generators.harmonic(2.0, horizontal=0.199 * G, duration=1.0)
    result = st.simulate(BLOCK, motion, cor=0.9, method="linear")
    level = st.G * BLOCK.alpha
    k = int(np.flatnonzero(motion.horizontal >= level)[0])
    t0, t1 = motion.t[k - 1], motion.t[k]
    a0, a1 = motion.horizontal[k - 1], motion.horizontal[k]
    expected = t0 + (level - a0) / (a1 - a0) * (t1 - t0)
    assert result.t_start == pytest.approx(expected, abs=1e-9)
