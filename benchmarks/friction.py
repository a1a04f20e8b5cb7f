"""Friction curve benchmarks (pipeline/caches/friction_curves.py): `run() -> str` gives the markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks friction [--update]

On the default case's contact (its static pressure field from the contact stage's setup, the
0.5 mm grid of dt = 36 us at 50 km/h), side by side in one process after numba's warm-up:

* before: the contact stage's fixed family, 11 Coulomb curves mu = 0.10 .. 0.60 (step 0.05),
  one ``rf_curve`` each, as the stage built them for every case;
* now: the curve of one new value (0.33, 0.05, 0.65: each not on the old grid) through the
  stage's cache (``pipeline.caches.friction_curves.CurveCache``, an empty temporary folder: computed and
  written), and the same value again (read back from the cache).

Target (issue 26): a new friction value costs under 1 s.
"""
from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

import numpy as np

OLD_GRID = np.round(np.arange(0.10, 0.6001, 0.05), 2)        # the contact stage's family before issue 26
NEW = (0.33, 0.05, 0.65)
TARGET = 1.0                                                 # s per new value


def _static_contact():
    """(p3, dx, dy, v, E, nu) of the default case's static contact (the contact stage's code)."""
    from solvers.contact.static import static_contact
    from pipeline.stages.contact import contact_setup

    c, pw, _, geo, _ = contact_setup("default")
    E, nu = pw["material"]["E"], pw["material"]["nu"]
    v, dt, F_L = c["kinematics"]["speed"], c["time"]["dt"], c["loading"]["preload"]
    dx = v * dt
    x, y, gap, A, B, xi, static = static_contact(geo, E, nu, F_L, dx)
    return static.p, dx, float(y[1] - y[0]), v, E, nu


def run() -> str:
    from benchmarks.__main__ import machine
    from pipeline.caches.friction_curves import CurveCache, Friction
    from solvers.contact.friction import rf_curve

    from pipeline.store.provenance import git_revision, library_versions

    p3, dx, dy, v, E, nu = _static_contact()
    rf_curve(p3, dx, dy, v, 0.3, E, nu)                       # numba compiled / loaded from its cache
    t0 = time.perf_counter()
    library_versions(), git_revision()                        # what every artifact's provenance records
    t_prov = time.perf_counter() - t0
    t0 = time.perf_counter()
    for mu in OLD_GRID:
        rf_curve(p3, dx, dy, v, float(mu), E, nu)
    old = time.perf_counter() - t0
    new, again = {}, {}
    with tempfile.TemporaryDirectory() as d:
        cache = CurveCache(Path(d))
        for mu in NEW:
            t0 = time.perf_counter()
            cache(p3, dx, dy, v, Friction.coulomb(mu), E, nu)
            new[mu] = time.perf_counter() - t0
            t0 = time.perf_counter()
            cache(p3, dx, dy, v, Friction.coulomb(mu), E, nu)
            again[mu] = time.perf_counter() - t0
        assert (cache.built, cache.reused) == (len(NEW), len(NEW))
    load = " / ".join(f"{x:.1f}" for x in os.getloadavg())
    worst = max(new.values())
    rows = "\n".join(f"| {mu:g} | {new[mu]:.2f} s | {1e3 * again[mu]:.1f} ms |" for mu in NEW)
    return f"""## Friction curves (issue 26)

`benchmarks/friction.py`: the regularized friction curves mu_RF(s) of the default case's contact (its
static pressure field, {p3.shape[0]} x {p3.shape[1]} elements of {1e3 * dx:.2f} x {1e3 * dy:.2f} mm), one process after
numba's warm-up and the provenance's once-per-process import of the numerical stack ({t_prov:.1f} s, paid by
every stage that writes an artifact), side by side in one run. Machine: {machine()}; load average {load} at the end (the machine
is shared: wall times are noisy, the ratio is the figure to compare).

Before: the contact stage built the fixed family mu = 0.10 .. 0.60 (step 0.05) for every case: 11 curves in
**{old:.2f} s** ({old / len(OLD_GRID):.2f} s per curve), and no other value existed. Now: the case's own value,
and a study's values, each once per contact (`pipeline.caches.friction_curves.CurveCache`, build/cases/<case>/friction/):

| new value mu | first time (built and written) | again (from the cache) |
|---:|---:|---:|
{rows}

A new value costs {worst:.2f} s at most (target < {TARGET:g} s: **{'met' if worst < TARGET else 'NOT met'}**),
{old / worst:.0f}x less than the old fixed family; the default case's contact stage builds one curve instead of 11.
"""


if __name__ == "__main__":
    print(run())
