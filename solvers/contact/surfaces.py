"""Running surfaces: undeformed gap around a nominal contact point and the
rigid-profile contact search (SPEC 2 and 4.1).

Profiles enter as vectorised callables of the lateral coordinate (positive
toward the field side, SPEC 2): the wheel's rolling radius r_W(y^W) and the
rail head's height z_R(y^R).  The wheel rolls on a straight rail, so along
the rolling direction x only the wheel is curved.

Gap (vertical separation of the undeformed surfaces, SPEC 4.1 [4.16]) at
longitudinal x and lateral offset eta from the nominal contact point:

    h(x, eta) = [r_W(y_W0) - r_W(y_W0 + eta)] + [z_R(y_R0) - z_R(y_R0 + eta)]
                + x^2 / (2 r_W(y_W0 + eta))

The profiles of this project are nominal (the thesis' contact points come from
measured worn profiles), so the tangents of the two profiles at a tabulated
contact pair need not coincide; the linear part of h(0, eta) at eta = 0 (the
tilt between the two tangents) is removed, i.e. the gap is measured from the
common tangent plane at the nominal point, and h is shifted so its minimum is
0 (the approach xi3 then starts at first contact).  Direction 3 is taken as
vertical (the contact angle is neglected, as in the thesis' model).
"""
from __future__ import annotations

import numpy as np


def contact_gap(r_wheel, z_rail, y_w0: float, y_r0: float, x: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Undeformed gap h (len(x), len(eta)) in m around the nominal contact
    pair (y_w0 on the tread, y_r0 on the rail head); x along the rolling
    direction, eta lateral (+ field side), both centred on the contact."""
    x = np.asarray(x, float)[:, None]
    eta = np.asarray(eta, float)
    rw = np.asarray(r_wheel(y_w0 + eta), float)
    zr = np.asarray(z_rail(y_r0 + eta), float)
    if np.any(~np.isfinite(rw)) or np.any(~np.isfinite(zr)):
        raise ValueError("the potential contact area runs off the wheel or rail profile; reduce its width")
    lateral = (r_wheel(y_w0) - rw) + (z_rail(y_r0) - zr)
    h_eps = 1e-5
    tilt = ((r_wheel(y_w0) - r_wheel(y_w0 + h_eps)) + (z_rail(y_r0) - z_rail(y_r0 + h_eps))
            - (r_wheel(y_w0) - r_wheel(y_w0 - h_eps)) - (z_rail(y_r0) - z_rail(y_r0 - h_eps))) / (2 * h_eps)
    lateral = lateral - tilt * eta
    h = lateral[None, :] + x**2 / (2 * rw[None, :])
    return h - h.min()


def curvatures(r_wheel, z_rail, y_w0: float, y_r0: float, step: float = 2e-4) -> tuple[float, float]:
    """Relative curvatures (A along x, B lateral) of the gap at the nominal
    point, h ~ A x^2 + B eta^2: for Hertz estimates and grid sizing."""
    eta = np.array([-step, 0.0, step])
    h = contact_gap(r_wheel, z_rail, y_w0, y_r0, np.array([0.0]), eta)[0]
    B = (h[0] - 2 * h[1] + h[2]) / (2 * step**2)
    A = 1.0 / (2 * r_wheel(y_w0))
    return float(A), float(B)


def rigid_contact_search(r_wheel, z_rail, dy: float, y_wheel: np.ndarray) -> tuple[float, float]:
    """Contact point of the rigid profiles for a wheel whose y^W = 0 lies
    at y^R = dy over the rail (lateral wheelset position): the point of
    smallest vertical separation over the sampled tread positions y_wheel.
    Returns (y^W, y^R); a parabola through the best sample and its
    neighbours refines it."""
    y = np.asarray(y_wheel, float)
    sep = -np.asarray(r_wheel(y), float) - np.asarray(z_rail(y + dy), float)
    sep = np.where(np.isfinite(sep), sep, np.inf)
    i = int(np.argmin(sep))
    if not np.isfinite(sep[i]):
        raise ValueError(f"no overlap of wheel and rail profiles at dy = {dy}")
    yw = y[i]
    if 0 < i < len(y) - 1 and np.all(np.isfinite(sep[i - 1:i + 2])):
        a, b, c = sep[i - 1:i + 2]
        den = a - 2 * b + c
        if den > 0:
            yw = y[i] + 0.5 * (a - c) / den * (y[1] - y[0])
    return float(yw), float(yw + dy)


def contact_grid(a_est: float, b_est: float, dx: float, dy: float, margin: float = 1.6) -> tuple[np.ndarray, np.ndarray]:
    """Element centres of the potential contact area: dx along x (= v dt,
    SPEC 4.1), dy laterally, covering margin x the estimated semi-axes."""
    nx = 2 * int(np.ceil(margin * a_est / dx)) + 1
    ny = 2 * int(np.ceil(margin * b_est / dy)) + 1
    return (np.arange(nx) - nx // 2) * dx, (np.arange(ny) - ny // 2) * dy
