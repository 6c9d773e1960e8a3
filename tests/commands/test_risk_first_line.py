"""``risk`` leads with the answer, P(overturn in the design life), and rounds a median
and its interval alike."""

from __future__ import annotations

import json
import re

import pandas as pd

from shaketable.cli import main


def _sweep(folder):
    (folder / "parts").mkdir(parents=True)
    levels = [0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9] * 2
    overturned = [level > (0.45 if k % 3 else 0.65) for k, level in enumerate(levels)]
    pd.DataFrame({"run": range(len(levels)), "record": [f"r{k % 3}" for k in range(16)],
                  "block": "24 x 6 in", "cor [-]": 0.9, "status": "completed",
                  "pgv [m/s]": levels, "overturned": overturned}
                 ).to_csv(folder / "parts" / "part-000000.csv", index=False)
    (folder / "manifest.json").write_text(json.dumps({"format": "csv", "n_chunks": 1,
                                                      "n_runs": len(levels)}))
    return folder


def test_risk_leads_with_the_probability(tmp_path, capsys):
    folder = _sweep(tmp_path / "sweep")
    assert main(["risk", str(folder), "--hazard", "example"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("24 x 6 in, COR 0.9: P(overturn in 50 yr) = "), lines
    curve = [k for k, line in enumerate(lines) if line.startswith("hazard curve ")]
    assert curve and curve[0] > 0        # the hazard curve's description after the answer
    # the median and its interval to the same number of decimals
    said = re.search(r"median (\d+\.(\d+)) \[(\d+\.(\d+)), (\d+\.(\d+))\]", lines[1])
    assert said, lines[1]
    assert len(said[2]) == len(said[4]) == len(said[6])


def test_a_median_and_its_interval_round_alike():
    from shaketable.sweeps.fragility import FragilityFit

    # trial 4's fit: median 0.3246 [0.2264, 0.41] to three significant digits of the median
    fit = FragilityFit(0.3246, 0.3, 10, 5, median_interval=(0.2264, 0.41),
                       beta_interval=(0.2, 0.5), measure="pgv [m/s]")
    assert "median 0.325 [0.226, 0.410]" in fit.summary()
