"""The planar reference's events frame against the free-rocking closed form."""

from __future__ import annotations

import pytest

from shaketable.core import theory
from shaketable.core.geometry import Block
from shaketable.models.planar.reference import simulate_reference
from shaketable.models.sliding.result import Friction


def test_the_reference_events_frame_holds_the_first_free_rocking_impact():
    """With friction too high to slide, a block released at theta0 rocks as the rocking
    model: its first impact comes after a quarter of the exact period of Eq. (2-3)."""
    block = Block(1.0, 0.3)
    amplitude = 0.5 * block.alpha
    quarter = theory.exact_period(block, amplitude) / 4.0
    result = simulate_reference(block, cor=0.9, friction=Friction(5.0), theta0=amplitude,
                                duration=quarter + 0.02)
    events = result.events_frame()
    assert list(events.columns) == ["time [s]", "event", "mode before", "mode after"]
    impact = events[events["event"] == "impact"].iloc[0]
    assert impact["time [s]"] == pytest.approx(quarter, rel=1e-8)
    assert impact["mode before"] == "rock"
