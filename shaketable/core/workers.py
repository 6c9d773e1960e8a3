"""Worker processes that end with their command: Ctrl-C stops the parent, which ends them.

A command that computes in a ``concurrent.futures.ProcessPoolExecutor`` (a sweep's chunks,
the reproduction's sections) starts its workers ignoring Ctrl-C
(:func:`interrupts_ignored` around the submits, :func:`ignore_interrupts` as their
initializer) and, when Ctrl-C or an error stops it, ends them at once
(:func:`end_workers`). Otherwise Ctrl-C, sent to every process of the terminal's group,
interrupts each worker wherever it is: the pool then waits for the chunk each had queued,
or for a worker left blocked on its queue's lock, and a worker still starting prints a
traceback.
"""

from __future__ import annotations

import time
from contextlib import contextmanager

#: Seconds a worker process is given to end after SIGTERM before it is killed.
WORKER_GRACE = 2.0

#: Whether this process has started a pool of worker processes (:func:`process_pool`).
_POOL_STARTED = False


def process_pool(workers: int, initializer):
    """A ``ProcessPoolExecutor`` of ``workers`` fresh ("spawn") processes, each running
    ``initializer`` first, recorded as started (:func:`pool_started`)."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    global _POOL_STARTED
    _POOL_STARTED = True
    return ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn"),
                               initializer=initializer)


def pool_started() -> bool:
    """Whether this process has started a pool of worker processes (:func:`process_pool`):
    only then has it multiprocessing's helpers (its resource tracker) to end."""
    return _POOL_STARTED


def ignore_interrupts() -> None:
    """In a worker process: ignore Ctrl-C (its parent ends it)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextmanager
def interrupts_ignored():
    """Ignore Ctrl-C while worker processes start, so that they start ignoring it (an
    ignored signal stays ignored in a new program, and Python keeps it so); a Ctrl-C in
    these few milliseconds is lost. Outside the main thread (where signals cannot be
    set) nothing changes and the workers ignore Ctrl-C from their initializer on."""
    import signal
    import threading

    previous = signal.getsignal(signal.SIGINT)
    # a handler set outside Python (None) could not be put back: left as it is
    if threading.current_thread() is not threading.main_thread() or previous is None:
        yield
        return
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def end_workers(pool) -> None:
    """End a process pool's workers now (SIGTERM, then SIGKILL after
    :data:`WORKER_GRACE` s) and wait for them: the work in progress is abandoned, no
    worker outlives its command.

    A Ctrl-C while waiting (the workers ignore it) ends the grace: the workers still
    running are killed and waited for, then the KeyboardInterrupt is raised."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    interrupted = False
    for process in processes:
        try:
            if process.is_alive():
                process.terminate()
        except KeyboardInterrupt:
            interrupted = True
    while True:   # the pool's queued work cancelled, whatever Ctrl-C comes meanwhile
        try:
            pool.shutdown(wait=False, cancel_futures=True)
            break
        except KeyboardInterrupt:
            interrupted = True
    deadline = time.monotonic() + WORKER_GRACE
    for process in processes:
        while True:   # until this worker has ended, whatever Ctrl-C comes meanwhile
            try:
                if not interrupted:
                    process.join(max(0.0, deadline - time.monotonic()))
                if process.is_alive():
                    process.kill()
                    process.join()
                break
            except KeyboardInterrupt:
                interrupted = True
    if interrupted:
        raise KeyboardInterrupt


def end_workers_after(pool) -> None:
    """:func:`end_workers` while an error that stopped the work (Ctrl-C, a crash) is being
    handled: a second Ctrl-C meanwhile is not raised (the workers end all the same), so
    that the error raised is the one that stopped the work."""
    try:
        end_workers(pool)
    except KeyboardInterrupt:
        pass
