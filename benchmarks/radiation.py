"""Radiation benchmarks (pipeline/stages/radiate.py, solvers/radiation/force_power.py): `run() -> str`.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks radiation

The default case's model (C20 modes at its contact point y^W = +32 mm, build/wheels/c20/modes.npz) loaded once, then
`sound_power_of_forces` on the simulation's final stretch (build/cases/default/simulate.npz, 0.5 s at
36 us; without it a synthetic squeal tone with two harmonics at the (3,0,a) mode), the call the studies
make per simulation; and the two unit-force curves on the stage's frequency grid.
"""
from __future__ import annotations

import time

import numpy as np

from benchmarks.timing import median_time
from pipeline.store import paths
from pipeline.stages.radiate import load_radiation_model, sound_power_of_forces
from solvers.constants import F_MAX_HZ as F_MAX
from solvers.radiation.force_power import frequency_grid_for, unit_force_curve


def run() -> str:
    t0 = time.perf_counter()
    model = load_radiation_model("default")
    t_load = time.perf_counter() - t0
    sim = paths.case_dir("default") / "simulate.npz"
    if sim.exists():
        with np.load(sim) as d:
            F, dt = d["F_final"], float(np.median(np.diff(d["t_final"])))
        src = "build/cases/default/simulate.npz"
    else:
        dt, n = 36e-6, 13889
        t = np.arange(n) * dt
        f0 = model.f_r[np.flatnonzero((model.n == 3) & (model.m == 0) & (model.cls == "a"))[0]] - 2.0
        F = np.column_stack([np.zeros(n), 1500 * np.cos(2 * np.pi * f0 * t) + 150 * np.cos(4 * np.pi * f0 * t),
                             65e3 + 600 * np.cos(2 * np.pi * f0 * t + 1.2)])
        src = "a synthetic squeal tone at the (3,0,a) mode"
    res = []
    t_call = median_time(lambda: res.append(sound_power_of_forces(model, F, dt)), 20, warm=2)
    r = res[-1]
    from benchmarks.baseline import BASELINE, previous

    base = previous("postprocess", "force_radiation")
    old_row = ""
    if base is not None:                                # the tone fit before issue 15's closed-form Gram
        old = []
        t_old = median_time(lambda: old.append(base.power_of_forces(model, F[:, 1], F[:, 2], dt)),
                            20, warm=2)
        o = old[-1]
        old_row = (f"| the same with the previous tone fit ({BASELINE}: the Gram matrix summed over the samples, "
                   f"the DTFT with N exponentials); L_W {o['L_W']:.6f} dB, difference {abs(o['L_W'] - r['L_W']):.0e} dB "
                   f"| {1e3 * t_old:.0f} ms ({t_old / t_call:.1f}x) |\n")
    fu = frequency_grid_for(model, 100.0, F_MAX)
    t_unit = median_time(lambda: (unit_force_curve(model, fu, "lateral"), unit_force_curve(model, fu, "radial")), 5)
    return f"""## Radiation

Model of the default case ({model.f_r.size} C20 modes, harmonics 0..{int(model.harmonics.max())}, contact at
y^W = {1e3 * model.meta['y_wheel']:+.0f} mm): loaded in {t_load:.2f} s (modes artifact, surfaces, Gram matrices).

| step | wall |
|---|---:|
| `sound_power_of_forces`, {len(F)} samples ({src}: {len(r['decomposition'].tone_f)} tones, L_W = {r['L_W']:.1f} dB) | {1e3 * t_call:.0f} ms |
{old_row}| unit lateral + radial curves, {fu.size} frequencies (100 Hz - {F_MAX / 1e3:.1f} kHz) | {1e3 * t_unit:.0f} ms |

Median of 20 calls after 2 warm-up calls. The tone fit's normal equations are summed in closed form (Dirichlet
kernels of the Hann window at the tones' sum and difference phases) and the peak refinement's DTFT as a two-level
sum: the same numbers to ~1e-11 dB; every squealing case of a study pays this once.
"""
