"""Figure of the simulate stage (simulate.png): the contact forces and their spectrum."""
from __future__ import annotations

import numpy as np
from solvers.spectra import amplitude_spectrum


def forces_figure(res, m: dict, case: str):
    """F2 history, the last 20 ms of F2 and F3, the F2 spectrum (``res``: the
    interaction result; ``m``: its squeal measures)."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib


    fig, axs = plt.subplots(3, 1, figsize=(9, 8))
    axs[0].plot(res.t, res.F[:, 1] / 1e3, lw=0.5)
    axs[0].set_ylabel("F2 (kN)")
    axs[0].set_title(f"{case}: {res.stop_reason} after {res.duration:.2f} s; L_F2 = {m['L_F2']:.1f} dB, "
                     f"dominant {m['f_dominant']:.1f} Hz")
    tail = slice(max(0, len(res.t_final) - int(0.02 / (res.dt_final or res.dt))), None)
    axs[1].plot(1e3 * res.t_final[tail], res.F_final[tail, 1] / 1e3, label="F2")
    axs[1].plot(1e3 * res.t_final[tail], (res.F_final[tail, 2] - res.F_final[:, 2].mean()) / 1e3,
                label="F3 - mean")
    axs[1].set_xlabel("time (ms)")
    axs[1].set_ylabel("kN")
    axs[1].legend(fontsize=8)
    f, A = amplitude_spectrum(res.F_final[:, 1], res.dt_final or res.dt)
    axs[2].semilogy(f, np.maximum(np.abs(A), 1e-6))
    axs[2].set_xlim(0, 7000)
    axs[2].set_xlabel("frequency (Hz)")
    axs[2].set_ylabel("|F2| (N)")
    for ax in axs:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig
