"""The asymmetric block in the planar model (compiled engine): each pivot's b, alpha, I0.

References: the asymmetric rocking solver (``models/rocking/asymmetric.py``, its SciPy
``reference`` method) in the rocking limit (ample friction: the pivots never slip); the
closed forms of the start of motion (uplift toward side s at |ug| = g tan(alpha_s),
Eq. 2-1 with that side's b_s; slip at |ug| = mu_s g whatever the geometry, Eq. 2-2); the
symmetric planar block (a :class:`Block`) for an AsymmetricBlock with equal sides; the
mirror image; and the impact law's energy bound.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaketable import AsymmetricBlock, Block, Friction, Motion, simulate
from shaketable.core.constants import G
from shaketable.ground.generators import half_sine_pulse, harmonic
from shaketable.models.planar.physics import (
    ROCK,
    SLIDE,
    impact,
    kinetic_energy,
)
from shaketable.models.planar.run import simulate_planar
from shaketable.models.rocking.physics import RHO_MINUS, RHO_PLUS, asymmetric_parameters

BLOCK = AsymmetricBlock.from_angles(0.15, 0.35, 0.5)
AMPLE = Friction(10.0)
IMPACT = 1.0   # the event kind of an impact


def _impacts(result):
    return result.events[result.events[:, 1] == IMPACT][:, 0]


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_free_rocking_with_ample_friction_is_the_asymmetric_rocking_block(side):
    # released low enough not to overturn over the narrow side (alpha+ = 0.15 rad)
    options = dict(cor=0.9, theta0=side * 0.03, duration=1.5, output_dt=0.002)
    planar = simulate_planar(BLOCK, None, friction=AMPLE, **options)
    rocking = simulate(BLOCK, None, method="reference", **options)
    assert planar.modes_visited == ("rock",)
    mine, theirs = _impacts(planar), rocking.impact_times
    assert len(mine) >= 4
    n = min(len(mine), len(theirs))
    np.testing.assert_allclose(mine[:n], theirs[:n], rtol=0, atol=1e-9)
    m = min(planar.t.size, rocking.t.size)
    np.testing.assert_allclose(planar.theta[:m], rocking.theta[:m], rtol=0, atol=1e-9)


def test_a_pulse_with_ample_friction_is_the_asymmetric_rocking_block():
    motion = half_sine_pulse(amplitude=0.2 * G, pulse_duration=0.3, duration=1.5, dt=0.005)
    planar = simulate_planar(BLOCK, motion, cor=0.8, friction=AMPLE)
    rocking = simulate(BLOCK, motion, cor=0.8, method="reference")
    assert "rock" in planar.modes_visited and not planar.overturned
    assert planar.t_start == pytest.approx(rocking.t_start, abs=1e-9)
    mine, theirs = _impacts(planar), rocking.impact_times
    assert len(mine) >= 2
    np.testing.assert_allclose(mine[:len(theirs)], theirs[:len(mine)], rtol=0, atol=1e-9)
    np.testing.assert_allclose(planar.theta, rocking.theta[:planar.t.size], rtol=0, atol=1e-9)


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_uplift_under_a_slow_ramp_at_g_tan_alpha_of_each_side(side):
    # ug = side * a t: rocking toward `side` starts at t = g tan(alpha_side) / a (Eq. 2-1)
    rate = 2.0
    t = np.linspace(0.0, 3.0, 301)
    result = simulate_planar(BLOCK, Motion(t, side * rate * t), cor=0.8, friction=AMPLE,
                             duration=2.5)
    assert result.t_start == pytest.approx(G * math.tan(BLOCK.alpha_of(side)) / rate,
                                           rel=1e-12)
    assert result.events[0, 3] == ROCK and np.sign(result.theta[-1]) == side


@pytest.mark.parametrize("block", [BLOCK, AsymmetricBlock.from_angles(0.35, 0.15, 0.5),
                                   Block(1.0, 0.3)])
@pytest.mark.parametrize("side", [1.0, -1.0])
def test_sliding_starts_at_mu_s_g_whatever_the_asymmetry(block, side):
    # mu_s below both tan(alpha): the block slides when |ug| = mu_s g (Eq. 2-2)
    rate, mu = 2.0, 0.1
    t = np.linspace(0.0, 1.0, 101)
    result = simulate_planar(block, Motion(t, side * rate * t), cor=0.8,
                             friction=Friction(mu, 0.08), duration=0.8)
    assert result.t_start == pytest.approx(mu * G / rate, rel=1e-12)
    assert result.events[0, 3] == SLIDE and result.modes_visited == ("rest", "slide")
    assert np.sign(result.slip[-1]) == -side   # it slides against the table's push


def test_equal_sides_give_the_symmetric_block():
    # an AsymmetricBlock with b+ = b- and the rectangle's inertia is a Block: the general
    # formulas (each pivot's b, I0; Ic = k^2) against the symmetric ones
    block = Block(1.0, 0.2)
    twin = AsymmetricBlock(0.5, 0.1, 0.1)
    motion = harmonic(3.0, horizontal=0.6 * G, duration=2.0, dt=0.005, ramp=0.25)
    options = dict(cor=0.9, friction=Friction(0.25, 0.22))
    plain, general = simulate_planar(block, motion, **options), \
        simulate_planar(twin, motion, **options)
    assert general.modes_visited == plain.modes_visited
    assert "slide-rock" in plain.modes_visited
    assert general.n_impacts == plain.n_impacts
    for name in ("x", "theta", "slip"):
        np.testing.assert_allclose(getattr(general, name), getattr(plain, name), rtol=0,
                                   atol=1e-9)
    assert general.peak_base_slip == pytest.approx(plain.peak_base_slip, abs=1e-9)


def test_the_mirrored_block_under_the_mirrored_motion_mirrors_the_response():
    mirror = AsymmetricBlock(BLOCK.h, BLOCK.b_minus, BLOCK.b_plus)
    motion = harmonic(2.5, horizontal=0.5 * G, duration=2.0, dt=0.005, ramp=0.25)
    flipped = Motion(motion.t, -motion.horizontal)
    options = dict(cor=0.9, friction=Friction(0.3, 0.25))
    one, other = simulate_planar(BLOCK, motion, **options), \
        simulate_planar(mirror, flipped, **options)
    assert {"rock", "slide-rock"} <= set(one.modes_visited)
    assert one.modes_visited == other.modes_visited and one.n_impacts == other.n_impacts
    for name in ("x", "theta", "x_dot", "theta_dot", "slip"):
        np.testing.assert_allclose(getattr(other, name), -getattr(one, name), rtol=0,
                                   atol=1e-9)
    np.testing.assert_allclose(other.y, one.y, rtol=0, atol=1e-12)


def _corner_rate(y_dot, theta, omega, side):
    """Y_s' of the bottom corner of ``side``: y' + r_x theta', r_x = -s b_s cos + h sin."""
    r_x = -side * BLOCK.b_of(side) * math.cos(theta) + BLOCK.h * math.sin(theta)
    return y_dot + r_x * omega


