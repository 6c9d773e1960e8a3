"""Sweeps over intensity measures: IM targets, the IM columns of every row,
record suites, spectrum matching, resume guard, ``shaketable risk``, and the similarity
law behind the dimensionless PGV p / (g tan alpha).

Expected values come from :mod:`shaketable.ground.intensity` applied to the record scaled
by hand (tested itself against closed forms, eqsig and pyrotd), never from the sweep code.
"""

from __future__ import annotations

import json
import math
import shutil

import numpy as np
import pytest

from shaketable import sweeps
from shaketable.cli import main
from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.ground import intensity as im
from shaketable.ground import records
from shaketable.models.rocking.batch import Case, simulate_cases

SPEC = """
name = "im-tiny"
[blocks]
sizes = ["24x6in", "48x12in"]
[rocking]
cor = 0.9
duration = "4 s"
[[records]]
name = "el-centro-chopra"
[[records]]
name = "el-centro-1940-270"
vertical = false
[intensity]
{intensity}
[run]
chunk_size = 5
"""


def _run(tmp_path, intensity, name="out"):
    path = tmp_path / f"{name}.toml"
    path.write_text(SPEC.format(intensity=intensity))
    outcome = sweeps.run_sweep(sweeps.load_spec(path), tmp_path / name, workers=1,
                               progress=False)
    return outcome.table


@pytest.mark.parametrize("intensity, column, check", [
    ('measure = "pgv"\nlevels = ["0.3 m/s", "60 cm/s"]', "pgv [m/s]", im.pgv),
    ('measure = "arias"\nlevels = ["0.5 m/s"]', "arias [m/s]", im.arias_intensity),
    ('measure = "sa"\nperiod = "0.7 s"\nlevels = ["0.8 g"]', "sa(0.7 s) [m/s^2]",
     lambda m: im.spectral_acceleration(m, 0.7)),
])
def test_records_are_scaled_to_the_target_measure(tmp_path, intensity, column, check):
    table = _run(tmp_path, intensity)
    for _, row in table.iterrows():
        motion = records.load(row["record"], vertical=False) if row["record"] != \
            "el-centro-chopra" else records.load("el-centro-chopra")
        scaled = motion.scaled(row["scale [-]"])
        # the record scaled by the row's factor, measured independently, hits the target
        assert check(scaled) == pytest.approx(row["target [SI]"], rel=1e-9)
        assert row[column] == pytest.approx(row["target [SI]"], rel=1e-9)
        assert row["target_measure"] in column


def test_every_row_records_the_measures_of_its_scaled_motion(tmp_path):
    table = _run(tmp_path, "scale = [0.5, 1.5]")
    row = table.iloc[-1]
    motion = records.load("el-centro-1940-270", vertical=False).scaled(1.5)
    expected = im.intensity_measures(motion)
    for column, value in expected.items():
        assert row[column] == pytest.approx(value, rel=1e-9), column
    block = Block.parse(row["block"].replace(" ", ""))
    assert row["pga/(g tan a) [-]"] == pytest.approx(motion.pga / (G * math.tan(block.alpha)),
                                                     rel=1e-9)
    assert row["pgv p/(g tan a) [-]"] == pytest.approx(
        expected["pgv [m/s]"] * block.p / (G * math.tan(block.alpha)), rel=1e-9)
    assert "target_measure" not in table          # a scale-factor sweep has no target


