"""Green's functions stage (SPEC 3.1, 3.3, 3.4): turn the wheel modes and the
rail waves into the causal kernels the time loop uses, for one case.

* Wheel: receptances at the case's tread point by modal superposition with
  the damping rule [4.11]; Kropp's Green's function on the automatic grid
  (checked to have decayed); the exact fast form = recursive modal filters
  (f_r, modal mass, zeta, the shapes at the contact point).
* Rail: the moving Green's function g_mov[k] = g^R(v k dt, k dt) at the case's
  rail-head point, from the waveguide wave table on Kropp's grid.  The rail
  model is valid to 6.5 kHz: the receptance is taken as zero above (it is
  below -190 dB re 1 m/N there).

Artifact: build/cases/<case>/greens.npz and greens_wheel.png, greens_rail.png.
The cache key is the resolved configuration (wheel, rail, case settings)
plus the wheel-modes and rail artifacts' own hashes.
"""
from __future__ import annotations

import logging
import time

import numpy as np

from . import artifacts, paths

log = logging.getLogger("pipeline.greens")

RAIL_F_MAX = 6500.0  # upper limit of the rail model (Hz)
RAIL_NT = 8192  # Kropp grid of the rail: df = 1/(N_t dt) = 3.4 Hz at 36 us
RAIL_LAGS = 4096  # moving-kernel length (0.147 s, 2 m at 50 km/h); its decay is checked


def greens_inputs(case: str):
    from .contact_stage import NOMINAL_POSITIONS
    from .config import load
    from .rail_stage import load_rail_params
    from .schemas import CASE
    from .wheel_stage import load_wheel

    c = load(paths.case_file(case), CASE)
    pw, _ = load_wheel(c["wheel"])
    pr, _ = load_rail_params(c["rail"])
    modes, mprov = artifacts.load_npz(paths.wheel_dir(c["wheel"]) / "modes.npz", "wheel-modes", pw,
                                      make_target=f"modes WHEEL={c['wheel']}")
    _, rprov = artifacts.load_npz(paths.rail_dir(c["rail"]) / "rail.npz", "rail", pr, make_target=f"rail RAIL={c['rail']}")
    yw, yr = NOMINAL_POSITIONS[round(c["contact"]["dy_wr"], 3)]
    cfg = {"case": {k: c[k] for k in ("contact", "kinematics", "time")}, "wheel_modes": mprov["config_hash"],
           "rail": rprov["config_hash"], "rail_nt": RAIL_NT, "rail_lags": RAIL_LAGS, "rail_f_max": RAIL_F_MAX}
    return c, pw, pr, modes, (yw, yr), cfg


def wheel_greens(pw: dict, modes: dict, y_w: float, dt: float) -> dict:
    from geometry.wheel import tread_radius
    from solvers.green import choose_grid, decayed, green_from_receptance
    from solvers.receptance import contact_point, contact_shape, modal_damping, wheel_receptance

    surface = np.unique(np.concatenate([modes["boundary_tread"], modes["boundary_flange"]]))
    z_rc = pw["axle"]["rolling_circle_z"]
    where = contact_point(modes["points"], surface, y_w, z_rc, r_of_y=lambda y: tread_radius(pw, y),
                          cells=modes["cells"])
    phi = contact_shape(modes["shapes"], where)
    zeta = modal_damping(modes["n"], modes["m"], modes["cls"], modes["kind"], modes["zeta_suspension"])
    f_r, mass = modes["f_hz"], modes["modal_mass"]
    n_t = choose_grid(f_r, zeta, dt)
    g = green_from_receptance(lambda f: wheel_receptance(f, f_r, mass, modes["n"], phi, zeta), dt, n_t)
    check = decayed(g)
    if not check.ok:
        raise RuntimeError(f"wheel Green's function has not decayed by N_t/2 dt ({check.level_db:.0f} dB)")
    return {"wheel_f": f_r, "wheel_mass": mass, "wheel_zeta": zeta, "wheel_phi": phi, "wheel_n": modes["n"],
            "wheel_nt": np.int64(n_t), "wheel_decay_db": np.float64(check.level_db),
            "wheel_kernel": g[: 1 << 15], "wheel_point_rz": np.array([where.r, where.Z])}


