"""Whether a run ended before its motion did, said in words and as summary keys.

A run ends normally when it reaches the end of its motion (status ``completed``) or
when the block overturns (``overturned``). Any other status is an early stop: the
rocking model stops where the block leaves the ground (``airborne``), the planar
model where no rigid-body answer exists or the contact sequence cannot be followed
(``painleve``, ``inconsistent``, ``chatter``, ``stalled``: see
:data:`shaketable.models.planar.result.STATUS_MESSAGES`). Its results cover the run up
to the stop only, so every command says so on the console, in ``summary.json``
(:func:`stop_summary`) and by its exit status (1). The sliding block
(:class:`~shaketable.models.sliding.result.SlidingResult`) always runs to the end (a
block without normal force is carried on without friction).
"""

from __future__ import annotations

import math

#: Statuses of a run that reached its end (or the overturn that ends it).
FINISHED_STATUSES = ("completed", "overturned")

#: What the rocking model's own early stop means.
_ROCKING_MESSAGES = {
    "airborne": "the block left the ground (vertical acceleration at or below -g); the "
                "rocking model stops there"}


def early_stop(result) -> str | None:
    """Why and when ``result`` stopped before its motion ended, in words; None if it did not.

    Parameters
    ----------
    result : RockingResult, PlanarResult, PlanarReferenceResult or SlidingResult

    Returns
    -------
    str or None
        E.g. ``"stopped at 2.856 s of 41.72 s of motion (status chatter: ...)"``.
    """
    from shaketable.models.sliding.result import SlidingResult

    status = getattr(result, "status", "completed")
    if isinstance(result, SlidingResult) or status in FINISHED_STATUSES:
        return None
    end = stopped_at(result)
    motion = getattr(result, "motion", None)
    span = "" if motion is None else f" of {float(motion.t[-1]):.4g} s of motion"
    try:
        meaning = result.message
    except (AttributeError, KeyError):
        meaning = _ROCKING_MESSAGES.get(status, "the solver stopped")
    return (f"stopped at {end:.4g} s{span} (status {status}: {meaning}); the results cover "
            "the run up to the stop only")


def stopped_at(result) -> float:
    """The time of the last state of ``result`` [s] (NaN without a time history)."""
    t = getattr(result, "t", None)
    return float(t[-1]) if t is not None and len(t) else math.nan


def stop_summary(result) -> dict:
    """``result.summary()`` with the early-stop keys: ``stopped early`` (bool), and for
    an early stop ``stopped at [s]`` and ``stop reason`` (None otherwise)."""
    summary = dict(result.summary())
    reason = early_stop(result)
    summary["stopped early"] = reason is not None
    summary["stopped at [s]"] = stopped_at(result) if reason is not None else None
    summary["stop reason"] = reason
    return summary
