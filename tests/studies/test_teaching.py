"""The teaching gallery (shaketable.studies.teaching): each physics claim against closed forms.

Expected numbers are written out here from the report's equations (not taken from the
code under test); each carries a comment with its source.
"""

import math

import numpy as np
import pytest

import shaketable as st
from shaketable.ground import generators as motions
from shaketable.ground import records
from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import SceneError, Study, load_scene, scene_from_dict
from shaketable.studies import teaching

G = 9.80665  # m/s^2, standard gravity (docs/conventions.md)


def test_period_grows_with_amplitude_eq_2_5_exact_and_engine():
    block = st.Block.from_inches(36, 9)  # the Table 3.1 block
    ratios = [0.1, 0.5, 0.9]
    item = teaching.period_amplitude(block, ratios)
    # Eq. (2-5) written out: T = (4/p) arccosh(1/(1 - theta0/alpha)), p = sqrt(3g/4R)
    R = math.hypot(4.5 * 0.0254, 18 * 0.0254)
    p = math.sqrt(3 * G / (4 * R))
    eq_2_5 = [4 / p * math.acosh(1 / (1 - r)) for r in ratios]
    np.testing.assert_allclose(item.housner_period, eq_2_5, rtol=1e-12)
    # The slender approximation of Eq. 2-5 is within 1 % of the exact period for
    # alpha = 0.245 rad (Fig. 2.3: Eq. 2-5 is slightly short; 0.46 % at most here).
    assert np.all(item.housner_period < item.exact_period)
    np.testing.assert_allclose(item.housner_period, item.exact_period, rtol=0.01)
    # The engine (default rtol, events located on the stepper) gives the exact period of
    # the energy integral; a quarter period x 4 and half a period x 2 agree.
    np.testing.assert_allclose(item.engine_period, item.exact_period, rtol=1e-8)
    np.testing.assert_allclose(2 * item.engine_half_period, item.exact_period, rtol=1e-8)
    # grows with amplitude: more than 6 times from 0.1 alpha to 0.9 alpha (Eq. 2-5:
    # arccosh(10)/arccosh(1/0.9) = 6.4), while the linear oscillator keeps one period
    assert item.exact_period[2] / item.exact_period[0] > 6
    assert item.linear_period == pytest.approx(item.exact_period[1], rel=1e-12)
    frame = item.to_frame()
    assert frame["linear oscillator period [s]"].nunique() == 1


def test_lower_cor_raises_the_peak_under_pacoima_s74w():
    # Section 4.3 (3), Figs. 4.13-4.14: the 6 x 2 ft block under S74W rocks higher at a
    # lower COR. With the bundled record the effect appears at COR 0.93 (about 0.45 of
    # alpha against 0.21 at COR 1; the report's own digitisation gave 0.58 at 0.90
    # against 0.38 at 1.0).
    item = teaching.cor_sweep("6x2ft", "pacoima-dam-s74w", cors=[1.0, 0.95, 0.94, 0.93])
    peaks = dict(zip(item.cors, item.max_theta_ratio))
    assert not np.any(item.overturned)
    assert peaks[0.93] > 1.5 * peaks[1.0]           # a lower COR, a larger peak
    assert peaks[0.94] < peaks[0.95] < peaks[0.93]  # and not monotonic in COR
    assert item.rises_when_cor_drops and item.worst_cor == 0.93
    # the sweep reports what simulate gives for the same inputs
    direct = st.simulate(st.Block.parse("6x2ft"), records.load("pacoima-dam-s74w"),
                         cor=0.93)
    assert peaks[0.93] == direct.max_theta_ratio
    assert item.report_points == ((1.0, 0.38), (0.90, 0.58))  # Tables 4.2 and 4.3


def test_larger_similar_block_rocks_less_and_scaling_law_holds():
    # Section 4.3 (1): "the response of the 15 ft x 3 ft block is always smaller than
    # the response of the 10 ft x 2 ft block" (Tables 4.2-4.3).
    item = teaching.similar_blocks(5.0, heights_ft=[4, 10, 15], cor=0.9)
    assert item.overturned.tolist() == [True, False, False]
    assert item.max_theta_ratio[2] < item.max_theta_ratio[1]
    # Scaling law (Eq. 2-13 in tau = p t): exact up to the solver tolerance (default rtol)
    assert item.scale == pytest.approx(1.5, rel=1e-12)
    assert item.scaling_difference < 1e-8
    assert np.max(np.abs(item.scaling_theta_small)) > 0.3 * item.scaling_blocks[0].alpha


