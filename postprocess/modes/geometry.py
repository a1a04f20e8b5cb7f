"""Geometry of axisymmetric (Fourier-harmonic) wheel mode shapes in 3D: the
cross-section boundary swept around the axis, and the 3D displacement of a
harmonic-n mode on it.  Pure numpy (plus ``pyvista.PolyData`` as the surface
container); the renderer is ``postprocess.modes.shapes``.

A wheel mode is computed on the 2D cross-section (``r`` = radius, ``z`` =
axial coordinate) with a circumferential harmonic order ``n``. The 3D
displacement of a cross-section point at angle ``phi`` is::

    u_r   = U_r(r, z)   cos(n phi)
    u_z   = U_z(r, z)   cos(n phi)
    u_phi = U_phi(r, z) sin(n phi)        (n >= 1)

For ``n == 0`` all three components use the factor 1 (a torsional mode has
``U_r = U_z = 0`` and ``u_phi = U_phi``).

The 3D position of ``(r, z)`` at angle ``phi`` is
``(r cos phi, r sin phi, z)`` and the Cartesian displacement is
``u_x = u_r cos phi - u_phi sin phi``, ``u_y = u_r sin phi + u_phi cos phi``,
``u_Z = u_z``.
"""

from __future__ import annotations

import os
from typing import NamedTuple

# Must be set before pyvista / vtk are imported anywhere in the process.
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import numpy as np  # noqa: E402
import pyvista as pv  # noqa: E402

__all__ = [
    "SweptSurface",
    "boundary_edges_from_triangles",
    "sweep_surface",
    "displacement_vectors",
    "displaced",
]


class SweptSurface(NamedTuple):
    """Result of :func:`sweep_surface`.

    mesh
        ``pyvista.PolyData`` of the swept boundary (quads; triangles where a
        boundary edge touches the axis with one end). Its point data also
        carries ``"rz_index"`` and ``"phi"``.
    point_index
        ``(M,)`` int array: for each 3D vertex, the index of its
        cross-section point in ``points_rz``.
    phi
        ``(M,)`` float array: for each 3D vertex, its angle (rad).
    """

    mesh: pv.PolyData
    point_index: np.ndarray
    phi: np.ndarray


# ---------------------------------------------------------------------------
# Geometry
# ---------------------------------------------------------------------------


def boundary_edges_from_triangles(triangles) -> np.ndarray:
    """Boundary edges ``(E, 2)`` of a 2D triangle mesh.

    An edge is a boundary edge when it belongs to exactly one triangle. For
    6-node quadratic triangles only the three corner nodes (the first three
    columns) are used. Each edge keeps the orientation it has in its
    triangle, so for a consistently oriented mesh the boundary is
    consistently oriented too (counter-clockwise triangles -> outer boundary
    counter-clockwise).
    """
    tri = np.asarray(triangles)
    if tri.ndim != 2 or tri.shape[1] < 3:
        raise ValueError(f"triangles must have shape (T, >=3), got {tri.shape}")
    tri = tri[:, :3].astype(np.int64, copy=False)
    if tri.shape[0] == 0:
        return np.empty((0, 2), dtype=np.int64)
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    keys = np.sort(edges, axis=1)
    _, inverse, counts = np.unique(
        keys, axis=0, return_inverse=True, return_counts=True
    )
    inverse = np.asarray(inverse).reshape(-1)
    return edges[counts[inverse] == 1]


