"""Contact angle (issue 26, solvers/contact/frame.py, pipeline/config/contact_plane.py): the projection of
the receptances, kernels and modal shapes on the contact plane.

* a rotation by 0 gives the old arrays exactly (the reference's `angle = "none"`);
* the projected Kropp kernel of the C20 (band-limited, as the greens stage makes it) against an
  independent computation: the receptance of the modal sum with the shapes taken along the tilted
  directions e2', e3' (each shape dotted with the unit vectors, not through ``rotation``);
* the projection of a 2x2 kernel lag by lag against e_i'^T g e_j' written out;
* the resolved preload and the force back-rotation are consistent (N cos delta = Q, R^T R = 1).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.config.contact_plane import RAIL_MATRICES, WHEEL_MATRICES, project_greens
from solvers.contact.frame import normal_preload, project_receptance, project_shapes, rotation, to_structure
from solvers.greens.kernels import choose_grid, frequency_grid
from pipeline.validation.references.greens import DT, pointwise_error, wheel_case
from pipeline.validation.references.two_point import ANGLE, projected_kernel, tilted_directions

def test_rotation_by_zero_is_exact():
    rng = np.random.default_rng(3)
    g = rng.standard_normal((257, 2, 2))
    G = rng.standard_normal((33, 2, 2)) + 1j * rng.standard_normal((33, 2, 2))
    phi = rng.standard_normal((40, 2))
    np.testing.assert_array_equal(project_receptance(g, 0.0), g)
    np.testing.assert_array_equal(project_receptance(G, 0.0), G)
    np.testing.assert_array_equal(project_shapes(phi, 0.0), phi)
    arrays = {k: g for k in WHEEL_MATRICES + RAIL_MATRICES} | {"wheel_phi": phi, "wheel_f": np.arange(40.0)}
    out = project_greens(arrays, 0.0, 0.0)
    for k, a in arrays.items():
        assert out[k] is a                                         # not even copied
    assert out["contact_angle_wheel"] == 0.0 and out["contact_angle_rail"] == 0.0
    assert normal_preload(65e3, 0.0) == 65e3


def test_projection_is_the_tilted_components():
    rng = np.random.default_rng(4)
    g = rng.standard_normal((64, 2, 2))
    e2, e3 = tilted_directions(ANGLE)
    E = (e2, e3)
    want = np.array([[[E[i] @ g[k] @ E[j] for j in range(2)] for i in range(2)] for k in range(64)])
    np.testing.assert_allclose(project_receptance(g, ANGLE), want, rtol=0, atol=1e-14)
    R = rotation(ANGLE)
    np.testing.assert_allclose(R.T @ R, np.eye(2), atol=1e-15)
    F2, F3 = to_structure(1.0, 0.0, ANGLE)
    np.testing.assert_allclose([F2, F3], e2, atol=1e-15)
    F2, F3 = to_structure(0.0, 1.0, ANGLE)
    np.testing.assert_allclose([F2, F3], e3, atol=1e-15)
    N = normal_preload(65e3, ANGLE)
    assert abs(N * e3[1] - 65e3) < 1e-9                            # the normal force carries the vertical load
    with pytest.raises(ValueError):
        normal_preload(65e3, math.pi / 2)


@pytest.fixture(scope="module")
def c20():
    w = wheel_case(-0.032)
    n_t = choose_grid(w["f_hz"], w["zeta"], DT, decay_db=120)
    return w, n_t, frequency_grid(DT, n_t)


def test_projected_kernel_reproduces_the_receptance_along_the_tilted_directions(c20):
    """DFT of the projected band-limited kernel = receptance of the modal sum with the shapes
    along e2', e3', pointwise to 0.2 % up to 6.5 kHz (the unprojected kernel's accuracy, 0.1 %):
    G22', G33' entrywise, the 2x2 matrix in the Frobenius norm."""
    w, n_t, f = c20
    k = projected_kernel(w, n_t, f)
    G, Gt, Gd, band, err, err0 = (k[n] for n in ("G", "Gt", "Gd", "band", "err", "err0"))
    np.testing.assert_allclose(project_shapes(w["phi"], ANGLE), k["phi_t"], rtol=0, atol=1e-15)
    # entrywise where the entry is not near a zero of its own; as a matrix everywhere (a projected
    # cross term G23' passes through zero where the 0.1 % error of G22, G33 is large against it)
    for i, j in ((0, 0), (1, 1)):
        (e2k, _), (e65, f65) = pointwise_error(f, Gd[:, i, j], Gt[:, i, j])
        assert e2k < 2e-3 and e65 < 2e-3, (i, j, e2k, e65, f65)
    assert err.max() < 2e-3, err.max()
    np.testing.assert_allclose(err, err0, rtol=1e-6, atol=1e-12)   # the same error as unprojected
    # the projection mixes the directions: the tilted G22' is not G22
    assert np.median(np.abs(Gt[band, 0, 0] / G[band, 0, 0] - 1.0)) > 0.1