def test_scaling_law_with_a_harmonic_and_time_stretched():
    # Similar blocks with R2 = 4 R1 (p2 = p1 / 2): the 2 Hz input for the small block
    # becomes 1 Hz for the large one, theta2(2 t) = theta1(t).
    small, large = st.Block.from_inches(30, 6), st.Block.from_inches(120, 24)
    motion = motions.harmonic(2.0, horizontal=0.3 * G, duration=3.0, dt=0.005)
    slow = teaching.time_stretched(motion, 2.0)
    np.testing.assert_array_equal(slow.t, 2.0 * motion.t)
    np.testing.assert_array_equal(slow.horizontal, motion.horizontal)
    first = st.simulate(small, motion, cor=0.9)
    second = st.simulate(large, slow, cor=0.9)
    assert first.max_theta_ratio > 0.2
    scale = np.max(np.abs(first.theta))
    assert np.max(np.abs(second.theta - first.theta)) / scale < 1e-8
    assert second.t_start == pytest.approx(2.0 * first.t_start, rel=1e-9)


def test_rocking_onset_follows_eq_2_1():
    block = st.Block.from_inches(30, 6)  # B/H = 0.2
    vertical = np.array([-0.5, -0.25, 0.0, 0.25])
    item = teaching.rocking_onset(block, vertical)
    # Eq. (2-1): u = (B/H) g (1 + v/g), written out
    expected = 0.2 * (1 + vertical)
    np.testing.assert_allclose(item.eq_2_1_g, expected, rtol=1e-12)
    # The engine locates the start at the exact crossing inside the (linear) sample
    # interval, so the measured onset matches Eq. 2-1 to rounding.
    np.testing.assert_allclose(item.engine_onset_g, expected, rtol=1e-9)
    # A downward table acceleration lowers the threshold: half of it at v = -0.5 g
    assert item.engine_onset_g[0] == pytest.approx(0.5 * item.engine_onset_g[2], rel=1e-9)


def test_harmonic_below_threshold_rocks_only_with_the_vertical():
    item = teaching.rocking_onset("30x6in", [0.0])
    # 0.18 g < B/H = 0.2 g: no uplift at all without the vertical (Eq. 2-1)
    assert np.all(item.theta_without_vertical == 0.0)
    # with 0.3 g vertical in phase, Eq. 2-1 first holds where |u| > 0.2 (1 + v/g) with
    # u = 0.18 sin(4 pi t), v = 0.3 sin(4 pi t) [g]: on a fine grid
    t = np.linspace(0, 1, 200_001)
    u, v = 0.18 * np.sin(4 * np.pi * t), 0.3 * np.sin(4 * np.pi * t)
    first = t[np.argmax(np.abs(u) > 0.2 * (1 + v))]
    assert item.t_start_with_vertical == pytest.approx(first, abs=1e-4)
    assert np.max(np.abs(item.theta_with_vertical)) > 0.3


def test_gallery_errors_name_the_parameter():
    with pytest.raises(ValueError, match="unknown teaching item 'wobble'"):
        teaching.run_item("wobble")
    with pytest.raises(ValueError, match="amplitude_ratios"):
        teaching.period_amplitude("36x9in", [0.5, 1.2])
    with pytest.raises(ValueError, match="cors"):
        teaching.cor_sweep("6x2ft", cors=[0.9])
    with pytest.raises(ValueError, match="vertical_g"):
        teaching.rocking_onset("30x6in", [-1.5])
    with pytest.raises(ValueError, match="factor"):
        teaching.time_stretched(motions.harmonic(2, horizontal=0.1 * G, duration=1), -1)
    with pytest.raises(SceneError, match="study.item must be one of"):
        scene_from_dict({"name": "x", "source": "s", "study": {"kind": "teaching",
                                                              "item": "wobble"}}, "x.toml")


def test_teaching_scenes_are_studies_and_plots_render(tmp_path):
    from shaketable.plots.teaching import save_item

    for name in teaching.ITEMS:
        study = load_scene(resolve_scene_path(f"teaching-{name}"))
        assert isinstance(study, Study) and study.kind == "teaching" and study.item == name
    item = teaching.period_amplitude("36x9in", [0.2, 0.6])
    save_item(item, tmp_path / "period.png")
    assert (tmp_path / "period.png").stat().st_size > 10_000
    assert any("times" in line for line in item.highlights())
