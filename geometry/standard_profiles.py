"""Standard (new) running-surface profiles generated from their published
definitions, as tabulated points in the profile convention of
``geometry.profiles`` (y lateral, + toward the field side; wheel z = r - r0,
rail z = height above the new crown top; metres unless a name says _mm).

* S1002 wheel (EN 13715 / UIC 510-2): the standard's piecewise definition,
  sections A (field chamfer) ... H (flange back), coefficients of the
  published table (as circulated with the DLR/Netter implementation).
* Rail heads from their arc radii (EN 13674-1 style: crown R1, shoulder R2,
  gauge corner R3, tangent to each other and to the head side), through the
  rail parameter files (``geometry.rail.crown_arcs``): the same head as the
  rail's FE section.  60E1 checked against the UIC60 file CONTACT ships
  (docs/validation/15_profiles.md; S1002 likewise).
* The parametric C20 running surface of a wheel parameter file (cone +
  worn flange, ``geometry.wheel.tread_profile``).

All functions are pure (parameters in, arrays out).
"""
from __future__ import annotations

import numpy as np
from geometry.rail import crown_arcs
from geometry.wheel import tread_profile

# --------------------------------------------------------------------------- S1002 (EN 13715)
# section bounds (mm, from the tape circle, + toward the field side) and coefficients
_S1002_BOUNDS = (-70.0, -62.764705882, -49.662510381, -39.764473993, -38.426669071, -35.0, -26.0, 32.15796, 60.0)
_B = (0.0, -3.358537058e-02, 1.565681624e-03, -2.810427944e-05, 5.844240864e-08, -1.562379023e-08,
      5.309217349e-15, -5.957839843e-12, 2.646656573e-13)  # section B: sum B[k] y^k
_C = (-4.320221063e+03, -1.038384026e+03, -1.065501873e+02, -6.051367875, -2.054332446e-01,
      -4.169739389e-03, -4.687195829e-05, -2.252755540e-07)  # section C: sum C[k] y^k
S1002_RANGE_MM = (-62.0, 60.0)  # tabulated part: flange top (-55) side to the field chamfer


def s1002(y_mm) -> np.ndarray:
    """S1002 wheel profile z = r - r0 (mm, radius above the tape circle; the
    flange is positive) at lateral positions y (mm from the tape circle, +
    toward the field side), EN 13715 piecewise definition, -70 <= y <= 60."""
    y = np.asarray(y_mm, float)
    if np.any((y < _S1002_BOUNDS[0]) | (y > _S1002_BOUNDS[-1])):
        raise ValueError(f"S1002 is defined for -70 <= y <= 60 mm; got {y.min():.3f} .. {y.max():.3f}")
    root = lambda r, c: np.sqrt(np.clip(r * r - (y + c) ** 2, 0.0, None))  # noqa: E731
    pieces = [
        9.519259302 + root(20.5, 49.5),        # H: flange back
        16.0 + root(12.0, 55.0),               # G: flange tip
        8.834924130 + root(20.0, 58.558326413),  # F: flange face, upper arc
        -93.576667419 - 2.747477419 * y,       # E: flange face line (70 deg)
        16.446 - root(13.0, 26.210665),        # D: flange root arc
        np.polyval(_C[::-1], y),               # C: root transition
        np.polyval(_B[::-1], y),               # B: tread
        1.364323640 - 0.066666667 * y,         # A: field chamfer
    ]
    idx = np.clip(np.searchsorted(_S1002_BOUNDS, y, side="right") - 1, 0, 7)
    return np.choose(idx, pieces)


def s1002_points(step_mm: float = 0.25) -> tuple[np.ndarray, np.ndarray]:
    """(y, z) in m of S1002 over S1002_RANGE_MM, every step_mm."""
    y = np.arange(S1002_RANGE_MM[0], S1002_RANGE_MM[1] + 1e-9, step_mm)
    return 1e-3 * y, 1e-3 * s1002(y)


