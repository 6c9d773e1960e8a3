"""Hardening, third pass: each class of the third audit as tests that failed before the fix.

Classes: (1) no write through a planted link, nothing created outside the output folder;
(2) a run that ends before its motion says so (console, ``summary.json``, exit 1);
(3) options that would be ignored are refused naming both; (4) a calibration used for
another block, a tampered calibration; (5) target spectra and intensity levels; (6) every
input of a sweep checked before its first chunk; (7) record suites; (8) ``risk`` and the
fragility and risk functions; (9) resources bounded before any work; (10) messages of the
API entry points; (11) resume, a failing write, a CSV fault on its line.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pytest

from shaketable.core.files import OutputPathError, folder_lock
from tests.test_bad_input import SWEEP, _replace, run_cli

TINY_SWEEP = _replace(SWEEP, '[rocking]\ncor = [0.9]',
                      '[rocking]\ncor = [0.9]\nduration = "1 s"') + (
    '[intensity]\npga = ["0.2 g", "0.3 g"]\n[run]\nchunk_size = 1\n')


def _outside(tmp_path) -> Path:
    victim = tmp_path / "outside" / "victim.txt"
    victim.parent.mkdir()
    victim.write_text("keep me")
    return victim


# ----------------------------------------------------------------- 1. planted links
@pytest.mark.parametrize("kind", ["symlink", "dangling", "hardlink"])
def test_the_lock_file_is_never_opened_through_a_link(tmp_path, kind):
    out = tmp_path / "out"
    out.mkdir()
    victim = _outside(tmp_path)
    lock = out / ".shaketable.lock"
    if kind == "symlink":
        lock.symlink_to(victim)
    elif kind == "dangling":
        lock.symlink_to(tmp_path / "outside" / "created.txt")
    else:
        os.link(victim, lock)
    with pytest.raises(OutputPathError, match="link"):
        with folder_lock(out):
            pass
    assert victim.read_text() == "keep me"
    assert not (tmp_path / "outside" / "created.txt").exists()


def test_examples_force_replaces_a_planted_link_never_its_target(tmp_path):
    out = tmp_path / "ex"
    out.mkdir()
    victim = _outside(tmp_path)
    (out / "plot_tutorial_rock_a_block.py").symlink_to(victim)
    (out / "README.rst").symlink_to(tmp_path / "outside" / "created.rst")   # dangling
    status, _, err = run_cli(["examples", "--out", out, "--force", "-q"], tmp_path)
    assert status == 0, err
    assert victim.read_text() == "keep me"
    assert not (tmp_path / "outside" / "created.rst").exists()
    assert not (out / "plot_tutorial_rock_a_block.py").is_symlink()
    assert "import" in (out / "plot_tutorial_rock_a_block.py").read_text()


def test_reproduce_writes_its_tables_by_rename_not_through_a_link(tmp_path):
    from shaketable.studies.overturning_spectrum import OverturningSpectrum

    # the one writer of a band table that opened its file in place
    victim = _outside(tmp_path)
    link = tmp_path / "spectrum.csv"
    link.symlink_to(victim)
    import pandas as pd

    from shaketable.core.geometry import Block

    spectrum = OverturningSpectrum(block=Block(height=1.0, width=0.25), cor=0.9,
                                   scan_step=0.01, tolerance=1e-6, ceiling=10.0,
                                   bands=pd.DataFrame({"a": [1.0]}), flags=[])
    spectrum.to_csv(link)
    assert victim.read_text() == "keep me"
    assert not link.is_symlink() and "overturning spectrum" in link.read_text()


def test_a_planted_subfolder_link_is_refused_and_nothing_is_written_outside(tmp_path):
    (tmp_path / "w.toml").write_text(TINY_SWEEP)
    out = tmp_path / "out"
    out.mkdir()
    (tmp_path / "outside").mkdir()
    (out / "parts").symlink_to(tmp_path / "outside")
    status, _, err = run_cli(["sweep", "w.toml", "--out", out, "-q"], tmp_path)
    assert status == 2 and "symbolic link" in err, err
    assert list((tmp_path / "outside").iterdir()) == []


def test_reproduce_refuses_a_scene_folder_that_is_a_link(tmp_path):
    from shaketable.reproduce import _study_section
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.studies.comparison import ComparisonTally

    (tmp_path / "outside").mkdir()
    out = tmp_path / "out"
    out.mkdir()
    study = load_scene(resolve_scene_path("fig-2-3"))
    (out / study.name).symlink_to(tmp_path / "outside")
    with pytest.raises(OutputPathError, match="symbolic link"):
        _study_section(study, out, ComparisonTally())
    assert list((tmp_path / "outside").iterdir()) == []


# ----------------------------------------------------------------- 11. resume, writes
def test_resume_removes_every_half_written_part(tmp_path):
    from shaketable import sweeps

    spec = tmp_path / "w.toml"
    spec.write_text(TINY_SWEEP)
    out = tmp_path / "out"
    outcome = sweeps.run_sweep(spec, out, progress=False, max_chunks=1, fmt="csv")
    assert not outcome.complete
    leftovers = [out / "parts" / ".part-000001.3f9a01bc.csv",
                 out / "parts" / ".part-000001.tmp-3f9a01bc.csv"]
    for path in leftovers:
        path.write_text("half")
    outcome = sweeps.run_sweep(spec, out, progress=False, resume=True, fmt="csv")
    assert outcome.complete
    assert not any(path.exists() for path in leftovers)


def test_a_part_that_cannot_be_written_stops_the_sweep_with_exit_1(tmp_path, monkeypatch):
    from shaketable.sweeps import execute, store

    written = []
    real = store.write_csv

    def read_only_after_one(path, frame, **options):
        if written:
            raise PermissionError(30, "Read-only file system", str(path))
        written.append(path)
        return real(path, frame, **options)

    monkeypatch.setattr(store, "write_csv", read_only_after_one)
    monkeypatch.setattr(execute, "parquet_available", lambda: False)
    (tmp_path / "w.toml").write_text(TINY_SWEEP)
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "-q"], tmp_path)
    assert status == 1, err
    assert "part-000001" in err and "Read-only" in err and "--resume" in err, err


def test_a_csv_with_minus_inf_names_its_line(tmp_path):
    rows = "".join(f"{0.01 * i:.2f},{0.001 * (i % 7)}\n" for i in range(2000))
    lines = ("time [s],acceleration [g]\n" + rows).splitlines()
    lines[78] = "0.77,-inf"            # line 79 of the file
    (tmp_path / "r.csv").write_text("\n".join(lines) + "\n")
    status, _, err = run_cli(["simulate", "--block", "4x1ft", "--cor", "0.9", "--record",
                              "r.csv", "--out", "o", "-q"], tmp_path)
    assert status == 2, err
    assert "line 79" in err, err


# ----------------------------------------------------------------- 2. early stops
@pytest.mark.usefixtures("figure_drafts")
def test_a_run_that_stops_early_says_so_and_exits_1(tmp_path):
    # A vertical harmonic of 1.5 g at 2 Hz reaches -g when sin(4 pi t) = -2/3, at
    # t = (pi + asin(2/3)) / (4 pi) = 0.3081 s: the rocking model stops there (airborne);
    # the motion is sampled and linear between samples, which moves the crossing by < 1 ms.
    status, out, err = run_cli(["simulate", "--block", "30x6in", "--cor", "0.9", "--harmonic",
                                "2Hz,0.5g,1.5g", "--duration", "3s", "--history", "none",
                                "--out", "o"], tmp_path)
    assert status == 1, err
    assert "stopped at 0.308" in err and "airborne" in err, err
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["stopped early"] is True and summary["status"] == "airborne"
    expected = (math.pi + math.asin(2.0 / 3.0)) / (4.0 * math.pi)
    assert abs(summary["stopped at [s]"] - expected) < 1e-3
    assert "airborne" in summary["stop reason"]


def test_a_rocking_run_that_leaves_the_ground_is_an_early_stop(tmp_path):
    import numpy as np

    import shaketable as st
    from shaketable.models.stops import early_stop, stop_summary

    t = np.arange(0.0, 2.0, 0.01)
    motion = st.Motion(t=t, horizontal=np.zeros_like(t),
                       vertical=np.where(t > 0.5, -1.5 * 9.80665, 0.0))
    result = st.simulate(st.Block.parse("30x6in"), motion, cor=0.9, theta0=0.05)
    assert result.status == "airborne"
    assert "left the ground" in early_stop(result)
    assert stop_summary(result)["stopped early"] is True
    free = st.simulate(st.Block.parse("30x6in"), None, cor=0.9, theta0=0.05, duration=1.0)
    assert early_stop(free) is None and stop_summary(free)["stopped early"] is False


# ----------------------------------------------------------------- 3. ignored options
@pytest.mark.parametrize("extra, both", [
    (["--friction", "0.3", "--method", "reference"], ("--method", "--friction")),
    (["--friction", "0.3", "--subdivisions", "8"], ("--subdivisions", "--friction")),
    (["--subdivisions", "8"], ("--subdivisions", "--method fast")),
    (["--perturb-cor", "0.01"], ("--perturb-cor", "--ensemble")),
    (["--horizon-threshold", "0.01"], ("--horizon-threshold", "--ensemble")),
    (["--seed", "3"], ("--seed", "--ensemble")),
    (["--ensemble", "4", "--history", "full", "--pulse", "half-sine,0.1g,0.2s"],
     ("--history", "--ensemble")),
    (["--ensemble", "4"], ("--ensemble", "--record")),
])
def test_options_another_model_would_ignore_are_refused_naming_both(tmp_path, extra, both):
    status, _, err = run_cli(["simulate", "--block", "30x6in", "--cor", "0.9", "--theta0",
                              "0.5alpha", "--duration", "1s", "--out", "o", *extra], tmp_path)
    assert status == 2, err
    assert all(option in err for option in both), err
    assert not (tmp_path / "o").exists()


def test_friction_with_a_calibration_file_is_refused_naming_both(tmp_path):
    (tmp_path / "calibration.json").write_text("{}")
    status, _, err = run_cli(["simulate", "--block", "30x6in", "--cor", "calibration.json",
                              "--friction", "0.3", "--out", "o"], tmp_path)
    assert status == 2 and "--friction" in err and "calibration.json" in err, err


# ----------------------------------------------------------------- 4. calibrations
CALIBRATION = {"cor_mean [-]": 0.91, "cor_mean_se [-]": 0.006, "cor_mean_dof": 11,
               "cor_scatter_sigma [-]": 0.01, "cor [-]": 0.91, "cor_se [-]": 0.0001,
               "block_height [m]": 0.762, "block_width [m]": 0.1524}


@pytest.mark.parametrize("block, warned", [("16x4ft", True), ("30x6in", False)])
def test_a_calibration_of_another_block_is_named_with_both_sizes(tmp_path, block, warned):
    (tmp_path / "calibration.json").write_text(json.dumps(CALIBRATION))
    status, _, err = run_cli(["simulate", "--block", block, "--cor", "calibration.json",
                              "--pulse", "half-sine,0.1g,0.2s", "--duration", "1s",
                              "--ensemble", "3", "--out", "o"], tmp_path)
    assert status == 0, err
    assert ("30 x 6 in" in err and "16 x 4 ft" in err) is warned, err


@pytest.mark.parametrize("key, value, fragment", [
    ("cor_mean_dof", 1e300, "'cor_mean_dof'"), ("cor_mean_dof", float("nan"), "'cor_mean_dof'"),
    ("cor_mean_dof", 2.5, "'cor_mean_dof'"), ("cor_mean_dof", -3, "'cor_mean_dof'"),
    ("cor_mean_se [-]", 1e300, "mean_se"), ("block_width [m]", -1.0, "'block_width [m]'"),
    ("cor_scatter_sigma [-]", None, "'cor_scatter_sigma [-]'")])
def test_a_tampered_calibration_is_a_clear_error_naming_the_key(tmp_path, key, value, fragment):
    from shaketable.calibration.uncertainty import CalibratedCor

    data = dict(CALIBRATION)
    if value is None:
        del data[key]
    else:
        data[key] = value
    (tmp_path / "calibration.json").write_text(json.dumps(data))
    with pytest.raises(ValueError, match="calibration.json") as error:
        CalibratedCor.from_json(tmp_path / "calibration.json")
    assert fragment in str(error.value)
    status, _, err = run_cli(["simulate", "--block", "30x6in", "--cor", "calibration.json",
                              "--out", "o"], tmp_path)
    assert status == 2 and fragment in err and "internal" not in err, err


# ----------------------------------------------------------------- 5. target spectra, levels
SPECTRUM_SPEC = """name = "target"
[blocks]
width = ["1 ft"]
aspect = [4]
[rocking]
cor = [0.9]
duration = "1 s"
[[records]]
name = "el-centro-chopra"
[intensity]
{intensity}
"""


def _spectrum_spec(tmp_path, spectrum_text, intensity='spectrum = "target.csv"'):
    from shaketable import sweeps

    (tmp_path / "target.csv").write_text(spectrum_text)
    (tmp_path / "s.toml").write_text(SPECTRUM_SPEC.format(intensity=intensity))
    return sweeps.load_spec(tmp_path / "s.toml")


ROWS = "0.1, 0.5\n0.5, 0.9\n1.0, 0.6\n3.0, 0.2\n"


def test_a_spectrum_header_in_ms_and_cm_s2_is_read_in_its_units(tmp_path):
    from shaketable.core.constants import G

    in_g = _spectrum_spec(tmp_path, "period [s], sa [g]\n" + ROWS).measures.spectrum
    converted = "".join(f"{1000 * float(t)}, {float(sa) * G * 100}\n"
                        for t, sa in (row.split(",") for row in ROWS.splitlines()))
    in_ms = _spectrum_spec(tmp_path, "period [ms], sa [cm/s^2]\n" + converted).measures.spectrum
    import numpy as np

    np.testing.assert_allclose(np.array(in_ms), np.array(in_g), rtol=1e-12)
    assert in_g[0] == pytest.approx((0.1, 0.5 * G))


@pytest.mark.parametrize("text, fragment", [
    (ROWS, "no header"),                                         # the first row is not lost
    ("period, sa\n" + ROWS, "units"),                            # a header without units
    ("period [s], sa [furlong]\n" + ROWS, "units"),
    ("period [s], sa [g]\n0.1, 1e300\n3.0, 0.2\n", "Sa"),        # beyond any earthquake
    ("period [s], sa [g]\n0.5, 0.9\n1.0, 0.6\n", "covers 0.5 to 1 s"),   # would extrapolate
])
def test_a_spectrum_that_cannot_be_read_safely_is_refused(tmp_path, text, fragment):
    from shaketable import sweeps

    with pytest.raises(sweeps.SweepError, match="target.csv|s.toml") as error:
        _spectrum_spec(tmp_path, text)
    assert fragment in str(error.value)


@pytest.mark.parametrize("intensity, fragment", [
    ('pga = ["1e300 g"]', "beyond any earthquake"),
    ('pga = ["0.3 g", "0.3 g"]', "more than once"),
    ('measure = "pgv"\nlevels = ["1e300 m/s"]', "beyond any earthquake"),
    ('scale = [1e300]', "beyond any earthquake"),
    ('measure = "sa"\nperiod = "1000 s"\nlevels = ["1 g"]', "intensity.period"),
])
def test_absurd_or_repeated_levels_are_refused(tmp_path, intensity, fragment):
    from shaketable import sweeps

    with pytest.raises(sweeps.SweepError, match="intensity") as error:
        _spectrum_spec(tmp_path, "period [s], sa [g]\n" + ROWS, intensity)
    assert fragment in str(error.value)


# ----------------------------------------------------------------- 6, 7. sweep inputs, suites
SUITE_SPEC = """name = "suite"
[blocks]
width = ["1 ft"]
aspect = [4]
[rocking]
cor = [0.9]
[[records]]
folder = "suite"
pattern = "*.csv"
units = "g"
[intensity]
pga = ["0.2 g"]
[run]
chunk_size = 1
"""


def _suite(tmp_path, files: dict):
    folder = tmp_path / "suite"
    folder.mkdir()
    for name, text in files.items():
        (folder / name).write_text(text)
    (tmp_path / "s.toml").write_text(SUITE_SPEC)
    return folder


GOOD = "time [s],acceleration [g]\n" + "".join(f"{0.01 * i:.2f},{0.1 * (-1) ** i}\n"
                                               for i in range(100))


@pytest.mark.parametrize("bad", [
    "time [s],acceleration [g]\n" + "".join(f"{0.01 * i:.2f},0\n" for i in range(100)),
    "this is not a record\n",
])
def test_every_record_is_checked_before_the_first_chunk(tmp_path, bad):
    from shaketable import sweeps

    folder = _suite(tmp_path, {"a.csv": GOOD, "z.csv": bad})
    with pytest.raises(sweeps.SweepError, match="z.csv") as error:
        sweeps.run_sweep(tmp_path / "s.toml", tmp_path / "out", progress=False)
    assert "nothing was run" in str(error.value)
    assert not (tmp_path / "out" / "manifest.json").exists()
    (folder / "z.csv").unlink()   # the corrected suite runs into the same folder
    assert sweeps.run_sweep(tmp_path / "s.toml", tmp_path / "out", progress=False).complete


def test_a_link_loop_in_a_suite_is_named_not_dropped(tmp_path):
    folder = _suite(tmp_path, {"a.csv": GOOD})
    (folder / "loop.csv").symlink_to(folder / "loop.csv")
    status, _, err = run_cli(["sweep", "s.toml", "--out", "out", "-q"], tmp_path)
    assert status == 2 and "loop.csv" in err, err
    assert not (tmp_path / "out").exists() or not (tmp_path / "out" / "manifest.json").exists()


# ----------------------------------------------------------------- 9. resources
def test_a_grid_of_too_many_chunks_is_refused_before_any_work(tmp_path):
    spec = _replace(TINY_SWEEP, '[[records]]\nname = "pacoima-dam-s16e"',
                    '[[records]]\npreset = "B-1"\nseeds = 100000\nduration = "1 s"')
    spec = _replace(spec, 'pga = ["0.2 g", "0.3 g"]',
                    "pga = [" + ", ".join(f'"{0.01 * k:.2f} g"' for k in range(1, 21)) + "]")
    (tmp_path / "w.toml").write_text(spec)   # 2,000,000 runs in chunks of 1
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "-q"], tmp_path)
    assert status == 2 and "run.chunk_size" in err and "1,000,000" in err, err
    assert not (tmp_path / "out").exists()


# ----------------------------------------------------------------- 8. risk, 41.5 interval
def _fit():
    from shaketable.sweeps.fragility import FragilityFit

    return FragilityFit(median=0.5, beta=0.3, n_runs=10, n_overturned=5)


def _hazard(**changes):
    from shaketable.sweeps.risk import HazardCurve

    values = dict(im=(0.05, 0.5, 5.0), rate=(1e-2, 1e-4, 1e-6), measure="pgv",
                  column="pgv [m/s]")
    values.update(changes)
    return HazardCurve(**values)


@pytest.mark.parametrize("changes, error, fragment", [
    ({"rate": (1e-2, 1e-1, 1e-6)}, ValueError, "decrease"),
    ({"im": (0.5, 0.05, 5.0)}, ValueError, "increase"),
    ({"im": (1e-300, 0.5, 1e300)}, ValueError, "decades"),
    ({"rate": (1e300, 1e-4, 1e-6)}, ValueError, "annual rates"),
    ({"im": (0.05, float("nan"), 5.0)}, ValueError, "finite"),
    ({"im": "0.05"}, TypeError, "HazardCurve.im"),
    ({"measure": None}, TypeError, "HazardCurve.measure"),
])
def test_a_hazard_curve_built_in_python_gets_the_file_checks(changes, error, fragment):
    with pytest.raises(error, match=fragment):
        _hazard(**changes)


@pytest.mark.parametrize("call, error, fragment", [
    (lambda r: r.overturning_rate(None, _hazard()), TypeError, "fragility"),
    (lambda r: r.overturning_rate(_fit(), _hazard(), years=True), TypeError, "years"),
    (lambda r: r.overturning_rate(_fit(), _hazard(), years=-5), ValueError, "years"),
    (lambda r: r.overturning_rate(_fit(), _hazard(), points_per_decade=10**9), ValueError,
     "points_per_decade"),
    (lambda r: r.overturning_rate(_fit(), "hazard.csv"), TypeError, "hazard"),
    (lambda r: r.design_life_probability("1", 50), TypeError, "rate"),
    (lambda r: r.design_life_probability(1e-3, float("inf")), ValueError, "years"),
])
def test_risk_functions_name_the_bad_parameter(call, error, fragment):
    from shaketable.sweeps import risk

    with pytest.raises(error, match=fragment):
        call(risk)


@pytest.mark.parametrize("kwargs, error, fragment", [
    ({"beta": -0.3}, ValueError, "beta"), ({"median": None}, TypeError, "median"),
    ({"confidence": 2.0}, ValueError, "confidence"), ({"n_runs": -1}, ValueError, "n_runs"),
])
def test_a_fragility_built_by_hand_is_checked(kwargs, error, fragment):
    from shaketable.sweeps.fragility import FragilityFit

    with pytest.raises(error, match=fragment):
        FragilityFit(**{"median": 0.5, "beta": 0.3, "n_runs": 10, "n_overturned": 5, **kwargs})


@pytest.mark.parametrize("call, error, fragment", [
    (lambda f: f(None, [True, False]), TypeError, "im"),
    (lambda f: f([0.1, 0.2], ["yes", "no"]), TypeError, "overturned"),
    (lambda f: f([0.1, 0.2, 0.3], [0, 1, 2]), ValueError, "overturned"),
    (lambda f: f([0.1, 0.2, 0.3], [0, 1, 0], confidence=True), ValueError, "confidence"),
])
def test_fragility_fit_names_the_bad_parameter(call, error, fragment):
    from shaketable.sweeps.fragility import fragility_fit

    with pytest.raises(error, match=fragment):
        call(fragility_fit)


def test_a_hazard_curve_that_is_not_utf8_is_named_with_its_line(tmp_path):
    from shaketable.sweeps.risk import read_hazard_curve

    path = tmp_path / "hazard.csv"
    path.write_bytes(b"# site \xe9\npgv [m/s], annual_rate [1/yr]\n0.1, 1e-2\n1.0, 1e-4\n")
    with pytest.raises(ValueError, match=r"hazard.csv, line 1: not UTF-8"):
        read_hazard_curve(path)


def test_the_rate_interval_is_the_range_over_the_fits_likelihood_region():
    # independent check: lambda at the corners of the fit's own profile intervals of
    # median and beta bounds the interval from outside (the likelihood region lies inside
    # that rectangle), and the interval holds the point estimate
    import numpy as np

    from shaketable.sweeps.fragility import FragilityFit, fragility_fit
    from shaketable.sweeps.risk import overturning_rate

    rng = np.random.default_rng(4)
    levels = np.repeat([0.2, 0.3, 0.4, 0.5, 0.6, 0.8], 12)
    from scipy.stats import norm

    overturned = rng.random(levels.size) < norm.cdf(np.log(levels / 0.45) / 0.35)
    fit = fragility_fit(levels, overturned, measure="pgv [m/s]")
    hazard = _hazard()
    result = overturning_rate(fit, hazard)
    low, high = result.rate_interval
    assert low < result.rate < high
    corners = [overturning_rate(FragilityFit(median=m, beta=b, n_runs=1, n_overturned=1),
                                hazard, interval=False).rate
               for m in fit.median_interval for b in fit.beta_interval]
    assert min(corners) <= low and high <= max(corners)
    assert result.probability_interval[0] < result.probability < result.probability_interval[1]
    assert "interval" in result.summary() and result.confidence == 0.95


def test_the_region_search_stays_finite_from_a_point_that_is_not_the_fits_best():
    # the assessment evaluates lambda with the fit's median moved to an end of its interval
    # (beta kept): from there the likelihood region is not centred, and its boundary
    # search along a steep direction must stop without overflowing exp() (OverflowError);
    # every boundary point must be finite and the interval must hold the rate
    from dataclasses import replace

    import numpy as np

    from shaketable.sweeps.fragility import fragility_fit, region_boundary
    from shaketable.sweeps.risk import overturning_rate

    levels = np.repeat([0.3, 0.6, 0.9, 1.2], 4)          # 4 records x 4 levels, few data
    overturned = np.array([False] * 9 + [True] * 7)
    fit = fragility_fit(levels, overturned, measure="pgv [m/s]")
    hazard = _hazard()
    for median in fit.median_interval:
        moved = replace(fit, median=median)
        points = region_boundary(moved, 96)
        assert all(np.isfinite(m) and np.isfinite(b) and m > 0 and b > 0 for m, b in points)
        result = overturning_rate(moved, hazard)
        low, high = result.rate_interval
        assert np.isfinite(low) and np.isfinite(high) and low <= result.rate <= high


def _risk_sweep(tmp_path, levels, runs):
    folder = tmp_path / "sweep"
    (folder / "parts").mkdir(parents=True)
    import pandas as pd

    overturned = [level > (0.45 if k % 3 else 0.65) for k, level in enumerate(levels)]
    table = pd.DataFrame({"run": range(len(levels)), "record": [f"r{k % 3}" for k in
                                                                 range(len(levels))],
                          "seed": pd.array([None] * len(levels), dtype="Int64"),
                          "block": "24 x 6 in", "cor [-]": 0.9, "status": "completed",
                          "pgv [m/s]": levels, "overturned": overturned})
    table.to_csv(folder / "parts" / "part-000000.csv", index=False)
    (folder / "manifest.json").write_text(json.dumps({"format": "csv", "n_chunks": 3,
                                                      "n_runs": runs}))
    return folder


def test_risk_warns_of_an_unfinished_sweep_and_a_small_suite(tmp_path):
    levels = [0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9] * 2
    folder = _risk_sweep(tmp_path, levels, runs=48)
    status, out, err = run_cli(["risk", folder, "--hazard", "example"], tmp_path)
    assert status == 0, err
    assert "unfinished sweep (16 of 48 runs" in err, err
    assert "3 ground motion(s)" in err and "interval" in out, (out, err)


def test_risk_exits_1_when_no_rate_can_be_given_and_checks_the_figure_first(tmp_path):
    folder = _risk_sweep(tmp_path, [0.2, 0.3, 0.4, 0.5] * 2, runs=8)
    hazard = tmp_path / "pga.csv"   # the sweep's PGV runs all far below this PGA curve
    hazard.write_text("pgv [m/s], annual_rate [1/yr]\n1, 1e-3\n10, 1e-5\n")
    import pandas as pd

    part = folder / "parts" / "part-000000.csv"
    pd.read_csv(part).assign(overturned=False).to_csv(part, index=False)
    status, _, err = run_cli(["risk", folder, "--hazard", hazard], tmp_path)
    assert status == 1 and "no rate" in err, err
    status, _, err = run_cli(["risk", folder, "--hazard", hazard, "--figure",
                              tmp_path / "risk.txt"], tmp_path)
    assert status == 2 and "--figure" in err, err


@pytest.mark.parametrize("option, value", [("--dpi", "100000"), ("--fps", "1e-9"),
                                           ("--fps", "1e9"), ("--dpi", "0.001")])
def test_animate_bounds_dpi_and_fps_before_any_work(tmp_path, option, value):
    status, _, err = run_cli(["animate", "fig-3-4", "--out", "a.gif", option, value],
                             tmp_path)
    assert status == 2 and option in err and "from" in err, err
    assert not (tmp_path / "a.gif").exists()


def test_an_ensemble_too_large_to_draw_is_refused_naming_the_option(tmp_path):
    status, _, err = run_cli(["simulate", "--block", "30x6in", "--cor", "0.9", "--record",
                              "pacoima-dam-s16e", "--ensemble", "1000000000", "--out", "o"],
                             tmp_path)
    assert status == 2 and "--ensemble" in err and "1,000,000" in err, err
    from shaketable.core.ensemble import Perturbation, perturbed_members

    with pytest.raises(ValueError, match="members must be an integer >= 2 .at most 1,000,000"):
        perturbed_members(10**9, Perturbation())


def test_the_animation_functions_bound_dpi_and_fps():
    from shaketable.plots.animation import _size, frame_times

    with pytest.raises(ValueError, match="dpi must be from"):
        _size((320, 180), 1e5)
    with pytest.raises(ValueError, match="fps must be from"):
        frame_times(0.0, 1.0, fps=1e-9, speed=1.0)


# ----------------------------------------------------------------- 10. messages
@pytest.mark.parametrize("extra, fragment", [
    (["--method", "linear", "--cor", "2"], "--cor must be"),
    (["--method", "linear", "--scan-step", "0"], "--scan-step must be"),
    (["--method", "linear", "--ceiling", "0.5"], "--ceiling must be"),
    (["--method", "linear", "--alpha", "1.5rad"], "--cor 'housner'"),
    (["--method", "linear", "--compare-linear"], "--compare-linear"),
    (["--method", "linear", "--scan-step", "1e-9", "--tolerance", "1e-12"], "--scan-step"),
])
def test_spectrum_refusals_name_the_options(tmp_path, extra, fragment):
    argv = ["spectrum", "--alpha", "0.1rad", "--p", "2rad/s", "--ratios", "4", "--out", "o"]
    if "--alpha" in extra:
        argv[2] = extra[extra.index("--alpha") + 1]
        extra = [item for k, item in enumerate(extra)
                 if item != "--alpha" and (k == 0 or extra[k - 1] != "--alpha")]
    status, _, err = run_cli(argv + extra, tmp_path)
    assert status == 2 and fragment in err, err
    assert "Case." not in err and "Number of samples" not in err, err


@pytest.mark.parametrize("call, error, fragment", [
    (lambda f, b, m, F: f(None, m, F(0.3), 0.9), TypeError, "blocks"),
    (lambda f, b, m, F: f("30x6in", m, F(0.3), 0.9), TypeError, "blocks"),
    (lambda f, b, m, F: f(b, m, 0.3, 0.9), TypeError, "frictions"),
    (lambda f, b, m, F: f(b, m, F(0.3), None), TypeError, "cors"),
    (lambda f, b, m, F: f(b, m, F(0.3), []), ValueError, "cors is empty"),
    (lambda f, b, m, F: f([], m, F(0.3), 0.9), ValueError, "blocks is empty"),
])
def test_simulate_many_planar_names_the_bad_parameter(call, error, fragment):
    import shaketable as st
    from shaketable.models.planar.batch import simulate_many_planar
    from shaketable.models.sliding.result import Friction

    with pytest.raises(error, match=fragment):
        call(simulate_many_planar, st.Block.parse("30x6in"), st.Motion.at_rest(0.5), Friction)


@pytest.mark.parametrize("call, error, fragment", [
    (lambda C, e, b, m: C(0.9, 0.01, 5, 0.0, 1), TypeError, "source"),
    (lambda C, e, b, m: C(0.9, 0.01, 10**12), ValueError, "dof"),
    (lambda C, e, b, m: C(0.9, 5.0, 10), ValueError, "mean_se"),
    (lambda C, e, b, m: e("30x6in", m, C(0.9, 0.01, 5)), TypeError, "block"),
    (lambda C, e, b, m: e(b, m, 0.9), TypeError, "cor"),
    (lambda C, e, b, m: e(b, m, C(0.9, 0.01, 5), members=10**9), ValueError, "members"),
    (lambda C, e, b, m: e(b, m, C(0.9, 0.01, 5), seed=-1), ValueError, "seed"),
])
def test_calibrated_cor_and_ensemble_name_the_bad_parameter(call, error, fragment):
    import shaketable as st
    from shaketable.calibration.uncertainty import CalibratedCor, calibrated_ensemble

    with pytest.raises(error, match=fragment):
        call(CalibratedCor, calibrated_ensemble, st.Block.parse("30x6in"),
             st.Motion.at_rest(0.5))


@pytest.mark.usefixtures("figure_drafts")
@pytest.mark.parametrize("ensemble", [[], ["--ensemble", "3"]])
def test_a_block_that_leaves_the_ground_exits_1_alone_or_in_an_ensemble(tmp_path, ensemble):
    # a vertical table acceleration of 1.5 g amplitude passes -g: the block leaves the ground
    status, _, err = run_cli(["simulate", "--block", "30x6in", "--cor", "0.9", "--harmonic",
                              "2Hz,0.05g,1.5g", "--duration", "2s", "--out", "o", *ensemble],
                             tmp_path)
    assert status == 1 and "airborne" in err and "stopped" in err, err
    if not ensemble:
        summary = json.loads((tmp_path / "o" / "summary.json").read_text())
        assert summary["stopped early"] is True and "left the ground" in summary["stop reason"]


@pytest.mark.parametrize("argv, both", [
    (["--table-4-4", "--record", "pacoima-dam-s16e"], ("--record", "--table-4-4")),
    (["--table-4-4", "--static-friction", "0.3"], ("--static-friction", "--table-4-4")),
    (["--record", "pacoima-dam-s16e", "--sweep", "0.1", "0.2", "--block", "4x1ft"],
     ("--block", "--sweep")),
    (["--record", "pacoima-dam-s16e", "--seed", "4"], ("--seed", "--table-4-4")),
])
def test_slide_refuses_options_its_mode_would_ignore(tmp_path, argv, both):
    status, _, err = run_cli(["slide", *argv, "--out", "o"], tmp_path)
    assert status == 2 and all(option in err for option in both), err
    assert not (tmp_path / "o").exists()


def test_a_chunk_too_large_to_hold_is_refused_naming_the_key(tmp_path):
    (tmp_path / "w.toml").write_text(_replace(TINY_SWEEP, "chunk_size = 1",
                                              "chunk_size = 100000000"))
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "-q"], tmp_path)
    assert status == 2 and "run.chunk_size" in err and "100,000" in err, err


def test_a_sweep_whose_runs_leave_the_ground_says_so_and_exits_1(tmp_path):
    spec = _replace(TINY_SWEEP, '[[records]]\nname = "pacoima-dam-s16e"',
                    '[[records]]\npreset = "B-1"\nduration = "1 s"\nvertical_pga = "2 g"')
    (tmp_path / "w.toml").write_text(spec)
    status, _, err = run_cli(["sweep", "w.toml", "--out", "out", "--no-progress"], tmp_path)
    assert status == 1, err
    assert "stopped before their motion ended" in err and "airborne" in err, err
    assert (tmp_path / "out" / "results.parquet").exists() or \
        (tmp_path / "out" / "results.csv").exists()


def test_the_share_of_lambda_outside_the_levels_run_is_measured():
    # the whole hazard range holds all of lambda; a range beyond the curve holds none
    from shaketable.sweeps.risk import share_outside

    hazard = _hazard()
    assert share_outside(_fit(), hazard, 0.05, 5.0) == pytest.approx(0.0, abs=1e-12)
    assert share_outside(_fit(), hazard, 10.0, 20.0) == pytest.approx(1.0, abs=1e-12)
    assert 0.0 < share_outside(_fit(), hazard, 0.05, 0.5) < 1.0


@pytest.mark.parametrize("bad, named", [(["--cor", "2"], "--cor"),
                                        (["--cor", "0.9", "--friction", "-1"], "--friction"),
                                        (["--cor", "0.9", "--friction", "0.3,0.5"], "--friction")])
def test_simulate_refuses_bad_input_before_it_creates_the_output_folder(tmp_path, bad, named):
    status, _, err = run_cli(["simulate", "--block", "30x6in", "--theta0", "0.5alpha",
                              "--duration", "1s", *bad, "--out", "o"], tmp_path)
    assert status == 2 and named in err, err
    assert not (tmp_path / "o").exists()
