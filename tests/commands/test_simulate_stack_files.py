"""``simulate --stack`` offers ``--history peaks`` and ``--parquet`` with the single block's
meaning: the extremes and the events of the run, and the history table as Parquet too."""

from __future__ import annotations

import numpy as np
import pandas as pd

from shaketable.cli import main


def test_stack_history_peaks_keeps_every_event_and_extreme(tmp_path, capsys):
    from shaketable.models.stack import simulate_stack
    from shaketable.scenes.stack import per_block_angles, stack_from_text

    assert main(["simulate", "--stack", "30x6in,30x6in", "--theta0", "0.6alpha,0.3alpha",
                 "--duration", "1.5s", "--history", "peaks", "--parquet",
                 "--out", str(tmp_path / "peaks")]) == 0
    said = capsys.readouterr().out
    assert "history.parquet" in said
    # the same run in full (free rocking from the same tilts)
    stack = stack_from_text("30x6in,30x6in")
    full = simulate_stack(stack, None, theta0=per_block_angles("0.6alpha,0.3alpha", stack,
                                                                where="--theta0"),
                          duration=1.5).to_frame()
    peaks = pd.read_csv(tmp_path / "peaks" / "history.csv")
    # the same samples, fewer of them: each row of peaks is the full history's row
    assert 2 < len(peaks) < len(full) / 3
    rows = np.searchsorted(full["t [s]"].to_numpy(), peaks["t [s]"].to_numpy())
    pd.testing.assert_frame_equal(full.iloc[rows].reset_index(drop=True), peaks,
                                  check_dtype=False, check_exact=False, rtol=1e-15)
    kept = set(rows)
    assert {0, len(full) - 1} <= kept
    # every change of contact pattern (uplift, impact, rest) with the sample before it
    pattern = full["pattern"].to_numpy()
    changes = np.flatnonzero(pattern[1:] != pattern[:-1]) + 1
    assert changes.size and set(changes) <= kept and set(changes - 1) <= kept
    # every block's largest |theta| (a turning point: theta' changes sign there)
    for i in (0, 1):
        assert int(np.argmax(np.abs(full[f"theta_{i} [rad]"].to_numpy()))) in kept
    # the Parquet table is the CSV's
    parquet = pd.read_parquet(tmp_path / "peaks" / "history.parquet")
    pd.testing.assert_frame_equal(parquet, peaks, check_dtype=False, check_exact=False,
                                  rtol=1e-15)


def test_parquet_without_a_history_is_refused(tmp_path, capsys):
    assert main(["simulate", "--stack", "30x6in,30x6in", "--theta0", "0.5alpha",
                 "--duration", "1s", "--history", "none", "--parquet",
                 "--out", str(tmp_path / "o")]) == 2
    assert "--parquet" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()
