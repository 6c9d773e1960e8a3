"""What a free-rocking run answers, in words: :mod:`shaketable.models.rocking.free_rocking`
(the result's own verdict uses it), under the name the studies and commands import."""

from __future__ import annotations

from shaketable.models.rocking.free_rocking import (
    VISIBLE_FRACTION,
    free_rocking_verdict,
    impacts_words,
    is_free,
    last_swing_ratio,
    rocking_rest_time,
    visible_impacts,
)

__all__ = ["VISIBLE_FRACTION", "free_rocking_verdict", "impacts_words", "is_free",
           "last_swing_ratio", "rocking_rest_time", "visible_impacts"]
