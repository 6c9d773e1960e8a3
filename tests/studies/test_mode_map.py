"""The mode map of the planar block against Section 2.1's rule.

References used here:
* Section 2.1 of the report, Eqs. (2-1) and (2-2): from rest, slip needs |ug| > mu_s (g + vg),
  tipping |ug| > (B/H)(g + vg); both scale with g + vg, so with mu_s < B/H slip comes first
  whatever the record, and a flat block sliding with mu_d <= B/H keeps its centre of pressure
  at mu_d h < b inside its base (moment balance about the centre): it never tips. So the
  largest mu (mu_s = mu_d) at which a block only slides is B/H exactly, for any record
  that reaches the tipping threshold.
* Table 4.4's model, :func:`shaketable.models.sliding.engine.slide` (exact piecewise
  integration): a planar block that only slides must give its peak slip.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaketable.core.constants import FOOT, G
from shaketable.core.geometry import Block
from shaketable.ground import records
from shaketable.scenes.parse import SceneError, load_scene
from shaketable.studies.mode_map import (
    VERDICT_ORDER,
    mode_map,
    sliding_limit,
    table_4_4_coupled,
)


@pytest.fixture(scope="module")
def pacoima():
    return records.load("pacoima-dam-s16e")


@pytest.mark.parametrize("size", ["16x4ft", "15x5ft"])
def test_sliding_limit_is_b_over_h(size, pacoima):
    """Section 2.1 (Eqs. 2-1, 2-2): the block only slides exactly while mu < B/H."""
    block = Block.parse(size)
    limit = sliding_limit(block, pacoima, tolerance=1e-5)
    assert abs(limit - block.width / block.height) <= 2e-5


def test_sliding_limit_refuses_a_bracket_that_does_not_slide(pacoima):
    with pytest.raises(ValueError, match="does more than slide"):
        sliding_limit(Block.parse("16x4ft"), pacoima, low=0.5)


def test_sliding_limit_is_nan_when_the_record_never_tips_the_block(pacoima):
    """At 0.1 g the 8 x 8 ft block (B/H = 1) cannot reach Eq. (2-1): no limit."""
    from shaketable.ground.signals import scale_to_pga

    weak = scale_to_pga(pacoima, pga=0.1 * G)
    assert math.isnan(sliding_limit(Block.parse("8x8ft"), weak, high=1.2))


def test_mode_map_below_the_rule_only_slides_and_above_it_lifts(pacoima):
    """Below mu = B/H every block only slides (Section 2.1, exact here); above it, under the
    full record (PGA 1.2 g, far above tan(alpha) g) every block lifts a corner."""
    result = mode_map(pacoima, aspect_ratios=(0.2, 0.3), frictions=(0.1, 0.25, 0.45),
                      height=12 * FOOT)
    frame = result.to_frame()
    assert len(frame) == 6 and set(frame["verdict"]) <= set(VERDICT_ORDER)
    below = frame[frame["rule"] == "slide"]
    above = frame[frame["rule"] == "rock"]
    assert below["verdict"].isin(["stayed", "slid"]).all()
    assert (~above["verdict"].isin(["stayed", "slid"])).all()
    counts = result.counts()
    assert int(counts["rule slides"].iloc[0]) == len(below) == 3


def test_table_4_4_coupled_equals_the_sliding_model_where_the_block_only_slides():
    """Where mu < B/H the planar block is Table 4.4's sliding block: same peak slip."""
    frame = table_4_4_coupled(blocks_ft=((15.0, 5.0), (16.0, 4.0)),
                              columns=("pacoima-dam-s16e",), frictions=(0.2, 0.3))
    slid = frame[frame["planar verdict"] == "slid"]
    assert len(slid) == 3   # 15 x 5 at 0.2 and 0.3, 16 x 4 at 0.2 (B/H = 0.25)
    np.testing.assert_allclose(slid["planar peak slip [in]"],
                               slid["sliding model peak slip [in]"], rtol=1e-9)
    rocks = frame[(frame["block [ft]"] == "16 x 4") & (frame["mu [-]"] == 0.3)]
    assert rocks["planar verdict"].iloc[0] not in ("stayed", "slid")


def test_mode_map_scene_parses_and_refuses_bad_keys(tmp_path):
    good = tmp_path / "map.toml"
    good.write_text('name = "m"\n[study]\nkind = "mode-map"\npga = ["0.5 g", "record"]\n'
                    'aspect_ratios = [0.2]\nfrictions = "0.1:0.3:0.1"\nheight = "12 ft"\n')
    study = load_scene(good)
    settings = study.mode_map
    assert settings.pga_levels == (0.5 * G, None)
    assert settings.frictions == (0.1, 0.2, 0.3)
    assert settings.height == pytest.approx(12 * FOOT)
    for text, message in [('pga = [0.5]', "study.pga"),
                          ('frictions = "0.3:0.1:0.1"', "study.frictions"),
                          ('record = "nowhere"', "study.record"),
                          ('height = 4', "study.height"),
                          ('cor = 1.5', "study.cor"),
                          ('colour = "red"', "colour")]:
        bad = tmp_path / "bad.toml"
        bad.write_text(f'name = "m"\n[study]\nkind = "mode-map"\n{text}\n')
        with pytest.raises(SceneError, match=message):
            load_scene(bad)


def test_the_rule_is_a_knife_edge(pacoima):
    """Section 2.1's line mu = B/H: the 16 x 4 ft block at COR 1 only slides a relative 1e-6
    below it (a flat block with mu_s < B/H slips before Eq. (2-1) and, with mu_d < B/H,
    never tips) and overturns 1e-6 above it: the verdict jumps across the line."""
    from shaketable.studies.mode_map import knife_edge

    frame = knife_edge(Block.parse("16x4ft"), records.load("pacoima-dam-s16e", vertical=True),
                       cor=1.0, offsets=(1e-6, 5e-2, -1e-6))
    assert list(frame["verdict"]) == ["slid", "slid", "overturned"]
    assert (frame["peak base slip [m]"] > 0).all()
