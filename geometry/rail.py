"""Parametric flat-bottom (Vignole) rail cross-section with a rail pad.

Coordinates of the section (SPEC 2, rail frame): y = y^R lateral from the
rail centre line, positive toward the field side; z = z^R vertical, positive
UP, measured from the underside of the rail foot (z = 0).  The pad is a layer
-t_pad <= z <= 0 under the foot, standing on rigid ground (its underside is
clamped).  The rail is symmetric about y = 0, so the mesh covers the half
section y >= 0 only: the waveguide solver treats the symmetric and the
antisymmetric wave families separately (``solvers.rail.waveguide``), which halves
the problem size and makes the family of every wave exact.

The parameter file (``geometry/rails/<name>.toml``) gives the published
nominal dimensions (EN 13674-1 style: rail height, head width, head depth E,
foot depth F, web thickness, foot width, foot edge thickness) and the head
running profile (crown radius R1 over |y| <= crown_half_width, shoulder
radius R2, gauge-corner radius R3, tangent to each other and to the head
side, vertical or widening downward at ``side_taper``).  Fillets and slopes not printed in the published tables are
parameters too; they were chosen so that the section properties (area, mass,
second moments) match the published values (tests/rail/test_section.py).

``rail_half_outline(p)`` and ``head_profile(p, y)`` are pure; ``check_rail(p)``
raises ``GeometryError(key, value, allowed)`` before any meshing;
``geometry.rail_mesh.mesh_rail(p, path)`` writes a two-region Gmsh mesh
(physical surface 1 = rail steel, 2 = pad) whose regions share the foot/pad
interface line.  Reading the parameter file is the pipeline's
(``pipeline.stages.rail_io.load_rail``, ``pipeline.stages.rail.load_rail_params``).
"""
from __future__ import annotations

import numpy as np

from geometry.outline import GeometryError, Segment, check_simple, fillet

# physical tags of the two regions (cell tags in dolfinx)
RAIL_TAG = 1
PAD_TAG = 2
# physical curve names (facet tags); the numbers are fixed so that solvers can rely on them
CURVE_TAGS = {
    "running_surface": 1,  # crown, shoulder and gauge-corner arcs
    "rail_surface": 2,  # the rest of the free steel surface (head side, underside, web, foot top and edge)
    "foot_pad": 3,  # steel/pad interface (foot underside over the pad width)
    "foot_free": 4,  # foot underside beyond the pad (only when the pad is narrower than the foot)
    "symmetry": 5,  # y = 0 (rail and pad)
    "pad_side": 6,
    "pad_bottom": 7,  # on rigid ground: clamped
}


def _require(cond: bool, key: str, value, allowed: str) -> None:
    if not cond:
        raise GeometryError(key, value, allowed)


# --------------------------------------------------------------------------- head running profile
def crown_arcs(p: dict) -> dict:
    """Centres, radii and angular ranges of the three tangent head arcs.

    Angles are measured from the vertical (theta = 0 at the crown top); a
    point of arc j is c_j + R_j (sin theta, cos theta).  The corner arc ends
    at theta = pi/2 - atan(side_taper), tangent to the head side, which
    widens downward at the taper (1:20 on 60E1) and is vertical for a zero
    taper; ``head.width`` is the width at that tangent point (EN 13674-1
    drawing convention, as in the 60E1/UIC60 profile file CONTACT ships,
    docs/validation/15_profiles.md).
    """
    H = p["section"]["height"]
    hd = p["head"]
    R1, R2, R3 = hd["crown_radius"], hd["shoulder_radius"], hd["corner_radius"]
    y1 = hd["crown_half_width"]
    half = hd["width"] / 2
    _require(R1 > R2 > R3 > 0, "head.shoulder_radius", R2,
             f"crown_radius > shoulder_radius > corner_radius > 0 (got {R1}, {R2}, {R3})")
    _require(0 < y1 < min(R1, half - R3), "head.crown_half_width", y1,
             f"0 < crown_half_width < min(crown_radius, head.width/2 - corner_radius) = {min(R1, half - R3):.4g}")
    th1 = np.arcsin(y1 / R1)
    alpha = np.arctan(hd.get("side_taper", 0.0))
    s2 = (half - R3 * np.cos(alpha) - (R1 - R2) * np.sin(th1)) / (R2 - R3)
    _require(np.sin(th1) < s2 < 1.0, "head.width", hd["width"],
             "a head width that the crown, shoulder and corner arcs can span tangentially "
             f"(shoulder end sin(theta) = {s2:.3f} must lie between {np.sin(th1):.3f} and 1)")
    th2 = np.arcsin(s2)
    c1 = np.array([0.0, H - R1])
    c2 = c1 + (R1 - R2) * np.array([np.sin(th1), np.cos(th1)])
    c3 = c2 + (R2 - R3) * np.array([np.sin(th2), np.cos(th2)])
    th3 = np.pi / 2 - alpha  # the corner arc ends tangent to the head side, which widens downward
    side_top = c3 + R3 * np.array([np.sin(th3), np.cos(th3)])
    return {"c": [c1, c2, c3], "R": [R1, R2, R3], "theta": [0.0, th1, th2, np.pi / 2, th3],
            "y_breaks": [0.0, y1, c2[0] + R2 * np.sin(th2), half], "side_top": side_top,
            "side_top_z": float(side_top[1]), "side_dir": np.array([np.sin(alpha), -np.cos(alpha)])}


