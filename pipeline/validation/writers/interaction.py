"""Validation of solvers/timeloop/interaction.py: measured numbers and plots for
docs/validation/60_interaction.md and docs/validation/interaction_*.png (the ramp, NORM and Kalker's loop
here; the default case and the -10 mm squeal in ``interaction_cases``).

    OMP_NUM_THREADS=1 .venv/bin/python -m pipeline.validation.writers.interaction   # minutes, one core

A writer, run by `make validate` (the BV50 rail and the default contact built through Make); the contact of
dy_WR = -10 mm and the contacts at dt/2 (dx = v dt / 2) are built with the contact stage's own functions
(NORM table, compliance table, the friction curve).  Its criteria are asserted by
tests/interaction/test_interaction_validation.py (the default case's squeal and its convergence in dt) and
the other tests in tests/interaction/.
"""
from __future__ import annotations

import time

import numpy as np

from solvers.timeloop.interaction import refine_table, simulate

from pipeline.validation.make import make_targets
from pipeline.validation.references.interaction import DT, GAMMA_Y, PRELOAD, V, default_contact, reduced_squealer
from pipeline.validation.writers import DOCS, pyplot, save_figure, save_fragment
from pipeline.validation.writers.interaction_cases import MU, default_section, squeal_section
from solvers.contact.compliance import table_compliance
from solvers.contact.friction import mu_rf


def ramp_section() -> str:
    c = default_contact(MU)
    out = {}
    for T in (2.0, 8.0):
        n = int(round(T / DT))
        gy = -0.05 * np.arange(n) / n
        r = simulate(None, None, c, dt=DT, v=V, gamma_y=gy, duration=T, stop=None, final=0)
        s_own = np.hypot(*r.slip.T)
        w = np.abs(gy) * V
        ratio = r.F[:, 1] / r.F[:, 2]
        own = np.array([mu_rf(s, c.s_nodes, c.mu_nodes, c.slopes) for s in s_own])
        rig = np.array([mu_rf(s, c.s_nodes, c.mu_nodes, c.slopes) for s in w])
        out[T] = dict(own=np.abs(ratio - own).max(), rigid=np.abs(ratio - rig).max(), w=w, ratio=ratio, s=s_own)
    A2 = table_compliance(r.xi3_static, c.xi3_nodes, c.A2_nodes)
    plt = pyplot()
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
    ss = np.linspace(0, 0.3, 1000)
    ax[0].plot(ss, [mu_rf(s, c.s_nodes, c.mu_nodes, c.slopes) for s in ss], "k", lw=2.5, label="mu_RF (given)")
    o = out[2.0]
    ax[0].plot(o["s"][::50], o["ratio"][::50], "C1.", ms=3, label="F2/F3 vs slip s of the run")
    ax[0].plot(o["w"][::50], o["ratio"][::50], "C0-", lw=1, label="F2/F3 vs rigid slip |gamma_y| v")
    ax[0].set_xlim(0, 0.3)
    ax[0].set_xlabel("slip velocity (m/s)")
    ax[0].set_ylabel("F2 / F3")
    ax[0].legend(fontsize=8)
    ax[0].set_title("ramp gamma_y = -0.05 t / 2 s, no structural dynamics", fontsize=9)
    for T in (2.0, 8.0):
        o = out[T]
        rig = np.array([mu_rf(s, c.s_nodes, c.mu_nodes, c.slopes) for s in o["w"]])
        ax[1].plot(o["w"][::20], (o["ratio"] - rig)[::20], label=f"ramp to -0.05 in {T:.0f} s")
    ax[1].set_xlabel("rigid slip |gamma_y| v (m/s)")
    ax[1].set_ylabel("F2/F3 - mu_RF(|gamma_y| v)")
    ax[1].set_xlim(0, 0.3)
    ax[1].legend(fontsize=8)
    ax[1].set_title("lag of the contact spring, s = w + A2 dF2/dt", fontsize=9)
    for a in ax:
        a.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, DOCS / "interaction_ramp.png", dpi=90)
    return f"""### Friction-curve ramp without structural dynamics (SPEC 4.4, [4.36])

Zero kernels (wheel and rail rigid and fixed), the thesis' ramp gamma_y = -0.05 t / 2 s from the steady state at
gamma_y = 0, default contact, mu = 0.35, 55,556 steps. F2/F3 against the slip velocity s of the run reproduces
mu_RF(s) to **{out[2.0]['own']:.1e}** (rounding: the Newton solve is exact). Against the rigid slip |gamma_y| v
it lags by the tangential contact spring, s2 = w2 + A2 dF2/dt (A2 = {A2:.3g} m/N): at most
**{out[2.0]['rigid']:.2e}** on the steep start of the curve (mu_RF' = 9 per m/s there, dF2/dt = 2e5 N/s);
a four times slower ramp (8 s) stays within **{out[8.0]['rigid']:.1e}** of mu_RF(|gamma_y| v), i.e. within
1e-3. (The friction curve itself is TANG's steady state at the same creepages, contact stage.)

![ramp](validation/interaction_ramp.png)
"""


