"""The virtual test of Section 3.7: test (sensors on a pitching table) against theory."""

from dataclasses import replace

import numpy as np
import pytest

from shaketable import Block
from shaketable.lab.sensors import Potentiometers, Sensors
from shaketable.lab.stage import TableSetup, run_table, table_setup_from_dict
from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import SceneError, load_scene, scene_from_dict
from shaketable.scenes.run import build_motion, run_scene
from shaketable.scenes.virtual_test import (
    TheorySetup,
    run_virtual_test,
    sensors_from_dict,
)

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


def _harmonic_virtual_test(name, seed, **motion_changes):
    """The scene ``name`` (Figs. 3.7-3.9) with pitch and sensor seed ``seed``.

    The theory runs with the report's COR 0.925 (Section 3.7 (2)) instead of
    calibrating it (identified as 0.92501 from the virtual free rocking, see
    docs/virtual_test.md), which keeps the test fast.
    """
    scene = load_scene(resolve_scene_path(name))
    if motion_changes:
        scene = replace(scene, motion={**scene.motion, **motion_changes})
    setup = scene.table if scene.table is not None else TableSetup()
    if motion_changes.get("ramp") == 0.0:  # the abrupt start: no displacement command
        setup = replace(setup, command=False)
    setup = replace(setup, pitch=replace(setup.pitch, seed=seed))
    felt = run_table(build_motion(scene), setup).felt
    return run_virtual_test(scene.block, felt, cor=0.925, sensors=Sensors(seed=seed),
                            theory=TheorySetup(cor=0.925)).metrics()


@pytest.mark.parametrize("name", ["fig-3-7", "fig-3-8", "fig-3-9"])
def test_harmonic_test_unstable_at_about_the_same_time(name):
    # Figs. 3.7-3.9, Section 3.7 (2): "the block becomes unstable at about the same
    # points in both test and computer results, and overturning is in the same
    # direction". Test: the block on the table pitching at 12 Hz, 0.22 rad/s^2 (four
    # pitch phases, seeds 1-4), read by the sensors; theory: driven by the 50 samples/s
    # digitized accelerations. "About the same point" = on the same excursion, i.e.
    # within half a period of the 2 Hz table motion (0.25 s, the scenes' tolerance);
    # peaks within the report's about 10 %.
    for seed in (1, 2, 3, 4):
        metrics = _harmonic_virtual_test(name, seed)
        assert metrics["overturned test"] and metrics["overturned theory"], (name, seed)
        assert abs(metrics["t unstable test [s]"] - metrics["t unstable theory [s]"]) <= 0.25, \
            (name, seed, metrics)
        assert metrics["direction test"] == metrics["direction theory"] != 0, (name, seed)
        assert abs(metrics["peak ratio test/theory"] - 1.0) <= 0.10, (name, seed, metrics)


def test_abrupt_fig_3_7_start_lets_the_pitch_decide():
    # The scenes' start matters (docs/virtual_test.md): started abruptly at phase 0
    # (no ramp, no displacement command, the scenes before the ramp), Fig. 3.7 sits
    # near an overturning boundary and the pitch changes when and which way the block
    # falls, so test and theory disagree for some pitch phase (seed 1 was reported by
    # the audit as 8.98 s vs 5.28 s, opposite directions).
    disagree = 0
    for seed in (1, 2, 3):
        metrics = _harmonic_virtual_test("fig-3-7", seed, ramp=0.0, duration=10.0)
        t_test, t_theory = metrics["t unstable test [s]"], metrics["t unstable theory [s]"]
        disagree += (t_test is None or t_theory is None or abs(t_test - t_theory) > 0.25
                     or metrics["direction test"] != metrics["direction theory"])
    assert disagree >= 1


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


@pytest.mark.usefixtures("figure_drafts")
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
    from shaketable.studies.report_tables import table_3_1

    frame = table_3_1()
    assert (abs(frame["virtual / exact [-]"] - 1.0) < 0.02).all()
    # the half cycles measured are the table's amplitudes (within 0.1 deg)
    assert (abs(frame["virtual test amplitude [deg]"] - frame["amplitude [deg]"]) < 0.1).all()


