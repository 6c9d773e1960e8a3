"""Refused command-line inputs: said naming the option, before any output folder is left
behind; plausible slips noted; short refusals for misspelt options and scene names."""

import pytest

from shaketable.cli import main

BLOCK = ["--block", "30x6in", "--cor", "0.9"]

#: (arguments without --out, the option the message must name, what it must say)
REFUSED = [
    (["simulate", *BLOCK, "--duration", "-3s"], "--duration",
     "--duration must be positive, got -3 s"),
    (["simulate", *BLOCK, "--duration", "0s"], "--duration", "got 0 s"),
    (["simulate", *BLOCK, "--duration", "3s", "--method", "predictor-corrector",
      "--subdivisions", "0"], "--subdivisions", "got 0"),
    (["simulate", "--stack", "30x6in,30x6in", "--cor", "0.9", "--duration", "-3s"],
     "--duration", "must be positive"),
    (["spectrum", "--block", "16x4ft", "--pulse", "half-sin"], "--pulse", "half-sin"),
    (["spectrum", "--block", "16x4ft", "--ratios", "-1,2"], "--ratios", "positive"),
    (["spectrum", "--block", "16x4ft", "--ceiling", "-1"], "--ceiling", "above 1"),
    (["spectrum", "--block", "16x4ft", "--scan-step", "-1"], "--scan-step", "(0, 1)"),
    (["spectrum", "--alpha", "0.25rad", "--p", "-2rad/s"], "--p", "got -2 rad/s"),
    (["slide", "--record", "pacoima-dam-s16e", "--sweep", "-0.1"], "--sweep", "-0.1"),
    (["slide", "--record", "nosuch"], "--record", "nosuch"),
    (["modemap", *BLOCK, "--record", "pacoima-dam-s16e", "--duration", "-3s"], "--duration",
     "got -3 s"),
    (["calibrate", "virtual-fig-3-4", "--block", "30x6in", "--rate", "-50Hz"], "--rate",
     "got -50 Hz"),
]


@pytest.mark.parametrize("argv, option, says", REFUSED,
                         ids=[f"{case[0][0]}-{case[1]}-{i}" for i, case in enumerate(REFUSED)])
def test_a_refused_value_names_its_option_and_leaves_no_output_folder(argv, option, says,
                                                                     tmp_path, monkeypatch,
                                                                     capsys):
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "results" / "run"
    try:
        status = main(argv + ["--out", str(out)])
    except SystemExit as stop:   # refused as the command line is read
        status = stop.code
    err = capsys.readouterr().err
    assert status == 2, err
    assert option in err and says in err, err
    assert "Traceback" not in err and "internal error" not in err, err
    assert list(tmp_path.iterdir()) == [], "a refused run left " + str(list(tmp_path.iterdir()))


def test_a_refusal_keeps_a_folder_that_existed_and_its_files(tmp_path, capsys):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("kept")
    (out / "empty").mkdir()
    status = main(["spectrum", "--block", "16x4ft", "--ceiling", "-1", "--out", str(out)])
    assert status == 2, capsys.readouterr().err
    assert (out / "notes.txt").read_text() == "kept" and (out / "empty").is_dir()
