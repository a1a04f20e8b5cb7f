"""solvers/wheel/receptance.py: contact point, modal damping [4.11], receptances [4.10]."""
import numpy as np
import pytest

from solvers.wheel.receptance import (ContactPoint, contact_node, contact_point, contact_shape, modal_damping,
                                receptance_by_harmonic, shape_at, surface_edges, transfer_receptance,
                                wheel_receptance)
from pipeline.validation.references.greens import ARTIFACT, Y_CONTACT, Z_RC, sdof_receptance, tread_radius_function, wheel_case

needs_artifact = pytest.mark.skipif(not ARTIFACT.exists(), reason="no build/wheels/c20/modes.npz")


def test_modal_damping_rules_and_overrides():
    n = np.array([1, 1, 0, 1, 0, 2, 1, 0, 5, 1])
    m = np.array([0, 0, 0, 0, 0, 0, 0, 1, 0, 0])
    cls = np.array(["s", "s", "s", "a", "a", "a", "r", "a", "r", "c"])
    kind = np.array(["bounce", "roll", "lateral"] + ["flexible"] * 7)
    zs = np.array([0.18, 0.25, 0.08] + [np.nan] * 7)
    z = modal_damping(n, m, cls, kind, zs)
    np.testing.assert_array_equal(z, [0.18, 0.25, 0.08, 1e-2, 1e-3, 1e-4, 1.0, 1e-3, 1e-4, 1e-2])
    z2 = modal_damping(n, m, cls, kind, zs, overrides={5: 0.05, 6: 1e-6})
    assert z2[5] == 0.05 and z2[6] == 1e-6 and z2[3] == 1e-2
    with pytest.raises(IndexError):
        modal_damping(n, m, cls, kind, zs, overrides={10: 0.1})
    with pytest.raises(ValueError):
        modal_damping(n, m, cls, kind, np.full(10, np.nan))


def _arc_mesh():
    """Nodes on a curved 'tread' (r = 0.39 - 0.02 (Z-0.75)^2 ... ) plus interior nodes."""
    Z = np.linspace(0.70, 0.80, 21)
    r = 0.39 - 0.025 * (Z - 0.75) - 3.0 * (Z - 0.75) ** 2
    surf = np.column_stack([r, Z])
    inner = surf - [0.02, 0.0]
    pts = np.vstack([surf, inner])
    nodes = np.arange(21)
    cells = []
    for i in range(20):
        a, b, c, d = i, i + 1, 21 + i, 22 + i
        cells += [[a, c, b], [b, c, d]]
    return pts, nodes, np.array(cells), lambda y: 0.39 - 0.025 * y - 3.0 * y ** 2


def test_contact_point_interpolates_linear_fields_exactly():
    pts, nodes, cells, r_of_y = _arc_mesh()
    rng = np.random.default_rng(0)
    order = rng.permutation(nodes)   # any order of the surface nodes
    field = np.column_stack([2.0 * pts[:, 0] - pts[:, 1], pts[:, 1] ** 0 * 0.3, 5 * pts[:, 1]])
    shapes = field[None]              # one "mode", (1, nodes, 3)
    for y in (-0.037, 0.0, 0.0041, 0.02):
        for kw in (dict(r_of_y=r_of_y), dict(), dict(r_of_y=r_of_y, cells=cells)):
            cp = contact_point(pts, order, y, Z_RC, **kw)
            assert isinstance(cp, ContactPoint)
            assert abs(cp.Z - (Z_RC + y)) < 2e-5          # on the chord next to the curve
            U = shape_at(shapes, cp)[0]
            # linear along the edge: exact for a field linear in (r, Z) at the chord point
            np.testing.assert_allclose(U, [2 * cp.r - cp.Z, 0.3, 5 * cp.Z], rtol=1e-12)
            assert abs(cp.weights.sum() - 1) < 1e-15 and (cp.weights >= 0).all()
        node = contact_node(pts, order, r_of_y, y, Z_RC)
        assert abs(pts[node, 1] - (Z_RC + y)) <= 0.0025 + 1e-12
    with pytest.raises(ValueError):
        contact_point(pts, nodes, 0.2, Z_RC)                   # off the surface
    # MST polyline == the mesh's boundary edges
    e1 = {tuple(sorted(e)) for e in surface_edges(pts, nodes)}
    e2 = {tuple(sorted(e)) for e in surface_edges(pts, nodes, cells)}
    assert e1 == e2 and len(e1) == 20


