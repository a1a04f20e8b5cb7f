"""Exact Kirchhoff frequencies of a completely FREE solid circular plate.

W(r) = A J_n(kr) + C I_n(kr) (regular at the centre); the free edge r = a
gives M_r = 0 and the Kirchhoff shear V_r = 0.  The edge rows are the same
dimensionless expressions as in ``annular_plate`` (m(Z), v(Z) with s = -1
for J_n and +1 for I_n); the I_n column is scaled by exp(-lambda).
"""
from __future__ import annotations

import numpy as np
from scipy import optimize, special


def _det(lam, n, nu):
    x = lam
    nn = float(n * n)

    def rows(z, dz, s):
        d2z = -dz / x + (s + nn / (x * x)) * z
        return d2z + nu * (dz / x - nn * z / (x * x)), s * dz - (1.0 - nu) * nn / (x * x) * (dz - z / x)

    mj, vj = rows(special.jv(n, x), 0.5 * (special.jv(n - 1, x) - special.jv(n + 1, x)), -1.0)
    mi, vi = rows(special.ive(n, x), 0.5 * (special.ive(n - 1, x) + special.ive(n + 1, x)), +1.0)
    return (mj * vi - mi * vj) / np.hypot(np.hypot(mj, vj), np.hypot(mi, vi)) ** 2


def free_disc_nondimensional(n: int, nu: float, count: int = 2) -> np.ndarray:
    """lambda^2 = omega a^2 sqrt(rho h / D) of the first `count` elastic
    modes with n nodal diameters (rigid-body modes excluded)."""
    grid = np.arange(0.3, 30.0, 0.005)
    d = _det(grid, n, nu)
    roots = []
    for i in np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0]:
        r = optimize.brentq(_det, grid[i], grid[i + 1], args=(n, nu), xtol=1e-13)
        if abs(_det(r, n, nu)) < 1e-8:
            roots.append(r)
        if len(roots) == count:
            break
    return np.array(roots) ** 2
