"""Gmsh mesh of the rail's half section with its pad (two regions, conforming at the foot/pad
interface), from the parameters of ``geometry.rail`` (SPEC 3.2)."""
from __future__ import annotations

import numpy as np

from geometry.rail import CURVE_TAGS, PAD_TAG, RAIL_TAG, check_rail, rail_half_outline


def mesh_rail(p: dict, path: str, verbose: bool = False) -> dict:
    """Mesh the half section (rail steel + pad) with triangles and write
    ``path`` (.msh 4.1).  Physical surfaces: RAIL_TAG = 1 (steel), PAD_TAG = 2
    (pad); physical curves as in CURVE_TAGS.  The two regions share the
    foot/pad interface lines (conforming mesh).  Returns CURVE_TAGS for the
    names present.  Calls check_rail first."""
    import gmsh  # lazy: brings in gmsh

    check_rail(p)
    segs = rail_half_outline(p)
    ms = p["mesh"]
    H = p["section"]["height"]
    z_head = H - p["head"]["depth"]
    z_foot = p["foot"]["thickness_web"]
    t_pad = p["pad"]["thickness"]

    def size_at(xy):
        z = xy[1]
        if z < 0:
            return min(ms["size_foot"], t_pad / max(ms.get("pad_layers", 2), 1))
        if z >= z_head - 0.004:
            return ms["size_head"]
        if z <= z_foot + 0.004:
            return ms["size_foot"]
        return ms["size_web"]

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.model.add("rail")
        geo = gmsh.model.geo
        pts: dict[tuple, int] = {}

        def point(xy):
            key = (round(float(xy[0]), 9), round(float(xy[1]), 9))
            if key not in pts:
                pts[key] = geo.addPoint(key[0], key[1], 0.0, size_at(key))
            return pts[key]

        lines: dict[tuple, int] = {}
        groups: dict[str, list[int]] = {}

        def line(a, b, name):
            ta, tb = point(a), point(b)
            if (tb, ta) in lines:
                tag = -lines[(tb, ta)]
            else:
                tag = lines.setdefault((ta, tb), geo.addLine(ta, tb))
                groups.setdefault(name, []).append(tag)
            return tag

        def polyline(points, name):
            return [line(points[i], points[i + 1], name) for i in range(len(points) - 1)]

        # rail loop (clockwise as built; gmsh does not care)
        rail_loop = []
        for s in segs:
            if s.name == "symmetry":
                # subdivide the symmetry line at the head and foot levels for size grading
                zs = [0.0, z_foot, 0.5 * (z_foot + z_head), z_head, H]
                rail_loop += polyline(np.array([[0.0, z] for z in zs]), "symmetry")
            else:
                rail_loop += polyline(s.points, s.name)
        # pad loop: interface (0,0)->(bp2,0) reuses the rail lines reversed
        iface = [s for s in segs if s.name == "foot_pad"][0].points  # from (bp2, 0) to (0, 0)
        bp2 = float(iface[0][0])  # the pad covers the flat part of the foot underside
        pad_loop = polyline(iface[::-1], "foot_pad")
        pad_loop += polyline(np.array([[bp2, 0.0], [bp2, -t_pad]]), "pad_side")
        pad_loop += polyline(np.array([[bp2, -t_pad], [0.0, -t_pad]]), "pad_bottom")
        pad_loop += polyline(np.array([[0.0, -t_pad], [0.0, 0.0]]), "symmetry")
        l_rail = geo.addCurveLoop(rail_loop)
        l_pad = geo.addCurveLoop(pad_loop)
        s_rail = geo.addPlaneSurface([l_rail])
        s_pad = geo.addPlaneSurface([l_pad])
        geo.synchronize()
        names = {}
        for name, tags in groups.items():
            ptag = CURVE_TAGS[name]
            gmsh.model.addPhysicalGroup(1, tags, ptag)
            gmsh.model.setPhysicalName(1, ptag, name)
            names[name] = ptag
        gmsh.model.addPhysicalGroup(2, [s_rail], RAIL_TAG)
        gmsh.model.setPhysicalName(2, RAIL_TAG, "rail")
        gmsh.model.addPhysicalGroup(2, [s_pad], PAD_TAG)
        gmsh.model.setPhysicalName(2, PAD_TAG, "pad")
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.CharacteristicLengthExtendFromBoundary", 1)
        gmsh.model.mesh.generate(2)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.write(str(path))
        return names
    finally:
        gmsh.finalize()
