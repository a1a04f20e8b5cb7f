"""Figures of the stability screen: the closed-loop poles of a case (stability.png)
and the screen over a map study's grid (stability_<case>.png)."""
from __future__ import annotations

import numpy as np


def screen_figure(a: dict, case: str, c: dict):
    """Growth rate against frequency of every pole (``a``: stability.npz; ``c``: the case)."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig, ax = plt.subplots(figsize=(8, 4.5))
    f, s, lab = a["f_hz"], a["sigma"], a["label"]
    un = s > 0
    ax.semilogx(f[~un], s[~un], "o", color="0.6", ms=4, label="stable")
    ax.semilogx(f[un], s[un], "o", color="C3", ms=6, label="unstable")
    for fi, si, li in zip(f[un], s[un], lab[un]):
        ax.annotate(li, (fi, si), textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("growth rate sigma (1/s)")
    ax.set_ylim(max(-30.0, float(s.min()) - 1) if len(s) else -30, max(5.0, 1.15 * float(s.max())) if len(s) else 5)
    fr = c["friction"]
    fr_text = f"mu = {fr['mu']}" if fr.get("mu") is not None else f"friction {fr.get('preset') or fr.get('law')}"
    ax.set_title(f"{case}: dy_WR = {1e3 * c['contact']['dy_wr']:.0f} mm, {fr_text}, "
                 f"gamma_y = {c['kinematics']['gamma_y']}")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    show_every_pole(ax, f, s, lab)
    fig.tight_layout()
    return fig


def show_every_pole(ax, f, s, lab) -> None:
    """Every pole on the axes (issue 27: the limits above cut them at -30 1/s): growth rates span 1e-2
    (lightly damped wheel modes) to 1e3 1/s (the damped track and axle roots), so the axis is linear
    within +-1 1/s and logarithmic beyond; the wheelset's roots on the track marked apart."""
    ax.set_yscale("symlog", linthresh=1.0)
    if len(s):
        ax.set_ylim(min(-1.0, 1.5 * float(s.min())), max(1.0, 1.5 * float(s.max())))
    track = lab == "track"
    if track.any():
        ax.semilogx(f[track], s[track], "x", color="C0", ms=6, label="wheelset on the track")
        ax.legend(fontsize=8)
    ax.set_ylabel("growth rate sigma (1/s, symlog)")
    ax.text(0.01, 0.02, f"all {len(s)} poles", transform=ax.transAxes, fontsize=8, color="0.3")


def map_figure(rows: list[dict], gammas, mus, case: str):
    """The largest growth rate over the (gamma_y, mu) grid of one case."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    S = np.full((len(mus), len(gammas)), np.nan)
    labels = {}
    for r in rows:
        i, j = int(np.argmin(np.abs(mus - r["mu"]))), int(np.argmin(np.abs(gammas - r["gamma_y"])))
        S[i, j] = r["sigma_max"]
        labels[(i, j)] = r["label_max"] if r["sigma_max"] > 0 else ""
    fig, ax = plt.subplots(figsize=(9, 4))
    lim = np.nanmax(np.abs(S)) if np.isfinite(S).any() else 1.0
    im = ax.pcolormesh(gammas, mus, S, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
    fig.colorbar(im, ax=ax, label="largest growth rate (1/s)")
    for (i, j), lab in labels.items():
        if lab:
            ax.text(gammas[j], mus[i], lab.replace("track", "LF"), ha="center", va="center", fontsize=5, rotation=90)
    ax.set_xlabel("gamma_y (lateral creepage, signed)")
    ax.set_ylabel("mu")
    ax.set_title(f"Stability screen, {case}: fastest-growing pole (label where unstable)")
    fig.tight_layout()
    return fig
