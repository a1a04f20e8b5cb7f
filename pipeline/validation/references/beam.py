"""Analytic beam models of a continuously supported rail (independent of
the waveguide FE code): reference receptances for tests/rail.

1. Vertical: Timoshenko beam on a Winkler foundation (TBOEF).

       kGA (w'' - psi') - k_s w + m w^2 w = -F delta(x)
       EI psi'' + kGA (w' - psi) + rho I w^2 psi = 0

   With w, psi ~ exp(-i k x) the wavenumber-domain receptance is
   H(k) = N(s) / Q(s), s = k^2, with

       N(s) = EI s + kGA - rho I w^2
       Q(s) = (kGA s + k_s - m w^2)(EI s + kGA - rho I w^2) - (kGA)^2 s   (quadratic in s)

   and the point / transfer receptance is the exact residue sum

       G(x) = (1/2 pi) int H(k) exp(-i k x) dk
            = sum_j N(s_j) / Q'(s_j) * (-i) exp(-i q_j |x|) / (2 q_j),
       q_j = sqrt(s_j) with Im q_j < 0,

   using (1/2 pi) int exp(-i k x) / (k^2 - q^2) dk = -i exp(-i q |x|) / (2 q).
   Euler-Bernoulli: kGA -> inf, rho I -> 0 (static point receptance
   beta / (2 k_s), beta = (k_s / 4 EI)^(1/4)).  Damping: complex EI, kGA and
   k_s (loss factors); the roots never lie on the real axis then.

2. Lateral with torsion: Euler-Bernoulli lateral bending (with rotary
   inertia) + Vlasov torsion (GJ, E Gamma) of a mono-symmetric section on
   a lateral spring k_y acting at the foot underside (z = 0) and a rocking
   spring k_r.  Unknowns: lateral displacement v of the shear centre S
   (height z_s) and twist theta (positive from +y toward +z); a section
   point (y, z) moves u_y = v - (z - z_s) theta, u_z = y theta.  Per unit
   length: stiffness diag(EI_l k^4, GJ k^2 + E Gamma k^4) plus the springs
   k_y (v + z_s theta)^2 and k_r theta^2; inertia m (v - e theta)^2 +
   rho I_pc theta^2 + rho I_l k^2 v^2, e = z_c - z_s, I_pc the polar moment
   about the centroid.  A lateral force at head height z_h and a vertical
   force at lateral position y_h load b = (1, -(z_h - z_s)) and (0, y_h).
   G(x) = b_o^T adj(P) b_i / det P summed over the four roots s_j of the
   quartic det P(s) in the same way.
"""
from __future__ import annotations

import numpy as np


def _q(s):
    q = np.sqrt(np.asarray(s, complex))
    return np.where(q.imag > 0, -q, q)


def tboef_receptance(freqs, x, EI, kGA, m, rhoI, k_s, eta_beam=0.0, eta_support=0.0):
    """Vertical receptance (m/N) of a Timoshenko beam on a Winkler
    foundation, force and response at the same cross-section line,
    distance x (array) from the force.  Returns (nx, nf) complex.
    kGA = None gives the Euler-Bernoulli beam (with rhoI = 0)."""
    f = np.atleast_1d(np.asarray(freqs, float))
    x = np.abs(np.atleast_1d(np.asarray(x, float)))
    w2 = (2 * np.pi * f) ** 2
    EIc = EI * (1 + 1j * eta_beam)
    ks = k_s * (1 + 1j * eta_support)
    out = np.zeros((len(x), len(f)), complex)
    for j, ww in enumerate(w2):
        if kGA is None:  # Euler-Bernoulli: H = 1 / (EI s^2 + k_s - m w^2)
            roots = np.roots([EIc, 0.0, ks - m * ww])
            for s in roots:
                qq = _q(s)
                out[:, j] += 1.0 / (2 * EIc * s) * (-1j) * np.exp(-1j * qq * x) / (2 * qq)
            continue
        G = kGA * (1 + 1j * eta_beam)
        a = G * EIc
        b = -G * rhoI * ww + EIc * (ks - m * ww)
        c = (ks - m * ww) * (G - rhoI * ww)
        for s in np.roots([a, b, c]):
            N = EIc * s + G - rhoI * ww
            qq = _q(s)
            out[:, j] += N / (2 * a * s + b) * (-1j) * np.exp(-1j * qq * x) / (2 * qq)
    return out