def sweep_surface(points_rz, boundary_edges, n_phi: int = 120) -> SweptSurface:
    """Sweep the cross-section boundary around the axis into a 3D surface.

    Parameters
    ----------
    points_rz
        ``(N, 2)`` cross-section coordinates ``(r, z)``.
    boundary_edges
        ``(E, 2)`` edges (indices into ``points_rz``) of the cross-section
        boundary, e.g. from :func:`boundary_edges_from_triangles`.
    n_phi
        Number of angular subdivisions (the seam is closed, no duplicated
        angle): vertex angles are ``2 pi k / n_phi``, ``k = 0..n_phi-1``.

    Edges lying on the axis (both ends at ``r == 0``) would give degenerate
    quads and are dropped; edges with one end on the axis give triangles.
    """
    pts = np.asarray(points_rz, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ValueError(f"points_rz must have shape (N, 2), got {pts.shape}")
    edges = np.asarray(boundary_edges, dtype=np.int64).reshape(-1, 2)
    n_phi = int(n_phi)
    if n_phi < 3:
        raise ValueError("n_phi must be >= 3")
    if edges.size and (edges.min() < 0 or edges.max() >= len(pts)):
        raise ValueError("boundary_edges index out of range of points_rz")

    r = pts[:, 0]
    rmax = float(np.max(np.abs(r))) if len(r) else 0.0
    on_axis = np.abs(r) <= 1e-12 * max(rmax, 1.0)

    keep = (edges[:, 0] != edges[:, 1]) & ~(on_axis[edges[:, 0]] & on_axis[edges[:, 1]])
    edges = edges[keep]
    if len(edges) == 0:
        raise ValueError("no boundary edge off the axis: nothing to sweep")

    used = np.unique(edges.ravel())
    n_b = len(used)
    local = np.full(len(pts), -1, dtype=np.int64)
    local[used] = np.arange(n_b)
    a = local[edges[:, 0]]
    b = local[edges[:, 1]]

    phis = 2.0 * np.pi * np.arange(n_phi) / n_phi
    point_index = np.tile(used, n_phi)
    phi = np.repeat(phis, n_b)
    rr = pts[point_index, 0]
    points = np.column_stack([rr * np.cos(phi), rr * np.sin(phi), pts[point_index, 1]])

    k = np.arange(n_phi)[:, None]  # (n_phi, 1)
    k1 = (k + 1) % n_phi
    a_ax = on_axis[edges[:, 0]]
    b_ax = on_axis[edges[:, 1]]
    quad = ~a_ax & ~b_ax

    cells = []
    if quad.any():
        aq, bq = a[quad][None, :], b[quad][None, :]
        c = np.stack(
            np.broadcast_arrays(k * n_b + aq, k * n_b + bq, k1 * n_b + bq, k1 * n_b + aq),
            axis=-1,
        ).reshape(-1, 4)
        cells.append(np.hstack([np.full((len(c), 1), 4), c]).ravel())
    if a_ax.any():  # a on the axis: (a_k, b_k, b_k+1)
        at, bt = a[a_ax][None, :], b[a_ax][None, :]
        c = np.stack(
            np.broadcast_arrays(k * n_b + at, k * n_b + bt, k1 * n_b + bt), axis=-1
        ).reshape(-1, 3)
        cells.append(np.hstack([np.full((len(c), 1), 3), c]).ravel())
    if b_ax.any():  # b on the axis: (a_k, b_k, a_k+1)
        at, bt = a[b_ax][None, :], b[b_ax][None, :]
        c = np.stack(
            np.broadcast_arrays(k * n_b + at, k * n_b + bt, k1 * n_b + at), axis=-1
        ).reshape(-1, 3)
        cells.append(np.hstack([np.full((len(c), 1), 3), c]).ravel())

    mesh = pv.PolyData(points, faces=np.concatenate(cells).astype(np.int64))
    mesh.point_data["rz_index"] = point_index
    mesh.point_data["phi"] = phi
    return SweptSurface(mesh, point_index, phi)


# ---------------------------------------------------------------------------
# Displacements
# ---------------------------------------------------------------------------


def _as_real_amplitude(U) -> np.ndarray:
    U = np.asarray(U)
    if U.ndim != 2 or U.shape[1] != 3:
        raise ValueError(f"U must have shape (N, 3) = (U_r, U_z, U_phi), got {U.shape}")
    if np.iscomplexobj(U):
        # Rotate the phase so that the largest entry is real, then drop the
        # imaginary part (standing-wave snapshot at maximum amplitude).
        flat = U.ravel()
        ref = flat[np.argmax(np.abs(flat))]
        U = np.real(U * (np.conj(ref) / abs(ref))) if ref != 0 else np.real(U)
    return np.asarray(U, dtype=float)


def _unpack(surface_info):
    if isinstance(surface_info, pv.PolyData):
        mesh = surface_info
        return mesh, np.asarray(mesh.point_data["rz_index"]), np.asarray(mesh.point_data["phi"])
    mesh, point_index, phi = surface_info
    return mesh, np.asarray(point_index), np.asarray(phi)


def displacement_vectors(surface_info, U, n: int, scale: float) -> np.ndarray:
    """Cartesian displacement ``(M, 3)`` of every vertex of a swept surface.

    ``U`` is ``(N, 3)`` with columns ``(U_r, U_z, U_phi)`` indexed like
    ``points_rz``; ``n`` is the harmonic order (``n == 0``: factor 1 for all
    components). The field is normalised so that the largest 3D displacement
    over the surface vertices equals ``scale`` (an all-zero field stays 0).
    """
    _, point_index, phi = _unpack(surface_info)
    U = _as_real_amplitude(U)
    n = int(n)
    if n < 0:
        raise ValueError("harmonic order n must be >= 0")
    if point_index.size and point_index.max() >= len(U):
        raise ValueError("U has fewer rows than the cross-section points")

    Ur, Uz, Up = (U[point_index, i] for i in range(3))
    if n == 0:
        c = np.ones_like(phi)
        s = np.ones_like(phi)
    else:
        c = np.cos(n * phi)
        s = np.sin(n * phi)
    ur, uz, up = Ur * c, Uz * c, Up * s
    cp, sp = np.cos(phi), np.sin(phi)
    u = np.column_stack([ur * cp - up * sp, ur * sp + up * cp, uz])

    umax = float(np.max(np.linalg.norm(u, axis=1))) if len(u) else 0.0
    if umax > 0.0:
        u *= float(scale) / umax
    else:
        u[:] = 0.0
    return u


def displaced(surface_info, U, n: int, scale: float) -> np.ndarray:
    """Displaced 3D vertex coordinates ``(M, 3)`` of a swept surface.

    See :func:`displacement_vectors` for the meaning of ``U``, ``n`` and
    ``scale`` (metres of the largest 3D displacement).
    """
    mesh, _, _ = _unpack(surface_info)
    return np.asarray(mesh.points, dtype=float) + displacement_vectors(surface_info, U, n, scale)
