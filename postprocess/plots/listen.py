"""Figure of the listen stage (listen.png): the 1/3-octave spectrum at the
receiver (unweighted and A-weighted) and the envelope of the sound (onset,
limit cycle)."""
from __future__ import annotations

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB


def listening_figure(a: dict, case: str):
    """``a``: the arrays of listen.npz.  Returns the figure."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(9, 8), gridspec_kw={"height_ratios": [2, 1]})
    nom = a["band_nominal"]
    keep = np.isfinite(a["band_L_p"]) | np.isfinite(a["band_L_pA"])
    top = np.nanmax(np.where(np.isfinite(a["band_L_p"]), a["band_L_p"], np.nan)) if keep.any() else 0.0
    floor = top - 80
    x = np.arange(len(nom))
    Lz = np.where(np.isfinite(a["band_L_p"]), a["band_L_p"], floor)
    LA = np.where(np.isfinite(a["band_L_pA"]), a["band_L_pA"], floor)
    ax.bar(x - 0.2, Lz - floor, 0.4, bottom=floor, label=f"unweighted: L_p = {float(a['L_p']):.1f} dB")
    ax.bar(x + 0.2, LA - floor, 0.4, bottom=floor, label=f"A-weighted: L_pA = {float(a['L_pA']):.1f} dB(A)")
    ax.set_xticks(x[::3], [f"{v:g}" for v in nom[::3]], rotation=45)
    ax.set_xlim(-0.7, len(nom) - 0.3)
    ax.set_ylim(floor, top + 10)
    ax.set_xlabel("1/3-octave band, nominal mid-band frequency (Hz)")
    ax.set_ylabel("L_p (dB re 20 uPa)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    flag = "" if a["meaningful"] else f" (no squeal: L_F2 < {SQUEAL_LEVEL_DB:g} dB, levels not meaningful)"
    ax.set_title(f"{case}: receiver {float(a['distance']):g} m from the track centre, {float(a['height']):g} m above "
                 f"the rail\n(wheel centre {float(a['r_direct']):.2f} m away; {a['ground']} ground "
                 f"{float(a['ground_depth']):g} m below the rail, {a['directivity']} source){flag}", fontsize=9)
    t, g = a["onset_t"], a["onset_gain"]
    Lp = float(a["L_p"]) if np.isfinite(a["L_p"]) else 0.0  # -inf: no sound power at all
    ax2.plot(t, 20 * np.log10(np.maximum(g, 1e-12)) + Lp, lw=0.8)
    ax2.axvline(float(a["t_limit_cycle"]), color="k", lw=0.6, ls="--", label="limit cycle from here")
    ax2.set_ylim(Lp - 60, Lp + 10)
    ax2.set_xlabel("time in the WAV (s)")
    ax2.set_ylabel("L_p envelope (dB)")
    ax2.set_title(f"the sound: onset from the growth phase, then the limit cycle ({float(a['wav_duration']):.2f} s, "
                  f"0 dBFS sine = {float(a['full_scale_sine_dB']):.1f} dB SPL)", fontsize=9)
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    return fig
