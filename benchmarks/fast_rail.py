"""Rail fast-path benchmarks (issue 15): `run() -> str` gives the markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks fast_rail

Side by side in one run, on the BV50 rail at the default case's head point (y^R = 12 mm,
v = 50 km/h, dt = 36 us, Kropp's grid N_t = 8192, 4096 lags):

* the moving Green's function: the reference construction (``solvers.greens.kernels.moving_green``,
  Kropp per lag from the transfer receptance, as the greens stage did before) against the
  wave-table form (``solvers.rail.moving_kernel.moving_green_waves``), from the same wave table;
  the rail model and the wave table themselves (the cache's cold path);
* the greens stage of a case in a fresh process: with the rail kernel in the shared cache
  (a new wheel, friction or creepage) and with an empty cache (a new rail point);
* the rail convolution per step: direct sum (ring buffer) against the partitioned FFT
  convolution for several head lengths, on a random force history.

Wall-clock figures are minima of repeats unless stated (the machine may be shared).
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from benchmarks.timing import min_time

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build"




def _kernels(rows: list) -> None:
    from solvers.greens.grid import RAIL_F_TAPER, RAIL_LAGS, RAIL_NT, rail_taper
    from pipeline.caches.rail_kernel import table_transfer, wave_table_threads
    from pipeline.stages.rail import load_rail_params
    from solvers.greens.kernels import frequency_grid, moving_green
    from solvers.rail.moving_kernel import moving_green_waves
    from pipeline.stages.rail_io import build_rail_model

    dt, v, y = 36e-6, 50 / 3.6, 0.012
    pr, _ = load_rail_params("bv50")
    t0 = time.perf_counter()
    model = build_rail_model(pr, str(BUILD / "rails" / "bv50" / "section.msh"), contact_y=[y], with_centre=False)
    t_model = time.perf_counter() - t0
    f = frequency_grid(dt, RAIL_NT)
    inside = f < RAIL_F_TAPER
    fin = np.maximum(f[inside], 1.0)
    t0 = time.perf_counter()
    T = wave_table_threads(model, fin, y, workers=1)
    t_tab1 = time.perf_counter() - t0
    t0 = time.perf_counter()
    T = wave_table_threads(model, fin, y, workers=2)
    t_tab2 = time.perf_counter() - t0
    w = rail_taper(f[inside])
    a = T["a"][:, :, 0] * w[:, None, None, None]

    transfer = table_transfer(T, inside, w)

    moving_green_waves(T["k"][:4], a[:4], v, dt, 8, RAIL_NT)          # JIT (or cache load)
    t_new = min_time(lambda: moving_green_waves(T["k"], a, v, dt, RAIL_LAGS, RAIL_NT), 3)
    g_new = moving_green_waves(T["k"], a, v, dt, RAIL_LAGS, RAIL_NT)
    t0 = time.perf_counter()
    g_old = moving_green(transfer, v, dt, RAIL_LAGS, RAIL_NT)
    t_old = time.perf_counter() - t0
    err = np.abs(g_new - g_old).max() / np.abs(g_old).max()
    nf, M = T["k"].shape
    from benchmarks.baseline import BASELINE, previous

    base = previous("solvers", "moving_kernel")         # the wave-table form before its SoA/fastmath loop
    prev = []
    if base is not None:
        base.moving_green_waves(T["k"][:4], a[:4], v, dt, 8, RAIL_NT)
        t_prev = min_time(lambda: base.moving_green_waves(T["k"], a, v, dt, RAIL_LAGS, RAIL_NT), 3)
        g_prev = base.moving_green_waves(T["k"], a, v, dt, RAIL_LAGS, RAIL_NT)
        e_prev = np.abs(g_new - g_prev).max() / np.abs(g_prev).max()
        prev = [f"| moving kernel, {RAIL_LAGS} lags: the previous wave-table loop ({BASELINE}: four complex powers "
                f"per wave, array of structures) | {t_prev:.2f} s | {t_old / t_prev:.0f}x |",
                f"| difference now - previous, max / max \\|g\\| | {e_prev:.1e} | |"]
    rows += [f"| BV50 waveguide model (reduced wave families; dolfinx assembly, SLEPc basis) | {t_model:.1f} s | |",
             f"| wave table on Kropp's grid, {nf} frequencies x {M} waves, 1 thread | {t_tab1:.1f} s | |",
             f"| same, 2 threads (frequency halves) | {t_tab2:.1f} s | {t_tab1 / t_tab2:.2f}x |",
             f"| moving kernel, {RAIL_LAGS} lags: reference (Kropp per lag, `moving_green`, one run) | {t_old:.1f} s | 1x |",
             f"| moving kernel, {RAIL_LAGS} lags: wave-table form (`moving_green_waves`) | {t_new:.2f} s | "
             f"**{t_old / t_new:.0f}x** |",
             f"| difference new - reference, max over lags and components / max \\|g\\| | {err:.1e} | |"] + prev


def _stage(rows: list) -> None:
    """The greens stage of the default case in a fresh process, cache warm and cold."""
    need = [BUILD / "wheels" / "c20" / "modes.npz", BUILD / "rails" / "bv50" / "rail.npz",
            BUILD / "rails" / "bv50" / "section.msh", BUILD / "cases" / "default" / "contact.npz"]
    if not all(p.exists() for p in need):
        rows.append("| greens stage | (needs the default case's wheel, rail and contact artifacts) | |")
        return
    with tempfile.TemporaryDirectory() as d:
        b = Path(d)
        for p in need:
            q = b / p.relative_to(BUILD)
            q.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(p, q)
        env = dict(os.environ, SQUEAL_BUILD_DIR=str(b), OMP_NUM_THREADS="1")
        cmd = [sys.executable, "-m", "pipeline", "greens", "--case", "default"]

        def once():
            t0 = time.perf_counter()
            subprocess.run(cmd, cwd=ROOT, env=env, check=True, capture_output=True)
            return time.perf_counter() - t0

        t_cold = once()                                 # empty cache: builds the rail kernel
        t_warm = min(once() for _ in range(2))          # kernel from the shared cache
    rows += [f"| greens stage of a case, fresh process, rail kernel not cached (new rail point) | {t_cold:.1f} s | |",
             f"| greens stage of a case, fresh process, rail kernel from the shared cache (new wheel, friction, "
             f"creepage) | {t_warm:.1f} s | |"]


def _convolution(rows: list) -> None:
    import numba

    from solvers.greens.kernels import convolve_direct, ring_convolver, ring_step
    from solvers.timeloop.partitioned import partitioned_convolver, partitioned_history

    @numba.njit(cache=False)
    def ring_history(rc, F):
        xi = np.zeros((F.shape[0], 2))
        for n in range(F.shape[0] - 1):
            a, b = ring_step(rc, F[n, 0], F[n, 1])
            xi[n + 1, 0] = a
            xi[n + 1, 1] = b
        return xi

    g_path = BUILD / "cases" / "default" / "greens.npz"
    if g_path.exists():
        with np.load(g_path) as d:
            g = d["rail_kernel"]
        src = "BV50 moving kernel of the default case"
    else:
        rng = np.random.default_rng(1)
        g = 1e-9 * rng.standard_normal((4096, 2, 2)) * np.exp(-np.arange(4096) / 600.0)[:, None, None]
        src = "random decaying kernel"
    K = g.shape[0]
    F = np.random.default_rng(0).standard_normal((100_000, 2)) * [2e3, 6e3]
    ref = convolve_direct(g, F[:20000])
    rc = ring_convolver(g)
    ring_history(rc, F[:10])
    t_d = min_time(lambda: ring_history(ring_convolver(g), F), 3) / len(F)
    rows.append(f"| direct sum (ring buffer, the former time loop), {K} lags ({src}) | {1e9 * t_d:.0f} ns/step | 1x |")
    for B in (64, 128, 256):
        pc = partitioned_convolver(g, B)
        partitioned_history(pc, F[:10])
        t_p = min_time(lambda: partitioned_history(partitioned_convolver(g, B), F), 3) / len(F)
        err = np.abs(partitioned_convolver(g, B).response(F[:20000]) - ref).max() / np.abs(ref).max()
        flops = 8 * (B - 1) + 32 * (-(-K // B) - 1) * (B + 1) / B
        rows.append(f"| partitioned FFT convolution, head B = {B} ({flops:.0f} flops/step + FFTs), error vs direct "
                    f"{err:.0e} | {1e9 * t_p:.0f} ns/step | **{t_d / t_p:.0f}x** |")


def run() -> str:
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    rows: list = []
    if (BUILD / "rails" / "bv50" / "section.msh").exists():
        _kernels(rows)
        _stage(rows)
    else:
        rows.append("| rail kernel | (needs build/rails/bv50: `make rail`) | |")
    conv: list = []
    _convolution(conv)
    load = " / ".join(f"{x:.1f}" for x in os.getloadavg())
    return f"""## Rail fast paths (issue 15)

