"""The boundary-element solution of a body of revolution vibrating in one circumferential harmonic, by
the rotational symmetry of its mesh (the radiation check of issue 28 for the wheel's higher modes).

A mesh made of ``n_phi`` rotated copies of one ring of vertices (``solvers.radiation.bem_surface.revolve``:
vertex (j, i) = node i of ring j, angle phi_j = 2 pi j / n_phi) is invariant under the rotation by
2 pi / n_phi, so the Galerkin matrices of any rotation-invariant operator are block-circulant:
A[(j, i), (k, l)] = A[(0, i), (k - j mod n_phi, l)].  A field x[(k, l)] = x_l e^{i m phi_k} is then
mapped to (A x)[(j, i)] = e^{i m phi_j} (A_m x)_i with the ring matrix
A_m[i, l] = sum_k A[(0, i), (k, l)] e^{i m phi_k}, so the 3-D Burton-Miller problem of ``solvers.radiation.bem``
splits exactly (to rounding) into one (ring nodes)-sized problem per harmonic m.  Only the first block
row is assembled, by bempp-cl itself (test functions: the P1 hat functions of ring 0), so the cost
is 1/n_phi of the full dense assembly and the same discrete solution as ``solvers.radiation.bem.radiated_power``
on the same mesh (checked in tests/radiation/test_bem_revolution.py).  A velocity field of harmonic n
(cos n (phi - phi_c) times a profile along the ring) is the sum of its m = +n and m = -n parts; their
cross terms in the power sum to zero over the rings.

A rigid ground breaks the symmetry: ``ground_power`` uses the image body (``solvers.radiation.bem.mirrored``)
and the mirror symmetry of the pair (the image's pressure is the mirror of the body's), so the
unknowns are the body's only: (A_11 + A_12) p = -(B_11 + B_12) q with A_11 the body's own (block-
circulant, from its first block row) and A_12 the image's action on the body (assembled by bempp,
no singular integrals; image vertices in the body's order).
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from solvers.radiation.bem import _api, _weak_forms, grid_from_arrays, mirrored


def _ring_test_space(grid, n_nodes: int):
    """P1 test space of the hat functions of ring 0's vertices (0 .. n_nodes - 1): the triangles
    touching ring 0, vertices on the support's boundary (rings -1 and 1) excluded."""
    el = grid.elements                                                   # (3, T)
    support = np.flatnonzero(np.any(el < n_nodes, axis=0))
    test = _api().function_space(grid, "P", 1, support_elements=support, include_boundary_dofs=False)
    if test.global_dof_count != n_nodes:
        raise ValueError(f"ring 0 has {n_nodes} vertices but its test space {test.global_dof_count} dofs")
    return test


def harmonic_parts(vn: np.ndarray, n_nodes: int, n: int, tol: float = 1e-8) -> dict[int, np.ndarray]:
    """The ring profiles x_m (m = +n, -n; m = 0 if n = 0) of a per-vertex field of harmonic n,
    x[(j, l)] = sum_m x_m[l] e^{i m phi_j}; ValueError if the field has other harmonics."""
    x = np.asarray(vn, complex).reshape(-1, n_nodes)                    # (n_phi, n_nodes)
    n_phi = len(x)
    if n_phi <= 2 * n:
        raise ValueError(f"{n_phi} rings cannot carry harmonic {n}")
    phi = 2 * np.pi * np.arange(n_phi) / n_phi
    ms = (0,) if n == 0 else (n, -n)
    parts = {m: np.exp(-1j * m * phi) @ x / n_phi for m in ms}
    rest = x - sum(np.outer(np.exp(1j * m * phi), parts[m]) for m in ms)
    if np.linalg.norm(rest) > tol * max(np.linalg.norm(x), 1e-300):
        raise ValueError(f"the velocity field is not of harmonic {n} alone")
    return parts


def _ring_matrix(row: np.ndarray, n_nodes: int, m: int) -> np.ndarray:
    """A_m[i, l] = sum_k row[i, (k, l)] e^{i m phi_k} of a first block row (n_nodes, n_phi n_nodes)."""
    r = np.asarray(row).reshape(n_nodes, -1, n_nodes)
    phi = 2 * np.pi * np.arange(r.shape[1]) / r.shape[1]
    return np.einsum("ikl,k->il", r, np.exp(1j * m * phi))


def first_block_row(vertices: np.ndarray, triangles: np.ndarray, n_nodes: int, k: float):
    """Ring 0's rows (n_nodes, N) of the Burton-Miller matrices A, B and the mass matrix M (dense) of
    the mesh (``solvers.radiation.bem``'s equation, bempp-cl's assembly)."""
    grid = grid_from_arrays(vertices, triangles)
    A, B, M = _weak_forms(grid, k, _ring_test_space(grid, n_nodes))
    M = M.toarray() if hasattr(M, "toarray") else np.asarray(M)
    return A, B, M


