"""A cached rail kernel is a function of its key: the same bits whoever builds it first (issue 34).

Each build runs in a fresh build folder (``SQUEAL_BUILD_DIR``, with the rail's section mesh and
rail.npz copied in), once as Make runs a stage (a subprocess with ``OMP_NUM_THREADS=1``, Makefile)
and once as a pytest session does (this process, OpenBLAS on 2 threads), through the two paths
that write the shared kernel file: the greens stage's (``greens_stage.rail_greens``) and the
screen-first verdict's (``verdict.rail_point.rail_arrays``).  Before ``pipeline.caches.blas_threads`` the
listed point's kernels of the two differed by 3e-7 of the peak and the surface table's waves in
their last bits (8e-8 of the kernel's peak at y^R = 10.3 mm), and the kernel's key rounded |y^R| to
1 nm while the kernel was built at the caller's y^R."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
RAIL = ROOT / "build" / "rails" / "bv50"
DT, V = 36e-6, 50 / 3.6
KEYS = ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance")

pytestmark = pytest.mark.skipif(not (RAIL / "rail.npz").exists() or not (RAIL / "section.msh").exists(),
                                reason="the BV50 rail is not built (make rail)")


def _fresh(tmp: Path) -> Path:
    (tmp / "rails" / "bv50").mkdir(parents=True)
    for f in ("section.msh", "rail.npz"):
        shutil.copy2(RAIL / f, tmp / "rails" / "bv50" / f)
    return tmp


# in a subprocess as Make runs it: rail_greens (rail_kernel.rail_kernel / rail_surface.surface_kernel)
MAKE_SIDE = """
import sys, numpy as np
from pipeline.config.loader import config_hash
from pipeline.stages.greens import rail_greens
from pipeline.stages.rail import load_rail_params
pr, _ = load_rail_params("bv50")
a, cached = rail_greens(pr, config_hash(pr), float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]))
assert not cached
np.savez(sys.argv[4], **{k: a[k] for k in %r})
""" % (KEYS,)


def _start(build: Path, code: str, *args: str) -> subprocess.Popen:
    """A subprocess as Make runs a stage (OMP_NUM_THREADS=1) building in ``build``; it runs while this
    process builds its own copy."""
    env = dict(os.environ, SQUEAL_BUILD_DIR=str(build), OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    return subprocess.Popen([sys.executable, "-c", code, *args], cwd=ROOT, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def _wait(proc: subprocess.Popen, out: Path) -> dict:
    _, err = proc.communicate(timeout=900)
    assert proc.returncode == 0, err[-2000:]
    return dict(np.load(out))


def _pytest_side(build: Path, y: float, monkeypatch) -> dict:
    from pipeline.caches.blas_threads import blas_threads, set_blas_threads
    from pipeline.curve.rail_point import rail_arrays, surface_arrays
    from pipeline.stages.rail import load_rail_params

    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(build))
    pr, _ = load_rail_params("bv50")
    before = blas_threads()
    set_blas_threads(2)                     # as a pytest session on 2 cores (and more) has it
    try:
        a = rail_arrays(pr, y, V, DT)       # the screen-first path (fresh folder: it builds)
    finally:
        if before is not None:
            set_blas_threads(before)
    assert blas_threads() == before          # one_blas_thread restored it
    return a


def _kernel_files(build: Path) -> list:
    return sorted((build / "rails" / "bv50" / "moving").glob("*.npz"))


def _same(a: dict, b: dict) -> None:
    for k in KEYS:
        x, y = np.asarray(a[k]), np.asarray(b[k])
        assert np.array_equal(x, y), (k, float(np.abs(x - y).max() / np.abs(y).max()))


def test_listed_point_kernel_same_bits_whoever_builds_it(tmp_path, monkeypatch):
    """y^R = -12 mm (a node of the rail file's contact.y: the greens stage's own model and wave table
    against the screen-first path's cached point table), 50 km/h: bit for bit, and one kernel file
    under one key in either folder."""
    proc = _start(_fresh(tmp_path / "make"), MAKE_SIDE, "-0.012", repr(V), repr(DT), str(tmp_path / "make.npz"))
    mine = _pytest_side(_fresh(tmp_path / "pytest"), -0.012, monkeypatch)
    _same(_wait(proc, tmp_path / "make.npz"), mine)
    files = [_kernel_files(tmp_path / d) for d in ("make", "pytest")]
    assert [f.name for f in files[0]] == [f.name for f in files[1]] and len(files[0]) == 1


# the running surface's wave table on a coarse Kropp grid (its eigenproblems are the full grid's, 4x fewer
# frequencies; the full grid's kernel would not pass its decay check on it), as point_waves builds it
TABLE_SIDE = """
import sys, numpy as np
from pipeline.config.loader import config_hash
from pipeline.stages.rail import load_rail_params
from pipeline.caches.rail_surface_table import point_waves
pr, _ = load_rail_params("bv50")
k, a = point_waves(pr, config_hash(pr), float(sys.argv[1]), 36e-6, eval(sys.argv[2]))
np.savez(sys.argv[3], k=k, a=a)
"""
COARSE = {"n_t": 2048, "n_lags": 512, "f_max": 5000.0, "f_taper": 9000.0}


def test_surface_table_same_bits_whoever_builds_it(tmp_path, monkeypatch):
    """The running surface's wave table (what a point off the rail file's list has its kernel from,
    r300/a1o's y^R = 10.300367802283973 mm among them), built by Make's environment and by this one:
    every node file bit for bit, and the point's waves."""
    y = 0.010300367802283973
    make, mine = _fresh(tmp_path / "make"), _fresh(tmp_path / "pytest")
    proc = _start(make, TABLE_SIDE, repr(y), repr(COARSE), str(tmp_path / "make.npz"))
    from pipeline.caches.blas_threads import blas_threads, set_blas_threads
    from pipeline.config.loader import config_hash
    from pipeline.stages.rail import load_rail_params
    from pipeline.caches.rail_surface_table import point_waves

    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(mine))
    pr, _ = load_rail_params("bv50")
    before = blas_threads()
    set_blas_threads(2)
    try:
        k, a = point_waves(pr, config_hash(pr), y, DT, COARSE)
    finally:
        if before is not None:
            set_blas_threads(before)
    ref = _wait(proc, tmp_path / "make.npz")
    assert np.array_equal(ref["k"], k) and np.array_equal(ref["a"], a)
    tables = [sorted((d / "rails" / "bv50" / "surface").glob("*/*.npz")) for d in (make, mine)]
    assert [p.relative_to(make) for p in tables[0]] == [p.relative_to(mine) for p in tables[1]]
    for p, q in zip(*tables):
        A, B = np.load(p), np.load(q)
        for key in A.files:
            if key != "__provenance__":
                assert np.array_equal(A[key], B[key]), (p.name, key)