def test_a_folder_of_at2_files_is_one_suite(tmp_path):
    folder = tmp_path / "suite"
    folder.mkdir()
    source = records.__file__.replace("ground/records.py", "data/records")
    for name in ("RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"):
        shutil.copy(f"{source}/{name}", folder / name)
    (folder / "notes.txt").write_text("not a record")
    spec = sweeps.spec_from_dict({
        "name": "suite", "blocks": {"sizes": ["24x6in"]}, "rocking": {"cor": 0.9},
        "records": [{"folder": "suite", "suite": "el-centro"}],
        "intensity": {"measure": "pga", "levels": ["0.3 g"]}}, directory=tmp_path)
    assert [r.label for r in spec.records] == ["RSN6_IMPVALL.I_I-ELC180-hor1",
                                               "RSN6_IMPVALL.I_I-ELC270-hor2"]
    assert {r.suite for r in spec.records} == {"el-centro"}
    with pytest.raises(sweeps.SweepError, match=r"records\[0\].folder: no file matching"):
        sweeps.spec_from_dict({"name": "x", "blocks": {"sizes": ["24x6in"]},
                               "rocking": {"cor": 0.9},
                               "records": [{"folder": "suite", "pattern": "*.V2"}]},
                              directory=tmp_path)


def test_records_are_scaled_to_a_target_spectrum(tmp_path):
    # target = 2 x the record's own Sa at the matching periods: the factor must be 2
    motion = records.load("el-centro-chopra")
    periods = np.geomspace(0.2, 2.0, im.SA_AVG_POINTS)
    sa = im.spectral_acceleration(motion, periods)
    lines = ["period [s], sa [g]"] + [f"{float(t)!r}, {float(2 * s / G)!r}"
                                     for t, s in zip(periods, sa)]
    (tmp_path / "target.csv").write_text("\n".join(lines) + "\n")
    table = _run(tmp_path, 'spectrum = "target.csv"\nscale = [1.0, 0.5]')
    chopra = table[table["record"] == "el-centro-chopra"]
    assert np.allclose(chopra["spectrum_scale [-]"], 2.0, rtol=1e-9)
    # the spectrum factor times each scale level (1.0, 0.5)
    np.testing.assert_allclose(sorted(chopra["scale [-]"].round(12).unique()), [1.0, 2.0],
                               rtol=1e-9)


@pytest.mark.parametrize("intensity, message", [
    ('measure = "pgx"\nlevels = ["1 m/s"]', "intensity.measure must be one of"),
    ('levels = ["1 m/s"]', "intensity.levels needs intensity.measure"),
    ('measure = "sa"\nlevels = ["1 g"]', "needs intensity.period"),
    ('measure = "pgv"\nlevels = ["1 g"]', "intensity.levels"),
    ('scale = [1.0]\npga = ["1 g"]', "gives both scale and pga"),
    ('spectrum = "absent.csv"', "intensity.spectrum: no such file"),
])
def test_bad_intensity_sections_are_named(tmp_path, intensity, message):
    path = tmp_path / "bad.toml"
    path.write_text(SPEC.format(intensity=intensity))
    with pytest.raises(sweeps.SweepError, match=message):
        sweeps.load_spec(path)


def test_a_sweep_folder_of_the_previous_format_is_not_resumed(tmp_path):
    _run(tmp_path, "scale = [1.0]")
    manifest = tmp_path / "out" / "manifest.json"
    data = json.loads(manifest.read_text())
    data["format_version"] = 1
    manifest.write_text(json.dumps(data))
    with pytest.raises(sweeps.SweepError, match="format_version"):
        sweeps.run_sweep(sweeps.load_spec(tmp_path / "out.toml"), tmp_path / "out",
                         resume=True, progress=False)


@pytest.mark.usefixtures("figure_drafts")
def test_risk_command_prints_lambda_and_refuses_bad_input(tmp_path, capsys):
    _run(tmp_path, 'measure = "pgv"\nlevels = ["0.1 m/s", "0.2 m/s", "0.4 m/s", "0.8 m/s", '
                   '"1.6 m/s"]')
    folder = str(tmp_path / "out")
    code = main(["risk", folder, "--hazard", "example", "--years", "50", "--figure",
                 str(tmp_path / "risk.png")])
    output = capsys.readouterr()
    assert code == 0, output.err
    # with two records per level the fits may be separated; either way each block is named
    assert "24 x 6 in" in output.out and "48 x 12 in" in output.out
    assert main(["risk", folder, "--hazard", str(tmp_path / "absent.csv")]) == 2
    assert main(["risk", str(tmp_path), "--hazard", "example"]) == 2
    assert "not a sweep folder" in capsys.readouterr().err


