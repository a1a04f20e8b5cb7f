"""Sound radiation of the wheel: the Thompson-Jones model as used in TWINS
(SPEC section 5; thesis section 4.4, equations [4.38]-[4.57]).

Pure functions on arrays: no file or configuration I/O.  The pipeline loads
the wheel's modal artifact and geometry and calls these.

Model
-----
Sound power per frequency, summed over the harmonics n (nodal diameters)
[4.38]::

    W(f) = rho c0 sum_n [ sigma_a(n,f) sum_q S_aq <v_aq^2>(n,f)
                          + sigma_r(n,f) S_r <v_r^2>(n,f)
                          (+ sigma_t(f) S_t <v_t^2>(n,f), neglected by default) ]

* radiation efficiencies [4.39]-[4.50]: ``sigma_axial``, ``sigma_radial``,
  ``sigma_torsion`` (vectorised over n and f by broadcasting);
* surfaces [4.51]-[4.53]: ``radiation_surfaces`` from the geometry
  (``geometry.wheel.surface_radii`` plus the named outline segments);
* which boundary nodes make up each surface: ``surface_nodes``;
* velocities [4.54]-[4.57]: ``surface_velocities`` from a private modal sum
  (only the modes of harmonic n in the harmonic-n receptance);
* sound power: ``sound_power`` for given contact-force spectra and
  ``unit_force_power`` for a unit force at the contact point (the curve a
  designer compares wheels with).

Choices (documented where they are made)
----------------------------------------
* Axial annuli: BOTH faces of the wheel are counted, S_aq = 2 pi (r_{q+1}^2 -
  r_q^2) (``faces=2``).  The axial motion of web and tyre moves both the
  gauge-side and the field-side faces, each radiating into its own half
  space; in the high-frequency limit sigma_a -> 1 each face radiates
  rho c0 S_face <v^2> independently, so the radiating area is that of both
  faces (counting one face would lose 3 dB).  The mean square <v_aq^2> is
  averaged over the nodes of both faces in the annulus.  [4.51] prints
  2 pi (r_{q+1} - r_q), which has the dimension of a length; SPEC 5 asks for the
  annulus area.
* Annulus radii: r_1 = hub outer radius, r_5 = inner tyre radius (from the
  radii dict), r_6 = r the nominal rolling radius; r_2, r_3, r_4 divide the
  web r_1..r_5 into four rings of equal radial width (the web is where the
  axial velocity changes most; the fifth annulus r_5..r_6 is the tyre's side
  faces, as in the thesis' Fig. 4.14).  The disc r < r_1 (hub, axle) is not
  counted [4.57].  Flange-back nodes above r_6 (the flange) are put in the
  outer annulus.
* Web thickness w_web in S_r, S_t and Gamma (a tapered web): by default the
  axial thickness of the web where it meets the tyre, measured on the outline
  (the smallest axial web thickness over the outer quarter of the web,
  r_4 <= r <= r_5, i.e. just below the tyre fillets).  w - w_web is the part of
  the tyre's inner surface the web does not cover, so the web's root, not its
  mean, is what matters.  ``web_thickness='mean'`` takes the dict's value
  (``surface_radii``: mean of hub and tyre thickness), a float is used as is.
* Rigid half-wheelset modes (kind bounce/roll/lateral, 7-15 Hz on the C20):
  included by default with their own damping ``zeta_suspension``: they are
  real motion of the wheel surfaces (a rigid axial translation radiates as
  an n = 0 axial motion, bounce/roll as n = 1), and below ~300 Hz their
  mass-line receptance is comparable to the flexible modes' stiffness line.
  ``rigid=False`` drops them.
* Modal damping [4.11]: zeta = 1e-3 (n = 0), 1e-2 (n = 1), 1e-4 (n >= 2), 1.0 for
  the (1,0,r) mode; rigid modes: zeta_suspension.
* Directions at the contact point (phi = 0, the cos twin of each harmonic):
  2 = lateral = +U_z (toward the field side), 3 = vertical = +U_r (radially
  outward = toward the ground at the contact).  The wheel receives -F
  (SPEC 2); the common sign does not change mean squares, so it is left out.
* Force amplitudes: <v^2> follows [4.56] literally (|v|^2 for n = 0, 0.5 |v|^2
  for n > 0; the 0.5 is the circumferential mean of cos^2 n phi).  That is a
  time mean square only if |F| (hence |v|) is an RMS amplitude, so
  ``sound_power`` expects RMS force amplitudes by default
  (``force_amplitude='rms'``); with ``'peak'`` the time-average factor 1/2 is
  applied.  The unit-force power is per N^2 (RMS): W / F_rms^2.
* Frequency resolution: the wheel's narrow peaks (zeta = 1e-4: -3 dB band
  2 zeta f_r, 0.09 Hz at 434 Hz) make G(f) F(f) on FFT bins (1/T apart)
  sensitive to where the bins fall relative to the modes; for unit-force
  curves use ``frequency_grid``, for a squeal tone evaluate at the
  interpolated tone frequency (``spectra.dominant_frequency``) as well.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

RHO_AIR = 1.21  # kg/m3 (SPEC 5)
C0 = 343.0  # m/s (SPEC 5)
W_REF = 1e-12  # W, reference sound power

AXIAL_SIDE_SEGMENTS = ("web_gauge", "web_field", "flange_back", "field_face", "hub_inboard", "hub_outboard")
RADIAL_SEGMENTS = ("tread", "flange", "tyre_inner")
TYRE_SEGMENTS = ("tread", "flange", "flange_back", "field_face", "tyre_inner")


# --------------------------------------------------------------------------
# radiation efficiencies [4.39]-[4.50]
# --------------------------------------------------------------------------
def kappa(n):
    """kappa(n) = 1.9 + 1.015 n - 0.0189 n^2 [4.41]."""
    n = np.asarray(n, dtype=float)
    return 1.9 + 1.015 * n - 0.0189 * n**2


def f_ca(n, r, c0=C0):
    """Axial critical frequency f_ca(n) = c0 kappa(n) / (2 pi r) [4.40]; r the nominal rolling radius."""
    return c0 * kappa(n) / (2 * np.pi * r)


def _ratio_pow(fc, f, p):
    """(fc / f)^p with f = 0 -> inf (efficiency 0 there), fc = 0 -> 0."""
    f = np.asarray(f, dtype=float)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        x = np.where(f > 0, fc / np.where(f > 0, f, 1.0), np.inf)
        return np.where(np.asarray(fc) == 0, 0.0, x**p)


def sigma_axial(n, f, r, c0=C0):
    """Axial radiation efficiency sigma_a = 1 / (1 + (f_ca(n)/f)^(2n+4)) [4.39].
    n and f broadcast against each other (e.g. n[:, None], f[None, :])."""
    n = np.asarray(n)
    return 1.0 / (1.0 + _ratio_pow(f_ca(n, r, c0), f, 2 * n + 4))


def radial_frequencies(n, r):
    """(f_r1(n), f_r2, f_r3(n)) = (120 n, 800, 280 + 150 n) / sqrt(r / 0.42) [4.43]-[4.45]."""
    n = np.asarray(n, dtype=float)
    s = np.sqrt(r / 0.42)
    return 120.0 * n / s, 800.0 / s + 0.0 * n, (280.0 + 150.0 * n) / s


def gamma_cancellation(r, w, r_in, w_web):
    """Gamma = sqrt((S_out - S_in) / (S_out + S_in)) with S_out = 2 pi r w,
    S_in = 2 pi r_in (w - w_web) [4.46]-[4.48]: cancellation between the tread and
    the tyre's inner surface (applies below f_r3)."""
    s_out, s_in = 2 * np.pi * r * w, 2 * np.pi * r_in * (w - w_web)
    return float(np.sqrt((s_out - s_in) / (s_out + s_in)))


