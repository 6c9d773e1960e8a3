"""Tests of shaketable.lab.sensors: potentiometer geometry, clipping, digitization, wires, noise."""

from __future__ import annotations

import math

import numpy as np
import pytest

import shaketable as st
from shaketable.core.constants import INCH, G
from shaketable.core.motion import Motion
from shaketable.lab.digitizer import Digitizer
from shaketable.lab.sensors import (
    Accelerometers,
    Measurement,
    Potentiometers,
    Sensors,
    measure,
    theta_from_top_displacement,
    top_displacement,
)

BLOCK = st.Block.parse("30x6in")   # the report's test block (Section 3.2)
QUIET = Digitizer(bits=0, noise=0.0)   # no ADC step, no ADC noise


def _quiet_sensors(**digitizer):
    return Sensors(potentiometers=Potentiometers(noise=0.0),
                   accelerometers=Accelerometers(noise=0.0),
                   digitizer=Digitizer(bits=0, noise=0.0, **digitizer), seed=0)


# ------------------------------------------------------------------ geometry
def test_top_displacement_by_hand_for_both_corners():
    # 30 x 6 in block tilted by 0.1 rad onto its -x corner (theta > 0): the top middle point,
    # 3 in from the pivot horizontally and 30 in above it, moves by
    # -30 sin(0.1) - 3 (1 - cos 0.1) = -2.9950025 - 0.0149875 = -3.0099900 in (hand calculation).
    assert top_displacement(0.1, BLOCK) / INCH == pytest.approx(-3.0099900, abs=1e-6)
    # mirror image on the +x corner
    assert top_displacement(-0.1, BLOCK) / INCH == pytest.approx(3.0099900, abs=1e-6)
    # theta = alpha = atan(3/15): the centroid is above the pivot; the top middle point sits at
    # x = -3 + 15.297 * sin(alpha) ... evaluated directly: rotate (3, 30) about (-3, 0) by alpha.
    alpha = math.atan2(3.0, 15.0)
    x = -3.0 + 3.0 * math.cos(alpha) - 30.0 * math.sin(alpha)
    assert top_displacement(alpha, BLOCK) / INCH == pytest.approx(x, abs=1e-9)


def test_exact_inversion_round_trip_and_small_angle_difference():
    theta = np.linspace(-1.2, 1.2, 241)
    back = theta_from_top_displacement(top_displacement(theta, BLOCK), BLOCK)
    np.testing.assert_allclose(back, theta, atol=1e-12)
    # the report's conversion -x/H differs from the exact angle by (b/2H) theta^2 - theta^3/6
    # + O(theta^4) (expand -x/H = sin(theta) + (b/H)(1 - cos(theta)) by hand)
    small = 0.05
    report = -top_displacement(small, BLOCK) / BLOCK.height
    expected = BLOCK.b / (2 * BLOCK.height) * small**2 - small**3 / 6
    assert report - small == pytest.approx(expected, rel=0.02)


def test_measured_angles_of_a_held_block():
    # a free-rocking run recorded from 1 s before the release: while held, the block sits at
    # theta0 and the potentiometer reads top_displacement(theta0) exactly (no noise, no ADC)
    theta0 = 0.1
    run = st.simulate(BLOCK, cor=0.9, theta0=theta0, duration=3.0)
    record = measure(run, sensors=_quiet_sensors(start=-1.0))
    held = record.t < -0.2          # the filter has settled on the held value long before
    expected = -30.0 * math.sin(0.1) - 3.0 * (1.0 - math.cos(0.1))   # in, as above
    np.testing.assert_allclose(record.top_displacement[held] / INCH, expected, atol=1e-9)
    np.testing.assert_allclose(record.theta_exact[held], theta0, atol=1e-12)
    np.testing.assert_allclose(record.theta[held], -expected / 30.0, atol=1e-12)


# ------------------------------------------------------------------ clipping
def test_potentiometer_clips_at_15_in_when_the_block_overturns():
    run = st.simulate(BLOCK, cor=0.9, theta0=1.05 * BLOCK.alpha, duration=3.0)
    assert run.overturned
    record = measure(run, sensors=Sensors(potentiometers=Potentiometers(noise=0.0),
                                          accelerometers=None, digitizer=Digitizer(noise=0.0),
                                          seed=0))
    # the range is +-15 in (Section 3.3); overturning takes the top 33 in away
    assert np.max(np.abs(record.top_displacement)) == pytest.approx(15.0 * INCH, abs=1e-12)
    assert record.clipped and record.top_clipped[-1]
    assert not record.top_clipped[0]
    # every sample at the stroke is flagged; a flagged sample below it is one where the
    # potentiometer clipped but the anti-alias filter had not yet caught up (within 1 in)
    at_stroke = np.abs(record.top_displacement) >= 15.0 * INCH - 1e-12
    assert np.all(record.top_clipped[at_stroke])
    below = record.top_clipped & ~at_stroke
    assert np.all(np.abs(record.top_displacement[below]) > 14.0 * INCH)


