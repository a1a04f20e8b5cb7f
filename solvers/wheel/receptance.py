"""Wheel receptances by modal superposition (SPEC 3.1, thesis [4.10], [4.11]).

Inputs are the arrays of the wheel's modal artifact (docs/reference.md, 'Artifacts'):
f_hz, n, m, cls, kind, modal_mass (kg, for shapes with max |U| = 1, the
circumferential integral included, so the n >= 1 cos twin enters [4.10] with
this mass directly), shapes (M, nodes, 3) = (U_r, U_z, U_phi), points (r, Z).

Directions and signs (SPEC 2).  The excitation point is the bottom of the wheel
(phi = 0) where, with u_r = U_r cos(n phi), u_z = U_z cos(n phi),
u_phi = U_phi sin(n phi), only the cos twin of each n >= 1 pair is excited by a
lateral or vertical force (the sin twin has no radial or axial motion at
phi = 0) and U_phi does not enter:

* direction 2 = lateral = axial U_z (Z grows toward the field side, as y^W);
* direction 3 = vertical, toward the ground = radial outward U_r at phi = 0.

So Phi_r2 = U_z, Phi_r3 = U_r at the contact point, with no sign changes.
Receptance arrays have shape (nf, 2, 2), index 0 = direction 2, 1 = direction 3,
G[:, i, j] = response in i per unit force in j: G[:, 0, 0] = G22,
G[:, 1, 1] = G33, G[:, 0, 1] = G23 = G[:, 1, 0] = G32 (m/N), the layout of
``solvers.rail.response.receptances`` and ``solvers.greens.kernels``.  These are the
receptances for a force ON the wheel; the time loop applies the wheel's -F.

Contact point.  ``contact_point`` interpolates the shapes at the exact surface
point (linear along the boundary edge that contains it: the nodal values of the
P1 boundary trace) and is what the stages should use (continuous in y^W, no
jump when the contact point crosses a node midway).  ``contact_node`` gives the
nearest surface node for comparison: at the C20 tread node spacing (~3 mm)
the levels differ by a median 0.2-0.5 dB in G33 and G23 and by up to 7-25 dB
near the antiresonances of G23 (docs/validation/50_greens.md).
"""
from __future__ import annotations

from typing import Callable, NamedTuple, Sequence

import numpy as np
from scipy.sparse.csgraph import minimum_spanning_tree

DIRS = (2, 3)


# ----------------------------------------------------------------------------------------------
# contact point on the section boundary
# ----------------------------------------------------------------------------------------------

class ContactPoint(NamedTuple):
    """A point on the running surface: shape values = w0 U[nodes[0]] + w1 U[nodes[1]]."""
    nodes: np.ndarray     # (2,) node indices of the boundary edge
    weights: np.ndarray   # (2,) linear weights (sum 1)
    r: float              # point on the boundary polyline (m)
    Z: float
    y: float              # requested y^W (m)
    offset: float         # distance from the requested surface point to the polyline (m)
    node: int             # nearest of the two nodes (by weight)


def surface_edges(points: np.ndarray, surface_nodes, cells: np.ndarray | None = None) -> np.ndarray:
    """Edges (E, 2) of the boundary polyline through ``surface_nodes``.

    With ``cells`` (triangles) the boundary edges of the mesh joining two surface
    nodes; without, the minimum spanning tree of the nodes, which is the polyline
    whenever the node spacing is smaller than the distance between non-adjacent
    parts of the curve (true for a tread + flange sampled every few mm).  Checks
    that the result is a simple path."""
    nodes = np.unique(np.asarray(surface_nodes, dtype=np.int64))
    if len(nodes) < 2:
        raise ValueError("need at least two surface nodes")
    if cells is not None:
        c = np.asarray(cells, dtype=np.int64)[:, :3]
        e = np.sort(np.concatenate([c[:, [0, 1]], c[:, [1, 2]], c[:, [2, 0]]]), axis=1)
        uniq, count = np.unique(e, axis=0, return_counts=True)
        bnd = uniq[count == 1]
        on = np.isin(bnd, nodes).all(axis=1)
        edges = bnd[on]
    else:
        P = points[nodes]
        D = np.sqrt(((P[:, None, :] - P[None, :, :]) ** 2).sum(-1))
        T = minimum_spanning_tree(D).tocoo()
        edges = np.column_stack([nodes[T.row], nodes[T.col]])
    deg = np.bincount(edges.ravel(), minlength=points.shape[0])[nodes]
    if len(edges) != len(nodes) - 1 or deg.max() > 2:
        raise ValueError("the surface nodes do not form one simple polyline "
                         "(pass cells=, or the nodes of one connected running surface)")
    return edges


