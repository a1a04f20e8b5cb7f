"""Friction curves at any value (issue 26; docs/validation/32_friction_values.md, its writer's ``measures``):
the curve at mu = 0.33 between its neighbours 0.30 and 0.35, self-similar with them, reaching 0.33, and its
slope at zero slip the no-slip TANG stiffness and, on the Hertzian contact, Kalker's linear theory (C22,
pipeline/validation/references/kalker.py)."""
import pytest


@pytest.mark.validation
def test_curve_at_033_between_neighbours_and_kalker_slope():
    from pipeline.validation.writers.friction_values import measures

    res = measures()
    hz, dc = res["Hertz (SPEC 6)"][0], res["default case (worn C20/BV50)"][0]
    for r in (hz, dc):
        assert r["plateau"] == pytest.approx(0.33, rel=1e-4)
        assert r["below"] < 1e-5 and r["above"] < 1e-5            # ordered (equal in the no-slip start)
        assert r["similar"] < 2e-3                                # mu_RF(s; mu) / mu = f(s / mu), no spin
        assert r["slope_num"] == pytest.approx(r["slope_lin"], rel=0.05)   # first secant: starts on the linear theory
    assert hz["slope_lin"] == pytest.approx(hz["slope_kalker"], rel=0.05)  # Kalker's C22, 0.5 mm grid
    assert dc["slope_lin"] == pytest.approx(dc["slope_kalker"], rel=0.25)  # not Hertzian: an ellipse estimate
