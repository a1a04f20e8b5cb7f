"""Figures of the rail stage: receptances (receptance.png) and dispersion (dispersion.png)."""
from __future__ import annotations

import numpy as np


def _db(G):
    return 20 * np.log10(np.maximum(np.abs(G), 1e-30))

def receptance_figure(a: dict, name: str):
    """The usual rail receptance figure: |G| in dB re 1 m/N and phase."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    f, G = a["f_hz"], a["G"][:, 0]  # x = 0: point receptances
    fig, axs = plt.subplots(3, 2, figsize=(11, 9), sharex=True)
    for row, (title, i, j) in enumerate([("G33 vertical", 1, 1), ("G22 lateral", 0, 0), ("G23 cross", 0, 1)]):
        for ip, yp in enumerate(a["point_y_m"]):
            axs[row, 0].semilogx(f, _db(G[ip, :, i, j]), label=f"y^R = {1e3 * yp:+.0f} mm")
            axs[row, 1].semilogx(f, np.degrees(np.angle(G[ip, :, i, j])))
        axs[row, 0].set_ylabel(f"{title}\n|G| (dB re 1 m/N)")
        axs[row, 1].set_ylabel("phase (deg)")
        for ax in axs[row]:
            ax.grid(alpha=0.3, which="both")
    axs[0, 0].legend(fontsize=8)
    for ax in axs[-1]:
        ax.set_xlabel("frequency (Hz)")
    fig.suptitle(f"{name}: point receptances at the rail-head contact points", fontsize=10)
    fig.tight_layout()
    return fig


def dispersion_figure(a: dict, name: str):
    """Dispersion curves f(k) of the free and supported rail, both families."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    k = a["disp_k"]
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for ax, sup in zip(axs, ("free", "supported")):
        for fam, style in (("sym", "-"), ("anti", "--")):
            F = a[f"disp_{sup}_{fam}_f_hz"]
            labels = a[f"disp_{sup}_{fam}_label"]
            for b in range(F.shape[1]):
                ax.plot(k, F[:, b], style, lw=1.2, label=f"{fam}: {labels[b]}")
        ax.set_xlabel("wavenumber k (rad/m)")
        ax.set_title(f"{sup} rail")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6, ncol=2)
    axs[0].set_ylabel("frequency (Hz)")
    fig.suptitle(f"{name}: dispersion (symmetric and antisymmetric wave families)", fontsize=10)
    fig.tight_layout()
    return fig
