"""The operating point of every wheel of a solved bogie (ids a1o, a1i, a2o, a2i: axle 1 leading,
o/i outer/inner rail), in the project's conventions (BRIEF "Sign conventions of a curve wheel";
SPEC 2): dy_wr = +y on the outer wheel and -y on the inner wheel (+ toward that wheel's field
side), creepages and spin of the tread contact in its contact frame, contact points y^W, y^R,
contact angle, loads, and the flange contact's Nadal ratio Y/Q (NaN without a flange contact)
with Nadal's limit (tan d - mu) / (1 + mu tan d) at its angle.
"""
from __future__ import annotations

import math


def _rail_loads(c):
    """(Y toward the field side, Q down) of one contact's force on the rail (N)."""
    fx, fy, fz = c.force_on_wheel()
    return -c.side * fy, -fz


def wheel_points(sol, mu: float) -> list[dict]:
    """One dict per wheel (see module doc; SI units, angles in rad)."""
    out = []
    for k, ws in enumerate(sol.wheelsets, start=1):
        for side, tag in ((+1, "o"), (-1, "i")):
            cs = [c for c in ws.contacts if c.side == side]
            tread = max((c for c in cs if c.point.zone == "tread"), key=lambda c: c.N)  # of two: the more loaded
            flange = next((c for c in cs if c.point.zone == "flange"), None)
            Y = sum(_rail_loads(c)[0] for c in cs)
            Q = sum(_rail_loads(c)[1] for c in cs)
            row = dict(wheel=f"a{k}{tag}", axle=k, side="outer" if side > 0 else "inner",
                       dy_wr=side * ws.y, angle_of_attack=ws.psi, gamma_x=tread.gamma_1, gamma_y=tread.gamma_2,
                       spin=tread.spin, y_wheel=tread.point.y_wheel, y_rail=tread.point.y_rail,
                       contact_angle=tread.point.angle, rolling_radius=tread.r, wheel_load=Q, lateral_force=Y,
                       normal_load=tread.N, F1=tread.F1, F2=tread.F2,
                       creep_use=math.hypot(tread.F1, tread.F2) / (mu * tread.N) if tread.N > 0 else math.nan,
                       patch_a=tread.a, patch_b=tread.b, contact_points=len(cs),
                       nadal=math.nan, nadal_limit=math.nan, flange_y_wheel=math.nan, flange_y_rail=math.nan,
                       flange_angle=math.nan, flange_load=math.nan)
            if flange is not None:
                Yf, Qf = _rail_loads(flange)
                t = math.tan(flange.point.angle)
                row.update(nadal=Yf / Qf, nadal_limit=(t - mu) / (1.0 + mu * t), flange_y_wheel=flange.point.y_wheel,
                           flange_y_rail=flange.point.y_rail, flange_angle=flange.point.angle, flange_load=flange.N)
            out.append(row)
    return out
