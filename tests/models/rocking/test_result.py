"""The rocking result's events frame against the free-rocking closed forms.

A block released from rest at theta0 > 0 on a table at rest first strikes after a quarter
of the exact period of Eq. (2-3) at that amplitude, with the impact velocity of Eq. (2-3)'s
energy integral; the impact keeps cor^2 of the energy (Eq. 2-6), which gives the next
amplitude and the next half period (``core.theory``).
"""

from __future__ import annotations

import numpy as np
import pytest

import shaketable as st
from shaketable.core import theory


def test_the_events_frame_holds_the_free_rocking_impacts_of_the_closed_forms():
    block = st.Block(1.0, 0.3)
    amplitude, cor = 0.5 * block.alpha, 0.9
    first = theory.exact_period(block, amplitude) / 4.0
    after = theory.amplitude_after_impact(block, amplitude, cor)
    second = first + theory.exact_period(block, after) / 2.0
    result = st.simulate(block, cor=cor, theta0=amplitude, duration=second + 0.05)
    events = result.events_frame()
    assert list(events.columns) == ["time [s]", "event", "theta_dot before [rad/s]"]
    impacts = events[events["event"] == "impact"]
    assert impacts["time [s]"].to_numpy()[:2] == pytest.approx([first, second], rel=1e-7)
    assert impacts["theta_dot before [rad/s]"].iloc[0] == pytest.approx(
        -theory.impact_velocity(block, amplitude), rel=1e-7)
    assert np.all(np.diff(events["time [s]"].to_numpy()) >= 0.0)
    assert "overturn" not in set(events["event"])


def test_an_overturn_is_the_last_event():
    block = st.Block(1.0, 0.3)
    result = st.simulate(block, cor=0.9, theta0=1.05 * block.alpha, duration=3.0)
    events = result.events_frame()
    assert events["event"].iloc[-1] == "overturn"
    assert events["time [s]"].iloc[-1] == result.t_overturn


def test_the_asymmetric_events_frame_of_a_symmetric_shape_has_the_same_impacts():
    """An AsymmetricBlock with b_plus = b_minus = B/2 and the rectangle's gyration is the
    symmetric block (AsymmetricBlock's docstring): its free-rocking impacts are the
    closed form's too."""
    block = st.Block(1.0, 0.3)
    shape = st.AsymmetricBlock(h=0.5, b_plus=0.15, b_minus=0.15)
    amplitude = 0.5 * block.alpha
    first = theory.exact_period(block, amplitude) / 4.0
    result = st.simulate(shape, cor=0.9, theta0=amplitude, duration=first + 0.05)
    events = result.events_frame()
    assert list(events.columns) == ["time [s]", "event"]
    impacts = events[events["event"] == "impact"]
    assert impacts["time [s]"].iloc[0] == pytest.approx(first, rel=1e-7)
