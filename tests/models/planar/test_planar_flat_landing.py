"""A block landing flat on both bottom corners (docs/planar.md, "Both corners on the
table"): the two-corner contact problem decides whether it stops, slides or tips.

Reference: the independent Moreau-Jean time-stepping solver of
:mod:`shaketable.models.planar.moreau` (numpy only, no modes or events): the
midpoint scheme of Moreau and Jean with both bottom corners as unilateral contacts, the
plastic Newton law and Coulomb friction at the velocity level, the contact problem of each
step solved exactly by enumerating every contact's status (off, sticking, slipping either
way), refined to convergence (three steps, each half the last). Before the two-corner
problem, a landing with mu_s > B/H and |x'| > (B/H)|y'| stopped or slid on flat; the
Moreau-Jean solution tips it.
"""

from __future__ import annotations

import numpy as np
import pytest

from shaketable import Block
from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.models.planar.moreau import simulate_moreau_jean
from shaketable.models.planar.run import simulate_planar
from shaketable.models.sliding.result import Friction

BLOCK = Block(height=1.0, width=0.5)

#: Moreau-Jean steps [s]: each half the last; the spread of their max |theta| is the
#: solver's convergence error.
STEPS = (1e-4, 5e-5, 2.5e-5)


def moreau_jean(state, mu, step, duration):
    """(theta at each step, the corners that push at each step) from ``state`` (x, y,
    theta and their rates) on a table at rest."""
    result = simulate_moreau_jean(BLOCK, friction=Friction(mu), step=step,
                                  duration=duration, state=state)
    return result.theta, list(result.pushing)


def _landing_motion(x_speed, lift):
    """The table at rest but for a downward pulse of -2 g, ``lift`` [s] long, that throws
    the flat block up, and a horizontal pulse in its flight that gives it x' = x_speed."""
    t = np.round(np.arange(0.0, 0.6 + 1e-9, 0.001), 12)
    vertical = np.where((t >= 0.01) & (t <= 0.01 + lift), -2.0 * G, 0.0)
    horizontal = np.where((t >= 0.02) & (t <= 0.03), -x_speed / 0.01, 0.0)
    return Motion(t, horizontal, vertical)


def _sequence(pushing):
    """The successive sets of pushing corners, from the first contact."""
    sequence = []
    for corners in pushing:
        if corners and (not sequence or corners != sequence[-1]):
            sequence.append(corners)
    return sequence


@pytest.mark.parametrize("x_speed, lift, mu", [
    (0.1, 0.04, 0.8),    # |x'| < (B/H)|y'|: sticks flat
    (0.8, 0.05, 0.3),    # mu < B/H: slides flat
    (0.4, 0.04, 0.8),    # mu > B/H, |x'| > (B/H)|y'|: tips onto the leading corner
    (0.8, 0.03, 0.8),
    (0.6, 0.05, 1.0),
])
def test_a_flat_landing_follows_the_moreau_jean_solution(x_speed, lift, mu):
    # cor "housner": the plastic Newton law, the one Moreau-Jean converges to
    result = simulate_planar(BLOCK, _landing_motion(x_speed, lift), cor="housner",
                             friction=Friction(mu))
    start = int(np.searchsorted(result.t, 0.07))   # in flight, the table at rest again
    assert result.mode[start] == 4 and result.status == "completed"
    state = [result.x[start], result.y[start], result.theta[start], result.x_dot[start],
             result.y_dot[start], result.theta_dot[start]]
    landing = result.events[result.events[:, 1] == 6, 0][0]
    tips = result.n_impacts > 0
    # the first excursion (to the first impact), refined; or 10 ms after a flat landing
    end = result.impact_times[0] + 0.005 if tips else landing + 0.01
    runs = [moreau_jean(state, mu, step, end - result.t[start])
            for step in (STEPS if tips else STEPS[:1])]
    peaks = [np.max(np.abs(thetas)) for thetas, _ in runs]
    expected_sequence = _sequence(runs[-1][1])
    if tips:
        error = max(abs(peaks[1] - peaks[0]), abs(peaks[2] - peaks[1]))
        side = -1.0 if x_speed > 0 else 1.0   # the leading corner (+x: side -1)
        assert expected_sequence[:2] == [(side,), (-side,)]
        assert np.sign(result.theta[result.t > landing][1]) == side
        assert result.max_abs_theta == pytest.approx(peaks[-1], abs=2.0 * error)
        assert error < 0.01 * peaks[-1]
    else:
        assert expected_sequence == [(1.0, -1.0)]
        assert result.max_abs_theta == 0.0 and peaks[-1] < 1e-15
        after = result.mode[(result.t > landing) & (result.t < end)]
        assert set(after) <= {0, 1}   # rest or slide: both corners