def tboef_numeric(freq, x, EI, kGA, m, rhoI, k_s, eta_beam=0.0, eta_support=0.0, kmax=400.0, n=400001):
    """The same receptance by direct numerical wavenumber integration
    (trapezoid on a fine grid plus the 1/k^2 tail): a check of the residues."""
    w2 = (2 * np.pi * freq) ** 2
    EIc = EI * (1 + 1j * eta_beam)
    G = kGA * (1 + 1j * eta_beam)
    ks = k_s * (1 + 1j * eta_support)
    k = np.linspace(0.0, kmax, n)
    s = k * k
    H = (EIc * s + G - rhoI * w2) / ((G * s + ks - m * w2) * (EIc * s + G - rhoI * w2) - G * G * s)
    integ = np.trapz(H * np.cos(k * abs(x)), k) / np.pi
    if x == 0:
        integ += (H[-1] * kmax) / np.pi
    return integ


def lateral_torsion_receptance(freqs, x, p: dict, out=("lateral", "lateral"), z_h=None, y_h=0.0):
    """Lateral/torsional beam on a lateral and a rocking spring.

    p: EI_l (N m^2), GJ (N m^2), EGamma (N m^4), m (kg/m), rhoI_l (kg m),
    rhoI_pc (kg m, polar about the centroid), z_c, z_s (m, from the foot
    underside), k_y (N/m^2), k_r (N m/m per rad), eta_beam, eta_support.
    out = (response, force), each 'lateral' (at head height z_h) or
    'vertical' (at lateral position y_h, only its torsional part) or
    'rotation' / 'mean_lateral' (responses: twist, centroid lateral).
    Returns (nx, nf) complex (m/N or rad/N)."""
    f = np.atleast_1d(np.asarray(freqs, float))
    x = np.abs(np.atleast_1d(np.asarray(x, float)))
    eb, es = p.get("eta_beam", 0.0), p.get("eta_support", 0.0)
    EI = p["EI_l"] * (1 + 1j * eb)
    GJ = p["GJ"] * (1 + 1j * eb)
    EG = p["EGamma"] * (1 + 1j * eb)
    ky = p["k_y"] * (1 + 1j * es)
    kr = p["k_r"] * (1 + 1j * es)
    m, zs, zc = p["m"], p["z_s"], p["z_c"]
    e = zc - zs
    zh = p.get("z_h", None) if z_h is None else z_h

    def vec(kind, response):
        if kind == "lateral":
            return np.array([1.0, -(zh - zs)])
        if kind == "vertical":
            return np.array([0.0, y_h])
        if kind == "rotation":
            return np.array([0.0, 1.0])
        if kind == "mean_lateral":
            return np.array([1.0, -e])
        raise ValueError(kind)

    bo, bi = vec(out[0], True), vec(out[1], False)
    P = np.polynomial.polynomial
    res = np.zeros((len(x), len(f)), complex)
    for j, ff in enumerate(f):
        w2 = (2 * np.pi * ff) ** 2
        # polynomial coefficients in s = k^2, lowest order first
        p11 = np.array([ky - w2 * m, -w2 * p.get("rhoI_l", 0.0), EI])
        p12 = np.array([ky * zs + w2 * m * e])
        p22 = np.array([ky * zs * zs + kr - w2 * (m * e * e + p["rhoI_pc"]), GJ, EG])
        det = P.polysub(P.polymul(p11, p22), P.polymul(p12, p12))
        num = P.polyadd(P.polyadd(bo[0] * bi[0] * p22, -(bo[0] * bi[1] + bo[1] * bi[0]) * p12),
                        bo[1] * bi[1] * p11)
        ddet = P.polyder(det)
        for s in P.polyroots(det):
            qq = _q(s)
            res[:, j] += P.polyval(s, num) / P.polyval(s, ddet) * (-1j) * np.exp(-1j * qq * x) / (2 * qq)
    return res


def timoshenko_dispersion(k, EI, kGA, m, rhoI):
    """Free Timoshenko beam: the lower (bending) branch w(k) in rad/s."""
    k = np.asarray(k, float)
    a = m * rhoI
    b = -(m * (EI * k**2 + kGA) + rhoI * kGA * k**2)
    c = kGA * EI * k**4
    disc = np.sqrt(b * b - 4 * a * c)
    return np.sqrt((-b - disc) / (2 * a))


def vlasov_torsion_dispersion(k, GJ, EGamma, rhoIp):
    """Free torsional wave (Vlasov): w = k sqrt((GJ + E Gamma k^2) / rho I_p)."""
    k = np.asarray(k, float)
    return k * np.sqrt((GJ + EGamma * k**2) / rhoIp)
