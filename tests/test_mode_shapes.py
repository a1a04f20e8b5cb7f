"""Tests for postprocess.modes.geometry and postprocess.modes.shapes (geometry,
displacement mapping, rendered images saved through pipeline.store.atomic)."""

import os

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from pipeline.store.atomic import save_figure, save_image  # noqa: E402
from postprocess.modes import geometry as mg  # noqa: E402
from postprocess.modes import shapes as ms  # noqa: E402

RI, RO, H = 0.1, 0.4, 0.02
NR, NZ = 13, 3  # grid nodes in r and z


def annulus_section(ri=RI, ro=RO, h=H, nr=NR, nz=NZ, quadratic=False):
    """Structured triangulation of the rectangle [ri, ro] x [0, h] (CCW triangles)."""
    rs = np.linspace(ri, ro, nr)
    zs = np.linspace(0.0, h, nz)
    R, Z = np.meshgrid(rs, zs, indexing="ij")
    pts = np.column_stack([R.ravel(), Z.ravel()])
    tris = []
    for i in range(nr - 1):
        for j in range(nz - 1):
            a, b = i * nz + j, (i + 1) * nz + j
            c, d = (i + 1) * nz + j + 1, i * nz + j + 1
            tris += [(a, b, c), (a, c, d)]
    tris = np.array(tris)
    if quadratic:  # fake mid-side node columns: must be ignored
        tris = np.hstack([tris, np.full((len(tris), 3), 10**6)])
    return pts, tris


def perimeter_edges(nr=NR, nz=NZ):
    """Expected boundary edges of the structured grid, as a set of sorted pairs."""
    idx = lambda i, j: i * nz + j  # noqa: E731
    e = set()
    for i in range(nr - 1):
        e.add(tuple(sorted((idx(i, 0), idx(i + 1, 0)))))
        e.add(tuple(sorted((idx(i, nz - 1), idx(i + 1, nz - 1)))))
    for j in range(nz - 1):
        e.add(tuple(sorted((idx(0, j), idx(0, j + 1)))))
        e.add(tuple(sorted((idx(nr - 1, j), idx(nr - 1, j + 1)))))
    return e


# ---------------------------------------------------------------------------
# boundary_edges_from_triangles
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("quadratic", [False, True])
def test_boundary_edges_are_exactly_the_perimeter(quadratic):
    pts, tris = annulus_section(quadratic=quadratic)
    edges = mg.boundary_edges_from_triangles(tris)
    assert edges.shape == (2 * (NR - 1) + 2 * (NZ - 1), 2)
    got = {tuple(sorted(map(int, e))) for e in edges}
    assert len(got) == len(edges)  # no duplicates
    assert got == perimeter_edges()


def test_boundary_edges_keep_triangle_orientation():
    # CCW triangles -> boundary traversed CCW: signed area (shoelace) > 0
    pts, tris = annulus_section()
    edges = mg.boundary_edges_from_triangles(tris)
    p, q = pts[edges[:, 0]], pts[edges[:, 1]]
    signed_area = 0.5 * np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1])
    assert signed_area == pytest.approx((RO - RI) * H, rel=1e-12)


# ---------------------------------------------------------------------------
# sweep_surface
# ---------------------------------------------------------------------------


def test_sweep_area_matches_annular_disc():
    pts, tris = annulus_section()
    edges = mg.boundary_edges_from_triangles(tris)
    surf = mg.sweep_surface(pts, edges, n_phi=120)
    area = surf.mesh.compute_cell_sizes(length=False, volume=False)["Area"].sum()
    exact = 2 * np.pi * (RO**2 - RI**2) + 2 * np.pi * (RO + RI) * H
    assert abs(area - exact) / exact < 0.01
    # bookkeeping: one vertex per (boundary point, angle)
    n_b = len(np.unique(edges))
    assert surf.mesh.n_points == 120 * n_b
    assert surf.mesh.n_cells == 120 * len(edges)
    np.testing.assert_allclose(
        np.hypot(surf.mesh.points[:, 0], surf.mesh.points[:, 1]), pts[surf.point_index, 0]
    )
    np.testing.assert_allclose(surf.mesh.points[:, 2], pts[surf.point_index, 1])
    np.testing.assert_allclose(
        np.arctan2(surf.mesh.points[:, 1], surf.mesh.points[:, 0]) % (2 * np.pi),
        surf.phi % (2 * np.pi),
        atol=1e-12,
    )


def test_sweep_solid_disc_drops_axis_edges():
    # r starts at 0: the edges on the axis must not create degenerate cells
    pts, tris = annulus_section(ri=0.0)
    edges = mg.boundary_edges_from_triangles(tris)
    surf = mg.sweep_surface(pts, edges, n_phi=120)
    sizes = surf.mesh.compute_cell_sizes(length=False, volume=False)["Area"]
    assert sizes.min() > 0.0
    assert surf.mesh.n_cells == 120 * (len(edges) - (NZ - 1))
    exact = 2 * np.pi * RO**2 + 2 * np.pi * RO * H
    assert abs(sizes.sum() - exact) / exact < 0.01


