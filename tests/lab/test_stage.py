"""The table stage of a scene: command, servo and pitch between the record and the block."""

import math

import numpy as np
import pytest

from shaketable import Block, Motion
from shaketable.core.constants import G
from shaketable.ground.generators import harmonic
from shaketable.lab.pitch import Pitch
from shaketable.lab.servo import Actuator
from shaketable.lab.stage import (
    SAMPLES_PER_PITCH_CYCLE,
    TableSetup,
    pitch_sampled,
    run_table,
    table_setup_from_dict,
)
from shaketable.scenes.parse import SceneError, scene_from_dict
from shaketable.scenes.run import run_scene


def _ramped(amplitude_g=0.3, frequency=2.0, duration=12.0):
    # 2 s ramps at both ends so that the table starts and ends at rest
    motion = harmonic(frequency, horizontal=amplitude_g * G, duration=duration, dt=0.01, ramp=2.0)
    taper = np.clip((duration - motion.t) / 2.0, 0.0, 1.0)
    return Motion(motion.t, motion.horizontal * taper, name="ramped harmonic")


def test_no_table_returns_the_motion_itself():
    motion = _ramped()
    assert run_table(motion, None).felt is motion
    assert run_table(motion, TableSetup()).felt is motion


def test_command_of_a_smooth_motion_reproduces_it():
    # A 2 Hz motion with ramps needs no correction: the 0.1 Hz high-pass has gain
    # 1/sqrt(1 + (0.1/2)^8) = 1 - 2e-11 at 2 Hz and the baseline removes (almost)
    # nothing from a motion that ends at rest, so the command's acceleration is
    # the commanded one to well under 1 % of the peak.
    motion = _ramped()
    run = run_table(motion, TableSetup(command=True))
    difference = np.max(np.abs(run.felt.horizontal - motion.horizontal))
    assert difference < 0.01 * np.max(np.abs(motion.horizontal))
    # displacement amplitude of a 0.3 g, 2 Hz sine: a / (2 pi f)^2 = 18.6 mm (< 5 in stroke)
    # (over one steady cycle: the ramps leave a slow drift of the mean that the
    # 0.1 Hz high-pass only partly removes)
    cycle = (motion.t >= 6.0) & (motion.t <= 6.5)
    displacement = run.command.horizontal_displacement[cycle]
    half_range = 0.5 * (displacement.max() - displacement.min())
    assert half_range == pytest.approx(0.3 * G / (2 * math.pi * 2.0) ** 2, rel=0.03)
    assert run.exceedances == ()


def test_a_command_beyond_the_stroke_is_reported():
    # 0.5 g at 0.5 Hz needs a / (2 pi f)^2 = 0.50 m of stroke, the table has 5 in.
    motion = _ramped(0.5, 0.5, duration=24.0)
    run = run_table(motion, TableSetup(command=True))
    assert any(entry.axis == "horizontal" and entry.quantity == "displacement"
               for entry in run.exceedances)
    assert "exceeds the limit" in run.warnings()[0]


def test_actuator_attenuates_above_its_corner():
    # A 25 Hz, damping 0.7 servo passes 2 Hz with gain |H| = 1.000 (within 0.1 %)
    motion = _ramped()
    run = run_table(motion, TableSetup(command=True, actuator=Actuator()))
    steady = (motion.t > 4.0) & (motion.t < 8.0)
    ratio = np.max(np.abs(run.felt.horizontal[steady])) / np.max(np.abs(motion.horizontal[steady]))
    assert ratio == pytest.approx(float(Actuator().gain(2.0)), abs=5e-3)


def test_pitching_table_at_rest():
    # A table at rest that only pitches: rotation channel = phi'' = A sin(2 pi f t + psi)
    # (the closed form of table.pitch_history without drift), sampled >= 20 per cycle.
    pitch = Pitch(frequency=12.0, amplitude=0.25, phase=0.3)
    run = run_table(None, TableSetup(pitch=pitch), duration=2.0)
    felt = run.felt
    assert np.max(np.diff(felt.t)) <= 1.0 / (12.0 * SAMPLES_PER_PITCH_CYCLE) + 1e-12
    expected = 0.25 * np.sin(2 * math.pi * 12.0 * felt.t + 0.3)
    np.testing.assert_allclose(felt.rotation, expected, atol=1e-12)
    # tilt of gravity: g sin(phi) with phi = -phi''/(2 pi f)^2
    np.testing.assert_allclose(felt.horizontal,
                               G * np.sin(-expected / (2 * math.pi * 12.0) ** 2), atol=1e-12)


