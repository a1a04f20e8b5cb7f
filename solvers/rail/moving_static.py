"""The moving kernel's part from frequency-independent waves, summed once (SPEC 3.4).

In a wave table whose waves include the static near field of the load subtracted as extra
waves (``solvers.rail.reduced.wave_amplitudes`` with k_local; ``solvers.rail.surface``), those
waves have the same wavenumber k_n and amplitude a_n at every frequency, up to the taper w_m that
rolls the receptance off.  Their term of Kropp's construction (``solvers.rail.moving_kernel``)

    sum_m c_m cos(2 pi m k / N_t) w_m Re(a_n z_n^k) = Re(a_n z_n^k) C[k],
    C[k] = sum_m c_m w_m cos(2 pi m k / N_t),   z_n = exp(-i k_n v dt),

factors into one sum over frequencies for all of them: the same numbers as running them with
the other waves (``moving_green_waves``), without the nf-fold repetition (half the waves of a
table with many loads).
"""
from __future__ import annotations

import numpy as np


def static_waves(k_table: np.ndarray) -> np.ndarray:
    """Mask (M,) of the waves whose wavenumber is the same at every frequency of the table."""
    k = np.asarray(k_table)
    return np.all(k == k[:1], axis=0) if len(k) > 1 else np.zeros(k.shape[1], bool)


def static_kernel(k_static: np.ndarray, a_static: np.ndarray, taper: np.ndarray, v: float, dt: float,
                  n_k: int, n_t: int) -> np.ndarray:
    """g[k] (n_k, 2, 2) of frequency-independent waves k_static (S,), a_static (S, 2, 2) (untapered)
    on Kropp's grid f_m = m / (N_t dt), m = 0..nf-1, with the receptance's taper w_m (nf,): the
    weights of ``moving_kernel.moving_green_waves`` (c_m = 2 w / N_t, w = 2, 1 at m = 0 and at
    N_t/2; lag 0 halved)."""
    nf, n_t = len(taper), int(n_t)
    w = np.full(nf, 2.0)
    w[0] = 1.0
    if nf == n_t // 2 + 1:
        w[-1] = 1.0
    lags = np.arange(int(n_k))
    m = np.arange(nf)
    C = np.empty(len(lags))
    cm = 2.0 * w / n_t * np.asarray(taper, float)
    for s in range(0, len(lags), 512):
        kk = lags[s:s + 512]
        C[s:s + 512] = np.cos(2 * np.pi * ((np.outer(kk, m)) % n_t) / n_t) @ cm
    z = np.exp(-1j * np.outer(lags, k_static) * (float(v) * float(dt)))          # (n_k, S)
    g = np.einsum("ks,sij->kij", z, np.asarray(a_static, complex)).real * C[:, None, None]
    g[0] *= 0.5
    return g
