"""Per-case cost of the map study, the previous code against the current, side by side (issue 15):
`run() -> str` gives the markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks study_cases

A map case on a worker is the time loop (8 s at most, early stop) plus, when it squeals, the
sound power of its final 0.5 s (``solvers.radiation.force_power.power_of_forces``).  Here 80 cases
drawn at random (fixed seed) from the grid of pipeline/studies/map.toml at its three contact
positions run in one process, each first with the current code and then with the previous
revision's (``benchmarks.baseline``: its solvers and postprocess packages) on the same inputs,
alternating, so that a shared machine's load falls on both alike.  The two must give the same
squeal measures (L_F2 within 0.1 dB, frequency within 1e-4, the same stop reason).
"""
from __future__ import annotations

import os
import time

import numpy as np

N_CASES = 80


def run() -> str:
    from benchmarks.baseline import BASELINE, previous
    from pipeline.study.context import load_context
    from pipeline.study.definition import grid_of
    from pipeline.study.kinds import load_study
    from pipeline.study.worker import _contact, _warm, _wheel
    from solvers.timeloop.interaction import StopRule, simulate

    old = previous("solvers", "interaction")
    old_fr = previous("postprocess", "force_radiation")
    if old is None or old_fr is None:
        return "## Study cases, previous and current code\n\n(The previous revision is not in git here: skipped.)\n"
    from solvers.radiation.force_power import power_of_forces

    load0 = os.getloadavg()[0]
    spec, _ = load_study("map")
    gammas, mus = grid_of(spec, False)
    sim = spec["simulation"]
    rng = np.random.default_rng(0)
    cases = [(spec["cases"][rng.integers(len(spec["cases"]))], float(rng.choice(gammas)), float(rng.choice(mus)))
             for _ in range(N_CASES)]
    ctxs = {c: load_context(c) for c in sorted({c for c, _, _ in cases})}
    t = {"new": [0.0, 0.0], "old": [0.0, 0.0]}
    n_sq = 0
    worst = [0.0, 0.0, 0]
    for case, gy, mu in cases:
        ctx = ctxs[case]
        w = _wheel(ctx)
        kw = dict(dt=ctx.dt, v=ctx.v, gamma_y=gy, gamma_x=ctx.gamma_x, preload=ctx.preload,
                  duration=sim["duration"], tangential=ctx.tangential, normal=ctx.normal,
                  stop=StopRule(window=sim["window"]) if sim["early_stop"] else None,
                  store_every=max(1, int(round(0.01 / ctx.dt))), final=sim["final"])
        cm, ocm = _contact(ctx, mu), old.contact_model(ctx.contact, mu)
        ow = old.WheelModes(w.f_r, w.modal_mass, w.zeta, w.phi)
        _warm(ctx, ctx.tangential)
        old.simulate(ow, ctx.rail_kernel, ocm, **dict(kw, duration=20 * ctx.dt, stop=None, final=0))
        t0 = time.perf_counter()
        a = simulate(w, ctx.rail_kernel, cm, **kw)
        t1 = time.perf_counter()
        b = old.simulate(ow, ctx.rail_kernel, ocm, **kw)
        t2 = time.perf_counter()
        t["new"][0] += t1 - t0
        t["old"][0] += t2 - t1
        ma, mb = a.measures(), b.measures()
        if np.isfinite(ma["L_F2"]) or np.isfinite(mb["L_F2"]):
            worst[0] = max(worst[0], abs(ma["L_F2"] - mb["L_F2"]))
        if np.isfinite(ma["f_dominant"]) and np.isfinite(mb["f_dominant"]):
            worst[1] = max(worst[1], abs(ma["f_dominant"] / mb["f_dominant"] - 1))
        worst[2] += a.stop_reason != b.stop_reason
        if ctx.radiation is not None and ma["L_F2"] >= sim["squeal_level"]:
            n_sq += 1
            F, dt = a.F_final, a.dt_final or a.dt
            t0 = time.perf_counter()
            power_of_forces(ctx.radiation, F[:, 1], F[:, 2], dt)
            t1 = time.perf_counter()
            old_fr.power_of_forces(ctx.radiation, F[:, 1], F[:, 2], dt)
            t2 = time.perf_counter()
            t["new"][1] += t1 - t0
            t["old"][1] += t2 - t1
    load1 = os.getloadavg()[0]
    rows = []
    for label, i in (("time loop (8 s at most, early stop)", 0), (f"sound power ({n_sq} squealing cases)", 1)):
        rows.append(f"| {label} | {t['old'][i]:.2f} s | {t['new'][i]:.2f} s | {t['old'][i] / t['new'][i]:.2f}x |")
    so, sn = sum(t["old"]), sum(t["new"])
    rows.append(f"| both | {so:.2f} s | {sn:.2f} s | **{so / sn:.2f}x** |")
    return f"""## Study cases, previous and current code (issue 15)

`benchmarks/study_cases.py`: {N_CASES} cases drawn at random (seed 0) from the map study's grid at its
three contact positions, each run with the current code and with the previous revision's ({BASELINE}),
alternating, one process, OMP_NUM_THREADS=1; sums over the cases. Load average {load0:.1f} at the start,
{load1:.1f} at the end (2 cores; above 1 other processes shared them).

| part of a case | previous | current | speed-up |
|---|---:|---:|---:|
{chr(10).join(rows)}

Same squeal measures: largest differences {worst[0]:.1e} dB in L_F2 and {worst[1]:.1e} in the dominant
frequency; {worst[2]} cases with another stop reason. What changed: the time loop's point-contact Newton
step (section "Interaction") and the tone fit of the sound power (section "Radiation"); the rest of a
case's cost (the simulation's set-up, the squeal measures) is the same.
"""


if __name__ == "__main__":
    print(run())