# ------------------------------------------------------------------ digitization
def _sine_record(frequency, anti_alias):
    t = np.arange(0.0, 4.0 + 1e-9, 0.0005)   # 2000 samples/s: the sine is well resolved
    motion = Motion(t, 0.5 * G * np.sin(2 * np.pi * frequency * t))
    run = st.simulate(st.Block.parse("30x30in"), motion, cor=0.9)   # alpha = 45 deg: no rocking
    assert np.isnan(run.t_start)
    sensors = Sensors(potentiometers=None, accelerometers=Accelerometers(noise=0.0),
                      digitizer=Digitizer(rate=50.0, anti_alias=anti_alias, bits=0, noise=0.0),
                      seed=0)
    record = measure(run, sensors=sensors)
    steady = record.t > 1.0       # after the filter's transient
    return np.sqrt(2.0) * np.std(record.table_horizontal[steady]) / (0.5 * G)


def test_anti_alias_filter_attenuates_a_sine_above_nyquist():
    # 40 Hz is above the 25 Hz Nyquist frequency of 50 samples/s. A 4-pole Butterworth at
    # 20 Hz has |H| = 1 / sqrt(1 + (40/20)^8) = 0.0624 (analog formula).
    assert _sine_record(40.0, anti_alias=True) == pytest.approx(0.0624, abs=0.01)
    # without the filter the sine aliases to 10 Hz with its full amplitude
    assert _sine_record(40.0, anti_alias=False) == pytest.approx(1.0, abs=0.02)
    # 2 Hz (the report's harmonic tests) passes: |H| = 1 / sqrt(1 + 0.1^8) = 1.0000
    assert _sine_record(2.0, anti_alias=True) == pytest.approx(1.0, abs=0.01)


def test_sampling_rate_and_the_table_systems_100_samples_per_second():
    run = st.simulate(BLOCK, cor=0.9, theta0=0.05, duration=2.0)
    for rate in (50.0, 100.0):
        record = measure(run, sensors=Sensors(digitizer=Digitizer(rate=rate), seed=1))
        np.testing.assert_allclose(np.diff(record.t), 1.0 / rate, rtol=1e-9)
        assert record.t[0] == 0.0 and record.t[-1] == pytest.approx(2.0)


def test_adc_quantises_to_the_lsb():
    run = st.simulate(BLOCK, cor=0.9, theta0=0.05, duration=2.0)
    record = measure(run, sensors=Sensors(digitizer=Digitizer(bits=8, noise=0.0),
                                          potentiometers=Potentiometers(noise=0.0), seed=1))
    lsb = 2 * 15.0 * INCH / 2**8     # +-15 in over 8 bits
    steps = record.top_displacement / lsb
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-9)


# ------------------------------------------------------------------ wires
def test_one_wire_pulls_with_20_oz_over_the_block_mass():
    # 20 oz = 20 x 0.028349523125 kg x 9.80665 m/s^2 = 5.56028 N (definition of the ounce-force;
    # the report's "20 ounces", Section 3.3)
    one = Potentiometers(wires="minus-x", block_mass=100.0)
    assert one.top_force(BLOCK) == pytest.approx(-5.56028 / 100.0, rel=1e-5)
    assert Potentiometers(wires="plus-x", block_mass=100.0).top_force(BLOCK) == pytest.approx(
        +5.56028 / 100.0, rel=1e-5)
    # default mass: 2400 kg/m^3 x 30 in x 6 in x 12 in = 2400 x 0.762 x 0.1524 x 0.3048 = 84.95 kg
    assert Potentiometers(wires="minus-x").top_force(BLOCK) == pytest.approx(-5.56028 / 84.9505,
                                                                             rel=1e-4)


def test_two_wires_cancel():
    assert Potentiometers(wires="both").top_force(BLOCK) == 0.0
    assert Sensors().top_force(BLOCK) == 0.0


def test_a_minus_x_wire_tilts_a_released_block_toward_minus_x():
    # The -x wire pulls the top toward -x, which is the direction of positive theta
    # (docs/conventions.md): released from a small positive angle, the wire adds a positive
    # moment, so the block stays out longer than without it.
    force = Potentiometers(wires="minus-x").top_force(BLOCK)
    free = st.simulate(BLOCK, cor=0.9, theta0=0.05, duration=1.0)
    pulled = st.simulate(BLOCK, cor=0.9, theta0=0.05, duration=1.0, top_force=force)
    first_zero = lambda run: run.t[np.flatnonzero(run.theta <= 0)[0]]
    assert first_zero(pulled) > first_zero(free)


# ------------------------------------------------------------------ noise and seeds
def _at_rest(seed, **kwargs):
    run = st.simulate(BLOCK, cor=0.9, theta0=0.0, duration=40.0)
    sensors = Sensors(potentiometers=Potentiometers(noise=0.02 * INCH),
                      accelerometers=Accelerometers(noise=0.01 * G),
                      digitizer=Digitizer(bits=0, noise=0.0, **kwargs), seed=seed)
    return measure(run, sensors=sensors)


