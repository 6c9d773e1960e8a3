"""What ``simulate --history`` writes of a run, and the figure of a very long run.

A run of 10 million samples has a history CSV of about 350 MB and a figure whose
lines hold 10 million points each (tens of seconds to draw, and no more visible
than a few thousand). ``--history``:

* ``full``: every output sample (``history.csv``, as before);
* ``peaks``: the first and last samples, every impact (theta changes sign) and
  every turning point (theta' changes sign): the extremes of the rocking, a few
  rows per cycle; a block at rest writes two rows (a stack: :func:`stack_peak_rows`,
  every change of contact pattern, crossing of an interface and turning point of a
  block);
* ``none``: no history file (``summary.json`` and the figure only);
* ``auto`` (default): ``full`` up to :data:`FULL_HISTORY_ROWS` samples, ``peaks``
  beyond.

A run longer than :data:`FULL_HISTORY_ROWS` samples is drawn from a min/max
envelope (per bin of its time axis, the samples where each drawn curve is
lowest and highest, plus every impact and turning point), which looks the same
at the figure's resolution; shorter runs are drawn from every sample.
"""

from __future__ import annotations

import dataclasses

import numpy as np

#: Largest run written in full and drawn from every sample by default.
FULL_HISTORY_ROWS = 1_000_000

#: Bins of the envelope a long run is drawn from (a few per pixel of the figure).
ENVELOPE_BINS = 4000

HISTORY_CHOICES = ("auto", "full", "peaks", "none")


def history_mode(choice: str, samples: int) -> str:
    """``full``, ``peaks`` or ``none``: ``auto`` resolved for a run of ``samples`` rows."""
    if choice == "auto":
        return "full" if samples <= FULL_HISTORY_ROWS else "peaks"
    return choice


def _sign_changes(values: np.ndarray) -> np.ndarray:
    """Indices ``i`` where ``values[i]`` has another sign than ``values[i - 1]`` (0 as +)."""
    negative = np.signbit(values)
    return np.flatnonzero(negative[1:] != negative[:-1]) + 1


def peak_rows(result) -> np.ndarray:
    """Rows of the first and last samples, the impacts and the turning points, in order."""
    last = result.t.size - 1
    impacts, turns = _sign_changes(result.theta), _sign_changes(result.theta_dot)
    rows = np.concatenate([[0, last], impacts - 1, impacts, turns - 1, turns])
    return np.unique(np.clip(rows, 0, last))


def stack_peak_rows(result) -> np.ndarray:
    """The ``peaks`` rows of a stack run, in order: the first and last samples, every change
    of the contact pattern (an uplift, an impact, a rest) and the samples either side of
    it, every crossing of an interface (its relative rotation changes sign) and every
    turning point of a block (its theta' changes sign)."""
    last = result.t.size - 1
    relative = np.diff(result.theta, axis=1, prepend=0.0)   # phi_j = theta_j - theta_(j-1)
    rows = [np.array([0, last])]
    for values in (*relative.T, *result.theta_dot.T):
        changes = _sign_changes(values)
        rows += [changes - 1, changes]
    patterns = np.asarray(result.patterns)
    changed = np.flatnonzero(np.any(patterns[1:] != patterns[:-1], axis=1)) + 1
    rows += [changed - 1, changed]
    return np.unique(np.clip(np.concatenate(rows), 0, last))


def _envelope(curves, size: int, bins: int = ENVELOPE_BINS) -> np.ndarray:
    """Rows where each curve is lowest and highest in each of ``bins`` bins, first, last."""
    width = max(size // bins, 1)
    full = (size // width) * width
    rows = [np.array([0, size - 1])]
    for values in curves:
        blocks = np.asarray(values)[:full].reshape(-1, width)
        offsets = np.arange(blocks.shape[0]) * width
        rows += [offsets + blocks.argmin(axis=1), offsets + blocks.argmax(axis=1),
                 full + np.arange(size - full)]
    return np.unique(np.concatenate(rows))


def history_frame(result, mode: str):
    """The history table ``simulate`` writes for ``mode`` (``full`` or ``peaks``)."""
    if mode == "full":
        return result.to_frame()
    return drawn_from(result, peak_rows(result), motion_rows=None).to_frame()


def drawn_from(result, rows: np.ndarray, motion_rows: np.ndarray | None):
    """A copy of ``result`` (its scalars untouched) at the output ``rows`` only, its
    motion at ``motion_rows`` only (None keeps the whole motion)."""
    from shaketable.core.motion import Motion

    motion = result.motion
    if motion_rows is not None:
        def pick(values):
            return None if values is None else values[motion_rows]

        motion = Motion(motion.t[motion_rows], motion.horizontal[motion_rows],
                        pick(motion.vertical), name=motion.name,
                        rotation=pick(motion.rotation), metadata=motion.metadata)
    return dataclasses.replace(result, motion=motion, t=result.t[rows],
                               theta=result.theta[rows], theta_dot=result.theta_dot[rows],
                               theta_ddot=result.theta_ddot[rows])


def for_figure(result):
    """``result`` itself, or for a run longer than :data:`FULL_HISTORY_ROWS` its envelope."""
    if result.t.size <= FULL_HISTORY_ROWS and result.motion.t.size <= FULL_HISTORY_ROWS:
        return result
    rows = np.union1d(_envelope((result.theta, result.theta_dot, result.theta_ddot),
                                result.t.size), peak_rows(result))
    motion = result.motion
    channels = [motion.horizontal] + [values for values in (motion.vertical, motion.rotation)
                                      if values is not None]
    return drawn_from(result, rows, motion_rows=_envelope(channels, motion.t.size))
