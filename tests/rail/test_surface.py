"""The rail's receptances at any point of the running surface (solvers/rail/surface.py,
pipeline/caches/rail_surface_table.py; issue 25).

1. The quadratic edge weights reproduce any quadratic in y exactly and are 1 at a node.
2. At a loaded node, the stored wave shapes give the wave table's amplitudes
   (solvers.rail.response.wave_table) to rounding: the same formula, -i phi phi / D.
3. At a node that is not loaded (12 mm in the surface model, whose loads are ~7.5 mm apart),
   the point receptance against the direct model loaded there: within 0.5 % of its largest
   entry (measured 1.6e-3 .. 3.5e-3 below 250 Hz, 2e-5 .. 1.4e-3 from 250 Hz to 6.4 kHz; the
   reduced model itself is within 1e-4 .. 5e-4 of the unreduced one, tests/rail/test_response.py).
The validation (--validation): the moving kernel of the default case's point from the surface
table against its direct construction, and a point between nodes against a mesh rebuilt with a
node there (docs/validation/53_any_rail_point.md).
"""
from __future__ import annotations

import numpy as np
import pytest

from solvers.rail import surface as RS
from pipeline.validation.references.rail import mesh_path, rail_params

F_CHECK = np.array([5.0, 60.0, 250.0, 435.0, 900.0, 1500.0, 2500.0, 4000.0, 5500.0, 6400.0])


def test_edge_weights_are_quadratic_lagrange():
    y = np.array([0.0, 1.0, 2.0, 3.5, 5.0])
    vertex = np.array([True, False, True, False, True])
    for yy in (0.0, 0.3, 1.0, 2.0, 2.7, 5.0):
        idx, N = RS.point_weights(y, vertex, yy)
        assert abs(N.sum() - 1) < 1e-14
        q = 3.0 - 2.0 * y + 0.7 * y**2
        assert abs(N @ q[idx] - (3.0 - 2.0 * yy + 0.7 * yy**2)) < 1e-12
    assert np.allclose(RS.point_weights(y, vertex, 2.0)[1], [1, 0, 0]) or \
        np.allclose(RS.point_weights(y, vertex, 2.0)[1], [0, 0, 1])
    with pytest.raises(ValueError, match="off the running surface"):
        RS.point_weights(y, vertex, 5.5)


def test_load_points_span_the_surface():
    poly = np.column_stack([np.array([0.0, 2.5, 5.0, 7.5, 10.0, 12.0, 14.95, 17.4, 19.9, 22.4, 24.85]) * 1e-3,
                            np.zeros(11)])
    pts = RS.load_points(poly, 7.5e-3)
    assert np.allclose(pts, np.array([0.0, 7.5, 14.95, 22.4, 24.85]) * 1e-3)


def _surface(model, rail, f):
    from geometry.rail import running_surface

    poly = RS.surface_polyline(running_surface(rail, rail["contact"]["y"]))
    idx, vertex = RS.surface_nodes(model.families["sym"].nodes, poly, float(poly[-1, 0]))
    K, S = [], []
    for name in ("sym", "anti"):
        rf = getattr(model, name)
        k, s = RS.family_shapes(rf, RS.surface_rows(model.families[name], rf.BY, idx), 2 * np.pi * f)
        K.append(k)
        S.append(s)
    return np.concatenate(K, 1), np.concatenate(S, 1), model.families["sym"].nodes[idx, 0], vertex


def _direct(rail, y, f):
    from pipeline.stages.rail_io import build_rail_model
    from solvers.rail.response import wave_table

    model = build_rail_model(rail, mesh_path("bv50"), contact_y=[y], with_centre=False)
    return model, wave_table(model, f, points=[y])


def test_loaded_node_is_the_wave_table():
    rail = rail_params("bv50")
    model, T = _direct(rail, 0.012, F_CHECK)
    K, S, y_nodes, vertex = _surface(model, rail, F_CHECK)
    idx, N = RS.point_weights(y_nodes, vertex, 0.012)
    a = RS.point_amplitudes(S, idx, N)
    assert np.allclose(K, T["k"], rtol=0, atol=0)
    G, G_ref = a.sum(axis=1), T["a"][:, :, 0].sum(axis=1)
    assert np.abs(G - G_ref).max() / np.abs(G_ref).max() < 1e-12


def test_unloaded_node_against_the_direct_model():
    from geometry.rail import running_surface
    from pipeline.stages.rail_io import build_rail_model

    rail = rail_params("bv50")
    _, T = _direct(rail, 0.012, F_CHECK)
    loads = RS.load_points(RS.surface_polyline(running_surface(rail, rail["contact"]["y"])), 7.5e-3)
    assert np.min(np.abs(loads - 0.012)) > 2e-3  # 12 mm is not loaded in the surface model
    model = build_rail_model(rail, mesh_path("bv50"), contact_y=list(loads), with_centre=False)
    K, S, y_nodes, vertex = _surface(model, rail, F_CHECK)
    idx, N = RS.point_weights(y_nodes, vertex, 0.012)
    G, G_ref = RS.point_amplitudes(S, idx, N).sum(axis=1), T["a"][:, :, 0].sum(axis=1)
    err = np.abs(G - G_ref).max(axis=(1, 2)) / np.abs(G_ref).max(axis=(1, 2))
    assert err.max() < 5e-3, err  # measured 3.5e-3 at 60 Hz, 2e-5 .. 1.4e-3 from 250 Hz to 6.4 kHz


# ------------------------------------------------------------------ validation (docs/validation/53_any_rail_point.md)
# the criteria the fragment states, on the writer's measurements (pipeline.validation.writers.rail_surface: the
# surface table against the direct construction the greens stage stores, and a mesh with a node between two)

@pytest.fixture(scope="module")
def surface_writer():
    from pipeline.validation.make import make_targets
    from pipeline.validation.writers import rail_surface

    make_targets("rail", "contact", "greens", CASE="default")
    return rail_surface


@pytest.mark.validation
def test_default_point_from_the_surface_table(surface_writer):
    d = surface_writer.default_point()
    assert d["e_G"][d["band"]].max() < 1e-2          # point receptance, f <= 6.5 kHz
    assert d["e_g"] < 5e-3                           # moving kernel, 4096 lags
    sims = surface_writer.simulate_both(d["surf"]["rail_kernel"])
    (L0, f0), (L1, f1) = sims.values()
    assert abs(L1 - L0) < 0.1 and abs(f1 / f0 - 1) < 1e-3, sims


@pytest.mark.validation
def test_between_nodes_against_a_mesh_with_a_node_there(surface_writer):
    f, e = surface_writer.between_nodes()
    assert e[f <= 6500.0].max() < 2e-2, e
