"""Shenton's (1996) initiation criteria (models/planar/shenton.py), checked two independent ways.

* The closed form of mu_cr against the contact forces of the planar reference's
  Newton-Euler system (a 5 x 5 linear solve, models/planar/reference.py) and
  against its algebraic properties derived in the module docstring.
* The mode classification against the planar reference solver started from rest
  under constant table accelerations (docs/planar.md), over a
  grid of mu_s, B/H, a/g and vg/g that includes the slide-rock wedge
  B/H < mu < mu_cr(A) and mu_d < mu_s.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.planar.contact import PlanarGeometry, rock_solution
from shaketable.models.planar.reference import simulate_reference
from shaketable.models.planar.shenton import (
    FLIGHT,
    MODE_NAMES,
    REST,
    ROCK,
    SLIDE,
    SLIDE_ROCK,
    critical_friction,
    critical_friction_ratio,
    initial_mode,
)
from shaketable.models.sliding.result import Friction


def test_critical_friction_is_the_force_ratio_of_the_newton_euler_rock_solution():
    # mu_cr = F / N of a block held on its corner at theta = theta' = 0, here from the
    # reference's linear solve (a different formulation from the closed form)
    for height, width in ((1.0, 0.2), (1.0, 0.5), (0.6, 0.6)):
        geometry = PlanarGeometry(Block(height, width))
        for a_g, v_g in ((0.3, 0.0), (0.8, -0.4), (2.0, 0.5)):
            if a_g / (1 + v_g) <= width / height:
                continue
            _, _, _, force, normal = rock_solution(geometry, 1, 0.0, 0.0, a_g * G, v_g * G)
            assert critical_friction(a_g, v_g, width=width, height=height) == pytest.approx(
                force / normal, rel=1e-13)


def test_critical_friction_bounds_and_limits():
    # module docstring: mu_cr(t) = t, t < mu_cr(A) < A for A > t, increasing,
    # limit (4 t^2 + 1) / (3 t) as A -> infinity
    for t in (0.1, 0.25, 0.5, 1.0, 2.0):
        assert critical_friction_ratio(t, t) == pytest.approx(t, rel=1e-14)
        ratios = t * np.array([1.001, 1.1, 1.5, 3.0, 10.0, 100.0])
        values = critical_friction_ratio(ratios, t)
        assert np.all(values > t) and np.all(values < ratios) and np.all(np.diff(values) > 0)
        assert critical_friction_ratio(1e12, t) == pytest.approx((4 * t * t + 1) / (3 * t),
                                                                 rel=1e-9)
    # vertical acceleration enters through A = (a/g) / (1 + vg/g) only
    assert critical_friction(0.6, -0.25, width=1, height=4) == pytest.approx(
        critical_friction(0.8, 0.0, width=1, height=4), rel=1e-15)


def test_bad_input_is_refused_with_the_parameter_named():
    with pytest.raises(ValueError, match="vertical_g"):
        critical_friction(0.5, -1.0, width=1, height=2)
    with pytest.raises(ValueError, match="dynamic_friction"):
        initial_mode(1, 2, 0.3, 0.4, 1.0)
    with pytest.raises(ValueError, match="static_friction"):
        initial_mode(1, 2, float("nan"), 0.1, 1.0)
    with pytest.raises(ValueError, match="width"):
        initial_mode(-1, 2, 0.3, 0.2, 1.0)


def _entered_mode(width, height, mu_s, mu_d, a_g, v_g):
    """Mode the reference enters from rest under constant accelerations (a_g, v_g) [g]."""
    motion = Motion.uniform(0.01, [a_g * G] * 2, [v_g * G] * 2)
    result = simulate_reference(Block(height, width), motion, cor=0.9,
                                friction=Friction(mu_s, mu_d))
    assert result.status in ("completed", "overturned"), result.message
    if result.event_times.size == 0:
        return REST
    assert result.event_times[0] == 0.0  # a constant acceleration acts at once
    return int(result.event_mode_after[0])


def shenton_grid():
    cells = []
    for mu_s, ratio, a_g, v_g in itertools.product((0.1, 0.3, 0.5, 0.8), (0.25, 0.5, 1.0),
                                                   (0.05, 0.2, 0.4, 0.7, 1.2),
                                                   (-0.3, 0.0, 0.3)):
        cells.append((ratio, mu_s, mu_s, a_g, v_g))
    # the slide-rock wedge: mu halfway between B/H and mu_cr(A), and just inside it
    for ratio, a_g, v_g in itertools.product((0.2, 0.4), (0.5, 0.9, 1.5), (-0.2, 0.0, 0.4)):
        A = a_g / (1 + v_g)
        mu_cr = critical_friction_ratio(A, ratio)
        for mu in (0.5 * (ratio + mu_cr), ratio + 0.05 * (mu_cr - ratio),
                   mu_cr - 0.05 * (mu_cr - ratio), mu_cr + 0.05 * (A - mu_cr)):
            cells.append((ratio, mu, mu, a_g, v_g))
    # mu_d < mu_s (the spec's start rules) and flight
    for ratio, a_g, (mu_s, mu_d) in itertools.product((0.25, 0.5), (0.3, 0.6, 1.0),
                                                      ((0.6, 0.3), (0.35, 0.2), (0.9, 0.1))):
        cells.append((ratio, mu_s, mu_d, a_g, 0.0))
    cells += [(0.5, 0.5, 0.5, 0.3, -1.5), (0.3, 0.2, 0.2, 0.0, -1.2)]
    return cells


def near_a_boundary(ratio, mu_s, mu_d, a_g, v_g):
    if v_g <= -1:
        return False
    A = a_g / (1 + v_g)
    mu_cr = critical_friction_ratio(A, ratio)
    return any(abs(u - v) < 1e-3 for u, v in ((A, ratio), (A, mu_s), (mu_s, mu_cr),
                                              (mu_d, ratio)))


def test_the_reference_enters_the_mode_shenton_predicts():
    cells = [cell for cell in shenton_grid() if not near_a_boundary(*cell)]
    predicted = [int(initial_mode(ratio, 1.0, mu_s, mu_d, a_g * G, v_g * G))
                 for ratio, mu_s, mu_d, a_g, v_g in cells]
    entered = [_entered_mode(ratio, 1.0, mu_s, mu_d, a_g, v_g)
               for ratio, mu_s, mu_d, a_g, v_g in cells]
    wrong = [(cell, MODE_NAMES[p], MODE_NAMES[e]) for cell, p, e in
             zip(cells, predicted, entered) if p != e]
    assert wrong == []
    # the grid visits every mode, the wedge included
    assert set(predicted) == {REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT}
    assert predicted.count(SLIDE_ROCK) >= 20


def test_shentons_wedge_is_where_section_2_1_says_rock():
    # Section 2.1 of the report: mu_s > B/H rocks. Shenton: it slide-rocks below mu_cr.
    ratio, a_g = 0.25, 0.6
    mu = 0.5 * (ratio + critical_friction(a_g, width=ratio, height=1.0))
    assert mu > ratio
    assert initial_mode(ratio, 1.0, mu, mu, a_g * G) == SLIDE_ROCK
    assert _entered_mode(ratio, 1.0, mu, mu, a_g, 0.0) == SLIDE_ROCK