def test_noise_level_is_honoured():
    record = _at_rest(3)
    # 2001 samples; the filtered noise is correlated over ~2 samples, so the standard error of
    # a standard deviation is ~ 1/sqrt(2 x 1000) = 2.2 %: allow 8 %.
    assert np.std(record.top_displacement) / INCH == pytest.approx(0.02, rel=0.08)
    assert np.std(record.table_horizontal) / G == pytest.approx(0.01, rel=0.08)
    # the vertical is the average of two independent accelerometers: noise / sqrt(2)
    assert np.std(record.table_vertical) / G == pytest.approx(0.01 / np.sqrt(2), rel=0.08)
    # also without the anti-alias filter (white noise at the samples)
    assert np.std(_at_rest(4, anti_alias=False).top_displacement) / INCH == pytest.approx(
        0.02, rel=0.08)


def test_seeds_are_reproducible():
    a, b, c = _at_rest(7), _at_rest(7), _at_rest(8)
    np.testing.assert_array_equal(a.top_displacement, b.top_displacement)
    np.testing.assert_array_equal(a.table_vertical, b.table_vertical)
    assert not np.array_equal(a.top_displacement, c.top_displacement)


# ------------------------------------------------------------------ pitch and outputs
def test_vertical_pair_averages_out_the_pitch():
    t = np.arange(0.0, 2.0 + 1e-9, 0.001)
    rotation = 0.22 * np.sin(2 * np.pi * 12.0 * t)        # Section 3.7 (2): 12 Hz, 0.22 rad/s^2
    motion = Motion(t, np.zeros_like(t), np.zeros_like(t), rotation=rotation)
    run = st.simulate(BLOCK, motion, cor=0.9)
    record = measure(run, sensors=_quiet_sensors())
    # each accelerometer alone reads +-spacing x rotation (12 in x 0.22 = 0.067 m/s^2 peak);
    # the average cancels it exactly
    assert np.max(np.abs(record.table_vertical)) < 1e-12


def test_measurement_motion_and_frame():
    t = np.arange(0.0, 3.0 + 1e-9, 0.005)
    motion = Motion(t, 0.1 * G * np.sin(2 * np.pi * 2 * t), 0.05 * G * np.sin(2 * np.pi * 2 * t))
    run = st.simulate(BLOCK, motion, cor=0.9)
    record = measure(run, sensors=_quiet_sensors())
    digitized = record.motion()
    assert isinstance(digitized, Motion) and digitized.dt == pytest.approx(0.02)
    # the 2 Hz accelerations pass the 20 Hz filter with a delay of about 0.03 s: compare the
    # amplitude only (4-pole Butterworth gain at 2 Hz = 1.0000)
    assert np.max(np.abs(digitized.horizontal)) / G == pytest.approx(0.1, rel=0.01)
    frame = record.to_frame()
    assert {"time [s]", "theta [rad]", "table horizontal [g]", "top displacement [in]"} <= set(
        frame.columns)
    with pytest.raises(ValueError, match="accelerometers"):
        Measurement(t=record.t, top_displacement=None, theta=None, theta_exact=None,
                    table_horizontal=None, table_vertical=None, rate=50.0,
                    block=BLOCK).motion()


def test_measurement_plot(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    run = st.simulate(BLOCK, cor=0.925, theta0=0.5 * BLOCK.alpha, duration=3.0)
    fig = measure(run, sensors=Sensors(seed=2)).plot()
    fig.savefig(tmp_path / "record.png")
    assert (tmp_path / "record.png").stat().st_size > 1000


# ------------------------------------------------------------------ validation
@pytest.mark.parametrize("build, name", [
    (lambda: Potentiometers(wires="left"), "wires"),
    (lambda: Potentiometers(stroke=-1.0), "stroke"),
    (lambda: Potentiometers(noise=float("nan")), "noise"),
    (lambda: Potentiometers(block_mass=0.0), "block_mass"),
    (lambda: Accelerometers(spacing=-0.1), "spacing"),
    (lambda: Digitizer(rate=0.0), "rate"),
    (lambda: Digitizer(rate=50.0, cutoff=30.0), "cutoff"),
    (lambda: Digitizer(bits=40), "bits"),
    (lambda: Digitizer(filter_order=0), "filter_order"),
    (lambda: Digitizer(start=2.0, end=1.0), "end"),
    (lambda: Sensors(seed=-1), "seed"),
    (lambda: Sensors(digitizer="50 Hz"), "digitizer"),
])
def test_bad_parameters_name_the_parameter(build, name):
    with pytest.raises(ValueError, match=name):
        build()


def test_measure_rejects_bad_arguments():
    run = st.simulate(BLOCK, cor=0.9, theta0=0.05, duration=1.0)
    with pytest.raises(ValueError, match="result"):
        measure("run")
    with pytest.raises(ValueError, match="sensors"):
        measure(run, sensors={"rate": 50})
    with pytest.raises(ValueError, match="block"):
        Potentiometers().top_force("30x6in")
