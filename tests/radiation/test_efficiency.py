"""Radiation efficiencies of SPEC 5 ([4.39]-[4.50]) against values worked out
by hand (the arithmetic is written out with literal numbers, not by calling the
formulas under test), their high-frequency limits and low-frequency slopes."""
import numpy as np
import pytest

from solvers.radiation.thompson_jones import (f_ca, f_ct, gamma_cancellation, kappa, radial_frequencies, sigma_axial,
                                   sigma_radial, sigma_torsion)

R = 0.39  # C20 nominal rolling radius (m)
SQ = (0.39 / 0.42) ** 0.5  # sqrt(r / 0.42) = 0.963624...


# ---------------------------------------------------------------- axial
# (n, f, hand value).  kappa = 1.9 + 1.015 n - 0.0189 n^2;  f_ca = 343 kappa / (2 pi 0.39),
# 2 pi 0.39 = 2.4504423;  sigma_a = 1 / (1 + (f_ca / f)^(2n + 4))
AXIAL_HAND = [
    # n = 0: kappa = 1.9, f_ca = 651.7 / 2.4504423 = 265.951991 Hz, (265.951991/200)^4 = 3.126747
    (0, 200.0, 1.9, 265.951991, 1 / (1 + (265.951991 / 200.0) ** 4), 0.24232151),
    # n = 1: kappa = 1.9 + 1.015 - 0.0189 = 2.8961, f_ca = 993.3623 / 2.4504423 = 405.380821 Hz
    (1, 500.0, 2.8961, 405.380821, 1 / (1 + (405.380821 / 500.0) ** 6), 0.77880001),
    # n = 2: kappa = 1.9 + 2.03 - 0.0756 = 3.8544, f_ca = 1322.0592 / 2.4504423 = 539.518607 Hz
    (2, 400.0, 3.8544, 539.518607, 1 / (1 + (539.518607 / 400.0) ** 8), 0.083654227),
    # n = 5: kappa = 1.9 + 5.075 - 0.4725 = 6.5025, f_ca = 2230.3575 / 2.4504423 = 910.185695 Hz
    (5, 800.0, 6.5025, 910.185695, 1 / (1 + (910.185695 / 800.0) ** 14), 0.14105963),
    # n = 8: kappa = 1.9 + 8.12 - 1.2096 = 8.8104, f_ca = 3021.9672 / 2.4504423 = 1233.233379 Hz
    (8, 1000.0, 8.8104, 1233.233379, 1 / (1 + (1233.233379 / 1000.0) ** 20), 0.014879352),
]


@pytest.mark.parametrize("n, f, kap, fca, expr, value", AXIAL_HAND)
def test_axial_efficiency_by_hand(n, f, kap, fca, expr, value):
    assert kappa(n) == pytest.approx(kap, rel=1e-12)
    assert f_ca(n, R) == pytest.approx(fca, rel=1e-8)
    assert expr == pytest.approx(value, rel=1e-6)  # the hand numbers agree with each other
    assert sigma_axial(n, f, R) == pytest.approx(value, rel=1e-6)


def test_axial_vectorised_and_limits():
    n = np.arange(0, 9)[:, None]
    f = np.geomspace(10, 1e6, 50)[None, :]
    s = sigma_axial(n, f, R)
    assert s.shape == (9, 50)
    assert np.all(np.diff(s, axis=1) >= 0)  # rises with frequency
    np.testing.assert_allclose(s[:, -1], 1.0, atol=1e-9)  # -> 1 at high frequency
    assert np.all(sigma_axial(n, 0.0, R) == 0.0)
    # efficiency 1/2 exactly at the critical frequency
    np.testing.assert_allclose(sigma_axial(n[:, 0], f_ca(n[:, 0], R), R), 0.5, rtol=1e-12)


@pytest.mark.parametrize("n", range(0, 9))
def test_axial_low_frequency_slope(n):
    fl = f_ca(n, R) / 1000
    s1, s2 = sigma_axial(n, fl, R), sigma_axial(n, 1.01 * fl, R)
    slope = np.log(s2 / s1) / np.log(1.01)
    assert slope == pytest.approx(2 * n + 4, rel=1e-6)
    assert s1 / (fl / f_ca(n, R)) ** (2 * n + 4) == pytest.approx(1.0, rel=1e-9)


# ---------------------------------------------------------------- radial
# f_r1 = 120 n / 0.9636241, f_r2 = 800 / 0.9636241 = 830.199235, f_r3 = (280 + 150 n) / 0.9636241
GAMMA = 0.4
RADIAL_HAND = [
    # n = 0, f = 200 < f_r3(0) = 290.569732: Gamma / (1 + (830.199235/200)^2) = 0.4 / 18.231 = 0.021940928
    (0, 200.0, 0.4 / (1 + (830.199235 / 200.0) ** 2), 0.021940928),
    # n = 0, f = 500 > f_r3(0): Gamma = 1: 1 / (1 + (830.199235/500)^2) = 0.266175266
    (0, 500.0, 1 / (1 + (830.199235 / 500.0) ** 2), 0.266175266),
    # n = 1, f = 100 < f_r3(1) = 446.232089; f_r1 = 124.529885
    (1, 100.0, 0.4 / (1 + (124.529885 / 100.0) ** 2) / (1 + (830.199235 / 100.0) ** 2), 0.0022426851),
    # n = 2, f = 400 < f_r3(2) = 601.894445; f_r1 = 249.059770
    (2, 400.0, 0.4 / (1 + (249.059770 / 400.0) ** 4) / (1 + (830.199235 / 400.0) ** 2), 0.065515057),
    # n = 3, f = 1500 > f_r3(3) = 757.556802: Gamma = 1; f_r1 = 373.589656
    (3, 1500.0, 1 / (1 + (373.589656 / 1500.0) ** 6) / (1 + (830.199235 / 1500.0) ** 2), 0.76532374),
]