def sigma_radial(n, f, r, gamma):
    """Radial radiation efficiency [4.42] with Gamma [4.46]:
    n = 0: Gamma / (1 + (f_r2/f)^2); n > 0: Gamma / (1 + (f_r1/f)^(2n)) / (1 + (f_r2/f)^2),
    where Gamma is the cancellation factor for f < f_r3(n) and 1 above.
    ``gamma`` from ``gamma_cancellation`` (or ``Surfaces.gamma``)."""
    n = np.asarray(n)
    f = np.asarray(f, dtype=float)
    fr1, fr2, fr3 = radial_frequencies(n, r)
    g = np.where(f < fr3, gamma, 1.0)
    t1 = np.where(n == 0, 1.0, 1.0 / (1.0 + _ratio_pow(fr1, f, 2 * n)))
    return g * t1 / (1.0 + _ratio_pow(fr2, f, 2))


def f_ct(w, c0=C0):
    """Torsional critical frequency f_ct = 2 c0 / (pi w) [4.50]; w the tyre width."""
    return 2 * c0 / (np.pi * w)


def sigma_torsion(f, w, c0=C0):
    """Torsional radiation efficiency sigma_t = 1 / (1 + (f_ct/f)^4) [4.49] (independent of n)."""
    return 1.0 / (1.0 + _ratio_pow(f_ct(w, c0), f, 4))


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


