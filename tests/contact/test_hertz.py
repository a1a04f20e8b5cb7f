"""Checks of the Hertz reference itself (pipeline/validation/references/hertz.py)."""
import numpy as np
import pytest

from pipeline.validation.references.hertz import (contact_modulus, curvature_ratio, eccentricity, ellipsoidal_traction_compliance,
                                  hertz, load_for_approach, wheel_rail)


def test_circular_limit():
    R, P, E, nu = 0.3, 65e3, 210e9, 0.3
    Es = contact_modulus(E, nu)
    h = hertz(1 / (2 * R), 1 / (2 * R) * (1 + 1e-9), P)
    a = (3 * P * R / (4 * Es)) ** (1 / 3)
    assert h.a == pytest.approx(a, rel=1e-6) and h.b == pytest.approx(a, rel=1e-6)
    assert h.delta == pytest.approx(a * a / R, rel=1e-6)
    assert h.p0 == pytest.approx(3 * P / (2 * np.pi * a * a), rel=1e-6)


def test_elliptic_relations():
    h = wheel_rail()
    # Johnson's approximation b/a ~ (A/B)^(2/3) within a few percent for mild ellipses
    assert h.b / h.a == pytest.approx((0.3 / 0.39) ** (2 / 3), rel=0.03)
    assert curvature_ratio(h.b / h.a) == pytest.approx(0.39 / 0.3, rel=1e-9)
    assert eccentricity(curvature_ratio(0.5)) == pytest.approx(np.sqrt(0.75), rel=1e-9)
    # swapping the axes swaps the semi-axes
    s = hertz(1 / (2 * 0.3), 1 / (2 * 0.39), 65e3)
    assert (s.a, s.b) == pytest.approx((h.b, h.a), rel=1e-12)
    # delta ~ P^(2/3) and the inverse relation
    assert hertz(1.0, 2.0, 8e3).delta == pytest.approx(4 * hertz(1.0, 2.0, 1e3).delta, rel=1e-12)
    assert load_for_approach(1.0, 2.0, hertz(1.0, 2.0, 5e4).delta) == pytest.approx(5e4, rel=1e-12)


def test_ellipsoidal_compliance_circle_is_mindlin():
    a, E, nu = 5e-3, 210e9, 0.3
    G = E / (2 * (1 + nu))
    A1, A2 = ellipsoidal_traction_compliance(a, a, E, nu)
    assert A1 == pytest.approx((2 - nu) / (4 * G * a), rel=1e-10) and A2 == pytest.approx(A1, rel=1e-12)
