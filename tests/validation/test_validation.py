"""The validation workflow: folder, likelihood fit, scores, cross-validation, commands.

Synthetic folders are built here (harmonic table motions; outcomes of a block of known
angle, or hand-made); the measured granite-rock tests are read from the shared folder only
(GPL-3.0, never copied into the repository) and those tests skip when it is absent.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

from shaketable.cli import main
from shaketable.core.constants import G
from shaketable.validation.check import bootstrap_coverage, cross_validate, folds
from shaketable.validation.fit import SIGMAS, fit, likelihood_table, scale_weights
from shaketable.validation.folder import read_folder
from shaketable.validation.model import LOG_SCALES, CandidateGrid, EquivalentBlock, verdicts
from shaketable.validation.score import fragility, reliability, scores, threshold_fit
from tests.helpers import SHARED_PBR, needs_pbr


def _harmonic_folder(tmp_path, amplitudes_g, outcomes=None, frequency=2.0):
    """A folder of 3-s harmonic tests (100 Hz) at the given amplitudes [g]."""
    (tmp_path / "tests").mkdir(parents=True, exist_ok=True)
    rows = []
    for k, amplitude in enumerate(amplitudes_g):
        t = np.arange(300) / 100.0
        acceleration = amplitude * G * np.sin(2 * math.pi * frequency * t)
        np.savez(tmp_path / "tests" / f"T{k:03d}.npz", acc_h=acceleration.astype(np.float32),
                 fs=100.0)
        row = {"test": k, "file": f"tests/T{k:03d}.npz", "specimens": "A+B"}
        if outcomes is not None:
            row["a_overturned"], row["b_overturned"] = outcomes[0][k], outcomes[1][k]
        rows.append(row)
    pd.DataFrame(rows).to_csv(tmp_path / "metadata.csv", index=False)
    return tmp_path


def test_scores_closed_forms():
    result = scores([0.5, 0.5, 0.9, 0.1], [1, 0, 1, 1])
    assert result["accuracy"] == 0.5               # 0.5 counts as overturned
    assert (result["true_positive"], result["false_positive"], result["true_negative"],
            result["false_negative"]) == (2, 1, 0, 1)
    expected = -(2 * math.log(0.5) + math.log(0.9) + math.log(0.1)) / 4
    assert result["log_loss"] == pytest.approx(expected, rel=1e-12)
    assert result["brier"] == pytest.approx((0.25 + 0.25 + 0.01 + 0.81) / 4, rel=1e-12)


def test_reliability_and_fragility_tables():
    p = np.array([0.05, 0.05, 0.95, 0.95, 0.6])
    y = np.array([0, 0, 1, 1, 0])
    table = reliability(p, y)
    assert list(table["n"]) == [2, 1, 2]
    assert list(table["measured"]) == [0.0, 0.0, 1.0]
    frame = fragility(p, y, [0.1, 0.1, 1.0, 1.0, 0.5], [0.05, 0.3, 2.0])
    assert list(frame["n"]) == [2, 3]
    assert frame["measured"].iloc[1] == pytest.approx(2 / 3)
    assert frame["measured_low"].iloc[1] < 2 / 3 < frame["measured_high"].iloc[1]


def test_threshold_and_folds():
    x = np.array([0.1, 0.2, 0.3, 0.7, 0.8, 0.9])
    y = np.array([0, 0, 0, 1, 1, 1])
    assert 0.3 < threshold_fit(x, y) < 0.7
    fold = folds(np.array([0] * 10 + [1] * 5), 5, seed=1)
    for f in range(5):   # stratified: two standing and one overturned test per fold
        assert (fold[:10] == f).sum() == 2 and (fold[10:] == f).sum() == 1
    with pytest.raises(ValueError, match="k must be"):
        folds([0, 1], 3, seed=0)


def test_scale_weights():
    assert np.array_equal(scale_weights(0.0), (np.asarray(LOG_SCALES) == 0).astype(float))
    weights = scale_weights(0.2)
    assert weights.sum() == pytest.approx(1.0)
    assert np.allclose(weights, weights[::-1])       # symmetric about the recorded amplitude


def test_fit_recovers_the_candidate_that_made_the_outcomes():
    rng = np.random.default_rng(3)
    n_c, n_t = 6, 120
    candidates = [EquivalentBlock(0.05 + 0.02 * k, 0.05 + 0.02 * k, 0.3, 0.9) for k in range(n_c)]
    # candidate k overturns in test i at scale s when the test's intensity exceeds its
    # threshold: a monotone toy with a known truth (candidate 2, sigma 0)
    intensity = rng.uniform(0.0, 1.0, n_t)
    thresholds = np.linspace(0.2, 0.7, n_c)
    overturned = (intensity[None, :, None] * np.exp(np.asarray(LOG_SCALES))[None, None, :]
                  > thresholds[:, None, None])
    outcomes = overturned[2, :, LOG_SCALES.index(0.0)].astype(int)
    calibration = fit(overturned, outcomes, candidates, "toy")
    assert calibration.best.block == candidates[2]
    assert calibration.best.sigma == SIGMAS[0]
    assert calibration.accuracy == 1.0
    assert calibration.intervals["alpha_weak"][0] <= candidates[2].alpha_weak \
        <= calibration.intervals["alpha_weak"][1]
    # bagged: every bootstrap refit picks the candidate that made the outcomes (each
    # resample still holds tests between its neighbours' thresholds)
    bagged = fit(overturned, outcomes, candidates, "toy", bags=10, seed=1)
    assert bagged.best == calibration.best
    assert [member.block for member in bagged.members] == [candidates[2]]
    assert list(bagged.weights) == [1.0]
    with pytest.raises(ValueError, match="bags"):
        fit(overturned, outcomes, candidates, bags=-1)
    table = likelihood_table(overturned, outcomes)
    assert table.shape == (n_c, len(SIGMAS), 4)
    frame = cross_validate(overturned, outcomes, candidates, intensity, k=3, repeats=1)
    calibrated = frame[frame["model"] == "calibrated"]["accuracy"]
    assert calibrated.mean() > 0.95
    coverage = bootstrap_coverage(overturned, outcomes, candidates, calibration.intervals,
                                  resamples=20)
    assert coverage["alpha_weak"] >= 0.9


def test_folder_errors_name_the_file(tmp_path):
    with pytest.raises(ValueError, match="no metadata.csv"):
        read_folder(tmp_path)
    (tmp_path / "metadata.csv").write_text("test,path\n1,a.npz\n")
    with pytest.raises(ValueError, match="metadata.csv: no column 'file'"):
        read_folder(tmp_path)
    _harmonic_folder(tmp_path, [0.1, 0.2], outcomes=([0, 2], [0, 1]))
    folder = read_folder(tmp_path)
    assert folder.specimens == ("a", "b")
    with pytest.raises(ValueError, match="line 3: a_overturned must be 0 or 1"):
        folder.outcomes("a")


@pytest.mark.usefixtures("figure_drafts")
def test_calibration_recovers_a_known_block_and_the_commands(tmp_path, capsys):
    # outcomes made by a symmetric block of alpha 0.1 (uplift at 0.1 g, overturning higher):
    # the calibration must pick alpha 0.1 among 0.05, 0.1, 0.2
    amplitudes = np.linspace(0.04, 0.3, 16)
    truth = EquivalentBlock(0.1, 0.1, 0.3, 0.9)
    folder = _harmonic_folder(tmp_path / "made", amplitudes)
    motions = read_folder_with_specimens(folder).motions()
    made, _ = verdicts([truth], motions, threads=1, log_scales=(0.0,))
    outcome = made[0, :, 0].astype(int)
    assert 0 < outcome.sum() < outcome.size          # some stand, some overturn
    data = _harmonic_folder(tmp_path / "data", amplitudes, outcomes=(outcome, outcome))
    out = tmp_path / "cal.json"
    assert main(["validate", "calibrate", str(data), "--out", str(out), "--alphas",
                 "0.05,0.1,0.2", "--ratios", "1", "--cors", "0.9", "--folds", "2",
                 "--repeats", "1", "--bootstrap", "5", "--threads", "1", "--verdicts",
                 str(tmp_path / "verdicts.npz"), "--cv-predictions",
                 str(tmp_path / "cv.csv")]) == 0
    assert (tmp_path / "verdicts.npz").is_file()
    # progress on stderr: each stage's last line at least (done/total, elapsed)
    captured = capsys.readouterr()
    err = captured.err
    # the intervals carry their units (alpha in rad, the heights in m, the COR in -)
    for axis in ("alpha_weak [rad]", "half_width [m]", "h [m]", "cor [-]"):
        assert f"95 % profile-likelihood set of {axis}: [" in captured.out
        assert f"95 % bootstrap set of {axis}: [" in captured.out
    assert "\nA: " in captured.out and "specimens A, B;" in captured.out
    assert f"simulating the candidates: {3 * 16 * len(LOG_SCALES)}/{3 * 16 * len(LOG_SCALES)}" \
        " runs (100 %)" in err
    assert "a cross-validation: 2/2 folds (100 %)" in err and "s elapsed" in err
    assert "b bootstrap check: 5/5 refits (100 %)" in err
    assert len(pd.read_csv(tmp_path / "cv.csv")) == 2 * amplitudes.size
    saved = json.loads(out.read_text())
    assert saved["specimens"]["a"]["best"]["block"]["alpha_weak"] == 0.1
    assert saved["specimens"]["a"]["tests"] == [str(k) for k in range(16)]
    # --quiet: no progress (the verdicts come from the cache)
    assert main(["validate", "calibrate", str(data), "--out", str(tmp_path / "quiet.json"),
                 "--alphas", "0.05,0.1,0.2", "--ratios", "1", "--cors", "0.9", "--folds", "0",
                 "--bootstrap", "0", "--verdicts", str(tmp_path / "verdicts.npz"), "-q"]) == 0
    assert capsys.readouterr().err == ""
    assert "cross_validation" in saved["checks"]["a"]
    assert set(saved["checks"]["a"]["bootstrap"]["sets"]) >= {"alpha_weak", "cor"}
    # predict a folder without outcome columns: one row per test and specimen
    predictions = tmp_path / "predictions.csv"
    assert main(["validate", "predict", str(folder), "--calibration", str(out), "--out",
                 str(predictions)]) == 0
    frame = pd.read_csv(predictions)
    assert len(frame) == 2 * amplitudes.size
    assert set(frame["specimen"]) == {"a", "b"}
    assert np.array_equal(frame[frame["specimen"] == "a"]["best_overturned"], outcome)
    assert (frame["in_training"] == 1).all()          # the same test ids as the calibration's
    # a calibration that saw only the last 8 tests: the first 8 are out-of-sample
    for name in ("a", "b"):
        saved["specimens"][name]["tests"] = [str(k) for k in range(8, 16)]
    out.write_text(json.dumps(saved))
    assert main(["validate", "predict", str(folder), "--calibration", str(out), "--out",
                 str(predictions)]) == 0
    assert list(pd.read_csv(predictions)["in_training"]) == ([0] * 8 + [1] * 8) * 2
    capsys.readouterr()
    assert main(["validate", "score", str(predictions), str(data), "--figures",
                 str(tmp_path / "figures")]) == 0
    printed = capsys.readouterr().out
    # mixed rows: the out-of-sample score leads, then the in-sample one, then all pooled;
    # the specimens as the folder's 'specimens' column spells them (A+B), not a, b
    assert printed.startswith("out-of-sample (tests the calibration never saw):\n"
                              "  A: accuracy 1.000 on 8"), printed
    out_of_sample, rest = printed.split("in-sample (tests the calibration was fitted on")
    in_sample, pooled = rest.split("all rows pooled")
    assert "  B: accuracy 1.000 on 8" in out_of_sample and "  A: accuracy 1.000 on 8" in in_sample
    assert "  A: accuracy 1.000 on 16" in pooled and "  a: " not in printed
    # a calibration file that does not record its tests: in-sample or not is unknown
    for name in ("a", "b"):
        del saved["specimens"][name]["tests"]
    out.write_text(json.dumps(saved))
    assert main(["validate", "predict", str(folder), "--calibration", str(out), "--out",
                 str(tmp_path / "unknown.csv")]) == 0
    assert "a, b: the calibration does not record the tests" in capsys.readouterr().out
    assert set(pd.read_csv(tmp_path / "unknown.csv")["in_training"]) == {-1}
    assert (tmp_path / "figures" / "reliability.png").is_file()
    # bad input: a calibration file that is not one
    (tmp_path / "bad.json").write_text("{}")
    assert main(["validate", "predict", str(folder), "--calibration",
                 str(tmp_path / "bad.json"), "--out", str(predictions)]) == 2


def read_folder_with_specimens(path):
    return read_folder(path)


def test_grid_and_block_checks():
    grid = CandidateGrid(alphas=(0.1,), ratios=(1.0, 2.0), heights=(0.3,), cors=(0.9,))
    candidates = grid.candidates()
    assert len(candidates) == 3                      # symmetric once, asymmetric with both signs
    assert {c.sign for c in candidates if not c.symmetric} == {1, -1}
    with pytest.raises(ValueError, match="alpha_strong"):
        EquivalentBlock(0.2, 0.1, 0.3, 0.9)
    with pytest.raises(ValueError, match="sign"):
        EquivalentBlock(0.1, 0.2, 0.3, 0.9, sign=0)


@needs_pbr
def test_measured_folder_reads_as_its_provenance_says():
    folder = read_folder(SHARED_PBR)
    assert folder.specimens == ("sp1", "sp2")
    # a few tests only: the motion's PGA is the metadata's (acc_h as stored, in g)
    for row in (0, 50, 120):
        motion = folder.motion(row)
        expected = float(folder.metadata["pga_g"][row])   # type: ignore[index]
        assert motion.pga / G == pytest.approx(expected, rel=1e-4)
        assert motion.dt == pytest.approx(1 / 200.0)
    # SP1 fell in 93 of the 244 training tests, SP2 in 76 (PROVENANCE: strata 23+70, 6+70)
    assert folder.outcomes("sp1").sum() == 93
    assert folder.outcomes("sp2").sum() == 76


@needs_pbr
def test_scan_based_block_scores_as_an_independent_integrator(tmp_path):
    # PROVENANCE.md of the measured tests ("Baseline on this half"): the data's authors' own
    # asymmetric rocking integrator on the scans' blocks in the simulator's orientation
    # scored 0.664 (SP1) and 0.721 (SP2); that orientation is sign +1 here
    predictions = tmp_path / "scan.csv"
    assert main(["validate", "predict", str(SHARED_PBR), "--geometry",
                 str(SHARED_PBR / "geometry.csv"), "--sign", "1", "--out", str(predictions),
                 "--threads", "1", "--quiet"]) == 0
    from shaketable.validation.workflow import read_predictions, score_folder

    result = score_folder(read_predictions(predictions), read_folder(SHARED_PBR))
    assert result["specimens"]["sp1"]["accuracy"] == pytest.approx(0.664, abs=0.0021)
    assert result["specimens"]["sp2"]["accuracy"] == pytest.approx(0.721, abs=0.0021)


@pytest.mark.usefixtures("figure_drafts")
def test_reproduce_validation_section_runs_or_skips(tmp_path):
    from shaketable.reproduce import reproduce

    # absent folder: the section is one line saying why and how to give it, and the
    # report counts it as skipped, not as rerun
    report = reproduce([], out=tmp_path / "out", progress=False,
                       extra={"validation": {"data": tmp_path / "absent"}})
    text = report.read_text()
    assert f"Skipped: no folder of measured tests at {tmp_path / 'absent'}" in text
    assert "--validation-data DIR" in text and "SHAKETABLE_PBR=DIR" in text
    assert "all rerun now" not in text
    assert "1 section: 0 rerun now, 1 skipped (validation: its section says why" in text
    # a folder of tests with outcomes (made by a symmetric block of alpha 0.1, COR 0.9, one
    # of the section's candidates): the coarse calibration finds it and cross-validates
    amplitudes = np.linspace(0.04, 0.3, 20)
    made, _ = verdicts([EquivalentBlock(0.1, 0.1, 0.3, 0.9)],
                       read_folder(_harmonic_folder(tmp_path / "made", amplitudes)).motions(),
                       threads=1, log_scales=(0.0,))
    outcome = made[0, :, 0].astype(int)
    data = _harmonic_folder(tmp_path / "data", amplitudes, outcomes=(outcome, outcome))
    from shaketable.validation.report import reproduce_section

    section = reproduce_section(tmp_path / "section", data, threads=1)
    assert "* A, the most likely block: alpha 0.1 rad" in section
    assert "| A | PGV threshold |" in section and "| B | calibrated |" in section
    assert (tmp_path / "section" / "reliability.png").is_file()


def test_an_installed_package_looks_for_no_data_beside_itself(tmp_path, monkeypatch):
    # pip puts the package in .../lib/python3.11/site-packages/shaketable: nothing beside
    # it is the project's, so no default folder (the section says how to give one); a
    # source checkout (pyproject.toml beside the package) has ../shared/data/pbr
    from shaketable.validation.report import data_folder, reproduce_section

    monkeypatch.delenv("SHAKETABLE_PBR", raising=False)
    installed = tmp_path / "venv" / "lib" / "python3.11" / "site-packages" / "shaketable"
    installed.mkdir(parents=True)
    assert data_folder(package=installed) is None
    checkout = tmp_path / "work" / "project"
    (checkout / "shaketable").mkdir(parents=True)
    (checkout / "pyproject.toml").write_text("[project]\n")
    assert data_folder(package=checkout / "shaketable") == tmp_path / "work" / "shared" / \
        "data" / "pbr"
    monkeypatch.setenv("SHAKETABLE_PBR", str(tmp_path / "pbr"))
    assert data_folder(package=installed) == tmp_path / "pbr"
    assert data_folder(tmp_path / "given", package=installed) == tmp_path / "given"
    monkeypatch.delenv("SHAKETABLE_PBR")
    import shaketable.validation.report as report

    monkeypatch.setattr(report, "source_checkout", lambda package=None: None)
    section = reproduce_section(tmp_path / "section")
    assert "Skipped: no folder of measured tests given" in section
    assert "`shaketable reproduce --all --validation-data DIR`" in section
