"""The Moreau-Jean time stepping of the planar block (``models.planar.moreau``) on closed forms.

Its convergence on a coupled run is in tests/studies/test_planar_work_precision.py and its
flat landings in tests/models/planar/test_planar_flat_landing.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaketable import Block
from shaketable.core.constants import G
from shaketable.models.planar.moreau import simulate_moreau_jean
from shaketable.models.sliding.result import Friction


def test_free_flight_is_exact():
    # above the table, no contact: the midpoint scheme is exact for constant gravity
    block = Block(height=1.0, width=0.5)
    state = (0.0, 2.0, 0.1, 0.3, 1.0, 0.5)
    result = simulate_moreau_jean(block, friction=Friction(0.5), step=1e-3, duration=0.1,
                                  state=state)
    t = result.t
    np.testing.assert_allclose(result.y, 2.0 + t - 0.5 * G * t * t, rtol=0, atol=1e-13)
    np.testing.assert_allclose(result.x, 0.3 * t, rtol=0, atol=1e-14)
    np.testing.assert_allclose(result.theta, 0.1 + 0.5 * t, rtol=0, atol=1e-14)
    assert all(not corners for corners in result.pushing)


def test_a_block_at_rest_stays_at_rest():
    block = Block(height=1.0, width=0.5)
    result = simulate_moreau_jean(block, friction=Friction(0.5), step=1e-3, duration=0.05)
    # the stacked solves leave rounding only (1e-20 measured)
    assert result.max_abs_theta < 1e-15 and result.peak_slip < 1e-15
    np.testing.assert_allclose(result.y, block.h, rtol=0, atol=1e-15)
    assert all(corners == (1.0, -1.0) for corners in result.pushing)


def test_sliding_stops_after_the_coulomb_distance():
    # a squat block (cannot rock at mu 0.3) pushed at 1 m/s on a table at rest stops after
    # v^2 / (2 mu_d g): 0.1699 m at mu_d 0.3 (first order in h)
    block = Block(height=0.25, width=1.0)
    result = simulate_moreau_jean(block, friction=Friction(0.3), step=1e-4, duration=0.5,
                                  state=(0.0, block.h, 0.0, 1.0, 0.0, 0.0))
    expected = 1.0 / (2.0 * 0.3 * G)
    assert result.peak_slip == pytest.approx(expected, abs=2e-4)
    assert result.max_abs_theta < 1e-12


def test_a_block_released_past_alpha_overturns():
    # free rocking from 1.05 alpha: the block falls; the time is that of the step crossing
    block = Block.from_inches(30, 6)
    upright = simulate_moreau_jean(block, friction=Friction(10.0), step=1e-3, duration=1.0,
                                   state=_tilted(block, 0.5 * block.alpha))
    assert not upright.overturned and math.isnan(upright.t_overturn)
    tilted = simulate_moreau_jean(
        block, friction=Friction(10.0), step=1e-3, duration=5.0,
        state=_tilted(block, 1.05 * block.alpha))
    assert tilted.overturned and tilted.status == "overturned"
    assert 0.0 < tilted.t_overturn < 5.0 and tilted.max_abs_theta == 0.5 * math.pi


def _tilted(block, theta):
    """At rest tilted by ``theta`` on the corner side +1 (arm (-b cos + h sin,
    -b sin - h cos)), that corner where it stands upright (x = -b)."""
    b, h = block.b, block.h
    return (-b + b * math.cos(theta) - h * math.sin(theta),
            b * math.sin(theta) + h * math.cos(theta), theta, 0.0, 0.0, 0.0)


def test_bad_input_names_the_parameter():
    block = Block(height=1.0, width=0.5)
    with pytest.raises(ValueError, match="step"):
        simulate_moreau_jean(block, friction=Friction(0.5), step=0.0, duration=1.0)
    with pytest.raises(ValueError, match="duration"):
        simulate_moreau_jean(block, friction=Friction(0.5), step=1e-3)
    with pytest.raises(ValueError, match="state"):
        simulate_moreau_jean(block, friction=Friction(0.5), step=1e-3, duration=1.0,
                             state=(0.0, 1.0))
    with pytest.raises(TypeError, match="friction"):
        simulate_moreau_jean(block, friction=0.5, step=1e-3, duration=1.0)
    with pytest.raises(TypeError, match="block"):
        simulate_moreau_jean("1x0.5m", friction=Friction(0.5), step=1e-3, duration=1.0)