def test_similarity_law_is_an_identity_of_the_dimensionless_measures():
    # lengths x k and times x sqrt(k) at the same accelerations: the same theta(p t), so
    # the same max |theta| / alpha; PGA and PGA/(g tan a) are unchanged and PGV p/(g tan a)
    # too (PGV x sqrt(k), p / sqrt(k)), while PGV alone is not
    k = 4.0
    small = Block.parse("48x12in")
    large = Block(small.height * k, small.width * k)
    base = records.load("el-centro-chopra")
    keep = base.t <= 8.0
    motion = Motion(base.t[keep], base.horizontal[keep])
    stretched = Motion(base.t[keep] * math.sqrt(k), base.horizontal[keep])
    rows = simulate_cases([Case(small, motion, 0.9, scale=1.1),
                           Case(large, stretched, 0.9, scale=1.1)], threads=1,
                          method="predictor-corrector", rtol=1e-10)
    assert not rows["overturned"].any() and rows["max_theta_ratio [-]"].iloc[0] > 0.1
    assert rows["max_theta_ratio [-]"].iloc[1] == pytest.approx(
        rows["max_theta_ratio [-]"].iloc[0], rel=1e-6)
    pgv_small, pgv_large = im.pgv(motion.scaled(1.1)), im.pgv(stretched.scaled(1.1))
    assert pgv_large == pytest.approx(math.sqrt(k) * pgv_small, rel=1e-12)
    assert im.normalised_pgv(pgv_large, large.p, large.alpha) == pytest.approx(
        im.normalised_pgv(pgv_small, small.p, small.alpha), rel=1e-12)


def test_measure_figures_are_drawn_from_a_measure_sweep(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    from shaketable.plots.sweeps import sweep_figures
    from shaketable.sweeps.fragility import fragility_fit

    table = _run(tmp_path, 'measure = "pgv"\nlevels = ["0.1 m/s", "0.2 m/s", "0.3 m/s", '
                           '"0.4 m/s", "0.6 m/s", "0.9 m/s"]')
    written = sweep_figures(table, tmp_path / "figures")
    names = {path.name for path in written}
    assert {"fragility-pgv-cor0.9.png", "fragility-pga-cor0.9.png",
            "fragility-pgv-star-cor0.9.png", "im-comparison-cor0.9.csv"} <= names
    assert all(path.stat().st_size > 0 for path in written)
    # a fit's own plot() draws its band (profile-likelihood envelope contains the curve)
    rows = table[table["block"] == table["block"].iloc[0]]
    try:
        fit = fragility_fit(rows["pgv [m/s]"], rows["overturned"], measure="pgv [m/s]")
    except ValueError:
        pytest.skip("two records per level: outcomes separated for this block")
    grid = np.geomspace(0.05, 2.0, 50)
    low, high = fit.band(grid)
    assert np.all(low <= fit.probability(grid) + 1e-12)
    assert np.all(fit.probability(grid) <= high + 1e-12)
    assert fit.plot() is not None


def test_a_vertical_only_record_has_nan_measures_and_cannot_be_a_target():
    from shaketable.sweeps.execute import build_motion, compute_chunk

    base = {"name": "v", "blocks": {"sizes": ["24x6in"]},
            "rocking": {"cor": 0.9, "duration": "2 s"},
            "records": [{"name": "el-centro-1940-up"}]}
    row = compute_chunk(sweeps.spec_from_dict(base), 0, threads=1).iloc[0]
    assert row["pga [m/s^2]"] == 0.0 and math.isnan(row["pgv [m/s]"])
    target = sweeps.spec_from_dict(base | {"intensity": {"measure": "pgv",
                                                         "levels": ["0.5 m/s"]}})
    with pytest.raises(sweeps.SweepError, match="el-centro-1940-up.*pgv"):
        build_motion(target, 0)
