"""The rail's receptances and moving kernel at any point of the head's running surface.

A contact point y^R that is not a loaded node of the rail file's ``contact.y`` list used to stop
the greens stage ("add it to contact.y and rebuild the rail").  Instead, once per rail and time
step, the waves of the rail (both families, on Kropp's grid below the taper's end) are stored
with their shapes at every node of the running surface (``solvers.rail.surface``: the reduced
model's basis holds the attachment modes of loads at vertices every ``SPACING`` across the
surface), in

    build/rails/<RAIL>/surface/<key>/waves.npz        k (nf, M), the surface nodes, settings
    build/rails/<RAIL>/surface/<key>/node_<i>.npz     psi (nf, M, 2) of surface node i (complex64)

(key: the hash of the rail, its mesh, the code, dt and the grid).  A point is then the quadratic
form of its P2 edge's three nodes (no eigenproblem): its moving kernel is cached like the
listed points' (build/rails/<RAIL>/moving/<key>.npz, pipeline/caches/rail_kernel.py).  The listed points
keep their own direct construction (``rail_kernel.rail_kernel``: bit for bit the numbers of
before); docs/validation/53_any_rail_point.md compares the two at a listed point.
"""
from __future__ import annotations

import logging
import time
from concurrent.futures import ThreadPoolExecutor
import fcntl

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.code_hash import code_key
from pipeline.caches.blas_threads import pinned
from pipeline.caches.rail_kernel import kernel_config, kernel_path
from pipeline.config.loader import config_hash
from geometry.rail import running_surface
from pipeline.stages.rail import rail_mesh
from solvers.rail.kernel_arrays import moving_kernel_arrays

log = logging.getLogger("pipeline.greens")

KIND_WAVES, KIND_NODE, KIND_KERNEL = "rail-surface-waves", "rail-surface-node", "rail-moving-kernel"
SPACING = 7.5e-3  # m: loads (attachment modes of the reduced basis) at vertices about this far apart
K_LOCAL = 20.0  # rad/m: the static near field subtracted (as solvers.rail.response.wave_table)
# the moving kernel's drop tolerance (moving_green_waves: a wave's remainder below KERNEL_TOL of the point
# receptance): 1e-12 gives 1e-11 of the kernel's peak against 1e-17 (measured), ~2x faster, far below the
# table's own 2e-3 against the direct construction (docs/validation/53_any_rail_point.md)
KERNEL_TOL = 1e-12
TABLE_VERSION = 1  # of build_table's procedure (its code is hashed as well: TABLE_FUNCTIONS)
# the functions whose results are cached; their code (what they reach) is hashed into the keys
TABLE_FUNCTIONS = ("pipeline.caches.rail_surface_table:build_table",)
KERNEL_FUNCTIONS = ("pipeline.caches.rail_surface_table:kernel_from_waves",)


def table_config(pr: dict, rail_hash: str, dt: float, grid: dict) -> dict:
    """What the surface wave table depends on: the rail kernel's key without the point, the speed
    and the lags (``rail_kernel.kernel_config``), plus this module's settings and code."""
    cfg = kernel_config(pr, rail_hash, 0.0, 1.0, dt, grid)
    for k in ("y_r_abs", "v", "n_lags"):
        cfg.pop(k, None)
    cfg["surface"] = {"spacing": SPACING, "k_local": K_LOCAL, "code": code_key(*TABLE_FUNCTIONS), "version": TABLE_VERSION}
    return cfg


def table_dir(rail: str, cfg: dict):
    return paths.rail_dir(rail) / "surface" / config_hash(cfg)[:16]


@pinned
def build_table(pr: dict, dt: float, grid: dict, folder, cfg: dict, workers: int = 2) -> None:
    """Compute the surface wave table (module notes) and write it to ``folder``; OpenBLAS on one thread
    (``blas_threads``: the same bits whoever builds it)."""
    from solvers.greens.kernels import frequency_grid  # lazy: brings in numba, scipy
    from solvers.rail.surface import family_shapes, load_points, surface_nodes, surface_polyline, surface_rows  # lazy: brings in scipy

    from pipeline.stages.rail_io import build_rail_model  # lazy: brings in scipy

    t0 = time.perf_counter()
    poly = surface_polyline(running_surface(pr, pr.get("contact", {}).get("y", [])))
    loads = load_points(poly, SPACING)
    model = build_rail_model(pr, str(paths.rail_dir(pr["name"]) / "section.msh"), contact_y=list(loads),
                             with_centre=False)
    idx, vertex = surface_nodes(model.families["sym"].nodes, poly, float(poly[-1, 0]))
    t1 = time.perf_counter()
    f = frequency_grid(dt, int(grid["n_t"]))
    freqs = np.maximum(f[f < grid["f_taper"]], 1.0)  # the static limit: the 1 Hz response (as rail_kernel)
    parts = np.array_split(freqs, max(1, min(workers, len(freqs))))
    Ks, Ss = [], []
    for name in ("sym", "anti"):
        rf = getattr(model, name)
        rows = surface_rows(model.families[name], rf.BY, idx)
        with ThreadPoolExecutor(len(parts)) as ex:  # LAPACK releases the GIL
            out = list(ex.map(lambda fp: family_shapes(rf, rows, 2 * np.pi * fp, K_LOCAL), parts))
        Ks.append(np.concatenate([o[0] for o in out]))
        Ss.append(np.concatenate([o[1].astype(np.complex64) for o in out]))
        del out
    K, S = np.concatenate(Ks, axis=1), np.concatenate(Ss, axis=1)
    del Ks, Ss
    y_nodes = model.families["sym"].nodes[idx, 0]
    for i in range(len(idx)):
        artifacts.save_npz(folder / f"node_{i}.npz", KIND_NODE, cfg, psi=np.ascontiguousarray(S[:, :, i]))
    artifacts.save_npz(folder / "waves.npz", KIND_WAVES, cfg, k=K, f=freqs, y_nodes=y_nodes, vertex=vertex,
                       z_nodes=model.families["sym"].nodes[idx, 1], loads=loads)  # last: marks it complete
    log.info("rail surface wave table: model (loads at %d points) %.1f s, %d frequencies x %d waves at %d "
             "surface nodes %.1f s -> %s", len(loads), t1 - t0, len(freqs), K.shape[1], len(idx),
             time.perf_counter() - t1, folder)


