"""Rigid contact point of a wheel and a rail profile for a lateral wheelset
offset (SPEC 2, thesis section 4.1.1): the point where the undeformed
surfaces first touch when the wheel is lowered onto the rail.

Frames.  The wheel profile z_W(y^W) = r - r0 and the rail profile z_R(y^R)
(height above the crown top) are tabulated in their own frames
(``geometry.profiles``).  The track frame is the rail's frame turned by the
rail inclination alpha (the head tilted toward the track centre, i.e. toward
-y, so its surface rises toward the field side by tan(alpha) at the crown
top) about the crown top; the wheelset does not roll, so the wheel profile is
already in the track frame.  The wheel's y^W = 0 (rolling circle) lies at
track-frame position ``shift`` = c + dy_WR over the rail centre line
(``wheel_shift``), where c is the rolling circle's position over the rail
centre for the centred wheelset: y^W and y^R both + toward the field side
(SPEC 2), so a wheelset moved by dy_WR moves every wheel point by dy_WR over
the rail, Y = y^W + c + dy_WR.  Thesis [4.1] fits this with c = -17/3 mm once
its printed y^W (positive toward the flange) is negated
(``solvers.constants.THESIS_CONTACT_POINTS_FIELD``,
docs/validation/31_contact_positions.md).

Contact: wheel point y^W is above track point Y = y^W + shift; the vertical
separation is  sep(y^W) = -z_W(y^W) - z_T(y^W + shift)  up to a constant, and
the contact is its global minimum (grid search on the wheel profile's grid,
then refined by a bounded scalar minimisation on the splines).  The next
lowest other contact zone is reported (``second``): a local minimum of the
separation behind a ridge, less than SECOND_WINDOW above the contact; when
its extra separation is below the static approach the loaded contact has two
patches, and the contact point jumps there as the offset grows.

Flange contact: a contact angle above FLANGE_ANGLE_DEG or a wheel point more
than FLANGE_HEIGHT above the rolling circle is flange contact, which the
tread/rail-head contact model does not cover: ``FlangeContact`` is raised.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

FLANGE_ANGLE_DEG = 45.0
FLANGE_HEIGHT = 0.010  # m above the rolling circle: the flange (flange thickness is measured at this height)
SECOND_WINDOW = 0.25e-3  # m: separations looked at for a second contact zone (a few static approaches)
RIDGE = 1e-5  # m: a second zone is a local minimum behind a ridge at least this high
OVERHANG_TOL = 1e-6  # m: a turned rail point must lie this far left of the rest (single-valued z_T(Y))


class FlangeContact(ValueError):
    """The rigid contact lies on the flange (or runs off a profile)."""


@dataclass(frozen=True)
class RigidContact:
    """Contact point of the rigid profiles (m, rad).

    shift: position of the wheel's rolling circle over the rail centre in the
    track frame; y_wheel: y^W; y_rail: y^R in the rail's own frame; y_track:
    Y in the track frame; angle: contact angle (slope of the rail surface in
    the track frame, + rising toward the field side); z_wheel: r - r0 there;
    second: (y^W, extra separation in m) of the lowest point of the next
    separate zone within SECOND_WINDOW, or None.
    """

    shift: float
    y_wheel: float
    y_rail: float
    y_track: float
    angle: float
    z_wheel: float
    second: tuple | None


class TrackRail:
    """A rail profile turned by its inclination into the track frame:
    callable z_T(Y), with ``slope``, ``curvature`` and ``to_rail(Y)``."""

    def __init__(self, rail, inclination: float):
        from scipy.interpolate import make_interp_spline  # lazy: brings in scipy

        self.rail, self.alpha = rail, float(np.arctan(inclination))
        ca, sa = np.cos(self.alpha), np.sin(self.alpha)
        y, z = rail.y, rail.z
        Y, Z = y * ca - z * sa, y * sa + z * ca
        # a head side turned to 90 deg or more (a 1:20 side at 1:20 or more) overhangs: keep the single-valued
        # part, the points at least OVERHANG_TOL left of everything after them
        keep = Y < np.r_[np.minimum.accumulate(Y[::-1])[::-1][1:], np.inf] - OVERHANG_TOL
        self._Y, self._Z = Y[keep], Z[keep]
        self._spl = make_interp_spline(self._Y, self._Z, k=3) if self.alpha else None
        self.y = self._Y

    def _eval(self, Y, nu):
        Y = np.asarray(Y, float)
        if self._spl is None:
            return {0: self.rail, 1: self.rail.slope, 2: self.rail.curvature}[nu](Y)
        out = self._spl(Y, nu)
        return np.where((Y >= self._Y[0]) & (Y <= self._Y[-1]), out, np.nan)

    def __call__(self, Y):
        return self._eval(Y, 0)

    def slope(self, Y):
        return self._eval(Y, 1)

    def curvature(self, Y):
        return self._eval(Y, 2)

    def to_rail(self, Y: float) -> float:
        """y^R (rail frame) of the surface point at track-frame Y."""
        z = float(self(Y))
        return float(Y * np.cos(self.alpha) + z * np.sin(self.alpha))


def second_zone(y, sep, i: int, window: float, ridge: float = RIDGE):
    """(y, sep - sep[i]) of the lowest other contact zone within ``window``:
    a local minimum of sep (other than the contact, index i) that is less
    than ``window`` above sep[i] and separated from it by a ridge rising
    more than ``ridge`` above that minimum; None if there is none."""
    sep = np.asarray(sep, float)
    inner = (sep[1:-1] <= sep[:-2]) & (sep[1:-1] < sep[2:])
    best = None
    for j in np.flatnonzero(inner) + 1:
        extra = sep[j] - sep[i]
        if j == i or extra >= window or (best is not None and extra >= best[1]):
            continue
        lo, hi = sorted((i, j))
        if np.max(sep[lo:hi + 1]) - sep[j] > ridge:
            best = (float(y[j]), float(extra))
    return best


def wheel_shift(c: float, dy_wr: float) -> float:
    """Track-frame position (m, + field side) of the wheel's rolling circle
    for the wheelset offset dy_WR (m): c + dy_WR (Y = y^W + shift)."""
    return float(c) + float(dy_wr)


def _separation(wheel, rail_t, shift, y):
    s = -np.asarray(wheel(y)) - np.asarray(rail_t(np.asarray(y) + shift))
    return np.where(np.isfinite(s), s, np.inf)


def rigid_contact(wheel, rail_t: TrackRail, shift: float) -> RigidContact:
    """Contact of ``wheel`` (Profile) on ``rail_t`` (TrackRail) with the
    wheel's rolling circle at track position ``shift`` (m).  Raises
    FlangeContact for flange contact or profiles that do not overlap."""
    from scipy.optimize import minimize_scalar  # lazy: brings in scipy

    y = wheel.y
    sep = _separation(wheel, rail_t, shift, y)
    if not np.isfinite(sep).any():
        raise FlangeContact(f"the wheel and rail profiles do not overlap laterally (rolling circle "
                            f"{1e3 * shift:+.1f} mm from the rail centre)")
    i = int(np.argmin(sep))
    h = y[1] - y[0]
    if 0 < i < len(y) - 1 and np.isfinite(sep[i - 1]) and np.isfinite(sep[i + 1]):
        r = minimize_scalar(lambda t: float(_separation(wheel, rail_t, shift, t)), bounds=(y[i] - h, y[i] + h),
                            method="bounded", options={"xatol": 1e-9})
        yc = float(r.x)
    else:
        yc = float(y[i])
    second = second_zone(y, sep, i, SECOND_WINDOW)
    Y = yc + shift
    out = RigidContact(shift=float(shift), y_wheel=yc, y_rail=rail_t.to_rail(Y), y_track=float(Y),
                       angle=float(np.arctan(rail_t.slope(Y))), z_wheel=float(wheel(yc)), second=second)
    if abs(np.degrees(out.angle)) > FLANGE_ANGLE_DEG or out.z_wheel > FLANGE_HEIGHT:
        raise FlangeContact(f"flange contact: the rigid contact is at y^W = {1e3 * yc:+.1f} mm, "
                            f"{1e3 * out.z_wheel:.1f} mm above the rolling circle, contact angle "
                            f"{np.degrees(out.angle):+.0f} deg (tread contact needs < {FLANGE_ANGLE_DEG:.0f} deg and "
                            f"< {1e3 * FLANGE_HEIGHT:.0f} mm); the tread/rail-head contact model does not cover it")
    return out


def contact_sweep(wheel, rail_t: TrackRail, c: float, offsets) -> list:
    """Rigid contacts for several wheelset offsets dy_WR (``wheel_shift``);
    a FlangeContact becomes None in the list."""
    out = []
    for dy in offsets:
        try:
            out.append(rigid_contact(wheel, rail_t, wheel_shift(c, dy)))
        except FlangeContact:
            out.append(None)
    return out