@pytest.mark.parametrize("cor", [0.0, 0.7, 1.0, "housner"])
def test_an_impact_of_either_corner_never_gains_energy_nor_pulls(cor):
    parameters = asymmetric_parameters(BLOCK, cor)
    rng = np.random.default_rng(7)
    tried = 0
    while tried < 400:
        striking = rng.choice([1.0, -1.0])
        # at theta = 0 (the other corner on the table) or tilted onto the other corner
        theta = -striking * rng.uniform(0.0, 0.3) * rng.integers(0, 2)
        x_dot, omega = rng.normal(0.0, 0.5), rng.normal(0.0, 2.0)
        y_dot = rng.normal(0.0, 0.5)
        if not _corner_rate(y_dot, theta, omega, striking) < 0.0:
            continue   # the corner does not strike
        tried += 1
        mu_s = rng.uniform(0.0, 1.5)
        rho = parameters[RHO_PLUS] if striking > 0 else parameters[RHO_MINUS]
        before = kinetic_energy(x_dot, y_dot, omega, parameters)
        x1, y1, w1, mode, _, lost, _ = impact(theta, x_dot, y_dot, omega, striking, rho,
                                              mu_s, mu_s * rng.uniform(0.5, 1.0), parameters)
        if mode < 0:   # Painleve: no impulse
            continue
        assert lost >= -1e-12 * before
        assert kinetic_energy(x1, y1, w1, parameters) <= before * (1 + 1e-12)
        # the struck corner does not enter the table (a plastic normal impact)
        assert _corner_rate(y1, theta, w1, striking) >= -1e-12


