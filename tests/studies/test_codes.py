"""The codes' formulas against worked examples computed by hand from the clauses cited
(each formula is one line of arithmetic; the numbers below are written out)."""

import math

import pytest

from shaketable.core.constants import G
from shaketable.studies.codes import (
    asce7_fp,
    asce7_overturning,
    asce43_sliding,
    kinematic_a0,
    kinematic_multiplier,
)


@pytest.mark.parametrize("z_over_h, fp, governs", [
    # ASCE 7-16 Eq. 13.3-1 with a_p = 1, R_p = 2.5, I_p = 1, S_DS = 1.0, W_p = 1000 N:
    # 0.4 * 1 * 1.0 * 1000 * (1 + 2 z/h) / 2.5 = 160 (1 + 2 z/h) N
    (0.0, 300.0, "Eq. 13.3-3"),   # 160 N < 0.3 * 1.0 * 1 * 1000 = 300 N (Eq. 13.3-3)
    (0.5, 320.0, "Eq. 13.3-1"),   # 160 * 2 = 320 N
    (1.0, 480.0, "Eq. 13.3-1"),   # 160 * 3 = 480 N
    (1.7, 480.0, "Eq. 13.3-1"),   # z/h need not exceed 1.0
])
def test_asce7_fp_equation_13_3_1_and_lower_bound(z_over_h, fp, governs):
    result = asce7_fp(1000.0, 1.0, z_over_h=z_over_h)
    assert result.fp == pytest.approx(fp, rel=1e-14)
    assert result.governs == governs


@pytest.mark.parametrize("z_over_h, fp, governs", [
    # a_p = 2.5, R_p = 1.5, I_p = 1.5, S_DS = 0.8, W_p = 2000 N:
    # 0.4 * 2.5 * 0.8 * 2000 * (1 + 2 z/h) / (1.5 / 1.5) = 1600 (1 + 2 z/h) N;
    # bounds 0.3 * 0.8 * 1.5 * 2000 = 720 N, 1.6 * 0.8 * 1.5 * 2000 = 3840 N
    (0.0, 1600.0, "Eq. 13.3-1"),
    (0.5, 3200.0, "Eq. 13.3-1"),
    (1.0, 3840.0, "Eq. 13.3-2"),  # 4800 N > 3840 N (Eq. 13.3-2)
])
def test_asce7_fp_upper_bound(z_over_h, fp, governs):
    result = asce7_fp(2000.0, 0.8, z_over_h=z_over_h, a_p=2.5, r_p=1.5, i_p=1.5)
    assert result.fp == pytest.approx(fp, rel=1e-14)
    assert result.governs == governs
    assert (result.lower, result.upper) == pytest.approx((720.0, 3840.0), rel=1e-14)


def test_asce7_overturning_dead_load_factor():
    # S_DS = 1.0: factor 0.9 - 0.2 = 0.7 (Section 2.3.6, combination 7, Eq. 12.4-4a).
    # W = 1000 N, b = 0.5 m, h_cg = 1.0 m, Fp = 480 N: M = 480 N m,
    # resisting 0.7 * 1000 * 0.25 = 175 N m, uplift (480 - 175) / 0.5 = 610 N
    check = asce7_overturning(480.0, 1000.0, 1.0, width=0.5, height_cg=1.0)
    assert check.factor == pytest.approx(0.7, rel=1e-14)
    assert check.moment == pytest.approx(480.0, rel=1e-14)
    assert check.resisting == pytest.approx(175.0, rel=1e-14)
    assert check.uplift == pytest.approx(610.0, rel=1e-14)
    assert not check.stable
    squat = asce7_overturning(300.0, 1000.0, 1.0, width=2.0, height_cg=1.0)
    assert squat.stable and squat.uplift == 0.0  # 300 N m <= 0.7 * 1000 * 1.0 = 700 N m


def test_kinematic_a0_of_a_rigid_block_about_its_corner():
    # Circolare 2019 C8.7.1: alpha_0 = b/h = 0.5/2.0 = 0.25; e* = 1; a0* = alpha_0 g / (e* FC)
    alpha0 = kinematic_multiplier(0.5, 2.0)
    assert alpha0 == 0.25
    assert kinematic_a0(alpha0) == pytest.approx(0.25 * G, rel=1e-15)
    # knowledge level LC1 of the Circolare: FC = 1.35 -> a0* = 0.25 g / 1.35
    assert kinematic_a0(alpha0, fc=1.35) == pytest.approx(0.25 * G / 1.35, rel=1e-15)


def test_asce43_sliding_coefficient():
    # ASCE 43-05 Eq. A-1: mu = 0.5, A_v = 0.3 g: mu_e = 0.5 (1 - 0.12) = 0.44;
    # Eq. A-2: c_s = 2 * 0.44 g = 0.88 g
    result = asce43_sliding(0.5, 0.3 * G)
    assert result.mu_e == pytest.approx(0.44, rel=1e-14)
    assert result.c_s == pytest.approx(0.88 * G, rel=1e-14)
    assert math.isnan(result.f_s)
    # f_s: the spectrum 0.5 g at 1 Hz, 1.0 g at 2 Hz crosses 0.88 g at 1.76 Hz
    crossing = asce43_sliding(0.5, 0.3 * G, frequencies=[1.0, 2.0], spectrum=[0.5 * G, G])
    assert crossing.f_s == pytest.approx(1.76, rel=1e-12)


@pytest.mark.parametrize("call, match", [
    (lambda: asce7_fp(1000.0, 0.0, z_over_h=0.5), "S_DS"),
    (lambda: asce7_fp(1000.0, 1.0, z_over_h=-0.1), "z/h"),
    (lambda: kinematic_a0(0.25, fc=0.9), "FC"),
    (lambda: asce43_sliding(0.0, 0.0), "mu"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()
