"""Figures of the limit-cycle diagnosis (issue 28, docs/validation/68_limit_cycle.md): the records
over the limit cycle against the friction curve, and the scan of creepage and friction."""
from __future__ import annotations

import numpy as np

from postprocess.limit_cycle_measures import curve

def _plt():
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    return plt


def _pos(dy: float) -> str:
    return f"{1e3 * dy:.0f} mm"


def cycles_figure(records: dict, n_periods: int = 5):
    """Per case (rows): lateral slip with the steady slip and the knee of mu_RF; F2/(mu F3) and
    F3/F3_mean with the contact state; mu_RF(s) with the band the limit cycle visits."""
    plt = _plt()
    fig, axes = plt.subplots(len(records), 3, figsize=(13, 3.1 * len(records)), squeeze=False)
    for ax, (case, r) in zip(axes, records.items()):
        row = r["row"]
        t, F, s2, st = r["t"], r["F"], r["slip"][:, 1], r["state"]
        n = min(len(t), int(round(n_periods / max(row["f_dominant"], 1.0) / (t[1] - t[0]))))
        tt = 1e3 * (t[-n:] - t[-n])
        a = ax[0]
        a.plot(tt, s2[-n:], "C0", lw=1.2, label="s2 (lateral slip)")
        a.axhline(-row["s0"], color="k", ls="--", lw=0.8, label="-|gamma_y| V")
        a.axhline(-row["s_knee"], color="C3", ls=":", lw=1.2, label="-s_knee (mu_RF = 0.99 mu)")
        a.axhline(0, color="0.5", lw=0.6)
        part = st[-n:] == 1
        a.fill_between(tt, s2[-n:].min(), 0, where=part, color="C3", alpha=0.12, step="mid", label="partial slip")
        a.set_ylabel("m/s")
        a.set_title(f"{case} ({_pos(row['dy_wr'])}), mu {row['mu']}, gamma_y {row['gamma_y']}", fontsize=9)
        a.legend(fontsize=7, loc="lower right")
        b = ax[1]
        on = F[-n:, 2] > 0
        b.plot(tt, np.where(on, F[-n:, 1] / (row["plateau"] * np.maximum(F[-n:, 2], 1e-9)), np.nan), "C2",
               label="F2 / (mu F3)")
        b.plot(tt, F[-n:, 2] / row["F3_mean"], "C1", label="F3 / mean F3")
        b.fill_between(tt, 0.7, 1.3, where=part, color="C3", alpha=0.12, step="mid")
        b.set_ylim(0.7, 1.3)
        b.legend(fontsize=7, loc="lower right")
        c = ax[2]
        sn, mn, sl = r["curve"]
        s = np.linspace(0, max(1.2 * abs(s2).max(), 0.3), 400)
        c.plot(s, curve(s, sn, mn, sl), "k", lw=1.2, label="mu_RF(s)")
        c.plot(sn[sn <= s[-1]], mn[sn <= s[-1]], "k.", ms=4, label="TANG nodes")
        c.axvspan(abs(s2).min(), abs(s2).max(), color="C0", alpha=0.2, label="visited |s|")
        c.axvline(row["s0"], color="k", ls="--", lw=0.8)
        c.axvline(row["s_knee"], color="C3", ls=":", lw=1.2)
        c.set_xlim(0, s[-1])
        c.legend(fontsize=7, loc="lower right")
    axes[-1, 0].set_xlabel("time over the last periods (ms)")
    axes[-1, 1].set_xlabel("time over the last periods (ms)")
    axes[-1, 2].set_xlabel("|slip velocity| s (m/s)")
    fig.tight_layout()
    return fig


def scan_figure(rows: list[dict]):
    """Top: the limit cycle's dip of |s2| below |gamma_y| V against the margin |gamma_y| V - s_knee
    (saturation bound: on the diagonal). Middle: L_W, bottom: the screen's largest growth rate,
    over |gamma_y| per friction coefficient, one column per position."""
    plt = _plt()
    dys = sorted({r["dy_wr"] for r in rows}, reverse=True)
    mus = sorted({r["mu"] for r in rows})
    fig, axes = plt.subplots(3, len(dys), figsize=(4.2 * len(dys), 9.5), squeeze=False)
    for j, dy in enumerate(dys):
        rr = [r for r in rows if r["dy_wr"] == dy]
        a = axes[0, j]
        for k, mu in enumerate(mus):
            q = [r for r in rr if r["mu"] == mu and np.isfinite(r["L_W"])]
            a.plot([r["margin"] for r in q], [r["s2_swing_down"] for r in q], "o", color=f"C{k}", label=f"mu {mu}")
            q = sorted([r for r in rr if r["mu"] == mu], key=lambda r: -r["gamma_y"])
            axes[1, j].plot([-r["gamma_y"] for r in q], [r["L_W"] for r in q], "o-", color=f"C{k}", label=f"mu {mu}")
            axes[2, j].plot([-r["gamma_y"] for r in q], [r["sigma_max"] for r in q], "o-", color=f"C{k}")
        lim = max([r["margin"] for r in rr] + [0.1])
        a.plot([0, lim], [0, lim], "k--", lw=0.8, label="dip = margin")
        a.set_xlabel("margin |gamma_y| V - s_knee (m/s)")
        a.set_ylabel("dip of |s2| below |gamma_y| V (m/s)")
        a.set_title(_pos(dy))
        a.legend(fontsize=7)
        axes[1, j].set_ylabel("L_W (dB re 1e-12 W)")
        axes[1, j].legend(fontsize=7)
        axes[2, j].axhline(0, color="k", lw=0.6)
        axes[2, j].set_ylabel("screen: largest growth rate (1/s)")
        axes[2, j].set_xlabel("|gamma_y|")
        for a in axes[:, j]:
            a.grid(alpha=0.3)
    fig.tight_layout()
    return fig
