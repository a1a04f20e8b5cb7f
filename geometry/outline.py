"""Planar outline helpers shared by the wheel and rail cross-sections.

An outline is a closed polygon described as a list of named boundary
segments (``Segment``): each is a polyline whose last point is the next
segment's first point.  The names become Gmsh physical groups, so the solvers
can find the tread, the bore, the web faces and so on by name.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


class GeometryError(ValueError):
    """Geometry parameters that do not describe a valid cross-section.

    ``key`` is the dotted parameter name, ``value`` the offending value and
    ``allowed`` what would be accepted; the pipeline adds the file name.
    """

    def __init__(self, key: str, value, allowed: str):
        self.key, self.value, self.allowed = key, value, allowed
        super().__init__(f"{key} = {value!r}: {allowed}")


@dataclass
class Segment:
    name: str
    points: np.ndarray  # (k, 2) polyline, k >= 2
    size: float | None = None  # target element size along it (m)
    meta: dict = field(default_factory=dict)


def arc(center, radius, a0, a1, num):
    """Points on a circular arc from angle a0 to a1 (radians), inclusive."""
    t = np.linspace(a0, a1, num)
    return np.column_stack([center[0] + radius * np.cos(t), center[1] + radius * np.sin(t)])


def fillet(p_prev, corner, p_next, radius, num=6):
    """Replace the sharp corner p_prev-corner-p_next by a tangent arc.

    Returns the arc points (from the tangent point on the first leg to the
    tangent point on the second).  Raises ValueError when the legs are too
    short for the radius.
    """
    p_prev, corner, p_next = (np.asarray(p, float) for p in (p_prev, corner, p_next))
    d1 = p_prev - corner
    d2 = p_next - corner
    l1, l2 = np.linalg.norm(d1), np.linalg.norm(d2)
    d1, d2 = d1 / l1, d2 / l2
    cos_t = np.clip(d1 @ d2, -1.0, 1.0)
    theta = np.arccos(cos_t)  # interior angle between the legs
    if radius <= 0 or theta < 1e-6 or abs(np.pi - theta) < 1e-6:
        return corner[None, :]
    t = radius / np.tan(theta / 2)  # distance from corner to tangent points
    if t >= 0.95 * min(l1, l2):
        raise ValueError(f"fillet radius {radius} too large for legs {l1:.4g}, {l2:.4g}")
    a = corner + d1 * t
    b = corner + d2 * t
    bis = d1 + d2
    bis /= np.linalg.norm(bis)
    c = corner + bis * radius / np.sin(theta / 2)
    a0 = np.arctan2(a[1] - c[1], a[0] - c[0])
    a1 = np.arctan2(b[1] - c[1], b[0] - c[0])
    da = (a1 - a0 + np.pi) % (2 * np.pi) - np.pi  # short way round
    return arc(c, radius, a0, a0 + da, num)


def bezier(p0, p1, p2, num):
    """Quadratic Bezier curve through p0 and p2 with control point p1."""
    t = np.linspace(0.0, 1.0, num)[:, None]
    p0, p1, p2 = (np.asarray(p, float) for p in (p0, p1, p2))
    return (1 - t) ** 2 * p0 + 2 * (1 - t) * t * p1 + t**2 * p2


def closed_polygon(segments: list[Segment]) -> np.ndarray:
    """Vertices of the closed polygon (no repeated closing vertex)."""
    pts = [seg.points[:-1] for seg in segments]
    return np.vstack(pts)


def _segments_intersect(p, q, r, s):
    """Proper or touching intersection of segments pq and rs."""
    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    o1, o2, o3, o4 = orient(p, q, r), orient(p, q, s), orient(r, s, p), orient(r, s, q)
    if o1 != o2 and o3 != o4:
        return True
    return False


def check_simple(poly: np.ndarray, key: str = "outline") -> None:
    """Raise GeometryError if the closed polygon crosses itself or has
    repeated vertices (O(N^2), fine for a few hundred vertices)."""
    n = len(poly)
    seg_len = np.linalg.norm(np.roll(poly, -1, axis=0) - poly, axis=1)
    if np.any(seg_len < 1e-9):
        i = int(np.argmin(seg_len))
        raise GeometryError(key, tuple(np.round(poly[i], 6)), "outline edges of non-zero length (repeated vertex)")
    a = poly
    b = np.roll(poly, -1, axis=0)
    for i in range(n):
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue  # adjacent through the closing edge
            if _segments_intersect(a[i], b[i], a[j], b[j]):
                raise GeometryError(
                    key,
                    f"edges near r,z = {tuple(np.round(a[i], 4))} and {tuple(np.round(a[j], 4))}",
                    "a cross-section outline that does not intersect itself (check the dimensions)",
                )


def signed_area(poly: np.ndarray) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
