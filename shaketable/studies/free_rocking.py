"""What a free-rocking run (a released block, no table motion) answers, in words.

A block released from a tilt on a still table answers when it came to rest and after
how many impacts; its max θ/α is the release angle (Section 3.2's free-rocking tests,
Fig. 3.4), so it comes last, said as the release.
"""

from __future__ import annotations

import math

import numpy as np


def is_free(result) -> bool:
    """True when the table did not move in ``result`` (a rocking run): free rocking."""
    motion = result.motion
    vertical = motion.vertical if motion.vertical is not None else np.zeros(1)
    return not (np.any(np.asarray(motion.horizontal) != 0.0)
                or np.any(np.asarray(vertical) != 0.0))


def rocking_rest_time(result) -> float:
    """When a rocking block (:class:`~shaketable.models.rocking.result.RockingResult`) came to rest
    for good [s]: NaN when it overturned, left the ground or still rocks at the end, 0
    when it never rocked."""
    if result.status != "completed":
        return math.nan
    if not math.isfinite(result.t_start):
        return 0.0
    moving = np.flatnonzero((result.theta != 0.0) | (result.theta_dot != 0.0))
    if not moving.size:
        return 0.0
    if moving[-1] == result.t.size - 1:
        return math.nan
    settled = float(result.t[moving[-1] + 1])
    # the summed cascade's end lies between the last moving sample and the next
    if math.isfinite(result.t_rest) and result.t[moving[-1]] <= result.t_rest <= settled:
        return float(result.t_rest)
    return settled


def last_swing_ratio(result) -> float:
    """The largest |θ|/α [-] since the last impact (the whole run without one): the
    amplitude a block still rocking at the end has left."""
    after = result.t >= result.impact_times[-1] if result.impact_times.size else slice(None)
    return float(np.max(np.abs(result.theta[after])) / result.block.alpha)


def impacts_words(result) -> str:
    """``"27 impacts"`` (``"1 impact"``), with the summed endless cascades if any."""
    count = int(result.n_impacts)
    words = f"{count} impact{'' if count == 1 else 's'}"
    if result.cascades:
        words += f" and {result.cascades} summed cascade{'' if result.cascades == 1 else 's'}"
    return words


def free_rocking_verdict(result) -> str:
    """A free-rocking run in words, the answer first: ``"came to rest at t = 5.76 s
    after 27 impacts (released at θ/α = 0.50)"``, or ``"still rocking at the end
    (t = 8.00 s), last swing θ/α = 0.03, after 40 impacts (released at θ/α = 0.50)"``;
    an overturned or airborne run, or one that never rocked, as
    :meth:`~shaketable.models.rocking.result.RockingResult.verdict` says it."""
    if result.status != "completed" or not math.isfinite(result.t_start):
        return result.verdict()
    release = f"released at θ/α = {abs(result.theta[0]) / result.block.alpha:.2f}"
    rest = rocking_rest_time(result)
    if math.isnan(rest):
        return (f"still rocking at the end (t = {result.t[-1]:.2f} s), last swing "
                f"θ/α = {last_swing_ratio(result):.2g}, after {impacts_words(result)} "
                f"({release})")
    return f"came to rest at t = {rest:.2f} s after {impacts_words(result)} ({release})"
