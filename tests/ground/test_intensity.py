"""Intensity measures (shaketable.ground.intensity) against closed forms and against two
independent libraries (eqsig, pyrotd: test-only dependencies, the ``test`` extra)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.ground import intensity as im
from shaketable.ground import records

AMPLITUDE = 2.0          # [m/s^2]
OMEGA = 2.0 * math.pi    # 1 Hz [rad/s]
CYCLES = 10


def _cosine(dt=1e-3, cycles=CYCLES):
    """a = A cos(w t) over whole cycles: v = (A/w) sin(w t), d = (A/w^2)(1 - cos w t)."""
    t = np.arange(0.0, cycles * 2 * math.pi / OMEGA + dt / 2, dt)
    return Motion(t, AMPLITUDE * np.cos(OMEGA * t), name="cosine")


def test_peaks_of_a_harmonic_motion_match_the_closed_forms():
    motion = _cosine()
    # PGA = A; PGV = A / w (sin peaks); PGD = A / w^2 after removing the baseline line
    assert im.pga(motion) == pytest.approx(AMPLITUDE, rel=1e-12)
    assert im.pgv(motion) == pytest.approx(AMPLITUDE / OMEGA, rel=1e-5)
    assert im.pgd(motion) == pytest.approx(AMPLITUDE / OMEGA**2, rel=1e-4)
    assert im.pgv_pga_ratio(motion) == pytest.approx(1.0 / OMEGA, rel=1e-5)
    # without the correction the displacement oscillates about A / w^2: peak 2 A / w^2
    raw = im.ground_displacement(motion, baseline=False)
    assert np.max(np.abs(raw)) == pytest.approx(2 * AMPLITUDE / OMEGA**2, rel=1e-4)


def test_arias_cav_and_duration_of_a_sine_match_the_closed_forms():
    motion = _cosine()
    duration = CYCLES * 2 * math.pi / OMEGA
    # Arias: pi/(2g) int A^2 cos^2 = pi A^2 t_d / (4 g); CAV: int |A cos| = 2 A t_d / pi
    # (rel 1e-5: the samples of the cosine joined by straight lines differ from the
    # cosine by O((w dt)^2))
    assert im.arias_intensity(motion) == pytest.approx(
        math.pi * AMPLITUDE**2 * duration / (4 * G), rel=1e-5)
    assert im.cumulative_absolute_velocity(motion) == pytest.approx(
        2 * AMPLITUDE * duration / math.pi, rel=1e-5)
    # a stationary sine: 5 % to 95 % of its (nearly linear) Arias build-up is 0.9 t_d,
    # to within the ripple of the cos^2 (at most 1 / (2 w) per end)
    assert im.significant_duration(motion) == pytest.approx(0.9 * duration,
                                                             abs=1.0 / OMEGA)


def test_cav_is_exact_across_a_sign_change():
    # two samples a = +1, -1 one second apart: |a| is two triangles of area 1/4
    motion = Motion(np.array([0.0, 1.0]), np.array([1.0, -1.0]))
    assert im.cumulative_absolute_velocity(motion) == pytest.approx(0.5, rel=1e-15)


def test_spectral_acceleration_at_resonance_and_its_geometric_mean():
    # Sa at T -> 0 is the PGA (a rigid oscillator follows the ground); a sine starts from
    # a = 0, so the oscillator starting at rest sees no step
    t = np.arange(0.0, 40.0, 2e-3)
    motion = Motion(t, AMPLITUDE * np.sin(OMEGA * t))
    assert im.spectral_acceleration(motion, 0.01) == pytest.approx(AMPLITUDE, rel=2e-3)
    # geometric mean of Sa over a range equals exp(mean ln Sa) of the same periods
    periods = np.geomspace(0.3, 3.0, 10)
    values = im.spectral_acceleration(motion, periods)
    assert im.average_spectral_acceleration(motion, 0.3, 3.0) == pytest.approx(
        float(np.prod(values) ** 0.1), rel=1e-12)


def test_block_normalised_measures():
    alpha = math.atan(0.25)        # B/H = 1/4
    assert im.normalised_pga(0.25 * G, alpha) == pytest.approx(1.0, rel=1e-15)
    assert im.normalised_pgv(1.0, 2.0, alpha) == pytest.approx(2.0 / (0.25 * G), rel=1e-15)
    with pytest.raises(ValueError, match="alpha"):
        im.normalised_pga(1.0, 2.0)


def test_scale_exponents_hold_for_a_scaled_record():
    motion = records.load("el-centro-chopra")
    base = im.intensity_measures(motion)
    scaled = im.intensity_measures(motion.scaled(1.7))
    for column, value in base.items():
        assert scaled[column] == pytest.approx(value * 1.7 ** im.scale_exponent(column),
                                               rel=1e-9), column


def test_a_zero_motion_is_refused_by_name():
    motion = Motion(np.array([0.0, 0.01, 0.02]), np.zeros(3), name="still")
    with pytest.raises(ValueError, match="still"):
        im.intensity_measures(motion)


# ------------------------------------------------------------------ independent libraries
def _el_centro():
    return records.load("el-centro-1940-180", vertical=False)


def test_peaks_arias_cav_duration_match_eqsig():
    eqsig = pytest.importorskip("eqsig")
    motion = _el_centro()
    signal = eqsig.AccSignal(np.asarray(motion.horizontal), motion.dt)
    assert im.pga(motion) == pytest.approx(signal.pga, rel=1e-12)
    # eqsig integrates with the trapezoid rule from rest too: same velocity
    assert im.pgv(motion) == pytest.approx(signal.pgv, rel=1e-9)
    # eqsig's Arias (g = 9.81) and CAV are trapezoid sums of a^2 and |a|; ours are exact
    # for the piecewise-linear motion. The same motion sampled 20 times finer (linear
    # interpolation: the same function) brings eqsig's sums within O((dt/20)^2) of it.
    fine_t = np.linspace(motion.t[0], motion.t[-1], 20 * (motion.t.size - 1) + 1)
    fine = eqsig.AccSignal(np.interp(fine_t, motion.t, motion.horizontal), motion.dt / 20)
    arias = eqsig.im.calc_arias_intensity(fine)[-1] * 9.81 / G
    assert im.arias_intensity(motion) == pytest.approx(arias, rel=1e-4)
    assert im.cumulative_absolute_velocity(motion) == pytest.approx(
        eqsig.im.calc_cav(fine)[-1], rel=1e-4)
    # eqsig's duration is sample-based (rounded to whole steps)
    assert im.significant_duration(motion) == pytest.approx(eqsig.im.calc_sig_dur(signal),
                                                            abs=3 * motion.dt)


def test_spectral_acceleration_matches_eqsig_and_pyrotd():
    eqsig = pytest.importorskip("eqsig")
    pyrotd = pytest.importorskip("pyrotd")
    motion = _el_centro()
    periods = np.array([0.1, 0.2, 0.5, 1.0, 2.0])
    ours = im.spectral_acceleration(motion, periods)
    # eqsig: Nigam-Jennings too, same piecewise-linear input (up to its own discretisation)
    eqsig_sa = eqsig.sdof.pseudo_response_spectra(np.asarray(motion.horizontal), motion.dt,
                                                  periods, 0.05)[2]
    np.testing.assert_allclose(ours, eqsig_sa, rtol=1e-3)
    # pyrotd: frequency-domain oscillator (zero padding, interpolated): a few per cent
    spectrum = pyrotd.calc_spec_accels(motion.dt, np.asarray(motion.horizontal) / G,
                                       1.0 / periods, 0.05)
    np.testing.assert_allclose(ours / G, spectrum.spec_accel, rtol=0.03)
