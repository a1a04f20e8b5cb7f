"""The per-step tangential point-contact solver (solvers/timeloop/interaction.py: point_contact,
mu_and_slope) against its defining equations [4.25]-[4.31]."""
import math

import numpy as np
import pytest

from solvers.contact.friction import monotone_slopes, mu_rf
from solvers.timeloop.interaction import EPS_SLIP, point_contact, mu_and_slope, steady_forces
from pipeline.validation.references.interaction import DT, GAMMA_Y, PRELOAD, V, default_contact


@pytest.fixture(scope="module")
def curve():
    c = default_contact(0.35)
    return c.s_nodes, c.mu_nodes, c.slopes


def test_mu_and_slope_is_mu_rf_and_its_derivative(curve):
    s_nodes, mu_nodes, slopes = curve
    s = np.concatenate([np.linspace(0, 1.2 * s_nodes[-1], 3001), s_nodes])
    for x in s:
        m, d = mu_and_slope(x, s_nodes, mu_nodes, slopes)
        assert m == mu_rf(x, s_nodes, mu_nodes, slopes)
    h = 1e-7
    for x in np.linspace(1e-4, 0.9 * s_nodes[-1], 997):
        num = (mu_rf(x + h, s_nodes, mu_nodes, slopes) - mu_rf(x - h, s_nodes, mu_nodes, slopes)) / (2 * h)
        assert abs(mu_and_slope(x, s_nodes, mu_nodes, slopes)[1] - num) < 1e-6 * max(1.0, abs(num))


def _residual(F, s, b, c, F3, curve, eps):
    """Max violation of s = b + c F and F = -mu_RF(|s|) F3 s / sqrt(|s|^2 + eps^2)."""
    sn = math.hypot(*s)
    q = mu_rf(sn, *curve) / math.sqrt(sn * sn + eps ** 2)
    kin = max(abs(s[i] - b[i] - c[i] * F[i]) for i in range(2))
    law = max(abs(F[i] + F3 * q * s[i]) for i in range(2))
    return kin, law


def test_point_contact_solves_its_equations(curve):
    rng = np.random.default_rng(4)
    F3 = PRELOAD
    worst_kin = worst_law = 0.0
    its = []
    for trial in range(3000):
        eps = (0.0, EPS_SLIP)[trial % 2]
        scale = 10.0 ** rng.uniform(-9, 0.5)              # |b| from 1e-9 to 3 m/s
        b = rng.standard_normal(2) * scale
        c = np.array([1.26e-9, 1.15e-9]) / DT * rng.uniform(0.2, 3.0, 2)   # A/dt, anisotropic
        F1, F2, s1, s2, sig, it, nb = point_contact(b[0], b[1], c[0], c[1], F3, *curve, eps, 0.0)
        assert np.all(np.isfinite([F1, F2, s1, s2, sig]))
        kin, law = _residual((F1, F2), (s1, s2), b, c, F3, curve, eps)
        worst_kin = max(worst_kin, kin / np.abs(b).max())
        worst_law = max(worst_law, law / F3)
        assert abs(sig - math.hypot(s1, s2)) <= 1e-12 * np.abs(b).max()
        assert math.hypot(F1, F2) <= 0.35 * F3 * (1 + 1e-12)
        assert F1 * s1 <= 0 and F2 * s2 <= 0                # friction opposes the slip
        its.append(it)
    assert worst_kin < 1e-12 and worst_law < 1e-12
    assert max(its) <= 12 and np.mean(its) < 6


def test_point_contact_zero_slip_and_warm_start(curve):
    # |b| = 0: no slip, no force, no NaN
    assert point_contact(0.0, 0.0, 1e-5, 1e-5, PRELOAD, *curve, EPS_SLIP, 0.3)[:5] == (0.0, 0.0, 0.0, 0.0, 0.0)
    # tiny |b|: linear (viscous) regime of the regularised curve, s = b / (1 + c F3 mu'(0)),
    # exactly with eps = 0 (the default for mu_RF(0) = 0), down to any |b|
    c = 3e-5
    k = curve[2][0] * PRELOAD
    for b in (1e-6, 1e-12, 1e-200):
        F1, F2, s1, s2, *_ = point_contact(0.0, b, c, c, PRELOAD, *curve, 0.0, 0.0)
        assert abs(s2 - b / (1 + c * k)) < 1e-4 * b and abs(F2 + k * s2) < 1e-4 * k * b
    # warm start from the exact root converges at once
    out = point_contact(0.01, -0.19, 3e-5, 2.8e-5, PRELOAD, *curve, EPS_SLIP, 0.0)
    again = point_contact(0.01, -0.19, 3e-5, 2.8e-5, PRELOAD, *curve, EPS_SLIP, out[4])
    assert again[5] <= 2 and abs(again[1] - out[1]) < 1e-9 * abs(out[1])


def test_point_contact_with_a_coulomb_curve():
    """mu(0) > 0 (pure Coulomb): the direction regularisation keeps it finite and monotone."""
    s = np.array([0.0, 1.0])
    m = np.array([0.3, 0.3])
    curve = (s, m, monotone_slopes(s, m))
    for b2 in (-1e-3, -1e-8, -1e-12, 0.0, 1e-10):
        F1, F2, s1, s2, sig, it, nb = point_contact(0.0, b2, 3e-5, 3e-5, PRELOAD, *curve, EPS_SLIP, 0.0)
        assert np.isfinite(F2) and abs(F2) <= 0.3 * PRELOAD * (1 + 1e-12)
        if b2 != 0.0:
            assert np.sign(F2) == -np.sign(b2)
    # slip the contact spring cannot absorb in one step (|b| > c mu F3): F2 = -mu F3 sign(b)
    F2 = point_contact(0.0, -2.0, 3e-5, 3e-5, PRELOAD, *curve, EPS_SLIP, 0.0)[1]
    assert abs(F2 - 0.3 * PRELOAD) < 1e-9 * PRELOAD
    # slip it can absorb: (regularised) stick, c F2 = -b, |s| of the order of eps
    F1, F2, s1, s2, *_ = point_contact(0.0, -0.2, 3e-5, 3e-5, PRELOAD, *curve, EPS_SLIP, 0.0)
    assert abs(F2 - 0.2 / 3e-5) < 1e-6 * F2 and abs(s2) < 10 * EPS_SLIP


def test_steady_forces_sign_convention(curve):
    """gamma_y < 0 gives F2 > 0 on the rail (toward the field side), = mu_RF(|gamma_y| v) F3."""
    c = default_contact(0.35)
    F = steady_forces(c, V, 0.0, GAMMA_Y, PRELOAD)
    assert F[0] == 0.0 and F[2] == PRELOAD
    assert abs(F[1] - mu_rf(abs(GAMMA_Y) * V, *curve) * PRELOAD) < 1e-9 * PRELOAD
    assert F[1] > 0
