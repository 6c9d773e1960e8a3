"""The command line, run in-process through ``shaketable.cli.main``."""

import json

import pandas as pd
import pytest

from shaketable.cli import SUBCOMMANDS, main


def test_every_subcommand_has_help(capsys):
    for name in SUBCOMMANDS:
        with pytest.raises(SystemExit) as exit_info:
            main([name, "--help"])
        assert exit_info.value.code == 0
        assert "usage: shaketable" in capsys.readouterr().out


def test_simulate_free_rocking_writes_csv_json_and_figure(tmp_path, capsys):
    status = main(["simulate", "--block", "30x6in", "--cor", "0.925", "--theta0", "0.5alpha",
                   "--duration", "8", "--out", str(tmp_path)])
    assert status == 0
    frame = pd.read_csv(tmp_path / "history.csv")
    assert "theta [rad]" in frame.columns and frame["time [s]"].iloc[-1] == pytest.approx(8.0)
    summary = json.loads((tmp_path / "summary.json").read_text())
    # Fig. 3.4: released at 0.5 alpha, at rest after about 6 s
    assert summary["max_theta_ratio [-]"] == pytest.approx(0.5, rel=1e-12)
    assert 5.0 < summary["t_rest [s]"] < 7.0
    assert (tmp_path / "calcomp.png").stat().st_size > 10_000


def test_simulate_bundled_record(tmp_path):
    status = main(["simulate", "--block", "16x4ft", "--cor", "0.95", "--record",
                   "pacoima-dam-s16e", "--out", str(tmp_path), "--format", "svg"])
    assert status == 0
    assert (tmp_path / "calcomp.svg").exists()


@pytest.mark.parametrize("argv, message", [
    (["simulate", "--block", "30x6", "--cor", "0.9", "--duration", "1"], "no unit"),
    (["simulate", "--block", "30x6in", "--cor", "1.2", "--duration", "1"], "cor"),
    (["simulate", "--block", "30x6in", "--cor", "0.9", "--theta0", "0.1", "--duration", "1"],
     "theta0"),
    (["simulate", "--block", "30x6in", "--cor", "0.9", "--record", "no-such-record"],
     "no such file"),
])
def test_simulate_bad_input_is_a_clear_error(argv, message, tmp_path, capsys):
    assert main(argv + ["--out", str(tmp_path)]) == 2
    assert message in capsys.readouterr().err


def test_run_writes_parquet_and_svg_on_request(tmp_path, capsys):
    # `shaketable run SCENE --parquet --svg` (issue 5): history.parquet holds the same table
    # as history.csv, and the Calcomp figure is written as SVG besides PNG
    pytest.importorskip("pyarrow")
    out = tmp_path / "fig-2-9"
    assert main(["run", "fig-2-9", "--out", str(out), "--parquet", "--svg"]) == 0
    csv = pd.read_csv(out / "history.csv")
    parquet = pd.read_parquet(out / "history.parquet")
    assert list(parquet.columns) == list(csv.columns) and len(parquet) == len(csv) > 100
    pd.testing.assert_frame_equal(parquet, csv, check_exact=False, rtol=1e-12)
    assert (out / "calcomp.svg").read_text().lstrip().startswith(("<?xml", "<svg"))
    assert (out / "calcomp.png").stat().st_size > 10_000
    summary = json.loads((out / "summary.json").read_text())
    assert summary["scene"] == "fig-2-9" and summary["runs"][0]["cor [-]"] is not None
    # without the flags: neither
    plain = tmp_path / "plain"
    assert main(["run", "fig-2-9", "--out", str(plain)]) == 0
    assert not (plain / "history.parquet").exists() and not (plain / "calcomp.svg").exists()
    capsys.readouterr()
