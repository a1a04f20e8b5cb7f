"""Regularized friction curves mu_RF(s) (SPEC 4.4 [4.36-4.37]) on the Hertzian
wheel/rail contact (R = 0.39 m on a 0.3 m crown, 65 kN)."""
import numpy as np
import pytest

from solvers.contact.friction import GAMMA_END, mu_rf, rf_curve
from solvers.contact.norm import approach_for_load
from solvers.contact.tang import tang_steady
from pipeline.validation.references.contact import DX, V, hertz_case

MUS = np.round(np.arange(0.1, 0.6001, 0.05), 2)


@pytest.fixture(scope="module")
def curves_1mm():
    """All 11 curves on a 1 mm grid (fast); the validation report uses dx = 0.5 mm."""
    X, Y, h, H = hertz_case(dx=1e-3, dy=1e-3)
    _, ns = approach_for_load(65e3, h, 1e-3, 1e-3)
    return ns, [rf_curve(ns.p, 1e-3, 1e-3, V, mu) for mu in MUS]


def test_rise_from_zero_to_mu(curves_1mm):
    _, curves = curves_1mm
    for c in curves:
        assert c.s[0] == 0 and c.mu_rf[0] == 0
        assert np.all(np.diff(c.mu_rf) >= 0) and np.all(np.diff(c.mu_rf[:12]) > 0)
        assert c.mu_rf[-1] == pytest.approx(c.mu, rel=1e-4) and c.mu_rf.max() <= c.mu * (1 + 1e-9)
        assert c.gamma[-1] == pytest.approx(GAMMA_END) and c.s[-1] == pytest.approx(GAMMA_END * V)
        assert np.abs(c.F1_over_F3).max() < 1e-9 * c.mu        # no spin, no gamma_x: F1 = 0


def test_longer_transition_for_larger_mu(curves_1mm):
    _, curves = curves_1mm
    s99 = []
    for c in curves:
        s = np.linspace(0, c.s[-1], 20001)
        m = np.array([mu_rf(si, c.s, c.mu_rf, c.slope) for si in s])
        s99.append(s[np.argmax(m >= 0.99 * c.mu)])
    assert np.all(np.diff(s99) > 0)
    # without spin the problem is self-similar: mu_RF(s; mu) / mu = f(s / mu)
    ref = curves[2]                                           # mu = 0.2
    n = 19                                                    # the nodes below 1.25 gamma_sat scale with mu
    for c in curves:
        assert np.allclose(c.s[:n] / c.mu, ref.s[:n] / ref.mu, rtol=1e-9)
        assert np.allclose(c.mu_rf[:n] / c.mu, ref.mu_rf[:n] / ref.mu, rtol=0, atol=1e-8)


def test_numba_interpolant(curves_1mm):
    _, curves = curves_1mm
    c = curves[4]
    for k in range(len(c.s)):
        assert mu_rf(c.s[k], c.s, c.mu_rf, c.slope) == pytest.approx(c.mu_rf[k], abs=1e-14)
    s = np.linspace(0, 1.2 * c.s[-1], 5001)
    m = np.array([mu_rf(si, c.s, c.mu_rf, c.slope) for si in s])
    assert np.all(np.diff(m) >= -1e-15) and m[0] == 0 and m.max() <= c.mu_rf[-1] + 1e-15
    assert mu_rf(-s[100], c.s, c.mu_rf, c.slope) == m[100]    # even in s
    # interpolation between nodes against direct steady TANG at a midpoint
    ns = curves_1mm[0]
    for k in (3, 8, 14):
        g = 0.5 * (c.gamma[k] + c.gamma[k + 1])
        sol = tang_steady(ns.p, 1e-3, 1e-3, V, c.mu, gamma_y=-g)
        assert mu_rf(g * V, c.s, c.mu_rf, c.slope) == pytest.approx(sol.F2 / ns.F3, abs=0.005 * c.mu)


def test_full_slip_creepage_mu03_at_65kN():
    """Thesis 4.3.4 / SPEC 4.4: mu = 0.3, 65 kN, Hertzian contact: full slip near |gamma_y| = 0.006."""
    X, Y, h, H = hertz_case(dx=DX, dy=DX)
    _, ns = approach_for_load(65e3, h, DX, DX)
    c = rf_curve(ns.p, DX, DX, V, 0.3, n_plateau=1)
    g_full = c.gamma[np.argmax(c.stick_fraction == 0)]
    assert 0.005 < g_full < 0.0075
    assert c.mu_rf[np.argmax(c.gamma >= 0.006)] > 0.995 * 0.3
