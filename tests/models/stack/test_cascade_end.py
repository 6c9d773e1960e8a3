"""The end of a free-rocking stack's endless cascade against the sum of its flights."""

import math

from scipy.integrate import quad

import shaketable as st
from shaketable.core.constants import G
from shaketable.models.stack import Stack, simulate_stack
from tests.models.stack.one_body import first_base_impact, rigid_pair


def test_a_decaying_stack_rests_within_the_documented_bound_of_its_flights_sum():
    # two 30 x 6 in blocks released as one body from 0.05 rad rock as one rigid body (the
    # issue's check 2: I_O, R, alpha of the pair) and lose the ratio r = 1 - 2 M b^2 / I_O
    # at every base impact; the cascade truly ends at the accumulation point of the
    # impacts, t1 + sum of the flights T(r^i |w1|). Reference: t1 and w1 by quadrature of
    # the energy integral (one_body.first_base_impact), each flight by quadrature while the
    # rate is above 1e-3 rad/s, below it by the motion linearized about the corner
    # (theta'' = -a0 + lambda^2 theta: T = 2 atanh(lambda w / a0) / lambda, within 2.3e-10
    # of the quadrature at 1e-3 rad/s). docs/stack.md (Cascades): the engine ends a cascade
    # whose rebounds rise below rtol alpha_min at once, early by at most that series'
    # length, 2 sqrt(2 rtol alpha_min / a0) / (1 - r) (8.65e-5 s here, 376 times
    # rest_tolerance); measured 8.630e-5 s early, and never late
    block = st.Block.parse("30x6in")
    stack = Stack([block, block])
    result = simulate_stack(stack, None, theta0=[0.05, 0.05], duration=60.0, rtol=1e-12)
    assert {e["pattern_after"] for e in result.events if e["kind"] == "impact"} \
        == {(1, 0), (-1, 0)}   # one body throughout
    rest = [e["t"] for e in result.events if e["kind"] == "rest"]

    b, h = block.width / 2, block.height / 2
    mass, _, _, radius, alpha, inertia = rigid_pair(b, h, b, h, 1.0, 1.0)
    ratio = 1.0 - 2.0 * mass * b ** 2 / inertia
    t1, w1 = first_base_impact(mass, radius, alpha, inertia, 0.05)
    k = 2.0 * mass * G * radius / inertia   # theta'^2 = w^2 - k (cos(alpha - theta) - cos alpha)
    a0, lam = 0.5 * k * math.sin(alpha), math.sqrt(0.5 * k * math.cos(alpha))

    def flight(w):
        top = alpha - math.acos(math.cos(alpha) + w * w / k)   # the excursion's peak
        low = alpha - top

        def integrand(s):   # theta = top - s^2; cos A - cos(A + x) = 2 sin(A + x/2) sin(x/2)
            if s == 0.0:
                return 2.0 / math.sqrt(k * math.sin(low))
            return 2.0 * s / math.sqrt(2.0 * k * math.sin(low + s * s / 2) * math.sin(s * s / 2))

        value, _ = quad(integrand, 0.0, math.sqrt(top), epsabs=0, epsrel=1e-12, limit=200)
        return 2.0 * value

    end, w = t1, abs(w1) * ratio
    while w > 1e-3:
        end += flight(w)
        w *= ratio
    while w > 1e-300:
        end += 2.0 * math.atanh(lam * w / a0) / lam
        w *= ratio
    assert len(rest) == 1
    bound = 2.0 * math.sqrt(2.0 * 1e-12 * stack.alpha_min / a0) / (1.0 - ratio)
    assert -1e-9 <= end - rest[0] <= bound + 1e-6 / block.p   # + rest_tolerance
    assert end - rest[0] > 0.5 * bound   # the noise rule ended it (not the rest_tolerance)
