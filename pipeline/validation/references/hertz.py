"""Hertz theory of two elastic bodies touching at a point (elliptical contact).

Independent analytic reference for the NORM solver (solvers/contact/norm.py);
nothing here depends on the contact code.  Exact relations of Johnson,
Contact Mechanics (1985), section 4.2, eqs (4.36)-(4.39), with the complete
elliptic integrals K(e), E(e) of the eccentricity e = sqrt(1 - b^2 / a^2):

    undeformed gap       h = A x^2 + B y^2            (A <= B: a along x)
    B / A              = [(a/b)^2 E(e) - K(e)] / [K(e) - E(e)]   -> e (root find)
    A                  = p0 / E* * b / (e^2 a^2) * [K(e) - E(e)]
    P                  = (2/3) pi a b p0
    approach     delta = p0 b K(e) / E*
    1 / E*             = (1 - nu1^2) / E1 + (1 - nu2^2) / E2

Pressure p = p0 sqrt(1 - x^2/a^2 - y^2/b^2).  When A > B the axes are swapped so
that 'a' is always the semi-axis along x and 'b' along y.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk


@dataclass(frozen=True)
class HertzContact:
    a: float        # semi-axis along x [m]
    b: float        # semi-axis along y [m]
    p0: float       # peak pressure [Pa]
    delta: float    # rigid approach [m]
    load: float     # normal force [N]

    @property
    def c(self) -> float:
        return float(np.sqrt(self.a * self.b))

    def pressure(self, x, y):
        r = 1.0 - (np.asarray(x) / self.a) ** 2 - (np.asarray(y) / self.b) ** 2
        return self.p0 * np.sqrt(np.clip(r, 0.0, None))


def contact_modulus(E: float, nu: float) -> float:
    """E* for two bodies of the same material."""
    return E / (2.0 * (1.0 - nu**2))


def eccentricity(ratio: float) -> float:
    """e (major/minor semi-axes) from the curvature ratio B/A >= 1 (Johnson 4.39)."""
    if ratio < 1.0:
        raise ValueError("curvature ratio must be >= 1")
    if ratio - 1.0 < 1e-12:
        return 0.0

    def f(e):
        m = e * e
        K, Ee = ellipk(m), ellipe(m)
        return (Ee / (1.0 - m) - K) / (K - Ee) - ratio

    return brentq(f, 1e-6, 1.0 - 1e-15, xtol=1e-15, rtol=1e-14, maxiter=500)


def hertz(A: float, B: float, load: float, E: float = 210e9, nu: float = 0.3) -> HertzContact:
    """Hertz solution for gap h = A x^2 + B y^2 pressed with `load` [N]."""
    swap = A > B
    Amin, Amax = (B, A) if swap else (A, B)
    Es = contact_modulus(E, nu)
    e = eccentricity(Amax / Amin)
    m = e * e
    if e == 0.0:
        a = (3.0 * load / (8.0 * Es * Amin)) ** (1.0 / 3.0)    # R = 1/(2A): a^3 = 3 P R / (4 E*)
        K = np.pi / 2
    else:
        K, Ee = ellipk(m), ellipe(m)
        a = (3.0 * load * (K - Ee) / (2.0 * np.pi * Es * Amin * m)) ** (1.0 / 3.0)
    b = a * np.sqrt(1.0 - m)
    p0 = 3.0 * load / (2.0 * np.pi * a * b)
    delta = p0 * b * K / Es
    if swap:
        a, b = b, a
    return HertzContact(a=float(a), b=float(b), p0=float(p0), delta=float(delta), load=float(load))


def load_for_approach(A: float, B: float, delta: float, E: float = 210e9, nu: float = 0.3) -> float:
    """P(delta): inverse of the approach-load relation (delta ~ P^(2/3))."""
    d1 = hertz(A, B, 1.0, E, nu).delta
    return float((delta / d1) ** 1.5) if delta > 0 else 0.0


def wheel_rail(R_wheel: float = 0.39, R_crown: float = 0.3, load: float = 65e3,
               E: float = 210e9, nu: float = 0.3) -> HertzContact:
    """Cylindrical wheel (rolling radius R_wheel, flat tread laterally) on a rail head
    with crown radius R_crown (straight along x)."""
    return hertz(1.0 / (2.0 * R_wheel), 1.0 / (2.0 * R_crown), load, E, nu)


def curvature_ratio(b_over_a: float) -> float:
    """B/A of the gap A x^2 + B y^2 that gives the semi-axis ratio b/a (< 1: b along y
    shorter); 1/curvature_ratio(a/b) for the other orientation (Johnson 4.39)."""
    if b_over_a >= 1.0:
        return 1.0 / curvature_ratio(1.0 / b_over_a) if b_over_a > 1.0 else 1.0
    m = 1.0 - b_over_a**2
    K, Ee = ellipk(m), ellipe(m)
    return (Ee / b_over_a**2 - K) / (K - Ee)


def ellipsoidal_traction_compliance(a: float, b: float, E: float = 210e9, nu: float = 0.3):
    """(A1, A2) [m/N] of the thesis' recipe [4.32-4.35] in the continuum: a tangential
    traction shaped like the Hertz pressure, q = q0 sqrt(1 - x^2/a^2 - y^2/b^2), on a
    half-space pair (compliance of wheel + rail), mean displacement 2/3 of the peak,
    divided by the force (2/3) pi a b q0.  The peak is at the centre, where the
    Cerruti integral in polar coordinates reduces to one quadrature
        u_1(0) = q0 / (pi G) Int_0^2pi [(1 - nu) + nu cos^2 phi] pi / (4 rho(phi)) dphi,
        rho(phi)^2 = cos^2 phi / a^2 + sin^2 phi / b^2
    (Int_0^(1/rho) sqrt(1 - r^2 rho^2) dr = pi / (4 rho)).  For a circle this is
    Mindlin's no-slip compliance (2 - nu) / (4 G a) (Johnson eq. 7.35, both bodies)."""
    from scipy.integrate import quad  # lazy: brings in scipy

    G = E / (2.0 * (1.0 + nu))
    rho = lambda f: np.sqrt(np.cos(f) ** 2 / a**2 + np.sin(f) ** 2 / b**2)
    out = []
    for trig in (np.cos, np.sin):
        I = quad(lambda f: ((1 - nu) + nu * trig(f) ** 2) * np.pi / (4.0 * rho(f)), 0.0, 2 * np.pi,
                 epsabs=0.0, epsrel=1e-12, limit=200)[0]
        u0 = I / (np.pi * G)                          # per unit q0
        out.append((2.0 / 3.0) * u0 / ((2.0 / 3.0) * np.pi * a * b))
    return out[0], out[1]
