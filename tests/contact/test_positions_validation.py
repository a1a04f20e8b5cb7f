"""The contact of the three SPEC 2 positions from the calibrated worn C20 and BV50 profiles, as
docs/validation/31_contact_positions.md states it checked (its writer's ``positions``: the contact stage's
own functions): pressures >= 0 and their sum the preload, every friction curve rising monotonically from 0
to mu, the thesis' points [4.1] in the field-positive convention within 1 mm, and patches that differ (area
or length/width by more than 25 % between two positions)."""
import numpy as np
import pytest

pytestmark = pytest.mark.validation


@pytest.fixture(scope="module")
def res():
    from pipeline.validation.writers.contact_positions import positions

    return positions()


def test_patches_carry_the_preload_and_curves_rise_to_mu(res):
    for r in res.values():
        a, F_L = r["a"], r["c"]["loading"]["preload"]
        p = a["p3_static"]
        assert p.min() >= 0 and abs(p.sum() * a["dx"] * a["dy"] - F_L) < 1e-6 * F_L
        for i, mu in enumerate(a["mu_values"]):
            m = a["rf_mu"][i, :a["rf_n"][i]]
            assert np.all(np.diff(m) >= -1e-9) and m[0] == 0 and m[-1] == pytest.approx(mu, rel=2e-3)


def test_contact_points_are_the_thesis_table(res):
    from geometry.calibration import THESIS_POSITIONS

    for r in res.values():
        yw, yr = THESIS_POSITIONS[r["c"]["contact"]["dy_wr"]]
        assert abs(r["a"]["y_wheel"] - yw) < 1e-3 and abs(r["a"]["y_rail"] - yr) < 1e-3  # field-positive table


def test_the_patches_differ_as_the_profiles_make_them_differ(res):
    area = np.array([r["m"]["area"] for r in res.values()])
    ratio = np.array([r["m"]["ratio"] for r in res.values()])
    assert area.max() / area.min() > 1.25 or ratio.max() / ratio.min() > 1.25
