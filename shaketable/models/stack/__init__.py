"""A planar column of rigid rectangular blocks rocking on the table and on each other.

``Stack`` (the input), ``simulate_stack`` (one run; ``shaketable.simulate`` routes a Stack
here) and ``StackResult``. The equations, the contact patterns, the impact law and the
model's assumptions are in ``docs/stack.md``.
"""

from shaketable.models.stack.geometry import Stack
from shaketable.models.stack.model import (
    IMPACT_LAWS,
    StackFrictionWarning,
    StackRetryWarning,
    StackStalledWarning,
    StackTensionWarning,
    simulate_stack,
)
from shaketable.models.stack.result import PLAUSIBLE_FRICTION, StackResult, pattern_name

__all__ = ["Stack", "StackResult", "simulate_stack", "pattern_name", "IMPACT_LAWS",
           "StackTensionWarning", "StackFrictionWarning", "StackRetryWarning",
           "StackStalledWarning",            "PLAUSIBLE_FRICTION"]
