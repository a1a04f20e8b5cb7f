"""Creep forces of one wheel/rail contact: Kalker's linear theory on the Hertz ellipse with
its coefficients computed by the project's TANG, saturated as in Shen, Hedrick & Elkins (1983).

Convention (SPEC 2, ``solvers.contact.tang``): creepages gamma_1 (longitudinal, travel
direction), gamma_2 (lateral, toward the field side) and the spin phi (1/m) are those of
the rail relative to the wheel; F1, F2 act on the rail, so that in the linear range

    F1 = -c^2 G C11 gamma_1,      F2 = -c^2 G C22 gamma_2 - c^3 G C23 phi       (thesis [3.5])

with c = sqrt(a b) of the Hertz ellipse (``hertz``) and G the shear modulus.  Kalker's
coefficients C11, C22, C23 depend on a/b and nu only; here they come from steady TANG
(``solvers.contact.tang.tang_steady``) on the Hertz pressure of an ellipse at a creepage so
small that the patch sticks (the no-slip limit Kalker's table gives), tabulated once per
process over a/b = 0.1 .. 10 and interpolated by a cubic spline in log(a/b).  Checked
against Kalker's Table E.3 in tests/curving/test_creep.py.

Saturation (Shen, Hedrick & Elkins, 1983, the Vermeulen-Johnson cubic on the resultant):
with u = |F_lin| / (mu N),  |F| = mu N (u - u^2/3 + u^3/27) for u < 3, mu N beyond, and F
along F_lin.  It is C1 (the cubic meets the limit with zero slope), so the curving solver's
Newton iterations stay smooth.  Its error against TANG with the same patch, creepages and
mu is measured in tests/curving/test_creep.py (docs/validation/90_curving.md).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from solvers.contact.influence import shear_modulus

from solvers.curving.hertz import hertz_semi_axes
from solvers.contact.tang import tang_steady

RATIOS = np.geomspace(0.1, 10.0, 13)   # a/b where the coefficients are computed
TANG_ELEMENTS = 40                     # elements across each semi-axis pair (the ellipse's box)


def tang_coefficients(ratio: float, E: float = 210e9, nu: float = 0.3, n: int = TANG_ELEMENTS):
    """(C11, C22, C23) from steady TANG on the Hertz pressure of an ellipse a/b = ratio (no slip:
    mu large, creepages 1e-6 and spin 1e-4 1/m on a c = 5 mm patch)."""
    c = 5e-3
    a, b = c * math.sqrt(ratio), c / math.sqrt(ratio)
    dx, dy = 2 * a / n, 2 * b / n
    x = (np.arange(n) - 0.5 * (n - 1)) * dx
    y = (np.arange(n) - 0.5 * (n - 1)) * dy
    p3 = 1e9 * np.sqrt(np.clip(1 - (x[:, None] / a) ** 2 - (y[None, :] / b) ** 2, 0.0, None))
    G = shear_modulus(E, nu)
    g, w = 1e-6, 1e-4
    c11 = -tang_steady(p3, dx, dy, 10.0, 50.0, gamma_x=g, E=E, nu=nu).F1 / (c * c * G * g)
    c22 = -tang_steady(p3, dx, dy, 10.0, 50.0, gamma_y=g, E=E, nu=nu).F2 / (c * c * G * g)
    c23 = -tang_steady(p3, dx, dy, 10.0, 50.0, spin=w, E=E, nu=nu).F2 / (c ** 3 * G * w)
    return c11, c22, c23


@functools.lru_cache(maxsize=4)
def kalker_table(E: float = 210e9, nu: float = 0.3):
    """Cubic splines C_ij(log(a/b)) over RATIOS, computed with TANG once per process."""
    from scipy.interpolate import CubicSpline  # lazy: brings in scipy

    C = np.array([tang_coefficients(r, E, nu) for r in RATIOS])
    return tuple(CubicSpline(np.log(RATIOS), C[:, k]) for k in range(3))


def kalker_coefficients(ratio: float, E: float = 210e9, nu: float = 0.3) -> tuple[float, float, float]:
    """C11, C22, C23 at a/b = ratio (clamped to the tabulated 0.1 .. 10)."""
    t = math.log(min(max(ratio, RATIOS[0]), RATIOS[-1]))
    return tuple(float(s(t)) for s in kalker_table(E, nu))


def saturate(F1, F2, limit):
    """Shen-Hedrick-Elkins: the linear forces (F1, F2) scaled so that the resultant follows
    mu N (u - u^2/3 + u^3/27), u = |F_lin| / (mu N), saturating at mu N for u >= 3."""
    Fr = math.hypot(F1, F2)
    if limit <= 0.0:
        return 0.0, 0.0
    u = Fr / limit
    if u < 3.0:
        k = 1.0 - u / 3.0 + u * u / 27.0
    else:
        k = 1.0 / u  # |F| = limit
    return k * F1, k * F2


@dataclass(frozen=True)
class CreepLaw:
    """How the creep forces are computed.

    kind 'kalker': Hertz patch + TANG coefficients + Shen-Hedrick-Elkins saturation with
    Coulomb mu (E, nu of steel).  kind 'linear': F1 = -f11 g1, F2 = -f22 g2 - f23 phi with fixed
    coefficients (N, N, N m) and no saturation, the creep law of the linear curving theory.
    """

    kind: str = "kalker"
    mu: float = 0.35
    E: float = 210e9
    nu: float = 0.3
    f11: float = 0.0
    f22: float = 0.0
    f23: float = 0.0


@dataclass(frozen=True)
class Patch:
    """Contact patch and its creep forces (N on the rail, SI)."""

    a: float
    b: float
    F1: float
    F2: float


def creep_forces(law: CreepLaw, N: float, A: float, B: float, g1: float, g2: float, phi: float) -> Patch:
    """Creep forces on the rail for normal load N (N), relative curvatures A (rolling) and B
    (lateral, 1/m), creepages g1, g2 and spin phi (1/m)."""
    if law.kind == "linear":
        return Patch(math.nan, math.nan, -law.f11 * g1, -law.f22 * g2 - law.f23 * phi)
    if N <= 0.0:
        return Patch(0.0, 0.0, 0.0, 0.0)
    a, b = hertz_semi_axes(A, B, N, law.E, law.nu)
    C11, C22, C23 = kalker_coefficients(a / b, law.E, law.nu)
    G, c = shear_modulus(law.E, law.nu), math.sqrt(a * b)
    F1, F2 = saturate(-c * c * G * C11 * g1, -c * c * G * C22 * g2 - c ** 3 * G * C23 * phi, law.mu * N)
    return Patch(a, b, F1, F2)