# --------------------------------------------------------------------------- rail heads from their arcs
def rail_head_curve(p: dict, ds: float = 5e-5, side_depth: float = 0.016) -> dict:
    """The rail head's running profile as a parametric curve, gauge side to
    field side: crown R1, shoulder R2, corner R3 arcs of ``crown_arcs(p)``
    and the (tapered) head sides down to ``side_depth`` below the crown top.

    Returns {'s': arc length from the crown top (m, + field side), 'y', 'z'
    (m; z = height above the crown top, <= 0), 'n' (outward unit normals,
    (k, 2))}, sampled every ~ds of arc length."""
    a = crown_arcs(p)
    H = p["section"]["height"]
    pts, nrm = [], []
    for j in range(3):
        t0, t1 = a["theta"][j], (a["theta"][j + 1] if j < 2 else a["theta"][4])
        n = max(2, int(np.ceil(a["R"][j] * (t1 - t0) / ds)) + 1)
        th = np.linspace(t0, t1, n)[(1 if j else 0):]
        u = np.column_stack([np.sin(th), np.cos(th)])
        pts.append(a["c"][j] + a["R"][j] * u)
        nrm.append(u)
    side0, d = a["side_top"], a["side_dir"]
    length = (side0[1] - (H - side_depth)) / -d[1]
    t = np.linspace(0.0, length, max(2, int(np.ceil(length / ds)) + 1))[1:]
    pts.append(side0 + t[:, None] * d)
    nrm.append(np.tile([-d[1], d[0]], (len(t), 1)))  # outward (+y) normal of the side
    half, nh = np.vstack(pts), np.vstack(nrm)
    seg = np.r_[0.0, np.cumsum(np.hypot(*np.diff(half, axis=0).T))]
    y = np.r_[-half[:0:-1, 0], half[:, 0]]
    z = np.r_[half[:0:-1, 1], half[:, 1]] - H
    s = np.r_[-seg[:0:-1], seg]
    n = np.vstack([nh[:0:-1] * [-1.0, 1.0], nh])
    return {"s": s, "y": y, "z": z, "n": n / np.linalg.norm(n, axis=1)[:, None]}


TABLE_DEPTH = 0.022  # m below the crown top a tapered head's table reaches: past the gauge point (14 mm)


def rail_head_points(p: dict, max_angle_deg: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(y, z) in m of the head's running profile, single-valued in y.

    A head whose sides widen downward (``head.side_taper`` > 0, 1:20 on
    60E1) is single-valued down its sides: it is given down to TABLE_DEPTH
    below the crown top, so that the gauge point 14 mm below it (EN 13848-1,
    ``pipeline.curving.gauge_face``) lies on it.  A vertical side is not:
    there the profile stops where its slope reaches 75 deg.  An explicit
    ``max_angle_deg`` cuts both at that slope."""
    tapered = p["head"].get("side_taper", 0.0) > 0.0
    c = rail_head_curve(p, side_depth=TABLE_DEPTH) if tapered else rail_head_curve(p)
    if max_angle_deg is None:
        max_angle_deg = 90.0 if tapered else 75.0
    keep = np.abs(np.degrees(np.arctan2(c["n"][:, 0], c["n"][:, 1]))) <= max_angle_deg
    return c["y"][keep], c["z"][keep]


# --------------------------------------------------------------------------- parametric wheel tread
def wheel_tread_points(p: dict) -> tuple[np.ndarray, np.ndarray]:
    """(y^W, r - r0) in m of a parametric wheel's running surface
    (``geometry.wheel.tread_profile``) from the flange top to the field face:
    the polyline vertices (arcs sampled on the arc), single-valued in y."""
    pts = tread_profile(p)["points"]
    top = pts[np.argmax(pts[:, 1]):]
    keep = np.r_[True, np.diff(top[:, 0]) > 1e-7]
    return top[keep, 0], top[keep, 1] - p["tyre"]["rolling_radius"]
