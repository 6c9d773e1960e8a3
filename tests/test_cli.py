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
                   "--duration", "8s", "--out", str(tmp_path)])
    assert status == 0
    frame = pd.read_csv(tmp_path / "history.csv")
    assert "theta [rad]" in frame.columns and frame["time [s]"].iloc[-1] == pytest.approx(8.0)
    summary = json.loads((tmp_path / "summary.json").read_text())
    # Fig. 3.4: released at 0.5 alpha, at rest after about 6 s
    assert summary["max_theta_ratio [-]"] == pytest.approx(0.5, rel=1e-12)
    assert 5.0 < summary["t_rest [s]"] < 7.0
    assert (tmp_path / "calcomp.png").stat().st_size > 10_000


@pytest.mark.usefixtures("figure_drafts")
def test_simulate_bundled_record(tmp_path):
    status = main(["simulate", "--block", "16x4ft", "--cor", "0.95", "--record",
                   "pacoima-dam-s16e", "--out", str(tmp_path), "--format", "svg"])
    assert status == 0
    assert (tmp_path / "calcomp.svg").exists()


@pytest.mark.parametrize("argv, message", [
    (["simulate", "--block", "30x6", "--cor", "0.9", "--duration", "1s"], "no unit"),
    (["simulate", "--block", "30x6in", "--cor", "1.2", "--duration", "1s"], "cor"),
    (["simulate", "--block", "30x6in", "--cor", "0.9", "--theta0", "0.1", "--duration", "1s"],
     "theta0"),
    (["simulate", "--block", "30x6in", "--cor", "0.9", "--record", "no-such-record"],
     "no such file"),
])
def test_simulate_bad_input_is_a_clear_error(argv, message, tmp_path, capsys):
    assert main(argv + ["--out", str(tmp_path)]) == 2
    assert message in capsys.readouterr().err


#: Every dimensional option of every subcommand, with a value lacking its unit.
DIMENSIONAL_OPTIONS = [
    (["simulate", "--block", "30x6in", "--cor", "0.9"], "--duration", "8", "time"),
    (["simulate", "--block", "30x6in", "--cor", "0.9"], "--dt", "0.02", "time"),
    (["animate", "fig-3-4", "--out", "x.gif"], "--start", "2", "time"),
    (["animate", "fig-3-4", "--out", "x.gif"], "--end", "4", "time"),
    (["spectrum"], "--alpha", "0.25", "angle"),
    (["spectrum"], "--p", "2", "angular frequency"),
    (["calibrate", "free.csv", "--block", "30x6in"], "--rate", "50", "frequency"),
]


@pytest.mark.parametrize("argv, option, bare, kind", DIMENSIONAL_OPTIONS)
def test_dimensional_options_need_their_unit_and_say_so_in_one_line(argv, option, bare, kind,
                                                                     capsys):
    # `--duration 8` is refused like `--theta0 0.5`: one line naming the option, the value
    # and the kind of quantity, exit status 2, no argparse usage dump
    with pytest.raises(SystemExit) as exit_info:
        main(argv + [option, bare])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "usage:" not in err
    assert err.startswith(f"shaketable {argv[0]}: error: {option}: '{bare}' has no unit")
    assert f"write the {kind} with its unit" in err


def test_dimensional_options_take_their_unit():
    # the same options with a unit are read in SI: 8 s, 20 ms, 0.25 rad, 3 deg, 2 rad/s, 50 Hz
    from shaketable.cli import build_parser

    parser = build_parser()
    args = parser.parse_args(["simulate", "--block", "30x6in", "--cor", "0.9",
                              "--duration", "8s", "--dt", "20 ms"])
    assert (args.duration, args.dt) == (8.0, pytest.approx(0.02, rel=1e-15))
    args = parser.parse_args(["spectrum", "--alpha", "3deg", "--p", "2rad/s"])
    assert args.alpha == pytest.approx(3 * 3.141592653589793 / 180, rel=1e-15) and args.p == 2.0
    args = parser.parse_args(["calibrate", "x.csv", "--block", "30x6in", "--rate", "50Hz"])
    assert args.rate == 50.0


def test_run_writes_parquet_and_svg_on_request(tmp_path, capsys):
    # `shaketable run SCENE --parquet --svg`: history.parquet holds the same table
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


@pytest.mark.usefixtures("figure_drafts")
def test_simulate_harmonic_and_pulse_from_the_command_line(tmp_path, capsys):
    # table motions without a scene file. The ground column of history.csv is
    # the closed form: 0.15 sin(2 pi 2 t) [g], and a half sine 0.5 sin(pi t / 0.2 s) then 0
    import numpy as np

    out = tmp_path / "harmonic"
    assert main(["simulate", "--block", "30x6in", "--cor", "0.9", "--harmonic", "2Hz,0.15g",
                 "--duration", "2s", "--out", str(out)]) == 0
    frame = pd.read_csv(out / "history.csv")
    t = frame["time [s]"].to_numpy()
    assert t[-1] == pytest.approx(2.0)
    assert np.allclose(frame["ground horizontal [g]"], 0.15 * np.sin(4 * np.pi * t), atol=1e-12)
    # Eq. 2-1: 0.15 g is below B/H = 0.2 g, so the block never rocks
    assert np.all(frame["theta [rad]"] == 0.0)
    out = tmp_path / "pulse"
    assert main(["simulate", "--block", "30x6in", "--cor", "0.9", "--pulse",
                 "half-sine,0.5g,0.2s", "--duration", "2s", "--out", str(out)]) == 0
    frame = pd.read_csv(out / "history.csv")
    t, ground = frame["time [s]"].to_numpy(), frame["ground horizontal [g]"].to_numpy()
    assert np.allclose(ground, np.where(t <= 0.2, 0.5 * np.sin(np.pi * t / 0.2), 0.0),
                       atol=1e-12)
    out = tmp_path / "one-cosine"
    assert main(["simulate", "--block", "30x6in", "--cor", "0.9", "--pulse",
                 "one-cosine,0.3g,0.5s", "--duration", "2s", "--out", str(out)]) == 0
    frame = pd.read_csv(out / "history.csv")
    t, ground = frame["time [s]"].to_numpy(), frame["ground horizontal [g]"].to_numpy()
    inside = t < 0.5
    # one cosine of period 0.5 s: 0.3 cos(2 pi t / 0.5 s) during the pulse, then nothing
    assert np.allclose(ground[inside], 0.3 * np.cos(4 * np.pi * t[inside]), atol=1e-12)
    assert np.all(ground[t > 0.5 + 1e-6] == 0.0)


