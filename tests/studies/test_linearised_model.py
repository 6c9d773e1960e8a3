"""The literature's linearised rocking model side by side with the exact one.

Reference values and where they come from:

* the closed forms of Housner's linearised Eq. (2-4) under pulses
  (:func:`shaketable.core.theory.linear_pulse_response`, analytic between events), checked
  against an explicit formula written independently here (the half-sine threshold as the
  root of u' + u = 1) and against Eq. (2-7) for the rectangular pulse;
* the issue's literature values 2.79 (omega/p = 4) and 4.79 (omega/p = 8) for the exact
  linearised half-sine minimum (Voyagaki, Psycharis & Mylonakis 2013; Dimitrakopoulos &
  DeJong 2012), against Eq. (2-8)'s 4.12 and 8.06;
* the ``linear`` method (the compiled engine, a different solver: closed form on each
  sample interval of the sampled pulse) must reproduce the closed forms to the chord-area
  limit of the sampling, (2 pi / n)^2 / 12 relative: 7.7e-10 at n = 65536 samples per
  cycle, 4.9e-8 at the default 8192;
* the end-of-motion fate by energy against runs padded with a long free tail.
"""

import math

import numpy as np
import pytest

from shaketable.core import theory
from shaketable.core.fate import FATE_REASONS, free_rocking_fate
from shaketable.ground.pulses import Pulse, pulse_motion
from shaketable.models.api import simulate
from shaketable.scenes.spectrum import block_from
from shaketable.studies.overturning_spectrum import (
    housner_cor,
    overturning_spectrum,
    threshold,
)

P = 2.0


def test_half_sine_threshold_matches_the_literature_and_is_below_eq_2_8():
    # the literature gives 2.79 against Eq. (2-8)'s 4.12 at omega/p = 4, 4.79 against 8.06 at 8
    for ratio, published in ((4, 2.79), (8, 4.79)):
        exact = theory.linear_half_sine_threshold(ratio)
        assert exact == pytest.approx(published, abs=0.005)
        assert exact < math.sqrt(1 + ratio ** 2)


@pytest.mark.parametrize("ratio", [0.5, 1.0, 2.0, 4.0, 8.0])
def test_half_sine_threshold_solves_the_end_of_pulse_condition(ratio):
    """Written here from scratch: lift at p t0 = asin(1/x)/r, u = 1 - K sin(r tau)
    + C1 e^(tau - tau0) + C2 e^-(tau - tau0) with u = u' = 0 at tau0, K = x/(1 + r^2);
    at the end of the pulse tau = pi/r the block is exactly on the barrier: u' + u = 1."""
    x = theory.linear_half_sine_threshold(ratio)
    k = x / (1 + ratio ** 2)
    tau0 = math.asin(1 / x) / ratio
    c_sum = -1 + k * math.sin(ratio * tau0)           # C1 + C2
    c_diff = k * ratio * math.cos(ratio * tau0)       # C1 - C2
    c1, c2 = 0.5 * (c_sum + c_diff), 0.5 * (c_sum - c_diff)
    d = math.pi / ratio - tau0
    u = 1 + c1 * math.exp(d) + c2 * math.exp(-d)
    rate = k * ratio + c1 * math.exp(d) - c2 * math.exp(-d)
    assert 0 < u < 1 and rate > 0
    assert u + rate == pytest.approx(1.0, abs=1e-12)
    # the general closed-form solver (events found numerically) finds the same edge,
    # with any cor (no impact before it overturns)
    for cor in (1.0, 0.7):
        assert theory.linear_pulse_threshold("half-sine", ratio, cor) == pytest.approx(x, rel=1e-12)


@pytest.mark.parametrize("duration", [0.3, 1.0, 2.5])
def test_rectangular_threshold_inverts_eq_2_7(duration):
    x = theory.rectangular_pulse_threshold(duration)
    block = block_from(0.1, P)
    # Eq. (2-7) (core.theory.constant_pulse_overturn_duration) gives back t1 at that amplitude
    t1 = theory.constant_pulse_overturn_duration(block, x * 9.80665 * block.alpha)
    assert P * t1 == pytest.approx(duration, rel=1e-12)
    assert theory.linear_pulse_threshold("rectangular", None, 0.8, duration=duration) == \
        pytest.approx(x, rel=1e-12)


