"""The wheel's mode shapes and the squealing wheel's operating deflection shape (ODS) as 3D
fields on the swept wheel surface, for files ParaView opens (the pipeline writes them).

The surface is the cross-section boundary swept around the axle (``postprocess.modes.geometry``):
a vertex at angle phi of section point (r, Z) sits at (r cos phi, r sin phi, Z), the contact
point at phi = 0.  A harmonic-n mode moves it by u_r = U_r cos n phi, u_z = U_z cos n phi,
u_phi = U_phi sin n phi (n = 0: factor 1; docs/reference.md, "harmonic convention").

The ODS is the wheel's steady response to the squeal's dominant tone: the modal amplitudes of
[4.10] driven by the tone's complex RMS contact forces F2, F3 at the contact point,
q_r = H_r(f) (Phi_r2 F2 + Phi_r3 F3), H_r = 1 / (m_r (w_r^2 - W^2 + 2 i zeta_r w_r W)), summed
over all modes: u(x, t) = sqrt(2) Re(sum_r q_r u_r(x) e^{i W t}) (peak displacement in m)."""
from __future__ import annotations

import numpy as np

from solvers.wheel.receptance import modal_frf

from postprocess.modes.geometry import boundary_edges_from_triangles, sweep_surface


def wheel_surface(points_rz, cells, n_phi: int = 72):
    """The swept surface (``mode_geometry.SweptSurface``) of the section mesh."""
    return sweep_surface(points_rz, boundary_edges_from_triangles(cells), n_phi=n_phi)


def mode_field(surface, U, n: int) -> np.ndarray:
    """Cartesian displacement (vertices, 3) of the harmonic-n mode with section amplitudes U
    (nodes, 3) = (U_r, U_z, U_phi), unscaled (the mode's own normalisation, max |U| = 1)."""
    U = np.asarray(U, float)
    idx, phi = surface.point_index, surface.phi
    c, s = (np.ones_like(phi), np.ones_like(phi)) if int(n) == 0 else (np.cos(n * phi), np.sin(n * phi))
    ur, uz, up = U[idx, 0] * c, U[idx, 1] * c, U[idx, 2] * s
    cp, sp = np.cos(phi), np.sin(phi)
    return np.column_stack([ur * cp - up * sp, ur * sp + up * cp, uz])


def modal_amplitudes(f_hz: float, F2: complex, F3: complex, f_r, modal_mass, zeta, phi) -> np.ndarray:
    """q_r (modes,) complex RMS modal amplitudes under the tone (f_hz; F2, F3 complex RMS N) at the
    contact point, ``phi`` (modes, 2) the shapes there in directions 2 and 3 ([4.10])."""
    H = modal_frf(f_hz, f_r, modal_mass, zeta)[0]
    phi = np.asarray(phi, float)
    return H * (phi[:, 0] * F2 + phi[:, 1] * F3)


def ods_frames(surface, shapes, n, q, n_frames: int = 24) -> tuple[np.ndarray, np.ndarray]:
    """(phases (n_frames,) rad, displacements (n_frames, vertices, 3) m): the peak operating
    deflection sqrt(2) Re(sum_r q_r u_r e^{i theta}) at n_frames phases over one period."""
    q = np.asarray(q, complex)
    re = np.zeros((len(surface.phi), 3))
    im = np.zeros_like(re)
    for r in np.flatnonzero(np.abs(q) > 0):
        D = mode_field(surface, shapes[r], int(n[r]))
        re += q[r].real * D
        im += q[r].imag * D
    th = 2 * np.pi * np.arange(n_frames) / n_frames
    return th, np.sqrt(2) * (np.cos(th)[:, None, None] * re[None] - np.sin(th)[:, None, None] * im[None])
