"""Figures of the parameter studies (SPEC 7), from arrays; each function returns a matplotlib
figure (the pipeline saves it)."""
from __future__ import annotations

import numpy as np

from solvers.constants import SQUEAL_F_MIN_HZ, SQUEAL_LEVEL_DB


def _plt():
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    return plt


def _edges(x):
    x = np.asarray(x, float)
    if x.size == 1:
        w = 0.5 * abs(x[0]) if x[0] else 0.5
        return np.array([x[0] - w, x[0] + w])
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate([[2 * x[0] - mid[0]], mid, [2 * x[-1] - mid[-1]]])


LOW_LABEL = f"< {SQUEAL_F_MIN_HZ:g} Hz: wheelset oscillation, not squeal"


def sound_frequency(fields: dict) -> np.ndarray:
    """The sound's frequency per cell: the loudest sound entry (f_sound) where the sound power was
    computed, else the dominant frequency of F2 (which may be a harmonic of the sound's)."""
    fs = np.asarray(fields["f_sound"], float)
    return np.where(np.isfinite(fs), fs, np.asarray(fields["f_dominant"], float))


def mode_categories(fields: dict, mode_f, mode_labels, level: float = SQUEAL_LEVEL_DB):
    """(category index per cell, names): -1 no squeal (L_F2 < level or no data), 0 a self-excited
    oscillation below SQUEAL_F_MIN_HZ (the wheelset, LOW_LABEL), k >= 1 the wheel mode nearest in
    frequency to the sound's frequency (names[k]: its label and frequency)."""
    L = np.asarray(fields["L_F2"], float)
    f = sound_frequency(fields)
    squeal = np.isfinite(L) & (L >= level) & np.isfinite(f)
    mode_f = np.asarray(mode_f, float)
    cat = np.full(L.shape, -1, int)
    names = [LOW_LABEL]
    index = {}
    for ij in zip(*np.nonzero(squeal)):
        if f[ij] < SQUEAL_F_MIN_HZ:
            cat[ij] = 0
            continue
        k = int(np.argmin(np.abs(mode_f - f[ij])))
        if k not in index:
            index[k] = len(names)
            names.append(f"{mode_labels[k]} {mode_f[k]:.0f} Hz")
        cat[ij] = index[k]
    return cat, names


