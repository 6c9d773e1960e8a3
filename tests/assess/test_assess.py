"""The assessment orchestrates the package's own studies: it reproduces them exactly, and
its object files fail loudly, naming the key and the line."""

import json

import numpy as np
import pandas as pd
import pytest

from shaketable.assessment import assess
from shaketable.core.constants import INCH, G
from shaketable.core.geometry import Block
from shaketable.ground import records
from shaketable.ground.floor import Building, floor_motion
from shaketable.ground.signals import scale_to_pga
from shaketable.scenes.assess import load_assessment
from shaketable.scenes.parse import SceneError
from shaketable.studies import codes
from shaketable.studies.assess import (
    AssessedObject,
    Assessment,
    Criteria,
    Demand,
    run_assessment,
)
from shaketable.studies.mode_map import mode_map, table_4_4_coupled


@pytest.fixture(scope="module")
def shielding():
    """The report's 16 x 4 ft block at grade under Pacoima S16E as recorded (Table 4.4)."""
    motion = records.load("pacoima-dam-s16e")
    spec = Assessment("shielding", AssessedObject(Block.from_feet(16, 4), 17400.0, (0.1, 0.3),
                                                  0.95),
                      Demand(records=("pacoima-dam-s16e",), levels=(motion.pga,),
                             level_names=("as recorded",)),
                      Criteria(clearance=0.3, slide_friction=0.2))
    return spec, run_assessment(spec), motion


def test_mode_map_is_the_package_mode_map(shielding):
    spec, result, motion = shielding
    frictions = sorted(result.runs["mu [-]"].unique())
    block = spec.obj.block
    expected = mode_map(motion, pga_levels=(motion.pga,), aspect_ratios=(0.25,),
                        frictions=frictions, height=block.height, cor=0.95).frame
    ours = result.runs.drop(columns=["level", "level name", "ground pga [g]", "record"])
    # the map's PGA is the floor's (here at grade, the ground's): named so in runs.csv
    assert "pga [g]" not in result.runs and "ground pga [g]" in result.runs
    expected = expected.rename(columns={"pga [g]": "floor pga [g]"})
    pd.testing.assert_frame_equal(ours.reset_index(drop=True), expected, check_exact=True)


def test_table_4_4_coupled_slips_reproduced(shielding):
    _, result, _ = shielding
    table = table_4_4_coupled(blocks_ft=((16.0, 4.0),), columns=("pacoima-dam-s16e",),
                              frictions=(0.1, 0.2, 0.3))
    for row in table.itertuples(index=False):
        ours = result.runs[np.isclose(result.runs["mu [-]"], row[1])].iloc[0]
        assert ours["verdict"] == row[5]
        # the mode map builds its block as (B/H) H, Table 4.4 from feet: the same width
        # here (1.2192 m both ways), so the slips agree to the last digit
        assert ours["peak slip [m]"] / INCH == row[6]


def test_free_standing_statistics_from_the_runs(shielding):
    _, result, _ = shielding
    low = result.free[result.free["case"] == "low"].iloc[0]
    run = result.runs[np.isclose(result.runs["mu [-]"], 0.1)].iloc[0]
    assert low["records"] == 1
    assert low["P(overturn) [-]"] == float(run["overturned"])
    if not run["overturned"]:
        assert low["excursion median [m]"] == run["peak corner excursion [m]"]


def test_floor_anchored_forces_and_fp():
    building = Building(period=0.5, height=12.0, storeys=4)
    spec = Assessment("cab", AssessedObject(Block(1.8, 0.45), 300.0, (0.4, 0.4), 0.9),
                      Demand(records=("el-centro-chopra",), levels=(0.25 * G,),
                             level_names=("d",), s_ds=0.9),
                      Criteria(), building, floor=2)
    result = run_assessment(spec)
    floor = floor_motion(scale_to_pga(records.load("el-centro-chopra"), pga=0.25 * G),
                         building, floor=2)
    row = result.anchored.iloc[0]
    peak = np.max(np.abs(floor.horizontal))
    assert row["base shear median [N]"] == pytest.approx(300.0 * peak, rel=1e-15)
    # no vertical: uplift = m (a H/2 - g B/2) / B at the peak (moments about one edge)
    assert row["uplift median [N]"] == pytest.approx(
        max(0.0, 300.0 * (peak * 0.9 - G * 0.225) / 0.45), rel=1e-12)
    fp = codes.asce7_fp(300.0 * G, 0.9, z_over_h=0.5)  # floor 2 of 4
    assert row["Fp [N]"] == fp.fp


