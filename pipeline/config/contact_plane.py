"""The case key ``[contact] angle`` (issue 26): the contact's frame of a case, and the greens
stage's projection of the wheel's and the rail's receptances on it (``solvers.contact.frame``).

``angle = "none"`` (default, the reference's choice): forces in the track's directions, nothing
projected (today's numbers, bit for bit).  ``angle = "profiles"``: the contact plane of the rigid
contact of the profiles (``geometry.contact_point``: delta, + rising toward the field side); the
wheel is projected by delta, the rail model (rail-section axes) by delta - alpha, alpha the rail
inclination; the static preload is resolved in the contact plane (N = Q / cos delta).
"""
from __future__ import annotations

import numpy as np

# greens.npz keys projected as 2x2 matrices (per lag / per frequency), and as modal shapes
WHEEL_MATRICES = ("wheel_kernel", "wheel_correction")
RAIL_MATRICES = ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance")


def frame_angles(c: dict, geo) -> tuple[float, float]:
    """(wheel angle, rail angle) in rad of the case ``c`` with ContactGeometry ``geo``: (0, 0) for
    angle = "none", else (delta, delta - alpha)."""
    if c["contact"].get("angle", "none") == "none":
        return 0.0, 0.0
    delta = float(geo.contact.angle)
    return delta, delta - float(geo.rail_track.alpha)


def normal_preload(c: dict, geo) -> float:
    """The static normal force of the case (N): the preload itself for angle = "none", else its
    resolution in the contact plane (``solvers.contact.frame.normal_preload``)."""
    from solvers.contact.frame import normal_preload as resolve  # lazy: brings in numba, rocket_fft, scipy

    F_L = c["loading"]["preload"]
    if c["contact"].get("angle", "none") == "none":
        return F_L
    return resolve(F_L, float(geo.contact.angle))


def project_greens(arrays: dict, angle_wheel: float, angle_rail: float) -> dict:
    """The greens arrays projected on the contact frame (new dict; the wheel's band-limited fit
    error ``wheel_fit_error`` stays the track frame's) plus ``contact_angle_wheel``,
    ``contact_angle_rail``.  Zero angles leave every array as it is."""
    from solvers.contact.frame import project_receptance, project_shapes  # lazy: brings in numba, rocket_fft, scipy

    out = dict(arrays)
    if angle_wheel != 0.0:
        out["wheel_phi"] = project_shapes(arrays["wheel_phi"], angle_wheel)
        for k in WHEEL_MATRICES:
            out[k] = project_receptance(arrays[k], angle_wheel)
    if angle_rail != 0.0:
        for k in RAIL_MATRICES:
            out[k] = project_receptance(arrays[k], angle_rail)
    out["contact_angle_wheel"] = np.float64(angle_wheel)
    out["contact_angle_rail"] = np.float64(angle_rail)
    return out


def case_projection(rc, arrays: dict) -> dict:
    """``project_greens`` with the angles of the resolved case ``rc`` (``pipeline.config.case``: the
    greens stage's hook)."""
    return project_greens(arrays, *frame_angles(rc.case, rc.geometry))
