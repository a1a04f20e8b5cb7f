"""The rail's moving Green's function as a shared, cached artifact (SPEC 3.4).

The kernel depends on the rail (its parameter file, mesh and the code of the waveguide
model), the rail-head contact point |y^R|, the speed v, the time step dt, Kropp's grid N_t,
the number of lags and the taper of the receptance -- not on the wheel, the friction, the
creepage or the preload.  It is stored once per such key,

    build/rails/<RAIL>/moving/<key>.npz        (key: 16 hex digits of the hash of all of it)

written atomically (pipeline.store.artifacts) and loaded by the greens stage of every case with the
same key: a new wheel, friction or creepage never recomputes it, and the two mirror-image
points y^R = +-12 mm of the default and dy10 cases share one file (the kernel at -y^R is the
one at +y^R with g23, g32 negated, exactly: ``solvers.rail.moving_kernel.mirror``).  Make knows the
inputs through the greens rule (the rail file, the case file, the sources; the stage meshes the
rail section itself, ``stages.rail.rail_mesh``); the key catches the
rest (a changed mesh or model code makes a new key, so a stale kernel is never loaded).

Building it: the waveguide model of the rail (``build_rail_model``, ~5 s), its wave table on
Kropp's grid below the taper's end (two threads, one per half of the frequencies: an
eigenproblem per frequency and wave family, LAPACK releases the GIL), and the kernel from the
wave table by ``solvers.rail.moving_kernel.moving_green_waves`` (~2 s; the same numbers as the
reference ``solvers.greens.kernels.moving_green``, tests/greens/test_moving_kernel.py).
"""
from __future__ import annotations

import hashlib
import logging
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.code_hash import code_key
from pipeline.caches.blas_threads import pinned
from pipeline.config.loader import config_hash
from pipeline.stages.rail import rail_mesh
from solvers.rail.kernel_arrays import moving_kernel_arrays

log = logging.getLogger("pipeline.greens")

KIND = "rail-moving-kernel"
KERNEL_FUNCTIONS = ("pipeline.caches.rail_kernel:build_kernel",)  # the code they reach is in the key


def kernel_config(pr: dict, rail_hash: str, y_r: float, v: float, dt: float, grid: dict) -> dict:
    """Everything the kernel at |y_r| depends on (the cache key is its hash).  grid: n_t, n_lags,
    f_max, f_taper (solvers.greens.grid's RAIL_* settings).  |y_r| exactly, as the kernel is built
    at it: rounded (to 1 nm, as it was), two points of one bin shared a key and the first builder's
    kernel (8e-9 of its peak per 0.1 nm at 10.3 mm, issue 34)."""
    mesh = paths.rail_dir(pr["name"]) / "section.msh"
    return {"rail": rail_hash, "mesh": hashlib.sha256(mesh.read_bytes()).hexdigest()[:16],
            "code": code_key(*KERNEL_FUNCTIONS), "y_r_abs": abs(float(y_r)), "v": float(v), "dt": float(dt),
            **{k: (int(x) if k.startswith("n_") else float(x)) for k, x in grid.items()}}


def kernel_path(rail: str, cfg: dict):
    return paths.rail_dir(rail) / "moving" / f"{config_hash(cfg)[:16]}.npz"


