"""The stacks study (reproduce's stacks section): its closed forms and its uplift points.

References: the rigid stack's moment of inertia about a base corner, written out for two
blocks in the stack issue's check 2, I_O = (4/3) m1 (b1^2 + h1^2)
+ m2 [(b2^2 + h2^2)/3 + b1^2 + (2 h1 + h2)^2], and the uplift threshold of check 3,
(g + v'') min(A1, A2) with A1 = b1 (m1 + m2) / (m1 h1 + m2 (2 h1 + h2)), A2 = b2 / h2.
"""

from __future__ import annotations

import math

import pytest

from shaketable.core.geometry import Block
from shaketable.models.stack import Stack
from shaketable.studies.stacks import rigid_stack, uplift_thresholds

BOTTOM, TOP = Block(2.4384, 0.6096), Block(1.8288, 0.3048)     # 8 x 2 ft, 6 x 1 ft


def test_the_rigid_stack_is_the_issue_s_closed_form():
    m1, m2 = 3.0, 0.7
    b1, h1, b2, h2 = BOTTOM.b, BOTTOM.h, TOP.b, TOP.h
    rigid = rigid_stack(Stack((BOTTOM, TOP), masses=(m1, m2)))
    inertia = (4 / 3) * m1 * (b1 ** 2 + h1 ** 2) + m2 * (
        (b2 ** 2 + h2 ** 2) / 3 + b1 ** 2 + (2 * h1 + h2) ** 2)
    y_c = (m1 * h1 + m2 * (2 * h1 + h2)) / (m1 + m2)
    assert rigid["I_O"] == pytest.approx(inertia, rel=1e-14)
    assert rigid["alpha_eq"] == pytest.approx(math.atan(b1 / y_c), rel=1e-14)
    assert rigid["p_eq"] == pytest.approx(
        math.sqrt((m1 + m2) * 9.80665 * math.hypot(b1, y_c) / inertia), rel=1e-14)
    one = rigid_stack(Stack((BOTTOM,)))      # one block: Eq. (2-12), I_O = (4/3) m R^2
    assert one["I_O"] == pytest.approx((4 / 3) * BOTTOM.width * BOTTOM.height * BOTTOM.R ** 2,
                                       rel=1e-14)
    assert one["p_eq"] == pytest.approx(BOTTOM.p, rel=1e-14)


def test_computed_uplift_thresholds_meet_the_closed_form_on_both_branches():
    cases = [("whole stack", Stack((BOTTOM, TOP), masses=(1.0, 1.0))),   # A1 = 0.1333 < A2
             ("top alone", Stack((BOTTOM, TOP), masses=(1.0, 0.25)))]    # A2 = 0.1667 < A1
    frame = uplift_thresholds(cases)
    for (_, stack), (_, row) in zip(cases, frame.iterrows()):
        (b1, b2), (h1, h2), (m1, m2) = stack.b, stack.h, stack.m
        a1 = b1 * (m1 + m2) / (m1 * h1 + m2 * (2 * h1 + h2))
        assert row["computed [g]"] == pytest.approx(min(a1, b2 / h2), rel=1e-9)
    assert list(frame["pattern entered"]) == ["stack as one body (+)", "top alone (+)"]
    assert (frame["computed [g]"] < frame["bottom block alone tan(alpha1) [g]"]).all()


def test_the_stacks_scene_is_a_study_of_its_own_kind():
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import Study, load_scene

    study = load_scene(resolve_scene_path("stacks"))
    assert isinstance(study, Study) and study.kind == "stacks"


def test_eq_2_8_of_one_block_is_the_report_s_and_a_stack_s_is_lower():
    from shaketable.studies.stacks import eq_2_8

    omega = 3.0 * BOTTOM.p
    assert eq_2_8(Stack((BOTTOM,)), omega) == pytest.approx(
        math.tan(BOTTOM.alpha) * math.sqrt(1.0 + 9.0), rel=1e-14)
    assert eq_2_8(Stack((BOTTOM, BOTTOM)), omega) < eq_2_8(Stack((BOTTOM,)), omega)


@pytest.mark.parametrize("argv, message", [
    (["--stack", "8x2ft,8x3ft"], "--stack: block 1 (top) (8 x 3 ft) is wider than block 0"),
    (["--stack", "8x2ft,8x2ft", "--pulse", "one-sine"], "only half-sine pulses are offered"),
    (["--stack", "8x2ft,8x2ft", "--cor", "0.9"], "--cor '0.9' cannot be used with --stack"),
    (["--stack", "8x2ft,8x2ft", "--iterations", "0"], "--iterations must be from 1 to 30"),
])
def test_spectrum_with_a_stack_refuses_bad_input(tmp_path, argv, message):
    from tests.test_bad_input import run_cli

    status, _, err = run_cli(["spectrum", *argv, "--out", tmp_path / "out"], cwd=tmp_path)
    assert status == 2 and message in err, err
    assert not (tmp_path / "out").exists()
