"""Brent's method and the cascade sum of shaketable.numerics on known roots and series
(plain Python: ``py_func``, the source numba compiles into the engines)."""

import math

import pytest

from shaketable.numerics.cascade import cascade_rest_time
from shaketable.numerics.roots import brent

BRENT = brent.py_func


@pytest.mark.parametrize("f, args, a, b, root", [
    (lambda x, args: math.cos(x), (), 1.0, 2.0, 0.5 * math.pi),
    (lambda x, args: x ** 3 - args[0], (2.0,), 0.0, 2.0, 2.0 ** (1.0 / 3.0)),
    (lambda x, args: math.exp(x) - args[0], (10.0,), 3.0, 0.0, math.log(10.0)),
])
def test_brent_finds_known_roots_to_the_tolerance(f, args, a, b, root):
    assert BRENT(f, args, a, b, 1e-300, 4.0 * 2.2e-16) == pytest.approx(root, rel=1e-15)


def test_brent_returns_a_zero_end_and_the_right_end_without_a_sign_change():
    assert BRENT(lambda x, args: x - 1.0, (), 1.0, 3.0, 1e-12, 1e-12) == 1.0
    assert BRENT(lambda x, args: x - 3.0, (), 1.0, 3.0, 1e-12, 1e-12) == 3.0
    assert BRENT(lambda x, args: x * x + 1.0, (), -1.0, 2.0, 1e-12, 1e-12) == 2.0


def test_brent_stops_at_its_tolerance():
    found = BRENT(lambda x, args: x - 0.3, (), 0.0, 1.0, 1e-3, 0.0)
    assert abs(found - 0.3) < 1e-3


def test_the_cascade_time_is_the_sum_of_its_flights():
    # flights 2|w| r^k / a0 (k = 0, 1, ...), summed directly
    w, a0, r = -0.7, 3.0, 0.6
    flights = sum(2.0 * abs(w) * r ** k / a0 for k in range(200))
    assert cascade_rest_time(w, a0, r) == pytest.approx(flights, rel=1e-14)
    assert cascade_rest_time(w, a0, 1.0) == math.inf
    assert cascade_rest_time(w, 0.0, 0.5) == math.inf