def rail_greens(pr: dict, y_r: float, v: float, dt: float) -> dict:
    from solvers.green import decayed, frequency_grid, green_from_receptance, moving_green
    from solvers.rail_response import build_rail_model, evaluate_table, wave_table

    msh = paths.rail_dir(pr["name"]) / "section.msh"
    model = build_rail_model(pr, str(msh), contact_y=[y_r], with_centre=False)
    f = frequency_grid(dt, RAIL_NT)
    inside = f <= RAIL_F_MAX
    fin = np.maximum(f[inside], 1.0)  # the static limit: the 1 Hz response
    T = wave_table(model, fin, points=[y_r])

    def transfer(x, ff):
        G = np.zeros((len(x), len(ff), 2, 2), complex)
        G[:, inside] = evaluate_table(T, x)[0]
        return G

    g = moving_green(transfer, v, dt, RAIL_LAGS, RAIL_NT)
    g0 = green_from_receptance(transfer(np.zeros(1), f)[0], dt, RAIL_NT)  # fixed point: decay check
    check = decayed(g0)
    if not check.ok:
        raise RuntimeError(f"rail Green's function has not decayed by N_t/2 dt ({check.level_db:.0f} dB)")
    tail = np.abs(g[-RAIL_LAGS // 8:]).max() / np.abs(g).max()
    return {"rail_kernel": g, "rail_fixed_kernel": g0[:RAIL_LAGS], "rail_decay_db": np.float64(check.level_db),
            "rail_tail_ratio": np.float64(tail), "rail_nt": np.int64(RAIL_NT)}


def run_greens(case: str) -> dict:
    c, pw, pr, modes, (yw, yr), cfg = greens_inputs(case)
    dt, v = c["time"]["dt"], c["kinematics"]["speed"]
    t0 = time.perf_counter()
    arrays = {"dt": np.float64(dt), "v": np.float64(v), "y_wheel": np.float64(yw), "y_rail": np.float64(yr)}
    arrays.update(wheel_greens(pw, modes, yw, dt))
    t1 = time.perf_counter()
    arrays.update(rail_greens(pr, yr, v, dt))
    t2 = time.perf_counter()
    out = paths.case_dir(case)
    plot_kernels(arrays, out / "greens.png", case)
    artifacts.save_npz(out / "greens.npz", "greens", cfg, **arrays)
    log.info("greens %s: wheel %d modes, Kropp N_t = %d (decayed %.0f dB) in %.1f s; rail moving kernel %d lags "
             "(tail %.1e of peak) in %.1f s -> %s", case, len(arrays["wheel_f"]), arrays["wheel_nt"],
             arrays["wheel_decay_db"], t1 - t0, RAIL_LAGS, arrays["rail_tail_ratio"], t2 - t1, out / "greens.npz")
    return arrays


def plot_kernels(a: dict, path, case: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(2, 1, figsize=(8, 6))
    tw = np.arange(len(a["wheel_kernel"])) * a["dt"]
    tr = np.arange(len(a["rail_kernel"])) * a["dt"]
    for (i, j, lab) in ((0, 0, "g22"), (1, 1, "g33"), (0, 1, "g23")):
        axs[0].plot(1e3 * tw, a["wheel_kernel"][:, i, j], lw=0.6, label=lab)
        axs[1].plot(1e3 * tr, a["rail_kernel"][:, i, j], lw=0.8, label=lab)
    axs[0].set_title(f"{case}: wheel Green's function (Kropp), first {1e3 * tw[-1]:.0f} ms")
    axs[1].set_title(f"rail moving Green's function, v = {3.6 * a['v']:.0f} km/h")
    for ax in axs:
        ax.set_xlabel("time (ms)")
        ax.set_ylabel("m/N")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    with artifacts.atomic_write(path) as tmp:
        fig.savefig(tmp, dpi=90)
    plt.close(fig)
