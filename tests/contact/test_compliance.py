"""Tangential contact compliance A_tau (SPEC 4.3 [4.32-4.35])."""
import numpy as np
import pytest

from solvers.contact.compliance import compliance_table, contact_compliance, table_compliance
from solvers.contact.norm import approach_for_load, norm_table
from pipeline.validation.references.hertz import ellipsoidal_traction_compliance, hertz
from pipeline.validation.references.contact import DX, E, G, NU, grid, hertz_case
from pipeline.validation.references.kalker import creep_coefficient


def test_circle_matches_mindlin():
    R = 0.3
    H = hertz(1 / (2 * R), 1 / (2 * R), 65e3)
    dx = H.a / 15
    X, Y = grid(37, 37, dx, dx)
    A1, A2 = contact_compliance(H.pressure(X, Y), (1e4, 0.0), dx, dx)
    ref = (2 - NU) / (4 * G * H.a)
    # docs/validation/30_contact.md: Mindlin's no-slip compliance within 0.2 % (30 elements across)
    assert A1 == pytest.approx(ref, rel=0.002) and A2 == pytest.approx(ref, rel=0.002)


@pytest.fixture(scope="module")
def wheel_rail():
    X, Y, h, H = hertz_case(dx=DX, dy=DX)
    _, ns = approach_for_load(65e3, h, DX, DX)
    return h, H, ns


def test_wheel_rail_against_quadrature(wheel_rail):
    _, H, ns = wheel_rail
    A1, A2 = contact_compliance(ns.p, (-3e3, 1.5e4), DX, DX)
    r1, r2 = ellipsoidal_traction_compliance(H.a, H.b, E, NU)
    assert A1 == pytest.approx(r1, rel=0.02) and A2 == pytest.approx(r2, rel=0.02)


def test_against_linear_theory_flexibility(wheel_rail):
    """Kalker's simplified theory reproduces F2 = -c^2 G C22 gamma_y with the flexibility
    L2 = 8 a / (3 G C22); for an ellipsoidal traction mean(u) = L2 F / (pi a b).  SPEC 4.3:
    a factor of 2 does not matter; the ratio is documented in the validation report."""
    _, H, ns = wheel_rail
    A1, A2 = contact_compliance(ns.p, (1e3, 1e4), DX, DX)
    for A, C in ((A1, "C11"), (A2, "C22")):
        L = 8 * H.a / (3 * G * creep_coefficient(C, H.a, H.b))
        ratio = A / (L / (np.pi * H.a * H.b))
        assert 1.0 < ratio < 2.5


def test_independent_of_force_and_sign(wheel_rail):
    _, _, ns = wheel_rail
    ref = contact_compliance(ns.p, (0.0, 0.0), DX, DX)      # unit-force limit
    for F in [(5e3, 1e4), (-5e3, -2e4), (1.0, -1.0)]:
        A = contact_compliance(ns.p, F, DX, DX)
        assert A[0] > 0 and A[1] > 0
        assert np.allclose(A, ref, rtol=0.01)               # cross terms (A12) are small
    assert contact_compliance(np.zeros_like(ns.p), (1.0, 1.0), DX, DX) == (0.0, 0.0)


def test_table_over_the_approach(wheel_rail):
    h, H, _ = wheel_rail
    tab = norm_table(h, np.linspace(0, 1.3 * H.delta, 14), DX, DX)
    A1, A2 = compliance_table(tab.xi3, tab.p, DX, DX)
    assert np.all(A2[1:] > 0) and np.all(np.diff(A2[1:]) < 0)       # stiffer as the contact grows
    x = 0.5 * (tab.xi3[9] + tab.xi3[10])
    assert table_compliance(x, tab.xi3, A2) == pytest.approx(0.5 * (A2[9] + A2[10]))
    assert table_compliance(-1.0, tab.xi3, A2) == A2[0]
