"""The stack's equations, contact forces and impact law against independent statements."""

import math

import numpy as np
import pytest

from shaketable.models.stack.impact import cor_impact, plastic_impact
from shaketable.models.stack.physics import Chain, energy
from tests.models.stack.one_body import assert_every_pattern_is_newton_euler, rigid_pair


@pytest.mark.parametrize("n", [1, 2, 3])
def test_reduced_lagrange_equations_equal_newton_euler_in_every_pattern(n):
    # the reduced M(q) q'' = f of each pattern against the full-coordinate Newton-Euler
    # equations with the contact forces as unknowns (models/stack/reference.py): random
    # geometry, state and table accelerations, every pattern of n blocks
    rng = np.random.default_rng(n)
    b = np.sort(rng.uniform(0.1, 0.5, n))[::-1]
    h, m = rng.uniform(0.2, 1.5, n), rng.uniform(0.5, 3.0, n)
    assert_every_pattern_is_newton_euler(rng, b, h, m)


@pytest.mark.parametrize("b, h", [(0.1, 1.0), (0.25, 0.75), (0.5, 1.2)])
def test_plastic_law_of_one_block_is_housners(b, h):
    # Housner (1963): theta'+ / theta'- = 1 - 1.5 sin^2(alpha), alpha = atan(b / h)
    chain = Chain([b], [h], [7.0])
    after, pattern, admissible, _ = plastic_impact(chain, np.zeros(1), np.array([-1.3]), (1,), 0)
    ratio = 1.0 - 1.5 * math.sin(math.atan(b / h)) ** 2
    assert after[0] / -1.3 == pytest.approx(ratio, rel=1e-13, abs=1e-15)
    assert pattern == (-1,) and admissible == 1


def test_a_squat_block_stops_at_its_plastic_impact():
    # sin^2(alpha) > 2/3: Housner's ratio is negative, no rocking onto the other corner is
    # admissible; the block lands flat (both corners pushing, none pulling)
    chain = Chain([1.0], [0.3], [1.0])
    after, pattern, admissible, impulses = plastic_impact(chain, np.zeros(1), np.array([1.0]),
                                                          (-1,), 0)
    assert pattern == (0,) and after[0] == 0.0 and admissible == 1
    assert impulses[0, 2] >= 0 and impulses[0, 3] >= 0


@pytest.mark.parametrize("n", [2, 3])
def test_energy_never_rises_at_a_plastic_impact_and_no_two_solutions_compete(n):
    # random states just before a landing of a random interface; the kinetic energy after
    # (a projection of the velocities in the mass metric) can only fall. Never two
    # admissible active sets; in 2 of the 60 three-block states none is admissible within
    # the model (an open pivot would need a pulling impulse: the impact throws a block off,
    # outside the no-flight model), and the least violating one is kept
    rng = np.random.default_rng(10 + n)
    unique = 0
    for _ in range(60):
        b = np.sort(rng.uniform(0.05, 0.5, n))[::-1]
        chain = Chain(b, rng.uniform(0.05, 2.0, n), 10.0 ** rng.uniform(-3, 3, n))
        pattern = tuple(int(s) for s in rng.choice([-1, 0, 1], n))
        landing = int(rng.integers(n))
        pattern = pattern[:landing] + (int(rng.choice([-1, 1])),) + pattern[landing + 1:]
        phi = np.array([s * rng.uniform(0.0, 0.4) for s in pattern])
        phi[landing] = 0.0
        rate = np.array([rng.normal() if s else 0.0 for s in pattern])
        rate[landing] = -pattern[landing] * abs(rng.normal())
        before = energy(chain, phi, rate, pattern)[0]
        after_rate, after, admissible, _ = plastic_impact(chain, phi, rate, pattern, landing)
        assert energy(chain, phi, after_rate, after)[0] <= before * (1 + 1e-12)
        assert admissible <= 1
        unique += admissible == 1
    assert unique >= 58


def test_rigid_stack_plastic_ratio_closed_form():
    # a rigid stack rocking as one body landing on its other base corner with the interface
    # staying shut: angular momentum about the new corner gives
    # r = 1 - 2 M b1^2 / I_O  (one block: 1 - 1.5 sin^2(alpha), Housner),
    # I_O = (4/3) m1 (b1^2 + h1^2) + m2 [(b2^2 + h2^2)/3 + b1^2 + (2 h1 + h2)^2]
    b1, h1, b2, h2, m1, m2 = 0.15, 0.5, 0.15, 0.1, 2.0, 0.6
    mass, _, _, _, _, inertia = rigid_pair(b1, h1, b2, h2, m1, m2)
    ratio = 1.0 - 2.0 * mass * b1 ** 2 / inertia
    chain = Chain([b1, b2], [h1, h2], [m1, m2])
    after, pattern, admissible, _ = plastic_impact(chain, np.zeros(2), np.array([-0.8, 0.0]),
                                                   (1, 0), 0)
    assert pattern == (-1, 0) and admissible == 1
    assert after[0] / -0.8 == pytest.approx(ratio, rel=1e-12)


def test_a_one_dof_landing_is_linear_in_its_rate():
    # the compiled engine computes the plastic law at a landing of a one-DOF pattern (one
    # open interface, every interface at zero gap) once per unit rate and scales it: the
    # momentum balance and the admissibility tests are linear in the velocities before and
    # the geometry at zero gap is fixed, so the rates after are the rate times a constant
    # (the rigid stack's 1 - 2 M b_j^2 / I_O among them) and the chosen pattern does not
    # depend on the rate. Checked on the law itself at rates from 1e-6 to 10 rad/s; the
    # tolerance is the rounding of the momentum solve (mass ratios up to 1e3)
    rng = np.random.default_rng(38)
    for _ in range(20):
        n = int(rng.integers(2, 4))
        b = np.sort(rng.uniform(0.05, 0.5, n))[::-1]
        chain = Chain(b, rng.uniform(0.05, 2.0, n), 10.0 ** rng.uniform(-3, 3, n))
        landing, side = int(rng.integers(n)), int(rng.choice([-1, 1]))
        pattern = tuple(side if j == landing else 0 for j in range(n))
        unit = np.zeros(n)
        unit[landing] = -side
        per_unit, chosen, admissible, _ = plastic_impact(chain, np.zeros(n), unit, pattern,
                                                         landing)
        for rate in (1e-6, 0.03, 10.0):
            after, pattern_after, count, _ = plastic_impact(chain, np.zeros(n), rate * unit,
                                                            pattern, landing)
            assert pattern_after == chosen and count == admissible
            assert np.abs(after - rate * per_unit).max() <= 1e-12 * rate * np.abs(
                per_unit).max()


def test_the_constant_cor_law_scales_every_block_and_flips_the_landing_interface():
    chain = Chain([0.3, 0.2], [1.0, 0.8], [2.0, 1.0])
    after, pattern = cor_impact(chain, np.array([0.0, 0.1]), np.array([-0.5, 0.2]), (1, 1), 0,
                                0.9)
    assert pattern == (-1, 1)
    assert np.allclose(np.cumsum(after), 0.9 * np.array([-0.5, -0.3]), rtol=0, atol=1e-15)
