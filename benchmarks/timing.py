"""Timing helper shared by the benchmark suites."""
from __future__ import annotations

import time

import numpy as np


def _times(f, n: int, warm: int) -> list[float]:
    """Wall times (s) of n calls of f() after `warm` untimed calls."""
    for _ in range(warm):
        f()
    t = []
    for _ in range(n):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return t


def median_time(f, n: int, warm: int = 0) -> float:
    """Median wall time (s) of n calls of f() after `warm` untimed calls."""
    return float(np.median(_times(f, n, warm)))


def min_time(f, n: int, warm: int = 0) -> float:
    """Minimum wall time (s) of n calls of f() after `warm` untimed calls (on a shared machine the
    minimum is the cost)."""
    return float(min(_times(f, n, warm)))