def test_pitch_sampling_keeps_the_motion_at_its_samples():
    motion = _ramped()
    fine = pitch_sampled(motion, Pitch())
    index = np.searchsorted(fine.t, motion.t)
    np.testing.assert_allclose(fine.horizontal[index], motion.horizontal, atol=1e-12)
    assert fine.t.size > motion.t.size


def test_setup_from_scene_section_and_its_errors():
    setup = table_setup_from_dict({"command": True, "highpass": "0.2 Hz",
                                   "actuator": {"natural_frequency": "20 Hz", "damping": 0.6},
                                   "pitch": {"frequency": "12 Hz", "amplitude": "0.2 rad/s2",
                                             "seed": 4},
                                   "limits": {"horizontal_velocity": "30 in/s"}}, "s.toml")
    assert setup.highpass == 0.2 and setup.actuator.natural_frequency == 20.0
    assert setup.pitch.amplitude == 0.2 and setup.pitch.seed == 4
    assert setup.limits.horizontal_velocity == pytest.approx(30 * 0.0254)
    with pytest.raises(ValueError, match=r"s\.toml.*unknown key 'pich'"):
        table_setup_from_dict({"pich": True}, "s.toml")
    with pytest.raises(ValueError, match=r"s\.toml: table\.highpass.*no unit"):
        table_setup_from_dict({"command": True, "highpass": 0.1}, "s.toml")
    with pytest.raises(ValueError, match="actuator needs table.command"):
        table_setup_from_dict({"command": False, "actuator": True}, "s.toml")
    with pytest.raises(ValueError, match=r"table\.limits\.stroke"):
        table_setup_from_dict({"limits": {"stroke": "5 in"}}, "s.toml")
    with pytest.raises(ValueError, match=r"table\.pitch.*amplitude"):
        table_setup_from_dict({"pitch": {"amplitude": "-1 rad/s2"}}, "s.toml")


def _scene(**sections):
    data = {"name": "t", "block": {"size": "30x6in"},
            "motion": {"kind": "harmonic", "frequency": "2 Hz", "horizontal": "0.3 g",
                       "duration": "6 s", "dt": "0.01 s", "ramp": "1 s"},
            "rocking": {"cor": 0.925}}
    data.update(sections)
    return scene_from_dict(data, "scene.toml")


def test_scene_errors_at_load_time():
    with pytest.raises(SceneError, match=r"scene\.toml.*table\.pitch\.phase.*no unit"):
        _scene(table={"pitch": {"phase": 0.5}})
    with pytest.raises(SceneError, match="static_friction"):
        _scene(block={"size": "30x6in", "static_friction": -1})


def test_scene_with_a_pitching_table_runs_and_reports():
    result = run_scene(_scene(table={"pitch": {"phase": "0 rad"}, "command": True}))
    assert result.table is not None and result.motion.rotation is not None
    assert "table" in result.summary()
    # 0.3 g > Eq. 2-1's B/H g = 0.2 g: the block rocks. This case sits near the
    # overturning boundary, where the report's 0.22 rad/s^2 pitch can change the
    # fate; as the pitch amplitude goes to zero the response must converge to the
    # run without [table] (continuity of the model in the pitch).
    plain = run_scene(_scene()).main.max_theta_ratio
    faint = run_scene(_scene(table={"pitch": {"phase": "2 rad", "amplitude": "1e-4 rad/s2"}}))
    assert faint.main.max_theta_ratio == pytest.approx(plain, rel=1e-3)
    assert faint.main.max_theta_ratio != plain


def test_sliding_check_of_section_2_1():
    # Section 2.1: rocking only if mu_s > B/H (= 0.2 for the 30 x 6 in block)
    assert _scene(block={"size": "30x6in", "static_friction": 0.6}).mode().startswith("rocking")
    sliding = _scene(block={"size": "30x6in", "static_friction": 0.15})
    assert sliding.mode().startswith("SLIDING")
    assert "mode (Section 2.1)" in run_scene(sliding).summary()
    assert _scene().mode() is None
    assert Block.parse("30x6in").width / Block.parse("30x6in").height == pytest.approx(0.2)
