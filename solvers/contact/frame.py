"""The contact plane of a tilted contact: forces and receptances projected on it (issue 26).

The reference model (thesis ch. 4) takes the contact forces in the track's directions, 2 lateral
(+ toward the field side) and 3 vertical (+ down), whatever the slope of the profiles at the
contact; its ch. 7 names the contact angle as future work.  Here the contact's own frame is the
tangent plane of the profiles at the rigid contact: the normal is tilted by the contact angle
delta (the rail surface's slope, + rising toward the field side, ``geometry.contact_point``), so
in the SPEC directions (2, 3-down) of a structure

    e2' = ( cos delta, -sin delta)    tangential-lateral, in the contact plane, toward the field side
    e3' = ( sin delta,  cos delta)    normal, into the rail

and R = [e2' e3'] (columns).  A force F' = (F2', F3') in the contact frame is F = R F' in the
structure's directions, a displacement u is u' = R^T u, so a 2x2 receptance (or Green's function,
lag by lag) projects exactly as G' = R^T G R and a modal shape (row phi_r = (Phi_2, Phi_3)) as
phi_r R: the projected modal sum is the projected receptance, term by term.

Each structure is projected in its own frame: the wheel's directions are the track's (the wheelset
does not roll), the rail model's are the rail section's, turned by the rail inclination alpha
against the track (``geometry.contact_point.TrackRail``), so the rail's angle is delta - alpha.

Static preload: the case's preload is the vertical wheel load Q.  Resolved in the contact plane
with a frictionless static contact (the creep forces are the rolling state's, not the preload's),
the normal force carries all of it and the wheelset the lateral component Q tan delta:
N = Q / cos delta.
"""
from __future__ import annotations

import math

import numpy as np


def rotation(angle: float) -> np.ndarray:
    """R (2, 2): columns e2', e3' of the contact frame in SPEC directions (module notes)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, s], [-s, c]])


def project_receptance(G, angle: float) -> np.ndarray:
    """R^T G R for any (..., 2, 2) array of receptances or kernel lags (real or complex)."""
    G = np.asarray(G)
    R = rotation(angle)
    return np.einsum("ki,...kl,lj->...ij", R, G, R)


def project_shapes(phi, angle: float) -> np.ndarray:
    """Modal shapes (M, 2) at the contact point in the contact frame: phi R."""
    return np.asarray(phi, float) @ rotation(angle)


def to_structure(F2, F3, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """Contact-frame force components (F2', F3') in the structure's directions: R F'."""
    c, s = math.cos(angle), math.sin(angle)
    F2, F3 = np.asarray(F2, float), np.asarray(F3, float)
    return c * F2 + s * F3, -s * F2 + c * F3


def normal_preload(preload: float, angle: float) -> float:
    """The static normal force N = Q / cos(delta) of the vertical load Q (module notes)."""
    if abs(angle) >= 0.5 * math.pi:
        raise ValueError(f"contact angle {angle} rad: the normal must not be horizontal")
    return float(preload) / math.cos(angle)


def project_transfer(G, angle_out: float, angle_in: float) -> np.ndarray:
    """R_out^T G R_in: a transfer receptance (or kernel) from a force in one contact frame to the
    displacement in another (two contact points, each with its own frame)."""
    return np.einsum("ki,...kl,lj->...ij", rotation(angle_out), np.asarray(G), rotation(angle_in))
