"""A sweep's ``[ensemble]``: every cell as an ensemble of perturbed copies.

No expected value comes from the sweep code: each cell's P(overturn) and peak statistics
are compared with :func:`shaketable.studies.predictability.ensemble` (the API, which
builds its members through its own cases) on the same block, record and COR; the
nominal columns with the same sweep run without ``[ensemble]``; a resumed or re-chunked
ensemble sweep with an uninterrupted one. The cell 2 x 1 ft / Pacoima S74W / COR 1 is
fragile under a 1e-12 change of the input.
"""

import math

import numpy as np
import pandas as pd
import pytest

from shaketable import sweeps
from shaketable.core.ensemble import Perturbation, wilson_interval
from shaketable.core.geometry import Block
from shaketable.ground import records
from shaketable.studies.predictability import ensemble

BASE = """
name = "ensemble-cells"
[blocks]
sizes = ["2x1ft", "4x2ft"]
[rocking]
cor = [1.0, 0.9]
[[records]]
name = "pacoima-dam-s74w"
[run]
chunk_size = {chunk}
"""
ENSEMBLE = """
[ensemble]
members = 40
perturb = 1e-9
seed = 3
"""
MEMBERS = 40


def _spec(tmp_path, text, name):
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return sweeps.load_spec(path)


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ensemble-sweep")
    plain = sweeps.run_sweep(_spec(folder, BASE.format(chunk=3), "plain"), folder / "plain",
                             progress=False).table
    spec = _spec(folder, BASE.format(chunk=3) + ENSEMBLE, "ensemble")
    whole = sweeps.run_sweep(spec, folder / "whole", progress=False)
    return plain, whole.table, spec, folder


def test_each_cell_equals_the_api_ensemble(tables):
    _, table, _, _ = tables
    motion = records.load("pacoima-dam-s74w")
    assert len(table) == 4
    for _, row in table.iterrows():
        block = Block.parse({"2 x 1 ft": "2x1ft", "4 x 2 ft": "4x2ft"}[row["block"]])
        api = ensemble(block, motion, cor=row["cor [-]"], members=MEMBERS,
                       perturbation=Perturbation(), seed=3, horizon_pairs=0).summary
        assert row["members"] == MEMBERS
        assert row["overturned members"] == api["overturned"]
        assert row["P(overturn) [-]"] == api["P(overturn) [-]"]
        assert row["robust"] == api["robust"]
        for key in ("median max theta/alpha [-]", "p05 max theta/alpha [-]",
                    "p95 max theta/alpha [-]"):
            assert row[key] == api[key] or (math.isnan(row[key]) and math.isnan(api[key]))
        low, high = wilson_interval(int(row["overturned members"]), MEMBERS)
        assert (row["P low [-]"], row["P high [-]"]) == (low, high)
        assert row["mark"] == ("robust" if api["robust"] else "fragile")
    # the 2 x 1 ft block under S74W at COR 1 is fragile under 1e-9 perturbations
    cell = table[(table["block"] == "2 x 1 ft") & (table["cor [-]"] == 1.0)].iloc[0]
    assert cell["mark"] == "fragile" and 0 < cell["P(overturn) [-]"] < 1


def test_nominal_columns_are_the_sweep_without_ensemble(tables):
    plain, table, _, _ = tables
    added = ["members", "overturned members", "P(overturn) [-]", "P low [-]", "P high [-]",
             "robust", "standing members", "median max theta/alpha [-]",
             "p05 max theta/alpha [-]", "p95 max theta/alpha [-]", "mark"]
    assert list(table.columns) == list(plain.columns) + added
    pd.testing.assert_frame_equal(table[list(plain.columns)], plain, check_exact=True)


def test_resumed_and_rechunked_ensemble_sweeps_are_identical(tables):
    _, table, spec, folder = tables
    out = folder / "resumed"
    first = sweeps.run_sweep(spec, out, progress=False, max_chunks=1)
    assert not first.complete and first.computed_runs == 3
    final = sweeps.run_sweep(spec, out, progress=False, resume=True)
    assert final.complete and final.skipped_runs == 3 and final.computed_runs == 1
    pd.testing.assert_frame_equal(final.table, table, check_exact=True)
    other = sweeps.run_sweep(_spec(folder, BASE.format(chunk=4) + ENSEMBLE, "rechunked"),
                             folder / "rechunked", progress=False, workers=1).table
    pd.testing.assert_frame_equal(other.drop(columns=["chunk", "sweep"]),
                                  table.drop(columns=["chunk", "sweep"]), check_exact=True)


def test_resume_refuses_a_changed_ensemble(tables):
    _, _, spec, folder = tables
    changed = _spec(folder, BASE.format(chunk=3) + ENSEMBLE.replace("seed = 3", "seed = 4"),
                    "ensemble")
    with pytest.raises(sweeps.SweepError, match="cannot resume.*fingerprint"):
        sweeps.run_sweep(changed, folder / "whole", progress=False, resume=True)


@pytest.mark.parametrize("section, message", [
    ("members = 1", "ensemble.members must be an integer >= 2"),
    ("perturb_cor = 1.5", "ensemble.perturb_cor"),
    ("horizon_threshold = 1e-3", "ensemble.horizon_threshold.*no predictability horizon"),
    ("spread = 0.1", "unknown key ensemble.spread"),
])
def test_ensemble_errors_name_the_file_and_the_key(tmp_path, section, message):
    path = tmp_path / "bad.toml"
    path.write_text(BASE.format(chunk=3) + "[ensemble]\n" + section + "\n")
    with pytest.raises(sweeps.SweepError, match=f"bad.toml: .*{message}"):
        sweeps.load_spec(path)


def test_physical_spreads_widen_the_peak_range(tmp_path):
    """COR +/- 5 % (a physical spread) on a standing cell: the 5-95 % range of max
    theta/alpha contains the nominal run's and is wider than under 1e-9."""
    text = BASE.format(chunk=4).replace('"2x1ft", "4x2ft"', '"4x2ft"').replace(
        "[1.0, 0.9]", "0.9")
    tiny = sweeps.run_sweep(_spec(tmp_path, text + ENSEMBLE, "tiny"), tmp_path / "tiny",
                            progress=False).table.iloc[0]
    wide = sweeps.run_sweep(_spec(tmp_path, text + ENSEMBLE + "perturb_cor = 0.05\n", "wide"),
                            tmp_path / "wide", progress=False).table.iloc[0]
    assert not wide["overturned"]
    assert wide["p05 max theta/alpha [-]"] <= wide["max_theta_ratio [-]"] \
        <= wide["p95 max theta/alpha [-]"]
    spread = wide["p95 max theta/alpha [-]"] - wide["p05 max theta/alpha [-]"]
    assert spread > 100 * (tiny["p95 max theta/alpha [-]"] - tiny["p05 max theta/alpha [-]"])
    assert np.isfinite(spread)
