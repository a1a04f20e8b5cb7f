"""The pass-by of a train of incoherent point sources (pure numerics: arrays in, levels out).

Geometry: the train runs along x at speed v; its sources sit at x_i (m, backward from the train's
front, e.g. every axle), lateral y_i (m, + toward the receiver) and height z_i above the rail head.
A receiver at lateral distance d from the track centre and height h sees source i at
perpendicular distance rho_i = sqrt((d - y_i)^2 + (h - z_i)^2) and, when the train's front is at X,
at r_i = sqrt((X - x_i)^2 + rho_i^2).

Propagation: free field, geometric spreading of a point source over the whole sphere,
L_p = L_W - 10 lg(4 pi r^2) = L_W - 20 lg r - 11 dB (CNOSSOS-EU's A_div, Directive (EU) 2015/996
Annex II 2.5.6), optionally with the horizontal dipole directivity 10 lg(0.01 + 0.99 sin^2 phi) of
the rolling-noise source (2.3.15; sin phi = rho / r); no ground effect, no air absorption, no Doppler.
The sources add incoherently (energies).  Levels are A-weighted when the sound powers are.

* L_max: the maximum of sum_i p_i^2 over the passage, on a grid of the train's position fine enough
  (rho_min / 400) that it is within 1e-4 dB of the true maximum;
* the exposure in closed form, int dt / r^2 = pi / (rho v) for an omnidirectional source and
  int sin^2(phi) dt / r^2 = pi / (2 rho v) for the dipole's term, so
  E_i = W_i / (4 pi) * pi / (rho_i v) * (1 or 0.01 + 0.99 / 2);  L_E = 10 lg(sum E_i) (re 1 s);
* L_eq over the pass-by time T_p = train length / v: L_E - 10 lg T_p (ISO 3095:2013's transit
  exposure level TEL).
For a long uniform line of sources (W' per metre) this gives L_eq,Tp = L_W' - 10 lg(4 rho) (the
infinite line source), the hand check of the tests.
"""
from __future__ import annotations

import numpy as np


def _arrays(x, y, z, L_W):
    x, y, z, L = (np.atleast_1d(np.asarray(a, float)) for a in (x, y, z, L_W))
    x, y, z, L = np.broadcast_arrays(x, y, z, L)
    if x.size == 0 or not np.all(np.isfinite(x + y + z)):
        raise ValueError("sources: at least one, finite positions")
    return x, y, z, L


def perpendicular(y, z, d: float, h: float) -> np.ndarray:
    """rho_i (m) of sources at (y, z) from a receiver at lateral d and height h."""
    rho = np.hypot(d - np.asarray(y, float), h - np.asarray(z, float))
    if np.any(rho <= 0.0):
        raise ValueError("a receiver on a source's line of travel")
    return rho


def level_at(X, x, y, z, L_W, d: float, h: float, dipole=False) -> np.ndarray:
    """Sound pressure level (dB) at the receiver with the train's front at X (array of m); ``dipole``:
    per source (or for all), whether it has the horizontal dipole directivity."""
    x, y, z, L = _arrays(x, y, z, L_W)
    rho = perpendicular(y, z, d, h)
    X = np.atleast_1d(np.asarray(X, float))[:, None]
    r2 = (X - x[None, :]) ** 2 + rho[None, :] ** 2
    dip = np.broadcast_to(np.asarray(dipole, bool), x.shape)[None, :]
    g = np.where(dip, 0.01 + 0.99 * rho[None, :] ** 2 / r2, 1.0)
    e = np.sum(10.0 ** (L[None, :] / 10.0) * g / (4.0 * np.pi * r2), axis=1)
    return 10.0 * np.log10(e)


def passby_levels(x, y, z, L_W, speed: float, d: float, h: float, length: float, dipole=False) -> dict:
    """{'L_max', 'X_max' (the front's position at the maximum, m), 'L_E' (re 1 s), 'L_eq' (over
    T_p = length / speed), 'T_p'} of the sources (module notes); speed in m/s, length in m."""
    x, y, z, L = _arrays(x, y, z, L_W)
    if not (speed > 0.0 and length > 0.0):
        raise ValueError(f"speed {speed!r} m/s and length {length!r} m: both > 0")
    rho = perpendicular(y, z, d, h)
    step = float(rho.min()) / 400.0
    X = np.arange(x.min() - 3.0 * rho.max(), x.max() + 3.0 * rho.max() + step, step)
    lev = level_at(X, x, y, z, L, d, h, dipole)
    k = int(np.argmax(lev))
    w = 10.0 ** (L / 10.0)
    factor = np.where(np.broadcast_to(np.asarray(dipole, bool), x.shape), 0.01 + 0.99 / 2.0, 1.0)
    E = float(np.sum(w / (4.0 * np.pi) * np.pi / (rho * speed) * factor))
    T_p = length / speed
    L_E = 10.0 * np.log10(E)
    return {"L_max": float(lev[k]), "X_max": float(X[k]), "L_E": L_E, "L_eq": L_E - 10.0 * np.log10(T_p),
            "T_p": T_p}


def a_weighted_sum(f_hz, L_db) -> float:
    """10 lg sum 10^((L + A(f))/10): a band spectrum's A-weighted total (IEC 61672-1 A(f))."""
    f2 = np.asarray(f_hz, float) ** 2
    ra = 12194.0 ** 2 * f2 ** 2 / ((f2 + 20.6 ** 2) * np.sqrt((f2 + 107.7 ** 2) * (f2 + 737.9 ** 2))
                                   * (f2 + 12194.0 ** 2))
    A = 20.0 * np.log10(ra) + 2.00
    return float(10.0 * np.log10(np.sum(10.0 ** ((np.asarray(L_db, float) + A) / 10.0))))
