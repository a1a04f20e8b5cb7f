"""References of the listening checks (tests/listen/, the listening writer): the IEC 61672-1 A-weighting
table, ISO 9613-1's absorption formula, and the exact field of point monopoles over a rigid plane (image
sources summed, a dipole built from two monopoles, its power integrated over a sphere)."""
from __future__ import annotations

import numpy as np

from postprocess.listening import listener as L

# IEC 61672-1:2013 (Electroacoustics - Sound level meters - Part 1: Specifications), Table 3
# "Frequency weightings and tolerance limits", column "A" (dB), at the nominal 1/3-octave
# frequencies 10 Hz - 20 kHz.  Typed from the standard's published table; the standard states
# that the weightings are computed at the exact base-10 frequencies f_m = 1000 * 10^(0.1 x) Hz
# and rounded to 0.1 dB, the nominal frequencies being labels.
IEC_61672_A = {
    10: -70.4, 12.5: -63.4, 16: -56.7, 20: -50.5, 25: -44.7, 31.5: -39.4, 40: -34.6, 50: -30.2,
    63: -26.2, 80: -22.5, 100: -19.1, 125: -16.1, 160: -13.4, 200: -10.9, 250: -8.6, 315: -6.6,
    400: -4.8, 500: -3.2, 630: -1.9, 800: -0.8, 1000: 0.0, 1250: 0.6, 1600: 1.0, 2000: 1.2,
    2500: 1.3, 3150: 1.2, 4000: 1.0, 5000: 0.5, 6300: -0.1, 8000: -1.1, 10000: -2.5,
    12500: -4.3, 16000: -6.6, 20000: -9.3,
}
RHO, C0 = 1.21, 343.0


def iso_9613_alpha(f, T=293.15, rh=0.70, pa=101.325):
    """ISO 9613-1:1993 eqs. (3)-(5) and Annex B (saturation pressure), typed here: dB/m."""
    pr, T0, T01 = 101.325, 293.15, 273.16
    h = 100 * rh * 10 ** (-6.8346 * (T01 / T) ** 1.261 + 4.6151) * pr / pa  # molar conc. of water vapour (%)
    frO = pa / pr * (24 + 4.04e4 * h * (0.02 + h) / (0.391 + h))
    frN = pa / pr * (T / T0) ** -0.5 * (9 + 280 * h * np.exp(-4.170 * ((T / T0) ** (-1 / 3) - 1)))
    return 8.686 * f**2 * (1.84e-11 * (pr / pa) * (T / T0) ** 0.5 + (T / T0) ** -2.5 * (
        0.01275 * np.exp(-2239.1 / T) / (frO + f**2 / frO) + 0.1068 * np.exp(-3352.0 / T) / (frN + f**2 / frN)))


def monopole_field(points, sources, strengths, f):
    """Complex RMS pressure at ``points`` of point monopoles (RMS volume velocities, m^3/s):
    p = i w rho Q e^{-ikR} / (4 pi R)."""
    k, w = 2 * np.pi * f / C0, 2 * np.pi * f
    p = np.zeros(len(points), complex)
    for s, q in zip(sources, strengths):
        R = np.linalg.norm(points - s, axis=1)
        p += 1j * w * RHO * q * np.exp(-1j * k * R) / (4 * np.pi * R)
    return p


def dipole_from_two_monopoles(f=1151.5, d=6.75, h_s=0.59, h_r=1.4, delta=1e-3):
    """(model p^2, exact p^2) at the receiver of a dipole = two opposite monopoles ``delta`` apart
    along the axle (y), with their images in a rigid ground; the dipole's power from its free
    field integrated over a 60 m sphere (Gauss-Legendre in cos theta x uniform in phi)."""
    src = [np.array([0, -delta / 2, h_s]), np.array([0, delta / 2, h_s])]
    img = [s * np.array([1, 1, -1]) for s in src]
    q = [1e-3, -1e-3]
    mu, wmu = np.polynomial.legendre.leggauss(64)
    phi = np.linspace(0, 2 * np.pi, 128, endpoint=False)
    R = 60.0
    st = np.sqrt(1 - mu**2)
    pts = np.array([[R * s * np.cos(p), R * c, R * s * np.sin(p)] for c, s in zip(mu, st) for p in phi])
    pts[:, 2] += h_s
    p2 = np.abs(monopole_field(pts, src, q, f)) ** 2
    W = float(np.sum(p2.reshape(mu.size, phi.size).mean(axis=1) * wmu) * 2 * np.pi * R**2 / (RHO * C0))
    rec = np.array([[0.0, d, h_r]])
    ref = abs(monopole_field(rec, src + img, q + q, f)[0]) ** 2
    g = L.Geometry(distance=d, h_source=h_s, h_receiver=h_r, ground="rigid", directivity="dipole", air=False)
    return L.mean_square_pressure(f, W, g)[0], ref
