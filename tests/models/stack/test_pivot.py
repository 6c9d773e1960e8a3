"""The plastic law past three blocks: the complementarity pivot against the enumeration of
every active set (docs/stack.md, "Uniqueness, and the law as a complementarity problem")."""

import numpy as np
import pytest

import shaketable as st
from shaketable.ground import records
from shaketable.models.stack import Stack, impact, simulate_stack
from shaketable.models.stack.physics import Chain, energy


def _random_landing(rng, n):
    """A random column of ``n`` blocks just before a landing of a random interface: the
    others open at a gap, open at zero gap or flat (as docs/stack.md's patterns)."""
    b = np.sort(rng.uniform(0.05, 0.5, n))[::-1]
    chain = Chain(b, rng.uniform(0.05, 2.0, n), 10.0 ** rng.uniform(-2, 2, n))
    pattern = [int(s) for s in rng.choice([-1, 0, 1], n)]
    landing = int(rng.integers(n))
    pattern[landing] = int(rng.choice([-1, 1]))
    phi = np.array([s * rng.uniform(0.0, 0.3) * (rng.random() < 0.7) for s in pattern])
    phi[landing] = 0.0
    rate = np.array([rng.normal() if s else 0.0 for s in pattern])
    rate[landing] = -pattern[landing] * abs(rng.normal())
    return chain, phi, rate, tuple(pattern), landing


@pytest.mark.parametrize("n, states", [(4, 40), (5, 25)])
def test_the_pivot_finds_the_one_admissible_set_of_the_enumeration(n, states, monkeypatch):
    # reference: the law with every active set tried and the admissible ones counted (the
    # enumeration of up to three blocks, allowed here for n); the proof in docs/stack.md
    # says at most one is admissible (W positive definite: a P-matrix LCP), and the pivot
    # must return it, bit for bit (both compute the candidate the same way)
    rng = np.random.default_rng(1000 + n)
    counts = {0: 0, 1: 0}
    for _ in range(states):
        chain, phi, rate, pattern, landing = _random_landing(rng, n)
        with monkeypatch.context() as patch:
            patch.setattr(impact, "FULL_ENUMERATION", 99)
            every = impact.plastic_impact(chain, phi, rate, pattern, landing)
        pivot = impact.plastic_impact(chain, phi, rate, pattern, landing)
        assert every[2] <= 1   # never two admissible sets
        counts[every[2]] += 1
        before = energy(chain, phi, rate, pattern)[0]
        assert energy(chain, phi, pivot[0], pivot[1])[0] <= before * (1 + 1e-12)
        if every[2] == 1:
            assert pivot[1] == every[1] and pivot[2] == 1
            np.testing.assert_array_equal(pivot[0], every[0])
    assert counts[1] >= states // 2   # most random landings have their admissible set


def test_a_held_interface_stays_flat_in_the_pivot(monkeypatch):
    # the closure of a cascade holds interfaces flat (their corners equalities): the pivot
    # keeps them flat as the enumeration skips every set that opens them
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(40):
        chain, phi, rate, pattern, landing = _random_landing(rng, 4)
        flat = [j for j in range(4) if phi[j] == 0.0 and j != landing]
        if not flat:
            continue
        with monkeypatch.context() as patch:
            patch.setattr(impact, "FULL_ENUMERATION", 99)
            every = impact.plastic_impact(chain, phi, rate, pattern, landing, closed=flat)
        pivot = impact.plastic_impact(chain, phi, rate, pattern, landing, closed=flat)
        assert all(pivot[1][j] == 0 for j in flat)
        if every[2] == 1:
            assert pivot[1] == every[1]
            checked += 1
    assert checked >= 5


def test_compiled_and_reference_engines_agree_on_a_four_block_column():
    # the compiled pivot (compiled_lcp.py) against the Python one (pivot.py), each engine
    # at rtol 1e-12: the same events, patterns and solutions' counts over a run whose
    # impacts open several interfaces at once (a four-high column under the first 2.6 s of
    # El Centro 1940 x 1.5 with its vertical: 50 events, 16 impacts changing several
    # interfaces; measured 2.3e-16 rad apart)
    stack = Stack([st.Block(2.0, 2.0 - 0.15 * i) for i in range(4)])
    record = records.load("el-centro-1940-180")
    keep = record.t <= 2.6
    motion = st.Motion(record.t[keep], 1.5 * record.horizontal[keep],
                       1.5 * record.vertical[keep])
    compiled = simulate_stack(stack, motion, rtol=1e-12)
    reference = simulate_stack(stack, motion, rtol=1e-12, method="reference")
    kinds = [(e["kind"], e["interface"], e["pattern_after"]) for e in compiled.events]
    assert kinds == [(e["kind"], e["interface"], e["pattern_after"]) for e in reference.events]
    several = sum(1 for e in compiled.events if e["kind"] == "impact"
                  and sum(a != b for a, b in zip(e["pattern_before"], e["pattern_after"])) > 1)
    assert several >= 10
    times = np.array([e["t"] for e in compiled.events])
    np.testing.assert_allclose(times, [e["t"] for e in reference.events], rtol=0, atol=1e-9)
    np.testing.assert_allclose(compiled.theta, reference.theta, rtol=0, atol=1e-9)
