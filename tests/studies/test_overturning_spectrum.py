"""Overturning spectra of pulses: every band edge against an independent solver
and the literature; Section 4.3 (4) recomputed."""

import math

import numpy as np
import pytest

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.ground.pulses import PULSES, Pulse, cycloidal_phase, pulse_motion
from shaketable.studies import pulses as section_pulses
from shaketable.studies.overturning_spectrum import (
    decide_after_pulse,
    housner_cor,
    overturning_spectrum,
    threshold,
)
from tests.studies import pulse_reference  # SciPy DOP853 on the analytic pulse, written independently

# alpha = 0.25 rad, p = 2 rad/s (R = 3 g / 16), Housner's COR: the blocks of Zhang & Makris (2001)
BLOCK = Block.from_slenderness(3 * G / 16, 0.25)

# Half-sine minimum overturning a/(g tan alpha), literature values (4-5
# significant digits: tolerance half a unit of the last digit).
HALF_SINE = {1: 1.3213, 2: 1.8015, 3: 2.2974, 4: 2.7975, 6: 3.8018, 8: 4.8081, 10: 5.8150}
# One-sine at omega/p = 4: Zhang & Makris (2001), J. Eng. Mech. 127(5)
# (6 significant digits): overturns after one impact from 1.78856, safe 5.00928-5.32302,
# overturns without impact above.
ONE_SINE_4 = [1.78856, 5.00928, 5.32302]


@pytest.fixture(scope="module")
def spectra():
    half = overturning_spectrum(BLOCK, ["half-sine"], list(HALF_SINE))
    one = overturning_spectrum(BLOCK, ["one-sine"], [2, 3, 4])
    return half, one


def test_half_sine_minimum_matches_the_literature(spectra):
    half, _ = spectra
    for ratio, value in HALF_SINE.items():
        assert half.minimum("half-sine", ratio) == pytest.approx(value, abs=5e-5)
        # a single band: the half-sine has no safe window above its threshold
        assert len(half.edges("half-sine", ratio)) == 1


def test_one_sine_bands_zhang_makris_2001(spectra):
    _, one = spectra
    edges = one.edges("one-sine", 4)
    assert edges == pytest.approx(ONE_SINE_4, abs=5e-6)
    frame = one.to_frame()
    rows = frame[frame["omega/p [-]"] == 4]
    assert list(rows["verdict"]) == ["safe", "overturns", "safe", "overturns"]
    assert list(rows["how"])[1:] == ["after 1 impact", "", "without impact"]


@pytest.mark.parametrize("ratio", [2, 3, 4])
def test_one_sine_edges_against_independent_solver(spectra, ratio):
    # every edge to 1e-6 relative: the independent solver's verdict switches across
    # [edge (1 - 1e-6), edge (1 + 1e-6)]
    _, one = spectra
    for edge in one.edges("one-sine", ratio):
        below = pulse_reference.overturns(edge * (1 - 1e-6), "one-sine", ratio)[0]
        above = pulse_reference.overturns(edge * (1 + 1e-6), "one-sine", ratio)[0]
        assert below != above, edge


@pytest.mark.parametrize("ratio", [1, 4, 10])
def test_half_sine_edges_against_independent_solver(spectra, ratio):
    half, _ = spectra
    edge = half.minimum("half-sine", ratio)
    assert not pulse_reference.overturns(edge * (1 - 1e-6), "half-sine", ratio)[0]
    assert pulse_reference.overturns(edge * (1 + 1e-6), "half-sine", ratio)[0]


def test_spectrum_csv_has_units_and_provenance(spectra, tmp_path):
    _, one = spectra
    path = tmp_path / "spectrum.csv"
    one.to_csv(path)
    text = path.read_text()
    assert text.startswith("# overturning spectrum")
    assert "from a/(g tan alpha) [-]" in text and "omega/p [-]" in text


def test_section_4_3_4_exact_half_sine_threshold():
    # 16 x 4 ft block, 0.1 s half-sine, COR 1: 2.506643 g (exact value to 1e-6);
    # Eq. (2-9) 4.50 g with alpha = atan(B/H), 4.59 g with alpha = B/H; report 4.6 g.
    frame = section_pulses.section_4_3_4(pulse_durations=(0.1,))
    row = frame.iloc[0]
    assert row["engine [g]"] == pytest.approx(2.506643, abs=5e-7)
    assert row["Eq. 2-9 [g]"] == pytest.approx(4.50, abs=5e-3)
    assert row["Eq. 2-9, alpha = B/H [g]"] == pytest.approx(4.59, abs=5e-3)


def test_energy_decision_cases():
    alpha, p = 0.25, 2.0
    barrier = p * p * (1 - math.cos(alpha))
    speed = math.sqrt(2 * barrier)
    # at theta = 0 moving outward just above / below the barrier
    over, impacts = decide_after_pulse([1e-15, 1e-15], [1.001 * speed, 0.999 * speed],
                                       alpha, p, 1.0)
    assert list(over) == [True, False] and list(impacts) == [0, 0]
    # mirrored: the same
    over, _ = decide_after_pulse([-1e-15], [-1.001 * speed], alpha, p, 1.0)
    assert over[0]
    # moving inward fast: overturns after one impact only if cor^2 E clears the barrier
    over, impacts = decide_after_pulse([0.1, 0.1], [-2 * speed, -2 * speed], alpha, p,
                                       np.array(1.0))
    assert over[0] and impacts[0] == 1
    over, _ = decide_after_pulse([0.1], [-2 * speed], alpha, p, 0.4)
    assert not over[0]
    # at rest: safe
    assert not decide_after_pulse([0.0], [0.0], alpha, p, 1.0)[0][0]