def contact_point(points: np.ndarray, surface_nodes, y: float, z_rc: float,
                  r_of_y: Callable | None = None, cells: np.ndarray | None = None) -> ContactPoint:
    """The contact point at lateral position y^W (m, from the rolling circle, + to
    the field side) on the running surface (nodes of the tread and flange
    boundaries, e.g. ``boundary_tread`` and ``boundary_flange``).

    With ``r_of_y`` (the running-surface radius r(y^W), e.g.
    ``geometry.wheel.tread_radius`` bound to the wheel parameters) the exact
    surface point (r_of_y(y), z_rc + y) is projected on the nearest boundary edge;
    without, the boundary is intersected with Z = z_rc + y and the outermost
    intersection (largest r, the surface that touches the rail at the bottom of
    the wheel) is taken.  Returns the edge's nodes and linear weights."""
    points = np.asarray(points, float)
    edges = surface_edges(points, surface_nodes, cells)
    A, B = points[edges[:, 0]], points[edges[:, 1]]
    Zt = z_rc + y
    if r_of_y is not None:
        X = np.array([float(r_of_y(y)), Zt])
        d = B - A
        t = np.clip(((X - A) * d).sum(1) / (d * d).sum(1), 0.0, 1.0)
        foot = A + t[:, None] * d
        dist = np.sqrt(((foot - X) ** 2).sum(1))
        e = int(np.argmin(dist))
        te, off = float(t[e]), float(dist[e])
    else:
        dz = B[:, 1] - A[:, 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (Zt - A[:, 1]) / dz
        hit = (dz != 0) & (t >= 0) & (t <= 1)
        if not hit.any():
            raise ValueError(f"y^W = {y} m (Z = {Zt} m) is outside the running surface "
                             f"(Z from {points[edges, 1].min():.4f} to {points[edges, 1].max():.4f} m)")
        r_hit = np.where(hit, A[:, 0] + t * (B[:, 0] - A[:, 0]), -np.inf)
        e = int(np.argmax(r_hit))
        te, off = float(t[e]), 0.0
    nodes = edges[e].copy()
    w = np.array([1.0 - te, te])
    P = (1 - te) * A[e] + te * B[e]
    return ContactPoint(nodes, w, float(P[0]), float(P[1]), float(y), off, int(nodes[np.argmax(w)]))


def contact_node(points: np.ndarray, tread_nodes, r_of_y: Callable | None, y: float, z_rc: float,
                 cells: np.ndarray | None = None) -> int:
    """The surface node nearest to the contact point at y^W (see ``contact_point``;
    ``r_of_y`` may be None).  Prefer ``contact_point`` (interpolated values)."""
    cp = contact_point(points, tread_nodes, y, z_rc, r_of_y, cells)
    nodes = np.unique(np.asarray(tread_nodes, dtype=np.int64))
    target = np.array([float(r_of_y(y)), z_rc + y]) if r_of_y is not None else np.array([cp.r, cp.Z])
    return int(nodes[np.argmin(((np.asarray(points)[nodes] - target) ** 2).sum(1))])


def shape_at(shapes: np.ndarray, where) -> np.ndarray:
    """(M, 3) = (U_r, U_z, U_phi) of every mode at a node (int) or a ContactPoint."""
    shapes = np.asarray(shapes)
    if isinstance(where, ContactPoint):
        return where.weights[0] * shapes[:, where.nodes[0]] + where.weights[1] * shapes[:, where.nodes[1]]
    return shapes[:, int(where)].copy()


def contact_shape(shapes: np.ndarray, where) -> np.ndarray:
    """(M, 2) = (Phi_2, Phi_3) = (U_z, U_r) of every mode at the contact point
    (the cos twin at phi = 0, see the module notes)."""
    U = shape_at(shapes, where)
    return np.column_stack([U[:, 1], U[:, 0]])


# ----------------------------------------------------------------------------------------------
# damping
# ----------------------------------------------------------------------------------------------

def modal_damping(n, m, cls, kind, zeta_suspension, overrides: dict | None = None) -> np.ndarray:
    """Modal damping ratios [4.11], the one definition of the rule (the Green's
    functions, the radiation and the studies use it).

    Flexible modes: 1e-3 (n = 0), 1e-2 (n = 1), 1e-4 (n >= 2), the free wheel's
    values; the (1, 0, r) mode -- one nodal diameter and *no* nodal circle --
    1.0, because the axle damps it (thesis 4.2.1 after Thompson); an n = 1
    radial mode with nodal circles keeps 1e-2.  The rigid half-wheelset modes
    (kind != 'flexible': bounce, roll, lateral on the primary suspension) are not
    free-wheel modes: they take the suspension's damping ratio
    ``zeta_suspension`` (from the suspension's c and k), and a rigid mode without
    a finite one is an error.  ``overrides``: {mode index: zeta} applied last
    (damping study, single-mode validation)."""
    n = np.asarray(n)
    m = np.asarray(m)
    cls = np.asarray(cls).astype(str)
    kind = np.asarray(kind).astype(str)
    zs = np.asarray(zeta_suspension, float)
    z = np.where(n == 0, 1e-3, np.where(n == 1, 1e-2, 1e-4)).astype(float)
    z[(n == 1) & (m == 0) & (cls == "r") & (kind == "flexible")] = 1.0
    rigid = kind != "flexible"
    if np.any(~np.isfinite(zs[rigid])):
        raise ValueError("rigid-body modes need a finite zeta_suspension")
    z[rigid] = zs[rigid]
    for i, val in (overrides or {}).items():
        if not 0 <= int(i) < len(z):
            raise IndexError(f"damping override for mode {i}: only {len(z)} modes")
        if not val >= 0:
            raise ValueError(f"damping override for mode {i}: zeta = {val} must be >= 0")
        z[int(i)] = float(val)
    return z


# ----------------------------------------------------------------------------------------------
# receptances
# ----------------------------------------------------------------------------------------------

def modal_frf(f_hz, f_r, modal_mass, zeta) -> np.ndarray:
    """H_r(f) = 1 / (m_r (w_r^2 - W^2 + 2 i zeta_r w_r W)), (nf, M) complex (m/N per
    unit modal participation) -- the modal factor of [4.10]."""
    W = 2 * np.pi * np.atleast_1d(np.asarray(f_hz, float))[:, None]
    w = 2 * np.pi * np.asarray(f_r, float)[None, :]
    return 1.0 / (np.asarray(modal_mass, float)[None, :] * (w * w - W * W + 2j * np.asarray(zeta, float)[None, :] * w * W))


def _select(n, harmonics):
    n = np.asarray(n)
    if harmonics is None:
        return np.ones(len(n), bool)
    return np.isin(n, np.atleast_1d(np.asarray(harmonics)))


def _phi(at, shapes, M):
    if isinstance(at, ContactPoint) or np.ndim(at) == 0:
        if shapes is None:
            raise ValueError("a node index or ContactPoint needs shapes=")
        return contact_shape(shapes, at)
    phi = np.asarray(at, float)
    if phi.shape != (M, 2):
        raise ValueError(f"contact values must be (M, 2) = (Phi_2, Phi_3), got {phi.shape}")
    return phi


def _modal_sum(f_hz, f_r, modal_mass, zeta, left, right, chunk=8192):
    """sum_r H_r(f) left[r, a] right[r, b] -> (nf, A, B)."""
    f_hz = np.atleast_1d(np.asarray(f_hz, float))
    L = np.asarray(left, float)
    R = np.asarray(right, float)
    P = (L[:, :, None] * R[:, None, :]).reshape(L.shape[0], -1).astype(complex)
    out = np.empty((len(f_hz), P.shape[1]), complex)
    for a in range(0, len(f_hz), chunk):
        out[a:a + chunk] = modal_frf(f_hz[a:a + chunk], f_r, modal_mass, zeta) @ P
    return out.reshape(len(f_hz), L.shape[1], R.shape[1])


def wheel_receptance(f_hz, f_r, modal_mass, n, at, zeta, harmonics: Sequence[int] | None = None,
                     shapes: np.ndarray | None = None) -> np.ndarray:
    """Point receptance at the contact point [4.10], (nf, 2, 2) complex m/N:
    [:, 0, 0] = G22, [:, 1, 1] = G33, [:, 0, 1] = [:, 1, 0] = G23 = G32.

    f_hz (nf,), f_r / modal_mass / n / zeta (M,) from the modal artifact and
    ``modal_damping``; ``at``: the contact values (M, 2) = (Phi_2, Phi_3) from
    ``contact_shape``, or a node index / ContactPoint together with ``shapes``.
    ``harmonics``: keep only the modes with these n (per-harmonic split)."""
    f_r = np.asarray(f_r, float)
    phi = _phi(at, shapes, len(f_r))
    sel = _select(n, harmonics)
    return _modal_sum(f_hz, f_r[sel], np.asarray(modal_mass, float)[sel], np.asarray(zeta, float)[sel],
                      phi[sel], phi[sel])


def receptance_by_harmonic(f_hz, f_r, modal_mass, n, at, zeta, shapes=None) -> dict:
    """{n: (nf, 2, 2)}: the contribution of each harmonic n to ``wheel_receptance``
    (they sum to it)."""
    return {int(k): wheel_receptance(f_hz, f_r, modal_mass, n, at, zeta, harmonics=[k], shapes=shapes)
            for k in np.unique(n)}


def transfer_receptance(f_hz, f_r, modal_mass, n, at, zeta, response: np.ndarray,
                        harmonics: Sequence[int] | None = None, shapes: np.ndarray | None = None) -> np.ndarray:
    """Transfer receptance from a force at the contact point to other points:
    (nf, P, 3, 2) complex m/N, [f, p, c, j] = amplitude of component c
    (0 = U_r, 1 = U_z, 2 = U_phi) at point p per unit force in direction j
    (0 = F2, 1 = F3).  The response field of harmonic n is
    u_r = A_r cos(n phi), u_z = A_z cos(n phi), u_phi = A_phi sin(n phi) (phi from
    the contact point), so with ``harmonics=[n]`` these are the per-harmonic
    amplitudes the radiation model needs (velocity = i 2 pi f times them).
    ``response``: (M, P, 3) mode shapes at the response points (e.g.
    ``shapes[:, nodes]``).  Memory is nf * P * 6 complex numbers."""
    f_r = np.asarray(f_r, float)
    phi = _phi(at, shapes, len(f_r))
    U = np.asarray(response, float)
    if U.ndim != 3 or U.shape[0] != len(f_r) or U.shape[2] != 3:
        raise ValueError(f"response must be (M, P, 3), got {U.shape}")
    sel = _select(n, harmonics)
    P = U.shape[1]
    out = _modal_sum(f_hz, f_r[sel], np.asarray(modal_mass, float)[sel], np.asarray(zeta, float)[sel],
                     U[sel].reshape(sel.sum(), P * 3), phi[sel])
    return out.reshape(len(np.atleast_1d(f_hz)), P, 3, 2)