def _write(tmp_path, text, name="object.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


GOOD = """name = "thing"
[object]
size = "2x0.5m"
mass = "400 kg"
friction = [0.3, 0.5]
cor = 0.9
[location]
floor = 3
[building]
period = "0.6 s"
height = "17.5 m"
storeys = 5
[demand]
records = ["el-centro-chopra"]
pga = ["0.2 g"]
[criteria]
clearance = "100 mm"
"""


@pytest.mark.parametrize("old, new, key, line", [
    ("floor = 3", "floor = 6", "location.floor", 8),
    ('period = "0.6 s"', 'period = "0 s"', "building.period", 10),
    ('clearance = "100 mm"', "clearance = 0.1", "criteria.clearance", 17),
    ("friction = [0.3, 0.5]", "friction = [0.3, 2.5]", "object.friction", 5),
    ('pga = ["0.2 g"]', 'pga = ["0.2"]', "demand.pga", 15),
    ('records = ["el-centro-chopra"]', 'records = ["nowhere"]', "demand.records", 14),
])
def test_bad_input_names_the_key_and_line(tmp_path, old, new, key, line):
    assert old in GOOD
    path = _write(tmp_path, GOOD.replace(old, new))
    with pytest.raises(SceneError, match=rf"{path}: {key}: .*\(line {line}\)"):
        load_assessment(path)


@pytest.mark.parametrize("old, new, message", [
    ("storeys = 5", "storeys = 0",
     "building.storeys: must be an integer from 1 to 200, got 0 (line 12)"),
    ("storeys = 5", "storeys = true",
     "building.storeys: must be an integer from 1 to 200, got True (line 12)"),
    ('pga = ["0.2 g"]', 'pga = ["0.2 g"]\nartificial = {preset = "A-1", count = 101}',
     "demand.artificial: count must be an integer from 1 to 100, got 101 (line 16)"),
])
def test_counts_are_checked_as_everywhere(tmp_path, old, new, message):
    """The integer checks of core.validation, with the dotted key and its line."""
    path = _write(tmp_path, GOOD.replace(old, new))
    with pytest.raises(SceneError) as raised:
        load_assessment(path)
    assert str(raised.value) == f"{path}: {message}"


def test_a_stack_in_an_object_file_points_to_the_stack_model(tmp_path):
    path = _write(tmp_path, GOOD.replace('name = "thing"\n',
                                         'name = "thing"\n[stack]\nblocks = ["8x4ft", "6x4ft"]\n'))
    with pytest.raises(SceneError, match=r"stack: assess takes one object, not a stack of "
                                         r"blocks: for a column use `shaketable simulate "
                                         r"--stack`.* a sweep with \[stacks\] and `shaketable "
                                         r"risk`.*\(line 2\)"):
        load_assessment(path)


def test_calibration_of_another_block(tmp_path):
    _write(tmp_path, json.dumps({"cor [-]": 0.9, "cor_se [-]": 0.01, "fit samples": 100,
                                 "block_height [m]": 0.762, "block_width [m]": 0.1524}),
           "calibration.json")
    path = _write(tmp_path, GOOD.replace("cor = 0.9", 'cor = "calibration.json"'))
    with pytest.raises(SceneError, match=r"object.cor: .*another block.*\(line 6\)"):
        load_assessment(path)


@pytest.mark.usefixtures("figure_drafts")
def test_cli_style_run_writes_the_report(tmp_path):
    path = _write(tmp_path, GOOD)
    result = assess(path, tmp_path / "out")
    written = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"report.md", "summary.json", "runs.csv", "mode-map.png", "demands.png",
            "anchored.png", "spectra.png"} <= written
    data = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert data["recommendation"]["choice"] == result.recommendation["choice"]
    assert "Recommendation" in (tmp_path / "out" / "report.md").read_text()


