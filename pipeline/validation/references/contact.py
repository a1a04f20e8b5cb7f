"""Contact cases shared by the contact tests, the validation writer and benchmarks/contact.py: a Hertzian
wheel/rail case and Carter's 2D rolling solution (Carter 1926; Johnson, Contact Mechanics 1985, sec. 8.2)."""
from __future__ import annotations

import numpy as np

from pipeline.validation.references.hertz import HertzContact, hertz

E, NU = 210e9, 0.3
G = E / (2 * (1 + NU))
V = 50 / 3.6                 # rolling speed [m/s] (SPEC 6)
DT = 36e-6                   # time step [s] (SPEC 6): dx = v dt = 0.5 mm
DX = V * DT
R_WHEEL, R_CROWN, LOAD = 0.39, 0.3, 65e3


def grid(nx, ny, dx, dy):
    """Element centres (X, Y), (nx, ny), centred on the origin."""
    x = (np.arange(nx) - 0.5 * (nx - 1)) * dx
    y = (np.arange(ny) - 0.5 * (ny - 1)) * dy
    return np.meshgrid(x, y, indexing="ij")


def hertz_case(A=1 / (2 * R_WHEEL), B=1 / (2 * R_CROWN), load=LOAD, dx=DX, dy=DX, margin=1.25):
    """Quadratic gap h = A x^2 + B y^2 on a grid covering `margin` times the Hertz ellipse
    (odd counts, so one row and one column pass through the centre)."""
    H: HertzContact = hertz(A, B, load, E, NU)
    nx = 2 * int(np.ceil(margin * H.a / dx)) + 1
    ny = 2 * int(np.ceil(margin * H.b / dy)) + 1
    X, Y = grid(nx, ny, dx, dy)
    return X, Y, A * X**2 + B * Y**2, H


def ellipse_fit(p, X, Y):
    """Semi-axes and peak of a Hertz-like pressure field by least squares of
    p^2 = p0^2 (1 - x^2/a^2 - y^2/b^2) over the loaded elements."""
    C = p > 0
    M = np.column_stack([np.ones(C.sum()), X[C] ** 2, Y[C] ** 2])
    c = np.linalg.lstsq(M, p[C] ** 2, rcond=None)[0]
    return float(np.sqrt(-c[0] / c[1])), float(np.sqrt(-c[0] / c[2])), float(np.sqrt(c[0]))


def carter_traction(x, a, p0, mu, c):
    """Carter's 2D rolling traction magnitude (Johnson 8.1): mu p0 [sqrt(1 - x^2/a^2)
    - (c/a) sqrt(1 - (x - d)^2/c^2)], stick zone |x - d| < c at the leading edge
    (x = +a), d = a - c."""
    d = a - c
    q = mu * p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
    return q - mu * p0 * (c / a) * np.sqrt(np.clip(1 - ((x - d) / c) ** 2, 0, None))


def carter_creepage(c_over_a, p0, mu, direction=1, nu=NU):
    """Creepage giving the stick half-width c: |gamma| = K mu p0 (1 - c/a), with the 2D
    combined compliance K = 2(1 - nu)/G for longitudinal (plane strain, Carter) and
    K = 2/G for lateral creepage (anti-plane)."""
    K = 2 * (1 - nu) / G if direction == 1 else 2 / G
    return K * mu * p0 * (1 - c_over_a)


def hertz_pressure(a=6e-3, b=4e-3, F3=65e3, d=0.5e-3):
    """Hertzian pressure on a grid (independent of the NORM solver): p0 sqrt(1 - x^2/a^2 - y^2/b^2)."""
    x = np.arange(-a + d / 2, a, d)
    y = np.arange(-b + d / 2, b, d)
    X, Y = np.meshgrid(x, y, indexing="ij")
    r = 1 - (X / a) ** 2 - (Y / b) ** 2
    p = np.sqrt(np.clip(r, 0, None))
    return p * F3 / (p.sum() * d * d), d
