"""Rail stage: BV50 (or another rail) cross-section with the pad, waveguide FE,
dispersion, receptances at the rail-head contact points (SPEC 3.2).

Artifacts in build/rails/<name>/ (keys in the README):
  section.msh     half cross-section (rail steel = surface 1, pad = 2)
  rail.npz        receptances G (points, distances, frequencies, 2, 2), the
                  wave table (exact G at any distance), decay rates,
                  dispersion curves with wave types, section properties
  receptance.png  point receptances (magnitude and phase), dispersion.png
"""
from __future__ import annotations

import logging
import time

import numpy as np

from . import artifacts, paths
from .config import load_geometry
from .schemas import RAIL

log = logging.getLogger("pipeline.rail")

N_FREQ = 1000  # 25 Hz .. 6.5 kHz, log-spaced
N_DIST = 200  # 0 .. 2 m along the rail
X_MAX = 2.0


def load_rail_params(name: str) -> tuple[dict, str]:
    """Validated rail parameters (geometry checked too) and the file path."""
    from geometry.rail import check_rail

    path = paths.rail_file(name)
    return load_geometry(path, RAIL, check_rail, "rail", paths.available(paths.RAILS)), str(path)


def run_rail(name: str) -> dict:
    from geometry.rail_mesh import mesh_rail

    from .rail_model import build_rail_model, stage_arrays

    p, _ = load_rail_params(name)
    out = paths.rail_dir(name)
    t0 = time.perf_counter()
    with artifacts.atomic_write(out / "section.msh") as tmp:
        mesh_rail(p, str(tmp))
    model = build_rail_model(p, str(out / "section.msh"))
    t1 = time.perf_counter()
    freqs = np.geomspace(25.0, 6500.0, N_FREQ)
    arrays = stage_arrays(model, freqs, np.linspace(0.0, X_MAX, N_DIST))
    t2 = time.perf_counter()
    plot_receptances(arrays, out / "receptance.png", name)
    plot_dispersion(arrays, out / "dispersion.png", name)
    artifacts.save_npz(out / "rail.npz", "rail", p, **arrays)
    log.info("rail %s: model %.1f s, dispersion + receptances (%d frequencies x %d distances x %d points) "
             "%.1f s -> %s", name, t1 - t0, N_FREQ, N_DIST, len(arrays["point_y_m"]), t2 - t1, out / "rail.npz")
    return arrays


def _db(G):
    return 20 * np.log10(np.maximum(np.abs(G), 1e-30))


def plot_receptances(a: dict, path, name: str) -> None:
    """The usual rail receptance figure: |G| in dB re 1 m/N and phase."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    with artifacts.atomic_write(path) as tmp:
        fig.savefig(tmp, dpi=90)
    plt.close(fig)


def plot_dispersion(a: dict, path, name: str) -> None:
    """Dispersion curves f(k) of the free and supported rail, both families."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    with artifacts.atomic_write(path) as tmp:
        fig.savefig(tmp, dpi=90)
    plt.close(fig)
