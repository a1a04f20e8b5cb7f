"""The contact points of one wheel on its rail for a given lateral position, tread and flange
(SPEC 2; the rigid contact of ``geometry.contact_point``, refined to machine precision and
split into the tread zone and the flange zone, so that a flange contact is a second point).

Frames as in ``geometry.contact_point``: the wheel profile z_W(y^W) (+ field side, flange at
negative y^W) over a rail turned by its inclination into the track frame (``TrackRail``), the
wheel's rolling circle at track position ``shift`` over the rail centre, and the vertical
separation sep(y^W) = -z_W(y^W) - z_T(y^W + shift).  The wheelset does not roll (the two
wheels are lowered onto their rails independently; the roll angle, |r_o - r_i| / (2 l), tilts
a contact by less than a degree).

Zones: the flange zone is the part of the wheel profile on the flange side of the first point,
counted from the tread, where the wheel's slope reaches ``FLANGE_SLOPE`` (45 degrees, the
limit of ``geometry.contact_point.FLANGE_ANGLE_DEG``); the tread zone is the rest.  A flange
contact is a second contact zone: a local minimum of the separation in the flange zone behind
a ridge (``geometry.contact_point.RIDGE``), as the project's rigid contact search reports it
(``second``).  Each point is found on the profile grid and refined by Newton's method on
sep'(y) = 0 (sep'' from the splines' curvatures), so that it is a smooth function of the shift.
The wheel touches in its tread zone alone while the flange zone's lowest point is higher; the
shift where both are equally low is the flange (two-point) contact (``flange_shift``).  Where
the contact climbs the flange root without a jump (no second zone) there is no two-point
contact: the one contact point moves up the flange, its angle rising.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geometry.contact_point import FLANGE_ANGLE_DEG, RIDGE

FLANGE_SLOPE = math.tan(math.radians(FLANGE_ANGLE_DEG))
TIE = 1e-6   # m: tread minima this close in height on the grid are told apart by their refined heights


@dataclass(frozen=True)
class ContactPoint:
    """One contact point of a wheel (m, rad, 1/m): y_wheel y^W, y_track Y (track frame over the
    rail centre), y_rail y^R (rail frame), angle (contact angle, + rising toward the field side),
    z_wheel (r - r0), sep (separation there, m), B (relative lateral curvature of the gap in the
    contact plane), zone ('tread' or 'flange')."""

    y_wheel: float
    y_track: float
    y_rail: float
    angle: float
    z_wheel: float
    sep: float
    B: float
    zone: str


def flange_edge(wheel) -> float:
    """y^W where the flange zone begins: the first grid point from the rolling circle (y^W = 0,
    on the tread) toward the flange with slope <= -FLANGE_SLOPE."""
    y = wheel.y
    s = np.asarray(wheel.slope(y))
    i0 = int(np.argmin(np.abs(y)))  # the rolling circle
    steep = np.flatnonzero(s[: i0 + 1] <= -FLANGE_SLOPE)
    if steep.size == 0:
        return float(y[0]) - 1.0  # no flange on this profile
    return float(y[steep[-1]])


_RAIL_Z: dict = {}


def _rail_points(rail_t):
    """The rail's heights at its own points (track frame), memoised per TrackRail."""
    key = id(rail_t)
    hit = _RAIL_Z.get(key)
    if hit is None or hit[0] is not rail_t:
        hit = _RAIL_Z[key] = (rail_t, np.asarray(rail_t(rail_t.y), float))
    return hit[1]


def _sep(wheel, rail_t, shift, y):
    s = -np.asarray(wheel(y)) - np.asarray(rail_t(np.asarray(y) + shift))
    return np.where(np.isfinite(s), s, np.inf)


