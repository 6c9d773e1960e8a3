"""Angles at the edges: a bare zero needs no unit; other bare numbers are refused with
every way an angle may be written."""

import pytest


def test_a_bare_zero_angle_needs_no_unit_and_the_hint_names_alpha():
    # zero is zero in rad, deg and multiples of alpha: refusing "0" helps nobody; any other
    # bare number is refused, and the message lists every way an angle may be written
    from shaketable.core.units import parse_angle_or_ratio

    for zero in ("0", "0.0", 0, 0.0):
        assert parse_angle_or_ratio(zero, 0.2, where="theta0") == 0.0
    with pytest.raises(ValueError, match=r"theta0: '3' has no unit.*0\.5 alpha"):
        parse_angle_or_ratio("3", 0.2, where="theta0")
    with pytest.raises(ValueError):
        parse_angle_or_ratio(True, 0.2, where="theta0")
    assert parse_angle_or_ratio("0.5 alpha", 0.2) == pytest.approx(0.1, rel=1e-15)
