"""Floor motions: the modal filter against closed forms and an independent integration."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from shaketable.core.motion import Motion
from shaketable.ground.floor import (
    Building,
    Mode,
    floor_motion,
    linear_participation,
    participation,
    relative_acceleration,
)


def _one_mode(period, damping=0.05):
    """A one-storey building whose roof carries Gamma phi = 1: the floor is the oscillator."""
    return Building(period=period, height=3.0, storeys=1, damping=damping)


def test_harmonic_steady_state_amplification_at_resonance():
    # Closed-form transmissibility of a damped oscillator (Chopra, Dynamics of Structures,
    # Eq. 3.6.4): TR = sqrt(1 + (2 zeta r)^2) / sqrt((1 - r^2)^2 + (2 zeta r)^2);
    # r = 1, zeta = 0.05: sqrt(1.01) / 0.1 = 10.0499. The ground is the linear
    # interpolant of a sampled sine, whose fundamental is sinc^2(omega dt / 2) (the
    # Fourier transform of the hat function; N = 200 samples per period).
    period, zeta, per_period = 1.0, 0.05, 200
    omega = 2 * math.pi / period
    dt = period / per_period
    t = np.arange(80 * per_period + 1) * dt  # 80 periods: transient below exp(-25)
    floor = floor_motion(Motion(t, np.sin(omega * t)), _one_mode(period, zeta), floor=1)
    last = slice(60 * per_period, 80 * per_period)  # twenty whole periods
    basis = np.vstack([np.sin(omega * t[last]), np.cos(omega * t[last])]).T
    coefficients = np.linalg.lstsq(basis, floor.horizontal[last], rcond=None)[0]
    amplitude = math.hypot(*coefficients)
    x = omega * dt / 2
    expected = math.sqrt(1 + (2 * zeta) ** 2) / (2 * zeta) * (math.sin(x) / x) ** 2
    assert math.sqrt(1.01) / 0.1 == pytest.approx(10.0499, abs=1e-4)
    assert amplitude == pytest.approx(expected, rel=1e-6)


def test_off_resonance_amplification():
    # r = 0.5, zeta = 0.02: TR = sqrt(1 + 0.02^2) / sqrt(0.75^2 + 0.02^2) (same closed form)
    period, zeta, per_period = 1.0, 0.02, 200
    omega_g = 0.5 * 2 * math.pi / period
    dt = period / per_period
    t = np.arange(400 * per_period + 1) * dt
    floor = floor_motion(Motion(t, np.cos(omega_g * t)), _one_mode(period, zeta), floor=1)
    last = slice(200 * per_period, 400 * per_period)  # whole periods of the ground
    basis = np.vstack([np.sin(omega_g * t[last]), np.cos(omega_g * t[last])]).T
    amplitude = math.hypot(*np.linalg.lstsq(basis, floor.horizontal[last], rcond=None)[0])
    x = omega_g * dt / 2
    expected = math.sqrt(1 + 0.02**2) / math.sqrt(0.75**2 + 0.02**2) * (math.sin(x) / x) ** 2
    assert amplitude == pytest.approx(expected, rel=1e-6)


def test_constant_ground_acceleration_step_response_and_passes_unchanged():
    # A constant a from rest: u(t) = -a/w^2 (1 - e^{-zwt}(cos wd t + z/sqrt(1-z^2) sin wd t))
    # (Chopra Eq. 4.3.3, step force); the floor's absolute acceleration -2 z w u' - w^2 u
    # starts at a (1 - Gamma phi) and settles to a.
    period, zeta, a = 0.4, 0.05, 2.0
    w = 2 * math.pi / period
    wd = w * math.sqrt(1 - zeta**2)
    t = np.arange(0, 30.0, 0.01)
    building = Building(period=period, height=15.0, storeys=5, damping=zeta)
    gamma_phi = building.mode_list()[0].participation[2]  # floor 3
    floor = floor_motion(Motion(t, np.full(t.size, a)), building, floor=3)
    envelope = np.exp(-zeta * w * t)
    u = -a / w**2 * (1 - envelope * (np.cos(wd * t) + zeta / math.sqrt(1 - zeta**2)
                                     * np.sin(wd * t)))
    u_dot = -a / w**2 * envelope * (w**2 / wd) * np.sin(wd * t)
    relative = -a - 2 * zeta * w * u_dot - w**2 * u
    np.testing.assert_allclose(floor.horizontal, a + gamma_phi * relative, rtol=0, atol=1e-12)
    assert floor.horizontal[0] == pytest.approx(a * (1 - gamma_phi), abs=1e-12)
    assert floor.horizontal[-1] == pytest.approx(a, abs=1e-9)


@pytest.mark.parametrize("storeys", [1, 2, 5, 12])
def test_linear_mode_participation_is_3n_over_2n_plus_1(storeys):
    # Gamma = sum(k/N) / sum((k/N)^2) = (N+1)/2 / ((N+1)(2N+1)/(6N)) = 3N/(2N+1)
    building = Building(period=0.5, height=3.0 * storeys, storeys=storeys)
    roof = building.mode_list()[0].participation[-1]
    assert roof == pytest.approx(3 * storeys / (2 * storeys + 1), rel=1e-14)
    assert linear_participation(storeys) == pytest.approx(roof, rel=1e-14)
    phi = np.arange(1, storeys + 1) / storeys
    assert participation(phi) == pytest.approx(3 * storeys / (2 * storeys + 1), rel=1e-14)


def test_shear_beam_modes_are_the_uniform_shear_building_eigenmodes():
    # an independent eigen-solution: N equal masses m on N equal storey stiffnesses k,
    # K = k tridiag(-1, 2, -1) with K[N, N] = k (the roof), M = m I; Gamma_n phi_n at each
    # floor and T_n / T_1 = omega_1 / omega_n from numpy's symmetric eigensolver
    n = 7
    stiffness = 2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    stiffness[-1, -1] = 1.0
    eigenvalues, vectors = np.linalg.eigh(stiffness)
    building = Building(period=0.9, height=21.0, storeys=n, shape="shear-beam", n_modes=n)
    modes = building.mode_list()
    for mode, value, phi in zip(modes, eigenvalues, vectors.T):
        gamma_phi = phi.sum() / (phi @ phi) * phi
        np.testing.assert_allclose(mode.participation, gamma_phi, rtol=0, atol=1e-13)
        assert mode.period == pytest.approx(0.9 * math.sqrt(eigenvalues[0] / value), rel=1e-13)
    # orthogonal modes with equal masses: all N together carry the whole mass, so their
    # Gamma_n phi_n add up to 1 at every floor (a rigid building moves with the ground)
    total = np.sum([mode.participation for mode in modes], axis=0)
    np.testing.assert_allclose(total, np.ones(n), rtol=0, atol=1e-13)


def test_shear_beam_tends_to_the_continuous_cantilever():
    # continuous uniform shear beam: Gamma_1 phi_1(H) = int sin / int sin^2 = (2/pi) / (1/2)
    # = 4/pi, and T_n = T_1 / (2n - 1)
    building = Building(period=1.0, height=600.0, storeys=200, shape="shear-beam", n_modes=3)
    modes = building.mode_list()
    assert modes[0].participation[-1] == pytest.approx(4 / math.pi, rel=1e-4)
    assert [mode.period for mode in modes] == pytest.approx([1.0, 1 / 3, 1 / 5], rel=1e-3)


def test_exact_for_piecewise_linear_input_against_scipy():
    # an independent integration (DOP853, rtol 1e-10) of the same oscillator under the
    # same piecewise-linear ground, one interval at a time (no kink inside a step)
    rng = np.random.default_rng(3)
    dt, n, period, zeta = 0.02, 150, 0.7, 0.05
    ground = rng.normal(size=n)
    ground[0] = 0.4
    w = 2 * math.pi / period
    state = np.zeros(2)
    reference = np.empty(n)
    reference[0] = -ground[0]
    for i in range(n - 1):
        slope = (ground[i + 1] - ground[i]) / dt

        def rhs(s, x, i=i, slope=slope):
            return [x[1], -(ground[i] + slope * s) - 2 * zeta * w * x[1] - w * w * x[0]]

        state = solve_ivp(rhs, (0.0, dt), state, method="DOP853", rtol=1e-10,
                          atol=1e-14).y[:, -1]
        reference[i + 1] = -ground[i + 1] - 2 * zeta * w * state[1] - w * w * state[0]
    computed = relative_acceleration(ground, dt, period, zeta)
    assert np.max(np.abs(computed - reference)) <= 1e-9 * np.max(np.abs(reference))


def test_ground_floor_is_the_ground_and_height_interpolates():
    t = np.arange(0, 2.0, 0.01)
    motion = Motion(t, np.sin(3 * t), 0.5 * np.cos(t), name="m")
    building = Building(period=0.5, height=20.0, storeys=4)
    np.testing.assert_array_equal(floor_motion(motion, building, floor=0).horizontal,
                                  motion.horizontal)
    roof = floor_motion(motion, building, floor=4)
    by_height = floor_motion(motion, building, height=20.0)
    np.testing.assert_allclose(by_height.horizontal, roof.horizontal, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(roof.vertical, motion.vertical)


def test_explicit_modes_sum():
    t = np.arange(0, 3.0, 0.01)
    motion = Motion(t, np.sin(5 * t))
    one = Building(period=0.6, height=6.0, storeys=2, modes=(Mode(0.6, 0.05, (0.5, 1.2)),))
    two = Building(period=0.6, height=6.0, storeys=2,
                   modes=(Mode(0.6, 0.05, (0.5, 1.2)), Mode(0.2, 0.03, (0.4, -0.2))))
    expected = (floor_motion(motion, one, floor=2).horizontal
                - 0.2 * relative_acceleration(motion.horizontal, 0.01, 0.2, 0.03))
    np.testing.assert_allclose(floor_motion(motion, two, floor=2).horizontal, expected,
                               rtol=0, atol=1e-12)


@pytest.mark.parametrize("kwargs, match", [
    ({"period": 0.0, "height": 10.0, "storeys": 3}, "period"),
    ({"period": 0.5, "height": -1.0, "storeys": 3}, "height"),
    ({"period": 0.5, "height": 10.0, "storeys": 0}, "storeys"),
    ({"period": 0.5, "height": 10.0, "storeys": 3, "shape": "cantilever"}, "shape"),
    ({"period": 0.5, "height": 10.0, "storeys": 3, "damping": 1.0}, "damping"),
])
def test_bad_building(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Building(**kwargs)


def test_floor_above_the_roof():
    motion = Motion(np.arange(0, 1, 0.01), np.zeros(100))
    building = Building(period=0.5, height=10.0, storeys=3)
    with pytest.raises(ValueError, match="floor must be an integer from 0 .* to 3"):
        floor_motion(motion, building, floor=4)
    with pytest.raises(ValueError, match="height"):
        floor_motion(motion, building, height=12.0)
    with pytest.raises(ValueError, match="one of floor"):
        floor_motion(motion, building)
