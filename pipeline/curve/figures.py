"""bogie.png: the leading bogie in the curve (plan view) with its contact points, and the
verdict per wheel.  The rails are drawn at the running lines (the wheels' rolling circles,
``CONTACT_SPACING`` apart) and every wheel's contact point on its rail.  A wheelset's
yaw (its angle of attack, a few milliradians) is drawn exaggerated (the factor is in the title);
its lateral shift (millimetres, invisible at the scale of a bogie) is written beside each wheel,
not drawn."""
from __future__ import annotations

import math

import numpy as np

EXAGGERATE = 25.0     # yaw drawn this many times larger (up to YAW_DRAWN)
YAW_DRAWN = 0.25      # rad: the largest yaw drawn
WHEEL_DIAMETER = 0.78  # m, the wheel drawn in plan view (the C20's ~0.78 m)
COLOURS = {"squeals": "crimson", "unstable": "orange", "stable": "seagreen"}


def on_rail(xa: float, yc: float, ang: float, R: float, r: float) -> tuple[float, float]:
    """Where the axle through (xa, yc) with heading ``ang`` (its normal) crosses the rail of radius r
    about the curve centre (0, -R): the point (xa - t sin ang, yc + t cos ang) at distance r, t the
    root of t^2 + 2 B t + |P|^2 - r^2 = 0 nearer the axle (the other lies across the curve)."""
    dx, dy = -math.sin(ang), math.cos(ang)
    px, py = xa, yc + R                         # relative to the centre
    b = px * dx + py * dy
    root = math.sqrt(max(b * b - (px * px + py * py - r * r), 0.0))
    t = min((-b + root, -b - root), key=abs)
    return xa + t * dx, yc + t * dy


def _state(r: dict) -> str:
    if r.get("squeals"):
        return "squeals"
    return "unstable" if math.isfinite(r.get("screen_sigma", math.nan)) else "stable"


def _plan(ax, info, points, rows) -> float:
    """The left panel; returns the yaw's drawing factor."""
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib
    from matplotlib.lines import Line2D  # lazy: brings in matplotlib

    a, R, b = 0.5 * info.wheelbase, info.radius, 0.5 * CONTACT_SPACING
    x = np.linspace(-1.6 * a - 0.5, 1.6 * a + 0.5, 200)
    for side, name in ((+1, "outer rail"), (-1, "inner rail")):
        r = R + side * b                         # curve centre at (0, -R); y toward the outer rail
        ax.plot(x, -R + np.sqrt(r * r - x * x), color="0.3", lw=2.5, solid_capstyle="butt")
        ax.text(x[0], side * (b + 0.12), name, ha="left", va="center", fontsize=8, color="0.3")
    ax.plot(x, -R + np.sqrt(R * R - x * x), color="0.7", lw=0.8, ls="--")
    by, row = {p.wheel: p for p in points}, {r["wheel"]: r for r in rows}
    psi_max = max((abs(p.angle_of_attack) for p in points), default=0.0)
    yaw_x = min(EXAGGERATE, YAW_DRAWN / psi_max) if psi_max > 0 else EXAGGERATE   # yaw drawn at most YAW_DRAWN rad
    for axle, xa in (("a1", +a), ("a2", -a)):
        po, pi = by.get(axle + "o"), by.get(axle + "i")
        if po is None and pi is None:
            continue
        shift = po.dy_wr if po is not None else -pi.dy_wr     # the wheelset's shift toward the outer rail (true)
        psi = (po if po is not None else pi).angle_of_attack  # yaw relative to the radial direction
        yc = -R + math.sqrt(R * R - xa * xa) + shift
        ang = -math.atan2(xa, R) + yaw_x * psi    # the radial heading at xa (the tangent) plus the drawn yaw
        ends = {}
        for p, side in ((po, +1), (pi, -1)):
            if p is None:
                continue
            cx, cy = on_rail(xa, yc, ang, R, R + side * b)
            ends[side] = (cx, cy)
            ax.add_patch(plt.Rectangle((cx - WHEEL_DIAMETER / 2, cy - 0.035), WHEEL_DIAMETER, 0.07,
                                       angle=math.degrees(ang), rotation_point="center", color="0.6", zorder=3))
            col = COLOURS[_state(row.get(p.wheel, {}))]
            ax.plot(cx, cy, "o", color=col, ms=8, zorder=5)
            if p.contact_points > 1:
                ax.plot(cx, cy, "s", mfc="none", mec="k", ms=13, zorder=6)
            ax.annotate(f"{p.wheel}  {1e3 * p.dy_wr:+.1f} mm", (cx, cy), xytext=(0, 16 * side),
                        textcoords="offset points", ha="center", va="center", fontsize=8, zorder=7)
        if len(ends) == 2:
            (x1, y1), (x2, y2) = ends[+1], ends[-1]
            ax.plot([x1, x2], [y1, y2], color="0.2", lw=1.5, zorder=4)
    ax.annotate("", xy=(1.6 * a + 0.4, -1.25), xytext=(1.6 * a - 0.4, -1.25),
                arrowprops={"arrowstyle": "->", "color": "0.3"})
    ax.text(1.6 * a, -1.33, "travel", ha="center", va="top", fontsize=8, color="0.3")
    ax.set_aspect("equal")
    ax.set_ylim(-1.6, 1.6)
    ax.set_xlabel("along the track (m)")
    ax.set_ylabel("toward the outer rail (m)")
    handles = [Line2D([], [], marker="o", ls="", color=c, label=k if k != "unstable" else "screen unstable")
               for k, c in COLOURS.items()]
    handles.append(Line2D([], [], marker="s", ls="", mfc="none", mec="k", ms=9, label="flange contact"))
    ax.legend(handles=handles, fontsize=7, loc="lower left", ncol=2, frameon=False)
    ax.set_title(f"{info.vehicle.name} in {info.name}: R = {info.radius:g} m, {info.speed_kmh:g} km/h\n"
                 f"yaw drawn x{yaw_x:.3g}; beside each wheel its shift dy_WR (+: toward its field side)", fontsize=9)
    return yaw_x
CONTACT_SPACING = 1.5  # m between the rolling circles of a standard-gauge wheelset (the plot's scale)


def bogie_figure(info, points, rows):
    """The figure of the Curve ``info`` with its WheelOperatingPoints ``points`` and verdict ``rows``."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [1.5, 1]})
    _plan(ax, info, points, rows)
    names = [r["wheel"] for r in rows]
    lpa = [r["L_pA"] if r["squeals"] and math.isfinite(r["L_pA"]) else 0.0 for r in rows]
    bx.bar(names, lpa, color=[COLOURS[_state(r)] if r["squeals"] else "0.8" for r in rows])
    for i, r in enumerate(rows):
        txt = (f"{r['f_squeal']:.0f} Hz\n{r['mode']}" if r["squeals"] else
               (f"screen unstable\n{r['screen_sigma']:+.1f}/s" if math.isfinite(r["screen_sigma"]) else "stable"))
        bx.text(i, lpa[i] + 1, txt, ha="center", va="bottom", fontsize=8)
    bx.set_ylabel("L_pA at 7.5 m (dB(A))")
    bx.set_ylim(0, max(lpa + [60.0]) + 15)
    bx.set_title("verdict per wheel" + ("" if any(r["squeals"] for r in rows) else ": no wheel squeals"), fontsize=9)
    fig.tight_layout()
    return fig
