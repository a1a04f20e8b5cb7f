"""Figure of the pass-by (passby_<receiver>.png): the F-weighted A level over the passage."""
from __future__ import annotations

import numpy as np


def passby_figure(a: dict, title: str):
    """L_AF(t) (``a``: passby_<tag>.npz's arrays) with L_pAeq and L_AFmax marked."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig, ax = plt.subplots(figsize=(7.5, 3.8))
    ax.plot(a["t_F"], a["L_AF"], color="C0", label="L_AF(t) (F time weighting, 125 ms)")
    ax.axhline(float(a["L_Aeq"]), color="C1", ls="--", label=f"L_pAeq = {float(a['L_Aeq']):.1f} dB(A) over "
                                                               f"{float(a['T']):.1f} s")
    ax.plot([float(a["t_AFmax"])], [float(a["L_AFmax"])], "v", color="C3",
            label=f"L_AFmax = {float(a['L_AFmax']):.1f} dB(A)")
    top = float(a["L_AFmax"])
    ax.set_ylim(top - 40, top + 5)
    ax.set_xlim(0, float(a["T"]))
    ax.set_xlabel("time (s)")
    ax.set_ylabel("dB(A) re 20 uPa")
    ax.set_title(f"{title}: {int(a['n_bogies'])} squealing wheels, {float(a['bogie_spacing']):g} m apart, "
                 f"{3.6 * float(a['speed']):.0f} km/h", fontsize=9)
    ax.legend(fontsize=8, loc="lower center")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig
