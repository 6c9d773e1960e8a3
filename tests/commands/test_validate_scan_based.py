"""``validate predict --geometry`` then ``validate score``: a scan-based prediction has no
calibration, so it is said as what it is, not as out-of-sample."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from shaketable.cli import main
from shaketable.core.constants import G


def _folder(path, amplitudes_g):
    """A folder of 2-s, 2-Hz harmonic tests (100 Hz samples) of two specimens A and B,
    with outcomes (the strong half marked overturned: what is scored is not judged here)."""
    (path / "tests").mkdir(parents=True)
    rows = []
    for k, amplitude in enumerate(amplitudes_g):
        t = np.arange(200) / 100.0
        np.savez(path / "tests" / f"T{k}.npz",
                 acc_h=(amplitude * G * np.sin(2 * math.pi * 2.0 * t)).astype(np.float32),
                 fs=100.0)
        strong = int(amplitude > 0.2)
        rows.append({"test": k, "file": f"tests/T{k}.npz", "specimens": "A+B",
                     "a_overturned": strong, "b_overturned": strong})
    pd.DataFrame(rows).to_csv(path / "metadata.csv", index=False)
    # a rectangle 0.1 m wide and 0.6 m tall (b 0.05 m, h 0.3 m), both sides alike:
    # I_O = (4/3) m R^2 about a corner
    radius = math.hypot(0.05, 0.3)
    geometry = pd.DataFrame([{"specimen": name, "direction": "x", "side": side, "b_m": 0.05,
                              "h_m": 0.3, "R_m": radius, "I_O_over_mR2": 4 / 3}
                             for name in ("A", "B") for side in ("+x", "-x")])
    geometry.to_csv(path / "geometry.csv", index=False)
    return path


def test_a_scan_based_prediction_is_not_called_out_of_sample(tmp_path, capsys):
    folder = _folder(tmp_path / "tests", [0.05, 0.1, 0.3, 0.4])
    predictions = tmp_path / "scan.csv"
    assert main(["validate", "predict", str(folder), "--geometry",
                 str(folder / "geometry.csv"), "--out", str(predictions),
                 "--threads", "1"]) == 0
    said = capsys.readouterr().out
    assert said.startswith("scan-based prediction (no calibration)"), said
    assert main(["validate", "score", str(predictions), str(folder)]) == 0
    said = capsys.readouterr().out
    first = said.splitlines()[0]
    assert first.startswith("scan-based prediction (no calibration)"), said
    assert "out-of-sample" not in said and "in-sample" not in said and "calibration never" \
        not in said


def test_densities_help_states_the_default_masses():
    from shaketable.cli import build_parser
    from shaketable.models.stack.geometry import DEFAULT_DENSITY, DEFAULT_DEPTH

    simulate = build_parser()._subparsers._group_actions[0].choices["simulate"]
    (densities,) = [action for action in simulate._actions
                    if "--densities" in action.option_strings]
    # the masses a stack gets without --masses or --densities (models.stack.geometry)
    assert (f"default: concrete, {DEFAULT_DENSITY:g} kg/m^3 over {DEFAULT_DEPTH:g} m of depth"
            in densities.help)
    assert "proportion" not in densities.help
