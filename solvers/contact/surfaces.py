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

The contact point comes from the rigid contact of the two profiles
(``geometry.contact_point``), where their tangents coincide; any remaining
linear part of h(0, eta) at eta = 0 (the tilt between the two tangents, for
a contact pair given by hand) is removed, i.e. the gap is measured from the
common tangent plane, and h is shifted so its minimum is 0 (the approach xi3
then starts at first contact).  Direction 3 is taken as vertical (the
contact angle is neglected, as in the thesis' model).
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


def potential_area(r_wheel, z_rail, y_w0: float, y_r0: float, delta: float, A: float,
                   dy: float, reach: float = 0.03, factor: float = 1.3) -> tuple[float, float, float, float, float]:
    """Extent of the potential contact area (m): half-length along x, and
    the lateral range [eta_lo, eta_hi] where the undeformed gap is below
    ``factor * delta`` (delta: an estimate of the approach) -- from the gap
    itself, so wide, asymmetric or double valleys of non-Hertzian profiles
    are covered; longitudinally from A x^2 = factor * delta.  Also returns
    [lo, hi], the lateral range (within +-reach) where both profiles exist."""
    eta = np.arange(-int(reach / dy), int(reach / dy) + 1) * dy
    ok = np.isfinite(np.asarray(r_wheel(y_w0 + eta), float)) & np.isfinite(np.asarray(z_rail(y_r0 + eta), float))
    i0 = int(np.argmin(np.abs(eta)))
    lo, hi = i0, i0
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    while hi < len(eta) - 1 and ok[hi + 1]:
        hi += 1
    eta = eta[lo:hi + 1]
    h = contact_gap(r_wheel, z_rail, y_w0, y_r0, np.array([0.0]), eta)[0]
    i0 = int(np.argmin(np.abs(eta)))
    low = (h - h[i0]) < factor * delta
    a, b = i0, i0
    while a > 0 and low[a - 1]:
        a -= 1
    while b < len(eta) - 1 and low[b + 1]:
        b += 1
    return float(np.sqrt(factor * delta / A)), float(min(eta[a], -dy)), float(max(eta[b], dy)), \
        float(eta[0]), float(eta[-1])


def patch_metrics(p: np.ndarray, x: np.ndarray, y: np.ndarray) -> dict:
    """Size of a pressure field's contact patch: elements in contact, area
    (m^2), length along x and width along y (m, extents of the loaded
    elements incl. one element), length/width ratio, p_max (Pa)."""
    C = np.asarray(p) > 0
    dx, dy = x[1] - x[0], y[1] - y[0]
    ix, iy = np.flatnonzero(C.any(axis=1)), np.flatnonzero(C.any(axis=0))
    length = (x[ix[-1]] - x[ix[0]] + dx) if ix.size else 0.0
    width = (y[iy[-1]] - y[iy[0]] + dy) if iy.size else 0.0
    return {"elements": int(C.sum()), "area": float(C.sum() * dx * dy), "length": float(length),
            "width": float(width), "ratio": float(length / width) if width else np.nan,
            "p_max": float(np.max(p)) if C.any() else 0.0}


def contact_grid(a_est: float, b_est: float, dx: float, dy: float, margin: float = 1.6) -> tuple[np.ndarray, np.ndarray]:
    """Element centres of the potential contact area: dx along x (= v dt,
    SPEC 4.1), dy laterally, covering margin x the given half-extents."""
    nx = 2 * int(np.ceil(margin * a_est / dx)) + 1
    ny = 2 * int(np.ceil(margin * b_est / dy)) + 1
    return (np.arange(nx) - nx // 2) * dx, (np.arange(ny) - ny // 2) * dy
