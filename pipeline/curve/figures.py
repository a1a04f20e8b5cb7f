"""bogie.png: the leading bogie in the curve (plan view) with its contact points, and the
verdict per wheel.  Lateral shifts and yaw are exaggerated (the factor is in the title): a few
millimetres and milliradians would not show at the scale of a bogie."""
from __future__ import annotations

import math

import numpy as np

EXAGGERATE = 25.0     # lateral shift (and yaw, up to YAW_DRAWN) drawn this many times larger
YAW_DRAWN = 0.25      # rad: the largest yaw drawn
CONTACT_SPACING = 1.5  # m between the rolling circles of a standard-gauge wheelset (the plot's scale only)


def bogie_figure(info, points, rows):
    """The figure of the Curve ``info`` with its WheelOperatingPoints ``points`` and verdict ``rows``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [1.5, 1]})
    a, R, g = 0.5 * info.wheelbase, info.radius, info.gauge
    x = np.linspace(-1.6 * a - 0.5, 1.6 * a + 0.5, 200)
    for side, name in ((+1, "outer rail"), (-1, "inner rail")):
        r = R + side * g / 2                        # curve centre at (0, -R); y toward the outer rail
        ax.plot(x, -R + np.sqrt(r * r - x * x), color="0.3", lw=2)
        ax.text(x[-1], side * g / 2 + 0.08 * side, name, ha="right", va="center", fontsize=8, color="0.3")
    ax.plot(x, -R + np.sqrt(R * R - x * x), color="0.7", lw=0.8, ls="--")
    by = {p.wheel: p for p in points}
    row = {r["wheel"]: r for r in rows}
    b = 0.5 * CONTACT_SPACING
    psi_max = max((abs(p.angle_of_attack) for p in points), default=0.0)
    yaw_x = min(EXAGGERATE, YAW_DRAWN / psi_max) if psi_max > 0 else EXAGGERATE   # yaw drawn at most YAW_DRAWN rad
    for axle, xa in (("a1", +a), ("a2", -a)):
        po, pi = by.get(axle + "o"), by.get(axle + "i")
        if po is None and pi is None:
            continue
        shift = po.dy_wr if po is not None else -pi.dy_wr     # the wheelset's shift toward the outer rail
        psi = (po if po is not None else pi).angle_of_attack  # yaw relative to the radial direction
        yc = -R + math.sqrt(R * R - xa * xa) + EXAGGERATE * shift
        radial = -math.atan2(xa, R)                 # heading of a radial wheelset at xa (the tangent)
        ang = radial + yaw_x * psi
        for p, side in ((po, +1), (pi, -1)):
            if p is None:
                continue
            cx, cy = xa - side * b * math.sin(ang), yc + side * b * math.cos(ang)
            ax.plot([xa, cx], [yc, cy], color="0.2", lw=1.5)
            ax.add_patch(plt.Rectangle((cx - 0.39, cy - 0.035), 0.78, 0.07, angle=math.degrees(ang),
                                       rotation_point="center", color="0.55"))
            r_ = row.get(p.wheel, {})
            col = "crimson" if r_.get("squeals") else ("orange" if math.isfinite(r_.get("screen_sigma", math.nan))
                                                       else "seagreen")
            ax.plot(cx, cy, "o", color=col, ms=8, zorder=5)
            if p.contact_points > 1:
                ax.plot(cx, cy + side * 0.05, "s", color=col, ms=5, zorder=5)
            ax.annotate(p.wheel, (cx, cy), xytext=(0, 10 * side), textcoords="offset points", ha="center",
                        fontsize=8)
    ax.annotate("", xy=(1.6 * a + 0.4, -1.1), xytext=(1.6 * a - 0.4, -1.1),
                arrowprops={"arrowstyle": "->", "color": "0.3"})
    ax.text(1.6 * a, -1.2, "travel", ha="center", va="top", fontsize=8, color="0.3")
    ax.set_aspect("equal")
    ax.set_ylim(-1.5, 1.5)
    ax.set_xlabel("along the track (m)")
    ax.set_ylabel("toward the outer rail (m)")
    ax.set_title(f"{info.vehicle.name} in {info.name}: R = {info.radius:g} m, {info.speed_kmh:g} km/h\n"
                 f"(shift x{EXAGGERATE:g}, yaw x{yaw_x:.3g}; red: squeals, orange: screen unstable, green: stable; "
                 "square: flange contact)", fontsize=9)
    names = [r["wheel"] for r in rows]
    lpa = [r["L_pA"] if r["squeals"] and math.isfinite(r["L_pA"]) else 0.0 for r in rows]
    sig = [r["screen_sigma"] if math.isfinite(r["screen_sigma"]) else 0.0 for r in rows]
    bx.bar(names, lpa, color=["crimson" if r["squeals"] else "0.8" for r in rows])
    for i, r in enumerate(rows):
        txt = (f"{r['f_squeal']:.0f} Hz\n{r['mode']}" if r["squeals"] else
               ("screen\nunstable" if math.isfinite(r["screen_sigma"]) else "stable"))
        bx.text(i, lpa[i] + 1, txt, ha="center", va="bottom", fontsize=8)
    bx.set_ylabel("L_pA at 7.5 m (dB(A))")
    bx.set_ylim(0, max(lpa + [60.0]) + 15)
    bt = bx.twinx()
    bt.plot(names, sig, "kd", ms=5)
    bt.set_ylabel("screen growth rate (1/s)")
    bx.set_title("verdict per wheel", fontsize=9)
    fig.tight_layout()
    return fig