@needs_artifact
def test_c20_contact_points_on_the_running_surface():
    d = np.load(ARTIFACT)
    surf = np.concatenate([d["boundary_tread"], d["boundary_flange"]])
    r_of_y = tread_radius_function()
    for dy, y in Y_CONTACT.items():
        cp = contact_point(d["points"], surf, y, Z_RC, r_of_y=r_of_y)
        cq = contact_point(d["points"], surf, y, Z_RC)
        cc = contact_point(d["points"], surf, y, Z_RC, r_of_y=r_of_y, cells=d["cells"])
        assert cp.offset < 1e-9                       # the exact surface point lies on the mesh boundary
        assert abs(cp.r - r_of_y(y)) < 1e-9 and abs(cp.Z - Z_RC - y) < 1e-12
        assert abs(cq.r - cp.r) < 1e-9
        assert set(cc.nodes) == set(cp.nodes)
    # +5 and -4 mm lie on the coned tread
    tread = set(d["boundary_tread"].tolist())
    for y in (0.005, -0.004):
        assert set(contact_point(d["points"], surf, y, Z_RC).nodes) <= tread


def test_single_mode_receptance_is_the_sdof():
    f = np.linspace(1, 3000, 500)
    phi = np.array([[0.8, -0.3]])
    G = wheel_receptance(f, [500.0], [40.0], [2], phi, [1e-3])
    H = sdof_receptance(f, 40.0, 500.0, 1e-3)
    np.testing.assert_allclose(G[:, 0, 0], 0.64 * H, rtol=1e-13)
    np.testing.assert_allclose(G[:, 1, 1], 0.09 * H, rtol=1e-13)
    np.testing.assert_allclose(G[:, 0, 1], -0.24 * H, rtol=1e-13)
    np.testing.assert_allclose(G[:, 1, 0], -0.24 * H, rtol=1e-13)


def test_c20_receptance_symmetry_passivity_harmonics_transfer():
    w = wheel_case(-0.032)
    f = np.linspace(5.0, 7000.0, 4001)
    args = (w["f_hz"], w["modal_mass"], w["n"], w["phi"], w["zeta"])
    G = wheel_receptance(f, *args)
    assert np.array_equal(G[:, 0, 1], G[:, 1, 0])
    # passive: -Im G positive semi-definite (e^{i w t} convention)
    A = -G.imag
    assert np.linalg.eigvalsh(A).min() > -1e-12 * np.abs(G).max()
    parts = receptance_by_harmonic(f, *args)
    assert set(parts) == set(np.unique(w["n"]).tolist())
    np.testing.assert_allclose(sum(parts.values()), G, rtol=0, atol=1e-12 * np.abs(G).max())
    n1 = wheel_receptance(f, *args, harmonics=[1])
    np.testing.assert_array_equal(n1, parts[1])
    # node index / ContactPoint with shapes= gives the same as the contact values
    if "contact" in w:
        d = np.load(ARTIFACT)
        cp = w["contact"]
        np.testing.assert_allclose(wheel_receptance(f, w["f_hz"], w["modal_mass"], w["n"], cp, w["zeta"],
                                                    shapes=d["shapes"]), G, rtol=1e-13)
        # transfer to the two edge nodes, interpolated, = point receptance (U_z -> 2, U_r -> 3)
        T = transfer_receptance(f, w["f_hz"], w["modal_mass"], w["n"], cp, w["zeta"], d["shapes"][:, cp.nodes],
                                shapes=d["shapes"])
        Ti = cp.weights[0] * T[:, 0] + cp.weights[1] * T[:, 1]            # (nf, 3, 2)
        np.testing.assert_allclose(Ti[:, 1, :], G[:, 0, :], rtol=1e-10, atol=1e-14 * np.abs(G).max())
        np.testing.assert_allclose(Ti[:, 0, :], G[:, 1, :], rtol=1e-10, atol=1e-14 * np.abs(G).max())
        # the nearest node is one of the edge's nodes
        assert contact_node(d["points"], np.concatenate([d["boundary_tread"], d["boundary_flange"]]),
                            tread_radius_function(), -0.032, Z_RC) in cp.nodes
        np.testing.assert_array_equal(contact_shape(d["shapes"], cp.node), contact_shape(d["shapes"][:, [cp.node]], 0))
