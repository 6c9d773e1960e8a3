"""The planar block's impact law beyond the sticking rock-to-rock impact (docs/planar.md,
"Impacts"): a couple from the angular momentum in the striking corner's slip frame, no
pulling impulse, no energy gain; both the compiled law
(:func:`shaketable.models.planar.physics.impact`) and the reference's
(:func:`shaketable.models.planar.contact.impact_map`).

References: invariances of mechanics (a uniform horizontal velocity added to a corner
that slips before and after changes nothing but that velocity: Galilean invariance of a
frictional impact whose slip direction does not change), the energy theorem (a passive
contact never adds kinetic energy; the impulse of a unilateral contact pushes), the
closed form of the frictionless COR 1 impact at theta = 0 (theta'+ = theta'-, derived in
docs/planar.md), and the report's rock-to-rock law, Section 2.7 (5).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaketable import Block
from shaketable.core.constants import INCH
from shaketable.models.planar.contact import PlanarGeometry, impact_map
from shaketable.models.planar.contact import kinetic_energy as reference_energy
from shaketable.models.planar.physics import (
    PAINLEVE,
    corner_vector,
    housner_ratio,
    impact,
    kinetic_energy,
)
from shaketable.models.planar.run import simulate_planar
from shaketable.models.rocking.physics import block_parameters
from shaketable.models.sliding.result import Friction


def _random_state(rng, widest=1.4):
    """A block, a striking corner and a pre-impact state whose corner moves down."""
    block = Block(height=1.0, width=float(rng.uniform(0.05, widest)))
    side = float(rng.choice([-1.0, 1.0]))
    theta = float(side * rng.uniform(0.0, 1.2) * (rng.random() < 0.7))
    x_dot, omega = rng.normal(size=2)
    parameters = block_parameters(block)
    r_x, _ = corner_vector(theta, side, parameters)
    y_dot = -abs(float(rng.normal())) - r_x * omega
    return block, side, theta, float(x_dot), float(y_dot), float(omega)


def _both(block, side, theta, x_dot, y_dot, omega, rho, mu_s, mu_d):
    """(compiled, reference) post-impact velocities; None for Painleve."""
    parameters = block_parameters(block)
    xa, ya, wa, kind, _, _, _ = impact(theta, x_dot, y_dot, omega, side, rho, mu_s, mu_d,
                                       parameters)
    geometry = PlanarGeometry(block)
    r_x, r_y = geometry.arm(int(side), theta)
    state = np.array([0.0, -r_y, theta, x_dot, y_dot, omega])
    velocities, impulse, _, _ = impact_map(geometry, state, int(side), rho, mu_s, mu_d)
    compiled = None if kind == PAINLEVE else np.array([xa, ya, wa])
    return compiled, velocities, impulse


def test_the_impact_map_does_not_depend_on_a_uniform_sliding_speed():
    # a corner that slips the same way before and after (a large slip speed V): adding V
    # before adds V after, nothing else changes. (The law gains no energy in the table's
    # frame either: where that bound is the one that caps, at rho = cor / c_H of tens for
    # B/H near sqrt(2), the map depends on V until friction's loss u mu P_y exceeds the
    # couple's gain; B/H <= 1 here, rho <= 4)
    rng = np.random.default_rng(11)
    checked = 0
    for _ in range(300):
        block, side, theta, x_dot, y_dot, omega = _random_state(rng, widest=1.0)
        rho = float(rng.uniform(0.0, 1.0)) / housner_ratio(block_parameters(block))
        mu_s = float(rng.uniform(0.0, 1.0))
        mu_d = mu_s * float(rng.uniform(0.0, 1.0))
        speed = float(rng.choice([-1.0, 1.0]))
        posts = []
        for extra in (50.0, 100.0):
            compiled, reference, _ = _both(block, side, theta, x_dot + speed * extra, y_dot,
                                           omega, rho, mu_s, mu_d)
            if compiled is None:
                break
            shift = [speed * extra, 0, 0]
            posts.append((compiled - shift, reference - shift))
        if len(posts) < 2:
            continue
        checked += 1
        scale = 1.0 + abs(x_dot) + abs(y_dot) + abs(omega)
        np.testing.assert_allclose(posts[0][0], posts[1][0], rtol=0, atol=1e-12 * 100 * scale)
        np.testing.assert_allclose(posts[0][1], posts[1][1], rtol=0, atol=1e-12 * 100 * scale)
    assert checked > 250


def test_frictionless_impacts_do_not_see_the_sliding_speed():
    # mu = 0: the horizontal velocity is a spectator (any V, either side)
    rng = np.random.default_rng(12)
    for _ in range(300):
        block, side, theta, x_dot, y_dot, omega = _random_state(rng)
        rho = float(rng.uniform(0.0, 1.0)) / housner_ratio(block_parameters(block))
        shift = float(rng.normal()) * 3.0
        a, ra, _ = _both(block, side, theta, x_dot, y_dot, omega, rho, 0.0, 0.0)
        b, rb, _ = _both(block, side, theta, x_dot + shift, y_dot, omega, rho, 0.0, 0.0)
        np.testing.assert_allclose(b - [shift, 0, 0], a, rtol=0, atol=1e-12 * (1 + abs(shift)))
        np.testing.assert_allclose(rb - [shift, 0, 0], ra, rtol=0, atol=1e-12 * (1 + abs(shift)))


def test_an_impact_never_pulls_nor_adds_energy():
    rng = np.random.default_rng(13)
    for _ in range(2000):
        block, side, theta, x_dot, y_dot, omega = _random_state(rng)
        rho = float(rng.uniform(0.0, 1.0)) / housner_ratio(block_parameters(block))
        mu_s = float(rng.uniform(0.0, 1.5))
        mu_d = mu_s * float(rng.uniform(0.0, 1.0))
        compiled, reference, impulse = _both(block, side, theta, x_dot, y_dot, omega, rho,
                                             mu_s, mu_d)
        parameters = block_parameters(block)
        before = kinetic_energy(x_dot, y_dot, omega, parameters)
        geometry = PlanarGeometry(block)
        assert reference_energy(geometry, np.r_[0, 0, 0, reference]) <= before * (1 + 1e-12)
        assert impulse[1] >= -1e-12 * (1 + abs(y_dot))
        if compiled is not None:
            assert kinetic_energy(*compiled, parameters) <= before * (1 + 1e-12)
            assert compiled[1] - y_dot >= -1e-12 * (1 + abs(y_dot))   # P_y = y'+ - y'-


def test_frictionless_cor_1_impact_at_theta_0_is_elastic():
    # the other corner on the table (y' = s b theta' about corner s), any x': the corner
    # frame's momentum about the striking corner -s is (Ic + h^2 - b^2) theta'
    # = c_H I0 theta', and rho = 1 / c_H gives theta'+ = theta'-, y'+ = -y'-
    rng = np.random.default_rng(14)
    for _ in range(500):
        block = Block(height=1.0, width=float(rng.uniform(0.05, 1.4)))
        parameters = block_parameters(block)
        s = float(rng.choice([-1.0, 1.0]))
        omega = -s * abs(float(rng.normal()))     # turning back toward theta = 0
        b = block.width / 2
        x_dot, y_dot = float(rng.normal()), s * b * omega
        compiled, reference, _ = _both(block, -s, 0.0, x_dot, y_dot, omega,
                                       1.0 / housner_ratio(parameters), 0.0, 0.0)
        before = kinetic_energy(x_dot, y_dot, omega, parameters)
        for post in (compiled, reference):
            np.testing.assert_allclose(post, [x_dot, -y_dot, omega], rtol=1e-12, atol=1e-14)
            assert kinetic_energy(*post, parameters) == pytest.approx(before, rel=1e-12)


def test_frictionless_cor_1_run_loses_nothing():
    # a whole run: the 30 x 6 in block released at 0.1 rad on a frictionless table
    # slide-rocks from impact to impact; every impact is elastic
    result = simulate_planar(Block.from_inches(30, 6), None, cor=1.0, friction=Friction(0.0),
                             theta0=0.1, duration=2.0)
    assert result.n_impacts >= 3 and result.status == "completed"
    assert abs(result.impact_loss) <= 1e-12 * result.energy_start
    assert result.capped_impacts == 0


def test_sticking_rock_to_rock_impact_is_the_report_law_to_the_bit():
    # Section 2.7 (5): theta'+ = rho H_k / I0 with H_k = c_H I0 theta' (cor theta'- up to
    # rounding), evaluated in the order the law always used: unchanged bit for bit
    rng = np.random.default_rng(15)
    for _ in range(200):
        block = Block(height=1.0, width=float(rng.uniform(0.05, 1.4)))
        parameters = block_parameters(block)
        s = float(rng.choice([-1.0, 1.0]))
        omega = -s * abs(float(rng.normal()))
        r_x, r_y = corner_vector(0.0, s, parameters)
        x_dot, y_dot = r_y * omega, -r_x * omega
        cor = float(rng.uniform(0.0, 1.0))
        rho = cor / housner_ratio(parameters)
        xa, ya, wa, kind, sigma, _, capped = impact(0.0, x_dot, y_dot, omega, -s, rho, 1e4,
                                                    1e4, parameters)
        k_x, k_y = corner_vector(0.0, -s, parameters)
        momentum = 0.25 * parameters[2] * omega - k_x * y_dot + k_y * x_dot
        assert sigma == 0.0 and wa == rho * momentum / parameters[2]
        assert wa == pytest.approx(cor * omega, rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("aspect", [1.1, 1.2, 1.3, 1.4])
def test_squat_blocks_rocking_freely_complete(aspect):
    # B/H 1.1-1.4 released at 0.3 alpha: a slipping impact at theta = 0 turned the block
    # back onto the corner that was on the table, whose impact turned it back again, 1000
    # times at one instant (status "inconsistent"). With both corners on the table the
    # two-corner problem now decides, once
    block = Block(height=1.0, width=aspect)
    for cor in (0.5, 0.9, 1.0):
        for mu in (0.3, 0.5):
            result = simulate_planar(block, None, cor=cor, friction=Friction(mu),
                                     theta0=0.3 * block.alpha, duration=10.0)
            assert result.status == "completed", (cor, mu, result.status)
            assert result.t[-1] == 10.0


@pytest.mark.parametrize("aspect, mu", [(0.2, 10.0), (1.2, 10.0), (1.2, 0.3)])
def test_cor_0_rests_at_the_first_impact_as_the_rocking_model(aspect, mu):
    # reference: the rocking model (cor 0: the first impact is plastic, theta' = 0, rest)
    # for ample friction; with mu < B/H the block slide-rocks and must rest too
    block = Block(height=1.0, width=aspect)
    planar = simulate_planar(block, None, cor=0.0, friction=Friction(mu),
                             theta0=0.3 * block.alpha, duration=5.0)
    assert planar.status == "completed" and math.isfinite(planar.t_rest)
    assert planar.mode[-1] == 0   # rest
    if mu == 10.0:
        from shaketable.models.api import simulate
        rocking = simulate(block, None, cor=0.0, theta0=0.3 * block.alpha, duration=5.0)
        assert planar.t_rest == pytest.approx(rocking.t_rest, abs=1e-12)


def test_the_chatter_case_runs_to_its_end():
    # docs/planar.md: the 30 x 6 in block at mu = 0.2 (one rounding step above B/H) under
    # Pacoima S16E x 0.5 at COR 1 turned from corner to corner 7 ns apart with
    # |theta'| 1.2e-8 rad/s and stopped (status "chatter") after 2.9 s of 41.7 s. Impacts
    # without decay closer together than the rest tolerance are a block at rest
    from shaketable.ground import records

    motion = records.load("pacoima-dam-s16e").scaled(0.5)
    result = simulate_planar(Block(30 * INCH, 6 * INCH), motion, cor=1.0,
                             friction=Friction(0.2))
    assert result.status == "completed" and result.t[-1] == motion.t[-1]


def test_the_base_slip_is_the_slide_alone():
    # a block that rocks on corners that never slip (mu 10, free rocking): the pivot stays
    # where it stood, so the base slid 0 (to rounding); the midpoint, turning about the
    # pivot b away, moved b (1 - cos(theta)), largest at the release angle. A block that
    # cannot rock (B/H = 4) only slides: both are the sliding model's slip
    block = Block.from_inches(30, 6)
    rocking = simulate_planar(block, None, cor=0.9, friction=Friction(10.0), theta0=0.15,
                              duration=3.0)
    theta = 0.15
    assert rocking.peak_slip == pytest.approx(block.width / 2 * (1 - math.cos(theta)),
                                              rel=1e-12)
    assert rocking.peak_base_slip < 1e-15
    from shaketable.ground.generators import harmonic
    from shaketable.models.sliding.engine import slide

    motion = harmonic(2.0, horizontal=0.5 * 9.80665, duration=2.0, dt=0.01)
    sliding = simulate_planar(Block(height=0.5, width=2.0), motion, cor=0.9,
                              friction=Friction(0.3))
    expected = slide(motion, Friction(0.3)).peak_slip
    assert sliding.peak_base_slip == pytest.approx(expected, rel=1e-9)
    assert sliding.peak_slip == pytest.approx(expected, rel=1e-9)
    assert "no bouncing" in rocking.summary()["model limits"]


def test_cor_1_rock_to_rock_impacts_are_not_counted_as_capped():
    # a COR 1 rock-to-rock impact keeps the energy exactly (Section 2.7 (5): theta'+ =
    # theta'-); the law's last bits may still exceed it by an ulp, which the cap holds but
    # does not count (7 of 21 impacts of this run were counted before)
    result = simulate_planar(Block.from_inches(30, 6), None, cor=1.0, friction=Friction(10.0),
                             theta0=0.15, duration=20.0)
    assert result.n_impacts >= 20 and result.capped_impacts == 0
