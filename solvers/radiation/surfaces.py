"""Radiating surfaces of a wheel in the Thompson-Jones model (SPEC 5; thesis
[4.46]-[4.53]): the axial annuli, the radial and torsional surfaces, the
cancellation factor Gamma, and which section boundary nodes belong to each
surface.  The choices (both faces counted, annulus radii, web thickness at the
tyre) are stated in ``solvers.radiation.thompson_jones``'s module notes.  Pure functions
on arrays.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from solvers.radiation.thompson_jones import gamma_cancellation

AXIAL_SIDE_SEGMENTS = ("web_gauge", "web_field", "flange_back", "field_face", "hub_inboard", "hub_outboard")
RADIAL_SEGMENTS = ("tread", "flange", "tyre_inner")
TYRE_SEGMENTS = ("tread", "flange", "flange_back", "field_face", "tyre_inner")


# --------------------------------------------------------------------------
# surfaces [4.51]-[4.53]
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class Surfaces:
    """Radiating surfaces of a wheel (SI).  ``radii`` = r_1 .. r_6 of the axial
    annuli, ``S_a`` their areas (``faces`` faces each), ``S_r`` radial [4.52],
    ``S_t`` torsional (m^4) [4.53], ``S_out``/``S_in`` [4.47]-[4.48], ``gamma`` [4.46]."""
    r: float
    w: float
    w_web: float
    r_in: float
    radii: np.ndarray
    S_a: np.ndarray
    S_r: float
    S_t: float
    S_out: float
    S_in: float
    gamma: float
    faces: int
    web_thickness_rule: str = ""


def annulus_radii(r_hub: float, r_in: float, r: float, n_web: int = 4) -> np.ndarray:
    """r_1 = r_hub < r_2 < ... < r_5 = r_in < r_6 = r: the web divided into
    ``n_web`` rings of equal radial width, then the tyre side faces."""
    if not r_hub < r_in < r:
        raise ValueError(f"need r_hub < r_in < r, got {r_hub}, {r_in}, {r}")
    return np.append(np.linspace(r_hub, r_in, n_web + 1), r)


def _segments_by_name(segments) -> dict:
    """{name: [points (k, 2) in (r, Z)]} from Segment objects, (name, points)
    pairs or a dict {name: points or [points, ...]}."""
    out: dict = {}
    if isinstance(segments, Mapping):
        for k, v in segments.items():
            arrs = v if isinstance(v, (list, tuple)) else [v]
            out.setdefault(k, []).extend(np.asarray(a, dtype=float) for a in arrs)
        return out
    for s in segments:
        name, pts = (s.name, s.points) if hasattr(s, "name") else s
        out.setdefault(name, []).append(np.asarray(pts, dtype=float))
    return out


def web_thickness_profile(segments, num: int = 200):
    """Axial thickness of the web, t(r) = Z_field(r) - Z_gauge(r), from the
    outline segments ``web_gauge`` and ``web_field`` (points in (r, Z)).
    Returns (r, t) on ``num`` radii spanning both sides."""
    seg = _segments_by_name(segments)
    g = np.vstack(seg["web_gauge"])
    fd = np.vstack(seg["web_field"])
    lo = max(g[:, 0].min(), fd[:, 0].min())
    hi = min(g[:, 0].max(), fd[:, 0].max())
    rr = np.linspace(lo, hi, num)

    def z_of_r(p):
        # both sides are monotone in r away from the end fillets' turning points;
        # np.interp needs increasing r: sort, dropping duplicate radii
        o = np.argsort(p[:, 0], kind="stable")
        r_s, z_s = p[o, 0], p[o, 1]
        keep = np.append(np.diff(r_s) > 0, True)
        return np.interp(rr, r_s[keep], z_s[keep])

    return rr, np.abs(z_of_r(fd) - z_of_r(g))


def radiation_surfaces(radii: Mapping, segments=None, *, web_thickness="tyre", faces: int = 2,
                       n_web: int = 4) -> Surfaces:
    """Surfaces of the Thompson-Jones model from the geometry.

    ``radii``: a dict like ``geometry.wheel.surface_radii(p)``: r (nominal
    rolling radius), w (tyre width), w_web (web thickness, mean), r_in (inner
    tyre radius = r_5), r_hub (hub outer radius = r_1).
    ``segments``: the outline (``geometry.wheel.wheel_segments(p)``), used to
    measure the web thickness where the web meets the tyre.
    ``web_thickness``: 'tyre' (default; needs ``segments``: smallest axial web
    thickness over r_4 <= r <= r_5 on the outline), 'mean' (``radii['w_web']``)
    or a number in m.
    ``faces``: 2 (default, both faces of web and tyre radiate; see the module
    docstring) or 1.

    S_aq = faces * pi (r_{q+1}^2 - r_q^2), q = 1..5 (SPEC 5 / [4.51] corrected to an area);
    S_r = 2 pi [r w + r_5 (w - w_web)] [4.52];
    S_t = (pi/6) [r w^3 + r_5 (w^3 - w_web^3) + (r + r_5)(r - r_5)^3] [4.53] (m^4).
    """
    if faces not in (1, 2):
        raise ValueError("faces must be 1 or 2")
    r, w, r5, r1 = (float(radii[k]) for k in ("r", "w", "r_in", "r_hub"))
    rq = annulus_radii(r1, r5, r, n_web)
    if isinstance(web_thickness, str):
        if web_thickness == "mean":
            w_web, rule = float(radii["w_web"]), "mean (radii['w_web'])"
        elif web_thickness == "tyre":
            if segments is None:
                raise ValueError("web_thickness='tyre' needs the outline segments")
            rr, t = web_thickness_profile(segments)
            sel = (rr >= rq[n_web - 1]) & (rr <= rq[n_web])
            w_web, rule = float(t[sel].min()), "tyre (min axial web thickness over r_4..r_5 on the outline)"
        else:
            raise ValueError(f"web_thickness: 'tyre', 'mean' or a number, got {web_thickness!r}")
    else:
        w_web, rule = float(web_thickness), "given"
    if not 0 < w_web < w:
        raise ValueError(f"web thickness {w_web} must lie in (0, tyre width {w})")
    S_a = faces * np.pi * np.diff(rq**2)
    S_r = 2 * np.pi * (r * w + r5 * (w - w_web))
    S_t = np.pi / 6 * (r * w**3 + r5 * (w**3 - w_web**3) + (r + r5) * (r - r5) ** 3)
    S_out, S_in = 2 * np.pi * r * w, 2 * np.pi * r5 * (w - w_web)
    return Surfaces(r=r, w=w, w_web=w_web, r_in=r5, radii=rq, S_a=S_a, S_r=float(S_r), S_t=float(S_t),
                    S_out=float(S_out), S_in=float(S_in), gamma=gamma_cancellation(r, w, r5, w_web),
                    faces=faces, web_thickness_rule=rule)


# --------------------------------------------------------------------------
# surface nodes
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class SurfaceNodes:
    """Section node indices of each radiating surface: ``axial[q]`` for the
    annulus r_{q+1}..r_{q+2} (0-based q), ``radial`` (tread, flange, tyre inner),
    ``tyre`` (tyre outline, for the optional torsion term)."""
    axial: tuple
    radial: np.ndarray
    tyre: np.ndarray


def _boundary(boundary: Mapping, names) -> np.ndarray:
    """Union of the node indices of the named segments; keys 'tread' or
    'boundary_tread' (the modal artifact itself works as the mapping)."""
    idx = []
    for k in names:
        for key in (k, "boundary_" + k):
            if key in boundary:
                idx.append(np.asarray(boundary[key], dtype=int))
                break
    return np.unique(np.concatenate(idx)) if idx else np.zeros(0, dtype=int)


def surface_nodes(points, boundary: Mapping, surfaces: Surfaces, tol: float = 1e-9) -> SurfaceNodes:
    """Assign boundary nodes to surfaces.

    ``points`` (nodes, 2) = (r, Z); ``boundary`` {segment name: node indices},
    keys 'web_gauge' or 'boundary_web_gauge' (the modal artifact works as is).
    Axial: nodes of web_gauge, web_field, flange_back, field_face and the hub
    faces with r >= r_1, binned by radius into the annuli (r_q <= r < r_{q+1};
    r >= r_6, i.e. the flange back, goes to the outer annulus).  Radial: tread,
    flange and tyre_inner nodes.  A node on a corner between an axial and a
    radial segment belongs to both (it carries both velocity components)."""
    pts = np.asarray(points, dtype=float)
    rq = surfaces.radii
    ax = _boundary(boundary, AXIAL_SIDE_SEGMENTS)
    ax = ax[pts[ax, 0] >= rq[0] - tol]
    q = np.clip(np.searchsorted(rq, pts[ax, 0] + tol, side="right") - 1, 0, len(rq) - 2)
    axial = tuple(ax[q == k] for k in range(len(rq) - 1))
    return SurfaceNodes(axial=axial, radial=_boundary(boundary, RADIAL_SEGMENTS),
                        tyre=_boundary(boundary, TYRE_SEGMENTS))
