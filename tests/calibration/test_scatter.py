"""The COR of a real block (impact-to-impact scatter), warnings that speak, the
calibrated COR carried into prediction, and records as labs export them.

The records are made by ``tests/calibration/lab_records.py``, a generator that uses
nothing of the package (SciPy ``solve_ivp`` of the rocking equation with impact
events, an analog 4-pole 20 Hz filter by ``scipy.signal.lsim``, 50 samples/s, noise,
offset, 12-bit ADC); the truth of each test is what that generator was told.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import shaketable as st
from shaketable.calibration import calibrate, read_record
from shaketable.calibration.peaks import PeakEstimate
from shaketable.calibration.record import FreeRockingRecord
from shaketable.calibration.scatter import cor_scatter
from shaketable.calibration.uncertainty import CalibratedCor, calibrated_ensemble
from shaketable.cli import main
from tests.calibration.lab_records import lab_record

BLOCK = st.Block.parse("30x6in")
INCH = 0.0254


# The tests that read one record's calibration run on one xdist worker (--dist loadgroup),
# which then computes it once; a saving only: any test computes what it reads.
pytestmark = pytest.mark.xdist_group("tests/calibration/test_scatter.py")

_CALIBRATED: dict = {}


def _calibrated(seed, **options):
    """The calibration of lab record ``seed`` and the record (each made once per process:
    a function of the arguments only, which the tests read and never change)."""
    key = (seed, tuple(sorted(options.items())))
    if key not in _CALIBRATED:
        lab = lab_record(seed, **options)
        record = FreeRockingRecord.from_top_displacement(lab.t, lab.displacement_in,
                                                         units="in", name=f"lab {seed}")
        _CALIBRATED[key] = (calibrate(record, BLOCK), lab)
    return _CALIBRATED[key]


# ------------------------------------------------------------------ the scatter model
def _peaks(cors, log_se):
    """A PeakEstimate holding given per-impact CORs (energies E_n = prod of cor^2)."""
    cors = np.asarray(cors, dtype=float)
    energy = np.concatenate([[1.0], np.cumprod(cors**2)])
    per_se = 0.5 * cors * math.sqrt(2) * log_se
    return PeakEstimate(cor=float(np.mean(cors)), cor_interval=(0.0, 1.0),
                        peak_times=np.arange(energy.size, dtype=float), amplitudes=energy,
                        cor_per_impact=cors, cor_per_impact_se=np.full(cors.size, per_se),
                        impact_velocity=np.linspace(1.0, 0.2, cors.size), slope=math.nan,
                        slope_se=math.nan, intercept=float(np.mean(cors)),
                        log_energy_se=np.full(energy.size, log_se))


def test_random_effects_mean_covers_at_the_nominal_rate():
    # 400 blocks of 11 impacts, each impact's COR from N(0.90, 0.02^2) and measured with
    # independent noise on log E (se 0.005): the truth is the distribution's mean 0.90.
    rng = np.random.default_rng(1)
    covered, sigma_covered = [], []
    for _ in range(400):
        cors = rng.normal(0.90, 0.02, 11)
        log_e = np.log(np.concatenate([[1.0], np.cumprod(cors**2)]))
        noisy = np.exp(log_e + rng.normal(0.0, 0.005, log_e.size))
        measured = np.sqrt(noisy[1:] / noisy[:-1])
        model = cor_scatter(_peaks(measured, 0.005))
        covered.append(model.mean_interval[0] <= 0.90 <= model.mean_interval[1])
        sigma_covered.append(model.sigma_interval[0] <= 0.02 <= model.sigma_interval[1])
    # binomial sd of a 95 % coverage on 400 draws: 1.1 %; the band is +-3 sd
    assert 0.915 <= np.mean(covered) <= 0.985
    assert 0.88 <= np.mean(sigma_covered) <= 0.99


def test_random_effects_recovers_sigma_and_finds_none_without_scatter():
    rng = np.random.default_rng(2)
    cors = rng.normal(0.85, 0.03, 400)
    model = cor_scatter(_peaks(cors, 1e-4))
    # 400 draws: the sample sd is within ~3.5 % (1 sd) of 0.03
    assert model.sigma == pytest.approx(0.03, rel=0.12)
    assert model.sigma_interval[0] < 0.03 < model.sigma_interval[1]
    constant = cor_scatter(_peaks(np.full(12, 0.9) + rng.normal(0, 1e-5, 12), 1e-3))
    assert constant.sigma_interval[0] == 0.0 and constant.sigma < 0.005
    assert constant.mean_interval[0] <= 0.9 <= constant.mean_interval[1]


# ------------------------------------------------------------------ warnings both ways
@pytest.mark.parametrize("seed", [20_000, 20_001])
def test_no_warning_on_a_clean_constant_cor_record(seed):
    result, _ = _calibrated(seed, cor=0.85)
    assert result.warnings == () and not any(n.startswith("WARNING") for n in result.notes)
    assert result.cor_interval[0] <= 0.85 <= result.cor_interval[1]
    assert result.scatter.mean_interval[0] <= 0.85 <= result.scatter.mean_interval[1]
    assert result.scatter.sigma_interval[0] == 0.0


def test_scattered_cor_warns_and_the_mean_interval_covers():
    result, lab = _calibrated(20_002, cor=0.90, sigma=0.02)
    # the least-squares interval is +-5e-4 around a block whose impacts scatter by 0.02
    assert "residuals" in result.warning_kinds and "scatter" in result.warning_kinds
    assert result.scatter.mean_interval[0] <= 0.90 <= result.scatter.mean_interval[1]
    assert result.scatter.sigma_interval[0] <= 0.02 <= result.scatter.sigma_interval[1]
    summary = result.summary()
    assert any(note.startswith("WARNING: the COR scatters") for note in summary["notes"])
    assert summary["warning_kinds"] == list(result.warning_kinds)
    assert "WARNING: the residuals are strongly autocorrelated" in result.text()


def test_velocity_dependent_cor_warns():
    result, lab = _calibrated(20_003, cor=0.90, velocity_slope=-0.1)
    assert "velocity" in result.warning_kinds
    assert result.peaks.slope < 0          # the generator's COR falls with the velocity


def test_implausible_filter_and_size_warnings():
    from shaketable.calibration.diagnostics import diagnose

    result, _ = _calibrated(20_000, cor=0.85)
    # the same record claimed to be of a 30 x 5 in block (alpha 17 % small): with that
    # alpha held, the periods need R 20 % below the claimed block's
    wrong = calibrate(result.record, st.Block.parse("30x5in"))
    assert "size" in wrong.warning_kinds
    assert wrong.periods_alpha_held.R < 0.9 * wrong.block.R
    kinds = [kind for kind, _ in diagnose(
        rate=50.0, anti_alias="fit", filter_cutoff=3.7, residual_lag1=0.1, cor=0.9,
        cor_se=1e-4, peaks=None, scatter=None, periods=None)]
    assert kinds == ["filter"]


# ------------------------------------------------------------------ records as labs export them
def _lab_file(tmp_path, header, scale=1.0, name="lab.csv"):
    return lab_record(20_000, cor=0.85).write(tmp_path / name, header=header, time_scale=scale)


@pytest.mark.parametrize("header, scale", [
    ("Time (sec),WP1 Top Disp (in)", 1.0), ("time [ms],WP1 Top Disp (in)", 1e3),
    ("Time (ms),WP1 Top Disp (in)", 1e3), ("Zeit [s],WP1 Top Disp (in)", 1.0),
    ("t [us],WP1 Top Disp (in)", 1e6), ("Time (µs),WP1 Top Disp (in)", 1e6)])
def test_time_units_in_the_header(tmp_path, header, scale):
    lab = lab_record(20_000, cor=0.85)
    record = read_record(_lab_file(tmp_path, header, scale))
    np.testing.assert_allclose(record.t, lab.t, atol=2e-6)     # 6 decimals written
    assert record.rate == pytest.approx(50.0, rel=1e-3)
    # 5 decimals of an inch written
    np.testing.assert_allclose(record.values, lab.displacement_in * INCH, atol=6e-6 * INCH)


def test_units_contradicting_the_header_are_refused(tmp_path):
    path = _lab_file(tmp_path, "Time (sec),WP1 Top Disp (mm)")
    with pytest.raises(ValueError, match=r"--units 'in' contradicts the unit 'mm'.*WP1 Top Disp"):
        read_record(path, units="in")
    assert read_record(path, units="MM").quantity == "top displacement"   # the same unit
    text = tmp_path / "lab.txt"
    text.write_text("time [s]  theta [deg]\n0.0  0.5\n0.02  0.4\n")
    with pytest.raises(ValueError, match=r"--units 'rad' contradicts the unit 'deg'"):
        read_record(text, units="rad")


def test_columns_by_name_or_index(tmp_path):
    lab = lab_record(20_000, cor=0.85)
    path = tmp_path / "two.csv"
    lines = ["Stamp (ms),WP1 Top Disp (in),WP2 Top Disp (in)"] + [
        f"{1e3 * t:.4f},{x:.5f},{2 * x:.5f}" for t, x in zip(lab.t, lab.displacement_in)]
    path.write_text("\n".join(lines) + "\n")
    by_name = read_record(path, time_column="stamp (ms)", column="WP2 Top Disp (in)")
    by_index = read_record(path, time_column=0, column=2)
    np.testing.assert_array_equal(by_name.values, by_index.values)
    np.testing.assert_allclose(by_index.values, 2 * lab.displacement_in * INCH,
                               atol=6e-6 * INCH)
    np.testing.assert_allclose(by_index.t, lab.t, atol=1e-6)
    with pytest.raises(ValueError, match="--time-column: no column 'clock'"):
        read_record(path, time_column="clock", column=1)
    with pytest.raises(ValueError, match="--column 5 but the file has 3 columns"):
        read_record(path, time_column=0, column=5)
    bad = tmp_path / "hours.csv"
    bad.write_text("time [h],theta [rad]\n0,0.1\n1,0.1\n")
    with pytest.raises(ValueError, match=r"time column 'time \[h\]' is in 'h', not a time unit"):
        read_record(bad)


@pytest.mark.usefixtures("figure_drafts")
def test_cli_reads_a_daq_export_and_prints_the_size_with_its_error(tmp_path, capsys):
    path = _lab_file(tmp_path, "Time (ms),WP1 Top Disp (in)", 1e3)
    out = tmp_path / "out"
    assert main(["calibrate", str(path), "--block", "30x6in", "--time-column", "0",
                 "--column", "WP1 Top Disp (in)", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "WARNING" not in printed
    assert "period fit: R = " in printed and " in (standard errors" in printed
    assert "block's mean COR (random effects" in printed
    summary = json.loads((out / "calibration.json").read_text())
    assert summary["warnings"] == [] and summary["period_fit_height_se [m]"] > 0
    # every length in the block's inches: R of 30 x 6 in is sqrt(15^2 + 3^2) = 15.30 in
    assert "(nominal 15.30 in)" in printed and " m," not in printed and " m " not in printed
    assert f"; fit rms {summary['fit rms'] / 0.0254:#.3g} in, " in printed   # JSON: SI
    assert summary["cor_mean_interval [-]"][0] <= 0.85 <= summary["cor_mean_interval [-]"][1]
    assert main(["calibrate", str(path), "--block", "30x6in", "--units", "mm",
                 "--out", str(tmp_path / "o2")]) == 2
    assert "--units 'mm' contradicts the unit 'in'" in capsys.readouterr().err


# ------------------------------------------------------------------ uncertainty into prediction
def test_calibrated_cor_from_json_and_its_draws(tmp_path):
    result, _ = _calibrated(20_002, cor=0.90, sigma=0.02)
    path = tmp_path / "calibration.json"
    result.to_json(path)
    cor = CalibratedCor.from_json(path)
    assert cor.mean == pytest.approx(result.scatter.mean)
    assert cor.sigma == pytest.approx(result.scatter.sigma)
    draws = cor.draws(4000, seed=3)
    assert draws[0] == cor.mean
    # the draws' sd is sqrt(se^2 dof/(dof-2) + sigma^2) (Student t plus normal)
    expected = math.sqrt(cor.mean_se**2 * cor.dof / (cor.dof - 2) + cor.sigma**2)
    assert np.std(draws) == pytest.approx(expected, rel=0.08)
    assert np.std(cor.draws(4000, seed=3, scatter=False)) < np.std(draws)
    broken = tmp_path / "broken.json"
    broken.write_text(json.dumps({"cor [-]": 0.9}))
    with pytest.raises(ValueError, match=r"broken.json: 'cor_se \[-\]' is missing"):
        CalibratedCor.from_json(broken)


def test_simulate_with_a_calibration_file_reports_the_spread(tmp_path, capsys):
    result, _ = _calibrated(20_002, cor=0.90, sigma=0.02)
    path = tmp_path / "calibration.json"
    result.to_json(path)
    out = tmp_path / "sim"
    assert main(["simulate", "--block", "30x6in", "--cor", str(path), "--record",
                 "pacoima-dam-s16e", "--scale", "0.3", "--ensemble", "24", "--duration", "6s",
                 "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "P(overturn) = " in printed and "Wilson 95 %" in printed and "5-95 %" in printed
    summary = json.loads((out / "ensemble.json").read_text())
    assert summary["members"] == 24
    assert summary["cor p05 [-]"] < result.scatter.mean < summary["cor p95 [-]"]
    assert summary["P low [-]"] <= summary["P(overturn) [-]"] <= summary["P high [-]"]
    # member 0 is the mean COR: the same run as a plain simulate with that COR
    from shaketable.ground import records

    motion = records.load("pacoima-dam-s16e").scaled(0.3)
    plain = st.simulate(BLOCK, motion, cor=result.scatter.mean, duration=6.0)
    ensemble = calibrated_ensemble(BLOCK, motion, CalibratedCor.from_json(path), members=4,
                                   duration=6.0)
    assert ensemble.members["max_theta_ratio [-]"].iloc[0] == pytest.approx(
        plain.max_theta_ratio, rel=1e-6, nan_ok=True)


@pytest.mark.usefixtures("figure_drafts")
def test_scene_takes_a_calibration_file(tmp_path, capsys):
    from shaketable.scenes.parse import SceneError, load_scene

    (tmp_path / "lab").mkdir()
    # a calibration.json as `shaketable calibrate` writes it (the keys CalibratedCor reads)
    (tmp_path / "lab" / "calibration.json").write_text(json.dumps({
        "cor [-]": 0.905, "cor_se [-]": 1e-4, "cor_mean [-]": 0.90, "cor_mean_se [-]": 0.006,
        "cor_mean_dof": 10, "cor_scatter_sigma [-]": 0.02}))
    scene = tmp_path / "scene.toml"
    scene.write_text('name = "calibrated"\n[block]\nsize = "30x6in"\n'
                     '[motion]\nkind = "record"\nname = "pacoima-dam-s16e"\nscale = 0.3\n'
                     '[rocking]\ncor = "lab/calibration.json"\nduration = "6 s"\n')
    parsed = load_scene(scene)
    assert parsed.cors == (0.90,) and parsed.calibrated_cor.sigma == 0.02
    out = tmp_path / "out"
    assert main(["run", str(scene), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "calibrated COR 0.9000 (95 % interval" in printed and "P(overturn) = " in printed
    summary = json.loads((out / "summary.json").read_text())
    ensemble = summary["calibrated COR ensemble"]
    assert ensemble["members"] == 200 and ensemble["cor p05 [-]"] < 0.90 < ensemble["cor p95 [-]"]
    scene.write_text(scene.read_text().replace("lab/calibration.json", "lab/missing.json"))
    with pytest.raises(SceneError, match=r"rocking.cor 'lab/missing.json'.*no such calibration"):
        load_scene(scene)