def test_pulse_registry_is_loud_and_shapes_are_right():
    with pytest.raises(ValueError, match="unknown pulse kind 'square'"):
        Pulse("square", 1.0)
    assert "ricker" in PULSES
    assert Pulse("type-A", 2.0).kind == "one-sine"
    c1 = Pulse("type-C1", 2.0)
    phi = cycloidal_phase(1)
    assert 2 * math.cos(phi) == pytest.approx(math.sin(phi) * (3 * math.pi - 2 * phi), abs=1e-12)
    assert abs(c1(c1.duration * (1 - 1e-12)) - math.cos(3 * math.pi - phi)) < 1e-9
    # zero final velocity and displacement of the type-C1 pulse (trapezoidal double integration)
    t = np.linspace(0, c1.duration, 200001)
    velocity = np.concatenate([[0], np.cumsum(0.5 * (c1(t[1:]) + c1(t[:-1])) * np.diff(t))])
    displacement = np.sum(0.5 * (velocity[1:] + velocity[:-1]) * np.diff(t))
    assert abs(displacement) < 1e-6
    assert abs(velocity[-1]) < 1e-6
    motion = pulse_motion(Pulse("ricker", 4.0), 2.0)
    assert motion.pga == pytest.approx(2.0, rel=1e-6)


def test_housner_cor():
    assert housner_cor(BLOCK) == pytest.approx(1 - 1.5 * math.sin(0.25) ** 2)


def test_a_band_narrower_than_the_scan_is_flagged_not_hidden(tmp_path):
    """The one-sine safe window at omega/p = 4 (5.00928-5.32302, Zhang & Makris 2001, 6.3 %
    wide) scanned with a 20 % step: bisection still finds it (its two sides differ), to the
    literature's 6 digits, and it is flagged as narrower than the scan in the table, the
    windows, the CSV and the figure."""
    coarse = overturning_spectrum(BLOCK, ["one-sine"], [4], scan_step=0.2)
    assert coarse.edges("one-sine", 4) == pytest.approx(ONE_SINE_4, abs=5e-6)
    frame = coarse.to_frame()
    window = frame[frame["from a/(g tan alpha) [-]"].round(5) == 5.00928].iloc[0]
    assert window["verdict"] == "safe" and window["flagged"]
    assert "narrower than the scan step (0.2 relative)" in window["note"]
    assert not frame[frame["verdict"] == "overturns"]["flagged"].any()
    narrow = coarse.windows[coarse.windows["reason"] == "band narrower than the scan"]
    assert len(narrow) == 1
    assert narrow.iloc[0]["from a/(g tan alpha) [-]"] == pytest.approx(5.00928, abs=5e-6)
    path = tmp_path / "coarse.csv"
    coarse.to_csv(path)
    assert "# flag: one-sine omega/p=4: safe band 5.00928" in path.read_text()
    ax = coarse.plot()
    framed = [patch for patch in ax.patches if patch.get_edgecolor()[:3] == (1.0, 0.0, 0.0)]
    assert len(framed) == len(coarse.windows) == 1
    assert framed[0].get_y() == pytest.approx(5.00928, abs=5e-6)


def test_the_default_scan_resolves_the_known_bands(spectra):
    """At the default 0.5 % step no band of these spectra is narrower than the scan, and
    the half-sine (a single transition) has nothing to flag."""
    half, one = spectra
    assert half.flags == [] and not half.to_frame()["flagged"].any()
    assert "band narrower than the scan" not in set(one.windows["reason"])


def test_the_single_threshold_bisection_refuses_a_banded_pulse():
    """threshold() (Fig. 2.6, Section 4.3 (4)) checks its single-transition assumption:
    the one-sine at omega/p = 4 has three transitions in [1.5, 8] (1.78856, 5.00928,
    5.32302, Zhang & Makris 2001) and must raise rather than return one edge; the
    half-sine there has one (2.7975, the literature value)."""
    shape = Pulse("one-sine", 4 * BLOCK.p)
    with pytest.raises(ValueError, match="3 overturn/safe transitions.*overturning_spectrum"):
        threshold(BLOCK, shape, cor="housner", low=1.5, high=8.0)
    half = threshold(BLOCK, Pulse("half-sine", 4 * BLOCK.p), cor="housner", low=1.5, high=8.0,
                     tolerance=1e-7)
    assert half == pytest.approx(HALF_SINE[4], abs=5e-5)


def test_bisect_threshold_checks_a_single_switch():
    # a predicate true on (1, 2) and above 3: two switches in [0, 4] seen by the scan
    with pytest.raises(ValueError, match="switches 3 times"):
        section_pulses.bisect_threshold(lambda x: 1 < x < 2 or x > 3, 0.0, 4.0)
    edge = section_pulses.bisect_threshold(lambda x: x > math.pi, 0.0, 4.0, iterations=40)
    assert edge == pytest.approx(math.pi, abs=1e-11)
    with pytest.raises(ValueError, match="does not hold"):
        section_pulses.bisect_threshold(lambda x: x > 5, 0.0, 4.0)
