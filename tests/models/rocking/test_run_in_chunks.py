"""``run_in_chunks`` hands an exception back only once every thread has ended its chunk,
a Ctrl-C that reaches the calling thread while it waits for the others included (their
warnings and rows must not land after the call returned)."""

from __future__ import annotations

import signal
import threading
import time

import pytest

from shaketable.models.rocking.run import run_in_chunks


def test_a_ctrl_c_in_the_wait_still_waits_for_the_other_threads_chunk():
    caller = threading.get_ident()
    other_started, caller_done = threading.Event(), threading.Event()
    ended = []

    def run(start: int, stop: int) -> None:
        if threading.get_ident() == caller:
            other_started.wait(10.0)   # each thread takes one of the two chunks
            caller_done.set()
            return
        other_started.set()
        caller_done.wait(10.0)
        time.sleep(0.1)   # the calling thread has taken no other chunk: it waits
        signal.pthread_kill(caller, signal.SIGINT)   # Ctrl-C, delivered to that thread
        time.sleep(0.2)
        ended.append(start)

    # Python's own Ctrl-C handler for the test's duration: a test run started in the
    # background by a non-interactive shell inherits SIGINT ignored (tests/helpers.py)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            run_in_chunks(run, 2, 2, 1)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert len(ended) == 1   # the other thread's chunk ended before the call returned
