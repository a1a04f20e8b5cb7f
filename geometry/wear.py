"""Parametric wear of running surfaces: a worn profile is the new one moved
inward along its normal by a smooth wear depth d (m) that varies along the
profile.  Few parameters, named as a profile engineer measures wear:

* wheel: a hollow-wear band on the tread (depth, centre y^W, half-width);
* rail: a top-wear band (vertical head wear, like MiniProf's W1: depth,
  centre and half-width along the head's arc length from the crown top) and
  gauge-face wear (lateral wear, like W2: depth reached on the gauge face,
  ramping up smoothly over GAUGE_RAMP of arc length from where it starts).

Depth functions are C2 (the curvature of a worn profile stays continuous):
the band is (1 - u^2)^3 on |u| < 1, the ramp the quintic smoothstep.
Pure functions; see ``geometry.calibration`` for the fit to contact points.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

GAUGE_RAMP = 0.012  # m of arc length over which gauge-face wear ramps up (over the gauge corner)
MAX_ANGLE_DEG = 75.0  # the tabulated running profile ends where the slope exceeds this


def band(u) -> np.ndarray:
    """C2 compact bump: (1 - u^2)^3 for |u| < 1, else 0 (1 at u = 0)."""
    u = np.asarray(u, float)
    return np.where(np.abs(u) < 1.0, (1.0 - u * u) ** 3, 0.0)


def smoothstep(u) -> np.ndarray:
    """C2 step: 0 for u <= 0, 1 for u >= 1, u^3 (10 - 15 u + 6 u^2) between."""
    u = np.clip(np.asarray(u, float), 0.0, 1.0)
    return u**3 * (10.0 - 15.0 * u + 6.0 * u * u)


@dataclass(frozen=True)
class WheelWear:
    """Hollow tread wear (m): depth at the band centre, centre y^W, half-width."""

    hollow_depth: float
    hollow_centre: float
    hollow_half_width: float

    def depth(self, y) -> np.ndarray:
        return self.hollow_depth * band((np.asarray(y) - self.hollow_centre) / self.hollow_half_width)

    def as_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class RailWear:
    """Rail head wear (m): top band (depth, centre and half-width in arc length
    s from the crown top, + field side) and gauge-face wear (depth reached on
    the gauge face, arc length |s| from the crown top where it starts)."""

    top_depth: float
    top_centre: float
    top_half_width: float
    gauge_depth: float
    gauge_start: float

    def depth(self, s) -> np.ndarray:
        s = np.asarray(s, float)
        top = self.top_depth * band((s - self.top_centre) / self.top_half_width)
        return top + self.gauge_depth * smoothstep((-s - self.gauge_start) / GAUGE_RAMP)

    def as_dict(self) -> dict:
        return asdict(self)


def offset_inward(y, z, n, d) -> tuple[np.ndarray, np.ndarray]:
    """Points moved by d along -n (n the outward unit normal; the body lies
    below the curve in its own z)."""
    n = np.asarray(n, float)
    return np.asarray(y) - d * n[:, 0], np.asarray(z) - d * n[:, 1]


def running_part(y, z, max_angle_deg: float = MAX_ANGLE_DEG) -> tuple[np.ndarray, np.ndarray]:
    """The contiguous part of a polyline around its highest point whose
    slope stays below max_angle_deg, as a function z(y) (y increasing).
    Raises ValueError when that part is not single-valued in y."""
    y, z = np.asarray(y, float), np.asarray(z, float)
    ang = np.degrees(np.arctan2(np.abs(np.gradient(z)), np.gradient(y)))
    ok = ang <= max_angle_deg
    i0 = int(np.argmax(np.where(ok, z, -np.inf)))
    lo = i0
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    hi = i0
    while hi < len(y) - 1 and ok[hi + 1]:
        hi += 1
    ys, zs = y[lo:hi + 1], z[lo:hi + 1]
    if np.any(np.diff(ys) <= 0):
        raise ValueError("the worn profile folds over (wear depth varies faster than the profile can follow)")
    return ys, zs


def worn_rail(curve: dict, wear: RailWear, max_angle_deg: float = MAX_ANGLE_DEG) -> tuple[np.ndarray, np.ndarray]:
    """(y, z) of a worn rail head from the new head curve
    (``standard_profiles.rail_head_curve``): its running part."""
    y, z = offset_inward(curve["y"], curve["z"], curve["n"], wear.depth(curve["s"]))
    return running_part(y, z, max_angle_deg)


def wheel_normals(y, z) -> np.ndarray:
    """Outward unit normals (k, 2) of a finely sampled wheel curve z(y) (the
    wheel's material is at smaller z = r - r0)."""
    dz = np.gradient(np.asarray(z, float), np.asarray(y, float))
    n = np.column_stack([-dz, np.ones_like(dz)])
    return n / np.linalg.norm(n, axis=1)[:, None]


def worn_wheel(y, z, wear: WheelWear) -> tuple[np.ndarray, np.ndarray]:
    """(y, z) of a worn wheel from a finely sampled new running surface."""
    yw, zw = offset_inward(y, z, wheel_normals(y, z), wear.depth(y))
    if np.any(np.diff(yw) <= 0):
        raise ValueError("the worn wheel profile folds over (hollow band too narrow for its depth)")
    return yw, zw
