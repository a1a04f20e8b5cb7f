"""The wheel's surface for a boundary-element check of the radiation stage (issue 28; thesis sec. 5.1):
the axisymmetric FE section's outline revolved into a triangle mesh, and the outward normal velocity
on it for harmonic n driven by a force at the contact point, from the same modal velocities the
radiation stage uses (``solvers.radiation.force_power``: q_r = i W H_r (Phi_r2 F2 + Phi_r3 F3) [4.54],
shapes (U_r, U_z, U_phi) per section node, U_r, U_z ~ cos(n (phi - phi_c)); U_phi is tangential to
the revolved surface and radiates nothing).  Pure functions on arrays; axis of revolution = z, the
section's coordinates (r, z).
"""
from __future__ import annotations

import numpy as np

from solvers.wheel.receptance import modal_frf


def outline(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Node indices of the section's boundary as one closed loop, counter-clockwise in the (r, z)
    plane (the edges of the triangles ``cells`` that belong to one triangle only, chained)."""
    e = np.sort(np.vstack([cells[:, [0, 1]], cells[:, [1, 2]], cells[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(e, axis=0, return_counts=True)
    edges = uniq[count == 1]
    nbr: dict[int, list[int]] = {}
    for a, b in edges:
        nbr.setdefault(int(a), []).append(int(b))
        nbr.setdefault(int(b), []).append(int(a))
    start = int(edges[0, 0])
    loop, prev, cur = [start], -1, start
    while True:
        nxt = [x for x in nbr[cur] if x != prev]
        nxt = nxt[0] if prev != -1 else nbr[cur][0]
        if nxt == start:
            break
        loop.append(nxt)
        prev, cur = cur, nxt
    if len(loop) != len(edges):
        raise ValueError(f"the section's boundary is not one loop ({len(loop)} of {len(edges)} edges)")
    p = points[loop]
    area = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
    return np.array(loop if area > 0 else loop[::-1])


def coarsen(points: np.ndarray, loop: np.ndarray, ds: float, corner_deg: float = 25.0) -> np.ndarray:
    """A subset of the loop's nodes: every corner (turning angle > ``corner_deg``) and otherwise a node
    whenever the arclength since the last kept node reaches ``ds`` (m); the walk starts at the sharpest
    corner."""
    p = points[loop]
    d_in = p - np.roll(p, 1, axis=0)
    d_out = np.roll(p, -1, axis=0) - p
    turn = np.abs(np.arctan2(d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0], np.sum(d_in * d_out, axis=1)))
    loop = np.roll(loop, -int(np.argmax(turn)))
    p = points[loop]
    d_in = p - np.roll(p, 1, axis=0)
    d_out = np.roll(p, -1, axis=0) - p
    ang = np.degrees(np.abs(np.arctan2(d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0],
                                       np.sum(d_in * d_out, axis=1))))
    keep, run = [], np.inf
    for i in range(len(loop)):
        run += np.hypot(*d_in[i]) if i else 0.0
        if ang[i] > corner_deg or run >= ds or i == 0:
            keep.append(i)
            run = 0.0
    return loop[np.array(keep)]


def outward_normals(rz: np.ndarray) -> np.ndarray:
    """Unit outward normals (n_r, n_z) at the vertices of a closed counter-clockwise polygon (the mean
    of the two adjacent edges' normals)."""
    d = np.roll(rz, -1, axis=0) - rz
    en = np.column_stack([d[:, 1], -d[:, 0]])
    en /= np.linalg.norm(en, axis=1)[:, None]
    vn = en + np.roll(en, 1, axis=0)
    return vn / np.linalg.norm(vn, axis=1)[:, None]


def revolve(rz: np.ndarray, n_phi: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(vertices (N n_phi, 3), triangles, phi per vertex) of the closed polygon ``rz`` (counter-
    clockwise, r > 0) revolved about the z axis, triangles ordered so that normals point out."""
    phi = 2 * np.pi * np.arange(n_phi) / n_phi
    N = len(rz)
    V = np.column_stack([np.outer(np.cos(phi), rz[:, 0]).ravel(), np.outer(np.sin(phi), rz[:, 0]).ravel(),
                         np.tile(rz[:, 1], n_phi)])
    idx = lambda j, i: (j % n_phi) * N + (i % N)                                      # noqa: E731
    T = []
    for j in range(n_phi):
        for i in range(N):
            a, b, c, d = idx(j, i), idx(j, i + 1), idx(j + 1, i + 1), idx(j + 1, i)
            T += [(a, b, c), (a, c, d)]
    T = np.array(T)
    # orientation: the first triangle's normal against the outline's outward normal there
    nr = outward_normals(rz)[0]
    t0 = T[0]
    n_tri = np.cross(V[t0[1]] - V[t0[0]], V[t0[2]] - V[t0[0]])
    if np.dot(n_tri, [nr[0], 0.0, nr[1]]) < 0:
        T = T[:, ::-1]
    return V, T, np.repeat(phi, N)


def normal_velocity(modal, shapes: np.ndarray, idx, nodes: np.ndarray, normals: np.ndarray, phi_v: np.ndarray,
                    phi_contact: float, f: float, F2: complex, F3: complex, n: int) -> np.ndarray:
    """Outward normal velocity amplitude (complex, per vertex) of harmonic ``n`` at frequency f for a
    force (F2, F3) at the contact point.  ``modal``: the wheel's modes (attributes f_r, modal_mass,
    zeta and phi (M, 2) = (U_z, U_r) at the contact point: a ``force_radiation.RadiationModel``);
    ``idx`` the modes of harmonic n; ``shapes`` (M, section nodes, 3) = (U_r, U_z, U_phi); ``nodes`` the
    outline's section nodes (one per outline vertex, the revolved mesh's vertex order), ``normals``
    (n_r, n_z) per outline vertex; ``phi_v`` each vertex's angle, ``phi_contact`` the contact's."""
    H = modal_frf(f, modal.f_r[idx], modal.modal_mass[idx], modal.zeta[idx])[0]
    q = 1j * 2 * np.pi * f * H * (modal.phi[idx, 0] * F2 + modal.phi[idx, 1] * F3)       # [4.54]
    sh = shapes[idx][:, nodes, :]                                                         # (k, N, 3)
    un = sh[:, :, 0] * normals[:, 0] + sh[:, :, 1] * normals[:, 1]                        # (k, N)
    section = q @ un                                                                      # (N,)
    n_phi = len(phi_v) // len(nodes)
    return np.tile(section, n_phi) * np.cos(n * (phi_v - phi_contact))
