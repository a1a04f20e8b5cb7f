"""The root finding of the steady-curving equations shared by the active-set iteration (``solve``) and its
semismooth fallback (``semismooth``): Newton's polish with a forward-difference Jacobian, and a residual
that backs the iteration off a trial point outside the profiles instead of raising.
"""
from __future__ import annotations

import numpy as np

TOL = 1e-10          # residuals / (Q0, Q0 * 1 m) required


def newton(fun, z, tol=TOL, max_iter=40):
    """Polish a root with Newton steps (forward-difference Jacobian, step 1e-7 in scaled units)."""
    r = fun(z)
    for _ in range(max_iter):
        if np.max(np.abs(r)) < tol:
            break
        J = np.empty((len(r), len(z)))
        for k in range(len(z)):
            dz = np.zeros_like(z)
            dz[k] = 1e-7 * max(1.0, abs(z[k]))
            J[:, k] = (fun(z + dz) - r) / dz[k]
        step = np.linalg.lstsq(J, -r, rcond=None)[0]
        t = 1.0
        while t > 1e-3:
            r_new = fun(z + t * step)
            if np.max(np.abs(r_new)) < np.max(np.abs(r)):
                break
            t *= 0.5
        z, r = z + t * step, r_new
    return z, r


def safe_residual(fun_of, flanges, y_f, prof, veh, trk, law):
    """The residual function of one flange set; a trial point off the profiles gives a large
    residual (so that the iteration backs off) instead of an exception."""
    def fun(v):
        try:
            r = fun_of(v, flanges, y_f, prof, veh, trk, law)
        except (ValueError, ZeroDivisionError, OverflowError):
            return np.full(len(v), 1e3)
        return np.where(np.isfinite(r), r, 1e3)
    return fun
