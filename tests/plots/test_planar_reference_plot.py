"""The SciPy planar reference's result has the figure, frame and summary of the compiled
planar result (``to_frame()``, ``summary()``, ``plot()`` as for the other results).

Same run through both models (the 30 x 6 in block, mu_s 0.25, mu_d 0.22, COR 0.9, 3 Hz
0.6 g ramped, 3 s: rock, slide-rock and impacts): the two figures must have the same
panels, and each figure's traces must be its own result's columns. The mode bands are
compared between the two independent implementations (they agree to 1e-8 in event times,
tests/models/planar/test_planar_agreement.py).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from shaketable.core.constants import INCH, G
from shaketable.core.geometry import Block
from shaketable.ground.generators import harmonic
from shaketable.models.planar.reference import simulate_reference
from shaketable.models.planar.run import simulate_planar
from shaketable.models.sliding.result import Friction
from shaketable.plots.base import pyplot
from shaketable.plots.planar import mode_spans


@pytest.fixture(scope="module")
def runs():
    block = Block.from_inches(30, 6)
    motion = harmonic(3.0, horizontal=0.6 * G, duration=3.0, dt=0.005, ramp=0.25)
    options = dict(cor=0.9, friction=Friction(0.25, 0.22))
    return simulate_reference(block, motion, **options), simulate_planar(block, motion, **options)


def test_both_results_have_the_same_frame_columns(runs):
    reference, planar = runs
    frame, planar_frame = reference.to_frame(), planar.to_frame()
    assert list(frame.columns) == list(planar_frame.columns)
    assert len(frame) == reference.t.size
    np.testing.assert_array_equal(frame["theta [rad]"], reference.theta)
    np.testing.assert_array_equal(frame["slip [m]"], reference.slip)
    np.testing.assert_array_equal(frame["theta/alpha [-]"], reference.theta / reference.block.alpha)
    # the ground columns are the motion's samples in g (the two runs share the motion)
    np.testing.assert_array_equal(frame["ground horizontal [g]"],
                                  planar_frame["ground horizontal [g]"][:len(frame)])
    assert set(frame["mode"]) == {"rest", "rock", "slide-rock"}


def test_summary_is_json_ready_with_the_verdict(runs):
    reference, planar = runs
    summary = json.loads(json.dumps(reference.summary()))
    assert summary["verdict"] == planar.verdict() == "slide-rocked"
    assert summary["n_impacts"] == planar.n_impacts
    assert reference.modes_visited == planar.modes_visited
    # the keys of the compiled result's summary for what both compute, and equal values
    # there (independent implementations at rtol 1e-12: to 1e-6 relative)
    compiled = json.loads(json.dumps(planar.summary()))
    assert set(summary) - set(compiled) == {"model"}
    for key in ("block_height [m]", "cor [-]", "static friction mu_s [-]", "motion",
                "status", "verdict", "overturned", "modes visited", "n_impacts"):
        assert summary[key] == compiled[key], key
    for key in ("max_theta_ratio [-]", "max_abs_theta [rad]", "peak slip [m]",
                "residual slip [m]", "work of the table [J/kg]", "work of friction [J/kg]",
                "impact losses [J/kg]", "time slide-rock [s]"):
        assert summary[key] == pytest.approx(compiled[key], rel=1e-6, abs=1e-9), key


def test_the_figure_has_the_panels_of_the_compiled_result(runs):
    reference, planar = runs
    fig, planar_fig = reference.plot(title="reference"), planar.plot(title="reference")
    try:
        axes, planar_axes = fig.axes, planar_fig.axes
        # ground (horizontal only), theta', theta, slip, mode band
        assert len(axes) == len(planar_axes) == 5
        assert [a.get_ylabel() for a in axes] == [a.get_ylabel() for a in planar_axes]
        assert axes[-1].get_xlabel() == planar_axes[-1].get_xlabel() == "time [s]"
        # each trace is its own result's column
        rates, rotation, slip, band = axes[-4:]
        np.testing.assert_array_equal(rates.get_lines()[0].get_xdata(), reference.t)
        np.testing.assert_array_equal(rates.get_lines()[0].get_ydata(), reference.theta_dot)
        np.testing.assert_array_equal(rotation.get_lines()[0].get_ydata(), reference.theta)
        # the base's slip: the corner it stands or turns on (docs/planar.md)
        block = reference.block
        corner = reference.x + block.h * np.sin(reference.theta) \
            + np.sign(reference.theta) * block.b * (1.0 - np.cos(reference.theta))
        np.testing.assert_allclose(slip.get_lines()[0].get_ydata(), corner / INCH, rtol=0,
                                   atol=1e-12)
        # the peak-slip marker at the reference's own peak of the base's slip
        marker = slip.get_lines()[-1]
        assert abs(marker.get_ydata()[0]) == pytest.approx(reference.peak_base_slip / INCH)
        # the mode band: the same coloured stretches in both figures, from each result's
        # own located events (independent implementations: equal to 1e-8 s)
        shaded = [patch for patch in band.patches]
        planar_shaded = [patch for patch in planar_axes[-1].patches]
        assert len(shaded) == len(planar_shaded) > 0
        for mine, theirs in zip(shaded, planar_shaded):
            np.testing.assert_allclose(mine.get_x(), theirs.get_x(), atol=1e-8)
            np.testing.assert_allclose(mine.get_width(), theirs.get_width(), atol=1e-8)
            assert mine.get_facecolor() == theirs.get_facecolor()
        # every mode the run visited is in the band's legend, rest excepted (left blank)
        for axis in (band, planar_axes[-1]):
            labels = {text.get_text() for text in axis.get_legend().get_texts()}
            assert labels == set(planar.modes_visited) - {"rest"}
            assert "rock" in labels and "slide-rock" in labels
        # the caption: the same verdict line up to the corner excursion (the reference
        # computes none) and the model named
        caption = fig._suptitle.get_text()
        assert "independent SciPy reference" in caption and "slide-rocked" in caption
        assert "corner excursion" not in caption
        assert "corner excursion" in planar_fig._suptitle.get_text()
    finally:
        pyplot().close(fig)
        pyplot().close(planar_fig)


def test_mode_spans_of_both_results_agree(runs):
    reference, planar = runs
    spans, planar_spans = mode_spans(reference), mode_spans(planar)
    assert [code for *_, code in spans] == [code for *_, code in planar_spans]
    np.testing.assert_allclose([s[:2] for s in spans], [s[:2] for s in planar_spans],
                               atol=1e-8)
    # the spans cover the run and their slide-rock time is the reference's own count
    assert spans[0][0] == reference.t[0] and spans[-1][1] == reference.t[-1]
    assert sum(b - a for a, b, code in spans if code == 3) == pytest.approx(
        reference.time_in_mode["slide-rock"], abs=1e-9)


def test_an_overturned_reference_run_is_drawn_with_its_verdict():
    block = Block.parse("16x4ft")
    from shaketable.ground import records

    motion = records.load("pacoima-dam-s16e")
    result = simulate_reference(block, motion, cor=0.95, friction=Friction(0.3), rtol=1e-8)
    assert result.overturned and np.isnan(result.max_theta_ratio)
    # the side it falls to: the compiled engine's, located exactly
    assert result.overturn_direction == simulate_planar(
        block, motion, cor=0.95, friction=Friction(0.3)).overturn_direction != 0
    assert result.verdict() == "overturned"
    fig = result.plot()
    try:
        assert "overturned (" in fig._suptitle.get_text()
    finally:
        pyplot().close(fig)