def test_linear_method_reproduces_the_closed_form_thresholds_to_1e_8():
    """threshold(method="linear") bisected on the engine, 65536 samples per cycle."""
    block = block_from(0.1, P)
    unit = block.alpha / math.tan(block.alpha)          # a/(g alpha) -> a/(g tan alpha)
    for kind, ratio, cor, low, high in (("half-sine", 4.0, 1.0, 2.0, 4.0),
                                        ("half-sine", 8.0, 0.9, 4.0, 6.0),
                                        ("one-cosine", 3.0, 0.9, 1.01, 3.0)):
        closed = theory.linear_pulse_threshold(kind, ratio, cor)
        assert low < closed < high
        engine = threshold(block, Pulse(kind, ratio * P), cor=cor, low=low * unit,
                           high=high * unit, tolerance=1e-11, samples_per_cycle=65536,
                           method="linear") / unit
        assert engine == pytest.approx(closed, rel=1e-8), kind


def test_linear_spectrum_reproduces_the_closed_form_one_sine_bands():
    """The issue's 'done when': every one-sine band edge of the linear method, safe window
    included, against the closed forms; 1e-7 at the default sampling, 1e-8 finer."""
    block = block_from(0.1, P)
    cor = housner_cor(block)
    unit = block.alpha / math.tan(block.alpha)
    closed = theory.linear_pulse_bands("one-sine", 4.0, cor)
    assert [b[2] for b in closed] == [-1, 1, -1, 0]   # after one impact, safe window, without
    for samples, rel in ((8192, 1e-7), (65536, 1e-8)):
        spectrum = overturning_spectrum(block, ["one-sine"], [4.0], cor=cor, scan_step=0.02,
                                        tolerance=1e-10, samples_per_cycle=samples,
                                        method="linear")
        edges = [e / unit for e in spectrum.edges("one-sine", 4.0)]
        assert edges == pytest.approx([b[0] for b in closed[1:]], rel=rel)
        assert list(spectrum.to_frame()["impacts"]) == [-1, 1, -1, 0]


def test_fast_method_approaches_the_linearised_threshold_as_alpha_shrinks():
    """The exact model's half-sine threshold in a/(g tan alpha) tends to the linearised
    one in a/(g alpha) as alpha -> 0, the distance falling like alpha^2 (docs/pulses.md
    gives the numbers)."""
    closed = theory.linear_half_sine_threshold(4.0)
    distance = {}
    for alpha in (0.05, 0.1):
        block = block_from(alpha, P)
        exact = threshold(block, Pulse("half-sine", 4.0 * P), cor=1.0, low=2.0, high=4.0,
                          tolerance=1e-10)
        distance[alpha] = exact / closed - 1
    assert 0 < distance[0.05] < 2e-4
    assert 3.5 < distance[0.1] / distance[0.05] < 4.5


@pytest.mark.parametrize("method", ["fast", "linear"])
def test_end_of_motion_fate_agrees_with_padded_runs(method):
    """A run that ends with the pulse knows by energy whether the block will overturn; the
    same run padded with 50/p of table at rest must agree (overturned at pi/2 or not)."""
    block = block_from(0.1, P)
    cor = 0.9
    shape = Pulse("one-sine", 4.0 * P)
    unit = 9.80665 * (block.alpha if method == "linear" else math.tan(block.alpha))
    seen = set()
    for x in np.linspace(1.3, 6.0, 24):
        short = simulate(block, pulse_motion(shape, x * unit, samples_per_cycle=2048), cor=cor,
                         method=method)
        padded = simulate(block, pulse_motion(shape, x * unit, samples_per_cycle=2048,
                                              after=50.0 / P), cor=cor, method=method)
        fate = short.fate
        assert fate.will_overturn == padded.overturned, (x, fate)
        if short.overturned:
            assert fate.reason == "overturned"
        else:
            assert fate.impacts == (padded.n_impacts - short.n_impacts
                                    if padded.overturned else 0), x
        seen.add(fate.reason)
    # the sweep crosses the safe state and both ways of overturning after the pulse
    assert {"rocks down", "passes alpha after one impact"} <= seen


