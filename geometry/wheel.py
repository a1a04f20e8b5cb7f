"""Parametric railway wheel cross-section (axisymmetric), optionally with
the half axle out to the axle box.

Coordinates of the section: r (radius) and Z (axial, from the wheelset centre
plane, positive toward the field side).  Wheel features are given in the
parameter file relative to the nominal rolling circle, as the lateral tread
coordinate y^W = Z - Z_rc of SPEC section 2 (positive toward the field side,
so the flange sits at negative y).

``wheel_segments(p)`` is pure (parameters -> named polyline segments) and
checks the dimensions; ``geometry.mesher`` turns the segments into a mesh.
"""
from __future__ import annotations

import numpy as np

from solvers.constants import THESIS_CONTACT_POINTS_FIELD

from geometry.outline import GeometryError, Segment, bezier, check_simple, closed_polygon, fillet


# lateral tread positions y^W of the nominal contact points (SPEC 2, thesis [4.1] with its printed y^W
# negated: + toward the field side, solvers.constants.THESIS_CONTACT_POINTS_FIELD): mesh nodes there
CONTACT_Y = tuple(yw for yw, _ in THESIS_CONTACT_POINTS_FIELD.values())


def _require(cond: bool, key: str, value, allowed: str) -> None:
    if not cond:
        raise GeometryError(key, value, allowed)


def tyre_inner_radius(p: dict, y):
    """Radius of the tyre's inner (web-side) surface at lateral position y:
    depth ``tyre.depth`` below the rolling radius at the flange back,
    ``tyre.depth_field`` at the field face, linear in between."""
    t = p["tyre"]
    y_b, y_f = -t["back_offset"], t["width"] - t["back_offset"]
    d_f = t.get("depth_field") or t["depth"]
    return t["rolling_radius"] - (t["depth"] + (d_f - t["depth"]) * (np.asarray(y) - y_b) / (y_f - y_b))


def tread_profile(p: dict, num: int = 24) -> dict:
    """Running-surface profile of the tyre: the polyline (y^W, r) from the
    flange back face over the flange to the field face.  Returns the pieces
    so the outline and the contact stage use the same curve."""
    t, fl = p["tyre"], p["flange"]
    R0, c = t["rolling_radius"], t["conicity"]
    y_b = -t["back_offset"]
    y_f = t["width"] - t["back_offset"]
    r_in = R0 - t["depth"]
    h = fl["height"]
    tan_a = np.tan(np.radians(fl["face_angle_deg"]))
    # flange face: passes through (y_b + thickness, R0 + 10 mm), rising toward the back
    y_face10 = y_b + fl["thickness"]
    y_top = y_face10 - (h - 0.010) / tan_a

    def face_r(y):
        return R0 + 0.010 + (y_face10 - y) * tan_a

    # root corner: face line meets the coned tread r = R0 - c y
    y_root = (R0 + 0.010 + y_face10 * tan_a - R0) / (tan_a - c)
    _require(y_b < y_top, "flange.thickness", fl["thickness"],
             "a flange thick enough for its height and face angle (the flange top lies behind its back face)")
    _require(y_root < y_f - 0.01, "tyre.width", t["width"], "a tyre wide enough that the flange root stays 10 mm from the field face")
    _require(face_r(y_root) > r_in, "tyre.depth", t["depth"], "a depth that leaves material under the tread")
    tip = [np.array([y_b, R0 + h]), np.array([y_top, R0 + h])]
    root = np.array([y_root, R0 - c * y_root])
    field = np.array([y_f, R0 - c * y_f])
    cham = t["field_chamfer"]
    # flange back face bottom -> tip (two rounded corners) -> face -> root fillet -> tread
    pts = [np.array([y_b, r_in])]
    pts += list(fillet([y_b, r_in], tip[0], tip[1], min(fl["tip_radius"], 0.45 * (y_top - y_b)), 6))
    pts += list(fillet(tip[0], tip[1], root, fl["tip_radius"], 6))
    pts += list(fillet(tip[1], root, field, fl["root_radius"], 10))
    tread = np.linspace(pts[-1], field - [cham, -cham * c], num)[1:]
    # mesh nodes exactly at the nominal contact points (SPEC 2) that lie on the cone
    ys = [y for y in CONTACT_Y if pts[-1][0] + 1e-4 < y < tread[-1][0] - 1e-4]
    ys = np.union1d(tread[:, 0], ys)
    tread = np.column_stack([ys, R0 - c * ys])
    pts += list(tread)
    pts.append(np.array([y_f, field[1] - cham]))
    pts = np.array(pts)
    return {"points": pts, "y_back": y_b, "y_field": y_f, "r_inner": r_in, "y_root": y_root}


