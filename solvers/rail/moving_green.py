"""The rail's moving Green's function by Kropp's construction per lag (SPEC 3.4; thesis
[4.3]-[4.5]): the reference for the fast wave-table form of ``solvers.rail.moving_kernel``."""
from __future__ import annotations

from typing import Callable

import numpy as np

from solvers.greens.band_fit import BandFit, band_index, fit_first_taps
from solvers.greens.kropp import frequency_grid, kropp


def moving_green(transfer: Callable, v: float, dt: float, n_k: int, n_t: int, chunk: int = 16,
                 band_limit: float | None = None, taps: int = 16, fit_tol: float = 1e-3, info: bool = False):
    """Moving Green's function of a translation-invariant rail (SPEC 3.4):
    g_mov[k] = g^R(x_k = v k dt, k dt), k = 0..n_k-1, (n_k, 2, 2) in m/N.

    ``transfer(x (nx,), f (nf,)) -> complex (nx, nf, 2, 2)``: the transfer
    receptance at distance x >= 0 (m/N, components 2, 3 as in the module notes).
    Each lag is Kropp's construction (``green_from_receptance``) evaluated at the
    single time k dt with the receptance at x_k:

        g_mov[k] = 1/N_t [S_0 + 2 sum_{m=1}^{N_t/2-1} S_m cos(2 pi m k/N_t) + S_{N_t/2} (-1)^k],
        S_m = 2 Re G^R(x_k, f_m),  f_m = m/(N_t dt),

    halved at k = 0.  v = 0 gives exactly the fixed-point Green's function at x = 0.
    Cost: n_k evaluations of the transfer receptance on N_t/2 + 1 frequencies
    (``chunk`` distances per call).  n_k <= N_t/2 + 1; the fixed-point response
    must have decayed by N_t/2 dt (check with ``decayed`` on the x = 0 function).

    ``band_limit``: the lags k < taps take the band-limited correction of the
    fixed-x kernel of G^R(x_k, .) (``green_from_receptance``), so that each
    g^R(x_k, .) reproduces its receptance up to band_limit; v = 0 then equals
    ``green_from_receptance(G^R(0, .), band_limit=..)``.  For causal receptances
    only (not the hysteretic BV50 model).  ``info``: also return a ``BandFit``
    (correction = the values added at lags 0..taps-1, fit_error = the worst over
    those lags; None without band_limit).
    """
    n_t, n_k = int(n_t), int(n_k)
    if n_t % 2 or n_t < 2:
        raise ValueError(f"n_t must be even, got {n_t}")
    if not 1 <= n_k <= n_t // 2 + 1:
        raise ValueError(f"n_k = {n_k} must lie in 1..N_t/2 + 1 = {n_t // 2 + 1}")
    f = frequency_grid(dt, n_t)
    nf = len(f)
    kb = band_index(band_limit, dt, n_t) if band_limit is not None else -1
    taps = min(int(taps), n_k)
    wts = np.full(nf, 2.0)
    wts[0] = 1.0
    wts[-1] = 1.0
    m = np.arange(nf, dtype=np.int64)
    g = np.zeros((n_k, 2, 2))
    corr = np.zeros((taps, 2, 2))
    err = np.zeros((2, 2))
    n_fit = 0
    for a in range(0, n_k, chunk):
        ks = np.arange(a, min(n_k, a + chunk), dtype=np.int64)
        x = v * ks * dt
        G = np.asarray(transfer(x, f))
        if G.shape != (len(ks), nf, 2, 2):
            raise ValueError(f"transfer returned shape {G.shape}, expected {(len(ks), nf, 2, 2)}")
        C = np.cos((2 * np.pi / n_t) * ((ks[:, None] * m[None, :]) % n_t)) * (wts / n_t)
        g[ks] = np.einsum("km,kmij->kij", C, 2.0 * G.real)
        if band_limit is not None:
            for i, k in enumerate(ks[ks < taps]):    # lags with a correction: the whole kernel of G(x_k, .)
                gx = kropp(2.0 * G[i].real, n_t)
                h, e, n_fit = fit_first_taps(G[i, : kb + 1], gx, dt, n_t, taps, float(fit_tol))
                corr[k] = h[k]
                err = np.maximum(err, e)
    g[0] *= 0.5
    g[:taps] += corr if band_limit is not None else 0.0
    if not info:
        return g
    return g, (BandFit(float(band_limit), taps, corr, err, n_fit) if band_limit is not None else None)
