"""The running profiles turned into the contact plane of a steep second zone (a flange or gauge-corner
contact, issue 26): the gap measured along the zone's normal, as a half-space contact reads it.

The profiles are turned by -delta about the zone's rail point; the wheel's rolling-direction curvature in
that normal section is cos(delta) / r_b (Meusnier's theorem for a surface of revolution of radius r_b).
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from scipy.interpolate import CubicSpline

SAMPLE = 2.5e-5      # m: profile sampling of the turned profiles
REACH = 0.012        # m: half-width of the turned profiles about the zone


def turned_geometry(geo, y2: float, Y2: float, delta: float, r_b: float):
    """The profiles about the zone (wheel y^W = y2 over track Y2) turned by -delta about the rail
    point, as ``static_contact`` reads a ContactGeometry: r_wheel(u) = R - w_W(u),
    z_rail(u) = w_R(u) in the turned lateral coordinate u (0 at the zone), R = r_b / cos(delta)."""
    c, s = np.cos(delta), np.sin(delta)
    H2 = float(geo.rail_track(Y2))
    Y = Y2 + np.arange(-REACH, REACH + SAMPLE / 2, SAMPLE)
    shift = Y2 - y2
    h_w = H2 - (np.asarray(geo.wheel(Y - shift), float) - float(geo.wheel(y2)))   # the wheel's surface height
    h_r = np.asarray(geo.rail_track(Y), float)
    R = r_b / c

    def turned(h, extend=False):
        ok = np.isfinite(h)
        u = (Y[ok] - Y2) * c + (h[ok] - H2) * s
        w = -(Y[ok] - Y2) * s + (h[ok] - H2) * c
        i0 = int(np.argmin(np.abs(u)))
        lo, hi = i0, i0                                   # the stretch where u increases through the zone
        while lo > 0 and u[lo - 1] < u[lo]:
            lo -= 1
        while hi < len(u) - 1 and u[hi + 1] > u[hi]:
            hi += 1
        spl = CubicSpline(u[lo:hi + 1], w[lo:hi + 1])
        a, b = u[lo], u[hi]
        if not extend:
            return lambda q: np.where((np.asarray(q) >= a) & (np.asarray(q) <= b), spl(np.clip(q, a, b)), np.nan)
        # beyond the profile's ends: continued along its end curvature (a circle's Taylor polynomial)
        ends = [(e, float(spl(e)), float(spl(e, 1)), float(spl(e, 2))) for e in (a, b)]

        def f(q):
            q = np.asarray(q, float)
            out = spl(np.clip(q, a, b))
            for e, w0, w1, w2, side in ((*ends[0], q < a), (*ends[1], q > b)):
                t = q - e
                out = np.where(side, w0 + w1 * t + 0.5 * w2 * t * t, out)
            return out
        return f

    ww, wr = turned(h_w), turned(h_r, extend=True)   # the rail profile ends at the head's widest point
    return SimpleNamespace(r_wheel=lambda u: R - ww(u), z_rail=wr,
                           contact=SimpleNamespace(y_wheel=0.0, y_track=0.0))