def test_a_sticking_rock_to_rock_impact_gives_cor_on_either_pivot():
    # Section 2.7 (5): theta'+ = cor theta'- whatever the pivot (rho_k = cor / c_H,k)
    for side in (1.0, -1.0):
        result = simulate_planar(BLOCK, None, cor=0.7, friction=AMPLE, theta0=side * 0.03,
                                 duration=2.0, output_dt=0.001)
        impacts = result.events[result.events[:, 1] == IMPACT]
        assert len(impacts) >= 2
        # the rate after an impact: the rate before the next one, free rocking conserving
        # the energy on each side, is not needed: the engine's events give theta' before;
        # the next impact's theta'- is cor times this one's on the other pivot (free
        # rocking returns to theta = 0 with the rate it left with)
        ratios = impacts[1:, 4] / impacts[:-1, 4]
        np.testing.assert_allclose(ratios, -0.7, rtol=1e-9)


def test_the_result_of_an_asymmetric_block_has_its_summary_frame_and_figure():
    from shaketable.plots.base import pyplot

    motion = harmonic(2.5, horizontal=0.5 * G, duration=1.0, dt=0.005, ramp=0.25)
    result = simulate(BLOCK, motion, cor=0.9, friction=Friction(0.3, 0.25))
    summary = result.summary()
    assert summary["b_plus [m]"] == BLOCK.b_plus and summary["b_minus [m]"] == BLOCK.b_minus
    assert len(result.to_frame()) == result.t.size
    fig = result.plot()
    try:
        assert "asymmetric" in fig._suptitle.get_text()
    finally:
        pyplot().close(fig)


@pytest.mark.parametrize("block, frequency, amplitude", [
    (BLOCK, 2.5, 0.5), (AsymmetricBlock(0.5, 0.12, 0.3), 3.0, 0.7)])
def test_the_compiled_engine_agrees_with_the_scipy_reference(block, frequency, amplitude):
    # the independent Newton-Euler reference (models/planar/reference.py) with each
    # pivot's arm: runs that visit slide, rock and slide-rock with impacts on both pivots
    from shaketable.models.planar.reference import simulate_reference

    motion = harmonic(frequency, horizontal=amplitude * G, duration=2.0, dt=0.005, ramp=0.25)
    options = dict(cor=0.9, friction=Friction(0.3, 0.25))
    reference, planar = simulate_reference(block, motion, **options), \
        simulate_planar(block, motion, **options)
    assert set(planar.modes_visited) == {"rest", "slide", "rock", "slide-rock"}
    events = planar.events[planar.events[:, 1] != 4.0]   # |theta| = alpha: not an event there
    assert len(events) == len(reference.event_times) > 20
    np.testing.assert_allclose(events[:, 0], reference.event_times, rtol=0, atol=1e-8)
    np.testing.assert_array_equal(events[:, 3], reference.event_mode_after)
    for name in ("peak_slip", "residual_slip", "max_abs_theta", "peak_base_slip"):
        assert getattr(planar, name) == pytest.approx(getattr(reference, name), abs=1e-8)
    np.testing.assert_allclose(planar.theta, reference.theta, rtol=0, atol=1e-8)
    np.testing.assert_allclose(planar.x, reference.x, rtol=0, atol=1e-8)
