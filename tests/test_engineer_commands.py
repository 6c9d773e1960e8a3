"""What an engineer reaches for: the bundled records with their measures, a target PGA
instead of a bare factor, a precise refusal of --friction with --ensemble, and the mode
map of the user's own block and record.
"""

from __future__ import annotations

import json

import pytest

from shaketable.cli import main

# shaketable/data/records/PROVENANCE.md: DT, NPTS and PGA [g] as the files' headers and
# values give them (3 decimals there)
PROVENANCE = {"pacoima-dam-s16e": (0.01, 4172, 1.219), "pacoima-dam-s74w": (0.01, 4172, 1.238),
              "el-centro-1940-180": (0.01, 5378, 0.281), "el-centro-1940-270": (0.01, 5378, 0.211),
              "el-centro-chopra": (0.02, 1560, 0.319)}


def test_records_lists_every_bundled_record_with_its_measures(tmp_path, capsys):
    from shaketable.ground import records

    path = tmp_path / "records.csv"
    assert main(["records", "--csv", str(path)]) == 0
    printed = capsys.readouterr().out
    import pandas as pd

    table = pd.read_csv(path)
    assert sorted(table["name"]) == records.available()
    for name, (dt, samples, pga) in PROVENANCE.items():
        row = table[table["name"] == name].iloc[0]
        assert row["dt [s]"] == pytest.approx(dt)
        # the El Centro components are padded to the longest (5378 samples)
        assert row["samples"] == samples
        assert row["PGA [g]"] == pytest.approx(pga, abs=5e-4)
        assert f"{pga:.3f}" in printed.split(name, 1)[1].splitlines()[0]
    down = table[table["name"] == "pacoima-dam-down"].iloc[0]
    assert down["components"] == "vertical" and down["vertical PGA [g]"] == pytest.approx(
        0.687, abs=5e-4)
    assert "PEER NGA-West2 RSN77" in printed


