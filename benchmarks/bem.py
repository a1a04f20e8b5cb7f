"""BEM check benchmark (issue 28, solvers/radiation/bem.py, solvers/radiation/bem_revolution.py): `run() -> str`.

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 POCL_MAX_PTHREAD_COUNT=1 .venv/bin/python -m benchmarks bem --update

The default case's wheel at (2,0,a) (the lambda/6 mesh of pipeline.validation.bem_check, 912 vertices), one thread,
side by side in one run (alternated, minimum of 2 each, after a warm-up call that compiles bempp's
kernels): the free field by the 3-D solve and by the revolution solver (same discrete problem), and the
image wheel's cross block of the ground (the revolution solver's cost over a ground) on bempp's numba
and OpenCL (pocl) backends, quadrature orders 4 and 2.  Not in `make bench`'s default list (bempp's
compilation alone takes minutes).
"""
from __future__ import annotations

import os

import numpy as np

from benchmarks.timing import min_time


def run() -> str:
    from pipeline.validation.bem_check import GROUND_BELOW_CONTACT, wheel_mesh
    from pipeline.stages.radiate import load_radiation_model
    from solvers.radiation import bem
    from solvers.radiation.bem_revolution import cross_block, revolution_power

    import bempp_cl.api as api

    load0 = os.getloadavg()[0]
    model = load_radiation_model("default")
    i = [j for j in range(len(model.f_r)) if model.n[j] == 2 and model.m[j] == 0 and model.cls[j] == "a"][0]
    f = float(model.f_r[i])
    V, T, phi, loop, _ = wheel_mesh(model, 2, f, 0.03)
    k = 2 * np.pi * f / model.c0
    plane = -(float(model.meta["contact"].r) + GROUND_BELOW_CONTACT)
    v = np.tile(np.ones(len(loop)), len(V) // len(loop)) * np.cos(2 * (phi - np.pi))
    devices = ["numba"] + (["opencl"] if api.CPU_OPENCL_DRIVER_FOUND else [])
    runs = {"free field, 3-D solve (numba)": ("numba", lambda: bem.radiated_power(bem.grid_from_arrays(V, T), k, [v])),
            "free field, revolution solver (numba)": ("numba", lambda: revolution_power(V, T, len(loop), k, [v], 2))}
    for dev in devices:
        for q in (4, 2):
            runs[f"ground's cross block, {dev}, quadrature order {q}"] = (dev, lambda q=q: cross_block(V, T, k, 0, plane, q))
    for dev, fn in runs.values():                                          # warm-up: compile / load kernels
        bem.use_device(dev)
        fn()
    times = {key: [] for key in runs}
    for _ in range(2):
        for key, (dev, fn) in runs.items():
            bem.use_device(dev)
            times[key].append(min_time(fn, 1))
    bem.use_device("numba")
    t = {key: min(val) for key, val in times.items()}
    ref = t["free field, 3-D solve (numba)"]
    cb = t["ground's cross block, numba, quadrature order 4"]
    rows = [f"| {key} | {val:.1f} s | {val / ref:.3f} | {val / cb:.2f} |" for key, val in t.items()]
    return f"""## BEM check: revolution solver and backends (issue 28)

`python -m benchmarks bem --update`: the default case's wheel at (2,0,a), {len(V)} vertices ({len(loop)} along
x {len(V) // len(loop)} around), one thread, minimum of 2 alternated runs after a warm-up; load average
{load0:.1f} at the start (shared 2-core machine; the ratios are measured side by side).

| run | wall | / 3-D free field | / cross block numba q4 |
|---|---|---|---|
""" + "\n".join(rows) + "\n"
