"""Running surfaces: gap and rigid contact search against closed forms."""
import numpy as np
import pytest

from solvers.contact.surfaces import contact_gap, contact_grid, curvatures, rigid_contact_search

R_WHEEL, CONE, R_CROWN = 0.39, 1 / 40, 0.3


def cone_wheel(y):
    return R_WHEEL - CONE * np.asarray(y)


def crown_rail(y):
    return 0.15 + np.sqrt(R_CROWN**2 - np.asarray(y) ** 2) - R_CROWN


def test_gap_of_cone_on_crown_is_the_quadratic_form():
    x = np.linspace(-0.005, 0.005, 11)
    eta = np.linspace(-0.004, 0.004, 9)
    h = contact_gap(cone_wheel, crown_rail, 0.0, 0.0075, x, eta)
    # cone: no lateral curvature; crown: eta^2 / (2 R) about the tangent point; wheel: x^2 / (2 R_w)
    yr = 0.0075 + eta
    slope = -0.0075 / np.sqrt(R_CROWN**2 - 0.0075**2)  # crown slope at the contact point, analytic
    lat = crown_rail(0.0075) - crown_rail(yr) + slope * eta  # drop below the tangent line
    expected = lat[None, :] + x[:, None] ** 2 / (2 * cone_wheel(eta)[None, :])
    assert np.allclose(h, expected - expected.min(), atol=2e-9)
    A, B = curvatures(cone_wheel, crown_rail, 0.0, 0.0075)
    assert A == pytest.approx(1 / (2 * R_WHEEL), rel=1e-9)
    assert B == pytest.approx(1 / (2 * R_CROWN), rel=2e-3)


def test_rigid_contact_of_cone_on_crown_where_slopes_match():
    # the cone's slope -1/40 equals the crown's slope -y/sqrt(R^2 - y^2) at y = R sin(atan(1/40)),
    # on the side where the crown falls as the cone falls (wheel radius decreases toward +y)
    y_expected = -R_CROWN * np.sin(np.arctan(CONE))
    yw, yr = rigid_contact_search(cone_wheel, crown_rail, dy=0.0, y_wheel=np.linspace(-0.03, 0.03, 6001))
    assert yr == pytest.approx(y_expected, abs=2e-5) and yw == pytest.approx(yr)


def test_grid_is_odd_and_covers_the_margin():
    x, y = contact_grid(0.006, 0.004, 0.0005, 0.0005)
    assert len(x) % 2 == 1 and len(y) % 2 == 1
    assert x.max() >= 1.6 * 0.006 and y.max() >= 1.6 * 0.004 and x[len(x) // 2] == 0.0