def _refine(wheel, rail_t, shift, y, lo, hi):
    """Newton on sep'(y) = 0 from y, kept inside [lo, hi] (m)."""
    for _ in range(30):
        d1 = -float(wheel.slope(y)) - float(rail_t.slope(y + shift))
        d2 = -float(wheel.curvature(y)) - float(rail_t.curvature(y + shift))
        if not (np.isfinite(d1) and np.isfinite(d2)) or d2 <= 0.0:
            break
        step = d1 / d2
        y_new = min(max(y - step, lo), hi)
        if abs(y_new - y) < 1e-14:
            y = y_new
            break
        y = y_new
    return y


def _minima(sep):
    """Indices of the interior local minima of sep (sep[i] <= left, < right)."""
    return np.flatnonzero((sep[1:-1] <= sep[:-2]) & (sep[1:-1] < sep[2:])) + 1


_ZONE: dict = {}
_ZONE_MAX = 50000


def zone_point(wheel, rail_t, shift: float, zone: str, edge: float, near: float | None = None) -> ContactPoint | None:
    """``_zone_point`` memoised per profiles (by identity, held while cached), shift, zone and edge: the
    equilibrium's iterations ask again and again for the contact at an unchanged shift (the Jacobian
    columns of the other unknowns: yaw, spin, loads, the other wheelset, the frame), ~4 in 5 calls of
    a bogie's solve.  The same numbers (a pure function of its arguments).  ``near`` (y^W, m): the
    tread zone's local minimum nearest to it instead of the lowest (one point of a two-point tread
    contact, ``tread_jumps``)."""
    key = (id(wheel), id(rail_t), float(shift), zone, float(edge), near)
    hit = _ZONE.get(key)
    if hit is not None and hit[0] is wheel and hit[1] is rail_t:
        return hit[2]
    p = _zone_point(wheel, rail_t, shift, zone, edge, near)
    if len(_ZONE) >= _ZONE_MAX:
        _ZONE.clear()
    _ZONE[key] = (wheel, rail_t, p)
    return p


def _zone_point(wheel, rail_t, shift: float, zone: str, edge: float, near: float | None = None) -> ContactPoint | None:
    """The contact point of the tread or of the flange at this shift.

    On the profile grid (the rail interpolated linearly between its points, ``rail_t.y``): the
    tread point is the lowest local minimum of the separation on the tread side of ``edge``, or,
    when the separation falls without a break from the tread into the flange zone (a contact
    climbing the flange root, as S1002 on a new head), the lowest point of all; the flange
    point is the lowest local minimum on the flange side that a ridge higher than RIDGE
    separates from the tread point (a second contact zone), else None.  Refined by Newton's
    method on the splines.  Tread minima within TIE of each other on the grid are ranked by their
    refined heights, so that the tread point jumps exactly where ``tread_jumps`` finds both equally
    low; ``near``: the tread minimum nearest to that y^W."""
    y = wheel.y
    rz = _rail_points(rail_t)
    sep = -wheel.z - np.interp(y + shift, rail_t.y, rz, left=np.nan, right=np.nan)
    sep = np.where(np.isfinite(sep), sep, np.inf)
    if not np.isfinite(sep).any():
        return None
    mins = _minima(sep)
    tread = mins[y[mins] > edge]
    t = int(tread[np.argmin(sep[tread])]) if tread.size else int(np.argmin(sep))
    h = y[1] - y[0]
    if near is not None and zone == "tread" and tread.size:
        t = int(tread[np.argmin(np.abs(y[tread] - near))])
    elif tread.size > 1:  # two tread minima about equally low on the grid: the lower once refined
        close = tread[sep[tread] - sep[t] < TIE]
        if close.size > 1:
            t = int(min(close, key=lambda j: float(_sep(wheel, rail_t, shift, _refine(
                wheel, rail_t, shift, float(y[j]), float(y[j] - 8 * h), float(y[j] + 8 * h))))))
    if zone == "tread":
        i = t
    else:
        fl = mins[(y[mins] <= edge) & (mins != t)]
        fl = [j for j in fl if np.max(sep[min(j, t):max(j, t) + 1]) - sep[j] > RIDGE]
        if not fl:
            return None
        i = int(min(fl, key=lambda j: sep[j]))
    yc = _refine(wheel, rail_t, shift, float(y[i]), float(y[i] - 8 * h), float(y[i] + 8 * h))
    Y = yc + shift
    slope = float(rail_t.slope(Y))
    angle = math.atan(slope)
    d2 = -float(wheel.curvature(yc)) - float(rail_t.curvature(Y))
    return ContactPoint(y_wheel=yc, y_track=Y, y_rail=rail_t.to_rail(Y), angle=angle, z_wheel=float(wheel(yc)),
                        sep=float(_sep(wheel, rail_t, shift, yc)), B=0.5 * d2 * math.cos(angle) ** 3,
                        zone="flange" if zone == "flange" else "tread")