# ---------------------------------------------------------------------------
# displaced
# ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def disc_surface():
    pts, tris = annulus_section()
    edges = mg.boundary_edges_from_triangles(tris)
    return pts, edges, mg.sweep_surface(pts, edges, n_phi=120)


def test_displaced_axial_n2(disc_surface):
    pts, _, surf = disc_surface
    U = np.zeros((len(pts), 3))
    U[:, 1] = 1.0
    scale = 0.01
    new = mg.displaced(surf, U, 2, scale)
    old = np.asarray(surf.mesh.points)
    d = new - old
    np.testing.assert_allclose(d[:, :2], 0.0, atol=1e-15)  # x, y unchanged
    at0 = np.isclose(surf.phi, 0.0)
    at90 = np.isclose(surf.phi, np.pi / 2)
    assert at0.any() and at90.any()
    np.testing.assert_allclose(d[at0, 2], +scale, rtol=1e-12)
    np.testing.assert_allclose(d[at90, 2], -scale, rtol=1e-12)
    np.testing.assert_allclose(d[:, 2], scale * np.cos(2 * surf.phi), atol=1e-15)


def test_displaced_n1_is_rigid_translation(disc_surface):
    pts, _, surf = disc_surface
    U = np.zeros((len(pts), 3))
    U[:, 0] = 1.0
    U[:, 2] = -1.0
    scale = 0.02
    d = mg.displaced(surf, U, 1, scale) - np.asarray(surf.mesh.points)
    np.testing.assert_allclose(d, np.tile([scale, 0.0, 0.0], (len(d), 1)), atol=1e-14)


def test_displaced_n0_torsion_is_tangential(disc_surface):
    pts, _, surf = disc_surface
    U = np.zeros((len(pts), 3))
    U[:, 2] = 3.0  # arbitrary amplitude: normalised away
    scale = 0.005
    d = mg.displaced(surf, U, 0, scale) - np.asarray(surf.mesh.points)
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), scale, rtol=1e-12)
    radial = np.column_stack([np.cos(surf.phi), np.sin(surf.phi), np.zeros_like(surf.phi)])
    np.testing.assert_allclose(np.sum(d * radial, axis=1), 0.0, atol=1e-15)
    np.testing.assert_allclose(d[:, 2], 0.0, atol=1e-15)


def test_displaced_normalises_largest_displacement(disc_surface):
    pts, _, surf = disc_surface
    rng = np.random.default_rng(0)
    U = rng.normal(size=(len(pts), 3)) * 7.0
    d = mg.displaced(surf, U, 3, 0.03) - np.asarray(surf.mesh.points)
    assert np.linalg.norm(d, axis=1).max() == pytest.approx(0.03, rel=1e-12)


# ---------------------------------------------------------------------------
# rendering
# ---------------------------------------------------------------------------


def _rgb(path):
    img = mpimg.imread(path)
    assert img.dtype.kind == "f"  # PNG -> floats in [0, 1]
    return img[..., :3]


def test_render_mode_and_gallery(tmp_path):
    pts, tris = annulus_section()
    edges = mg.boundary_edges_from_triangles(tris)
    U = np.zeros((len(pts), 3))
    U[:, 1] = (pts[:, 0] - RI) / (RO - RI)  # axial, growing with radius
    images = []
    for n, label in [(2, "(2, 0, a)"), (0, "(0, 0, t)")]:
        Un = U if n else np.column_stack([0 * U[:, 0], 0 * U[:, 0], pts[:, 0]])
        out = tmp_path / f"mode_n{n}.png"
        image = ms.render_mode(pts, edges, Un, n, label, 1143.2, window_size=(400, 300))
        assert image.shape[:2] == (300, 400) and image.dtype == np.uint8
        save_image(image, out)
        img = _rgb(out)
        np.testing.assert_array_equal(np.round(img * 255).astype(np.uint8), image[..., :3])  # PNG is lossless
        assert img.std() > 0.05  # not blank
        chroma = img.max(axis=2) - img.min(axis=2)
        assert (chroma > 0.25).mean() > 0.02  # coloured (non-grey) pixels
        images.append(image)

    gal = tmp_path / "gallery.png"
    save_figure(ms.gallery_figure(images, ["(2, 0, a)", "(0, 0, t)"], ncols=4), gal, format="png", facecolor="white")
    g = _rgb(gal)
    assert g.ndim == 3 and g.shape[1] > g.shape[0]  # two tiles side by side
    assert g.std() > 0.05

    # atomic writes: only the final files, no leftover temporaries
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "gallery.png",
        "mode_n0.png",
        "mode_n2.png",
    ]


def test_gallery_rejects_mismatched_labels():
    with pytest.raises(ValueError):
        ms.gallery_figure([np.zeros((4, 4, 3), np.uint8)], [], ncols=2)
    with pytest.raises(ValueError):
        ms.gallery_figure([], [], ncols=2)
