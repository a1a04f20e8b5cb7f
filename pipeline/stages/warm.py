"""Compile the simulate stage's numba code into numba's cache ahead of it: ``python -m pipeline.stages.warm``
(Make runs it beside the rail stage on a fresh build, so that the ~6 s of compiling the time loop
are off the critical path).  The greens stage's rail-kernel sum is not here: that stage runs
beside this one and compiles it for itself (compiling it in both would be twice the work).

It runs the same njit functions with the same argument types as the stage does, on a small
model made up here (two wheel modes, a 512-lag rail kernel, a Hertzian NORM table, a cubic
friction curve, 300 steps): numba compiles per type signature and caches the machine code next to
the sources (``cache=True``), so the stages then load it instead of compiling.  Nothing is
written but numba's cache; a stage whose types differ simply compiles for itself.
"""
from __future__ import annotations

import logging
import time

import numpy as np
from pipeline.numba_setup import skip_special

log = logging.getLogger("pipeline.stages.warm")


def warm() -> float:
    """Compile (or load) the time loop; returns the wall time [s]."""
    skip_special()
    from solvers.contact.friction import monotone_slopes  # lazy: brings in numba, rocket_fft, scipy
    from solvers.timeloop.interaction import ContactModel, WheelModes, simulate  # lazy: brings in numba, rocket_fft, scipy

    t0 = time.perf_counter()
    xs = np.linspace(0.0, 2e-4, 41)                                # Hertz: F3 = K xi3^1.5, q = F3^(2/3)
    F3 = 65e3 * (xs / 9.7e-5) ** 1.5
    s = np.concatenate([np.linspace(0.0, 0.1, 19), [0.2, 0.7]])
    mu = np.where(s < 0.1, 0.35 * (1 - (1 - s / 0.1) ** 3), 0.35)
    contact = ContactModel(xs, F3 ** (2 / 3), np.full(41, 1.26e-9), np.full(41, 1.15e-9), s, mu,
                           monotone_slopes(s, mu), 0.35, F3)
    wheel = WheelModes(np.array([400.0, 1200.0]), np.array([40.0, 35.0]), np.array([2e-3, 2e-3]),
                       np.array([[0.8, 0.1], [0.3, 0.5]]))
    rail = np.zeros((512, 2, 2))
    rail[1:, 0, 0] = rail[1:, 1, 1] = 1e-12 * np.exp(-np.arange(1, 512) / 50.0)
    simulate(wheel, rail, contact, dt=36e-6, v=13.9, gamma_y=-0.012, gamma_x=0.0, preload=65e3,
             duration=300 * 36e-6, tangential="point", normal="table", store_every=10)
    return time.perf_counter() - t0


if __name__ == "__main__":
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    log.info("numba: time loop compiled (or loaded) in %.1f s", warm())