def contact_node(points, boundary: Mapping, y_w: float, z_rc: float,
                 segments=("tread", "flange")) -> int:
    """Index of the running-surface node nearest (laterally) to the nominal
    contact point y^W (from the rolling circle at Z = z_rc, SPEC 2).  The
    running surface is the tread plus the flange outer surface from the flange
    top on (both single-valued in Z), so a contact near the flange root is found."""
    idx = _boundary(boundary, segments)
    if idx.size == 0:
        raise ValueError(f"no boundary nodes on {segments}")
    z = np.asarray(points, dtype=float)[idx, 1]
    return int(idx[np.argmin(np.abs(z - (z_rc + y_w)))])


# --------------------------------------------------------------------------
# modal sum (private, simple)
# --------------------------------------------------------------------------
def modal_damping(n, cls, kind=None, zeta_suspension=None, *, rigid_zeta: bool = True) -> np.ndarray:
    """Damping ratios per SPEC 3.1 [4.11]: 1e-3 (n = 0), 1e-2 (n = 1), 1e-4
    (n >= 2), 1.0 for the (1,0,r) mode [m = 0 assumed: the only n = 1 radial mode
    with no nodal circle]; rigid modes (kind != 'flexible' or cls 's') get
    ``zeta_suspension`` when given."""
    n = np.asarray(n)
    cls = np.asarray(cls).astype(str)
    z = np.where(n == 0, 1e-3, np.where(n == 1, 1e-2, 1e-4)).astype(float)
    r1 = np.flatnonzero((n == 1) & (cls == "r"))
    if kind is not None:
        flex = np.asarray(kind).astype(str) == "flexible"
    else:
        flex = cls != "s"
    r1 = r1[flex[r1]]
    if r1.size:
        z[r1] = 1.0
    if rigid_zeta and zeta_suspension is not None:
        zs = np.asarray(zeta_suspension, dtype=float)
        rig = ~flex & np.isfinite(zs)
        z[rig] = zs[rig]
    return z


def _modal_factor(f_modes, modal_mass, zeta, f):
    """H_r(f) = 1 / (m_r (w_r^2 - W^2 + i 2 zeta_r w_r W)), shape (modes, freqs)."""
    wr = 2 * np.pi * np.asarray(f_modes, dtype=float)[:, None]
    W = 2 * np.pi * np.asarray(f, dtype=float)[None, :]
    return 1.0 / (np.asarray(modal_mass, float)[:, None] * (wr**2 - W**2 + 2j * np.asarray(zeta, float)[:, None] * wr * W))


def transfer_receptance(U_i, U_j, f_modes, modal_mass, zeta, f):
    """G_ij(W) = sum_r U_r,i U_r,j / (m_r (w_r^2 - W^2 + i 2 zeta_r w_r W)) [4.10].
    ``U_i`` (modes, nodes) response amplitudes, ``U_j`` (modes,) at the driving
    point; returns (nodes, freqs) complex receptance (m/N)."""
    H = _modal_factor(f_modes, modal_mass, zeta, f)
    return np.asarray(U_i, float).T @ (np.asarray(U_j, float)[:, None] * H)


