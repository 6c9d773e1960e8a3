"""The classroom page's computation, without a browser: fields -> scene -> runs -> picture.

The page's numbers are checked against ``simulate`` called directly with the same inputs
(built here from the generators, not from the page's scene), its lessons against the
bundled teaching scenes they name and against the closed forms their sentences state,
its drawing against the geometry of a block rocking about its corner.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from shaketable import Block, simulate
from shaketable.classroom.model import (
    LESSONS,
    FieldError,
    Settings,
    block_outlines,
    check,
    compute,
    key_numbers,
    scene_data,
    scene_toml,
)
from shaketable.core.constants import INCH, G
from shaketable.ground import generators, records


def test_a_harmonic_run_equals_simulate_with_the_same_inputs():
    settings = Settings(height="30 in", width="6 in", cor="0.925", frequency="2 Hz",
                        amplitude="0.3 g", duration="8 s")
    picture = compute(settings)
    direct = simulate(Block(30 * INCH, 6 * INCH),
                      generators.harmonic(2.0, horizontal=0.3 * G, duration=8.0), cor=0.925)
    (run,) = picture.runs
    assert run.max_abs_theta == direct.max_abs_theta
    assert run.n_impacts == direct.n_impacts
    assert (run.t_overturn == direct.t_overturn
            or (math.isnan(run.t_overturn) and math.isnan(direct.t_overturn)))
    assert picture.numbers[0] == key_numbers(direct, "in")
    assert picture.verdicts == (direct.verdict(),)
    # the trace is theta/alpha at the run's samples; the drawing covers the run
    np.testing.assert_array_equal(picture.traces[0][1], direct.theta / direct.block.alpha)
    assert picture.end == pytest.approx(8.0)


def test_a_record_scaled_to_a_target_pga_has_that_pga():
    settings = Settings(motion="record", record="el-centro-1940-180", target_pga="0.2 g",
                        duration="", record_vertical=False)
    data = scene_data(settings)
    recorded = records.load("el-centro-1940-180", vertical=False)
    scaled = recorded.scaled(data["motion"]["scale"])
    assert np.max(np.abs(scaled.horizontal)) == pytest.approx(0.2 * G, rel=1e-12)
    run = compute(settings).runs[0]
    direct = simulate(Block(30 * INCH, 6 * INCH), scaled, cor=0.925)
    assert (run.max_abs_theta, run.n_impacts) == (direct.max_abs_theta, direct.n_impacts)


@pytest.mark.parametrize("name", list(LESSONS))
def test_each_lesson_runs_the_blocks_of_its_bundled_scene(name):
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import run_scene

    lesson = LESSONS[name]
    picture = compute(lesson.settings)
    bundled = run_scene(load_scene(resolve_scene_path(lesson.scene))).runs
    assert len(picture.runs) == len(bundled) == 2
    for mine, theirs in zip(picture.runs, bundled):
        assert mine.block == theirs.block and mine.cor == theirs.cor
        assert mine.max_abs_theta == theirs.max_abs_theta
        assert mine.n_impacts == theirs.n_impacts


def test_the_lessons_say_what_their_runs_show():
    # (a) the period grows with the amplitude: 4 x the time to the first impact of each
    # block (COR 1, a quarter period) against the exact period of Eq. (2-3)
    from shaketable.core.theory import exact_period

    period = compute(LESSONS["period"].settings)
    quarters = [4 * run.impact_times[0] for run in period.runs]
    block = period.runs[0].block
    for quarter, ratio in zip(quarters, (0.2, 0.8)):
        assert quarter == pytest.approx(exact_period(block, ratio * block.alpha), rel=1e-6)
    assert quarters[1] > 2 * quarters[0]
    # (b) "rocks to twice the angle" with the lower COR (docs/teaching.md: 0.214 and 0.449)
    lower = compute(LESSONS["lower-cor"].settings)
    assert [run.cor for run in lower.runs] == [1.0, 0.93]
    assert lower.runs[1].max_theta_ratio > 2 * lower.runs[0].max_theta_ratio
    # (c) "the small one overturns near 4.3 s; the large one survives"
    small = compute(LESSONS["small-falls"].settings)
    assert small.runs[0].overturned and abs(small.runs[0].t_overturn - 4.3) < 0.05
    assert not small.runs[1].overturned
    assert small.numbers[0]["max |θ|/α"] == "F"
    assert small.runs[1].block.height == pytest.approx(12 * 0.3048)
    assert small.runs[1].block.width == pytest.approx(2.4 * 0.3048)


def test_bad_fields_get_their_own_message():
    settings = Settings(height="-3 in", cor="2", frequency="2")
    messages = check(settings)
    assert set(messages) == {"height", "cor", "frequency"}
    assert "positive" in messages["height"]
    assert "[0, 1]" in messages["cor"]
    assert "no unit" in messages["frequency"]
    with pytest.raises(FieldError) as error:
        compute(replace(Settings(), frequency="2"))
    assert error.value.field == "frequency"
    assert check(Settings()) == {}
    for name, value in (("duration", "500 s"), ("theta0", "2 rad"), ("record_scale", "x"),
                        ("second", "0.5 in")):
        trial = replace(Settings(), **{name: value},
                        compare="size" if name == "second" else "none")
        if name == "record_scale":
            trial = replace(trial, motion="record")
        if name == "second":
            assert check(trial) == {}   # a small second block is allowed
        else:
            assert set(check(trial)) == {name}


def test_the_saved_scene_reproduces_the_page(tmp_path):
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import run_scene

    for settings in (Settings(pulse_shape="half-sine", motion="pulse",
                              pulse_amplitude="-0.45 g", duration="3 s", compare="cor",
                              second="housner"),
                     Settings(motion="pulse", pulse_shape="constant", pulse_amplitude="0.3 g",
                              pulse_length="0.5 s", duration="4 s"),
                     Settings(motion="free", theta0="0.5 alpha", duration="4 s",
                              compare="size", second="60 in")):
        picture = compute(settings)
        path = tmp_path / "scene.toml"
        path.write_text(scene_toml(picture.data), encoding="utf-8")
        again = run_scene(load_scene(path)).runs
        assert [run.max_abs_theta for run in again] == [run.max_abs_theta
                                                         for run in picture.runs]
        assert [run.n_impacts for run in again] == [run.n_impacts for run in picture.runs]
    # Housner's COR of the 30 x 6 in block: 1 - 1.5 sin^2 alpha
    alpha = math.atan2(3.0, 15.0)
    assert scene_data(Settings(cor="housner"))["rocking"]["cor"] == pytest.approx(
        1 - 1.5 * math.sin(alpha) ** 2)


def test_the_drawn_block_rocks_about_its_corner():
    # at theta = alpha the centre of mass is straight above the pivot, at height R
    block = Block(30 * INCH, 6 * INCH)
    theta = np.array([0.0, block.alpha, -block.alpha])
    from shaketable.classroom.model import _centre

    class Run:   # the fields of a rocking result the drawing reads
        t = np.array([0.0, 1.0, 2.0])

    Run.theta, Run.block = theta, block
    angle, x, y = _centre(Run, np.array([0.0, 1.0, 2.0]))
    np.testing.assert_allclose(x, [0.0, -block.b, block.b], atol=1e-15)
    np.testing.assert_allclose(y, [block.h, block.R, block.R], rtol=1e-14)
    corners = block_outlines(block.width, block.height, angle, x, y)
    np.testing.assert_allclose(corners[0, :4], [[-block.b, 0], [block.b, 0],
                                                [block.b, block.height],
                                                [-block.b, block.height]], atol=1e-15)
    # the pivot corner stays on the table: (-b, 0) for theta > 0, (+b, 0) for theta < 0
    np.testing.assert_allclose(corners[1, 0], [-block.b, 0.0], atol=1e-15)
    np.testing.assert_allclose(corners[2, 1], [block.b, 0.0], atol=1e-15)


def test_pitch_adds_the_table_section_and_runs_as_the_lab_does():
    from shaketable.lab.pitch import Pitch
    from shaketable.lab.stage import TableSetup, run_table

    settings = Settings(pitch=True, amplitude="0.15 g", duration="4 s")
    picture = compute(settings)
    assert picture.data["table"]["pitch"]["frequency"] == "12 Hz"
    motion = generators.harmonic(2.0, horizontal=0.15 * G, duration=4.0)
    felt = run_table(motion, TableSetup(pitch=Pitch(12.0, 0.22, seed=1))).felt
    direct = simulate(Block(30 * INCH, 6 * INCH), felt, cor=0.925)
    assert picture.runs[0].max_abs_theta == direct.max_abs_theta
    assert np.any(picture.runs[0].motion.rotation_or_zero != 0.0)   # the pitch is felt


def test_a_picture_compares_by_value_and_the_same_inputs_give_the_same_picture():
    assert compute(Settings()) == compute(Settings())
    assert compute(Settings()) != compute(Settings(cor="0.8"))
