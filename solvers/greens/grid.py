"""The discretisation of the Green's functions the greens stage stores (SPEC 3.3, 3.4; thesis [4.3]-[4.5]):
the band of the models, the Kropp grids and the kernels' lengths, and the rail receptance's roll-off.
"""
from __future__ import annotations

import numpy as np

from solvers.constants import F_MAX_HZ

RAIL_F_MAX = F_MAX_HZ  # upper limit of the rail model (Hz)
RAIL_F_TAPER = 9000.0  # the rail receptance is rolled off smoothly from RAIL_F_MAX to zero here (Hz)
WHEEL_BAND_LIMIT = F_MAX_HZ  # the wheel kernel's DFT matches the receptance up to here (band-limited correction)
WHEEL_DECAY_DB = 120.0  # decay of the wheel kernel by N_t/2 dt (choose_grid)
KROPP_TAPS = 16  # samples refitted by the band-limited correction
KROPP_FIT_TOL = 1e-3  # its pointwise tolerance relative to |G|
WHEEL_LAGS = 1 << 15  # lags of the stored wheel kernel (1.2 s at 36 us)
RAIL_NT = 8192  # Kropp grid of the rail: df = 1/(N_t dt) = 3.4 Hz at 36 us
RAIL_LAGS = 4096  # moving-kernel length (0.147 s, 2 m at 50 km/h); its decay is checked


def rail_taper(f) -> np.ndarray:
    """1 up to RAIL_F_MAX, 0 from RAIL_F_TAPER, between them the C-infinity step
    1 - e(u) / (e(u) + e(1 - u)), e(u) = exp(-1/u), u = (f - RAIL_F_MAX)/(RAIL_F_TAPER - RAIL_F_MAX):
    all derivatives continuous, so the Hilbert transform of the tapered Re G (the
    Im of Kropp's kernel) is smooth at RAIL_F_MAX (a hard cut puts a log singularity there)."""
    u = np.clip((np.asarray(f, float) - RAIL_F_MAX) / (RAIL_F_TAPER - RAIL_F_MAX), 0.0, 1.0)
    out = np.where(u <= 0.0, 1.0, 0.0)
    mid = (u > 0.0) & (u < 1.0)
    a = np.exp(-1.0 / u[mid])
    b = np.exp(-1.0 / (1.0 - u[mid]))
    out[mid] = b / (a + b)
    return out
