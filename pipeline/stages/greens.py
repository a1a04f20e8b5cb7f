"""Green's functions stage (SPEC 3.1, 3.3, 3.4): turn the wheel modes and the
rail waves into the causal kernels the time loop uses, for one case.

* Wheel: receptances at the case's tread point by modal superposition with
  the damping rule [4.11]; the time loop convolves the wheel through the
  recursive modal filters (f_r, modal mass, zeta, the shapes at the contact
  point), whose kernel is the sampled modal impulse response.  The stored
  kernel (its first 32768 lags, for plots and checks) is that modal kernel
  with the band-limited correction of its first 16 samples
  (solvers/wheel/modal_band.py), fitted against the whole modal kernel's
  closed-form spectrum at the fit frequencies of Kropp's grid (decayed by
  120 dB at N_t/2 dt): its spectrum reproduces the receptance pointwise to
  0.1 % up to 6.5 kHz (C20, every grid point from 5 Hz: 0.1005 % at worst,
  tests/greens/test_modal_band.py).  It differs from Kropp's corrected kernel
  (the stage's kernel before, built by FFT on N_t ~ 2.8e6 samples in ~2.5 s)
  by < 5e-4 of the peak in the first 16 samples and < 6e-5 after.  The
  correction changes no simulation (the filters do not use it).
* Rail: the moving Green's function g_mov[k] = g^R(v k dt, k dt) at the case's
  rail-head point (a node of the rail file's contact.y within 1 mm, else the point itself from
  the running surface's wave table, pipeline/caches/rail_surface_table.py), from the waveguide wave table
  on Kropp's grid, shared by every case with
  the same rail, |y^R|, speed and time step through the cache build/rails/<rail>/moving/
  (pipeline/caches/rail_kernel.py; built in seconds by solvers/rail/moving_kernel.py).  The rail
  model is valid to 6.5 kHz; above, the receptance is rolled off to zero by
  9 kHz with a smooth (C-infinity) taper.  A hard cut at 6.5 kHz (the
  former choice) is a jump of Re G of a few 1e-10 m/N whose Hilbert transform puts
  a logarithmic Im error at 6.5 kHz: Im of the kernel's spectrum drops to ~0
  there and is slightly non-passive (negative damping) between 6.49 and
  6.51 kHz.  No band-limited correction for the rail: its receptance has
  hysteretic (constant loss factor) damping, Im G(0+) != 0, i.e. it is not the
  transform of a causal response, and Kropp's kernel keeps Re G and the Im
  that causality implies (docs/validation/50_greens.md).

Artifact: build/cases/<case>/greens.npz and greens_wheel.png, greens_rail.png.
The cache key is the resolved configuration (wheel, rail, case settings)
plus the wheel-modes artifact's hash and the rail parameters' hash (rail.npz's own:
the stage needs the rail's section mesh, not rail.npz, so that it runs beside the
rail stage).
"""
from __future__ import annotations

import logging
import time

import numpy as np

from solvers.greens.grid import (KROPP_FIT_TOL, KROPP_TAPS, RAIL_F_MAX, RAIL_F_TAPER, RAIL_LAGS,  # noqa: F401
                                 RAIL_NT, WHEEL_BAND_LIMIT, WHEEL_DECAY_DB, WHEEL_LAGS, rail_taper)

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.config.contact_plane import case_projection
from pipeline.config.rail_contact import rail_point
from pipeline.config.case import resolve_case
from pipeline.config.loader import config_hash
from geometry.wheel import tread_radius

log = logging.getLogger("pipeline.greens")

def greens_inputs(case: str):
    rc = resolve_case(case)  # the contact point of the profiles, as the contact stage's
    c, pw, pr, geo = rc.case, rc.wheel, rc.rail, rc.geometry
    where = f"case '{case}', dy_WR = {1e3 * c['contact']['dy_wr']:+.1f} mm (y^W = {1e3 * geo.contact.y_wheel:+.2f} mm)"
    yw, yr = geo.contact.y_wheel, rail_point(c["rail"], pr, geo.contact.y_rail, where)  # yr: the rail model's node
    modes, mprov = artifacts.load_npz(paths.wheel_dir(c["wheel"]) / "modes.npz", "wheel-modes", pw,
                                      make_target=f"modes WHEEL={c['wheel']}")
    # "rail": the rail parameters' hash, the one rail.npz carries (the rail stage saves with them)
    case_cfg = {k: c[k] for k in ("contact", "kinematics", "time")}
    case_cfg["kinematics"] = {k: v for k, v in case_cfg["kinematics"].items() if k != "spin"}   # issue 26: not an input here
    cfg = {"case": case_cfg, "wheel_modes": mprov["config_hash"],
           "running_surfaces": geo.config,
           "rail": config_hash(pr), "rail_nt": RAIL_NT, "rail_lags": RAIL_LAGS, "rail_f_max": RAIL_F_MAX,
           "rail_f_taper": RAIL_F_TAPER, "wheel_band_limit": WHEEL_BAND_LIMIT, "wheel_decay_db": WHEEL_DECAY_DB,
           "wheel_kernel": "modal+band-fit",
           "kropp_taps": KROPP_TAPS, "kropp_fit_tol": KROPP_FIT_TOL}
    return c, pw, pr, modes, (yw, yr, geo.contact.y_rail), cfg


