"""Standard profiles against their published definitions, and the wear
model's geometry."""
import numpy as np
import pytest

from geometry.standard_profiles import rail_head_curve, rail_head_points, s1002


def test_s1002_published_features():
    """EN 13715 S1002: 28 mm flange height (tip at y = -55), tread slope
    -0.0336 at the tape circle, 70 deg flange face (section E), continuous
    at the section bounds to the coefficients' rounding."""
    assert s1002(-55.0) == pytest.approx(28.0, abs=1e-9)
    assert s1002(0.0) == pytest.approx(0.0, abs=1e-12)
    assert (s1002(1e-4) - s1002(-1e-4)) / 2e-4 == pytest.approx(-3.358537058e-02, rel=1e-6)
    assert np.degrees(np.arctan(-(s1002(-39.0) - s1002(-38.5)) / -0.5)) == pytest.approx(70.0, abs=0.01)
    bounds = np.array([-62.764705882, -49.662510381, -39.764473993, -38.426669071, -35.0, -26.0, 32.15796])
    assert np.abs(s1002(bounds - 1e-9) - s1002(bounds + 1e-9)).max() < 2e-4
    with pytest.raises(ValueError):
        s1002(61.0)


@pytest.mark.parametrize("rail", ["bv50", "60e1"])
def test_rail_heads_from_their_arcs(rail):
    """Head curve: symmetric, radius R1 at the crown and R2 on the shoulder
    (curvature of the interpolated tabulation), tangent arcs (C1)."""
    from geometry.profiles import build_profile
    from pipeline.stages.rail import load_rail_params

    pr, _ = load_rail_params(rail)
    y, z = rail_head_points(pr)
    assert np.allclose(y, -y[::-1]) and np.allclose(z, z[::-1])
    p = build_profile(y, z, "rail", rail, "t", 0.0)
    hd = pr["head"]
    assert p.curvature(0.004) == pytest.approx(-1 / hd["crown_radius"] / (1 - (0.004 / hd["crown_radius"]) ** 2) ** 1.5,
                                               rel=1e-3)
    c = rail_head_curve(pr)
    t = np.gradient(np.column_stack([c["y"], c["z"]]), axis=0)
    t /= np.linalg.norm(t, axis=1)[:, None]
    assert np.abs((t * c["n"]).sum(1)).max() < 2e-3  # normals orthogonal to the curve, no kinks
    ys = 0.016  # on the shoulder arc (R2) of both heads
    kappa = p.curvature(ys)
    slope = p.slope(ys)
    assert -kappa / (1 + slope**2) ** 1.5 == pytest.approx(1 / hd["shoulder_radius"], rel=2e-3)


def test_wear_moves_the_surface_along_its_normal():
    """Top wear lowers the crown by its depth; gauge-face wear moves the
    vertical gauge face (normal +y there) inward by its depth and leaves the
    field face alone; the running part stays single-valued."""
    from geometry.wear import RailWear, band, offset_inward, smoothstep, worn_rail
    from pipeline.stages.rail import load_rail_params

    assert band(0.0) == 1.0 and band(1.0) == 0.0 and smoothstep(0.5) == 0.5
    c = rail_head_curve(load_rail_params("bv50")[0])
    w = RailWear(top_depth=1e-3, top_centre=0.0, top_half_width=0.02, gauge_depth=2e-3, gauge_start=0.02)
    y, z = worn_rail(c, w)
    assert np.all(np.diff(y) > 0) and np.interp(0.0, y, z) == pytest.approx(-1e-3, abs=1e-9)
    yo, zo = offset_inward(c["y"], c["z"], c["n"], w.depth(c["s"]))
    face = np.abs(c["n"][:, 1]) < 1e-9  # the vertical head sides
    gauge, field = face & (c["y"] < 0), face & (c["y"] > 0)
    assert gauge.sum() > 10 and np.allclose(yo[gauge] - c["y"][gauge], 2e-3, atol=1e-12)
    assert np.allclose(yo[field], c["y"][field]) and np.allclose(zo[face], c["z"][face])
