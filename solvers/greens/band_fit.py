"""The band-limited correction of Kropp's first samples (module notes of ``solvers.greens.kernels``):
refit g[:taps] so that the DFT of g reproduces the receptance pointwise up to a band limit, by
Tikhonov-regularised least squares with the regularisation chosen by the discrepancy principle."""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import scipy.fft as sfft


class BandFit(NamedTuple):
    """What the band-limited correction did (``green_from_receptance(.., info=True)``)."""
    band_limit: float       # Hz: top of the band where DFT(g) = G is fitted
    taps: int               # g[0..taps-1] were corrected
    correction: np.ndarray  # (taps, ...) m/N, added to Kropp's g[:taps]
    fit_error: np.ndarray   # (...) max |DFT(g) - G| / min|G| over the fit segments, per component
    n_fit: int              # number of fit frequencies


def band_index(band_limit: float, dt: float, n_t: int) -> int:
    """Last grid index k with f_k <= band_limit (checked against the Nyquist frequency)."""
    if not 0.0 < band_limit < 0.5 / dt:
        raise ValueError(f"band_limit = {band_limit} Hz must lie between 0 and the Nyquist frequency {0.5 / dt:.0f} Hz")
    kb = int(math.floor(band_limit * n_t * dt + 1e-9))
    if kb < 3:
        raise ValueError(f"band_limit = {band_limit} Hz holds fewer than 3 grid points (df = {1 / (n_t * dt):.3g} Hz)")
    return kb


def fit_first_taps(G_band: np.ndarray, g: np.ndarray, dt: float, n_t: int, taps: int, fit_tol: float,
                    n_fit: int = 2000):
    """The correction h of g[:taps] (module notes: band-limited correction).
    G_band: the receptance on grid points 0..kb (kb + 1, ...); g: Kropp's kernel
    (N_t/2 + 1, ...).  Returns h (taps, ...), the reached max weighted residual
    per component (...), the number of fit frequencies."""
    kb = G_band.shape[0] - 1
    if not 1 <= taps <= g.shape[0]:
        raise ValueError(f"taps = {taps} must lie in 1..N_t/2 + 1")
    comp = G_band.shape[1:]
    Gb = G_band.reshape(kb + 1, -1)
    E = Gb - sfft.rfft(g, n=n_t, axis=0)[: kb + 1].reshape(kb + 1, -1)   # what is missing in band
    edges = fit_edges(kb, n_fit)
    k0 = edges[:-1]
    h, err = fit_taps(np.abs(Gb), E[k0], E[k0 + 1], edges, n_t, taps, fit_tol)
    return h.reshape((taps,) + comp), err.reshape(comp), len(k0)


def fit_edges(kb: int, n_fit: int = 2000) -> np.ndarray:
    """The fit segments [e_i, e_i+1] of the band's grid points 1..kb: the pair of grid points
    (e_i, e_i + 1) is the fit point, min |G| over the segment its weight."""
    return np.unique(np.linspace(1, kb, min(n_fit, kb // 2) + 1).round().astype(np.int64))


def fit_taps(absG: np.ndarray, E0: np.ndarray, E1: np.ndarray, edges: np.ndarray, n_t: int, taps: int,
             fit_tol: float):
    """The correction h (taps, C) of the first samples and the reached max weighted residual (C,),
    from |G| on the band's grid points 0..edges[-1] (or more) (kb + 1, C) and the error E = G - DFT(g)
    at the fit points' two grid points k0 = edges[:-1] and k0 + 1 (len(k0), C) each."""
    k0 = edges[:-1]
    Gmin = np.minimum.reduceat(absG[: edges[-1] + 1], edges, axis=0)[:-1]
    Em = 0.5 * (E0 + E1)
    lags = np.arange(taps)
    ph = (2 * np.pi / n_t) * lags[None, :]
    X = 0.5 * (np.exp(-1j * ph * k0[:, None]) + np.exp(-1j * ph * (k0[:, None] + 1)))  # DFT of the taps, same means
    h = np.zeros((taps, absG.shape[1]))
    err = np.zeros(absG.shape[1])
    for c in range(absG.shape[1]):
        top = absG[:, c].max()
        if top == 0.0:
            continue
        W = 1.0 / np.maximum(Gmin[:, c], 1e-9 * top)
        A = np.vstack([W[:, None] * X.real, W[:, None] * X.imag])
        y = np.concatenate([W * Em[:, c].real, W * Em[:, c].imag])
        U, sv, Vt = np.linalg.svd(A, full_matrices=False)
        uy = U.T @ y

        def solve(lam):
            return Vt.T @ (sv * uy / (sv ** 2 + lam ** 2))

        def resid(x):
            return float(np.abs(W * (X @ x - Em[:, c])).max())

        # discrepancy principle: the largest lambda (smallest correction) that reaches fit_tol
        lo, hi = -12.0, 2.0
        if resid(solve(10 ** lo * sv[0])) <= fit_tol:
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                if resid(solve(10 ** mid * sv[0])) <= fit_tol:
                    lo = mid
                else:
                    hi = mid
        h[:, c] = solve(10 ** lo * sv[0])
        err[c] = resid(h[:, c])
    return h, err
