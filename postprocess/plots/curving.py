"""Figures of steady curving (issue 25): the leading bogie in its curve and the wheel/rail
contacts of its four wheels; the shift and angle of attack over the curve radius.

Takes the solvers' objects (``solvers.curving``: Vehicle, Track, Profiles, CurvingSolution)
and returns matplotlib figures; saving is the caller's.
"""
from __future__ import annotations

import math

import numpy as np

WHEELS = (("a1o", 0, +1), ("a1i", 0, -1), ("a2o", 1, +1), ("a2i", 1, -1))


def _plan(ax, sol, veh, trk, scale):
    """Plan view: the rails (straightened: positions are relative to the local track), the
    frame's side members and the wheelsets with their contact points; lateral offsets from the
    nominal positions and the yaw angles exaggerated by ``scale``."""
    R, a, b = trk.radius, veh.semi_wheelbase, trk.rail_centre
    x = np.linspace(-2.2 * a, 2.2 * a, 200)
    for side in (-1, 1):
        ax.plot(x, side * b + 0 * x, color="0.3", lw=2)
    ax.axhline(0.0, color="0.7", lw=0.8, ls=":")
    xf = np.linspace(-1.3 * a, 1.3 * a, 50)
    yf = scale * (sol.frame_y + xf * sol.frame_psi + xf ** 2 / (2 * R))
    for off in (-veh.box_half_spacing, veh.box_half_spacing):
        ax.plot(xf, off + yf, color="tab:blue", lw=1.5)
    for ws in sol.wheelsets:
        ang = scale * ws.psi  # + heading outward: the axle turns from +y toward -x
        yc = scale * ws.y
        ends = (np.array([-b - 0.08, b + 0.08]) - yc) / math.cos(ang)  # the axle reaches both rails
        ax.plot(ws.x - ends * math.sin(ang), yc + ends * math.cos(ang), color="k", lw=2.5)
        for c in ws.contacts:
            yp = c.side * (b - 0.04 * (c.point.zone == "flange"))  # on its rail (the sections show where)
            ax.plot(ws.x - (yp - yc) * math.tan(ang), yp, "o" if c.point.zone == "tread" else "^",
                    color="tab:red" if c.point.zone == "flange" else "tab:orange", ms=7)
    ax.annotate("travel", xy=(2.1 * a, 0), xytext=(1.4 * a, 0), arrowprops=dict(arrowstyle="->"), va="center")
    ax.set_xlabel("x along the track (m)")
    ax.set_ylabel("y toward the outer rail (m)")
    ax.set_title(f"leading bogie, R = {R:g} m: rails (grey), frame (blue), wheelsets; offsets and yaw x{scale:g}; "
                 "o tread, ^ flange contact", fontsize=9)
    ax.set_aspect("equal")


def _section(ax, prof, trk, veh, ws, side, name):
    """A wheel on its rail (that wheel's own frame: + field side), its contact points."""
    shift = trk.c + side * ws.y
    yw = prof.wheel.y
    Y = prof.rail.y
    ax.plot(1e3 * Y, 1e3 * np.asarray(prof.rail(Y)), color="0.3", label="rail")
    lift = next(c.point.sep for c in ws.contacts if c.side == side and c.point.zone == "tread")
    ax.plot(1e3 * (yw + shift), -1e3 * (np.asarray(prof.wheel(yw)) + lift), color="k", label="wheel")
    for c in ws.contacts:
        if c.side == side:
            p = c.point
            ax.plot(1e3 * p.y_track, 1e3 * float(prof.rail(p.y_track)), "o" if p.zone == "tread" else "^",
                    color="tab:red" if p.zone == "flange" else "tab:orange", ms=7)
    ax.set_title(f"{name}: dy_wr = {1e3 * side * ws.y:+.1f} mm", fontsize=9)
    ax.set_xlim(-45, 45)
    ax.set_ylim(-25, 8)
    ax.set_xlabel("y over the rail centre, + field side (mm)", fontsize=8)


def bogie_in_curve(sol, veh, trk, prof, scale: float = 20.0):
    """The plan view of the bogie in the curve and the four wheel/rail sections."""
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig = plt.figure(figsize=(11, 7.5))
    gs = fig.add_gridspec(2, 4, height_ratios=[1.3, 1])
    _plan(fig.add_subplot(gs[0, :]), sol, veh, trk, scale)
    for k, (name, i, side) in enumerate(WHEELS):
        _section(fig.add_subplot(gs[1, k]), prof, trk, veh, sol.wheelsets[i], side, name)
    fig.tight_layout()
    return fig


def radius_sweep(series: dict):
    """Leading and trailing wheelsets' shift and angle of attack over the radius.  ``series``:
    vehicle name -> dict of arrays R, y1, y2, psi1, psi2 (m, rad), flange1 (bool) and y_f (m)."""
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, (name, s) in enumerate(series.items()):
        col = f"C{k}"
        R = np.asarray(s["R"])
        a1.plot(R, 1e3 * np.asarray(s["y1"]), "-o", color=col, ms=4, label=f"{name}: leading")
        a1.plot(R, 1e3 * np.asarray(s["y2"]), "--s", color=col, ms=3, label=f"{name}: trailing")
        a1.axhline(1e3 * s["y_f"], color=col, ls=":", lw=1)
        a2.plot(R, 1e3 * np.asarray(s["psi1"]), "-o", color=col, ms=4, label=f"{name}: leading")
        a2.plot(R, 1e3 * np.asarray(s["psi2"]), "--s", color=col, ms=3, label=f"{name}: trailing")
        fl = np.asarray(s["flange1"], bool)
        a2.plot(R[fl], 1e3 * np.asarray(s["psi1"])[fl], "^", color="tab:red", ms=8, mfc="none")
        a2.plot(R, 1e3 * s["a"] / R, ":", color=col, lw=1)
    a1.set_xscale("log")
    a2.set_xscale("log")
    a1.set_xlabel("curve radius R (m)")
    a2.set_xlabel("curve radius R (m)")
    a1.set_ylabel("wheelset shift y (mm, outward)")
    a2.set_ylabel("angle of attack (mrad)")
    a1.set_title("shift (dotted: flange contact shift)", fontsize=9)
    a2.set_title("angle of attack (dotted: a/R; red: leading flange in contact)", fontsize=9)
    a1.legend(fontsize=7)
    a2.legend(fontsize=7)
    fig.tight_layout()
    return fig
