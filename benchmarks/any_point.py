"""A new contact position (issue 25): `run() -> str` gives the markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks any_point --update

Side by side in one run, BV50, v = 50 km/h, dt = 36 us, N_t = 8192, 4096 lags, at a head point
off the rail file's contact.y list (y^R = 8.1 mm, the default case at dy_WR = -22 mm):

* the rail part, before: "add it to contact.y and rebuild the rail" (the section meshed with a
  node there, the waveguide model loaded there, its wave table on Kropp's grid, the moving
  kernel), against now: the point from the running surface's stored wave table
  (pipeline/rail_surface.py: three nodes' wave shapes, the quadratic form, the kernel);
  the table itself once per rail and time step;
* the contact and greens stages of that case in fresh processes (wheel modes, rail section and
  surface table built; the point's kernel not cached), the contact stage's friction curves apart.
"""
from __future__ import annotations

import copy
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build"
DY = -0.022


def _grid():
    from pipeline.greens_stage import RAIL_F_MAX, RAIL_F_TAPER, RAIL_LAGS, RAIL_NT

    return {"n_t": RAIL_NT, "n_lags": RAIL_LAGS, "f_max": RAIL_F_MAX, "f_taper": RAIL_F_TAPER}


def _case_dir() -> Path:
    d = Path(tempfile.mkdtemp(prefix="bench_case_"))
    text = (ROOT / "pipeline" / "cases" / "default.toml").read_text()
    (d / "newpoint.toml").write_text(text.replace('name = "default"', 'name = "newpoint"')
                                     .replace("dy_wr = -0.015", f"dy_wr = {DY}"))
    return d


def _rail_rows(y: float) -> list:
    from geometry.rail_mesh import mesh_rail
    from pipeline.config import config_hash
    from pipeline.greens_stage import rail_taper
    from pipeline.rail_kernel import wave_table_threads
    from pipeline.rail_model import build_rail_model
    from pipeline.rail_stage import load_rail_params
    from pipeline.rail_surface import kernel_from_waves, point_waves, table_config, table_dir
    from solvers.green import frequency_grid
    from solvers.moving_kernel import moving_green_waves

    pr, _ = load_rail_params("bv50")
    grid = _grid()
    dt, v = 36e-6, 50 / 3.6
    folder = table_dir("bv50", table_config(pr, config_hash(pr), dt, grid))
    had_table = (folder / "waves.npz").exists()
    t0 = time.perf_counter()
    point_waves(pr, config_hash(pr), 0.0, dt, grid)       # builds the table when missing
    t_table = time.perf_counter() - t0
    # before: a node at y (a new mesh), the model loaded there, its wave table, the kernel
    t0 = time.perf_counter()
    p2 = copy.deepcopy(pr)
    p2["contact"]["y"] = sorted([*pr["contact"]["y"], y])
    with tempfile.TemporaryDirectory() as tmp:
        mesh_rail(p2, str(Path(tmp) / "section.msh"))
        t_mesh = time.perf_counter() - t0
        model = build_rail_model(p2, str(Path(tmp) / "section.msh"), contact_y=[y], with_centre=False)
    t_model = time.perf_counter() - t0 - t_mesh
    f = frequency_grid(dt, grid["n_t"])
    inside = f < grid["f_taper"]
    t1 = time.perf_counter()
    T = wave_table_threads(model, np.maximum(f[inside], 1.0), y)
    t_tab = time.perf_counter() - t1
    t1 = time.perf_counter()
    g_old = moving_green_waves(T["k"], T["a"][:, :, 0] * rail_taper(f[inside])[:, None, None, None], v, dt,
                               grid["n_lags"], grid["n_t"])
    t_ker = time.perf_counter() - t1
    t_old = time.perf_counter() - t0
    # now: the stored table
    t0 = time.perf_counter()
    k, a = point_waves(pr, config_hash(pr), y, dt, grid)
    t_w = time.perf_counter() - t0
    new = kernel_from_waves(k, a, v, dt, grid, rail_taper)
    t_new = time.perf_counter() - t0
    e = np.abs(new["rail_kernel"] - g_old).max() / np.abs(g_old).max()
    return [f"| before: mesh with a node at y^R ({t_mesh:.1f} s), model loaded there ({t_model:.1f} s), wave table "
            f"{T['k'].shape[0]} x {T['k'].shape[1]} waves, 2 threads ({t_tab:.1f} s), kernel ({t_ker:.1f} s) | "
            f"{t_old:.1f} s | 1x |",
            f"| now: three surface nodes' wave shapes ({t_w:.1f} s), the quadratic form and the kernel, "
            f"{k.shape[1]} waves ({t_new - t_w:.1f} s) | {t_new:.1f} s | **{t_old / t_new:.1f}x** |",
            f"| kernel now - before (another mesh and basis), max / max \\|g\\| | {e:.1e} | |",
            f"| the surface table, once per rail and time step ({'already built: load of one node' if had_table else 'built in this run'}) "
            f"| {t_table:.1f} s | |"]


