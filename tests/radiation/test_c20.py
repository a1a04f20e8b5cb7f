"""The radiation model on the built C20 modal artifact (skipped when
build/wheels/c20/modes.npz has not been made): surfaces and node sets from the
real outline, the unit-force sound power for a lateral force at the default case's y^W = +32 mm."""

import numpy as np
import pytest

from solvers.radiation import thompson_jones as R
from pipeline.validation.references import node_average as NA
from solvers.wheel.receptance import modal_damping
from pipeline.validation.references.radiation import ART, load_c20, Y_DEFAULT

pytestmark = pytest.mark.skipif(not ART.exists(), reason="C20 modal artifact not built (make modes)")


@pytest.fixture(scope="module")
def c20():
    return load_c20()


def test_surfaces_from_the_geometry(c20):
    d, p, s, nodes, c = c20
    assert s.radii[0] == p["hub"]["outer_radius"] and s.radii[-1] == p["tyre"]["rolling_radius"]
    assert np.all(np.diff(s.radii) > 0)
    # the web is tapered (thick at the hub): the tyre-end thickness lies between the two parameters
    assert p["web"]["thickness_tyre"] <= s.w_web < p["web"]["thickness_hub"]
    assert 0 < s.gamma < 1
    assert all(a.size >= 5 for a in nodes.axial)
    pts = d["points"]
    for q, a in enumerate(nodes.axial[:-1]):
        assert np.all((pts[a, 0] >= s.radii[q] - 1e-9) & (pts[a, 0] < s.radii[q + 1] + 1e-9))
    assert set(d["boundary_tread"]).issubset(nodes.radial)
    assert not set(d["boundary_bore"]) & set(np.concatenate(nodes.axial))


def test_contact_node(c20):
    d, p, s, nodes, c = c20
    y = d["points"][c, 1] - p["axle"]["rolling_circle_z"]
    assert abs(y - Y_DEFAULT) < 1e-3


def test_unit_lateral_force(c20):
    d, p, s, nodes, c = c20
    zeta = modal_damping(d["n"], d["m"], d["cls"], d["kind"], d["zeta_suspension"])
    f = R.frequency_grid(100.0, 6500.0, d["f_hz"], zeta, per_decade=200, per_peak=21)
    u = NA.unit_force_power(f, d, s, nodes, c, "lateral")
    res = u.result
    assert np.all(np.isfinite(res.W)) and np.all(res.W >= 0)
    np.testing.assert_allclose(res.W, res.W_n.sum(axis=0), rtol=1e-12)
    # the loudest frequency is a lightly damped axial mode with no nodal circle
    k = int(np.argmin(np.abs(d["f_hz"] - u.f_peak)))
    assert abs(d["f_hz"][k] - u.f_peak) < 1e-6 * u.f_peak
    assert d["cls"][k] == "a" and d["m"][k] == 0 and d["n"][k] >= 2
    assert sum(r["share"] for r in u.table) == pytest.approx(1.0)
    # the rigid half-wheelset modes matter only at low frequency
    flex = NA.unit_force_power(f, d, s, nodes, c, "lateral", rigid=False)
    hi = f > 1000
    assert np.max(np.abs(R.level_db(flex.result.W[hi]) - R.level_db(res.W[hi]))) < 0.5
    assert abs(flex.L_band - u.L_band) < 0.05