def test_fragility_is_the_package_fit_of_direct_runs(monkeypatch):
    # the report's 16 x 4 ft block, the four Section 4 records at 0.3, 0.6 and 1.2 g; the
    # outcomes recomputed here with simulate itself, fitted by sweeps.fragility
    import shaketable.studies.assess as study
    from shaketable.models.api import simulate
    from shaketable.models.sliding.result import Friction
    from shaketable.sweeps.fragility import fragility_fit

    monkeypatch.setattr(study, "MAP_FRICTIONS", ())  # only the object's frictions
    names = ("pacoima-dam-s16e", "pacoima-dam-s74w", "el-centro-1940-180",
             "el-centro-1940-270")
    levels = (0.3 * G, 0.6 * G, 1.2 * G)
    block = Block.from_feet(16, 4)
    spec = Assessment("block", AssessedObject(block, 17400.0, (0.2, 0.4), 0.95),
                      Demand(records=names, levels=levels, level_names=("a", "b", "c")),
                      Criteria(slide_friction=0.15))
    result = run_assessment(spec)
    im, outcome = [], []
    for name in names:
        for level in levels:
            motion = scale_to_pga(records.load(name), pga=level)
            im.append(level)
            outcome.append(simulate(block, motion, cor=0.95, friction=Friction(0.4)).overturned)
    expected = fragility_fit(np.array(im), np.array(outcome), measure="pga [m/s^2]")
    fit = result.fragility["high"]["fit"]
    assert sum(outcome) > 0  # the fit exists: some runs overturn
    assert (fit.median, fit.beta) == (expected.median, expected.beta)


def test_recommendation_says_when_the_suite_is_too_small(shielding):
    # one record: the Wilson 95 % interval of 0/1 is [0, z^2 / (1 + z^2)] = [0, 0.7935]
    # (z = 1.95996; the package rounds it to 1.959964), far above the acceptable 0.05:
    # a point estimate of 0 shows nothing
    _, result, _ = shielding
    rows = result.free[result.free["overturned"] == 0]
    assert len(rows) > 0
    z2 = 1.959963984540054 ** 2
    np.testing.assert_allclose(rows["P high [-]"].to_numpy(), z2 / (1 + z2), rtol=1e-6)
    within = [r for r in result.recommendation["reasons"] if "0 of 1 record " in r]
    assert within and all("cannot show that P(overturn) is within it" in r for r in within)


def test_a_bundled_name_beside_a_folder_of_that_name(tmp_path, monkeypatch):
    # `shaketable assess transformer --out transformer` run twice: the second time the
    # folder of the first run's report must not be taken for the object file
    from shaketable.scenes.catalog import experiments_folder
    from shaketable.scenes.catalog import resolve_object_path as object_path

    monkeypatch.chdir(tmp_path)
    (tmp_path / "transformer").mkdir()
    assert object_path("transformer") == experiments_folder() / "assess" / "transformer.toml"
    with pytest.raises(FileNotFoundError, match="bundled: lab-cabinet"):
        object_path("no-such-object")


def test_the_api_takes_the_bundled_names_as_the_cli_does(tmp_path, monkeypatch):
    # docs/assess.md's example, run from an empty folder after `pip install`
    import shaketable
    import shaketable.assessment as assessment

    monkeypatch.chdir(tmp_path)
    seen = []
    monkeypatch.setattr(assessment, "run_assessment", lambda spec: seen.append(spec) or spec)
    shaketable.assess("lab-cabinet")
    assert seen[0].name == "lab-cabinet"
    with pytest.raises(FileNotFoundError, match="did you mean lab-cabinet.*bundled: lab-cabinet"):
        shaketable.assess("experiments/assess/lab-cabinet.toml")