def revolution_power(vertices, triangles, n_nodes: int, k: float, vns, n: int, rho: float = 1.21,
                     c: float = 343.0, rows=None) -> list[float]:
    """Radiated power [W] (free field) of each outward normal velocity field of ``vns`` (per vertex,
    harmonic n) on a mesh of rotated rings of ``n_nodes`` vertices; ``rows``: ``first_block_row``'s
    output if already assembled."""
    A, B, M = rows if rows is not None else first_block_row(vertices, triangles, n_nodes, k)
    n_phi = len(vertices) // n_nodes
    ms = (0,) if n == 0 else (n, -n)
    if n and (2 * n) % n_phi == 0:
        raise ValueError(f"{n_phi} rings alias harmonics {n} and {-n}")
    mats = {m: (lu_factor(_ring_matrix(A, n_nodes, m)), _ring_matrix(B, n_nodes, m), _ring_matrix(M, n_nodes, m))
            for m in ms}
    out = []
    for vn in vns:
        parts = harmonic_parts(vn, n_nodes, n)
        W = 0.0
        for m, x in parts.items():
            lu, Bm, Mm = mats[m]
            p = lu_solve(lu, -(Bm @ (1j * k * c * rho * x)))
            W += 0.5 * n_phi * float(np.real(np.conj(x) @ (Mm @ p)))
        out.append(W)
    return out


def _cross_ops(vertices, triangles, k: float, axis: int, plane: float, order: int | None):
    """The image body's (mirror in x_axis = plane) operators on the body (Helmholtz double layer,
    hypersingular, single layer, adjoint double layer, not yet assembled): test functions on the body,
    trial functions on the image (vertex order as the body's; two grids, so bempp assembles only
    regular integrals); ``order``: the regular quadrature order (bempp's default 4: 6 points per
    triangle) of these non-singular integrals."""
    api = _api()
    par = api.DefaultParameters()
    if order is not None:
        par.quadrature.regular = int(order)
    Vm, Tm = mirrored(vertices, triangles, axis, plane)
    nv = len(vertices)
    body = api.function_space(grid_from_arrays(vertices, triangles), "P", 1)
    image = api.function_space(grid_from_arrays(Vm[nv:], Tm[len(triangles):] - nv), "P", 1)
    hz = api.operators.boundary.helmholtz
    return tuple(op(image, body, body, k, par) for op in
                 (hz.double_layer, hz.hypersingular, hz.single_layer, hz.adjoint_double_layer))


def cross_block(vertices, triangles, k: float, axis: int, plane: float, order: int | None = None):
    """A_12 and B_12 (N, N) of the image's action on the body (``_cross_ops``)."""
    K, W, V, Kp = _cross_ops(vertices, triangles, k, axis, plane, order)
    eta = 1j / k
    return (-np.asarray(K.weak_form().A) + eta * np.asarray(W.weak_form().A),
            np.asarray(V.weak_form().A) + eta * np.asarray(Kp.weak_form().A))


def add_circulant(full: np.ndarray, row: np.ndarray, n_nodes: int) -> np.ndarray:
    """full += the block-circulant matrix of first block row ``row`` (in place; returns ``full``)."""
    r = np.asarray(row).reshape(n_nodes, -1, n_nodes)
    n_phi = r.shape[1]
    view = full.reshape(n_phi, n_nodes, n_phi, n_nodes)
    for j in range(n_phi):
        view[j] += r[:, (np.arange(n_phi) - j) % n_phi, :]
    return full


def circulant_matvec(row: np.ndarray, n_nodes: int, x: np.ndarray) -> np.ndarray:
    """The block-circulant matrix of first block row ``row`` times x, without forming it."""
    r = np.asarray(row)
    xr = np.asarray(x).reshape(-1, n_nodes)
    return np.concatenate([r @ np.roll(xr, -j, axis=0).ravel() for j in range(len(xr))])


def ground_power(vertices, triangles, n_nodes: int, k: float, vns, axis: int, plane: float, rho: float = 1.21,
                 c: float = 343.0, rows=None, order: int | None = None) -> list[float]:
    """Radiated power [W] into the half space x_axis > plane (rigid plane) of each velocity field of
    ``vns`` (per vertex): the body and its image, by the pair's mirror symmetry (module docstring);
    ``rows``: ``first_block_row``'s output if already assembled.  Memory: two dense N x N matrices (the
    left-hand side, factored in place, and one operator at a time of the right-hand side)."""
    A, B, _ = rows if rows is not None else first_block_row(vertices, triangles, n_nodes, k)
    K, W, V, Kp = _cross_ops(vertices, triangles, k, axis, plane, order)
    eta = 1j / k
    lhs = np.asarray(K.weak_form().A)
    del K
    np.negative(lhs, out=lhs)
    m = np.asarray(W.weak_form().A)
    del W
    m *= eta
    lhs += m
    del m
    add_circulant(lhs, A, n_nodes)
    lu = lu_factor(lhs.T, overwrite_a=True, check_finite=False)        # F-ordered: factored in place
    del lhs
    qs = [1j * k * c * rho * np.asarray(vn, complex) for vn in vns]
    rhs = [circulant_matvec(B, n_nodes, q) for q in qs]
    for op, w in ((V, 1.0), (Kp, eta)):
        m = np.asarray(op.weak_form().A)
        rhs = [r + w * (m @ q) for r, q in zip(rhs, qs)]
        del m
    api = _api()
    space = api.function_space(grid_from_arrays(vertices, triangles), "P", 1)
    M = api.operators.boundary.sparse.identity(space, space, space).weak_form().A
    out = []
    for vn, r in zip(vns, rhs):
        p = lu_solve(lu, -r, trans=1, check_finite=False)
        out.append(0.5 * float(np.real(np.conj(np.asarray(vn, complex)) @ (M @ p))))
    return out
