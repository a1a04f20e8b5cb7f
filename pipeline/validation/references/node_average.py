"""The sound power [4.38] by node averages, the form the thesis writes
([4.54]-[4.57]: each surface's mean-square velocity averaged over its nodes),
kept in the tests as the second method the pipeline's Gram-matrix form
(``solvers.radiation.force_power.harmonic_power``) is checked against.  The modal
sum and the damping rule are the pipeline's own (``solvers.wheel.receptance``)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from solvers.radiation.thompson_jones import C0, RHO_AIR, W_REF, sigma_axial, sigma_radial, sigma_torsion
from solvers.radiation.surfaces import SurfaceNodes, Surfaces, _boundary
from solvers.wheel.receptance import modal_damping, modal_frf


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
    kind = np.asarray(modes["kind"]).astype(str) if "kind" in modes else np.where(cls == "s", "bounce", "flexible")
    m = np.asarray(modes["m"], int) if "m" in modes else np.zeros(f_m.size, int)
    zs = np.asarray(modes["zeta_suspension"], float) if "zeta_suspension" in modes else np.full(f_m.size, np.nan)
    z = modal_damping(n, m, cls, kind, zs) if zeta is None else np.broadcast_to(np.asarray(zeta, float), f_m.shape)
    keep = np.ones(f_m.size, bool)
    if not rigid:
        keep = kind == "flexible"
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
            H = modal_frf(fs, f_m[sel], mm[sel], z[sel]).T
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
                air: tuple = (RHO_AIR, C0), torsion_points=None, zeta=None, rigid: bool = True,
                force_amplitude: str = "rms") -> RadiationResult:
    """Sound power W(f) [4.38] of the wheel driven at node ``contact`` by the
    lateral and vertical contact-force amplitudes F2(f), F3(f).

    ``modes``: mapping with f_hz, n, cls, kind, modal_mass, shapes (M, nodes, 3)
    = (U_r, U_z, U_phi), zeta_suspension (the wheel modal artifact works as is).
    ``force_amplitude``: 'rms' (default; [4.56] as printed is then the space
    and time mean square) or 'peak' (adds the time average 1/2).
    ``air``: (rho, c0).  ``torsion_points``: the section's points, to add the torsion term (off by default as in
    the thesis).  ``rigid``: include the rigid half-wheelset modes."""
    f = np.atleast_1d(np.asarray(f, float))
    if force_amplitude not in ("rms", "peak"):
        raise ValueError("force_amplitude: 'rms' or 'peak'")
    rho, c0 = air
    torsion = torsion_points is not None
    harm, v2a, v2r, v2t = surface_velocities(f, F2, F3, modes, nodes, contact, zeta=zeta, rigid=rigid,
                                             points=torsion_points)
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
