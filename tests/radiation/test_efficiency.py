"""Radiation efficiencies of SPEC 5 ([4.39]-[4.50]) against values worked out
by hand (the arithmetic is written out with literal numbers, not by calling the
formulas under test), their high-frequency limits and low-frequency slopes."""
import numpy as np
import pytest

from solvers.radiation.thompson_jones import (f_ca, f_ct, gamma_cancellation, kappa, radial_frequencies, sigma_axial,
                                   sigma_radial, sigma_torsion)
from pipeline.validation.references.radiation import AXIAL_HAND, GAMMA, RADIAL_HAND

R = 0.39  # C20 nominal rolling radius (m)
SQ = (0.39 / 0.42) ** 0.5  # sqrt(r / 0.42) = 0.963624...


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