# --------------------------------------------------------------------------
# velocities and sound power [4.38], [4.54]-[4.57]
# --------------------------------------------------------------------------
@dataclass
class RadiationResult:
    """Sound power spectrum and its parts.  ``W`` (freqs,) in W; ``W_n``
    (harmonics, freqs) per harmonic; ``W_axial``/``W_radial``/``W_torsion``
    (harmonics, freqs) per term; ``v2_axial`` (harmonics, 5, freqs), ``v2_radial``
    (harmonics, freqs) mean-square velocities (m^2/s^2); ``L_W`` overall level
    10 log10(sum_f W / 1e-12) dB, the sum over the given frequencies: the total
    power when they are the bins of a force spectrum whose squared bins sum to
    the mean square (``spectra.amplitude_spectrum(..., scaling='power')``; with
    'rms' scaling a Hann-windowed tone counts 1.5 times, +1.76 dB); for a
    unit-force curve on an arbitrary grid use ``UnitForceResult.W_band``;
    ``f_dominant`` the frequency of max W."""
    f: np.ndarray
    harmonics: np.ndarray
    W: np.ndarray
    W_n: np.ndarray
    W_axial: np.ndarray
    W_radial: np.ndarray
    W_torsion: np.ndarray
    v2_axial: np.ndarray
    v2_radial: np.ndarray
    v2_torsion: np.ndarray
    L_W: float
    f_dominant: float
    meta: dict = field(default_factory=dict)


def _as_modes(modes: Mapping, zeta=None, rigid: bool = True):
    f_m = np.asarray(modes["f_hz"], float)
    n = np.asarray(modes["n"], int)
    cls = np.asarray(modes["cls"]).astype(str)
    kind = np.asarray(modes["kind"]).astype(str) if "kind" in modes else None
    zs = np.asarray(modes["zeta_suspension"], float) if "zeta_suspension" in modes else None
    z = modal_damping(n, cls, kind, zs) if zeta is None else np.broadcast_to(np.asarray(zeta, float), f_m.shape)
    keep = np.ones(f_m.size, bool)
    if not rigid:
        keep = (kind == "flexible") if kind is not None else (cls != "s")
    return f_m, n, np.asarray(modes["modal_mass"], float), np.asarray(modes["shapes"], float), z, keep


def _tyre_rotation(shapes, points, nodes):
    """Rotation amplitude of the tyre cross-section about the circumferential
    axis, least-squares rigid fit of (U_r, U_z) over ``nodes`` (rad per unit
    shape); for the optional torsion term."""
    p = np.asarray(points, float)[nodes]
    dr, dz = p[:, 0] - p[:, 0].mean(), p[:, 1] - p[:, 1].mean()
    ur, uz = shapes[:, nodes, 0], shapes[:, nodes, 1]
    return (uz @ dr - ur @ dz) / (dr @ dr + dz @ dz)


