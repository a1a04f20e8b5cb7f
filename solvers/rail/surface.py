"""Rail receptances at any point of the head's running surface (SPEC 3.2, 3.4).

The wave sum of ``solvers.rail.response`` gives the receptance between two dofs p, q of the
section as G_pq(x) = -i sum_n phi_n,p phi_n,q exp(-i k_n |x|) / D_n (residues of the wavenumber
integral; the section matrices are complex symmetric, so the left and right wave shapes are the
same).  With psi_n = phi_n / sqrt(D_n) stored at every node of the running surface (both families,
the static near field of the load subtracted as extra waves, directions 2 lateral and 3 downward,
the half-model factor 1/2 folded in), the receptance at a point y on a boundary edge of the mesh is
the quadratic form of the edge's quadratic Lagrange shape functions N_a(y) (the consistent point
load f = sum_a N_a e_a and the response u(y) = sum_a N_a u_a of the P2 section): psi(y) =
sum_a N_a psi_a, a_n,ij(y) = -i psi_n,i(y) psi_n,j(y).  At a mesh node this is the node's
receptance; between nodes it is the FE model's own response to a point load there.

The reduced families' basis holds static attachment modes for the loads they were built with;
``surface_model_points`` gives the loads that make the basis represent a load at any node of the
running surface: every vertex of it (tests/rail/test_surface.py measures the agreement with the
direct construction at a loaded point, docs/validation/53_any_rail_point.md).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from solvers.rail.reduced import waves

DIRS = np.array([1.0, -1.0])  # section (y, z up) -> SPEC directions (2 lateral, 3 downward)


def surface_nodes(nodes: np.ndarray, polyline: np.ndarray, y_max: float, tol: float = 1e-9):
    """The mesh nodes (indices into ``nodes`` (N, 2)) on the running-surface ``polyline`` (P, 2:
    ``geometry.rail.running_surface``) with 0 <= y <= y_max, sorted by y, and whether each is an
    element vertex (P2 edges: vertex, midside, vertex, ...; checked)."""
    P = np.asarray(polyline, float)
    a, b = P[:-1], P[1:]
    ab = b - a
    t = np.clip(np.einsum("nsk,sk->ns", nodes[:, None, :] - a[None], ab) / np.einsum("sk,sk->s", ab, ab), 0, 1)
    d = np.linalg.norm(nodes[:, None, :] - (a[None] + t[..., None] * ab[None]), axis=2).min(axis=1)
    idx = np.flatnonzero((d < tol) & (nodes[:, 0] >= -tol) & (nodes[:, 0] <= y_max + tol))
    idx = idx[np.argsort(nodes[idx, 0])]
    if len(idx) < 3 or len(idx) % 2 == 0:
        raise ValueError(f"running surface: {len(idx)} nodes, expected vertex, midside, ..., vertex")
    xy = nodes[idx]
    mid = 0.5 * (xy[:-2:2] + xy[2::2])
    if np.abs(mid - xy[1:-1:2]).max() > 1e-9:
        raise ValueError("running surface: the nodes are not the vertices and midside nodes of P2 edges")
    vertex = np.zeros(len(idx), bool)
    vertex[::2] = True
    return idx, vertex


def surface_rows(fam, BY: np.ndarray, node_idx: np.ndarray) -> np.ndarray:
    """Rows of the family's Y-basis ``BY`` at the (y, z) dofs of the nodes: (2 n, mY), zero
    where the family constrains the dof (the symmetry line)."""
    Yd = fam.dof_comp != 0
    pos = np.full(len(fam.dof_comp), -1)
    pos[Yd] = np.arange(int(Yd.sum()))
    rows = np.zeros((2 * len(node_idx), BY.shape[1]))
    for i, nd in enumerate(node_idx):
        for c in (1, 2):
            d = np.flatnonzero((fam.dof_node == nd) & (fam.dof_comp == c))
            if len(d) == 1:
                rows[2 * i + c - 1] = BY[pos[d[0]]]
    return rows


def family_shapes(rf, rows: np.ndarray, omegas, k_local: float | None = 20.0):
    """k (nf, m + ne) and psi (nf, m + ne, n, 2) of one reduced family at the surface rows (SPEC
    directions, the half-model 1/2 folded in); with k_local, the static near field (the waves with
    |k| > k_local at w = 0) appended with shapes i psi, i.e. negated amplitudes (as
    ``rail_reduced.wave_amplitudes``)."""
    n = rows.shape[0] // 2
    rf = replace(rf, outputs=rows, out_names=list(range(len(rows))))  # the wave shapes at the rows

    def shapes(w):
        k, _, s, D = waves(rf, w)
        psi = (s / np.sqrt(D)[:, None]).reshape(len(k), n, 2) * (DIRS * np.sqrt(0.5))
        return k, psi

    ek, epsi = np.zeros(0, complex), np.zeros((0, n, 2), complex)
    if k_local is not None:
        k0, p0 = shapes(0.0)
        hi = np.abs(k0) > k_local
        ek, epsi = k0[hi], 1j * p0[hi]
    m = rf.size
    K = np.empty((len(omegas), m + len(ek)), complex)
    S = np.empty((len(omegas), m + len(ek), n, 2), complex)
    for j, w in enumerate(omegas):
        K[j, :m], S[j, :m] = shapes(w)
        K[j, m:], S[j, m:] = ek, epsi
    return K, S


def point_weights(y_nodes: np.ndarray, vertex: np.ndarray, y: float) -> tuple[np.ndarray, np.ndarray]:
    """The three nodes (indices into the sorted surface nodes) of the P2 edge holding lateral
    position |y| and their quadratic Lagrange weights there (a node itself: weight 1)."""
    y = abs(float(y))
    v = np.flatnonzero(vertex)
    if not y_nodes[v[0]] - 1e-12 <= y <= y_nodes[v[-1]] + 1e-12:
        raise ValueError(f"|y| = {1e3 * y:.3f} mm is off the running surface "
                         f"({1e3 * y_nodes[v[0]]:.1f} .. {1e3 * y_nodes[v[-1]]:.1f} mm)")
    e = int(np.clip(np.searchsorted(y_nodes[v], y) - 1, 0, len(v) - 2))
    i0, im, i1 = v[e], v[e] + 1, v[e + 1]
    xi = (y - y_nodes[i0]) / (y_nodes[i1] - y_nodes[i0])
    N = np.array([(1 - xi) * (1 - 2 * xi), 4 * xi * (1 - xi), xi * (2 * xi - 1)])
    return np.array([i0, im, i1]), N


def point_amplitudes(psi: np.ndarray, idx: np.ndarray, N: np.ndarray) -> np.ndarray:
    """a (nf, M, 2, 2) = -i psi(y)_i psi(y)_j with psi(y) = sum_a N_a psi_a: the wave-table
    amplitudes (``rail_response.wave_table``'s ``a`` of one point, y >= 0)."""
    p = np.einsum("fman,a->fmn", psi[:, :, idx], N)
    return -1j * p[..., :, None] * p[..., None, :]


def surface_polyline(poly: np.ndarray) -> np.ndarray:
    """The running-surface polyline (``geometry.rail.running_surface``) up to the head's widest
    point (where y stops increasing)."""
    return np.asarray(poly, float)[: int(np.argmax(poly[:, 0])) + 1]


def load_points(poly: np.ndarray, spacing: float) -> np.ndarray:
    """|y| of the polyline's vertices nearest to a uniform grid of ``spacing`` over its extent
    (both ends included): the loads whose attachment modes enter the reduced basis."""
    ys = np.asarray(poly, float)[:, 0]
    targets = np.append(np.arange(0.0, ys[-1], spacing), ys[-1])
    return np.unique(ys[[int(np.argmin(np.abs(ys - t))) for t in targets]])
