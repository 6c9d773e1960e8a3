"""Figure defects found by the classroom trial: each checked on the drawn figure."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

import shaketable as st
from shaketable.plots.base import pyplot


def test_a_spectrum_of_few_omega_p_values_is_drawn_at_those_values_only():
    # three computed omega/p were drawn as strips filling the plane, like a continuous scan:
    # now each band is a narrow bar at its computed omega/p, with a point at each band edge
    from shaketable.studies.overturning_spectrum import overturning_spectrum

    block = st.Block.from_slenderness(3 * st.G / (4 * 2.0 ** 2), 0.25)   # p = 2 rad/s
    # a scan ten times coarser than the default 0.005 finds the same 12 bands (safe and
    # overturning, after and without impact, at each ratio): this test checks how they are
    # drawn (tests/studies/test_overturning_spectrum.py checks their edges)
    spectrum = overturning_spectrum(block, pulses=["one-sine"], ratios=[2, 3, 4],
                                    cor="housner", tolerance=1e-4, scan_step=0.05)
    assert len(spectrum.bands) == 12
    ax = spectrum.plot()
    try:
        bars = [collection.get_paths()[0].vertices for collection in ax.collections
                if len(collection.get_paths())]
        assert bars
        for vertices in bars:
            low, high = vertices[:, 0].min(), vertices[:, 0].max()
            centre = 0.5 * (low + high)
            # centred on a computed value, much narrower than the spacing of 1
            assert min(abs(centre - ratio) for ratio in (2, 3, 4)) < 1e-9
            assert high - low < 0.2
        points = [line for line in ax.lines if line.get_marker() == "o"]
        overturns = spectrum.bands[spectrum.bands["verdict"] == "overturns"]
        assert len(points) == len(overturns)   # one pair of edge points per overturn band
        assert list(ax.get_xticks()) == [2, 3, 4]
        assert "computed at ω/p = 2, 3, 4 only" in ax.get_title()
    finally:
        pyplot().close("all")


def test_the_ensemble_figure_says_how_many_members_it_draws():
    # a 200-member ensemble said "5 runs": it draws the nominal run and the horizon's pairs
    from shaketable.plots.predictability import plot_bundle

    block = st.Block.parse("30x6in")
    runs = [st.simulate(block, cor=0.9, theta0=ratio * block.alpha, duration=1.0)
            for ratio in (0.5, 0.51, 0.52)]
    try:
        title = plot_bundle(runs, members=200).get_title()
        assert "3 of the 200 members drawn" in title and "3 runs" not in title
        assert "3 runs" in plot_bundle(runs).get_title()
    finally:
        pyplot().close("all")


def test_the_pitch_phase_figure_has_a_legend():
    # Section 3.7 (2) figure of the pitch sweep: its dots, crosses and dotted line explained
    from shaketable.plots.sweeps import pitch_phase_spread

    rows = pd.DataFrame([{"record": "r", "seed": math.nan, "cor [-]": 0.9, "block": "1x0.25m",
                          "pga [g]": pga, "pitch_phase [rad]": phase,
                          "max_theta_ratio [-]": math.nan if pga > 0.5 else 0.2 + pga,
                          "overturned": bool(pga > 0.5)}
                         for pga in (0.3, 0.6) for phase in np.linspace(0, 6, 4)])
    try:
        legend = pitch_phase_spread(rows).get_legend()
        assert legend is not None
        texts = [text.get_text() for text in legend.get_texts()]
        assert any("standing" in text for text in texts)
        assert any("overturned" in text for text in texts) and "|θ| = α" in texts
    finally:
        pyplot().close("all")


@pytest.mark.parametrize("text, unit", [("6x2ft", "ft"), ("30x6in", "in"), ("1x0.2m", "m")])
def test_animation_labels_use_the_blocks_unit(text, unit, tmp_path):
    # the animation mixed cm (table), m (axes) and in (caption): now one unit
    from shaketable.plots.animation import snapshot

    block = st.Block.parse(text)
    run = st.simulate(block, cor=0.9, theta0=0.5 * block.alpha, duration=0.5)
    from matplotlib.figure import Figure

    saved = {}
    original = Figure.savefig

    def spy(self, *args, **kwargs):
        saved["texts"] = [t.get_text() for t in self.findobj(lambda a: hasattr(a, "get_text"))]
        saved["labels"] = [ax.get_xlabel() for ax in self.axes]
        return original(self, *args, **kwargs)

    Figure.savefig = spy
    try:
        snapshot(run, 0.25, out=tmp_path / "frame.png", size=(640, 360), dpi=60)
    finally:
        Figure.savefig = original
    assert f"x [{unit}]" in saved["labels"]
    clock = [t for t in saved["texts"] if t.startswith("t = ")]
    assert clock and clock[0].endswith(f" {unit}")


def test_risk_figure_merges_stripes_a_few_ulps_apart():
    # Motions scaled to one target PGV reach it only to a few ulps (0.3969999..., 0.397,
    # 0.3970000...1): one level of the analysis, drawn as one marker with the fraction of
    # all its runs (here 1 of 12 overturned, not three markers at 0, 1 and 0).
    from shaketable.plots.sweeps import _merged_stripes

    target = 0.397
    below, above = np.nextafter(target, 0.0), np.nextafter(np.nextafter(target, 1.0), 1.0)
    stripes = ((0.5, above, target, below), (12.0, 1.0, 10.0, 1.0), (6.0, 1.0, 0.0, 0.0))
    levels, runs, failures = _merged_stripes(stripes)
    np.testing.assert_allclose(levels, [target, 0.5], rtol=1e-15)
    np.testing.assert_array_equal(runs, [12.0, 12.0])
    np.testing.assert_array_equal(failures, [1.0, 6.0])
