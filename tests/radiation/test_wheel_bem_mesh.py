"""The wheel's BEM surface (``solvers.radiation.bem_surface``): the outline of a triangulated section, the
revolved mesh (closed, outward normals: its divergence-theorem volume is the exact volume of the
revolved polygon) and the normal velocity of a harmonic (its angular dependence and magnitude)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from solvers.radiation.bem_surface import coarsen, normal_velocity, outline, outward_normals, revolve


def _rectangle(r1=0.1, r2=0.4, z1=0.0, z2=0.05, nr=7, nz=3):
    r, z = np.meshgrid(np.linspace(r1, r2, nr), np.linspace(z1, z2, nz), indexing="ij")
    pts = np.column_stack([r.ravel(), z.ravel()])
    cells = []
    for i in range(nr - 1):
        for j in range(nz - 1):
            a, b, c, d = i * nz + j, (i + 1) * nz + j, (i + 1) * nz + j + 1, i * nz + j + 1
            cells += [(a, b, c), (a, c, d)]
    return pts, np.array(cells)


def test_outline_is_the_closed_counter_clockwise_boundary():
    pts, cells = _rectangle()
    loop = outline(pts, cells)
    assert len(loop) == 2 * (7 - 1) + 2 * (3 - 1)
    p = pts[loop]
    assert 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]) > 0
    kept = coarsen(pts, loop, ds=1.0)                 # only the four corners survive a coarse ds
    assert len(kept) == 4
    assert np.allclose(sorted(map(tuple, pts[kept])), [(0.1, 0.0), (0.1, 0.05), (0.4, 0.0), (0.4, 0.05)])
    n = outward_normals(pts[loop])
    mid_bottom = np.flatnonzero((np.abs(p[:, 1]) < 1e-12) & (p[:, 0] > 0.15) & (p[:, 0] < 0.35))
    assert np.allclose(n[mid_bottom], [0.0, -1.0])


def test_revolved_mesh_is_closed_with_outward_normals():
    pts, cells = _rectangle()
    rz = pts[coarsen(pts, outline(pts, cells), ds=1.0)]
    n_phi = 48
    V, T, phi = revolve(rz, n_phi)
    vol = np.sum(np.einsum("ij,ij->i", V[T[:, 0]], np.cross(V[T[:, 1]], V[T[:, 2]]))) / 6
    exact = n_phi / 2 * np.sin(2 * np.pi / n_phi) * (0.4**2 - 0.1**2) * 0.05     # regular n-gon rings
    assert abs(vol - exact) < 1e-12 * exact * 1e3
    e = np.sort(np.vstack([T[:, [0, 1]], T[:, [1, 2]], T[:, [2, 0]]]), axis=1)
    assert np.all(np.unique(e, axis=0, return_counts=True)[1] == 2)              # every edge shared twice
    assert len(phi) == len(V)


def test_normal_velocity_of_a_harmonic():
    pts, cells = _rectangle()
    loop = coarsen(pts, outline(pts, cells), ds=1.0)
    rz = pts[loop]
    V, T, phi = revolve(rz, 16)
    shapes = np.zeros((1, len(pts), 3))
    shapes[0, :, 1] = 1.0                              # a pure axial shape U_z = 1
    f_r, m_r, zeta = np.array([434.0]), np.array([1.0]), np.array([1e-3])
    phi_c = np.array([[1.0, 0.0]])                     # (U_z, U_r) at the contact point
    modal = SimpleNamespace(f_r=f_r, modal_mass=m_r, zeta=zeta, phi=phi_c)
    vn = normal_velocity(modal, shapes, np.array([0]), loop, outward_normals(rz), phi, np.pi, 434.0, 1.0, 0.0, 2)
    H = 1 / (m_r[0] * (2j * zeta[0] * (2 * np.pi * 434.0) ** 2))                  # at resonance
    amp = abs(1j * 2 * np.pi * 434.0 * H)
    nz = outward_normals(rz)[:, 1]
    expect = amp * np.tile(nz, 16) * np.cos(2 * (phi - np.pi))
    assert np.allclose(np.abs(vn), np.abs(expect), rtol=1e-9, atol=1e-12 * amp)
