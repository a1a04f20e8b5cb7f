"""The boundary-element solver of the radiation check (``solvers.radiation.bem``: bempp-cl, Burton-Miller, P1)
against the analytic pulsating and oscillating spheres at ka = 0.1 ... 5 (issue 28: within 0.5 dB).
Writes docs/validation/71_bem_spheres.md (a writer, run by `make validate`; the 0.5 dB is asserted by
tests/radiation/test_bem_spheres.py on ``sphere_rows`` here).  Slow: bempp compiles its numba kernels once
per process (~1-2 min per operator on a loaded machine).

    .venv/bin/python -m pipeline.validation.writers.bem_spheres
"""
from __future__ import annotations

import time

import numpy as np

from pipeline.validation.cached import cached
from pipeline.validation.writers import save_fragment

KA = (0.1, 0.5, 1.0, 2.0, 5.0)
LEVEL = 3            # bempp's regular sphere: 512 triangles, 258 vertices, edges ~0.18 a (<= lambda/6 up to ka = 5.8)


def _devices() -> list[str]:
    """bempp-cl's backends here: numba always, OpenCL when a CPU driver (pocl) is installed."""
    import bempp_cl.api as api  # lazy: brings in bempp_cl

    return ["numba"] + (["opencl"] if api.CPU_OPENCL_DRIVER_FOUND else [])


def sphere_rows() -> dict:
    """``_sphere_rows`` computed once per code (``pipeline.validation.cached``: the writer and
    tests/radiation/test_bem_spheres.py share it)."""
    return cached("bem_spheres", _sphere_rows, ("pipeline.validation.writers.bem_spheres:_sphere_rows",))


def _sphere_rows(devices=None, ka_values=KA) -> dict:
    """bempp's regular sphere's vertex count and per backend and ka the row (device, ka, L_W pulsating BEM,
    exact, oscillating BEM, exact, wall s), levels in dB re 1e-12 W."""
    import bempp_cl.api as api  # lazy: brings in bempp_cl

    from solvers.radiation import bem  # lazy: brings in scipy

    g = api.shapes.regular_sphere(LEVEL)
    v = g.vertices.T
    a = float(np.mean(np.linalg.norm(v, axis=1)))
    nz = v[:, 2] / np.linalg.norm(v, axis=1)
    rows = []
    for dev in devices or _devices():
        bem.use_device(dev)
        for ka in ka_values:
            t0 = time.perf_counter()
            Wp, Wo = bem.radiated_power(g, ka / a, [np.ones(len(v)), nz])
            wall = time.perf_counter() - t0
            ep, eo = bem.pulsating_sphere_power(a, ka / a), bem.oscillating_sphere_power(a, ka / a)
            rows.append((dev, ka, bem.level(Wp), bem.level(ep), bem.level(Wo), bem.level(eo), wall))
    bem.use_device("numba")
    return {"vertices": len(v), "rows": rows}


def write() -> str:
    d = sphere_rows()
    rows = d["rows"]
    table = "\n".join(f"| {dev} | {ka} | {lp:.2f} | {ep:.2f} | {lp - ep:+.2f} | {lo:.2f} | {eo:.2f} | {lo - eo:+.2f} | "
                      f"{w:.0f} |" for dev, ka, lp, ep, lo, eo, w in rows)
    text = f"""## The boundary-element solver on the analytic spheres (issue 28)

Written by `pipeline/validation/writers/bem_spheres.py` (`make validate`); the 0.5 dB of issue 28 is asserted by
`tests/radiation/test_bem_spheres.py`. `solvers.radiation.bem.radiated_power` (bempp-cl
0.4.2; exterior Burton-Miller (1/2 I - K + (i/k) W) p = -(V + (i/k)(1/2 I + K')) q,
q = i w rho v_n, P1 Galerkin, dense LU; W = 1/2 Re(v^H M p)) on bempp's regular sphere of level {LEVEL}
({d['vertices']} vertices, unit radius), unit normal velocity amplitude: pulsating (v_n = 1; exact
Re z = rho c (ka)^2 / (1 + (ka)^2)) and oscillating (v_n = cos theta; exact z = i rho c h_1(ka) / h_1'(ka)),
with each of bempp's backends present (numba; OpenCL through pocl when installed, debian-packages.txt).
Levels in dB re 1e-12 W; wall time per ka (both spheres; the first of each backend includes its kernels'
compilation; shared 2-core machine, loaded).

| backend | ka | pulsating BEM | exact | Delta | oscillating BEM | exact | Delta | wall (s) |
|---|---|---|---|---|---|---|---|---|
{table}
"""
    return save_fragment("71_bem_spheres.md", text)


if __name__ == "__main__":
    write()
