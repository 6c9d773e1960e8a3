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
    # checked before the folder is made: not left to the CLI's clean-up of a refusal
    monkeypatch.setattr("shaketable.cli._remove_empty_folders", lambda folders: None)
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


def test_a_late_refusal_removes_only_the_folders_its_command_made(tmp_path, monkeypatch,
                                                                  capsys):
    """A refusal found after the output folder was made (here the spectrum's own check,
    as if the command had not checked first) removes that folder, but not one that
    existed (another process may be writing there: two sweeps started together on one
    folder)."""
    from shaketable.studies import overturning_spectrum

    def refuse(*args, **kwargs):
        raise ValueError("scan_step must be in (0, 1), got 2")

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(overturning_spectrum, "overturning_spectrum", refuse)
    argv = ["spectrum", "--block", "16x4ft", "--ratios", "2"]
    assert main(argv + ["--out", "new/run"]) == 2, capsys.readouterr().err
    assert not (tmp_path / "new").exists()
    (tmp_path / "busy").mkdir()   # made by someone else, empty for now
    assert main(argv + ["--out", "busy"]) == 2, capsys.readouterr().err
    assert (tmp_path / "busy").is_dir()


def test_a_late_refusal_leaves_what_another_process_began_in_its_folder(tmp_path,
                                                                         monkeypatch, capsys):
    """Two sweeps started together on one folder: this command made ``out``, the other
    found it, took its lock and made ``out/parts``; this command's refusal must leave
    both (removing the empty ``parts`` broke the other's first chunk)."""
    from shaketable.studies import overturning_spectrum

    def other_process_begins_then_refuse(*args, **kwargs):
        (tmp_path / "out" / ".shaketable.lock").write_text("")
        (tmp_path / "out" / "parts").mkdir()
        raise ValueError("scan_step must be in (0, 1), got 2")

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(overturning_spectrum, "overturning_spectrum",
                        other_process_begins_then_refuse)
    argv = ["spectrum", "--block", "16x4ft", "--ratios", "2", "--out", "out"]
    assert main(argv) == 2, capsys.readouterr().err
    assert (tmp_path / "out" / "parts").is_dir()


# ------------------------------------------------------------ slips noted, runs kept
@pytest.mark.parametrize("text, says", [
    ("6x30in", "--block 6x30in is 6 in tall and 30 in wide (B/H = 5, alpha = 78.7 deg); "
               "the order is height x width: did you mean 30x6in?"),
    ("6in x 30in", "did you mean 30x6in?"),
    ("2ft x 30in", "2 ft tall and 30 in wide (B/H = 1.25, alpha = 51.3 deg); the order is "
                   "height x width: did you mean 30in x 2ft?"),
    ("1x2m", "(B/H = 2, alpha = 63.4 deg)"),
])
def test_a_block_wider_than_tall_is_noted_and_kept(text, says, capsys):
    import math

    from shaketable.commands.options import block_option

    block = block_option(text)
    # the block as written: B/H = 5 gives alpha = atan(5) = 78.69 deg (Eq. 2-1's tan alpha = B/H)
    assert block.width > block.height
    assert math.degrees(block.alpha) == pytest.approx(math.degrees(math.atan(
        block.width / block.height)), rel=1e-12)
    err = capsys.readouterr().err
    assert err.startswith("shaketable: note: ") and says in err and err.count("\n") == 1, err


@pytest.mark.parametrize("text", ["30x6in", "16x4ft", "2x2m"])
def test_a_block_not_wider_than_tall_gets_no_note(text, capsys):
    from shaketable.commands.options import block_option

    block_option(text)
    assert capsys.readouterr().err == ""


def test_simulate_runs_a_wide_block_after_the_note(tmp_path, capsys):
    status = main(["simulate", "--block", "6x30in", "--cor", "0.9", "--theta0", "0.5alpha",
                   "--duration", "0.2s", "--out", str(tmp_path / "wide")])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert "did you mean 30x6in?" in captured.err
    assert (tmp_path / "wide" / "summary.json").exists()


@pytest.mark.parametrize("text, noted", [("0.5alpha", False), ("-0.99alpha", False),
                                          ("2alpha", True), ("-1.5alpha", True),
                                          ("30deg", True), ("5deg", False)])
def test_a_release_past_alpha_is_noted(text, noted, capsys):
    from shaketable.commands.block import resolve_angle
    from shaketable.commands.options import block_option

    block = block_option("30x6in")   # alpha = atan(6/30) = 11.31 deg
    assert abs(resolve_angle(text, block)) > 0
    err = capsys.readouterr().err
    assert ("past alpha" in err and "falls at once" in err) == noted, err


def test_a_release_at_or_past_ninety_degrees_is_refused_naming_the_option():
    from shaketable.commands.block import resolve_angle
    from shaketable.commands.options import block_option

    with pytest.raises(ValueError, match=r"--theta0 10alpha: the tilt must be below 90 deg"):
        resolve_angle("10alpha", block_option("30x6in"))   # 10 x 11.31 deg = 113 deg


# ------------------------------------------------------- short refusals, the hint first
@pytest.mark.parametrize("argv, says", [
    (["simulate", "--blok", "30x6in", "--cor", "0.9"],
     "shaketable simulate: error: unrecognized arguments: --blok 30x6in; "
     "--blok: did you mean --block?"),
    (["calibrate", "virtual-fig-3-4"],
     "shaketable calibrate: error: the following arguments are required: --block"),
    (["simulate", "--method", "nope"], "shaketable simulate: error: argument --method"),
])
def test_a_usage_error_is_one_line_and_a_pointer_to_the_help(argv, says, capsys):
    with pytest.raises(SystemExit) as stop:
        main(argv)
    err = capsys.readouterr().err
    assert stop.value.code == 2
    command = argv[0]
    assert err == f"{err.splitlines()[0]}\nsee 'shaketable {command} --help'\n", err
    assert err.startswith(says), err


def test_a_misspelt_scene_name_leads_with_the_name_meant(capsys):
    assert main(["run", "fig-3-77"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("shaketable run: error: no scene 'fig-3-77': did you mean fig-3-7? ")
    assert err.index("did you mean") < err.index("available:")
    assert main(["run", "zzz"]) == 2   # nothing close: no guess
    assert "did you mean" not in capsys.readouterr().err


def test_reproduce_names_the_scene_meant_for_each_misspelt_one(tmp_path, capsys):
    assert main(["reproduce", "fig-3-77", "tabel-4-2", "zzz", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert ("no scene 'fig-3-77' (did you mean fig-3-7?), 'tabel-4-2' (did you mean "
            "table-4-2?), 'zzz'; ") in err, err
    assert not (tmp_path / "o").exists()
