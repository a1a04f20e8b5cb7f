"""Automatic labelling of wheel modes as (n, m, class), SPEC 3.1.

* class: from the rigid motion of the tyre cross-section (ring theory):
  'a' (axial) when its out-of-plane motion (axial translation and rotation
  about the circumferential axis) outweighs its in-plane motion; otherwise
  'r' (radial: inextensional ring bending, U_phi = -U_r / n, or breathing for
  n = 0) or 'c' (circumferential: extensional/shear family, U_phi ~ n U_r,
  or torsion for n = 0).
* m: nodal circles, counted as sign changes of the dominant displacement
  component along the web centreline from the hub to the tread, ignoring
  samples below 3 % (axial) or 30 % (in-plane) of the largest (a clamped hub
  would otherwise add spurious zeros), then made consistent within each
  (n, class) family by frequency order.
"""
from __future__ import annotations

import numpy as np


def nodal_weights(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Lumped r dA weight of each node (area/3 of each triangle times r)."""
    p = points[cells]
    area = 0.5 * np.abs((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                        - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    w = np.zeros(len(points))
    np.add.at(w, cells.ravel(), np.repeat(area / 3, 3))
    return w * points[:, 0]


def tyre_rigid_motion(U: np.ndarray, points: np.ndarray, weights: np.ndarray) -> dict:
    """Least-squares rigid motion of the tyre cross-section (the ring): the
    translations T_r, T_z, T_phi and the rotation theta about the
    circumferential axis through the section centroid, U_r = T_r - theta
    (Z - Z_c), U_z = T_z + theta (r - r_c), U_phi = T_phi (weights r dA).
    Returns those and the kinetic-energy-like measures of the out-of-plane
    (T_z, theta) and in-plane (T_r, T_phi) ring motion."""
    w = weights / weights.sum()
    rc, zc = w @ points[:, 0], w @ points[:, 1]
    dr, dz = points[:, 0] - rc, points[:, 1] - zc
    J = w @ (dr**2 + dz**2)  # polar moment per unit mass
    # about the centroid the normal equations decouple
    Tr, Tz, Tp = w @ U[:, 0], w @ U[:, 1], w @ U[:, 2]
    th = w @ (dr * U[:, 1] - dz * U[:, 0]) / J
    return {"T_r": Tr, "T_z": Tz, "T_phi": Tp, "theta": th,
            "out_of_plane": Tz**2 + J * th**2, "in_plane": Tr**2 + Tp**2}


def mode_class(U: np.ndarray, n: int, weights: np.ndarray, tyre: np.ndarray, points: np.ndarray) -> str:
    """'a', 'r' or 'c' from the mode shape U (nodes, 3) of harmonic n.

    Ring theory separates the motion of the tyre (the ring that carries the
    web) into out-of-plane (axial translation and rotation of its cross-section
    about the circumferential axis) and in-plane (radial and circumferential)
    families.  Axial modes are the out-of-plane family: the rim rocks with the
    web bending, so the tyre's rotation counts as axial motion even though it
    moves the tyre faces radially.  The web and hub add their own axial and
    in-plane kinetic energy (for modes the web dominates).  In-plane modes are radial (inextensional
    bending, U_r + n U_phi = 0, or breathing for n = 0) or circumferential
    (extensional/shear, U_phi ~ n U_r, or torsion for n = 0)."""
    m = tyre_rigid_motion(U[tyre], points[tyre], weights[tyre])
    mt = weights[tyre].sum()
    rest = ~tyre
    w = weights[rest]
    out_of_plane = mt * m["out_of_plane"] + w @ U[rest, 1] ** 2
    in_plane = mt * m["in_plane"] + w @ (U[rest, 0] ** 2 + U[rest, 2] ** 2)
    if out_of_plane >= in_plane:
        return "a"
    tr, tp = m["T_r"], m["T_phi"]
    if n == 0:
        return "r" if tr**2 >= tp**2 else "c"
    bend = (n * tr - tp) ** 2  # projection on (n, -1): U_r + n U_phi = 0
    ext = (tr + n * tp) ** 2  # projection on (1, n)
    return "r" if bend >= ext else "c"


def sign_changes(values: np.ndarray, floor: float = 0.03) -> int:
    """Sign changes of a sampled function, ignoring |v| < floor max|v|."""
    v = np.asarray(values, float)
    big = np.abs(v) >= floor * np.max(np.abs(v)) if np.any(v) else np.zeros(len(v), bool)
    s = np.sign(v[big])
    return int(np.count_nonzero(s[1:] != s[:-1]))


def nodal_circles(U_line: np.ndarray, cls: str) -> int:
    """m from the shape sampled along the web centreline (samples, 3).
    In-plane (r, c) modes count only strong sign changes (30% floor): their
    web carries little motion near the hub and weak zeros there are not
    nodal circles of the tyre motion that defines the family."""
    comp = {"a": 1, "r": 0, "c": 2}[cls]
    return sign_changes(U_line[:, comp], floor=0.03 if cls == "a" else 0.3)


def order_nodal_circles(freqs, labels):
    """Make m consistent within each (n, class) family: the modes of one
    harmonic and class are ordered by nodal circles as frequency rises,
    starting with none, so a family whose counts are not 0, 1, 2, ... (a
    zero lying exactly at the web-tyre junction is easily missed or
    doubled) takes the rank instead.  Returns the new
    labels and a flag per mode telling whether the count was overridden."""
    out = list(labels)
    fixed = [False] * len(labels)
    for cls in {c for _, c in labels}:
        idx = [i for i in np.argsort(freqs) if labels[i][1] == cls]
        counted = [labels[i][0] for i in idx]
        if counted != list(range(len(counted))):
            for rank, i in enumerate(idx):
                if labels[i][0] != rank:
                    out[i] = (rank, cls)
                    fixed[i] = True
    return out, fixed


class _Triangulation:
    """Barycentric interpolation on a given triangle mesh (not Delaunay)."""

    def __init__(self, points, cells):
        self.points, self.cells = points, cells
        p = points[cells]
        self.T = np.stack([p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]], axis=2)  # (c, 2, 2)
        self.Tinv = np.linalg.inv(self.T)
        self.p0 = p[:, 0]

    def locate(self, xy):
        lam = np.einsum("cij,cj->ci", self.Tinv, xy[None, :] - self.p0)
        l0 = 1 - lam.sum(axis=1)
        bary = np.column_stack([l0, lam])
        inside = np.all(bary >= -1e-9, axis=1)
        if np.any(inside):
            c = int(np.argmax(inside))
            return c, bary[c]
        return None, None

    def interpolate(self, U, line):
        out = np.zeros((len(line), U.shape[1]))
        for i, xy in enumerate(np.asarray(line, float)):
            c, b = self.locate(xy)
            if c is None:
                out[i] = U[np.argmin(np.linalg.norm(self.points - xy, axis=1))]
            else:
                out[i] = b @ U[self.cells[c]]
        return out


def classify_modes(points, cells, shapes, n, tyre_mask, web_line):
    """Labels (m, class) for each shape of harmonic n."""
    w = nodal_weights(points, cells)
    tri = _Triangulation(points, cells)
    labels = []
    for U in shapes:
        cls = mode_class(U, n, w, tyre_mask, points)
        m = nodal_circles(tri.interpolate(U, web_line), cls)
        labels.append((m, cls))
    return labels
