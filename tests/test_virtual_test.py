"""The virtual test of Section 3.7: test (sensors on a pitching table) against theory."""

import numpy as np
import pytest

from shaketable import Block
from shaketable.motions import harmonic
from shaketable.pipeline import run_scene
from shaketable.scenes import SceneError, scene_from_dict
from shaketable.sensors import Potentiometers, Sensors
from shaketable.table import Pitch
from shaketable.table_stage import TableSetup, run_table
from shaketable.virtual_test import TheorySetup, run_virtual_test, sensors_from_dict

BLOCK = Block.parse("30x6in")


def test_free_rocking_test_and_theory_with_the_true_cor_agree():
    # Fig. 3.4: "the two curves are identical, for all practical purposes". With the
    # theory's COR equal to the true one, the only differences are the sensors' noise,
    # the 20 Hz anti-alias filter's delay and the small-angle conversion x/H, whose
    # error at 0.5 alpha is (b/2H) theta^2 ~ 0.3 % (sensors.py): the peaks agree to 1 %.
    result = run_virtual_test(BLOCK, None, cor=0.925, sensors=Sensors(seed=2),
                              theory=TheorySetup(cor=0.925), theta0=0.5 * BLOCK.alpha,
                              duration=8.0)
    metrics = result.metrics()
    assert metrics["peak ratio test/theory"] == pytest.approx(1.0, abs=0.01)
    assert metrics["RMS difference theta/alpha"] < 0.05
    assert metrics["t unstable test [s]"] is None and not metrics["overturned test"]
    # a wrong COR shows: 0.85 instead of 0.925 decays visibly faster
    wrong = run_virtual_test(BLOCK, None, cor=0.925, sensors=Sensors(seed=2),
                             theory=TheorySetup(cor=0.85), theta0=0.5 * BLOCK.alpha,
                             duration=8.0)
    assert wrong.metrics()["RMS difference theta/alpha"] > 2 * metrics["RMS difference theta/alpha"]


def test_harmonic_test_unstable_at_about_the_same_time():
    # Fig. 3.8: "test and theory unstable at about the same time, overturning the same
    # way"; the test on a table pitching at 12 Hz, 0.22 rad/s^2, the theory driven by
    # the 50 samples/s digitized accelerations. (Figs. 3.7 and 3.9 started abruptly
    # sit near an overturning boundary where the pitch changes the fate for some
    # phases: see the section-3-7-pitch study.)
    motion = harmonic(2.0, 0.38, 0.33, duration=4.0, dt=0.01)
    for seed in (1, 2, 3):
        felt = run_table(motion, TableSetup(pitch=Pitch(seed=seed))).felt
        metrics = run_virtual_test(BLOCK, felt, cor=0.925, sensors=Sensors(seed=seed),
                                   theory=TheorySetup(cor=0.925)).metrics()
        assert metrics["overturned test"] and metrics["overturned theory"]
        assert metrics["t unstable test [s]"] == pytest.approx(metrics["t unstable theory [s]"],
                                                              abs=0.1)
        assert metrics["direction test"] == metrics["direction theory"] != 0


def test_one_wire_pulls_the_block():
    # One potentiometer wire (20 oz) is a force at the top (Section 3.3): the free
    # rocking differs from the run with both wires, whose forces cancel.
    kwargs = dict(cor=0.925, theory=TheorySetup(cor=0.925), theta0=0.5 * BLOCK.alpha,
                  duration=3.0)
    both = run_virtual_test(BLOCK, None, sensors=Sensors(seed=1), **kwargs)
    one = run_virtual_test(BLOCK, None, sensors=Sensors(Potentiometers(wires="minus-x"),
                                                        seed=1), **kwargs)
    assert not np.allclose(both.test.theta, one.test.theta)


def _scene(**sections):
    data = {"name": "vt", "block": {"size": "30x6in"},
            "motion": {"kind": "harmonic", "frequency": "2 Hz", "horizontal": "0.38 g",
                       "vertical": "0.33 g", "duration": "4 s", "dt": "0.01 s"},
            "rocking": {"cor": 0.925}}
    data.update(sections)
    return scene_from_dict(data, "vt.toml")


def test_scene_with_sensors_and_theory(tmp_path):
    scene = _scene(table={"pitch": {"seed": 3}}, sensors={"seed": 3}, theory={"cor": 0.925})
    result = run_scene(scene)
    assert len(result.tests) == 1
    summary = result.summary()
    assert summary["test vs theory"][0]["overturned theory"]
    written = {path.name for path in result.write(tmp_path)}
    assert {"test-vs-theory.png", "record.csv", "summary.json"} <= written


def test_scene_errors_name_the_key():
    with pytest.raises(SceneError, match=r"vt\.toml.*unknown key 'sampling'"):
        _scene(sensors={"sampling": "50 Hz"})
    with pytest.raises(SceneError, match=r"vt\.toml.*potentiometers"):
        _scene(sensors={"potentiometers": "left"})
    with pytest.raises(SceneError, match=r"vt\.toml.*\[theory\].*needs a \[sensors\]"):
        _scene(theory={"cor": 0.9})
    with pytest.raises(SceneError, match=r"vt\.toml: sensors\.rate.*no unit"):
        _scene(sensors={"rate": 50})
    with pytest.raises(ValueError, match=r"theory\.cor"):
        _scene(sensors={}, theory={"cor": 1.5})
    assert sensors_from_dict({"potentiometers": False, "accelerometers": False}).top_force(
        BLOCK) == 0.0


def test_table_3_1_periods_measured_the_reports_way():
    # Table 3.1 / Section 3.7 (1): 36 x 9 in block, period = 4 x (max to zero) read on
    # the 50 samples/s record; the report's test/theory agreement is within 2-3 %.
    # Reference: the exact nonlinear period (quadrature of the energy integral).
    from shaketable.report_tables import table_3_1

    frame = table_3_1()
    assert (abs(frame["virtual / exact [-]"] - 1.0) < 0.02).all()
    # the half cycles measured are the table's amplitudes (within 0.1 deg)
    assert (abs(frame["virtual test amplitude [deg]"] - frame["amplitude [deg]"]) < 0.1).all()