def wheel_greens(pw: dict, modes: dict, y_w: float, dt: float) -> dict:
    from solvers.greens.kernels import choose_grid  # lazy: brings in numba, scipy
    from solvers.wheel.modal_band import corrected_modal_kernel, decay_db  # lazy: brings in numba, scipy
    from solvers.wheel.receptance import contact_point, contact_shape, modal_damping  # lazy: brings in scipy

    surface = np.unique(np.concatenate([modes["boundary_tread"], modes["boundary_flange"]]))
    z_rc = pw["axle"]["rolling_circle_z"]
    where = contact_point(modes["points"], surface, y_w, z_rc, r_of_y=lambda y: tread_radius(pw, y),
                          cells=modes["cells"])
    phi = contact_shape(modes["shapes"], where)
    zeta = modal_damping(modes["n"], modes["m"], modes["cls"], modes["kind"], modes["zeta_suspension"])
    f_r, mass = modes["f_hz"], modes["modal_mass"]
    n_t = choose_grid(f_r, zeta, dt, decay_db=WHEEL_DECAY_DB)   # Kropp's grid: the fit's frequencies
    g, fit = corrected_modal_kernel(WHEEL_LAGS, dt, f_r, mass, zeta, phi, n_t, WHEEL_BAND_LIMIT, KROPP_TAPS,
                                    KROPP_FIT_TOL)
    level_db = decay_db(g, n_t, dt, f_r, mass, zeta, phi)
    if level_db > -60.0:
        raise RuntimeError(f"wheel Green's function has not decayed by N_t/2 dt ({level_db:.0f} dB)")
    if fit.fit_error.max() > 2 * KROPP_FIT_TOL:
        log.warning("wheel kernel: the band-limited correction reaches only %.1e relative to |G| (asked %.0e)",
                    fit.fit_error.max(), KROPP_FIT_TOL)
    return {"wheel_f": f_r, "wheel_mass": mass, "wheel_zeta": zeta, "wheel_phi": phi, "wheel_n": modes["n"],
            "wheel_nt": np.int64(n_t), "wheel_decay_db": np.float64(level_db),
            "wheel_kernel": g, "wheel_point_rz": np.array([where.r, where.Z]),
            "wheel_band_limit": np.float64(fit.band_limit), "wheel_fit_error": fit.fit_error,
            "wheel_correction": fit.correction}


def rail_greens(pr: dict, rail_hash: str, y_r: float, v: float, dt: float) -> tuple[dict, bool]:
    """The moving rail kernel and its companions at y_r, from the shared cache
    build/rails/<rail>/moving/ or built there (pipeline/caches/rail_kernel.py at the rail file's listed
    points, pipeline/caches/rail_surface_table.py at any other point of the running surface); also whether it
    came from the cache.  rail_hash: the rail parameters' configuration hash (rail.npz's)."""
    from pipeline.caches.rail_kernel import rail_kernel  # here: Make's DEPS of the module's other entry points stay without it
    from pipeline.caches.rail_surface_table import surface_kernel  # here: Make's DEPS of the module's other entry points stay without it

    grid = {"n_t": RAIL_NT, "n_lags": RAIL_LAGS, "f_max": RAIL_F_MAX, "f_taper": RAIL_F_TAPER}
    if np.any(np.abs(np.abs(np.asarray(pr["contact"]["y"], float)) - abs(y_r)) < 1e-12):
        return rail_kernel(pr, rail_hash, y_r, v, dt, grid, rail_taper)  # a listed point: its own model
    return surface_kernel(pr, rail_hash, y_r, v, dt, grid, rail_taper)   # any other: the surface table


def run_greens(case: str) -> dict:
    c, pw, pr, modes, (yw, yr, y_rail_contact), cfg = greens_inputs(case)
    dt, v = c["time"]["dt"], c["kinematics"]["speed"]
    t0 = time.perf_counter()
    arrays = {"dt": np.float64(dt), "v": np.float64(v), "y_wheel": np.float64(yw), "y_rail": np.float64(yr),
              "y_rail_contact": np.float64(y_rail_contact)}
    arrays.update(wheel_greens(pw, modes, yw, dt))
    t1 = time.perf_counter()
    rail, cached = rail_greens(pr, cfg["rail"], yr, v, dt)
    arrays.update(rail)
    arrays = case_projection(resolve_case(case), arrays)  # [contact] angle: the contact plane's frame (pipeline/config/contact_plane.py)
    if c["contact"].get("points", 1) == 2:  # [contact] points = 2: both points (pipeline/stages/greens_two_point.py)
        from pipeline.stages.greens_two_point import second_greens  # here: Make's DEPS of the module's other entry points stay without it

        arrays.update(second_greens(case, pw, pr, modes, yr, dt, v))
    t2 = time.perf_counter()
    out = paths.case_dir(case)
    plot_kernels(arrays, out / "greens.png", case)
    artifacts.save_npz(out / "greens.npz", "greens", cfg, **arrays)
    log.info("greens %s: wheel %d modes, modal kernel (Kropp's grid N_t = %d, decayed %.0f dB; spectrum = G to %.1e up to "
             "%.1f kHz) in %.1f s; "
             "rail moving kernel %d lags (tail %.1e of peak, %s) in %.1f s -> %s", case, len(arrays["wheel_f"]),
             arrays["wheel_nt"], arrays["wheel_decay_db"], arrays["wheel_fit_error"].max(),
             arrays["wheel_band_limit"] / 1e3, t1 - t0, RAIL_LAGS, arrays["rail_tail_ratio"],
             "shared cache" if cached else "built and cached", t2 - t1, out / "greens.npz")
    return arrays


def plot_kernels(a: dict, path, case: str) -> None:
    """``postprocess.plots.greens.kernels_figure``, saved atomically to ``path``."""
    from postprocess.plots.greens import kernels_figure  # here: Make's DEPS of the module's other entry points stay without it

    save_figure(kernels_figure(a, case), path, dpi=90)