def head_profile(p: dict, y) -> np.ndarray:
    """Height z^R (m, up, from the foot underside) of the rail-head running
    surface at lateral position y^R (m from the rail centre line, positive to
    the field side; the profile is symmetric).  Vectorised; NaN outside the
    head, |y| > head.width/2.  This is the undeformed rail surface the
    contact stage needs (SPEC 4.1): the drop below the crown top is
    ``p['section']['height'] - head_profile(p, y)``."""
    a = crown_arcs(p)
    y = np.abs(np.asarray(y, dtype=float))
    z = np.full(y.shape, np.nan)
    for j in range(3):
        lo, hi = a["y_breaks"][j], a["y_breaks"][j + 1]
        sel = (y >= lo) & (y <= hi) & np.isnan(z)
        c, R = a["c"][j], a["R"][j]
        dy = np.clip(y[sel] - c[0], -R, R)
        z[sel] = c[1] + np.sqrt(R * R - dy * dy)
    return z


def head_slope(p: dict, y) -> np.ndarray:
    """dz/dy of the running surface (the contact angle is arctan of it)."""
    y = np.asarray(y, dtype=float)
    h = 1e-7
    return (head_profile(p, y + h) - head_profile(p, y - h)) / (2 * h)


# --------------------------------------------------------------------------- checks
def _num(p, sect, key, lo=0.0, hi=np.inf, unit="m"):
    v = p[sect][key]
    _require(isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) and lo < v < hi,
             f"{sect}.{key}", v, f"a number in ({lo:g}, {hi:g}) {unit}")
    return float(v)


def check_rail(p: dict) -> None:
    """Dimension checks that make a valid section (raised before meshing)."""
    H = _num(p, "section", "height", 0.05, 0.3)
    w = _num(p, "head", "width", 0.02, 0.15)
    dh = _num(p, "head", "depth", 0.01, 0.1)
    tw = _num(p, "web", "thickness", 0.005, 0.05)
    b = _num(p, "foot", "width", 0.05, 0.3)
    df = _num(p, "foot", "thickness_web", 0.005, 0.08)
    te = _num(p, "foot", "thickness_edge", 0.002, 0.05)
    sh = _num(p, "head", "underside_slope", 0.0, 1.5, "(tan)")
    for k in ("crown_radius", "shoulder_radius", "corner_radius", "crown_half_width"):
        _num(p, "head", k, 0.0, 2.0)
    for sect, k in (("head", "underside_radius"), ("head", "web_fillet"), ("foot", "web_fillet"),
                    ("foot", "edge_radius"), ("foot", "bottom_radius")):
        _num(p, sect, k, -1e-12, 0.2)
    _require(tw < w, "web.thickness", tw, f"a web thinner than the head width {w}")
    _require(w < b, "head.width", w, f"a head narrower than the foot width {b}")
    _require(te < df, "foot.thickness_edge", te, f"a foot edge thinner than the foot at the web ({df})")
    _require(dh + df < H - 0.01, "head.depth", dh,
             f"head.depth + foot.thickness_web < height - 10 mm (web at least 10 mm high; height {H}, foot {df})")
    _num(p, "head", "side_taper", -1e-12, 0.3, "(tan)")
    a = crown_arcs(p)
    z_under_side = _key_points(p)["head_corner"][1]
    _require(z_under_side < a["side_top_z"] - 0.002, "head.depth", dh,
             f"a head deep enough that its side (below the corner arc at z = {a['side_top_z']:.4f}) "
             f"meets the underside (at z = {z_under_side:.4f}) at least 2 mm lower")
    _num(p, "pad", "thickness", 0.0005, 0.05)
    bp = _num(p, "pad", "width", 0.01, 0.3)
    _require(bp <= b + 1e-12, "pad.width", bp, f"a pad no wider than the foot ({b})")
    _num(p, "pad", "stiffness", 1e6, 1e11, "N/m^2")
    _num(p, "pad", "loss_factor", -1e-12, 2.0)
    _num(p, "pad", "poisson", -1e-12, 0.49, "")
    _num(p, "pad", "rho", 1.0, 1e4, "kg/m^3")
    for k, lo, hi in (("E", 1e9, 1e12), ("nu", 0.0, 0.49), ("rho", 100.0, 3e4)):
        _num(p, "material", k, lo, hi, "SI")
    _num(p, "material", "loss_factor", -1e-12, 1.0, "")
    for k in ("size_head", "size_web", "size_foot"):
        _num(p, "mesh", k, 2e-4, 0.05)
    nl = p["mesh"].get("pad_layers", 2)
    _require(isinstance(nl, int) and not isinstance(nl, bool) and 1 <= nl <= 20, "mesh.pad_layers", nl,
             "an integer 1 ... 20 (element layers through the pad)")
    ys = p.get("contact", {}).get("y", [])
    for y in ys:
        _require(abs(y) < a["y_breaks"][2], "contact.y", y,
                 f"contact points on the crown or shoulder arcs, |y| < {a['y_breaks'][2]:.4f} m")
    # the straight legs must be long enough for the fillets at both their ends
    rail_half_outline(p)