def flange_gap(wheel, rail_t, shift: float, edge: float) -> float:
    """Height (m) of the flange zone's lowest point above the tread zone's: > 0 while the
    flange is clear, 0 in two-point contact, < 0 when the flange would carry the wheel."""
    t = zone_point(wheel, rail_t, shift, "tread", edge)
    f = zone_point(wheel, rail_t, shift, "flange", edge)
    if t is None or f is None:
        return math.inf
    return f.sep - t.sep


def flange_shift(wheel, rail_t, c: float, edge: float, span: float = 0.04) -> float:
    """Wheelset shift y (m, toward this wheel's field side) at which the flange touches: the
    root of flange_gap(c + y) = 0 on [-10 mm, span] (brentq); inf when there is none."""
    from scipy.optimize import brentq  # lazy: brings in scipy

    g = lambda y: flange_gap(wheel, rail_t, c + y, edge)  # noqa: E731
    ys = np.linspace(-0.01, span, 101)
    gs = np.array([g(v) for v in ys])
    k = np.flatnonzero((gs[:-1] > 0) & (gs[1:] <= 0))
    if k.size == 0:
        return math.inf  # no flange within reach (a flangeless profile): no constraint
    return float(brentq(g, ys[k[0]], ys[k[0] + 1], xtol=1e-13, rtol=1e-13))


def tread_jumps(wheel, rail_t, c: float, edge: float, side: int, y_max: float, step: float = 5e-5,
                jump: float = 1e-3) -> list[tuple[float, float, float]]:
    """Wheelset shifts y (m, outward, |y| < y_max) where this wheel's (side +1 outer, -1 inner) tread
    contact jumps between two local minima of the separation (a worn pair's two-point tread contact:
    both points equally low there): [(y, y^W before, y^W after), ...] in increasing y, "before"
    and "after" in the sense of increasing y.  Found as jumps of more than ``jump`` in y^W on a
    grid of ``step`` and refined by brentq on the two points' separations' difference."""
    from scipy.optimize import brentq  # lazy: brings in scipy

    ys = np.arange(-y_max, y_max, step)
    yw = np.array([zone_point(wheel, rail_t, c + side * v, "tread", edge).y_wheel for v in ys])
    out = []
    for k in np.flatnonzero(np.abs(np.diff(yw)) > jump):
        a, b = float(yw[k]), float(yw[k + 1])

        def gap(v):
            pa = zone_point(wheel, rail_t, c + side * v, "tread", edge, near=a)
            pb = zone_point(wheel, rail_t, c + side * v, "tread", edge, near=b)
            return pb.sep - pa.sep
        try:
            yj = float(brentq(gap, ys[k], ys[k + 1], xtol=1e-13, rtol=1e-13))
        except ValueError:
            continue  # the two minima do not both exist across the step: no two-point contact
        pa = zone_point(wheel, rail_t, c + side * yj, "tread", edge, near=a)
        pb = zone_point(wheel, rail_t, c + side * yj, "tread", edge, near=b)
        if abs(pb.y_wheel - pa.y_wheel) > jump:
            out.append((yj, pa.y_wheel, pb.y_wheel))
    return out