def norm_section() -> str:
    c = default_contact(MU)
    wheel, g = reduced_squealer(DT)
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=200 * DT, stop=None, kick=(0.07, 0.18))
    a = simulate(wheel, g, c, **kw)
    t0 = time.perf_counter()
    n = simulate(wheel, g, c, normal="norm", **kw)
    t_norm = (time.perf_counter() - t0) / 200
    x0 = a.xi3_static
    app = x0 - a.xi[:, 1]
    fine = refine_table(c, np.linspace(0.97 * x0, 1.03 * x0, 121))
    a2 = simulate(wheel, g, fine, **kw)
    n2 = simulate(wheel, g, fine, normal="norm", **kw)
    e = simulate(wheel, g, c, compliance="exact", **kw)
    rel = lambda p, q: float(np.max(np.abs(p.F[:, 2] - q.F[:, 2]) / q.F[:, 2]))   # noqa: E731
    return f"""### NORM per step against the NORM table (SPEC 4.1)

200 steps of the reduced model below after a lateral and a vertical impulse (0.07 and 0.18 N s), so that the
approach varies by {100 * (app.max() - app.min()) / x0:.2f} % of the static approach and F3 by
{100 * (a.F[:, 2].max() - a.F[:, 2].min()) / PRELOAD:.1f} % of the preload. Per-step NORM (the Python reference
loop: `norm()` warm-started from the previous step, {1e3 * t_norm:.2f} ms per step) against the table mode
(numba), max |dF3|/F3 over the run:

| table | nodes | max \\|dF3\\|/F3 |
|---|---:|---:|
| contact stage's table, 0 .. 2 xi3_static | {len(c.xi3_nodes)} | {rel(n, a):.1e} |
| refined over 0.97 .. 1.03 xi3_static (`refine_table`) | {len(fine.xi3_nodes)} | **{rel(n2, a2):.1e}** |

The difference is the table's interpolation error (linear in q = F3^(2/3); the contact stage measures
~5e-5 midway between its nodes near the working point, zero at the nodes, and the static approach is a node);
with a node step of 5e-4 of the static approach it falls below 1e-6 over the visited range (1e-3 left
1.4e-6 at the step where a grid element enters the patch, a kink of F3(xi3)). For long runs the
table is the production path; the per-step NORM path is the reference. The literal compliance
[4.32]-[4.35] per step (previous forces, current pressures, cross influence A12 included,
`compliance='exact'`) instead of the unit-force table changes F2 by at most {np.abs(e.F[:, 1] - a.F[:, 1]).max():.1e} N
and F3 by {np.abs(e.F[:, 2] - a.F[:, 2]).max():.1e} N on this run.
"""


def kalker_section() -> str:
    c = default_contact(MU)
    wheel, g = reduced_squealer(DT)
    n = 500
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=n * DT, stop=None, kick=(0.7, 0.35))
    p = simulate(wheel, g, c, **kw)
    simulate(wheel, g, c, tangential="kalker", **dict(kw, duration=5 * DT))    # compiled before it is timed
    t0 = time.perf_counter()
    k = simulate(wheel, g, c, tangential="kalker", **kw)
    per = (time.perf_counter() - t0) / n
    d2 = np.abs(k.F[:, 1] - p.F[:, 1]).max()
    d3 = np.abs(k.F[:, 2] - p.F[:, 2]).max()
    return f"""### Kalker's transient TANG as the tangential model (SPEC 4.5)

{n} steps ({1e3 * n * DT:.0f} ms) of the reduced model after a 0.7 N s lateral / 0.35 N s vertical impulse, point model
against TANG per step (pressures from the NORM table, the structural lateral velocity added to the rigid slip,
gamma_y,eff = gamma_y + (xi2[n] - xi2[n-1])/dx, the previous step's tractions as the transient state):
max |dF2| = {d2:.1f} N ({100 * d2 / p.F_ref[1]:.2f} % of the steady F2), max |dF3| = {d3:.1f} N; TANG stays in full
slip ({100 * np.mean(k.state == 2):.0f} % of the steps). Cost **{1e3 * per:.2f} ms per step** in the reference loop after
compilation (~{per * 222222 / 60:.0f} min for 8 s of rolling at this cost; a squeal limit cycle, whose stick and slip
areas change every step, costs more: docs/benchmarks.md, "Interaction"); the contact-model validation of SPEC 7
(`make study STUDY=contact`) runs every mode with both models to its limit cycle or decay.
"""


def write() -> str:
    make_targets("rail", "contact", "greens", CASE="default")
    t0 = time.perf_counter()
    parts = [ramp_section(), norm_section(), default_section(), squeal_section(), kalker_section()]
    head = f"""## Wheel/rail interaction (time stepper)

Written by `pipeline/validation/writers/interaction.py` and `interaction_cases.py` (`make validate`;
{time.perf_counter() - t0:.0f} s on one core); the criteria are asserted by `tests/interaction/test_interaction_validation.py`.
Module: `solvers/timeloop/interaction.py` (SPEC 3.5, 4.1-4.4, 6; thesis [4.13]-[4.37]); fast tests in
`tests/interaction/`; timings in docs/benchmarks.md ("Interaction").

**Kinematics (derived, see the module notes).** Forces act on the rail; xi = xi^R - xi^W is the displacement of the
rail relative to the wheel from past force deviations (wheel: recursive modal filters with the minus sign of
[4.13]; rail: moving kernel). The NORM table's approach is xi3_static - xi3 (xi3 > 0: the rail moves away from the
wheel). The slip of the rail relative to the wheel is s2 = (gamma_y + du2/dx + dxi2/dx) v: the structural term
enters with the sign of the contact deformation u2 = A2 F2, because both are displacements of the rail's surface
relative to the wheel's. The thesis prints [4.30] (and SPEC 4.2 repeats) a minus sign; with it the rising
micro-slip branch of mu_RF becomes a negative damper on the lateral wheel/rail motion (friction work
-F2 s2 no longer equals the power taken from the structures), every lightly damped axial mode is unstable at
small creepage (tests/interaction `test_slip_sign_energy_argument`: +-300 1/s for the (3,0,a) mode at gamma_y =
-0.002), and a large disturbance of the default case then grows into a 438 Hz oscillation with ~90 % loss of
contact (below). `slip_sign=-1` keeps the printed form available.
"""
    text = head + "\n" + "\n".join(parts)
    return save_fragment("60_interaction.md", text)


if __name__ == "__main__":
    write()
