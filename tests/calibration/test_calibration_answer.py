"""A calibration leads with one answer everywhere: when the COR scatters from impact to
impact, the block's mean COR and its interval head the console, the figure, the JSON and
``predict()``; the least-squares fit is kept as a diagnostic.

The record is made by ``tests/calibration/lab_records.py`` (independent of the package):
a 30 x 6 in block whose impacts draw their COR from N(0.90, 0.02^2). The truth is what
that generator was told: the block's mean COR 0.90, which the least-squares interval
(+-5e-4 wide) misses and the random-effects interval covers.
"""

from __future__ import annotations

import dataclasses
import json

import pytest

import shaketable as st
from shaketable.calibration import calibrate
from shaketable.calibration.record import FreeRockingRecord
from shaketable.calibration.result import LEAST_SQUARES_KEY
from shaketable.calibration.uncertainty import CalibratedCor, CalibratedEnsemble
from shaketable.cli import main
from tests.calibration.lab_records import lab_record

BLOCK = st.Block.parse("30x6in")
TRUE_MEAN = 0.90        # the generator's mean COR of the impacts


@pytest.fixture(scope="module")
def scattered():
    lab = lab_record(20_002, cor=TRUE_MEAN, sigma=0.02)
    record = FreeRockingRecord.from_top_displacement(lab.t, lab.displacement_in, units="in",
                                                     name="lab 20002")
    return calibrate(record, BLOCK)


def test_the_block_mean_leads_text_json_figure(scattered):
    result = scattered
    assert result.mean_cor_leads
    low, high = result.scatter.mean_interval
    # the least-squares interval misses the truth; the mean's covers it
    assert not result.cor_interval[0] <= TRUE_MEAN <= result.cor_interval[1]
    assert low <= TRUE_MEAN <= high
    first, second = result.text().splitlines()[:2]
    assert first.startswith(f"COR = {result.scatter.mean:.4f}  (95 % interval {low:.4f} to "
                            f"{high:.4f}): the block's mean COR")
    assert second.startswith("least-squares fit (diagnostic") and f"{result.cor:.5f}" in second
    summary = result.summary()
    assert summary["cor [-]"] == pytest.approx(result.scatter.mean, abs=0)
    assert summary["cor_interval [-]"] == [low, high]
    assert summary["cor_source"] == "block mean (random effects)"
    assert summary[LEAST_SQUARES_KEY]["cor [-]"] == result.cor
    assert summary[LEAST_SQUARES_KEY]["cor_interval [-]"] == list(result.cor_interval)
    figure = result.plot()
    assert figure.axes[0].get_title().startswith(f"COR = {result.scatter.mean:.4f}  (95 % "
                                                 f"interval {low:.4f} to {high:.4f})")
    import matplotlib.pyplot as plt

    plt.close(figure)


def test_plus_minus_is_one_standard_error(scattered):
    text = scattered.text()
    slope_se = scattered.peaks.slope_se
    assert f"slope {scattered.peaks.slope:+.4f} +- {slope_se:.4f} s/rad" in text
    assert "(+- is one standard error; intervals are 95 %)" in text


def test_predict_runs_the_ensemble_of_the_mean_cor(scattered):
    from shaketable.ground import records

    motion = records.load("pacoima-dam-s16e").scaled(0.3)
    ensemble = scattered.predict(motion, members=3, duration=2.0)
    assert isinstance(ensemble, CalibratedEnsemble)
    assert ensemble.cor.mean == scattered.scatter.mean
    assert ensemble.members["cor [-]"].iloc[0] == scattered.scatter.mean
    # free rocking: one run with the mean COR
    free = scattered.predict(duration=1.0)
    assert free.cor == scattered.scatter.mean


def test_the_json_read_back_is_the_headline_and_old_files_still_read(scattered, tmp_path):
    path = tmp_path / "calibration.json"
    scattered.to_json(path)
    cor = CalibratedCor.from_json(path)
    assert (cor.mean, cor.mean_se, cor.dof) == (scattered.scatter.mean, scattered.scatter.mean_se,
                                                scattered.scatter.dof)
    # a file as the previous version wrote it: least squares at the top, the mean below
    old = tmp_path / "old.json"
    old.write_text(json.dumps({"cor [-]": 0.905, "cor_se [-]": 1e-4, "interval": "acf",
                               "cor_mean [-]": 0.90, "cor_mean_se [-]": 0.006,
                               "cor_mean_dof": 10, "cor_scatter_sigma [-]": 0.02,
                               "fit samples": 500}))
    assert CalibratedCor.from_json(old).mean == 0.90
    out = tmp_path / "sim"
    assert main(["simulate", "--block", "30x6in", "--cor", str(old), "--record",
                 "pacoima-dam-s16e", "--scale", "0.3", "--ensemble", "3", "--duration", "1s",
                 "--out", str(out)]) == 0


def test_a_fitted_cutoff_above_nyquist_reads_no_filter(scattered):
    # 50 samples/s: the Nyquist frequency is 25 Hz
    above = dataclasses.replace(scattered, anti_alias="fit", filter_cutoff=40.0)
    assert above.filter_text().startswith("fitted filter: no filter")
    assert "40 Hz" not in above.headline() or "no filter" in above.headline()
    below = dataclasses.replace(scattered, anti_alias="fit", filter_cutoff=20.0)
    assert below.filter_text() == f"fitted {scattered.filter_order}-pole filter at 20 Hz"


def test_a_record_in_mm_is_shown_in_mm(tmp_path):
    from shaketable.calibration import read_record

    path = tmp_path / "lab.csv"
    path.write_text("time [s],top displacement [mm]\n" + "\n".join(
        f"{0.02 * k:.2f},{-50.0 * (0.9 ** k):.4f}" for k in range(50)) + "\n")
    record = read_record(path)
    assert record.display_scale() == (pytest.approx(1000.0), "mm")
    assert record.values[0] == pytest.approx(-0.050)          # SI inside: metres
    # a record made in memory keeps the report's inches
    assert FreeRockingRecord.from_top_displacement([0.0, 0.1], [0.0, 0.01]).display_scale() \
        == (pytest.approx(1 / 0.0254), "in")
