"""Ensembles of perturbed copies (shaketable.studies.predictability)."""

import math

import numpy as np
import pytest

from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.api import simulate
from shaketable.studies import predictability as pr


def test_wilson_interval_newcombe_examples():
    # Newcombe, Stat. Med. 17, 857-872 (1998), Table I, method 3 (Wilson score):
    # 81/263 -> 0.2553-0.3662; 15/148 -> 0.0624-0.1605 (four decimals as printed)
    assert pr.wilson_interval(81, 263) == pytest.approx((0.2553, 0.3662), abs=6e-5)
    assert pr.wilson_interval(15, 148) == pytest.approx((0.0624, 0.1605), abs=6e-5)
    # 0 of n: the upper end is z^2 / (n + z^2) in closed form
    z2 = 1.959964 ** 2
    assert pr.wilson_interval(0, 20) == pytest.approx((0.0, z2 / (20 + z2)), abs=1e-12)
    with pytest.raises(ValueError, match="successes"):
        pr.wilson_interval(5, 4)


def test_perturbation_validation_and_draws():
    with pytest.raises(ValueError, match="Perturbation.cor"):
        pr.Perturbation(cor=-0.1)
    drawn = pr.perturbed_members(500, pr.Perturbation(amplitude=0.01, cor=0.02, size=0.03,
                                                      start=0.5), seed=3)
    assert drawn.amplitude[0] == drawn.cor[0] == drawn.height[0] == 1.0
    assert drawn.start[0] == 0.0
    assert np.all(np.abs(drawn.amplitude - 1) <= 0.01)
    assert np.all(np.abs(drawn.cor - 1) <= 0.02)
    assert np.all(np.abs(drawn.width - 1) <= 0.03)
    assert np.all(np.abs(drawn.start) <= 0.5)
    assert np.ptp(drawn.cor) > 0.03   # they do spread over the range


def test_shifted_record_is_the_record_read_later():
    t = np.linspace(0.0, 1.0, 101)
    motion = Motion(t, 2.0 * t, 0.5 * t)        # a ramp: linear interpolation is exact
    moved = pr.shifted(motion, 0.003)
    inner = t <= 1.0 - 0.003
    assert np.allclose(moved.horizontal[inner], 2.0 * (t[inner] + 0.003), atol=1e-14)
    assert np.allclose(moved.vertical[inner], 0.5 * (t[inner] + 0.003), atol=1e-14)


def _pulse_motion():
    t = np.linspace(0.0, 3.0, 601)
    horizontal = np.where(t < 1.0, 4.0 * np.sin(np.pi * t), 0.0)
    return Motion(t, horizontal, name="half-sine 4 m/s^2")


def test_unperturbed_ensemble_is_the_run_repeated():
    block, motion = Block.from_feet(4, 1), _pulse_motion()
    single = simulate(block, motion, cor=0.9)
    result = pr.ensemble(block, motion, cor=0.9, members=8,
                         perturbation=pr.Perturbation(0, 0, 0, 0), horizon_pairs=2,
                         horizon_spread=0.0)
    peaks = result.to_frame()["max_abs_theta [rad]"].to_numpy()
    assert np.all(peaks == peaks[0])
    assert peaks[0] == pytest.approx(single.max_abs_theta, rel=1e-12)
    # max theta/alpha as simulate gives it: NaN for an overturned member (the report's F)
    ratios = result.to_frame()["max_theta_ratio [-]"].to_numpy()
    np.testing.assert_array_equal(ratios, np.full(ratios.size, single.max_theta_ratio))
    assert result.robust
    assert result.p_overturn in (0.0, 1.0)
    assert result.horizon == math.inf       # identical copies never diverge


def test_block_that_never_rocks_is_robust_with_infinite_horizon():
    # 0.05 g is below the 4 x 1 ft block's rocking threshold g tan(alpha) = 0.25 g (Eq. 2-1)
    t = np.linspace(0.0, 2.0, 401)
    motion = Motion(t, 0.05 * 9.80665 * np.sin(2 * np.pi * t), name="small")
    result = pr.ensemble(Block.from_feet(4, 1), motion, cor=0.9, members=20,
                         perturbation=pr.Perturbation.uniform(0.01))
    assert result.robust and result.p_overturn == 0.0
    assert result.summary["P high [-]"] == pytest.approx(pr.wilson_interval(0, 20)[1])
    assert result.horizon == math.inf


def test_pacoima_s74w_2x1_cell_is_fragile():
    # one part in 1e12 flips this Table 4.2 cell; 1e-9 spreads give both verdicts
    from shaketable.studies.report_tables import column_motion

    result = pr.ensemble(Block.from_feet(2, 1), column_motion("pacoima S74W"), cor=1.0,
                         members=60, horizon_pairs=2)
    assert not result.robust
    low, high = result.interval
    assert 0.0 < low < result.p_overturn < high < 1.0
    assert 0.0 < result.horizon < column_motion("pacoima S74W").duration
    assert "fragile" in result.describe()


def test_simulate_ensemble_and_spectrum_from_the_command_line(tmp_path, capsys):
    import json

    from shaketable.cli import main

    assert main(["simulate", "--block", "4x1ft", "--cor", "0.9", "--record",
                 "pacoima-dam-s16e", "--duration", "4s", "--ensemble", "6", "--perturb", "0",
                 "--perturb-cor", "0.01", "--out", str(tmp_path / "sim")]) == 0
    summary = json.loads((tmp_path / "sim" / "ensemble.json").read_text())
    assert summary["members"] == 6 and summary["perturbation [-]"]["cor"] == 0.01
    assert (tmp_path / "sim" / "ensemble.png").exists()
    assert main(["spectrum", "--alpha", "0.25rad", "--p", "2rad/s", "--ratios", "2",
                 "--tolerance", "1e-6", "--out", str(tmp_path / "spec")]) == 0
    import pandas as pd

    bands = pd.read_csv(tmp_path / "spec" / "spectrum.csv", comment="#")
    first = bands[bands["verdict"] == "overturns"]["from a/(g tan alpha) [-]"].min()
    # half-sine, omega/p = 2: 1.8015 (the literature's value; four decimals)
    assert first == pytest.approx(1.8015, abs=5e-5)
    assert "overturns without impact" in capsys.readouterr().out


def test_scene_ensemble_section_is_validated():
    from shaketable.scenes.parse import SceneError, scene_from_dict

    base = {"name": "e", "block": {"height": "4 ft", "width": "1 ft"},
            "motion": {"kind": "record", "name": "pacoima-dam-s16e"}, "rocking": {"cor": 0.9}}
    scene = scene_from_dict({**base, "ensemble": {"members": 50, "perturb_cor": 0.01}})
    assert scene.ensemble == {"members": 50, "perturb_cor": 0.01}
    with pytest.raises(SceneError, match="ensemble.members"):
        scene_from_dict({**base, "ensemble": {"members": 1}})
    with pytest.raises(SceneError, match="unknown key ensemble.spread"):
        scene_from_dict({**base, "ensemble": {"spread": 0.1}})
