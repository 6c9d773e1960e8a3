"""Paths shared by the tests (the repository, and the project's shared data outside it)."""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

import pytest

#: The repository's root folder.
REPOSITORY = Path(__file__).resolve().parents[1]

#: The project's shared folder (report, real records); ``SHAKETABLE_SHARED`` overrides.
SHARED = Path(os.environ.get("SHAKETABLE_SHARED") or REPOSITORY.parent / "shared")

#: The real records with their ``PROVENANCE.md`` (read by tests, never committed).
SHARED_RECORDS = SHARED / "data" / "records"

#: Skip a test cleanly where the shared records are absent (e.g. a bare CI machine).
needs_shared = pytest.mark.skipif(not (SHARED_RECORDS / "PROVENANCE.md").is_file(),
                                  reason="the shared records folder is absent")

#: The measured shake-table tests of two granite rocks (GPL-3.0: read from the shared
#: folder, never copied into the repository); ``SHAKETABLE_PBR`` overrides.
SHARED_PBR = Path(os.environ.get("SHAKETABLE_PBR") or SHARED / "data" / "pbr")

#: Skip a test cleanly where the measured tests are absent.
needs_pbr = pytest.mark.skipif(not (SHARED_PBR / "metadata.csv").is_file(),
                               reason="the measured tests folder (shared/data/pbr) is absent")


#: Members per cell of the report tables' ensembles in tests that check that a command runs
#: and writes its report, not the ensembles' statistics (the package's default is 200).
TEST_MEMBERS = 20

#: Dots per inch of a draft figure (:func:`draft_figures`): the package writes 110.
DRAFT_DPI = 24

#: Factor on an animation's frame size and dpi in :func:`draft_animations` [-].
DRAFT_ANIMATION_SCALE = 4


@contextlib.contextmanager
def draft_figures():
    """While open, every figure the package writes through ``shaketable.plots.base.save``
    (every command's PNG figures) is a draft: built by the same code, every artist drawn
    on the same canvas into the same file, but at :data:`DRAFT_DPI` and without
    matplotlib's constrained-layout solver and tight box (about half a figure's CPU time).

    For tests that check that a command runs and writes its files, not what a figure looks
    like: an error in the package's figure code (building the axes, text, mathtext, ticks,
    colour scales, drawing) still fails them, as it would at full size. The layout the
    package gives its figures is checked by tests/plots (test_layout.py, test_save_tight.py,
    test_labels.py), at full size.
    """
    from shaketable.plots import base

    def draft(fig, target, dpi=None):
        fig.set_layout_engine("none")
        fig.savefig(target, dpi=DRAFT_DPI)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(base, "save_tight", draft)
        yield


@contextlib.contextmanager
def draft_animations():
    """While open, the frames of every animation :mod:`shaketable.plots.animation` writes
    are drafts: the same figure in inches (size and dpi both divided by
    :data:`DRAFT_ANIMATION_SCALE`, so the same layout), every frame built, drawn by blitting
    and written as asked (GIF or MP4), with a sixteenth of the pixels to draw, quantise
    and encode. The frame count, the times shown and the file written are those of the
    full-size run; what the command prints still names the size asked for.

    For tests that check that an ``animate`` line runs and writes its file, not what the
    frames look like (tests/plots/test_animation.py checks those at full size).
    """
    from shaketable.plots import animation

    class DraftStage(animation._Stage):
        def __init__(self, results, motions, times, highpass, *, size, dpi, **options):
            width, height = (value // DRAFT_ANIMATION_SCALE for value in size)
            super().__init__(results, motions, times, highpass,
                             size=(width - width % 2, height - height % 2),
                             dpi=dpi / DRAFT_ANIMATION_SCALE, **options)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(animation, "_Stage", DraftStage)
        yield


@contextlib.contextmanager
def ctrl_c_reaches_subprocesses():
    """While open, the subprocesses this process starts get SIGINT (Ctrl-C) at its default
    disposition, as a command typed in a terminal does, so that Python in them turns it into
    KeyboardInterrupt.

    For the tests that send SIGINT to a command. A test run started in the background by a
    non-interactive shell (``pytest ... &``, a script's ``nohup``) inherits SIGINT *ignored*,
    and so would every subprocess: an ignored signal stays ignored across ``exec``, and
    Python then installs no handler. The command would go on as if no Ctrl-C came (the
    compiled run for its whole minute, the sweep to its end), and the test would fail on
    what its run was started by, not on the package. Here the ignored disposition is
    replaced, for the moment of the ``Popen``, by Python's own handler, which a child does
    not inherit (it starts at the default); anything else is left as it is.
    """
    import signal
    import threading

    ignored = (threading.current_thread() is threading.main_thread()
               and signal.getsignal(signal.SIGINT) == signal.SIG_IGN)
    if ignored:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        if ignored:
            signal.signal(signal.SIGINT, signal.SIG_IGN)


#: The message of the stall :func:`stack_engine_stalling` makes the engine raise.
INJECTED_STALL = "stack model: 200 events in a row at t = 2.08799 s without progress"


def stack_engine_stalling(monkeypatch, rtol: float | None, *, above_pga: float = 0.0,
                          blocks: int | None = None) -> None:
    """Make the compiled stack engine stop with ``StackChatter`` (:data:`INJECTED_STALL`) on
    every run at ``rtol`` (None: at every tolerance, a stall no retry removes) whose motion's
    peak horizontal acceleration exceeds ``above_pga`` [m/s^2] and, with ``blocks``, whose
    stack has that many blocks; and run as usual otherwise: the retry's paths (warning,
    rows, reports) are tested on real runs without depending on which real runs stall (a
    stall is a defect the engines remove where they find one)."""
    import numpy as np

    from shaketable.models.stack import compiled
    from shaketable.models.stack.engine import StackChatter

    real = compiled.integrate

    def integrate(stack, motion, *, rtol: float, **options):
        if ((stalled is None or rtol == stalled) and (blocks is None or stack.n == blocks)
                and np.abs(motion.horizontal).max() > above_pga):
            raise StackChatter(INJECTED_STALL)
        return real(stack, motion, rtol=rtol, **options)

    stalled = rtol
    monkeypatch.setattr(compiled, "integrate", integrate)