def test_scene_scores_test_against_theory():
    # Section 3.7 (2) for Figs. 3.7-3.9: same verdict, same direction, unstable at
    # about the same point (|dt| <= 0.25 s, the scene's tolerance), peak ratio within
    # the report's about 10 %: four "test vs theory" lines besides the report's values.
    result = run_scene(load_scene(resolve_scene_path("fig-3-7")))
    lines = {line.quantity: line for line in result.comparisons}
    metrics = result.tests[0].metrics()
    assert lines["overturns"].reproduced == result.tests[0].theory.overturned
    scored = [line for line in result.comparisons if line.quantity.startswith("test vs theory")]
    assert len(scored) == 4 and all(line.agrees for line in scored)
    assert lines["test vs theory: peak ratio"].reproduced == metrics["peak ratio test/theory"]
    # The same scene started abruptly on a table without a displacement command (the
    # scene before the ramp) disagrees for pitch seed 1, and the lines must say so.
    scene = load_scene(resolve_scene_path("fig-3-7"))
    abrupt = replace(scene, motion={**scene.motion, "ramp": 0.0, "duration": 10.0},
                     table=table_setup_from_dict({"pitch": {"seed": 1}}))
    result = run_scene(abrupt)
    metrics = result.tests[0].metrics()
    lines = {line.quantity: line for line in result.comparisons}
    same_direction = metrics["direction test"] == metrics["direction theory"]
    assert lines["test vs theory: direction of instability"].agrees == same_direction
    assert not all(line.agrees for line in lines.values()
                   if line.quantity.startswith("test vs theory"))


def test_fig_3_5_values_are_the_tests():
    # Fig. 3.5 is "TEST DATA" (its caption): the report's overturning after about
    # 4 s (Section 3.6, a time to the nearest second: +-0.5 s) is compared with the
    # virtual test, not with the theory. For earthquake motions the report gives no
    # theory: test and theory "did not show the same level of agreement" (Section
    # 3.7 (2)), one line with the report's answer "no".
    result = run_scene(load_scene(resolve_scene_path("fig-3-5")))
    test = result.tests[0].test
    lines = {line.quantity.split(" (")[0]: line for line in result.comparisons}
    line = lines["t overturn"]
    assert line.report == 4.0 and line.reproduced == round(test.t_overturn, 3)
    # measured: the substitute overturns the block at 3.05 s, outside 4 +- 0.5 s
    assert "±0.5 s" in line.quantity and test.t_overturn < 3.5 and line.agrees is False
    (closeness,) = [c for c in result.comparisons if c.quantity.startswith("test vs theory")]
    # measured (docs/virtual_test.md): at 0.5 g the substitute's test and theory agree as
    # closely as the harmonic tests do, which the report says they did not: "differs"
    assert closeness.report is False and closeness.reproduced is True
    assert closeness.agrees is False


def test_an_initial_velocity_reaches_the_test_and_the_theory_with_sensors():
    # theta_dot0 reaches scenes with [sensors] too. Free rocking of the
    # 30 x 6 in block thrown from theta = 0 with theta' = 0.2 rad/s (table at rest).
    data = {"name": "thrown", "block": {"size": "30x6in"},
            "motion": {"kind": "free"},
            "rocking": {"cor": 0.925, "theta_dot0": "0.2 rad/s", "duration": "3 s"},
            "sensors": {"seed": 1}, "theory": {"cor": 0.925}}
    result = run_scene(scene_from_dict(data, "thrown.toml"))
    test = result.tests[0]
    assert test.test.theta_dot[0] == 0.2 and test.theory.theta_dot[0] == 0.2
    assert np.max(np.abs(test.test.theta)) > 0.0


def test_stage_sections_are_parsed_once_into_frozen_objects():
    """[table], [sensors] and [theory] are typed at load: the pipeline gets
    the objects, never the raw TOML tables, and a scene without them has None."""
    from shaketable.scenes.virtual_test import TheorySetup

    scene = _scene(table={"pitch": {"seed": 3}}, sensors={"seed": 3}, theory={"cor": 0.925})
    assert isinstance(scene.table, TableSetup) and scene.table.pitch is not None
    assert isinstance(scene.sensors, Sensors) and scene.sensors.seed == 3
    assert isinstance(scene.theory, TheorySetup) and scene.theory.cor == 0.925
    bare = _scene()
    assert bare.table is None and bare.sensors is None and bare.theory is None
    with pytest.raises(SceneError, match="needs a \\[sensors\\] section"):
        _scene(theory={"cor": 0.9})
