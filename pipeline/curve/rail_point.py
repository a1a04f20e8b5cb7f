"""The moving rail kernel for a new speed, as the greens stage makes it, for a line study's many curves.

At a point of the rail file's ``contact.y`` list, with the point's wave table cached (many speeds at the
same few points); at any other point, with the running surface's table files held in memory per
process (``surface_arrays``).

``rail_kernel.rail_kernel`` builds a listed point's kernel for each new speed from scratch: the
waveguide model of the rail and its wave table on Kropp's grid (~15 s), then the moving sum (~1 s).
The wave table does not depend on the speed; here it is stored once per rail, point, time step and
grid in ``build/rails/<RAIL>/points/<key>.npz`` (``k`` (nf, M), ``a`` (nf, M, 2, 2), complex128: the
same numbers), and the kernel is built from it by the same calls as ``rail_kernel.build_kernel`` and
written to the shared moving-kernel cache under the same key, so the greens stage of a curve's wheel
loads it (bit for bit the kernel ``build_kernel`` makes: tests/verdict/test_screen_first.py).
"""
from __future__ import annotations

import logging
import time
import fcntl

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.caches.blas_threads import one_blas_thread, pinned
from pipeline.caches.rail_kernel import kernel_config, wave_table_threads, KIND, kernel_path
from pipeline.config.loader import config_hash
from pipeline.stages.rail import rail_mesh
from pipeline.store.code_hash import code_key
from pipeline.caches.rail_surface_table import table_dir
from solvers.rail.kernel_arrays import moving_kernel_arrays
from solvers.greens.grid import RAIL_F_MAX, RAIL_F_TAPER, RAIL_LAGS, RAIL_NT, rail_taper
from pipeline.stages.greens import rail_greens

log = logging.getLogger("pipeline.greens")

KIND_TABLE = "rail-point-waves"


def table_config(pr: dict, rail_hash: str, y_r: float, dt: float, grid: dict) -> dict:
    """The wave table's key: the kernel's (``rail_kernel.kernel_config``) without the speed and lags."""
    cfg = kernel_config(pr, rail_hash, y_r, 1.0, dt, grid)
    for k in ("v", "n_lags"):
        cfg.pop(k, None)
    return cfg | {"table": "rail_kernel.wave_table_threads"}


def point_table(pr: dict, rail_hash: str, y_r: float, dt: float, grid: dict) -> dict:
    """{'k', 'a'} of the head point y_r >= 0 on Kropp's grid below the taper's end (cached; module notes)."""
    from solvers.greens.kernels import frequency_grid  # lazy: brings in numba, scipy

    from pipeline.stages.rail_io import build_rail_model  # lazy: brings in scipy

    cfg = table_config(pr, rail_hash, y_r, dt, grid)
    path = paths.rail_dir(pr["name"]) / "points" / f"{config_hash(cfg)[:16]}.npz"
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_suffix(".lock"), "w") as lock:        # one builder at a time (study workers)
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            a, _ = artifacts.load_npz(path, KIND_TABLE, cfg)
            return {"k": a["k"], "a": a["a"]}
        except artifacts.ArtifactError:
            pass
        t0 = time.perf_counter()
        with one_blas_thread():                               # the bits of rail_kernel.build_kernel's table
            model = build_rail_model(pr, str(paths.rail_dir(pr["name"]) / "section.msh"), contact_y=[y_r],
                                     with_centre=False)
            f = frequency_grid(dt, int(grid["n_t"]))
            inside = f < grid["f_taper"]
            T = wave_table_threads(model, np.maximum(f[inside], 1.0), y_r)   # the static limit: the 1 Hz response
        out = {"k": T["k"], "a": np.ascontiguousarray(T["a"][:, :, 0])}
        artifacts.save_npz(path, KIND_TABLE, cfg, **out)
        log.info("rail wave table at |y^R| = %.1f mm (a listed point) in %.1f s -> %s", 1e3 * y_r,
                 time.perf_counter() - t0, path)
        return out


@pinned
def kernel_from_table(T: dict, v: float, dt: float, grid: dict, taper) -> dict:
    """``rail_kernel.build_kernel``'s arrays from the point's wave table (``solvers.rail.kernel_arrays``)."""
    return moving_kernel_arrays(T["k"], T["a"], v, dt, grid, taper)