def map_figure(gamma_y, mu, fields: dict, title: str, level: float = SQUEAL_LEVEL_DB, modes=None):
    """Maps over (gamma_y, mu) of one contact position: L_F2 with the squeal contour; the squealing
    mode as a categorical colour with its label (``modes`` = (frequencies, labels) of the wheel's
    modes; oscillations below SQUEAL_F_MIN_HZ marked as the wheelset's, not squeal); L_W; the sound's
    frequency.  fields[name] (len(mu), len(gamma_y)), NaN where undefined (grey).  The creepage axis
    is signed (gamma_y < 0: the inner wheel of an under-radial leading wheelset)."""
    from matplotlib.colors import BoundaryNorm, ListedColormap, LogNorm  # lazy: brings in matplotlib
    from matplotlib.patches import Patch, Rectangle  # lazy: brings in matplotlib
    from matplotlib.ticker import FuncFormatter  # lazy: brings in matplotlib

    plt = _plt()
    fig, axs = plt.subplots(2, 2, figsize=(12, 8), sharex=True, sharey=True)
    gx, my = _edges(gamma_y), _edges(mu)
    L = np.asarray(fields["L_F2"], float)
    f = sound_frequency(fields)
    squeal = np.isfinite(L) & (L >= level)
    low = squeal & (f < SQUEAL_F_MIN_HZ)
    for ax in axs.flat:
        ax.set_facecolor("0.85")
    # L_F2 and the squeal contour
    ax = axs[0, 0]
    if np.isfinite(L).any():
        im = ax.pcolormesh(gx, my, np.ma.masked_invalid(L), cmap="magma", shading="flat")
        fig.colorbar(im, ax=ax, label="L_F2 (dB re 1 N)")
        if squeal.any() and (~squeal).any() and L.shape[0] > 1 and L.shape[1] > 1:
            ax.contour(gamma_y, mu, np.where(np.isfinite(L), L, -1e3), levels=[level], colors="w", linewidths=1.2)
            ax.legend(handles=[plt.Line2D([], [], color="w", lw=1.2, label=f"L_F2 = {level:g} dB")], fontsize=7,
                      loc="upper right", facecolor="0.5")
    ax.set_title("lateral force level L_F2", fontsize=9)
    # the squealing mode, one colour per mode
    ax = axs[0, 1]
    mf, ml = modes if modes is not None else (np.array([np.nan]), np.array(["?"]))
    cat, names = mode_categories(fields, mf, ml, level)
    colours = ["0.45"] + [plt.cm.tab10(i % 10) for i in range(len(names) - 1)]
    if (cat >= 0).any():
        ax.pcolormesh(gx, my, np.ma.masked_less(cat, 0), cmap=ListedColormap(colours),
                      norm=BoundaryNorm(np.arange(len(names) + 1) - 0.5, len(names)), shading="flat")
        used = sorted(set(cat[cat >= 0].ravel()))
        ax.legend(handles=[Patch(color=colours[k], label=names[k]) for k in used], fontsize=7, loc="upper right",
                  title="squealing mode", title_fontsize=7)
    else:
        ax.text(0.5, 0.5, "no squealing case", ha="center", va="center", transform=ax.transAxes, color="0.3")
    ax.set_title(f"the squealing mode (grey background: L_F2 < {level:g} dB)", fontsize=9)
    # L_W and the sound's frequency, for squeal (not the wheelset's low oscillation)
    for ax, z, label, cmap in ((axs[1, 0], np.asarray(fields["L_W"], float), "L_W (dB re 1e-12 W)", "magma"),
                               (axs[1, 1], f, "the sound's frequency (Hz)", "viridis")):
        z = np.where(squeal & ~low, z, np.nan)
        if np.isfinite(z).any():
            lo, hi = np.nanmin(z), np.nanmax(z)
            kw = ({"norm": LogNorm(lo, hi)} if label.startswith("the sound") and lo > 0 and hi > 1.5 * lo else
                  {"vmin": lo, "vmax": hi if hi > lo else None})
            im = ax.pcolormesh(gx, my, np.ma.masked_invalid(z), cmap=cmap, shading="flat", **kw)
            cb = fig.colorbar(im, ax=ax, label=label)
            if "norm" in kw:                                            # plain numbers on the log scale
                plain = FuncFormatter(lambda v, _: f"{v:g}")
                cb.ax.yaxis.set_major_formatter(plain)
                cb.ax.yaxis.set_minor_formatter(plain)
                cb.ax.tick_params(which="minor", labelsize=7)
        else:
            ax.text(0.5, 0.5, "no squealing case", ha="center", va="center", transform=ax.transAxes, color="0.3")
        ax.set_title(label + f" (squeal: L_F2 >= {level:g} dB, f >= {SQUEAL_F_MIN_HZ:g} Hz)", fontsize=9)
    for ax in axs.flat:                                                 # the wheelset's oscillations, hatched
        for i, j in zip(*np.nonzero(low)):
            ax.add_patch(Rectangle((gx[j], my[i]), gx[j + 1] - gx[j], my[i + 1] - my[i], facecolor="none",
                                   edgecolor="0.3", hatch="xx", lw=0))
    if low.any():
        axs[1, 1].legend(handles=[Patch(facecolor="none", edgecolor="0.3", hatch="xx", label=LOW_LABEL)],
                         fontsize=7, loc="lower right")
    for ax in axs[1]:
        ax.set_xlabel("gamma_y (lateral creepage, signed)")
    for ax in axs[:, 0]:
        ax.set_ylabel("mu")
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def damping_figure(steps: list, runs: list, labels: dict, title: str, level: float = SQUEAL_LEVEL_DB):
    """The damping study: L_F2 of the full model per step (annotated with the squealing mode) and
    every bisection run (L_F2 over the damping of the mode varied, per step), with the critical
    brackets.  ``steps``: DampingStep-like dicts; ``runs``: dicts with step, model, mode,
    zeta_mode, L_F2."""
    plt = _plt()
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.5))
    k = [s["step"] for s in steps]
    L = [s["L_F2"] if np.isfinite(s["L_F2"]) else np.nan for s in steps]
    axs[0].plot(k, L, "o-", color="k")
    axs[0].axhline(level, color="C3", ls="--", lw=1, label=f"squeal level {level:g} dB")
    for s in steps:
        if s.get("mode") is not None and s["mode"] >= 0 and np.isfinite(s["L_F2"]):
            axs[0].annotate(labels.get(s["mode"], str(s["mode"])), (s["step"], s["L_F2"]),
                            textcoords="offset points", xytext=(4, 6), fontsize=8)
    axs[0].set_xlabel("step")
    axs[0].set_ylabel("L_F2 of the full model (dB re 1 N)")
    axs[0].set_xticks(k)
    axs[0].legend(fontsize=8)
    axs[0].set_title("succession of squealing modes")
    for j, s in enumerate(steps):
        pts = [r for r in runs if r["step"] == s["step"] and r["mode"] >= 0]
        if not pts:
            continue
        pts.sort(key=lambda r: r["zeta_mode"])
        z = [r["zeta_mode"] for r in pts]
        y = [r["L_F2"] if np.isfinite(r["L_F2"]) else np.nan for r in pts]
        lab = f"step {s['step']}: {labels.get(s['mode'], s['mode'])} ({s.get('bisection_model', '')})"
        axs[1].semilogx(z, y, "o-", ms=4, color=f"C{j}", label=lab)
        if np.isfinite(s.get("zeta_hi", np.nan)):
            axs[1].axvspan(s["zeta_lo"], s["zeta_hi"], color=f"C{j}", alpha=0.25)
    axs[1].axhline(level, color="C3", ls="--", lw=1)
    axs[1].set_xlabel("damping ratio of the mode varied")
    axs[1].set_ylabel("L_F2 (dB re 1 N)")
    axs[1].set_title("bisection runs; shaded: squeal-critical bracket")
    if any(not ln.get_label().startswith("_") for ln in axs[1].lines):
        axs[1].legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def contact_modes_figure(rows: list, title: str):
    """Point contact vs Kalker per mode: F2 peak-to-peak and L_W against the mode frequency, and
    their relative differences.  ``rows``: dicts with f_mode, label, F2_pp_point, F2_pp_kalker,
    L_W_point, L_W_kalker, d_F2_pp, d_L_W."""
    plt = _plt()
    fig, axs = plt.subplots(2, 2, figsize=(12, 7), sharex=True)
    f = np.array([r["f_mode"] for r in rows], float)
    for model, mk in (("point", "o"), ("kalker", "s")):
        axs[0, 0].semilogy(f, [max(r[f"F2_pp_{model}"], 1e-12) for r in rows], mk, label=model, mfc="none")
        axs[1, 0].plot(f, [r[f"L_W_{model}"] for r in rows], mk, label=model, mfc="none")
    axs[0, 1].plot(f, [100 * r["d_F2_pp"] for r in rows], "ko")
    axs[1, 1].plot(f, [r["d_L_W"] for r in rows], "ko")
    for r in rows:
        axs[0, 0].annotate(r["label"], (r["f_mode"], max(r["F2_pp_point"], 1e-12)), fontsize=7,
                           textcoords="offset points", xytext=(3, 3))
    axs[0, 0].set_ylabel("F2 peak-to-peak (N)")
    axs[1, 0].set_ylabel("L_W (dB re 1e-12 W)")
    axs[0, 1].set_ylabel("(point - Kalker) / Kalker, F2 pp (%)")
    axs[1, 1].set_ylabel("L_W point - L_W Kalker (dB)")
    for ax in axs.flat:
        ax.grid(alpha=0.3)
    for ax in axs[1]:
        ax.set_xlabel("frequency of the mode kept (Hz)")
    axs[0, 0].legend(fontsize=8)
    axs[1, 0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def creepage_figure(rows: list, title: str):
    """Prescribed creepage: amplitude and phase of F2 at the excitation frequency, point vs
    Kalker, over frequency.  ``rows``: dicts with f, model, F2_amplitude, F2_phase, F2_mean."""
    plt = _plt()
    fig, axs = plt.subplots(1, 3, figsize=(13, 4))
    for model, mk in (("point", "o-"), ("kalker", "s--")):
        rr = sorted((r for r in rows if r["model"] == model), key=lambda r: r["f"])
        if not rr:
            continue
        f = [r["f"] for r in rr]
        axs[0].semilogx(f, [r["F2_amplitude"] for r in rr], mk, label=model, mfc="none")
        axs[1].semilogx(f, [np.degrees(np.angle(np.exp(1j * r["F2_phase"]))) for r in rr], mk, label=model,
                        mfc="none")
        axs[2].semilogx(f, [r["F2_mean"] for r in rr], mk, label=model, mfc="none")
    axs[0].set_ylabel("F2 amplitude at f (N)")
    axs[1].set_ylabel("F2 phase at f (deg)")
    axs[2].set_ylabel("F2 mean (N)")
    for ax in axs:
        ax.set_xlabel("creepage frequency f (Hz)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    return fig
