"""Kropp's method [4.3]-[4.5]: the discrete Green's function of a receptance, its frequency
grid, the choice of N_t and the check that the response has decayed (notes in ``solvers.greens.kernels``)."""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import scipy.fft as sfft

from solvers.greens.band_fit import BandFit, band_index, fit_first_taps


class GreenDecayError(ValueError):
    """The Green's function has not decayed by N_t/2 dt: the frequency grid is too coarse."""


def frequency_grid(dt: float, n_t: int) -> np.ndarray:
    """f_k = k / (N_t dt), k = 0..N_t/2 (Hz)."""
    return np.arange(n_t // 2 + 1) / (n_t * dt)


def kropp(S: np.ndarray, n_t: int) -> np.ndarray:
    """g[0..N_t/2] = causal half of ifft(S) with g[0] halved ([4.5])."""
    s = sfft.irfft(S, n=n_t, axis=0)  # = ifft of the even (real, symmetric) spectrum
    g = s[: n_t // 2 + 1].copy()
    g[0] *= 0.5
    return g


def green_from_receptance(G_of_f, dt: float, n_t: int, chunk: int = 1 << 16, band_limit: float | None = None,
                          taps: int = 16, fit_tol: float = 1e-3, info: bool = False):
    """Kropp's method [4.3]-[4.5]: the discrete Green's function g[k], k = 0..N_t/2.

    ``G_of_f``: a callable f (nf,) -> complex receptance (nf, ...) in m/N, or the
    receptance already sampled on ``frequency_grid(dt, n_t)``.  N_t must be even.
    Returns g (N_t/2 + 1, ...) in m/N: g[0] = 0.5 ifft(S)[0], g[k] = ifft(S)[k]
    (= dt s(k dt) of [4.5], see the module notes), S = 2 Re G.  The callable is
    evaluated in chunks of ``chunk`` frequencies.

    ``band_limit`` (Hz, default None = plain Kropp): refit g[:taps] so that the DFT
    of g reproduces G pointwise up to band_limit, to ``fit_tol`` relative to |G|
    (module notes: band-limited correction; for causal receptances only).
    ``info``: also return a ``BandFit`` (None without band_limit).
    """
    n_t = int(n_t)
    if n_t < 2 or n_t % 2:
        raise ValueError(f"n_t must be even and >= 2, got {n_t}")
    f = frequency_grid(dt, n_t)
    kb = band_index(band_limit, dt, n_t) if band_limit is not None else -1
    if callable(G_of_f):
        first = np.asarray(G_of_f(f[:1]))
        S = np.empty((len(f),) + first.shape[1:])
        G_band = np.empty((kb + 1,) + first.shape[1:], complex)
        for a in range(0, len(f), chunk):
            Gc = np.asarray(G_of_f(f[a:a + chunk]))
            S[a:a + chunk] = 2.0 * np.real(Gc)
            m = min(len(Gc), kb + 1 - a)
            if m > 0:
                G_band[a:a + m] = Gc[:m]
    else:
        G = np.asarray(G_of_f)
        if G.shape[0] != len(f):
            raise ValueError(f"sampled receptance has {G.shape[0]} frequencies, the grid N_t/2 + 1 = {len(f)}")
        S = 2.0 * np.real(G)
        G_band = G[: kb + 1]
    g = kropp(S, n_t)
    fit = None
    if band_limit is not None:
        h, err, n_fit = fit_first_taps(G_band, g, dt, n_t, int(taps), float(fit_tol))
        g[:taps] += h
        fit = BandFit(float(band_limit), int(taps), h, err, n_fit)
    return (g, fit) if info else g


def _slowest_decay(w, zeta):
    """Decay rate (1/s) of the slowest exponential of each mode."""
    w, zeta = np.asarray(w, float), np.asarray(zeta, float)
    over = zeta >= 1.0
    rate = zeta * w
    rate[over] = w[over] * (zeta[over] - np.sqrt(zeta[over] ** 2 - 1.0))
    return rate


def _even_fast_len(n: int) -> int:
    n = sfft.next_fast_len(int(n), real=True)
    while n % 2:
        n = sfft.next_fast_len(n + 1, real=True)
    return n


def choose_grid(f_r, zeta_r, dt: float, points_per_band: float = 6, decay_db: float = 60) -> int:
    """N_t for Kropp's method: the frequency step df = 1/(N_t dt) puts about
    ``points_per_band`` grid points inside the -3 dB band (width 2 zeta f_r) of the
    narrowest resonance, and N_t/2 dt is at least the time in which the slowest
    mode decays by ``decay_db``.  Rounded up to an even fast FFT length (a few %
    more points at most).  With zeta < 1 the band criterion governs for
    decay_db < ~82 dB at 6 points per band: N_t/2 dt = p / (4 zeta f_r) for p
    points per band, by which that mode has decayed by exp(-pi p / 2), 82 dB at
    p = 6.
    Modes with f_r <= 0 or zeta <= 0 are ignored.
    """
    f_r = np.atleast_1d(np.asarray(f_r, float))
    zeta_r = np.broadcast_to(np.asarray(zeta_r, float), f_r.shape)
    ok = (f_r > 0) & (zeta_r > 0) & np.isfinite(f_r) & np.isfinite(zeta_r)
    if not ok.any():
        raise ValueError("choose_grid needs at least one mode with f_r > 0 and zeta > 0")
    f_r, zeta_r = f_r[ok], zeta_r[ok]
    band = 2.0 * zeta_r * f_r
    df = band.min() / float(points_per_band)
    n_band = math.ceil(1.0 / (df * dt))
    t_decay = math.log(10.0 ** (decay_db / 20.0)) / _slowest_decay(2 * np.pi * f_r, zeta_r).min()
    n_decay = 2 * math.ceil(t_decay / dt)
    return _even_fast_len(max(n_band, n_decay, 2))


def points_in_band(f_r: float, zeta_r: float, dt: float, n_t: int) -> int:
    """Number of grid points f_k = k/(N_t dt) inside the -3 dB band
    [f_r (1 - zeta), f_r (1 + zeta)] of one resonance."""
    df = 1.0 / (n_t * dt)
    lo, hi = f_r * (1.0 - zeta_r), f_r * (1.0 + zeta_r)
    return int(math.floor(hi / df) - math.ceil(lo / df) + 1)


class DecayCheck(NamedTuple):
    ok: bool
    level_db: float   # max |g| over the tail relative to max |g| (all components), dB


def decayed(g: np.ndarray, decay_db: float = 60.0, tail: float = 0.05, strict: bool = False) -> DecayCheck:
    """Has the Green's function g[0..N_t/2] (any trailing component axes) decayed
    by ``decay_db`` at its end?  Compares max |g| over the last ``tail`` fraction
    of the lags with max |g| over all lags and components.  If N_t is too short
    the periodic inverse transform folds the undecayed response back (the end
    of g then holds about twice the true g(N_t/2 dt)), so this catches a grid
    that is too coarse.  ``strict``: raise GreenDecayError instead of returning
    ok = False."""
    a = np.abs(np.asarray(g)).reshape(len(g), -1).max(axis=1)
    m = max(1, int(round(tail * len(a))))
    peak = a.max()
    level = 20 * np.log10(max(a[-m:].max(), 1e-300) / peak) if peak > 0 else -np.inf
    res = DecayCheck(bool(level <= -decay_db), float(level))
    if strict and not res.ok:
        raise GreenDecayError(f"Green's function decayed only by {-level:.1f} dB at N_t/2 dt "
                              f"(needs {decay_db:.0f} dB): use a larger N_t (choose_grid)")
    return res