@pytest.mark.usefixtures("figure_drafts")
def test_pga_target_scales_the_record_and_says_by_how_much(tmp_path, capsys):
    out = tmp_path / "p"
    assert main(["simulate", "--block", "2x0.5m", "--record", "el-centro-chopra", "--pga",
                 "0.5g", "--cor", "0.9", "--duration", "2s", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    # the record's own PGA 0.3188 g (PROVENANCE.md: 0.319): the factor is 0.5 / 0.3188
    line = next(line for line in printed.splitlines() if "own PGA" in line)
    own = float(line.split("own PGA ")[1].split(" g")[0])
    factor = float(line.split("scaled by ")[1].split(" ")[0])
    assert own == pytest.approx(0.319, abs=5e-4)
    assert factor == pytest.approx(0.5 / own, rel=1e-3)
    assert main(["slide", "--block", "2x0.5m", "--record", "el-centro-chopra", "--pga", "0.4g",
                 "--static-friction", "0.2", "--out", str(tmp_path / "s")]) == 0
    first, second = capsys.readouterr().out.splitlines()[:2]
    assert first.startswith("slid: peak slip ") and " mm, residual " in first
    assert second.startswith("record el-centro-chopra: own PGA 0.3188 g, scaled by 1.255")
    with pytest.raises(SystemExit) as refused:       # argparse: mutually exclusive
        main(["simulate", "--block", "2x0.5m", "--record", "el-centro-chopra", "--pga",
              "0.5g", "--scale", "2", "--cor", "0.9", "--out", str(out)])
    assert refused.value.code == 2
    assert "not allowed with argument --pga" in capsys.readouterr().err
    assert main(["simulate", "--block", "2x0.5m", "--harmonic", "2Hz,0.1g", "--pga", "0.5g",
                 "--cor", "0.9", "--duration", "1s", "--out", str(out)]) == 2
    assert "--pga 0.5g: scales a --record" in capsys.readouterr().err


def test_friction_with_ensemble_runs_the_planar_model(tmp_path, capsys):
    import pandas as pd

    import shaketable as st
    from shaketable.ground import records

    out = tmp_path / "e"
    assert main(["simulate", "--block", "2x0.5m", "--record", "el-centro-chopra", "--pga",
                 "0.5g", "--cor", "0.9", "--friction", "0.3", "--ensemble", "3", "--perturb",
                 "0.01", "--duration", "4s", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith("2 x 0.5 m block, COR 0.9, mu_s 0.3, mu_d 0.3, 3 members (planar "
                              "model): P(overturn) = ")
    # what the members differ by is said with the answer (here 1 %: no chaos-probe note)
    assert ("  members differ by a relative spread of: amplitude 0.01, cor 0.01, size 0.01, "
            "start 0.01\n") in printed
    members = pd.read_csv(out / "ensemble.csv")
    # member 0 is the nominal run: the plain planar run of the same inputs, bit for bit
    motion = records.load("el-centro-chopra")
    motion = motion.scaled(0.5 * st.G / motion.pga)
    plain = st.simulate(st.Block.parse("2x0.5m"), motion, cor=0.9, friction=st.Friction(0.3),
                        duration=4.0)
    assert members["peak slip [m]"].iloc[0] == plain.peak_slip
    assert members["peak corner excursion [m]"].iloc[0] == plain.peak_excursion
    assert members["verdict"].iloc[0] == plain.verdict()
    # the others are perturbed copies: their factors within the spread
    assert (members["amplitude factor [-]"] - 1).abs().max() <= 0.01
    summary = json.loads((out / "ensemble.json").read_text())
    assert summary["members"] == 3 and summary["P low [-]"] <= summary["P(overturn) [-]"]


def test_modemap_of_the_users_block_and_record(tmp_path, capsys):
    out = tmp_path / "m"
    assert main(["modemap", "--block", "2x0.5m", "--record", "el-centro-chopra", "--pga",
                 "0.5g", "--frictions", "0.1,0.4", "--aspect-ratios", "0.5", "--duration",
                 "8s", "--tolerance", "1e-3", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith("2 x 0.5 m block (B/H 0.25) under El Centro")
    assert "nan" not in printed.lower() and "ft" not in printed
    summary = json.loads((out / "summary.json").read_text())
    assert summary["block"] == "2 x 0.5 m" and summary["pga [g]"] == pytest.approx(0.5)
    # Section 2.1: a block slides if mu_s < B/H and rocks otherwise (the planar model
    # agrees to the bisection's width, tests/studies/test_mode_map.py)
    assert summary["largest mu that only slides [-]"] == pytest.approx(0.25, abs=2e-3)
    assert summary["verdicts"]["0.1"] == "slid" and summary["verdicts"]["0.4"] != "slid"
    import pandas as pd

    frame = pd.read_csv(out / "mode_map.csv")
    assert sorted(frame["B/H [-]"].unique()) == [0.25, 0.5]     # the user's B/H added
    assert (out / "mode_map.png").stat().st_size > 0


def test_friction_sweep_slip_figure_draws_median_and_84th_percentile():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    from shaketable.plots.sweep_slip import slip_against_intensity

    # three records at two levels; at 0.4 g one of them overturns (left out)
    slips = {0.2: [0.001, 0.002, 0.004], 0.4: [0.010, 0.030, 0.5]}
    rows = pd.DataFrame([{"block": "2 x 0.5 m", "cor [-]": 0.9, "record": f"r{k}",
                          "pga [g]": level, "peak slip [m]": value,
                          "peak corner excursion [m]": 2 * value,
                          "overturned": level == 0.4 and k == 2}
                         for level, values in slips.items() for k, value in enumerate(values)])
    figure = slip_against_intensity(rows)
    slip_axis = figure.axes[0]
    lines = {line.get_label(): line for line in slip_axis.get_lines()}
    assert slip_axis.get_ylabel() == "peak slip of the base [mm]"
    # median and 84th percentile (linear interpolation) of the standing runs, in mm
    assert list(lines["median"].get_ydata()) == pytest.approx([2.0, 20.0])
    assert list(lines["84th percentile"].get_ydata()) == pytest.approx(
        [2.0 + 0.68 * 2.0, 10.0 + 0.84 * 20.0])
    assert any(text.get_text() == "1/3\nfell" for text in slip_axis.texts)
    plt.close(figure)
