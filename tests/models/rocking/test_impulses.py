"""Steps of the table's velocity (ideal impulses), applied exactly.

References: the jump of theta' from the angular-momentum balance about the pivot
(``shaketable.core.impulses``), checked against the engine under a very short
rectangular pulse of the same area (a different route: Eq. 2-13 integrated through
the pulse); the single-impulse overturning velocity from the energy barrier; and the
critical double-impulse velocity of Nabeshima, Taniguchi, Kojima & Takewaki (2016),
V_c = V1 / (1 + cor), derived here for the critical timing (second, opposite step at
the first impact): the block leaves theta = 0 with theta'_0 = c V (c = 3 cos(alpha) /
(4R)), comes back with the same speed (energy kept), the impact leaves cor c V and the
step -V adds c V in the same direction: (1 + cor) c V, which overturns iff it exceeds
c V1. The same holds in the linearised model with c = 3/(4R) and its V1.
"""

import math

import numpy as np
import pytest

from shaketable.core import theory
from shaketable.core.geometry import Block
from shaketable.core.impulses import (
    ImpulsiveMotion,
    single_impulse_overturn_velocity,
    theta_dot_jump,
)
from shaketable.core.motion import Motion
from shaketable.ground import generators
from shaketable.models.api import simulate

BLOCK = Block.from_feet(16, 4)


def _return_time(block, rate, linear):
    """Time from theta = 0 with theta' = rate back to theta = 0 (free rocking) [s]."""
    if linear:   # theta = alpha (1 - cosh pt) + (rate/p) sinh pt = 0: tanh(pt/2) = rate/(p alpha)
        return 2.0 / block.p * math.atanh(rate / (block.p * block.alpha))
    energy = 0.5 * rate * rate          # cos(alpha - amplitude) = cos(alpha) + E / p^2
    amplitude = block.alpha - math.acos(math.cos(block.alpha) + energy / block.p ** 2)
    return 0.5 * theory.exact_period(block, amplitude)


@pytest.mark.parametrize("method", ["fast", "linear"])
def test_double_impulse_critical_velocity_is_v1_over_one_plus_cor(method):
    linear = method == "linear"
    cor = 0.9
    v1 = single_impulse_overturn_velocity(BLOCK.alpha, BLOCK.R, linear)
    critical = v1 / (1 + cor)
    for factor, overturns in ((1 - 1e-6, False), (1 + 1e-6, True),
                              (1 - 1e-3, False), (1 + 1e-3, True)):
        velocity = critical * factor
        rate = theta_dot_jump(0.0, velocity, BLOCK.alpha, BLOCK.R, linear)
        interval = _return_time(BLOCK, rate, linear) * (1 + 1e-12)   # just after the impact
        tail = 40.0 / BLOCK.p if abs(factor - 1) > 1e-4 else 0.5
        motion = generators.double_impulse(velocity, interval, duration=0.1 + interval + tail,
                                           start=0.1)
        result = simulate(BLOCK, motion, cor=cor, method=method)
        assert result.n_impacts >= 1
        assert result.impact_times[0] == pytest.approx(0.1 + interval, abs=1e-9)
        assert result.fate.will_overturn is overturns, factor
        if abs(factor - 1) > 1e-4:          # long enough for the padded run to see it
            assert result.overturned is overturns, factor


@pytest.mark.parametrize("method", ["fast", "linear"])
def test_single_impulse_from_rest_overturns_above_v1(method):
    linear = method == "linear"
    v1 = single_impulse_overturn_velocity(BLOCK.alpha, BLOCK.R, linear)
    for factor, overturns in ((1 - 1e-6, False), (1 + 1e-6, True)):
        motion = generators.velocity_steps([0.2], [-v1 * factor], duration=1.0)
        result = simulate(BLOCK, motion, cor=0.8, method=method)
        assert result.fate.will_overturn is overturns
        assert result.theta[-1] < 0                 # a negative step tips it to theta < 0


