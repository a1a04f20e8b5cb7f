"""Figure of the greens stage (greens.png): the wheel and rail Green's functions."""
from __future__ import annotations

import numpy as np


def kernels_figure(a: dict, case: str):
    """The first lags of the wheel and rail Green's functions (``a``: greens.npz)."""
    from matplotlib.figure import Figure  # no pyplot (its import is half a second of a stage's time)

    fig = Figure(figsize=(8, 6))
    axs = fig.subplots(2, 1)
    tw = np.arange(len(a["wheel_kernel"])) * a["dt"]
    tr = np.arange(len(a["rail_kernel"])) * a["dt"]
    for (i, j, lab) in ((0, 0, "g22"), (1, 1, "g33"), (0, 1, "g23")):
        axs[0].plot(*envelope(1e3 * tw, a["wheel_kernel"][:, i, j]), lw=0.6, label=lab)
        axs[1].plot(1e3 * tr, a["rail_kernel"][:, i, j], lw=0.8, label=lab)
    axs[0].set_title(f"{case}: wheel Green's function (modal, band-limited to {a['wheel_band_limit'] / 1e3:.1f} kHz), "
                     f"first {len(tw)} lags of dt = {1e6 * a['dt']:.0f} us", fontsize=9)
    axs[1].set_title(f"rail moving Green's function ({len(tr)} lags), v = {3.6 * a['v']:.0f} km/h", fontsize=9)
    for ax in axs:
        ax.set_xlabel("time (ms)")
        ax.set_ylabel("m/N")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.subplots_adjust(left=0.11, right=0.98, bottom=0.08, top=0.94, hspace=0.4)  # fixed: tight_layout costs 0.3 s
    return fig


def envelope(t: np.ndarray, y: np.ndarray, n_bins: int = 2048) -> tuple[np.ndarray, np.ndarray]:
    """A long oscillating record as the line through each bin's minimum and maximum, in time order:
    at a figure's resolution (fewer pixels than bins) the same drawing as every sample, with
    2 n_bins points (records shorter than 4 n_bins are returned as they are)."""
    n = len(y) // n_bins
    if n < 4:
        return t, y
    m = n * n_bins
    yb, tb = y[:m].reshape(n_bins, n), t[:m].reshape(n_bins, n)
    lo, hi = yb.argmin(axis=1), yb.argmax(axis=1)
    first, second = np.minimum(lo, hi), np.maximum(lo, hi)
    rows = np.arange(n_bins)
    tt = np.stack([tb[rows, first], tb[rows, second]], axis=1).ravel()
    yy = np.stack([yb[rows, first], yb[rows, second]], axis=1).ravel()
    return np.append(tt, t[m:]), np.append(yy, y[m:])
