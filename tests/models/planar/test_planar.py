"""The planar block: rest, slide, rock, slide-rock and flight in one model.

Where each expected number comes from is said at each test: the rocking engine
(``simulate`` without friction, an independent integrator: RKN 6(4) against DOP853),
the exact stick-slip model (``models.sliding.engine.slide``, closed-form cubic pieces), closed
forms written here (ballistic flight, Eq. 2-13's impact ratio, Housner's ratio), and
invariances (mirror images, dimensional similarity, energy balance).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from shaketable import Block
from shaketable.core.constants import INCH, G
from shaketable.core.geometry import PrestressRods
from shaketable.core.motion import Motion
from shaketable.ground import generators, records
from shaketable.models.api import simulate
from shaketable.models.planar.modes import enter_contact
from shaketable.models.planar.physics import (
    FLIGHT,
    ROCK,
    SLIDE_ROCK,
    corner_vector,
    housner_ratio,
    impact,
    kinetic_energy,
    rock_forces,
    slide_rock_accelerations,
)
from shaketable.models.rocking.physics import block_parameters
from shaketable.models.sliding.engine import slide
from shaketable.models.sliding.result import Friction
from shaketable.studies.sliding import TABLE_4_4_COLUMNS, TABLE_4_4_FRICTIONS, table_4_4_motion

FOOT = 12 * INCH
AMPLE = Friction(10.0, 10.0)


@pytest.fixture(scope="module")
def pacoima():
    return records.load("pacoima-dam-s16e")


def fig_3_7_motion():
    # experiments/fig-3-7.toml, [motion]: harmonic 2 Hz, 0.5 g, half-cycle ramp 0.25 s,
    # 10.125 s at 0.01 s; [rocking] cor = 0.925; [block] 30 x 6 in
    return generators.harmonic(2.0, horizontal=0.5 * G, duration=10.125, dt=0.01, ramp=0.25)


def _friction_need(block, rocking):
    """|F| / N the rocking solution needs at its samples (inf where N <= 0)."""
    parameters = block_parameters(block)
    ug, vg = rocking.motion.at(rocking.t)
    need = []
    for theta, omega, u, v in zip(rocking.theta, rocking.theta_dot, ug, vg):
        side = 1.0 if theta > 0 else -1.0
        _, _, _, friction, normal = rock_forces(theta, omega, side, u, v, parameters)
        need.append(abs(friction) / normal if normal > 0 else math.inf)
    return np.array(need)


# ------------------------------------------------------------------ (a) rocking limit
@pytest.mark.parametrize("case", ["pacoima", "fig-3-7"])
def test_rocking_limit_equals_the_rocking_engine_until_the_rocking_model_needs_more_friction(
        case, pacoima):
    # reference: today's rocking engine (RKN 6(4), rtol 1e-11) on the same input; the
    # coupled model integrates Eq. (2-13) with DOP853 at rtol 1e-12, so only the
    # integration errors (~1e-12) separate them while the block rocks
    if case == "pacoima":
        block, motion, cor = Block(height=16 * FOOT, width=4 * FOOT), pacoima, 0.95
    else:
        block, motion, cor = Block(height=30 * INCH, width=6 * INCH), fig_3_7_motion(), 0.925
    rocking = simulate(block, motion, cor=cor)
    coupled = simulate(block, motion, cor=cor, friction=AMPLE)
    assert rocking.status == coupled.status == "overturned"
    assert coupled.n_impacts == rocking.n_impacts and rocking.n_impacts >= 1
    np.testing.assert_allclose(coupled.impact_times, rocking.impact_times, rtol=0, atol=1e-9)
    assert coupled.t_start == pytest.approx(rocking.t_start, abs=1e-9)
    assert coupled.t_unstable == pytest.approx(rocking.t_unstable, abs=1e-9)
    # both overturned: max theta/alpha is the report's "F" (NaN) for both
    assert math.isnan(coupled.max_theta_ratio) and math.isnan(rocking.max_theta_ratio)
    # the two part only where the rocking solution itself needs |F| > 10 N (the falling
    # block's normal force goes to zero): the coupled model then slide-rocks
    left_rock = coupled.events[(coupled.events[:, 2] == ROCK) & (coupled.events[:, 3]
                                                                 == SLIDE_ROCK), 0]
    assert left_rock.size and left_rock[0] > max(rocking.impact_times[-1], rocking.t_unstable)
    need = _friction_need(block, rocking)
    assert np.all(need[rocking.t < rocking.t_unstable] < 10.0)
    assert np.any(need > 10.0)
    assert coupled.t_overturn == pytest.approx(rocking.t_overturn, abs=5e-3)


def test_free_rocking_limit_with_its_cascade():
    # reference: the rocking engine (free rocking, cor 0.8, 20 s: the impacts die out in a
    # cascade summed in closed form by both)
    block = Block(height=1.0, width=0.2)
    rocking = simulate(block, None, cor=0.8, theta0=0.15, duration=20.0)
    coupled = simulate(block, None, cor=0.8, theta0=0.15, duration=20.0, friction=AMPLE)
    assert rocking.cascades == 1 and coupled.cascades == 1
    assert coupled.n_impacts == rocking.n_impacts
    np.testing.assert_allclose(coupled.impact_times, rocking.impact_times, rtol=0, atol=1e-9)
    assert coupled.t_rest == pytest.approx(rocking.t_rest, abs=1e-9)
    assert coupled.max_theta_ratio == pytest.approx(rocking.max_theta_ratio, abs=1e-9)
    np.testing.assert_allclose(coupled.theta, rocking.theta, rtol=0, atol=1e-9)
    assert coupled.modes_visited == ("rest", "rock") and coupled.verdict() == "rocked"


def test_a_plastic_impact_rests_and_rocks_again_as_in_the_rocking_engine():
    # reference: the rocking engine (cor = 0: every impact plastic). The table tips the
    # block back onto the striking corner at some impacts; the planar engine summed an
    # infinite cascade there and froze the block for the rest of the run (t_rest = inf,
    # 1 impact), where the block rests at once and rocks again (9 impacts).
    block = Block(height=1e3, width=100.0)
    motion = generators.harmonic(2.0, horizontal=0.5 * G, duration=4.0)
    rocking = simulate(block, motion, cor=0.0)
    coupled = simulate(block, motion, cor=0.0, friction=AMPLE)
    assert rocking.n_impacts == coupled.n_impacts == 9
    np.testing.assert_allclose(coupled.impact_times, rocking.impact_times, rtol=0, atol=1e-9)
    assert math.isfinite(coupled.t_rest)
    assert coupled.t_rest == pytest.approx(rocking.t_rest, abs=1e-9)
    assert coupled.max_abs_theta == pytest.approx(rocking.max_abs_theta, rel=1e-9)


# ------------------------------------------------------------------ (b) sliding limit
@pytest.mark.parametrize("column", list(TABLE_4_4_COLUMNS))
def test_sliding_limit_equals_slide_on_the_table_4_4_records(column):
    # reference: models.sliding.engine.slide (exact cubic pieces). A block with B/H = 4 cannot
    # rock: rocking needs |ug| > 4 (g + vg), sliding starts at mu <= 0.3
    block = Block(height=0.5, width=2.0)
    motion = table_4_4_motion(column)
    for mu_s, mu_d in [(mu, mu) for mu in TABLE_4_4_FRICTIONS] + [(0.3, 0.2)]:
        expected = slide(motion, Friction(mu_s, mu_d))
        result = simulate(block, motion, cor=0.9, friction=Friction(mu_s, mu_d))
        assert set(result.modes_visited) <= {"rest", "slide"}
        assert result.peak_slip == pytest.approx(expected.peak_slip, abs=1e-9)
        assert result.residual_slip == pytest.approx(expected.residual_slip, abs=1e-9)
        np.testing.assert_allclose(result.slip, expected.x, rtol=0, atol=1e-9)
        assert result.time_in_mode["slide"] == pytest.approx(expected.time_sliding, abs=1e-9)
        assert result.verdict() == ("slid" if expected.time_sliding > 0 else "stayed")


# ------------------------------------------------------------------ (c) free flight
def _lift_motion(depth=2.0, ramp=0.1, dt=0.005, duration=1.0):
    """Vertical table acceleration 0 -> -depth g -> 0 (linear ramps), then at rest."""
    t = np.arange(0.0, duration + dt / 2, dt)
    vertical = -depth * G * np.clip(1.0 - np.abs(t - ramp) / ramp, 0.0, None)
    return Motion(t, np.zeros_like(t), vertical, name="lift")


def _height_gain(t, motion):
    """y(t) - y(t_lift) of a block in flight from rest at t_lift with zero velocity:
    the double integral of -(g + vg), vg piecewise linear (exact, by sample pieces)."""
    times, vertical = motion.t, motion.vertical
    t_lift = brentq(lambda s: G + np.interp(s, times, vertical), 0.0, 0.1)
    knots = np.concatenate([[t_lift], times[(times > t_lift) & (times < t)], [t]])
    y = v = 0.0
    for a, b in zip(knots[:-1], knots[1:]):
        span = b - a
        f0 = -(G + np.interp(a, times, vertical))
        slope = (-(G + np.interp(b, times, vertical)) - f0) / span
        y += v * span + f0 * span ** 2 / 2 + slope * span ** 3 / 6
        v += f0 * span + slope * span ** 2 / 2
    return y, v, t_lift


def test_a_block_lifted_flat_flies_on_the_ballistic_path_and_lands_flat():
    # reference: the closed form above (double integral of the piecewise-linear table
    # acceleration), landing where it returns to zero height gain (brentq)
    block = Block(height=0.4, width=0.2)
    motion = _lift_motion()
    result = simulate(block, motion, cor=0.9, friction=Friction(0.5, 0.4))
    landing = brentq(lambda s: _height_gain(s, motion)[0], 0.12, 0.9)
    _, v_landing, t_lift = _height_gain(landing, motion)
    assert result.t_start == pytest.approx(t_lift, abs=1e-12)
    events = result.events_frame()
    flat = events[events["event"] == "flat landing"]
    assert len(flat) == 1
    assert flat["time [s]"].iloc[0] == pytest.approx(landing, abs=1e-10)
    assert flat["mode after"].iloc[0] == "rest"
    flying = (result.t > t_lift) & (result.t < landing)
    expected = np.array([_height_gain(s, motion)[0] for s in result.t[flying]])
    np.testing.assert_allclose(result.y[flying] - block.height / 2, expected, rtol=0, atol=1e-12)
    assert np.all(result.theta == 0.0)
    assert result.impact_loss == pytest.approx(0.5 * v_landing ** 2, rel=1e-9)
    assert result.verdict() == "flew"
    assert result.time_in_mode["flight"] == pytest.approx(landing - t_lift, abs=1e-10)


def test_a_sliding_block_lifted_just_before_a_sample_flies_and_lands_flat():
    # g + vg reaches 0 while the block slides, 5 us before a sample (the case of
    # tests/models/planar/test_planar_agreement.py "fuzz8 14", which stopped with status
    # "chatter": the first flight piece, 0.6 us long, rose by less than half an ulp of y,
    # and a gap of exactly 0 was taken for a landing). Reference: the closed form of
    # _height_gain, landing where it returns to zero (brentq); no flight before t_lift.
    block = Block(height=0.4, width=0.5)   # B/H 1.25 > mu_d: sliding never tips it
    ramp = 0.1
    motion = _lift_motion(depth=ramp / (0.05 - 5e-6), ramp=ramp)
    motion = Motion(motion.t, np.full_like(motion.t, 0.6 * G), motion.vertical, name="lift")
    result = simulate(block, motion, cor=0.9, friction=Friction(0.3, 0.25))
    assert result.status == "completed"
    landing = brentq(lambda s: _height_gain(s, motion)[0], 0.06, 0.9)
    _, _, t_lift = _height_gain(landing, motion)
    events = result.events_frame()
    assert list(zip(events["mode before"], events["mode after"])) == [
        ("rest", "slide"), ("slide", "flight"), ("flight", "slide")]
    assert events["time [s]"].iloc[1] == pytest.approx(t_lift, abs=1e-12)
    assert events["event"].iloc[2] == "flat landing"
    assert events["time [s]"].iloc[2] == pytest.approx(landing, abs=1e-10)
    flying = (result.t > t_lift) & (result.t < landing)
    expected = np.array([_height_gain(s, motion)[0] for s in result.t[flying]])
    np.testing.assert_allclose(result.y[flying] - block.height / 2, expected, rtol=0, atol=1e-12)
    assert np.all(result.theta == 0.0)


def test_a_rocking_block_thrown_off_flies_with_constant_rate_and_lands_on_its_corner():
    # the table drops at 2 g from t = 0 (constant for 0.3 s): a block released tilted and
    # rotating has N < 0 at once and flies: theta linear, the centre on a parabola relative
    # to the table (closed form here), landing where the lower corner reaches the table
    block = Block(height=0.6, width=0.2)
    theta0, omega0 = 0.05, 0.4
    t = np.arange(0.0, 1.5001, 0.01)
    vertical = np.where(t <= 0.3, -2.0 * G, 0.0)
    vertical[31] = 0.0   # 0.31 s: the table stops accelerating (a ramp of 0.01 s)
    motion = Motion(t, np.zeros_like(t), vertical, name="drop")
    result = simulate(block, motion, cor=0.9, theta0=theta0, theta_dot0=omega0,
                      friction=Friction(0.8, 0.8))
    b, h = block.width / 2, block.height / 2
    parameters = block_parameters(block)
    r_x, r_y = corner_vector(theta0, 1.0, parameters)
    y0, ydot0 = -r_y, -r_x * omega0          # the corner at -x on the table at t = 0

    def height(s):  # centre height: y'' = -(g + vg) = +g until 0.3 s, ramp, then -g
        y, v = y0 + ydot0 * 0.3 + G * 0.3 ** 2 / 2, ydot0 + G * 0.3
        if s <= 0.3:
            return y0 + ydot0 * s + G * s ** 2 / 2
        f0, f1 = G, -G
        if s <= 0.31:
            d = s - 0.3
            return y + v * d + f0 * d ** 2 / 2 + (f1 - f0) / 0.01 * d ** 3 / 6
        y += v * 0.01 + f0 * 0.01 ** 2 / 2 + (f1 - f0) / 0.01 * 0.01 ** 3 / 6
        v += f0 * 0.01 + (f1 - f0) / 0.01 * 0.01 ** 2 / 2
        d = s - 0.31
        return y + v * d + f1 * d ** 2 / 2

    def lowest(s):
        theta = theta0 + omega0 * s
        return min(height(s) - b * math.sin(theta) - h * math.cos(theta),
                   height(s) + b * math.sin(theta) - h * math.cos(theta))

    landing = brentq(lowest, 0.5, 1.5)
    impacts = result.impact_times
    assert impacts[0] == pytest.approx(landing, abs=1e-10)
    first = result.events_frame().iloc[0]
    assert (first["mode before"], first["mode after"]) == ("rock", "flight")
    assert result.events[0, 0] == 0.0
    flying = result.t < landing
    np.testing.assert_allclose(result.theta[flying], theta0 + omega0 * result.t[flying],
                               rtol=0, atol=1e-13)
    np.testing.assert_allclose(result.y[flying], [height(s) for s in result.t[flying]],
                               rtol=0, atol=1e-12)


def test_overturning_is_checked_in_flight():
    # thrown off fast enough, theta reaches pi/2 in the air: at (pi/2 - theta0)/omega0
    block = Block(height=0.6, width=0.2)
    t = np.arange(0.0, 2.0001, 0.01)
    motion = Motion(t, np.zeros_like(t), np.full_like(t, -2.0 * G), name="falling table")
    result = simulate(block, motion, cor=0.9, theta0=0.05, theta_dot0=3.0,
                      friction=Friction(0.8, 0.8))
    assert result.status == "overturned" and result.verdict() == "overturned"
    assert result.t_overturn == pytest.approx((math.pi / 2 - 0.05) / 3.0, abs=1e-12)
    assert result.overturn_direction == 1


# ------------------------------------------------------------------ (d) energy
def test_energy_balance_over_a_pacoima_run_that_slide_rocks(pacoima):
    # E_end - E_0 = W_table + W_friction - impact losses (all accumulated by the engine)
    block = Block(height=16 * FOOT, width=4 * FOOT)
    result = simulate(block, pacoima, cor=0.95, friction=Friction(0.3, 0.25))
    assert {"rock", "slide-rock"} <= set(result.modes_visited)
    assert result.impact_loss > 0.0 and result.work_friction < 0.0
    assert abs(result.energy_residual) <= 1e-9 * result.energy_start


def test_frictionless_sliding_and_flight_lose_nothing():
    # mu = 0 and no impact (a stocky block that slides and is lifted flat, COR 1): the
    # energy changes by exactly the table's work
    block = Block(height=0.2, width=0.8)
    t = np.arange(0.0, 1.0001, 0.005)
    horizontal = 0.3 * G * np.sin(2 * np.pi * 2 * t)
    vertical = -1.5 * G * np.clip(1.0 - np.abs(t - 0.3) / 0.2, 0.0, None)
    motion = Motion(t, horizontal, vertical, name="slide and jump")
    result = simulate(block, motion, cor=1.0, friction=Friction(0.0, 0.0))
    assert set(result.modes_visited) == {"rest", "slide", "flight"}
    assert result.work_friction == 0.0
    landing = result.events_frame()["event"] == "flat landing"
    assert landing.sum() == 1
    # the flat landing is plastic in the normal direction (the model text): its loss is
    # exactly the normal kinetic energy; nothing else is lost
    assert abs(result.energy_end - result.energy_start - result.work_table
               + result.impact_loss) <= 1e-12 * result.energy_start


# ------------------------------------------------------------------ (e) symmetry
def test_mirrored_input_gives_mirrored_response(pacoima):
    block = Block(height=8 * FOOT, width=4 * FOOT)
    mirrored = Motion(pacoima.t, -pacoima.horizontal, pacoima.vertical, name="mirror")
    a = simulate(block, pacoima, cor=0.9, friction=Friction(0.6, 0.5))
    b = simulate(block, mirrored, cor=0.9, friction=Friction(0.6, 0.5))
    assert "slide-rock" in a.modes_visited
    np.testing.assert_allclose(b.theta, -a.theta, rtol=0, atol=1e-9)
    np.testing.assert_allclose(b.slip, -a.slip, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(b.mode, a.mode)


def test_dimensional_similarity():
    # lengths x k, time x sqrt(k), accelerations unchanged: theta(t sqrt(k)) the same,
    # lengths (slip) x k
    k = 4.0
    small = Block(height=1.0, width=0.3)
    large = Block(height=k * 1.0, width=k * 0.3)
    t = np.arange(0.0, 4.0001, 0.01)
    horizontal = 0.45 * G * np.sin(2 * np.pi * 1.5 * t) * np.minimum(t / 0.5, 1.0)
    vertical = 0.3 * G * np.cos(2 * np.pi * 1.5 * t)
    a = simulate(small, Motion(t, horizontal, vertical), cor=0.9, friction=Friction(0.35, 0.3))
    b = simulate(large, Motion(t * math.sqrt(k), horizontal, vertical), cor=0.9,
                 friction=Friction(0.35, 0.3))
    assert {"rock", "slide-rock", "slide"} & set(a.modes_visited)
    np.testing.assert_allclose(b.theta, a.theta, rtol=0, atol=1e-8)
    np.testing.assert_allclose(b.slip, k * a.slip, rtol=0, atol=1e-8)
    assert b.n_impacts == a.n_impacts


# ------------------------------------------------------------------ (f) the impact law
def test_impact_reduces_to_the_report_cor_and_to_housner_with_ample_friction():
    block = Block(height=1.0, width=0.25)
    parameters = block_parameters(block)
    c_h = housner_ratio(parameters)
    assert c_h == pytest.approx(1 - 1.5 * math.sin(block.alpha) ** 2, rel=1e-15)
    r_x, r_y = corner_vector(0.0, 1.0, parameters)
    omega = -0.7   # rocking on the corner at -x, falling back: the +x corner strikes
    x_dot, y_dot = r_y * omega, -r_x * omega
    for rho, expected in ((0.9 / c_h, 0.9), (1.0, c_h)):  # cor 0.9; Housner
        _, y_after, omega_after, kind, _, lost, capped = impact(
            0.0, x_dot, y_dot, omega, -1.0, rho, 10.0, 10.0, parameters)
        assert kind == ROCK and capped == 0.0
        assert omega_after == pytest.approx(expected * omega, rel=1e-14)  # Section 2.7 (5)
        assert lost == pytest.approx(0.5 * parameters[2] * omega ** 2 * (1 - expected ** 2),
                                     rel=1e-12)


@pytest.mark.parametrize("omega", [0.2, 0.5])
def test_a_corner_that_cannot_be_held_flies_only_if_it_leaves_the_table_by_itself(omega):
    # docs/planar.md, "Entering a contact": a corner on the table (theta = 0, Y' = 0)
    # whose ROCK forces need N < 0 flies if its free vertical acceleration
    # -(g + vg) + h theta'^2 (r_y = -h at theta = 0, written here) is >= 0, else it
    # slide-rocks with N > 0. g + vg = 0.05 m/s^2, h = 0.5 m: omega 0.2 -> -0.03 (slips),
    # omega 0.5 -> +0.075 (flies).
    block = Block(height=1.0, width=0.8)
    parameters = block_parameters(block)
    ug, vg = -5.0, -G + 0.05
    b, h = block.width / 2, block.height / 2
    q = np.array([b, h, 0.0, -h * omega, b * omega, omega])   # about the corner at -x
    segment = np.array([0.0, 0.01, ug, 0.0, vg, 0.0])
    assert rock_forces(0.0, omega, 1.0, ug, vg, parameters)[4] < 0.0
    mode, sigma = enter_contact(ROCK, 1.0, 0.0, 0.0, q, segment, 0.5, 0.5, parameters)
    free = -(G + vg) + h * omega ** 2
    if free < 0.0:
        assert mode == SLIDE_ROCK
        assert slide_rock_accelerations(0.0, omega, 1.0, sigma, 0.5, ug, vg,
                                        parameters)[3] > 0.0
    else:
        assert mode == FLIGHT


def test_impact_never_adds_energy_and_is_plastic():
    rng = np.random.default_rng(7)
    for _ in range(2000):
        # B/H up to 1.4 (c_H > 0: rho = cor / c_H defined); B/H > sqrt(2): see below
        block = Block(height=1.0, width=float(rng.uniform(0.05, 1.4)))
        parameters = block_parameters(block)
        side = float(rng.choice([-1.0, 1.0]))
        theta = float(side * rng.uniform(0.0, 1.2) * (rng.random() < 0.7))
        x_dot, omega = rng.normal(size=2)
        r_x, _ = corner_vector(theta, side, parameters)
        y_dot = -abs(rng.normal()) - r_x * omega   # corner velocity Y' < 0
        mu_s = float(rng.uniform(0.0, 1.5))
        mu_d = float(rng.uniform(0.0, mu_s))
        rho = float(rng.uniform(0.0, 1.0 / housner_ratio(parameters)))
        xa, ya, wa, kind, _, lost, _ = impact(theta, x_dot, y_dot, omega, side, rho, mu_s,
                                              mu_d, parameters)
        if kind < 0:  # Painleve: refused, not resolved
            continue
        before = kinetic_energy(x_dot, y_dot, omega, parameters)
        assert kinetic_energy(xa, ya, wa, parameters) <= before * (1 + 1e-12)
        assert lost >= -1e-12 * before
        assert abs(ya + r_x * wa) <= 1e-12 * (1 + abs(y_dot) + abs(omega))  # Y'+ = 0


# ------------------------------------------------------------------ (g) bad input
def test_bad_friction_and_options_are_refused_by_name(pacoima):
    block = Block(height=1.0, width=0.25)
    with pytest.raises(ValueError, match="mu_d"):
        Friction(0.3, 0.5)
    with pytest.raises(ValueError, match="mu_s"):
        Friction(-0.1)
    with pytest.raises(ValueError, match="mu_s"):
        Friction(float("nan"))
    with pytest.raises(ValueError, match="friction"):
        simulate(block, pacoima, cor=0.9, friction=0.3)
    rods = Block(height=1.0, width=0.25, rods=PrestressRods(stiffness=1.0, force=0.1,
                                                             edge_distance=0.05))
    with pytest.raises(ValueError, match="rods"):
        simulate(rods, pacoima, cor=0.9, friction=AMPLE)
    with pytest.raises(ValueError, match="cor"):
        simulate(block, pacoima, cor="elastic", friction=AMPLE)
    with pytest.raises(ValueError, match="cor"):
        simulate(block, pacoima, cor=1.5, friction=AMPLE)
    with pytest.raises(ValueError, match="method"):
        simulate(block, pacoima, cor=0.9, friction=AMPLE, method="linear")
    with pytest.raises(ValueError, match="top_force"):
        simulate(block, pacoima, cor=0.9, friction=AMPLE, top_force=0.1)


def test_without_friction_simulate_is_unchanged(pacoima):
    # the keyword's default runs the rocking engine as before (its result type)
    block = Block(height=16 * FOOT, width=4 * FOOT)
    assert type(simulate(block, pacoima, cor=0.95)).__name__ == "RockingResult"
    assert type(simulate(block, pacoima, cor=0.95, friction=None)).__name__ == "RockingResult"


# ------------------------------------------------------------------ (h) extreme cases
@pytest.mark.parametrize("height,width", [(4e-3, 1e-3), (1000.0, 100.0), (10.0, 0.1),
                                          (0.05, 1.0)])
def test_extreme_blocks_run_to_a_status_without_nan(height, width, pacoima):
    block = Block(height=height, width=width)
    result = simulate(block, pacoima, cor=0.9, friction=Friction(0.5, 0.4))
    assert result.status in ("completed", "overturned")
    for values in (result.x, result.y, result.theta, result.slip, result.theta_dot):
        assert np.all(np.isfinite(values))
    assert abs(result.energy_residual) <= 1e-9 * result.energy_start


def test_near_threshold_shaking_starts_exactly_at_the_threshold():
    # |ug| = 1.000001 tan(alpha) g at the top of a slow sine: rocking starts where the
    # margin of Eq. (2-1) crosses zero (located like the rocking engine), the same instant
    block = Block(height=1.0, width=0.25)
    t = np.arange(0.0, 2.0001, 0.01)
    horizontal = 1.000001 * 0.25 * G * np.sin(np.pi * t / 2.0)
    motion = Motion(t, horizontal, name="threshold")
    rocking = simulate(block, motion, cor=0.9)
    coupled = simulate(block, motion, cor=0.9, friction=AMPLE)
    assert coupled.t_start == rocking.t_start
    assert coupled.max_abs_theta == pytest.approx(rocking.max_abs_theta, abs=1e-12)


# ------------------------------------------------------------------ result and figure
def test_result_frame_summary_and_figure(pacoima):
    block = Block(height=8 * FOOT, width=4 * FOOT)
    result = simulate(block, pacoima, cor=0.9, friction=Friction(0.6, 0.5))
    frame = result.to_frame()
    for column in ("time [s]", "x [m]", "y [m]", "theta [rad]", "slip [m]", "x_dot [m/s]",
                   "theta_dot [rad/s]", "mode"):
        assert column in frame.columns
    assert set(frame["mode"]) <= {"rest", "slide", "rock", "slide-rock", "flight"}
    summary = result.summary()
    for key in ("verdict", "peak slip [m]", "residual slip [m]", "peak corner excursion [m]",
                "max_theta_ratio [-]", "time slide-rock [s]", "impact losses [J/kg]",
                "work of friction [J/kg]", "energy residual [J/kg]", "overturned"):
        assert key in summary
    assert summary["verdict"] == "slide-rocked"
    # time in the modes adds up to the run's length
    assert sum(result.time_in_mode.values()) == pytest.approx(result.t[-1] - result.t[0],
                                                               abs=1e-9)
    from shaketable.plots.planar import mode_spans

    spans = mode_spans(result)
    assert spans[0][0] == result.t[0] and spans[-1][1] == result.t[-1]
    assert sum(stop - start for start, stop, code in spans if code == SLIDE_ROCK) \
        == pytest.approx(result.time_in_mode["slide-rock"], abs=1e-9)
    fig = result.plot(title="test")
    assert len(fig.axes) == 6   # two ground panels, theta', theta, slip, mode band


# ------------------------------------------------------------------ the batch
def test_the_batch_equals_single_runs(pacoima):
    # reference: simulate(..., friction=) run by run (same engine, full output arrays)
    from shaketable.models.planar.batch import simulate_many_planar

    blocks = [Block(height=16 * FOOT, width=4 * FOOT), Block(height=0.5, width=2.0)]
    frictions = [Friction(0.3, 0.25), Friction(0.6, 0.5)]
    frame = simulate_many_planar(blocks, pacoima, frictions, [0.9])
    assert len(frame) == 4
    for row, (block, friction) in zip(frame.itertuples(index=False),
                                      [(b, f) for b in blocks for f in frictions]):
        single = simulate(block, pacoima, cor=0.9, friction=friction).summary()
        assert row.verdict == single["verdict"] and row.status == single["status"]
        assert row[frame.columns.get_loc("peak slip [m]")] == single["peak slip [m]"]
        assert row[frame.columns.get_loc("residual slip [m]")] == single["residual slip [m]"]
        assert row.n_impacts == single["n_impacts"]