def test_radial_frequencies_by_hand():
    fr1, fr2, fr3 = radial_frequencies(np.array([0, 1, 2, 3]), R)
    np.testing.assert_allclose(fr1, [0.0, 124.529885, 249.059770, 373.589656], rtol=1e-8)
    np.testing.assert_allclose(fr2, 830.199235, rtol=1e-8)
    np.testing.assert_allclose(fr3, [290.569732, 446.232089, 601.894445, 757.556802], rtol=1e-8)
    assert 800 / SQ == pytest.approx(830.199235, rel=1e-8)


@pytest.mark.parametrize("n, f, expr, value", RADIAL_HAND)
def test_radial_efficiency_by_hand(n, f, expr, value):
    assert expr == pytest.approx(value, rel=1e-6)
    assert sigma_radial(n, f, R, GAMMA) == pytest.approx(value, rel=1e-6)


def test_gamma_by_hand():
    # r = 0.39, w = 0.12, r_in = 0.34, w_web = 0.02:
    # S_out = 2 pi 0.39 0.12 = 0.29405307, S_in = 2 pi 0.34 0.10 = 0.21362830
    # Gamma = sqrt(0.08042477 / 0.50768137) = sqrt(0.15841583) = 0.39801488
    assert gamma_cancellation(0.39, 0.12, 0.34, 0.02) == pytest.approx(0.39801488, rel=1e-7)
    assert (0.08042477 / 0.50768137) ** 0.5 == pytest.approx(0.39801488, rel=1e-6)


def test_radial_gamma_switch_and_limit():
    n = np.arange(0, 9)
    fr3 = radial_frequencies(n, R)[2]
    below = sigma_radial(n, fr3 * (1 - 1e-9), R, GAMMA)
    above = sigma_radial(n, fr3 * (1 + 1e-9), R, GAMMA)
    np.testing.assert_allclose(below / above, GAMMA, rtol=1e-6)  # Gamma below f_r3, 1 above
    np.testing.assert_allclose(sigma_radial(n, 1e7, R, GAMMA), 1.0, atol=1e-6)
    assert np.all(sigma_radial(n, 0.0, R, GAMMA) == 0.0)
    s = sigma_radial(n[:, None], np.geomspace(20, 2e4, 7)[None, :], R, GAMMA)
    assert s.shape == (9, 7)


@pytest.mark.parametrize("n", range(0, 9))
def test_radial_low_frequency_asymptote(n):
    fr1, fr2, _ = radial_frequencies(n, R)
    fl = (min(fr1, fr2) if n > 0 else fr2) / 1000
    s1, s2 = sigma_radial(n, fl, R, GAMMA), sigma_radial(n, 1.01 * fl, R, GAMMA)
    slope = np.log(s2 / s1) / np.log(1.01)
    assert slope == pytest.approx(2 * n + 2, rel=1e-5)  # (f/f_r1)^(2n) (f/f_r2)^2
    asym = GAMMA * (fl / fr1) ** (2 * n) * (fl / fr2) ** 2 if n > 0 else GAMMA * (fl / fr2) ** 2
    assert s1 / asym == pytest.approx(1.0, rel=1e-5)


# ---------------------------------------------------------------- torsion
def test_torsion_by_hand():
    # w = 0.1233: f_ct = 2 * 343 / (pi * 0.1233) = 686 / 0.38735836 = 1770.969845 Hz
    assert f_ct(0.1233) == pytest.approx(1770.969845, rel=1e-8)
    # f = 1000: 1 / (1 + 1.770969845^4) = 1 / (1 + 9.8366) = 0.092279933
    assert sigma_torsion(1000.0, 0.1233) == pytest.approx(1 / (1 + 1.770969845**4), rel=1e-7)
    assert sigma_torsion(1000.0, 0.1233) == pytest.approx(0.092279933, rel=1e-6)
    # f = 3000: 1 / (1 + 0.590323282^4) = 0.89171113
    assert sigma_torsion(3000.0, 0.1233) == pytest.approx(0.89171113, rel=1e-6)


def test_torsion_slope_and_limit():
    fct = f_ct(0.1233)
    s1, s2 = sigma_torsion(fct / 1000, 0.1233), sigma_torsion(1.01 * fct / 1000, 0.1233)
    assert np.log(s2 / s1) / np.log(1.01) == pytest.approx(4.0, rel=1e-6)
    assert sigma_torsion(1e7, 0.1233) == pytest.approx(1.0, abs=1e-9)
    assert sigma_torsion(fct, 0.1233) == pytest.approx(0.5, rel=1e-12)