`benchmarks/fast_rail.py`: BV50 at y^R = 12 mm, v = 50 km/h, dt = 36 us, N_t = 8192, one process
(OMP_NUM_THREADS=1); minima of repeats except where a row says one run; load average {load} at the end (the
machine may be shared with other jobs).

| rail moving Green's function | time | speed-up |
|---|---:|---:|
{chr(10).join(rows)}

The reference evaluates exp(-i k x) for every wave, frequency and lag (2.6e9 complex exponentials) and
contracts them per lag; the wave-table form runs the powers z^k of each wave as a recurrence and drops the
evanescent near-field waves once their geometric remainder is below 1e-17 of the point receptance
(`solvers/rail/moving_kernel.py`). The greens stage keeps the kernel in `build/rails/<rail>/moving/<key>.npz`,
shared by every case with the same rail, |y^R|, speed and time step (`pipeline/caches/rail_kernel.py`).

| rail convolution in the time loop, per step (njit loop over 100,000 steps) | time | speed-up |
|---|---:|---:|
{chr(10).join(conv)}

The partitioned form (`solvers/timeloop/partitioned.py`): the first B lags directly, the other K - B in partitions of B
lags by overlap-save FFTs of 2B points once per B steps (both force components in one complex FFT); exact
to rounding.
"""


if __name__ == "__main__":
    print(run())
