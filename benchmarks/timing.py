"""Timing helper shared by the benchmark suites."""
from __future__ import annotations

import time

import numpy as np


def median_time(f, n: int, warm: int = 0) -> float:
    """Median wall time (s) of n calls of f() after `warm` untimed calls."""
    for _ in range(warm):
        f()
    t = []
    for _ in range(n):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return float(np.median(t))


def min_time(f, n: int, warm: int = 0) -> float:
    """Minimum wall time (s) of n calls of f() after `warm` untimed calls (on a shared machine the
    minimum is the cost)."""
    for _ in range(warm):
        f()
    t = []
    for _ in range(n):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return float(min(t))