def tread_radius(p: dict, y: float) -> float:
    """Radius of the running surface at lateral position y^W (on the tread)."""
    prof = tread_profile(p)["points"]
    top = prof[np.argmax(prof[:, 1]):]  # from flange top toward the field side
    return float(np.interp(y, top[:, 0], top[:, 1]))


def _web_sides(p: dict, r_hub: float, r_in: float, num: int = 7):
    """Web centreline (quadratic Bezier from hub to tyre) offset by +-t/2.
    Returns (gauge_side, field_side) polylines from hub to tyre, as (y, r)."""
    w = p["web"]
    c0 = np.array([w["y_hub"], r_hub])
    c2 = np.array([w["y_tyre"], r_in])
    c1 = 0.5 * (c0 + c2) + np.array([w["bulge"], 0.0])
    s = np.linspace(0, 1, num)
    centre = bezier(c0, c1, c2, num)
    # extend the centreline a little into hub and tyre so the sides meet them
    tang = np.gradient(centre, axis=0)
    tang /= np.linalg.norm(tang, axis=1)[:, None]
    normal = np.column_stack([tang[:, 1], -tang[:, 0]])  # points toward -y (gauge) when the web runs outward in r
    if normal[num // 2, 0] > 0:
        normal = -normal
    thick = w["thickness_hub"] + (w["thickness_tyre"] - w["thickness_hub"]) * s
    gauge = centre + normal * thick[:, None] / 2
    field = centre - normal * thick[:, None] / 2
    # the end points must lie on the hub (r = r_hub) and on the tyre inner
    # surface r = r_in(y) (linear in y): intersect the end segments with them
    slope = float(tyre_inner_radius(p, 1.0) - tyre_inner_radius(p, 0.0))
    r0 = float(tyre_inner_radius(p, 0.0))
    for side in (gauge, field):
        d = side[0] - side[1]
        side[0] = side[1] + d * (r_hub - side[1][1]) / d[1]
        a, d = side[-2], side[-1] - side[-2]
        s_hit = (r0 + slope * a[0] - a[1]) / (d[1] - slope * d[0])
        side[-1] = a + s_hit * d
    return gauge, field


def _yr_to_rz(yr: np.ndarray, z_rc: float) -> np.ndarray:
    """(y^W, r) -> (r, Z) section coordinates."""
    yr = np.atleast_2d(yr)
    return np.column_stack([yr[:, 1], yr[:, 0] + z_rc])


def check_wheel(p: dict) -> None:
    """Dimension checks that make a valid section (before any meshing)."""
    t, web, hub = p["tyre"], p["web"], p["hub"]
    R0 = t["rolling_radius"]
    r_in = float(min(tyre_inner_radius(p, -t["back_offset"]), tyre_inner_radius(p, t["width"] - t["back_offset"])))
    _require(R0 > 0, "tyre.rolling_radius", R0, "a radius > 0")
    _require(0 < hub["bore_radius"] < hub["outer_radius"], "hub.bore_radius", hub["bore_radius"],
             f"0 < bore_radius < hub.outer_radius = {hub['outer_radius']}")
    _require(hub["outer_radius"] < r_in - 0.02, "hub.outer_radius", hub["outer_radius"],
             f"a hub radius at least 20 mm below the tyre inner radius {r_in:.4f} m")
    hub_w = hub["y_outboard"] - hub["y_inboard"]
    _require(hub_w > 0, "hub.y_outboard", hub["y_outboard"], f"a value > hub.y_inboard = {hub['y_inboard']}")
    for k in ("thickness_hub", "thickness_tyre"):
        _require(web[k] < hub_w, f"web.{k}", web[k], f"a web thinner than the hub width {hub_w:.4f} m")
        _require(web[k] < t["width"], f"web.{k}", web[k], f"a web thinner than the tyre width {t['width']:.4f} m")
    y_b, y_f = -t["back_offset"], t["width"] - t["back_offset"]
    half = web["thickness_tyre"] / 2 + web["fillet_tyre"]
    _require(y_b + half < web["y_tyre"] < y_f - half, "web.y_tyre", web["y_tyre"],
             f"a web (with fillets) meeting the tyre between y = {y_b + half:.4f} and {y_f - half:.4f} m")
    half = web["thickness_hub"] / 2 + web["fillet_hub"]
    _require(hub["y_inboard"] + half < web["y_hub"] < hub["y_outboard"] - half, "web.y_hub", web["y_hub"],
             f"a web (with fillets) meeting the hub between y = {hub['y_inboard'] + half:.4f} and "
             f"{hub['y_outboard'] - half:.4f} m")


def wheel_segments(p: dict) -> list[Segment]:
    """Named boundary segments of the cross-section in (r, Z).

    ``p['mount']['type']`` selects the section: 'clamped' (wheel alone, bore
    clamped) or 'axle' (wheel plus half axle from the wheelset centre plane to
    the axle box, bore bonded to the axle).
    """
    check_wheel(p)
    t, web, hub, m = p["tyre"], p["web"], p["hub"], p["mesh"]
    z_rc = p["axle"]["rolling_circle_z"]
    prof = tread_profile(p)
    y_b, y_f = prof["y_back"], prof["y_field"]
    r_hub, r_bore = hub["outer_radius"], hub["bore_radius"]
    gauge, field = _web_sides(p, r_hub, float(tyre_inner_radius(p, web["y_tyre"])))
    ft, fh = web["fillet_tyre"], web["fillet_hub"]

    # tyre inner surface and web sides with fillets, as (y, r) polylines
    hub_in = np.array([hub["y_inboard"], r_hub])
    hub_out = np.array([hub["y_outboard"], r_hub])
    tyre_b = np.array([y_b, float(tyre_inner_radius(p, y_b))])
    tyre_f = np.array([y_f, float(tyre_inner_radius(p, y_f))])
    g_hub = fillet(hub_in, gauge[0], gauge[1], fh, 6)
    g_tyre = fillet(gauge[-2], gauge[-1], tyre_b, ft, 6)
    f_tyre = fillet(tyre_f, field[-1], field[-2], ft, 6)
    f_hub = fillet(field[1], field[0], hub_out, fh, 6)
    web_gauge = np.vstack([g_hub, gauge[1:-1], g_tyre])
    web_field = np.vstack([f_tyre, field[-2:0:-1], f_hub])

    rz = lambda a: _yr_to_rz(np.asarray(a), z_rc)  # noqa: E731
    segs = [
        Segment("hub_outer", rz([hub_in, web_gauge[0]]), m["size_hub"]),
        Segment("web_gauge", rz(web_gauge), m["size_web"]),
        Segment("tyre_inner", rz([web_gauge[-1], tyre_b]), m["size_tyre"]),
        Segment("flange_back", rz(prof["points"][: np.argmax(prof["points"][:, 1]) + 1]), m["size_tread"]),
    ]
    top = int(np.argmax(prof["points"][:, 1]))
    tread_pts = prof["points"][top:]
    y_root = prof["y_root"]
    split = int(np.searchsorted(tread_pts[:, 0], y_root + 0.5 * p["flange"]["root_radius"]))
    segs += [
        Segment("flange", rz(tread_pts[: split + 1]), m["size_tread"]),
        Segment("tread", rz(tread_pts[split:]), m["size_tread"]),
        Segment("field_face", rz([tread_pts[-1], tyre_f]), m["size_tyre"]),
        Segment("tyre_inner", rz([tyre_f, web_field[0]]), m["size_tyre"]),
        Segment("web_field", rz(web_field), m["size_web"]),
        Segment("hub_outer", rz([web_field[-1], hub_out]), m["size_hub"]),
    ]
    if p["mount"]["type"] == "clamped":
        segs += [
            Segment("hub_outboard", rz([hub_out, [hub["y_outboard"], r_bore]]), m["size_hub"]),
            Segment("bore", rz([[hub["y_outboard"], r_bore], [hub["y_inboard"], r_bore]]), m["size_hub"]),
            Segment("hub_inboard", rz([[hub["y_inboard"], r_bore], hub_in]), m["size_hub"]),
        ]
    else:
        ax = p["axle"]
        _require(ax["journal_radius"] < r_hub and ax["body_radius"] < r_hub, "axle.body_radius",
                 ax["body_radius"], f"axle radii below hub.outer_radius = {r_hub}")
        z_hi = z_rc + hub["y_inboard"]
        z_ho = z_rc + hub["y_outboard"]
        z_end = ax["journal_end_z"]
        z_j0 = z_end - ax["journal_length"]
        _require(z_hi > 0.05, "hub.y_inboard", hub["y_inboard"], "a hub outboard of the wheelset centre")
        _require(z_j0 > z_ho + 0.005, "axle.journal_end_z", z_end,
                 f"a journal (length {ax['journal_length']}) starting outboard of the hub face Z = {z_ho:.4f} m")
        rb, rj = ax["body_radius"], ax["journal_radius"]
        sa = m["size_axle"]
        segs += [
            Segment("hub_outboard", np.array([[r_hub, z_ho], [rj, z_ho]]), m["size_hub"]),
            Segment("axle_outboard", np.array([[rj, z_ho], [rj, z_j0]]), sa),
            Segment("journal", np.array([[rj, z_j0], [rj, z_end]]), sa),
            Segment("axle_end", np.array([[rj, z_end], [0.0, z_end]]), sa),
            Segment("axis", np.array([[0.0, z_end], [0.0, 0.0]]), sa),
            Segment("midplane", np.array([[0.0, 0.0], [rb, 0.0]]), sa),
            Segment("axle_body", np.array([[rb, 0.0], [rb, z_hi]]), sa),
            Segment("hub_inboard", np.array([[rb, z_hi], [r_hub, z_hi]]), m["size_hub"]),
        ]
        # rotate the list so it starts at the axis: order does not matter for meshing
    poly = closed_polygon(segs)
    check_simple(poly, key="wheel outline")
    return segs


def web_centreline(p: dict, num: int = 40) -> np.ndarray:
    """(r, Z) samples along the web centreline from the hub surface up through
    the tyre to the rolling radius: the line on which nodal circles are
    counted."""
    t, w, hub = p["tyre"], p["web"], p["hub"]
    r_in = float(tyre_inner_radius(p, w["y_tyre"]))
    c0 = np.array([w["y_hub"], hub["outer_radius"]])
    c2 = np.array([w["y_tyre"], r_in])
    c1 = 0.5 * (c0 + c2) + np.array([w["bulge"], 0.0])
    web = bezier(c0, c1, c2, num)
    r_top = t["rolling_radius"] - t["conicity"] * w["y_tyre"] - 0.001
    tyre = np.column_stack([np.full(8, w["y_tyre"]), np.linspace(r_in, r_top, 8)])
    return _yr_to_rz(np.vstack([web, tyre[1:]]), p["axle"]["rolling_circle_z"])


def surface_radii(p: dict) -> dict:
    """Radii and widths the radiation model needs (SPEC 5), from the
    parameters: rolling radius r, tyre width w, web thickness, inner tyre
    radius r_in, hub radius."""
    t = p["tyre"]
    return {
        "r": t["rolling_radius"],
        "w": t["width"],
        "w_web": 0.5 * (p["web"]["thickness_tyre"] + p["web"]["thickness_hub"]),
        "r_in": float(tyre_inner_radius(p, 0.5 * (t["width"] - 2 * t["back_offset"]))),
        "r_hub": p["hub"]["outer_radius"],
    }