@pytest.mark.parametrize("motion, message", [
    (["--harmonic", "2Hz,0.5g", "--record", "pacoima-dam-s16e", "--duration", "1s"],
     "give one table motion"),
    (["--harmonic", "2Hz,0.5g"], "--harmonic needs --duration"),
    (["--harmonic", "2,0.5g", "--duration", "1s"], "'2' has no unit"),
    (["--harmonic", "2Hz", "--duration", "1s"], "give 2 or 3 values"),
    (["--pulse", "half-sine,0.5g", "--duration", "1s"], "--pulse 'half-sine,0.5g': give 2"),
    (["--pulse", "wobble,0.5g,1s", "--duration", "2s"], "unknown pulse kind 'wobble'"),
    (["--pulse", "half-sine,0.5g,3s", "--duration", "2s"], "--pulse"),
])
def test_simulate_motion_options_bad_input(motion, message, tmp_path, capsys):
    assert main(["simulate", "--block", "30x6in", "--cor", "0.9", *motion,
                 "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert message in err and "usage:" not in err


def test_reproduce_ends_with_the_agree_differ_summary(tmp_path, capsys):
    # the console ends with the report's headline, the same counts as report.md's
    # (Table 4.4 compares values of both kinds: the report's inputs and substitutes)
    out = tmp_path / "rep"
    assert main(["reproduce", "table-4-4", "--out", str(out)]) == 0
    printed = capsys.readouterr().out.splitlines()
    report = (out / "report.md").read_text()
    summary = [line for line in printed if line.startswith(("Against", "By construction"))]
    # no line for a kind without comparisons (Table 4.4 has none by construction)
    assert len(summary) == 2 and printed[-1].startswith("wrote ")
    assert summary[1].startswith("Against SUBSTITUTE") and "By construction" not in report
    for line in summary:
        assert f"**{line}**" in report
    assert "comparisons agree" in summary[0]


def test_examples_copies_the_gallery_scripts_out_of_the_package(tmp_path, capsys):
    # a pip user has no examples/ folder; the scripts are package data
    from tests.helpers import REPOSITORY

    out = tmp_path / "mine"
    assert main(["examples", "--out", str(out)]) == 0
    shipped = sorted(path.name for path in (REPOSITORY / "examples").glob("plot_*.py"))
    copied = sorted(path.name for path in out.glob("plot_*.py"))
    assert copied == shipped and len(copied) >= 10 and (out / "README.rst").is_file()
    for name in copied:   # the same text as the repository's gallery
        assert (out / name).read_bytes() == (REPOSITORY / "examples" / name).read_bytes()
    capsys.readouterr()
    assert main(["examples", "--out", str(out)]) == 2       # nothing overwritten silently
    assert "--force" in capsys.readouterr().err
    assert main(["examples", "--out", str(out), "--force"]) == 0
    assert main(["examples", "--list"]) == 0
    assert "plot_tutorial_rock_a_block.py" in capsys.readouterr().out


def test_a_misspelt_option_is_refused_by_its_subcommand_with_the_option_meant(capsys):
    # argparse's top-level parser would say "shaketable: error: unrecognized arguments"
    # with the top-level usage: the subcommand's own parser names itself and its option
    assert_exit = pytest.raises(SystemExit)
    with assert_exit as caught:
        main(["simulate", "--block", "30x6in", "--cor", "0.9", "--duraton", "5s"])
    assert caught.value.code == 2
    error = capsys.readouterr().err
    assert "shaketable simulate: error: unrecognized arguments: --duraton 5s" in error
    assert "did you mean --duration?" in error and "usage:" not in error
    assert error.endswith("see 'shaketable simulate --help'\n")
    # an argument far from every option gets no guess
    with pytest.raises(SystemExit):
        main(["run", "fig-3-7", "--nosuch"])
    assert "did you mean" not in capsys.readouterr().err


def test_sweep_and_assess_help_list_every_bundled_name(capsys):
    # the README sends a user to `sweep --help` and `assess --help` for the bundled names:
    # every spec of experiments/sweeps and every object of experiments/assess is listed
    from shaketable.scenes.catalog import experiments_folder

    for command, folder in (("sweep", "sweeps"), ("assess", "assess")):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        shown = "".join(capsys.readouterr().out.split())   # argparse wraps at hyphens
        names = sorted(p.stem for p in (experiments_folder() / folder).glob("*.toml"))
        assert names and all(name in shown for name in names), (command, names)