# --------------------------------------------------------------------------- outline
def _tangent_length(p_prev, corner, p_next, r):
    d1 = np.asarray(p_prev, float) - corner
    d2 = np.asarray(p_next, float) - corner
    c = np.clip(d1 @ d2 / (np.linalg.norm(d1) * np.linalg.norm(d2)), -1, 1)
    th = np.arccos(c)
    return 0.0 if r <= 0 else r / np.tan(th / 2)


def _key_points(p: dict) -> dict:
    H = p["section"]["height"]
    hd, web, ft = p["head"], p["web"], p["foot"]
    w2, t2, b2 = hd["width"] / 2, web["thickness"] / 2, ft["width"] / 2
    a = crown_arcs(p)
    # head side (through the end of the corner arc, tapered) meets the underside line
    P0, d = a["side_top"], a["side_dir"]
    s_u = hd["underside_slope"]
    Q0 = np.array([t2, H - hd["depth"]])
    # P0 + s d = Q0 + u (1, s_u)
    mat = np.array([[d[0], -1.0], [d[1], -s_u]])
    s_par, _ = np.linalg.solve(mat, Q0 - P0)
    head_corner = P0 + s_par * d
    return {
        "side_top": P0,
        "head_corner": head_corner,
        "head_web": np.array([t2, H - hd["depth"]]),
        "foot_web": np.array([t2, ft["thickness_web"]]),
        "foot_edge_top": np.array([b2, ft["thickness_edge"]]),
        "foot_edge_bottom": np.array([b2, 0.0]),
        "centre_bottom": np.array([0.0, 0.0]),
    }


def running_surface(p: dict, contact_y=(), n_crown: int = 5, n_shoulder: int = 7, n_corner: int = 7) -> np.ndarray:
    """Polyline of the running surface from the crown top (y = 0) to the top
    of the vertical head side (y = width/2), with vertices at the given
    contact positions |y| (so mesh nodes sit exactly there)."""
    a = crown_arcs(p)
    yb = a["y_breaks"]
    ys = np.concatenate([np.linspace(0, yb[1], n_crown), np.linspace(yb[1], yb[2], n_shoulder)[1:],
                         np.abs(np.asarray(contact_y, float))])
    ys = np.unique(np.round(ys, 10))
    # drop vertices closer than 0.6 mm to a contact vertex (keeps edges regular)
    cy = np.abs(np.asarray(contact_y, float))
    keep = [y for y in ys if np.all((np.abs(cy - y) > 6e-4) | (np.abs(cy - y) < 1e-10)) or y in (0.0,)]
    ys = np.array(sorted(set(keep)))
    ys = ys[ys <= yb[2] + 1e-12]
    pts = np.column_stack([ys, head_profile(p, ys)])
    c3, R3 = a["c"][2], a["R"][2]
    th = np.linspace(a["theta"][2], a["theta"][4], n_corner)[1:]
    th = np.unique(np.concatenate([th, [np.pi / 2]]))  # the arc's outermost point is a vertex
    th = th[th <= a["theta"][4]]
    corner = np.column_stack([c3[0] + R3 * np.sin(th), c3[1] + R3 * np.cos(th)])
    return np.vstack([pts, corner])


