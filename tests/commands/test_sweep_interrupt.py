"""Ctrl-C on ``shaketable sweep --workers 2`` while its worker processes are in the middle of
their chunks: the command ends at once (status 130, one line, no traceback), its workers
end with it (none goes on computing its chunk, none outlives the command), and the chunks
already on disk are kept for ``--resume``."""

from __future__ import annotations

import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.helpers import REPOSITORY, ctrl_c_reaches_subprocesses

# A stack sweep whose first chunk is cheap (400 runs of 0.5 s records, ~1 s of CPU) and whose
# three others are long (400 runs of 60 s records each, ~1.6 s of CPU per chunk: the stack
# batch takes a few ms per run): when part 0 is on disk both workers are mid-chunk.
SPEC = """\
name = "ctrl-c-check"
description = "a cheap first chunk, then long ones"
seed = 1

[stacks]
sizes = ["30x6in"]
blocks = [2]

[rocking]
cor = "plastic"

[[records]]
preset = "olive-view"
seeds = 100
duration = "0.5 s"
label = "short"

[[records]]
preset = "olive-view"
seeds = 300
duration = "60 s"

[intensity]
pga = ["0.05 g", "0.08 g", "0.12 g", "0.16 g"]

[run]
chunk_size = 400
"""


def _session_processes(session: int) -> list[int]:
    """The processes (zombies included) of the session ``session``."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:   # ended meanwhile
                continue
            if int(fields[3]) == session:   # the session id (field 6 of stat)
                found.append(int(entry.name))
    return found


def _session_cpu_seconds(session: int) -> float:
    """CPU time [s] used so far by every process of the session ``session``."""
    total = 0.0
    for pid in _session_processes(session):
        try:
            fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        total += (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    return total


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/stat").is_file(), reason="needs Linux's /proc")
def test_ctrl_c_ends_a_sweep_and_its_workers_at_once_and_keeps_the_finished_chunks(tmp_path):
    from multiprocessing.resource_tracker import ResourceTracker

    from shaketable.sweeps.execute import run_sweep
    from shaketable.sweeps.spec import load_spec

    def children_cpu() -> float:
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        return usage.ru_utime + usage.ru_stime

    (tmp_path / "spec.toml").write_text(SPEC)
    environment = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(REPOSITORY))
    cpu_before = children_cpu()
    # a session of its own, signalled as a whole: what Ctrl-C in a terminal does
    with ctrl_c_reaches_subprocesses():   # as from a terminal, however the tests started
        process = subprocess.Popen(
            [sys.executable, "-m", "shaketable", "sweep", "spec.toml", "--out", "out",
             "--workers", "2", "--no-progress"],
            cwd=tmp_path, env=environment, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
            text=True, start_new_session=True)
    first = tmp_path / "out" / "parts" / "part-000000.parquet"
    started = time.perf_counter()
    while not first.exists() and process.poll() is None \
            and time.perf_counter() - started < 240.0:
        time.sleep(0.02)
    assert process.poll() is None, process.communicate()
    assert first.exists(), "no chunk finished within 240 s"
    at_signal = _session_cpu_seconds(process.pid)
    sent = time.perf_counter()
    os.killpg(process.pid, signal.SIGINT)
    try:
        _, err = process.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        _, err = process.communicate()
        pytest.fail(f"still running 30 s after Ctrl-C; stderr: {err}")
    waited = time.perf_counter() - sent
    assert process.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err, err
    assert waited < 10.0, waited   # generous: a hang, not a busy machine
    # every process of the command, from the signal to its exit, by CPU time (what a busy
    # machine changes least): measured 0.10 s; 1.8-2.3 s when the workers finished their
    # chunks first (the parent waiting 2-3.5 s for them)
    after_signal = children_cpu() - cpu_before - at_signal
    assert after_signal < 0.6, after_signal
    if hasattr(ResourceTracker, "_stop"):   # Python >= 3.11: the tracker is waited for too
        assert _session_processes(process.pid) == [], "a process outlived the command"
    # the finished chunk is kept: resuming computes nothing again that is on disk
    parts = sorted(path.name for path in (tmp_path / "out" / "parts").iterdir())
    assert parts[0] == "part-000000.parquet" and all(
        name.startswith("part-") for name in parts), parts   # no half-written part
    outcome = run_sweep(load_spec(tmp_path / "spec.toml"), tmp_path / "out", resume=True,
                        progress=False, max_chunks=0)
    assert outcome.skipped_runs == 400 * len(parts) and outcome.computed_runs == 0
