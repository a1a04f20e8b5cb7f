"""A map study's grid of creepages and friction coefficients (its ``[grid]`` and ``[quick]`` tables)."""
from __future__ import annotations

import numpy as np

from solvers.study import grid


def grid_of(spec: dict, quick: bool) -> tuple[np.ndarray, np.ndarray]:
    g = spec["grid"]
    step = spec["quick"] if quick else g
    return (grid(g["gamma_y_first"], g["gamma_y_last"], step["gamma_y_step"]),
            grid(g["mu_first"], g["mu_last"], step["mu_step"]))