def test_fate_rules_on_hand_states():
    alpha, p, cor = 0.2, 2.0, 0.8
    barrier = p * p * (1 - math.cos(alpha))          # E* = p^2 (1 - cos alpha)
    barrier_rate = math.sqrt(2 * barrier)            # at theta = 0, E = E*
    half_up = p * p * (math.cos(0.5 * alpha) - math.cos(alpha))   # potential at alpha/2

    def inward(energy):                              # theta' at +alpha/2 moving inward
        return -math.sqrt(2 * (energy - half_up))
    states = [  # theta, theta_dot, overturns, impacts, reason
        (0.0, 0.0, False, 0, "at rest"),
        (1.1 * alpha, 1e-3, True, 0, "past alpha moving outward"),
        (-1.1 * alpha, 0.0, True, 0, "past alpha moving outward"),
        (1.1 * alpha, -1e-3, True, 0, "falls back out before alpha"),
        (0.0, 1.001 * barrier_rate, True, 0, "passes alpha outward"),
        (0.0, -0.999 * barrier_rate, False, 0, "rocks down"),
        (-0.5 * alpha, 1.01 * barrier_rate / cor, True, 1, "passes alpha after one impact"),
        (0.5 * alpha, inward(0.99 * barrier / cor ** 2), False, 0, "rocks down"),
        (0.5 * alpha, inward(1.01 * barrier / cor ** 2), True, 1, "passes alpha after one impact"),
    ]
    theta, rate, over, impacts, reason = zip(*states)
    got_over, got_impacts, got_reason, _ = free_rocking_fate(theta, rate, alpha, p, cor)
    assert list(got_over) == list(over)
    assert list(got_impacts) == list(impacts)
    assert [FATE_REASONS[k] for k in got_reason] == list(reason)
    # linearised: u' > 1 - u for an outward block (u = theta/alpha, u' = theta'/(p alpha))
    u = 0.4
    for factor, expected in ((1.001, True), (0.999, False)):
        over, _, _, _ = free_rocking_fate(u * alpha, factor * (1 - u) * p * alpha, alpha, p,
                                          0.0, "linear")
        assert bool(over) is expected


def test_spectrum_command_with_method_linear_gives_the_closed_form_bands(tmp_path, capsys):
    """The issue's 'done when': `shaketable spectrum --method linear` (one-sine, safe window
    included) against the closed forms, to 1e-7 (the CSV's 9 digits)."""
    import pandas as pd

    from shaketable.cli import main

    alpha = 0.1
    block = block_from(alpha, P)
    unit = block.alpha / math.tan(block.alpha)
    assert main(["spectrum", "--alpha", f"{alpha!r}rad", "--p", f"{P!r}rad/s", "--pulse", "one-sine",
                 "--ratios", "4", "--method", "linear", "--scan-step", "0.02",
                 "--out", str(tmp_path)]) == 0
    assert "method linear" in capsys.readouterr().out
    frame = pd.read_csv(tmp_path / "spectrum.csv", comment="#")
    closed = theory.linear_pulse_bands("one-sine", 4.0, housner_cor(block))
    assert list(frame["impacts"]) == [b[2] for b in closed]
    assert list(frame["from a/(g tan alpha) [-]"][1:] / unit) == pytest.approx(
        [b[0] for b in closed[1:]], rel=1e-7)
    assert "method linear" in (tmp_path / "spectrum.csv").read_text().splitlines()[0]


def test_spectrum_scene_method_key(tmp_path):
    from shaketable.scenes.parse import SceneError, load_scene

    text = """name = "linearised"
source = "the literature's linearised model"

[study]
kind = "overturning-spectrum"
pulse = "half-sine"
alpha = "0.1 rad"
p = "2 rad/s"
cor = 1
omega_over_p = [4]
method = "%s"
"""
    path = tmp_path / "scene.toml"
    path.write_text(text % "linear")
    assert load_scene(path).spectrum.method == "linear"
    path.write_text(text % "exact")
    with pytest.raises(SceneError, match="study.method"):
        load_scene(path)


def test_spectrum_and_threshold_refuse_an_unknown_method():
    block = block_from(0.1, P)
    with pytest.raises(ValueError, match="method"):
        overturning_spectrum(block, ["half-sine"], [4.0], method="reference")
    with pytest.raises(ValueError, match="method"):
        threshold(block, Pulse("half-sine", 8.0), cor=1.0, low=2.0, high=4.0, method="exact")
