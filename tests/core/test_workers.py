"""Worker processes end with their command: a second Ctrl-C while their pool is ended
still kills every one; the console command ends multiprocessing's helpers only after a
pool of its own, and never waits without bound for the resource tracker."""

from __future__ import annotations

import subprocess
import sys
import threading
import time

import pytest

from shaketable.core import workers


class _Process:
    """A worker that ignores SIGTERM (alive until killed); ``join`` of the first one is
    interrupted by a Ctrl-C."""

    def __init__(self, interrupts: int = 0):
        self.alive, self.killed, self.interrupts = True, False, interrupts

    def is_alive(self):
        return self.alive

    def terminate(self):
        pass

    def kill(self):
        self.alive, self.killed = False, True

    def join(self, timeout=None):
        if self.interrupts:
            self.interrupts -= 1
            raise KeyboardInterrupt


class _Pool:
    def __init__(self, processes):
        self._processes = dict(enumerate(processes))

    def shutdown(self, wait=True, cancel_futures=False):
        pass


def test_a_second_ctrl_c_while_waiting_still_kills_every_worker():
    processes = [_Process(interrupts=2), _Process(), _Process()]
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        workers.end_workers(_Pool(processes))
    assert all(process.killed for process in processes)
    assert time.monotonic() - start < 1.0   # no grace after the second Ctrl-C


class _InterruptedPool(_Pool):
    """A pool whose first ``shutdown`` is interrupted by a Ctrl-C."""

    def __init__(self, processes):
        super().__init__(processes)
        self.shutdowns = 0

    def shutdown(self, wait=True, cancel_futures=False):
        self.shutdowns += 1
        if self.shutdowns == 1:
            raise KeyboardInterrupt


def test_a_ctrl_c_while_the_pool_shuts_down_still_kills_every_worker():
    processes = [_Process(), _Process()]
    pool = _InterruptedPool(processes)
    with pytest.raises(KeyboardInterrupt):
        workers.end_workers(pool)
    assert all(process.killed for process in processes)
    assert pool.shutdowns == 2   # the queued work cancelled all the same


def test_a_ctrl_c_while_reproduce_ends_its_workers_keeps_the_error_that_stopped_it(
        monkeypatch, tmp_path):
    from shaketable import reproduce

    class _CrashingPool(_InterruptedPool):   # a second Ctrl-C while its workers are ended
        def submit(self, *args, **kwargs):
            raise RuntimeError("a scene crashed")

    pool = _CrashingPool([_Process()])
    monkeypatch.setattr(reproduce, "process_pool", lambda *args: pool)
    with pytest.raises(RuntimeError, match="a scene crashed"):
        reproduce._pooled(["a-scene"], tmp_path, 2, False, lambda *args: None)
    assert pool._processes[0].killed


def test_a_ctrl_c_while_the_command_ends_its_helpers_keeps_its_exit_status(monkeypatch, capsys):
    from shaketable import cli

    def interrupted():
        raise KeyboardInterrupt   # Ctrl-C during the wait for the resource tracker

    monkeypatch.setattr(cli, "_worker_processes_all_ended", lambda: True)
    monkeypatch.setattr(cli, "_stop_process_helpers", interrupted)
    monkeypatch.setattr(sys, "argv", ["shaketable", "records"])
    assert cli.main() == 0
    assert "PGA and PGV" in capsys.readouterr().out


def test_the_process_helpers_are_ended_only_after_a_pool_of_the_command(monkeypatch):
    import concurrent.futures.process  # noqa: F401  (imported by dask, say, without a pool)
    import multiprocessing

    from shaketable import cli

    monkeypatch.setattr(multiprocessing, "active_children", lambda: [])
    monkeypatch.setattr(workers, "_POOL_STARTED", False)
    assert not cli._worker_processes_all_ended()
    monkeypatch.setattr(workers, "_POOL_STARTED", True)
    assert cli._worker_processes_all_ended()


def test_the_wait_for_the_resource_tracker_is_bounded(monkeypatch):
    """A process that holds the tracker's pipe and that multiprocessing did not start
    keeps the tracker running: the command stops waiting after the time it gives. (A
    tracker of the test's own: the test process's tracker, which would unlink what other
    tests registered, is left running.)"""
    from multiprocessing import resource_tracker

    from shaketable import cli

    if not hasattr(resource_tracker.ResourceTracker, "_stop"):
        pytest.skip("Python < 3.11: the tracker ends on its own, nothing is waited for")
    shared = resource_tracker._resource_tracker
    shared_fd, shared_pid = shared._fd, shared._pid
    tracker = resource_tracker.ResourceTracker()
    monkeypatch.setattr(resource_tracker, "_resource_tracker", tracker)
    tracker.ensure_running()
    holder = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"],
                              pass_fds=(tracker._fd,))
    try:
        start = time.monotonic()
        assert cli._stop_resource_tracker(0.3) is False
        assert time.monotonic() - start < 2.0
    finally:
        holder.kill()
        holder.wait()
    for thread in threading.enumerate():   # the tracker ends once the holder has gone
        if thread.name == "shaketable-tracker-stop":
            thread.join(10)
            assert not thread.is_alive()
    assert tracker._fd is None   # this test's tracker ended; the process's is as it was
    assert (shared._fd, shared._pid) == (shared_fd, shared_pid)