def test_jump_matches_a_very_short_pulse_of_the_same_area():
    """A rocking block (theta = 0.3 alpha, moving) under a 20 us rectangular pulse of area
    dv: the engine's change of theta' across it against the exact jump; the gravity and
    the pulse's finite length contribute O(duration) = 1e-4 relative at most."""
    theta0, rate0, dv, width = 0.3 * BLOCK.alpha, 0.05, 0.4, 2e-5
    edge = 1e-8
    t = np.array([0.0, 0.01, 0.01 + edge, 0.01 + width - edge, 0.01 + width, 0.02])
    level = dv / (width - edge)                     # trapezoid area = dv
    motion = Motion(t, np.array([0.0, 0.0, level, level, 0.0, 0.0]))
    pulse = simulate(BLOCK, motion, cor=0.9, theta0=theta0, theta_dot0=rate0)
    free = simulate(BLOCK, Motion(t, np.zeros(t.size)), cor=0.9, theta0=theta0,
                    theta_dot0=rate0)
    change = pulse.theta_dot[-1] - free.theta_dot[-1]
    expected = theta_dot_jump(theta0, dv, BLOCK.alpha, BLOCK.R)
    assert expected == pytest.approx(0.75 * dv * math.cos(BLOCK.alpha - theta0) / BLOCK.R)
    assert change == pytest.approx(expected, rel=2e-3)


def test_a_step_at_the_first_sample_acts_on_the_initial_state():
    step = generators.velocity_steps([0.0], [0.2], duration=1.0)
    given = simulate(BLOCK, Motion.at_rest(1.0, 0.01), cor=0.8,
                     theta_dot0=theta_dot_jump(0.0, 0.2, BLOCK.alpha, BLOCK.R))
    result = simulate(BLOCK, step, cor=0.8)
    assert np.array_equal(result.theta, given.theta)
    assert result.t_start == 0.0


def test_joined_result_has_the_jump_and_every_piece():
    motion = generators.velocity_steps([0.2, 0.7], [0.3, 0.1], duration=1.5, dt=0.01)
    result = simulate(BLOCK, motion, cor=0.8)
    assert result.t[0] == 0.0 and result.t[-1] == pytest.approx(1.5)
    assert np.all(np.diff(result.t) >= 0)
    k = int(np.flatnonzero(np.isclose(result.t, 0.7, rtol=0, atol=1e-12))[0])   # twice
    assert result.t[k + 1] == result.t[k]
    jump = result.theta_dot[k + 1] - result.theta_dot[k]
    assert jump == pytest.approx(theta_dot_jump(result.theta[k], 0.1, BLOCK.alpha, BLOCK.R),
                                 rel=1e-12)
    assert result.t_start == pytest.approx(0.2)
    assert result.to_frame().shape[0] == result.t.size


def test_bad_impulses_are_refused_with_the_parameter_named():
    rest = Motion.at_rest(1.0)
    with pytest.raises(ValueError, match="velocity_steps"):
        ImpulsiveMotion(rest, (0.5,), (0.0,))
    with pytest.raises(ValueError, match="times"):
        ImpulsiveMotion(rest, (0.5, 0.4), (0.1, 0.1))
    with pytest.raises(ValueError, match="inside the motion"):
        ImpulsiveMotion(rest, (1.5,), (0.1,))
    with pytest.raises(ValueError, match="inside the motion"):
        ImpulsiveMotion(rest, (-0.1,), (0.1,))
    with pytest.raises(ValueError, match="velocity"):
        generators.double_impulse(0.0, 0.5, duration=2.0)


def test_impulses_scene_runs_and_converts_its_units(tmp_path):
    """A scene with ``kind = "impulses"`` (in/s and ms at the edge, SI inside)."""
    from shaketable.scenes.parse import SceneError, scene_from_dict
    from shaketable.scenes.run import run_scene

    data = {"name": "double impulse", "block": {"size": "16x4ft"},
            "motion": {"kind": "impulses", "times": ["100 ms", "0.6 s"],
                       "velocity_steps": ["10 in/s", "-10 in/s"], "duration": "2 s"},
            "rocking": {"cor": 0.9}}
    result = run_scene(scene_from_dict(data, "impulses.toml"))
    run = result.runs[0]
    expected = theta_dot_jump(0.0, 10 * 0.0254, BLOCK.alpha, BLOCK.R)
    k = int(np.flatnonzero(np.isclose(run.t, 0.1, rtol=0, atol=1e-12))[-1])
    assert run.theta_dot[k] == pytest.approx(expected, rel=1e-12)
    assert run.t[-1] == pytest.approx(2.0)
    bad = dict(data, motion={"kind": "impulses", "times": ["0.1 s"], "duration": "2 s"})
    with pytest.raises(SceneError, match="velocity_steps"):
        scene_from_dict(bad, "impulses.toml")
    bad = dict(data, motion=dict(data["motion"], times="0.1 s"))
    with pytest.raises(SceneError, match="motion.times must be a list"):
        scene_from_dict(bad, "impulses.toml")