def surface_velocities(f, F2, F3, modes: Mapping, nodes: SurfaceNodes, contact: int, *, zeta=None,
                       rigid: bool = True, points=None, chunk: int = 2048):
    """Mean-square surface velocities per harmonic [4.54]-[4.57].

    v_i(n, f) = i 2 pi f [G_i2(n, f) F2(f) + G_i3(n, f) F3(f)] with G from the
    modes of harmonic n only; G_i2 uses the contact point's U_z (lateral), G_i3
    its U_r (vertical); the response is U_z at axial-surface nodes, U_r at
    radial-surface nodes.  <v_i^2> = |v_i|^2 (n = 0), 0.5 |v_i|^2 (n > 0),
    averaged over the nodes of each surface.  F2, F3 complex amplitudes (N),
    scalars or (freqs,).  Returns (harmonics, v2_axial (H, Q, F), v2_radial (H, F),
    v2_torsion (H, F); the last needs ``points``, zeros otherwise)."""
    f = np.atleast_1d(np.asarray(f, float))
    F2 = np.broadcast_to(np.asarray(F2, complex), f.shape)
    F3 = np.broadcast_to(np.asarray(F3, complex), f.shape)
    f_m, n, mm, sh, z, keep = _as_modes(modes, zeta, rigid)
    harm = np.unique(n[keep])
    Q = len(nodes.axial)
    v2a = np.zeros((harm.size, Q, f.size))
    v2r = np.zeros((harm.size, f.size))
    v2t = np.zeros((harm.size, f.size))
    theta = _tyre_rotation(sh, points, nodes.tyre) if points is not None else None
    for h, nn in enumerate(harm):
        sel = np.flatnonzero(keep & (n == nn))
        u2, u3 = sh[sel, contact, 1], sh[sel, contact, 0]
        circ = 1.0 if nn == 0 else 0.5
        Ua = [sh[sel][:, ax, 1].T for ax in nodes.axial]  # axial velocity: U_z
        Ur = sh[sel][:, nodes.radial, 0].T  # radial velocity: U_r
        for s in range(0, f.size, chunk):
            fs = f[s:s + chunk]
            H = _modal_factor(f_m[sel], mm[sel], z[sel], fs)
            # modal participation q_r(f) = H_r (U_r,c2 F2 + U_r,c3 F3); velocity factor i 2 pi f
            q = H * (u2[:, None] * F2[None, s:s + chunk] + u3[:, None] * F3[None, s:s + chunk])
            q = q * (2j * np.pi * fs)[None, :]
            for k, Uk in enumerate(Ua):
                if Uk.size:
                    v2a[h, k, s:s + chunk] = circ * np.mean(np.abs(Uk @ q) ** 2, axis=0)
            v = Ur @ q
            v2r[h, s:s + chunk] = circ * np.mean(np.abs(v) ** 2, axis=0)
            if theta is not None:
                v2t[h, s:s + chunk] = circ * np.abs(theta[sel] @ q) ** 2
    return harm, v2a, v2r, v2t


def sound_power(f, F2, F3, modes: Mapping, surfaces: Surfaces, nodes: SurfaceNodes, contact: int, *,
                rho: float = RHO_AIR, c0: float = C0, torsion: bool = False, points=None, zeta=None,
                rigid: bool = True, force_amplitude: str = "rms") -> RadiationResult:
    """Sound power W(f) [4.38] of the wheel driven at node ``contact`` by the
    lateral and vertical contact-force amplitudes F2(f), F3(f).

    ``modes``: mapping with f_hz, n, cls, kind, modal_mass, shapes (M, nodes, 3)
    = (U_r, U_z, U_phi), zeta_suspension (the wheel modal artifact works as is).
    ``force_amplitude``: 'rms' (default; [4.56] as printed is then the space
    and time mean square) or 'peak' (adds the time average 1/2).
    ``torsion``: add the torsion term (needs ``points``; off by default as in
    the thesis).  ``rigid``: include the rigid half-wheelset modes."""
    f = np.atleast_1d(np.asarray(f, float))
    if force_amplitude not in ("rms", "peak"):
        raise ValueError("force_amplitude: 'rms' or 'peak'")
    if torsion and points is None:
        raise ValueError("torsion=True needs the section points")
    harm, v2a, v2r, v2t = surface_velocities(f, F2, F3, modes, nodes, contact, zeta=zeta, rigid=rigid,
                                             points=points if torsion else None)
    if force_amplitude == "peak":
        v2a, v2r, v2t = 0.5 * v2a, 0.5 * v2r, 0.5 * v2t
    sa = sigma_axial(harm[:, None], f[None, :], surfaces.r, c0)
    sr = sigma_radial(harm[:, None], f[None, :], surfaces.r, surfaces.gamma)
    st = sigma_torsion(f, surfaces.w, c0)[None, :]
    Wa = rho * c0 * sa * np.einsum("q,hqf->hf", surfaces.S_a, v2a)
    Wr = rho * c0 * sr * surfaces.S_r * v2r
    Wt = rho * c0 * st * surfaces.S_t * v2t if torsion else np.zeros_like(Wr)
    Wn = Wa + Wr + Wt
    W = Wn.sum(axis=0)
    tot = W.sum()
    return RadiationResult(f=f, harmonics=harm, W=W, W_n=Wn, W_axial=Wa, W_radial=Wr, W_torsion=Wt,
                           v2_axial=v2a, v2_radial=v2r, v2_torsion=v2t,
                           L_W=float(10 * np.log10(tot / W_REF)) if tot > 0 else -np.inf,
                           f_dominant=float(f[np.argmax(W)]) if W.size else np.nan,
                           meta={"rho": rho, "c0": c0, "torsion": torsion, "rigid": rigid,
                                 "force_amplitude": force_amplitude, "contact": int(contact)})