def test_kernel_key_is_the_point_it_is_built_at():
    """Two head points 0.2 nm apart (the same key while |y^R| was rounded to 1 nm in it, the kernel
    built at the caller's point: the first caller's kernel for both) have keys of their own."""
    from pipeline.config.loader import config_hash
    from pipeline.stages.greens import RAIL_F_MAX, RAIL_F_TAPER, RAIL_LAGS, RAIL_NT
    from pipeline.caches.rail_kernel import kernel_config, kernel_path
    from pipeline.stages.rail import load_rail_params

    pr, _ = load_rail_params("bv50")
    grid = {"n_t": RAIL_NT, "n_lags": RAIL_LAGS, "f_max": RAIL_F_MAX, "f_taper": RAIL_F_TAPER}
    y = -0.010300367802283973
    cfg = [kernel_config(pr, config_hash(pr), p, V, DT, grid) for p in (y, y - 2e-10, -y)]
    assert round(cfg[0]["y_r_abs"], 9) == round(cfg[1]["y_r_abs"], 9)
    assert cfg[0]["y_r_abs"] == abs(y) and cfg[1]["y_r_abs"] == abs(y - 2e-10)
    paths = [kernel_path("bv50", c) for c in cfg]
    assert paths[0] != paths[1] and paths[0] == paths[2]       # the mirror point shares its file
