"""Property tests (hypothesis) of the engine's invariants."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st_

import shaketable as st
from shaketable.core import theory
from shaketable.core.constants import G

blocks = st_.builds(lambda height, aspect: st.Block(height, height / aspect),
                    st_.floats(0.05, 10.0), st_.floats(1.0, 12.0))


@settings(max_examples=25, deadline=None)
@given(block=blocks, ratio=st_.floats(0.05, 0.95), cor=st_.floats(0.0, 1.0))
def test_free_rocking_never_gains_energy(block, ratio, cor):
    amplitude = ratio * block.alpha
    result = st.simulate(block, cor=cor, theta0=amplitude,
                         duration=3 * theory.exact_period(block, amplitude))
    # never beyond the release angle; impact velocities never grow (Eq. 2-6, cor <= 1)
    assert result.max_abs_theta <= amplitude * (1 + 1e-9)
    velocities = np.abs(result.impact_velocities)
    assert np.all(np.diff(velocities) <= 1e-9 * velocities[0] + 1e-15)
    assert np.all(np.isfinite(result.theta))


@settings(max_examples=20, deadline=None)
@given(block=blocks, amplitude_g=st_.floats(0.0, 1.5), frequency=st_.floats(0.5, 8.0),
       vertical_g=st_.floats(-0.5, 0.5), cor=st_.floats(0.5, 1.0))
def test_mirror_symmetry_and_density_free(block, amplitude_g, frequency, vertical_g, cor):
    t = np.arange(0.0, 3.0, 0.01)
    motion = st.Motion.from_g(t, amplitude_g * np.sin(2 * np.pi * frequency * t),
                              vertical_g * np.cos(2 * np.pi * frequency * t))
    result = st.simulate(block, motion, cor=cor)
    mirrored = st.simulate(block, motion.mirrored(), cor=cor)
    np.testing.assert_allclose(mirrored.theta, -result.theta, rtol=0, atol=1e-12)
    assert result.overturned == mirrored.overturned
    # Eq. (2-1): no rocking at all if the horizontal never exceeds (B/H)(g + v)
    threshold = block.width / block.height * (G + motion.vertical_or_zero)
    if np.all(np.abs(motion.horizontal) < threshold):
        assert math.isnan(result.t_start) and np.all(result.theta == 0.0)
