"""One BLAS thread while a cached artifact is computed, so that its bits are a function of its key.

OpenBLAS splits a factorisation or a product over its threads, and the order of the partial sums
(so the last bits) follows the number of threads.  The rail's wave tables (an eigenproblem per
frequency and wave family, ``solvers.rail.response.wave_table``) differ between 1 and 2 threads by
about 1e-15 relative, which the moving kernel carries as 3e-7 of its peak at the listed head point
y^R = 12 mm and 8e-8 at the surface point 10.3 mm (measured on this machine, issue 34).  Make runs
every stage with ``OMP_NUM_THREADS=1`` (Makefile), pytest and a Python session with one thread per
core, and the kernel files are shared by key: whichever caller built a kernel first decided its
digits for every later reader.

``one_blas_thread()`` sets OpenBLAS's thread count to 1 for its duration (the count Make's builds
run with, so their artifacts keep their bits) and restores it after; nested and concurrent uses
share one setting (a counter under a lock).  The OpenBLAS library is the one numpy and scipy
loaded (found through the process's mapped files); without it, ``threadpoolctl`` when installed;
otherwise nothing is changed (a warning once: the bits then follow the environment's thread count).
"""
from __future__ import annotations

import contextlib
import ctypes
import functools
import logging
import threading
import numpy

log = logging.getLogger("pipeline.blas")

_LOCK = threading.Lock()
_STATE = {"depth": 0, "saved": [], "limiter": None}


@functools.lru_cache(maxsize=1)
def _openblas() -> tuple:
    """((set_num_threads, get_num_threads), ...) of every OpenBLAS library mapped into the process."""
    import scipy.linalg  # noqa: F401  (and scipy's LAPACK)

    try:
        with open("/proc/self/maps") as fh:
            paths = sorted({ln.split()[-1] for ln in fh if "blas" in ln.lower() or "lapack" in ln.lower()})
    except OSError:                     # not Linux
        return ()
    found, seen = [], set()
    for p in paths:
        if not p.startswith("/"):
            continue
        try:
            lib = ctypes.CDLL(p)
        except OSError:
            continue
        for prefix in ("openblas", "scipy_openblas", "scipy_openblas64_"):
            for suffix in ("", "64_"):
                s = getattr(lib, f"{prefix}_set_num_threads{suffix}", None)
                g = getattr(lib, f"{prefix}_get_num_threads{suffix}", None)
                if s is None or g is None:
                    continue
                addr = ctypes.cast(s, ctypes.c_void_p).value
                if addr in seen:
                    continue
                seen.add(addr)
                s.argtypes, s.restype, g.restype = [ctypes.c_int], None, ctypes.c_int
                found.append((s, g))
    return tuple(found)


def blas_threads() -> int | None:
    """OpenBLAS's current thread count (None: no OpenBLAS found)."""
    libs = _openblas()
    return int(libs[0][1]()) if libs else None


def set_blas_threads(n: int) -> None:
    """Set OpenBLAS's thread count (every OpenBLAS library of the process); no-op without one."""
    for s, _ in _openblas():
        s(int(n))


@functools.lru_cache(maxsize=1)
def _warn_once() -> None:
    log.warning("no OpenBLAS found and threadpoolctl not installed: cached rail kernels are computed with the "
                "environment's BLAS thread count (set OMP_NUM_THREADS=1 for the bits Make's builds have)")


@contextlib.contextmanager
def one_blas_thread():
    """While it lasts, OpenBLAS runs on one thread (module notes)."""
    with _LOCK:
        if _STATE["depth"] == 0:
            libs = _openblas()
            if libs:
                _STATE["saved"] = [int(g()) for _, g in libs]
                for s, _ in libs:
                    s(1)
            else:
                try:
                    from threadpoolctl import threadpool_limits  # lazy: brings in threadpoolctl
                    _STATE["limiter"] = threadpool_limits(limits=1, user_api="blas")
                except ImportError:
                    _warn_once()
        _STATE["depth"] += 1
    try:
        yield
    finally:
        with _LOCK:
            _STATE["depth"] -= 1
            if _STATE["depth"] == 0:
                for (s, _), n in zip(_openblas(), _STATE["saved"]):
                    s(n)
                _STATE["saved"] = []
                if _STATE["limiter"] is not None:
                    _STATE["limiter"].restore_original_limits()
                    _STATE["limiter"] = None


def pinned(fn):
    """Decorator: ``fn`` runs inside ``one_blas_thread()``."""
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with one_blas_thread():
            return fn(*args, **kwargs)
    return wrapper
