"""Figure of the radiate stage (radiate.png): force spectra, sound power, unit-force curves."""
from __future__ import annotations

import numpy as np

from solvers.constants import F_MAX_HZ, SQUEAL_LEVEL_DB


def _db(x, ref):
    with np.errstate(divide="ignore"):
        return 10 * np.log10(np.maximum(np.asarray(x, float), 1e-300) / ref)


def radiation_figure(a: dict, case: str):
    """Three panels: |F2|, |F3| spectra (RMS) with the tones; the sound power per
    bin/tone; the unit-force sound power (lateral, radial).  ``a``: the arrays of
    radiate.npz.  Returns the figure."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig, axs = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    ff = a["force_f"]
    axs[0].plot(ff, _db(np.abs(a["F2_spectrum"]) ** 2, 1.0), lw=0.7, label="F2")
    axs[0].plot(ff, _db(np.abs(a["F3_spectrum"]) ** 2, 1.0), lw=0.7, label="F3")
    if len(a["tone_f"]):
        axs[0].plot(a["tone_f"], _db(np.abs(a["tone_F2"]) ** 2, 1.0), "v", ms=5, label="tones (F2, fitted)")
    axs[0].set_ylabel("dB re 1 N (RMS)")
    axs[0].set_title(f"{case}: {a['stop_reason']}, L_F2 = {float(a['L_F2']):.1f} dB"
                     + ("" if a["meaningful"] else f" (< {SQUEAL_LEVEL_DB:g} dB: sound power not meaningful, docs/physics.md section 6)"))
    tone = a["is_tone"]
    LW = _db(a["W"], 1e-12)
    top = LW.max() if np.isfinite(LW.max()) else 0.0
    axs[1].plot(a["f"][~tone], LW[~tone], "k", lw=0.6, label="residual, per bin")
    if tone.any():
        axs[1].vlines(a["f"][tone], top - 150, LW[tone], color="C3", lw=1.5, label="tones")
    axs[1].set_ylim(top - 150, top + 10)
    axs[1].set_ylabel("L_W (dB re 1e-12 W)")
    axs[1].set_title(f"sound power: L_W = {float(a['L_W']):.1f} dB, peak {float(a['f_sound']):.1f} Hz "
                     f"{a['sound_mode_label']}")
    fu = a["unit_f"]
    axs[2].plot(fu, _db(a["unit_W_lateral"], 1e-12), lw=0.8, label="unit lateral force F2 = 1 N")
    axs[2].plot(fu, _db(a["unit_W_radial"], 1e-12), lw=0.8, label="unit radial force F3 = 1 N")
    top = max(_db(a["unit_W_lateral"], 1e-12).max(), _db(a["unit_W_radial"], 1e-12).max())
    axs[2].set_ylim(top - 100, top + 5)
    axs[2].set_ylabel("dB re 1e-12 W per N^2")
    axs[2].set_xlabel("frequency (Hz)")
    axs[2].set_title(f"unit-force sound power at y^W = {1e3 * float(a['y_wheel']):+.0f} mm")
    for ax in axs:
        ax.set_xscale("log")
        ax.set_xlim(50, F_MAX_HZ)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