def frequency_grid(f_min: float, f_max: float, f_modes=(), zeta=(), *, per_decade: int = 400,
                   per_peak: int = 41, span: float = 50.0) -> np.ndarray:
    """Frequencies for unit-force curves: a log grid plus, around each mode
    inside the band, ``per_peak`` points spread over f_r (1 +- span zeta_r)
    (denser at the peak, through f_r itself), so the narrow peaks (zeta = 1e-4:
    -3 dB band 2 zeta f_r) are resolved and integrable."""
    f = [np.geomspace(f_min, f_max, int(round(per_decade * np.log10(f_max / f_min))) + 1)]
    x = np.sinh(np.linspace(-np.arcsinh(span), np.arcsinh(span), per_peak))  # offsets in units of zeta
    for fr, z in zip(np.atleast_1d(f_modes), np.atleast_1d(zeta)):
        if f_min <= fr <= f_max:
            f.append(fr * (1 + min(z, 0.02) * x))
    f = np.unique(np.concatenate(f))
    return f[(f >= f_min) & (f <= f_max)]


@dataclass
class UnitForceResult:
    """Sound power per unit (RMS) force: ``result`` (RadiationResult, W in
    W/N^2), ``table`` one row per harmonic: n, peak level L_peak (dB re 1e-12 W
    for 1 N), f_peak, band power for a white unit force spectrum
    (1 N^2/Hz: integral of W_n over the band, W) and its level, share of the total."""
    result: RadiationResult
    table: list
    L_peak: float
    f_peak: float
    W_band: float
    L_band: float


def unit_force_power(f, modes: Mapping, surfaces: Surfaces, nodes: SurfaceNodes, contact: int,
                     direction: str = "lateral", **kw) -> UnitForceResult:
    """Sound power for a unit lateral (F2 = 1 N) or radial (F3 = 1 N) RMS
    force at node ``contact`` over the frequencies ``f`` (use ``frequency_grid``
    to resolve the peaks).  Levels are dB re 1e-12 W for 1 N (i.e. per N^2).
    Keyword arguments go to ``sound_power``."""
    if direction not in ("lateral", "radial"):
        raise ValueError("direction: 'lateral' or 'radial'")
    F2, F3 = (1.0, 0.0) if direction == "lateral" else (0.0, 1.0)
    res = sound_power(f, F2, F3, modes, surfaces, nodes, contact, **kw)
    f = res.f
    band = np.trapz(res.W_n, f, axis=1) if f.size > 1 else res.W_n[:, 0]
    tot = float(band.sum())
    table = []
    for h, nn in enumerate(res.harmonics):
        k = int(np.argmax(res.W_n[h]))
        table.append({"n": int(nn), "L_peak_dB": _db(res.W_n[h, k]), "f_peak_hz": float(f[k]),
                      "W_band": float(band[h]), "L_band_dB": _db(band[h]),
                      "share": float(band[h] / tot) if tot > 0 else np.nan})
    k = int(np.argmax(res.W))
    return UnitForceResult(result=res, table=table, L_peak=_db(res.W[k]), f_peak=float(f[k]),
                           W_band=tot, L_band=_db(tot))


def _db(w) -> float:
    w = float(w)
    return 10 * np.log10(w / W_REF) if w > 0 else -np.inf


def level_db(W):
    """10 log10(W / 1e-12) elementwise (dB re 1e-12 W)."""
    W = np.asarray(W, float)
    with np.errstate(divide="ignore"):
        return 10 * np.log10(W / W_REF)
