"""The moving rail kernel's arrays from a head point's wave table: the one builder behind every cache of them.

``moving_kernel_arrays(k, a, v, dt, grid, taper)`` takes the waves (wavenumbers k, amplitudes a at the
frequencies of Kropp's grid below f_taper) of one head point and returns what the Green's-function stage
reads: the moving kernel g_mov (``solvers.rail.moving_kernel``, SPEC 3.4), the fixed-point kernel (the
same receptance at v = 0, whose decay by N_t/2 dt is the grid's check, SPEC 3.3), the kernel's tail ratio
and the untapered point receptance.  The waves come from a point's own table
(``pipeline.caches.rail_kernel``, ``pipeline.curve.rail_point``) or from the running surface's shared table
(``pipeline.caches.rail_surface_table``), whose static near-field waves are summed apart
(``static_tol``: ``solvers.rail.moving_static``; the same numbers as summing them with the others).
"""
from __future__ import annotations

import numpy as np

from solvers.greens.kropp import decayed, frequency_grid, green_from_receptance
from solvers.rail.moving_kernel import moving_green_waves
from solvers.rail.moving_static import static_kernel, static_waves


def moving_kernel_arrays(k: np.ndarray, a: np.ndarray, v: float, dt: float, grid: dict, taper,
                         static_tol: float | None = None) -> dict:
    """{'rail_kernel' (n_lags, 2, 2) m/N, 'rail_fixed_kernel', 'rail_decay_db', 'rail_tail_ratio', 'rail_nt',
    'rail_point_receptance' (untapered G(0, f_m))} of the waves ``k`` (nf, M) rad/m and ``a`` (nf, M, 2, 2)
    m/N at f_m = m / (N_t dt) < grid['f_taper'], moving at ``v`` m/s; ``grid``: n_t, n_lags, f_taper;
    ``taper(f)``: the roll-off weights; ``static_tol``: sum the static waves apart, the others' drop
    tolerance this.  Raises RuntimeError when the fixed-point kernel has not decayed (the grid is too short)."""
    n_t, n_lags = int(grid["n_t"]), int(grid["n_lags"])
    f = frequency_grid(dt, n_t)
    inside = f < grid["f_taper"]
    w = taper(f[inside])
    at = a * w[:, None, None, None]
    if static_tol is None:
        g = moving_green_waves(k, at, v, dt, n_lags, n_t)
    else:   # the subtracted static near field: the same at every frequency, summed once
        fixed = static_waves(k)
        g = moving_green_waves(k[:, ~fixed], at[:, ~fixed], v, dt, n_lags, n_t, tol=static_tol) + \
            static_kernel(k[0, fixed], a[0, fixed], w, v, dt, n_lags, n_t)
    G0 = np.zeros((len(f), 2, 2), complex)
    G0[inside] = at.sum(axis=1)                      # G(0, f_m), tapered
    g0 = green_from_receptance(G0, dt, n_t)          # the fixed point: the grid's decay check
    check = decayed(g0)
    if not check.ok:
        raise RuntimeError(f"rail Green's function has not decayed by N_t/2 dt ({check.level_db:.0f} dB)")
    tail = np.abs(g[-n_lags // 8:]).max() / np.abs(g).max()
    return {"rail_kernel": g, "rail_fixed_kernel": g0[:n_lags], "rail_decay_db": np.float64(check.level_db),
            "rail_tail_ratio": np.float64(tail), "rail_nt": np.int64(n_t), "rail_point_receptance": a.sum(axis=1)}