def listed_kernel(pr: dict, rail_hash: str, y_r: float, v: float, dt: float, grid: dict, taper) -> dict:
    """The rail arrays at the listed point y_r (signed) as ``rail_kernel.rail_kernel`` returns them: from
    the moving-kernel cache, or built from the cached wave table and stored there."""
    from solvers.rail.moving_kernel import mirror  # lazy: brings in numba


    rail_mesh(pr)
    cfg = kernel_config(pr, rail_hash, y_r, v, dt, grid)
    path = kernel_path(pr["name"], cfg)
    try:
        arrays, _ = artifacts.load_npz(path, KIND, cfg)
    except artifacts.ArtifactError:
        arrays = kernel_from_table(point_table(pr, rail_hash, abs(float(y_r)), dt, grid), v, dt, grid, taper)
        artifacts.save_npz(path, KIND, cfg, **arrays)
    if y_r < 0:
        arrays = dict(arrays)
        for key in ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance"):
            arrays[key] = mirror(arrays[key])
    return arrays


_SURFACE: dict = {}        # surface_kernel's table files held per process: (path, mtime) -> arrays
_SURFACE_MAX = 24          # node files kept (18 MB each on BV50)


def _held(path, kind: str, cfg: dict, key: str):
    st = path.stat()
    k = (str(path), st.st_mtime_ns)
    if k not in _SURFACE:
        if len(_SURFACE) >= _SURFACE_MAX:
            _SURFACE.pop(next(iter(_SURFACE)))
        a, _ = artifacts.load_npz(path, kind, cfg)
        _SURFACE[k] = a[key] if key else dict(a)
    return _SURFACE[k]


def surface_arrays(pr: dict, rail_hash: str, y_r: float, v: float, dt: float, grid: dict, taper) -> dict | None:
    """``rail_surface.surface_kernel``'s arrays at a point off the listed ones, with the surface table's
    files (its waves and the node shapes) held in memory per process: the same calls on the same arrays
    (bit for bit).  None when the surface table is not built yet (``surface_kernel`` builds it)."""
    from solvers.rail.moving_kernel import mirror  # lazy: brings in numba
    from solvers.rail.surface import point_amplitudes, point_weights  # lazy: brings in scipy

    from pipeline.caches.rail_surface_table import KERNEL_FUNCTIONS, KIND_KERNEL, KIND_NODE, KIND_WAVES, kernel_from_waves, table_config  # local: the module binds table_config otherwise

    rail_mesh(pr)
    tcfg = table_config(pr, rail_hash, dt, grid)
    cfg = dict(kernel_config(pr, rail_hash, y_r, v, dt, grid), surface=tcfg["surface"],
               surface_kernel=code_key(*KERNEL_FUNCTIONS))
    path = kernel_path(pr["name"], cfg)
    try:
        arrays, _ = artifacts.load_npz(path, KIND_KERNEL, cfg)
    except artifacts.ArtifactError:
        folder = table_dir(pr["name"], tcfg)
        if not (folder / "waves.npz").exists():
            return None
        w = _held(folder / "waves.npz", KIND_WAVES, tcfg, "")
        idx, N = point_weights(w["y_nodes"], w["vertex"], abs(float(y_r)))
        psi = np.stack([_held(folder / f"node_{i}.npz", KIND_NODE, tcfg, "psi") for i in idx], axis=2)
        arrays = kernel_from_waves(w["k"], point_amplitudes(psi, np.arange(3), N), v, dt, grid, taper)
        artifacts.save_npz(path, KIND_KERNEL, cfg, **arrays)
    if y_r < 0:
        arrays = dict(arrays)
        for key in ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance"):
            arrays[key] = mirror(arrays[key])
    return arrays


def rail_arrays(pr: dict, y_r: float, v: float, dt: float) -> dict:
    """``stages.greens.rail_greens``'s arrays at the rail model's point y_r (``stages.greens.rail_point``),
    a listed point's through ``listed_kernel``."""
    grid = {"n_t": RAIL_NT, "n_lags": RAIL_LAGS, "f_max": RAIL_F_MAX, "f_taper": RAIL_F_TAPER}
    if np.any(np.abs(np.abs(np.asarray(pr["contact"]["y"], float)) - abs(y_r)) < 1e-12):
        return listed_kernel(pr, config_hash(pr), y_r, v, dt, grid, rail_taper)
    held = surface_arrays(pr, config_hash(pr), y_r, v, dt, grid, rail_taper)
    return held if held is not None else rail_greens(pr, config_hash(pr), y_r, v, dt)[0]