def rail_half_outline(p: dict, contact_y=None) -> list[Segment]:
    """Named segments of the half section y >= 0, clockwise from the crown
    top: running_surface, rail_surface (head side ... foot edge), foot
    underside (split at the pad edge into foot_pad and foot_free), symmetry.
    Raises GeometryError when fillets do not fit their legs."""
    if contact_y is None:
        contact_y = p.get("contact", {}).get("y", [])
    kp = _key_points(p)
    hd, ft = p["head"], p["foot"]
    run = running_surface(p, contact_y)
    corners = [  # (name, corner point, radius, parameter key)
        ("head_corner", kp["head_corner"], hd["underside_radius"], "head.underside_radius"),
        ("head_web", kp["head_web"], hd["web_fillet"], "head.web_fillet"),
        ("foot_web", kp["foot_web"], ft["web_fillet"], "foot.web_fillet"),
        ("foot_edge_top", kp["foot_edge_top"], ft["edge_radius"], "foot.edge_radius"),
        ("foot_edge_bottom", kp["foot_edge_bottom"], ft["bottom_radius"], "foot.bottom_radius"),
    ]
    chain = [run[-1]] + [c[1] for c in corners] + [kp["centre_bottom"]]
    tl = [_tangent_length(chain[i], chain[i + 1], chain[i + 2], corners[i][2]) for i in range(len(corners))]
    # each straight leg between two corners must hold both tangent lengths
    for i in range(len(chain) - 1):
        leg = np.linalg.norm(chain[i + 1] - chain[i])
        used = (tl[i - 1] if 1 <= i <= len(corners) else 0.0) + (tl[i] if i < len(corners) else 0.0)
        if used > 0.95 * leg:
            key = corners[min(i, len(corners) - 1)][3]
            val = corners[min(i, len(corners) - 1)][2]
            raise GeometryError(key, val, f"fillet radii that fit the {leg * 1e3:.1f} mm straight edge "
                                f"(tangent lengths {used * 1e3:.1f} mm); reduce this radius or its neighbour")
    side = [run[-1]]
    for i, (name, corner, r, key) in enumerate(corners):
        arc = fillet(chain[i], corner, chain[i + 2], r, num=6)
        side.extend(list(arc))
    side.append(kp["centre_bottom"])
    side = np.array(side)
    # split the foot underside at the pad edge
    b2 = p["foot"]["width"] / 2
    bp2 = p["pad"]["width"] / 2
    bottom_start = side[-2]  # end of the bottom-corner fillet (z = 0)
    segs = [Segment("running_surface", run)]
    segs.append(Segment("rail_surface", side[:-1]))
    if bp2 < bottom_start[0] - 1e-9:
        segs.append(Segment("foot_free", np.array([bottom_start, [bp2, 0.0]])))
        segs.append(Segment("foot_pad", np.array([[bp2, 0.0], [0.0, 0.0]])))
    else:
        _require(bp2 >= bottom_start[0] - 1e-9 and bp2 <= b2 + 1e-12, "pad.width", p["pad"]["width"],
                 "a pad width within the flat part of the foot underside or equal to the foot width")
        segs.append(Segment("foot_pad", np.array([bottom_start, [0.0, 0.0]])))
    segs.append(Segment("symmetry", np.array([[0.0, 0.0], [0.0, p["section"]["height"]]])))
    poly = np.vstack([s.points[:-1] for s in segs])
    check_simple(poly, "rail outline")
    return segs


def full_outline(p: dict) -> np.ndarray:
    """Closed polygon (k, 2) of the whole rail section (both halves, no pad),
    counter-clockwise, no repeated closing vertex."""
    segs = rail_half_outline(p)
    body = [s for s in segs if s.name != "symmetry"]
    right = np.vstack([s.points[:-1] for s in body] + [body[-1].points[-1:]])  # (0, H) ... (0, 0)
    left = right[::-1].copy()
    left[:, 0] *= -1
    poly = np.vstack([right[:-1], left[:-1]])  # (0,H) -> ... -> (0,0) -> mirror ... -> back to (0,H)
    # make it counter-clockwise
    area2 = np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - np.roll(poly[:, 0], -1) * poly[:, 1])
    return poly if area2 > 0 else poly[::-1]


def section_properties(p: dict) -> dict:
    """Exact polygon properties of the steel section (SI units):
    area, mass per metre, centroid height z_c, second moments I_y (vertical
    bending, about the horizontal centroidal axis) and I_z (lateral bending,
    about the vertical axis y = 0), polar I_p = I_y + I_z about the centroid,
    and the pad stiffness per unit length as given."""
    P = full_outline(p)
    x, y = P[:, 0], P[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cr = x * yn - xn * y
    A = 0.5 * cr.sum()
    cy = ((y + yn) * cr).sum() / (6 * A)
    Ixx0 = ((y * y + y * yn + yn * yn) * cr).sum() / 12  # about z = 0
    Iyy = ((x * x + x * xn + xn * xn) * cr).sum() / 12  # about y = 0
    Iv = Ixx0 - A * cy * cy
    rho = p["material"]["rho"]
    return {"area": A, "mass_per_m": rho * A, "z_centroid": cy, "I_vertical": Iv, "I_lateral": Iyy,
            "I_polar": Iv + Iyy, "height": p["section"]["height"]}
