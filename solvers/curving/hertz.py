"""Hertz's elliptical contact from the relative curvatures and the normal load (Johnson,
*Contact Mechanics*, 1985, section 4.2, eqs. 4.36-4.39): the patch semi-axes that scale
Kalker's linear creep coefficients (``creep``).

The undeformed gap near the contact is h = A x^2 + B y^2 (x rolling direction, y lateral in
the contact plane).  With m = e^2 = 1 - (minor / major)^2 and K(m), E(m) the complete
elliptic integrals, the ratio of the curvatures fixes m,

    B / A = [E(m) / (1 - m) - K(m)] / [K(m) - E(m)]          (A <= B: the major axis along x)

and the load P the major semi-axis,  major^3 = 3 P [K(m) - E(m)] / (2 pi E* m A_small),
with E* = E / (2 (1 - nu^2)) for two bodies of one steel; for A > B the roles of x and y swap.
"""
from __future__ import annotations

import math

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

M_MAX = 1.0 - 1e-12


def _ratio(m: float) -> float:
    """B/A (>= 1) of an ellipse with eccentricity^2 m (Johnson 4.39)."""
    if m < 1e-8:
        return 1.0 + 1.5 * m  # series of the expression below about m = 0
    K, E = ellipk(m), ellipe(m)
    return (E / (1.0 - m) - K) / (K - E)


def _k_minus_e_over_m(m: float) -> float:
    if m < 1e-8:
        return 0.25 * math.pi * (1.0 + 0.375 * m)
    return (ellipk(m) - ellipe(m)) / m


def eccentricity2(ratio: float) -> float:
    """m = e^2 of the contact ellipse for the curvature ratio ``ratio`` = large / small >= 1."""
    if ratio <= 1.0 + 1e-12:
        return 0.0
    if ratio >= _ratio(M_MAX):
        return M_MAX
    return brentq(lambda m: _ratio(m) - ratio, 0.0, M_MAX, xtol=1e-15, rtol=1e-14)


def hertz_semi_axes(A: float, B: float, load: float, E: float = 210e9, nu: float = 0.3) -> tuple[float, float]:
    """Semi-axes (a along x, b along y) in m of the Hertz ellipse for the relative curvatures
    A, B (1/m, h = A x^2 + B y^2, both > 0) and the normal load (N, > 0)."""
    if A <= 0.0 or B <= 0.0 or load <= 0.0:
        raise ValueError(f"Hertz contact needs positive curvatures and load (A={A}, B={B}, P={load})")
    Es = E / (2.0 * (1.0 - nu * nu))
    small, large = min(A, B), max(A, B)
    m = eccentricity2(large / small)
    major = (3.0 * load * _k_minus_e_over_m(m) / (2.0 * math.pi * Es * small)) ** (1.0 / 3.0)
    minor = major * math.sqrt(1.0 - m)
    return (major, minor) if A <= B else (minor, major)