def _stage_rows() -> list:
    need = [BUILD / "wheels" / "c20" / "modes.npz", BUILD / "rails" / "bv50" / "section.msh"]
    if not all(p.exists() for p in need):
        return ["| contact and greens stages | (needs the C20 modes and the BV50 section: `make`) |"]
    cases = _case_dir()
    with tempfile.TemporaryDirectory() as d:
        b = Path(d)
        for p in need:
            q = b / p.relative_to(BUILD)
            q.parent.mkdir(parents=True, exist_ok=True)
            os.symlink(p, q)
        os.symlink(BUILD / "rails" / "bv50" / "surface", b / "rails" / "bv50" / "surface")
        env = dict(os.environ, SQUEAL_BUILD_DIR=str(b), SQUEAL_CASE_DIR=str(cases), OMP_NUM_THREADS="1")

        def stage(name):
            t0 = time.perf_counter()
            r = subprocess.run([sys.executable, "-m", "pipeline", name, "--case", "newpoint", "-v"], cwd=ROOT, env=env,
                               capture_output=True, text=True, check=True)
            return time.perf_counter() - t0, r.stderr

        t_c, _ = stage("contact")
        t_g, log_g = stage("greens")
        t_imp = min(_import_time(env) for _ in range(2))
    t_rf = _rf_time()
    line = [x for x in log_g.splitlines() if "greens newpoint: wheel" in x]
    t_wheel = float(line[0].split(") in ")[1].split(" s;")[0]) if line else float("nan")
    t_rail = float(line[0].split(") in ")[-1].split(" s ")[0]) if line else float("nan")
    n_rf = 11
    rows = [f"| contact stage (fresh process; NORM table, compliance, {n_rf} friction curves) | {t_c:.1f} s |",
            f"| of which the {n_rf} friction curves (one curve: {t_rf:.2f} s, timed apart) | {n_rf * t_rf:.1f} s |",
            f"| greens stage (fresh process; wheel kernel and modal filters, rail kernel from the surface table, "
            f"plots) | {t_g:.1f} s |",
            f"| of which the wheel kernel and modal filters (Kropp on N_t ~ 2.8e6) | {t_wheel:.1f} s |",
            f"| of which the rail kernel from the surface table | {t_rail:.1f} s |",
            f"| of which the process start and imports (python -c 'import pipeline.greens_stage ...') | {t_imp:.1f} s |",
            f"| **contact + greens, as they run today** | **{t_c + t_g:.1f} s** |",
            f"| contact + greens with one friction curve (the case's mu, issue 26) | {t_c + t_g - (n_rf - 1) * t_rf:.1f} s |"]
    return rows


def _import_time(env) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import pipeline.greens_stage, pipeline.contact_stage, pipeline.rail_surface, "
                    "solvers.moving_kernel, solvers.green"], cwd=ROOT, env=env, check=True)
    return time.perf_counter() - t0


def _rf_time() -> float:
    """One regularized friction curve of the default case's static patch (contact.npz)."""
    from solvers.contact.friction import rf_curve

    with np.load(BUILD / "cases" / "default" / "contact.npz") as d:
        p3, dx, dy = d["p3_static"], float(d["dx"]), float(d["dy"])
    rf_curve(p3, dx, dy, 50 / 3.6, 0.35, 210e9, 0.3)
    t0 = time.perf_counter()
    rf_curve(p3, dx, dy, 50 / 3.6, 0.35, 210e9, 0.3)
    return time.perf_counter() - t0


def run() -> str:
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    from pipeline.case import resolve_case

    cases = _case_dir()
    os.environ["SQUEAL_CASE_DIR"] = str(cases)
    y = abs(resolve_case("newpoint").contact.y_rail)
    del os.environ["SQUEAL_CASE_DIR"]
    rows = _rail_rows(y) if (BUILD / "rails" / "bv50" / "section.msh").exists() else ["| (needs `make rail`) | | |"]
    stages = _stage_rows()
    load = " / ".join(f"{x:.1f}" for x in os.getloadavg())
    return f"""## A new contact position (issue 25)

`benchmarks/any_point.py`: the default case at dy_WR = {1e3 * DY:.0f} mm (y^R = {1e3 * y:.1f} mm, off the BV50 file's
contact.y list), v = 50 km/h, dt = 36 us, N_t = 8192, 4096 lags; one run each, OMP_NUM_THREADS=1; load average
{load} at the end (the machine is shared: absolute times are inflated, the ratios are measured side by side).

| rail receptances and moving kernel at a new head point | time | speed-up |
|---|---:|---:|
{chr(10).join(rows)}

| a case at a new contact position (wheel modes, rail section and surface table built) | time |
|---|---:|
{chr(10).join(stages)}
"""


if __name__ == "__main__":
    print(run())