def rail_kernel(pr: dict, rail_hash: str, y_r: float, v: float, dt: float, grid: dict, taper) -> tuple[dict, bool]:
    """The rail arrays of the greens artifact at y_r (signed), from the cache or built and
    cached; returns (arrays, loaded_from_cache).  rail_hash: the rail parameters' (rail.npz's) configuration
    hash; ``taper(f)`` rolls the receptance off."""
    from solvers.rail.moving_kernel import mirror  # lazy: brings in numba


    rail_mesh(pr)                                   # section.msh, as the rail stage beside it makes it
    cfg = kernel_config(pr, rail_hash, y_r, v, dt, grid)
    path = kernel_path(pr["name"], cfg)
    cached = path.exists()
    if cached:
        try:
            arrays, _ = artifacts.load_npz(path, KIND, cfg)
        except artifacts.ArtifactError as e:          # unreadable: rebuild it
            log.warning("%s", e)
            cached = False
    if not cached:
        log.info("rail moving kernel at |y^R| = %.1f mm: not in the cache, building it", 1e3 * abs(float(y_r)))
        arrays = build_kernel(pr, abs(float(y_r)), v, dt, grid, taper)
        artifacts.save_npz(path, KIND, cfg, **arrays)
    if y_r < 0:
        arrays = dict(arrays)
        for key in ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance"):
            arrays[key] = mirror(arrays[key])
    return arrays, cached


@pinned
def wave_table_threads(model, freqs, y: float, workers: int = 2) -> dict:
    """``wave_table(model, freqs, points=[y])`` computed over ``workers`` frequency slices in
    threads (each frequency is independent: the same numbers as one call), OpenBLAS on one thread in
    each (``blas_threads``: the bits do not follow the process's thread count)."""
    from solvers.rail.response import wave_table  # lazy: brings in scipy

    parts = np.array_split(np.asarray(freqs, float), max(1, min(workers, len(freqs))))
    with ThreadPoolExecutor(len(parts)) as ex:
        tabs = list(ex.map(lambda f: wave_table(model, f, points=[y]), parts))
    out = dict(tabs[0])
    out["k"] = np.concatenate([t["k"] for t in tabs], axis=0)
    out["a"] = np.concatenate([t["a"] for t in tabs], axis=0)
    out["f"] = np.concatenate([t["f"] for t in tabs])
    return out


def table_transfer(T: dict, inside: np.ndarray, w: np.ndarray):
    """G(x, f) (n_x, n_f, 2, 2) of wave table ``T`` (frequencies f[inside]) times the taper ``w``,
    zero elsewhere: the input of the direct construction ``solvers.greens.kernels.moving_green`` that the
    wave-sum kernel replaces (its reference in the tests and the benchmark)."""
    from solvers.rail.response import evaluate_table  # lazy: brings in scipy

    def transfer(x, ff):
        G = np.zeros((len(x), len(ff), 2, 2), complex)
        G[:, inside] = evaluate_table(T, x)[0] * w[None, :, None, None]
        return G
    return transfer


@pinned
def build_kernel(pr: dict, y_r: float, v: float, dt: float, grid: dict, taper) -> dict:
    """Moving kernel g_mov (n_lags, 2, 2), the fixed-point kernel, its decay, the tail ratio and
    the point receptance at head point y_r >= 0 (module notes; ``solvers.rail.kernel_arrays``) from the
    point's own wave table; OpenBLAS on one thread (``blas_threads``)."""
    from solvers.greens.kernels import frequency_grid  # lazy: brings in numba, scipy
    from pipeline.stages.rail_io import build_rail_model  # lazy: brings in scipy

    t0 = time.perf_counter()
    msh = paths.rail_dir(pr["name"]) / "section.msh"
    model = build_rail_model(pr, str(msh), contact_y=[y_r], with_centre=False)
    t1 = time.perf_counter()
    f = frequency_grid(dt, int(grid["n_t"]))
    inside = f < grid["f_taper"]
    T = wave_table_threads(model, np.maximum(f[inside], 1.0), y_r)   # the static limit: the 1 Hz response
    t2 = time.perf_counter()
    arrays = moving_kernel_arrays(T["k"], T["a"][:, :, 0], v, dt, grid, taper)
    log.info("rail moving kernel at |y^R| = %.1f mm: model %.1f s, wave table (%d frequencies) %.1f s, "
             "kernel (%d lags) %.1f s", 1e3 * y_r, t1 - t0, int(inside.sum()), t2 - t1, int(grid["n_lags"]),
             time.perf_counter() - t2)
    return arrays
