"""Rigid half-wheelset on the primary suspension, in series with the
flexible wheel clamped at its bore (SPEC 3.1, the 'acceptable and simpler'
model).

The flexible modes are fixed-interface modes (bore clamped); the bore itself
rides on the rigid wheelset, whose motion on the suspension adds three
rigid-body modes to the modal set:

* bounce (n = 1): vertical translation, mass M, stiffness 2 k_v;
* roll (n = 1): rotation theta about the longitudinal axis through the
  wheelset centre; a wheel point (r, Z) moves vertically by Z theta and
  laterally by -r cos(phi) theta, so U_r = Z theta, U_phi = -Z theta,
  U_z = -r theta; inertia I, stiffness 2 k_v b^2 (b = axle-box half spacing);
* lateral (n = 0): axial translation, mass M, stiffness 2 k_lat.

Neglecting the coupling between interface (rigid) and fixed-interface
(flexible) modes is a Craig-Bampton reduction without the coupling terms:
valid while the rigid-body frequencies (a few to some tens of Hz) lie far
below the first flexible mode (~240 Hz for the C20), i.e. for the squeal band.
"""
from __future__ import annotations

import numpy as np


def rigid_modes(points: np.ndarray, z_rc: float, susp: dict) -> list[dict]:
    """The three rigid-body modes as dicts with keys name, n, f_hz, zeta,
    modal_mass (kg, for the shape normalised to max |U| = 1) and shape
    (nodes, 3) = (U_r, U_z, U_phi).  ``points`` are (r, Z) of the section
    nodes, ``susp`` the suspension parameters (per axle box, whole wheelset
    mass and roll inertia)."""
    r, Z = points[:, 0], points[:, 1]
    M, I, b = susp["wheelset_mass"], susp["wheelset_roll_inertia"], susp["box_half_spacing"]
    out = []

    def add(name, n, shape, mass, k, c):
        s = np.max(np.abs(shape))
        w = np.sqrt(k / mass)
        out.append({"name": name, "n": n, "f_hz": w / (2 * np.pi), "zeta": c / (2 * np.sqrt(k * mass)),
                    "modal_mass": mass / s**2, "shape": shape / s})

    one, zero = np.ones_like(r), np.zeros_like(r)
    add("bounce", 1, np.column_stack([one, zero, -one]), M, 2 * susp["k_vertical"], 2 * susp["c_vertical"])
    # roll, normalised to unit vertical motion at the rolling circle (theta = 1 / z_rc)
    add("roll", 1, np.column_stack([Z, -r, -Z]) / z_rc, I / z_rc**2,
        2 * susp["k_vertical"] * b**2 / z_rc**2, 2 * susp["c_vertical"] * b**2 / z_rc**2)
    add("lateral", 0, np.column_stack([zero, one, zero]), M, 2 * susp["k_lateral"], 2 * susp["c_lateral"])
    return out