def point_waves(pr: dict, rail_hash: str, y_r: float, dt: float, grid: dict) -> tuple[np.ndarray, np.ndarray]:
    """k (nf, M) and a (nf, M, 2, 2) of the head point |y_r| from the surface table (built when
    missing), on the frequencies f < f_taper of Kropp's grid."""
    from solvers.rail.surface import point_amplitudes, point_weights  # lazy: brings in scipy

    cfg = table_config(pr, rail_hash, dt, grid)
    folder = table_dir(pr["name"], cfg)
    try:
        w, _ = artifacts.load_npz(folder / "waves.npz", KIND_WAVES, cfg)
    except artifacts.ArtifactError:
        folder.mkdir(parents=True, exist_ok=True)
        with open(folder / ".lock", "w") as lock:     # one builder at a time (cases side by side, study workers)
            fcntl.flock(lock, fcntl.LOCK_EX)
            if not (folder / "waves.npz").exists():   # built by another process meanwhile
                build_table(pr, dt, grid, folder, cfg)
        w, _ = artifacts.load_npz(folder / "waves.npz", KIND_WAVES, cfg)
    idx, N = point_weights(w["y_nodes"], w["vertex"], y_r)
    psi = np.stack([artifacts.load_npz(folder / f"node_{i}.npz", KIND_NODE, cfg)[0]["psi"] for i in idx], axis=2)
    # psi stays complex64: einsum promotes to complex128 itself (the same numbers, bit for bit) without
    # a 110 MB copy, 3x faster
    return w["k"], point_amplitudes(psi, np.arange(3), N)


def surface_kernel(pr: dict, rail_hash: str, y_r: float, v: float, dt: float, grid: dict,
                   taper) -> tuple[dict, bool]:
    """The rail arrays of the greens artifact at any head point y_r (signed), as
    ``rail_kernel.rail_kernel`` gives them at a listed point: from the moving-kernel cache, or
    built from the surface table and cached; returns (arrays, loaded_from_cache)."""
    from solvers.rail.moving_kernel import mirror  # lazy: brings in numba


    rail_mesh(pr)
    cfg = dict(kernel_config(pr, rail_hash, y_r, v, dt, grid), surface=table_config(pr, rail_hash, dt, grid)["surface"],
               surface_kernel=code_key(*KERNEL_FUNCTIONS))
    path = kernel_path(pr["name"], cfg)
    try:
        arrays, _ = artifacts.load_npz(path, KIND_KERNEL, cfg)
        cached = True
    except artifacts.ArtifactError:
        t0 = time.perf_counter()
        k, a = point_waves(pr, rail_hash, abs(float(y_r)), dt, grid)
        t1 = time.perf_counter()
        arrays = kernel_from_waves(k, a, v, dt, grid, taper)
        artifacts.save_npz(path, KIND_KERNEL, cfg, **arrays)
        log.info("rail moving kernel at |y^R| = %.2f mm from the surface table: waves %.1f s, kernel %.1f s",
                 1e3 * abs(y_r), t1 - t0, time.perf_counter() - t1)
        cached = False
    if y_r < 0:
        arrays = dict(arrays)
        for key in ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance"):
            arrays[key] = mirror(arrays[key])
    return arrays, cached


@pinned
def kernel_from_waves(k: np.ndarray, a: np.ndarray, v: float, dt: float, grid: dict, taper) -> dict:
    """The moving kernel's arrays (``solvers.rail.kernel_arrays``) of a point's waves in the surface table,
    its static near-field waves summed apart."""
    return moving_kernel_arrays(k, a, v, dt, grid, taper, static_tol=KERNEL_TOL)
