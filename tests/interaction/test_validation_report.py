"""Validation report of solvers/timeloop/interaction.py: measured numbers and plots for
docs/validation/60_interaction.md and docs/validation/interaction_*.png.

    OMP_NUM_THREADS=1 .venv/bin/python -m tests.interaction.test_validation_report   # ~2 min, one core

Also run by `pytest --validation` (the test below is marked 'validation').  Needs the built
wheel, rail and default contact (build/); the contact of dy_WR = -10 mm and the contacts at
dt/2 (dx = v dt / 2) are built here with the contact stage's own functions (NORM table,
compliance table, the friction curve for mu = 0.35 only).  The fast assertions are the other
tests in tests/interaction/.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from solvers.constants import thesis_contact_point
from solvers.timeloop.interaction import WheelModes, contact_model, refine_table, simulate
from tests.interaction import (CONTACT, DT, GAMMA_Y, PRELOAD, RAIL, V, bv50_kernel, contact_stiffness,
                               decay_rates, default_contact, rail_point_receptance, reduced_squealer,
                               single_mode_growth)

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs" / "validation"
MU = 0.35
# dy_WR (mm) -> (y^W, y^R), SPEC 2: thesis [4.1] field-positive (its printed y^W negated, solvers.constants)
POSITIONS = {dy: thesis_contact_point(1e-3 * dy) for dy in (-15, -10)}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def build_contact(dy_mm: int, dt: float, mu: float = MU):
    """The contact of a nominal position at the grid dx = v dt: the contact stage's computation
    (pipeline/stages.contact.build_contact) for one friction coefficient."""
    from solvers.contact.static import DY, static_contact
    from pipeline.config.case_profiles import case_contact, contact_geometry
    from solvers.contact.compliance import compliance_table
    from solvers.contact.friction import rf_curve
    from solvers.contact.norm import norm_table

    c, pw, pr, _ = case_contact("default")
    c["contact"]["dy_wr"] = dy_mm * 1e-3
    geo = contact_geometry("default", c, pw, pr)  # the contact point of the profiles, as the contact stage's
    E, nu = pw["material"]["E"], pw["material"]["nu"]
    dx = V * dt
    x, y, gap, _, _, xi_s, static = static_contact(geo, E, nu, PRELOAD, dx)
    nodes = np.linspace(0.0, 2.0 * xi_s, 41)
    t = norm_table(gap, nodes, dx, DY, E, nu)
    A1, A2 = compliance_table(nodes, t.p, dx, DY, E, nu)
    rf = rf_curve(static.p, dx, DY, V, mu, E, nu)
    arrays = dict(xi3_nodes=nodes, q_nodes=t.q, F3_nodes=t.F3, pressure_nodes=t.p, A1_nodes=A1, A2_nodes=A2,
                  mu_values=np.array([mu]), rf_n=np.array([len(rf.s)]), rf_s=rf.s[None], rf_mu=rf.mu_rf[None],
                  rf_slope=rf.slope[None], gap=gap, dx=dx, dy=DY)
    return contact_model(arrays, mu), {"grid": gap.shape, "xi3_static": xi_s, "elements": int((static.p > 0).sum())}


def wheel_at(y_w: float) -> tuple[WheelModes, dict]:
    from tests.greens import wheel_case

    w = wheel_case(y_w)
    return WheelModes(w["f_hz"], w["modal_mass"], w["zeta"], w["phi"]), w


# ------------------------------------------------------------------------------------------ sections

def ramp_section() -> str:
    from solvers.contact.compliance import table_compliance
    from solvers.contact.friction import mu_rf

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
    plt = _plt()
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
    fig.savefig(DOCS / "interaction_ramp.png", dpi=90)
    plt.close(fig)
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


def run_case(wheel, g, c, dt, **kw):
    t0 = time.perf_counter()
    r = simulate(wheel, g, c, dt=dt, v=V, gamma_y=kw.pop("gamma_y", GAMMA_Y), **kw)
    return r, time.perf_counter() - t0


def default_section(cache: dict) -> str:
    """The default case (SPEC 6) at dt, dt/2 and dt/4: squeal, its convergence in dt, and the linear
    growth rates of the (n,0,a) modes against those measured in the time loop.  Stores the measures
    in cache['default'] for the assertions of the test."""
    wheel, wc = wheel_at(POSITIONS[-15][0])
    an = [i for i in range(len(wheel.f_r)) if wc["cls"][i] == "a" and wc["m"][i] == 0 and wc["n"][i] >= 0]
    rows, runs, growth = [], {}, {}
    contact_dt2 = None
    for dt in (DT, DT / 2, DT / 4):
        if dt == DT:
            c = default_contact(MU)
        elif dt == DT / 2:
            c = contact_dt2 = build_contact(-15, dt)[0]
        else:                    # the contact of dt/2 (dx/2): its grid is not what converges here
            c = contact_dt2
        g = bv50_kernel(dt, V, y_rail=0.012)
        cache[("rail", 0.012, dt)] = g
        for start in ("steady", "static"):
            r, wall = run_case(wheel, g, c, dt, duration=8.0, start=start)
            m = r.measures()
            runs[dt if start == "steady" else ("static", dt)] = (r, m, None)
            rows.append(f"| {1e6 * dt:.0f} | {c.dx * 1e3:.3f} | {g.shape[0]} | {start} | {r.stop_reason} at "
                        f"{r.duration:.2f} s | {m['L_F2']:.2f} | {m['f_dominant']:.2f} | {m['F2_pp'] / 1e3:.2f} | "
                        f"{100 * m['contact_loss_share']:.1f} % | {wall:.1f} s |")
        if dt > DT / 4:          # growth phase at full rate: complex demodulation near each (n,0,a) mode
            early, _ = run_case(wheel, g, c, dt, duration=0.45, stop=None, final=0.45)
            growth[dt] = decay_rates(early.F_final[:, 1], dt, wheel.f_r[an], t0=0.05, window=0.05)
    greens = ROOT / "build" / "cases" / "default" / "greens.npz"
    if greens.exists():          # the greens stage's kernels (exact wave sum) at dt
        with np.load(greens) as d:
            wg = WheelModes(d["wheel_f"], d["wheel_mass"], d["wheel_zeta"], d["wheel_phi"])
            gs = d["rail_kernel"]
        r, wall = run_case(wg, gs, default_contact(MU), DT, duration=8.0)
        m = r.measures()
        runs["greens"] = (r, m, None)
        rows.append(f"| 36 (greens.npz) | 0.500 | {gs.shape[0]} | steady | {r.stop_reason} at {r.duration:.2f} s | "
                    f"{m['L_F2']:.2f} | {m['f_dominant']:.2f} | {m['F2_pp'] / 1e3:.2f} | "
                    f"{100 * m['contact_loss_share']:.1f} % | {wall:.1f} s |")
    (ra, ma, _), mb = runs[DT], runs[DT / 2][1]
    dL = abs(ma["L_F2"] - mb["L_F2"])
    df = abs(ma["f_dominant"] / mb["f_dominant"] - 1)
    sa, sb, sc = (runs[("static", dt)][1] for dt in (DT, DT / 2, DT / 4))
    sl = np.hypot(*ra.slip_final.T)
    dLs, dfs = abs(sa["L_F2"] - sb["L_F2"]), abs(sa["f_dominant"] / sb["f_dominant"] - 1)

    def label(f):              # the (n,0,a) mode whose eigenfrequency or a harmonic is nearest f
        i, h = min(((i, h) for i in an for h in (1, 2, 3)), key=lambda ih: abs(f / (ih[1] * wheel.f_r[ih[0]]) - 1))
        return f"({wc['n'][i]},0,a)" + ("" if h == 1 else f" (harmonic {h})")

    attractors = "; ".join(f"{1e6 * dt:.0f} us: steady start {label(runs[dt][1]['f_dominant'])}, static start "
                           f"{label(runs[('static', dt)][1]['f_dominant'])}" for dt in (DT, DT / 2, DT / 4))
    # which mode: the (n,0,a) mode whose frequency (or a harmonic of it) is nearest the dominant one
    k_sq, h_sq = min(((i, h) for i in an for h in (1, 2, 3)),
                     key=lambda ih: abs(ma["f_dominant"] / (ih[1] * wheel.f_r[ih[0]]) - 1))
    off = ma["f_dominant"] / (h_sq * wheel.f_r[k_sq]) - 1
    cache["default"] = dict(dL=dL, df=df, dL_static=dLs, df_static=dfs, off=off, L_F2=ma["L_F2"], f=ma["f_dominant"], stop=ra.stop_reason,
                            label=(int(wc["n"][k_sq]), 0, "a"))
    c = default_contact(MU)
    kc = contact_stiffness(c, c.xi3_nodes[np.argmin(np.abs(c.F3_nodes - PRELOAD))])
    lin = single_mode_growth(wheel, rail_point_receptance(0.012), kc, MU, 1.0)
    trows = []
    for k, i in enumerate(an):
        kap = wheel.phi[i, 1] * (wheel.phi[i, 1] + MU * wheel.phi[i, 0])
        trows.append(f"| ({wc['n'][i]},0,a) | {wheel.f_r[i]:.1f} | {wheel.phi[i, 0]:+.3f} | {wheel.phi[i, 1]:+.4f} | "
                     f"{kap:+.1e} | {-wheel.zeta[i] * 2 * np.pi * wheel.f_r[i]:.2f} | {lin[i]:+.2f} | "
                     f"{growth[DT][0][k]:+.2f} | {growth[DT / 2][0][k]:+.2f} |")
    g = cache[("rail", 0.012, DT)]
    extra = []
    for label, kw in (("start 'static' (creep force switched on at t = 0)", dict(start="static")),
                      ("mu = 0.2", dict(mu=0.2)), ("mu = 0.6", dict(mu=0.6)),
                      ("gamma_y = -0.004", dict(gamma_y=-0.004)), ("gamma_y = -0.03", dict(gamma_y=-0.03)),
                      ("printed sign of [4.30] (slip_sign = -1)", dict(slip_sign=-1.0))):
        mu = kw.pop("mu", MU)
        r, _ = run_case(wheel, g, default_contact(mu), DT, duration=8.0, **kw)
        m = r.measures()
        extra.append(f"| {label} | {r.stop_reason} at {r.duration:.2f} s | {m['L_F2']:.1f} | {m['f_dominant']:.0f} | "
                     f"{m['F2_pp'] / 1e3:.1f} | {100 * m['contact_loss_share']:.0f} % |")
    plt = _plt()
    from solvers.spectra import amplitude_spectrum

    fig, ax = plt.subplots(1, 3, figsize=(14, 3.8))
    for dt, ls in ((DT, "-"), (DT / 2, "--"), (DT / 4, ":")):
        r = runs[dt][0]
        ax[0].plot(r.t, r.F[:, 1] / 1e3, ls, lw=0.4, label=f"dt = {1e6 * dt:.0f} us")
        n = int(round(0.005 / dt))
        ax[1].plot(1e3 * (r.t_final[-n:] - r.t_final[-n]), r.F_final[-n:, 1] / 1e3, ls, label=f"dt = {1e6 * dt:.0f} us")
    f, X = amplitude_spectrum(ra.F_final[:, 1], DT)
    ax[2].semilogy(f, np.abs(X), lw=0.7, label="|F2|, dt = 36 us")
    for i in an:
        ax[2].axvline(wheel.f_r[i], color="0.7", lw=0.6)
    ax[2].set_xlim(0, 6500)
    ax[0].set(xlabel="t (s)", ylabel="F2 (kN)", title="growth into the limit cycle")
    ax[1].set(xlabel="t (ms, end of the run)", ylabel="F2 (kN)", title="limit cycle")
    ax[2].set(xlabel="f (Hz)", ylabel="amplitude (N)", title="F2 spectrum; grey: (n,0,a) modes")
    for a in ax:
        a.legend(fontsize=7)
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(DOCS / "interaction_default.png", dpi=90)
    plt.close(fig)
    n_sq = int(wc["n"][k_sq])
    harm = "" if h_sq == 1 else f" (harmonic {h_sq})"
    return f"""### The default case (SPEC 6): C20 at y^W = {1e3 * POSITIONS[-15][0]:+.0f} mm, BV50 at y^R = +12 mm, mu = 0.35, gamma_y = -0.014

50 km/h, 65 kN, the C20 with its {len(wheel.f_r)} modes below 7 kHz (rigid half wheelset on the primary
suspension included, damping [4.11]) at the contact point, the BV50 moving Green's function at the head point
(`tests.interaction.bv50_kernel`: the rail stage's transfer receptances on Kropp's grid), the case's contact;
steady start with the default lateral impulse of 0.01 N s. At dt/2 the wheel filters, the rail kernel (N_t and
the lags doubled) and the contact tables (NORM table, compliance and friction curve on the grid dx = v dt / 2) are
all rebuilt; dt/4 keeps the contact of dt/2. Last row: the greens stage's own kernels (`make greens`).

| dt (us) | dx (mm) | rail lags | start | run (default stop rule) | L_F2 (dB) | dominant f (Hz) | F2 peak-to-peak (kN) | contact loss | wall |
|---:|---:|---:|---|---|---:|---:|---:|---:|---:|
{chr(10).join(rows)}

"steady": the default, steady creep forces plus the 0.01 N s lateral impulse; "static": creep forces switched on
at t = 0 (a large, broadband disturbance).

**The default case squeals at the ({n_sq},0,a) mode**: dominant F2 frequency {ma['f_dominant']:.1f} Hz, the
mode's eigenfrequency{harm} {h_sq * wheel.f_r[k_sq]:.1f} Hz ({100 * off:+.2f} %). **Convergence in dt**: halving dt
changes L_F2 by **{dL:.2f} dB** and the frequency by **{100 * df:.4f} %** (criteria < 1 dB, < 0.5 %).
**Two limit cycles.** (2,0,a) and (3,0,a) grow at nearly the same rate (table below), so which one the
oscillation settles on depends on the disturbance (and, at this margin, on dt): {attractors}. Each limit cycle
converges by itself: (3,0,a) (steady start) {ma['L_F2']:.2f} -> {mb['L_F2']:.2f} dB at 36 -> 18 us; the static-start
runs {sa['L_F2']:.2f} -> {sb['L_F2']:.2f} -> {sc['L_F2']:.2f} dB at 36 / 18 / 9 us (dL = {dLs:.2f} dB, df/f =
{100 * dfs:.3f} % for the halving). Which mode a real wheel squeals at when two are nearly equally unstable is
equally a matter of the disturbance history; the studies report the mode found from the standard start. The amplitude is set by
the friction curve: the lateral vibration velocity at the contact becomes comparable with the creep velocity
|gamma_y| v = {abs(GAMMA_Y) * V:.3f} m/s (slip {sl.min():.3f} .. {sl.max():.3f} m/s over the final stretch), the
contact dips into the rising branch of mu_RF once per period ({100 * np.mean(ra.state_final == 1):.0f} % of the
steps below full slip, F2/F3 down to {(ra.F_final[:, 1] / ra.F_final[:, 2]).min():.3f}), whose positive slope is a
damper that balances the coupling's energy input.

**Why it squeals -- linear growth rates.** In full slip (s = 0.19 m/s, on the plateau of mu_RF) F2 = mu F3
whatever the lateral motion, so the small-amplitude feedback is the geometric coupling: near a lightly damped
wheel mode r the closed loop is m_r (w_r^2 - W^2 + 2 i zeta_r w_r W) + kappa_r k_eff(W) = 0 with
kappa_r = Phi_r3 (Phi_r3 + mu Phi_r2) (the wheel receives -F) and k_eff the dynamic contact stiffness in series
with the rail and the other wheel modes (Im k_eff > 0 from the rail's damping). A mode gains energy if
-mu < Phi_3/Phi_2 < 0 (kappa < 0) and |kappa| Im k_eff > 2 zeta m w_r^2. The C20 section was fitted with that
coupling at -32 mm as a target (geometry/wheels/c20.toml). Single-mode linear estimate (frequency domain,
`tests.interaction.single_mode_growth`, rail point receptance at x = 0) against the rates measured in the
time loop's growth phase (complex demodulation of F2 over 0.05-0.45 s, 50 ms windows), in 1/s:

| mode | f_r (Hz) | Phi_2 | Phi_3 | kappa | structural | linear estimate | time loop, 36 us | time loop, 18 us |
|---|---:|---:|---:|---:|---:|---:|---:|---:|
{chr(10).join(trows)}

The fastest-growing mode of the estimate is the one that squeals; modes with a small positive estimate are
suppressed once the winner saturates the contact. Variants of the default case (dt = 36 us, at most 8 s):

| variant | stop | L_F2 (dB) | f (Hz) | F2 peak-to-peak (kN) | contact loss |
|---|---|---:|---:|---:|---:|
{chr(10).join(extra)}

![default case](validation/interaction_default.png)
"""


def squeal_section(cache: dict) -> str:
    wheel, wc = wheel_at(POSITIONS[-10][0])
    rows, res = [], {}
    for dt in (DT, DT / 2):
        c, info = build_contact(-10, dt)
        g = bv50_kernel(dt, V, y_rail=-0.012)
        r, wall = run_case(wheel, g, c, dt, duration=8.0)
        m = r.measures()
        f0, a0 = _fundamental(r.F_final[:, 1], dt)
        res[dt] = (r, m, f0)
        rows.append(f"| {1e6 * dt:.0f} | {info['grid'][0]} x {info['grid'][1]} | "
                    f"{r.stop_reason} at {r.duration:.2f} s | "
                    f"{m['L_F2']:.2f} | {m['f_dominant']:.2f} | {f0:.2f} | {m['F2_pp'] / 1e3:.1f} | "
                    f"{100 * m['contact_loss_share']:.1f} % | {wall:.1f} s |")
    (_, ma, fa), (_, mb, fb) = res[DT], res[DT / 2]
    # dt/4 (contact of dt/2: the contact tables' grid does not matter here, see the text), and the
    # share of the rail's static compliance that the omitted g(0) carries
    g4 = bv50_kernel(DT / 4, V, y_rail=-0.012)
    r4, wall4 = run_case(wheel, g4, c, DT / 4, duration=8.0)
    m4 = r4.measures()
    f4, _ = _fundamental(r4.F_final[:, 1], DT / 4)
    rows.append(f"| 9 | (that of 18 us) | {r4.stop_reason} at {r4.duration:.2f} s | {m4['L_F2']:.2f} | "
                f"{m4['f_dominant']:.2f} | {f4:.2f} | {m4['F2_pp'] / 1e3:.1f} | "
                f"{100 * m4['contact_loss_share']:.1f} % | {wall4:.1f} s |")
    g0 = {}
    for dt in (DT, DT / 2, DT / 4):
        g = g4 if dt == DT / 4 else bv50_kernel(dt, V, y_rail=-0.012)
        g0[dt] = np.diag(g[0]) / np.diag(g.sum(axis=0))
    # reduced model (the fast test's), the kHz squeal of the (3,0,a) mode
    red_rows, red = [], {}
    for dt in (DT, DT / 2):
        w, g = reduced_squealer(dt)
        r, wall = run_case(w, g, default_contact(MU), dt, duration=4.0)
        m = r.measures()
        red[dt] = (r, m)
        red_rows.append(f"| {1e6 * dt:.0f} | {r.stop_reason} at {r.duration:.2f} s | {m['L_F2']:.2f} | "
                        f"{m['f_dominant']:.2f} | {m['F2_pp'] / 1e3:.2f} | {wall:.2f} s |")
    plt = _plt()
    from solvers.spectra import amplitude_spectrum

    fig, ax = plt.subplots(2, 2, figsize=(11, 6.5))
    for j, (title, data, span) in enumerate((("C20 + BV50, dy_WR = -10 mm", {dt: res[dt][0] for dt in res}, 0.05),
                                             ("reduced model: (2,0,a) + (3,0,a) at y^W = -32 mm, beam rail",
                                              {dt: red[dt][0] for dt in red}, 0.005))):
        for dt, ls in ((DT, "-"), (DT / 2, "--")):
            r = data[dt]
            n = int(round(span / dt))
            ax[0, j].plot(1e3 * (r.t_final[-n:] - r.t_final[-n]), r.F_final[-n:, 1] / 1e3, ls,
                          label=f"F2, dt = {1e6 * dt:.0f} us")
            f, X = amplitude_spectrum(r.F_final[:, 1], dt)
            ax[1, j].semilogy(f, np.abs(X), ls, lw=0.8, label=f"dt = {1e6 * dt:.0f} us")
        ax[0, j].set_title(title, fontsize=9)
        ax[0, j].set_xlabel("t (ms, final stretch)")
        ax[0, j].set_ylabel("F2 (kN)")
        ax[1, j].set_xlim(0, 6000)
        ax[1, j].set_xlabel("f (Hz)")
        ax[1, j].set_ylabel("|F2| amplitude (N)")
        for a in ax[:, j]:
            a.legend(fontsize=7)
            a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(DOCS / "interaction_squeal.png", dpi=90)
    plt.close(fig)
    lin = single_mode_growth(wheel, rail_point_receptance(-0.012),
                             contact_stiffness(default_contact(MU), 9.7e-5), MU, 1.0)
    an = [i for i in range(len(wheel.f_r)) if wc["cls"][i] == "a" and wc["m"][i] == 0 and 2 <= wc["n"][i] <= 4]
    lin_txt = ", ".join(f"({wc['n'][i]},0,a) {lin[i]:+.1f}" for i in an)
    r32_txt = ", ".join(f"{wheel.phi[i, 1] / wheel.phi[i, 0]:+.2f}" for i in an)
    qma, qmb = red[DT][1], red[DT / 2][1]
    dfr = 100 * abs(qma["f_dominant"] / qmb["f_dominant"] - 1)
    near = int(np.argmin(np.abs(wheel.f_r / fa - 1)))
    near_lab = f"({wc['n'][near]},{wc['m'][near]},{wc['cls'][near]}) at {wheel.f_r[near]:.1f} Hz"
    return f"""### Squealing cases and convergence in dt

**Real wheel and rail, dy_WR = -10 mm** (C20 at y^W = {1e3 * POSITIONS[-10][0]:+.0f} mm with all {len(wheel.f_r)} modes, BV50 at
y^R = -12 mm, the contact of that position built at each dx, mu = 0.35, gamma_y = -0.014, 65 kN, 50 km/h):
Phi_3/Phi_2 of the (2..4,0,a) modes = {r32_txt}; single-mode linear estimate {lin_txt} 1/s. Fundamental of the
limit cycle {fa:.2f} Hz; the nearest wheel mode is {near_lab}.

| dt (us) | contact grid | stop | L_F2 (dB) | dominant f (Hz) | fundamental (Hz) | F2 peak-to-peak (kN) | contact loss | wall |
|---:|---|---|---:|---:|---:|---:|---:|---:|
{chr(10).join(rows)}

dL_F2 = **{abs(ma['L_F2'] - mb['L_F2']):.2f} dB**, fundamental frequency changed by
**{100 * abs(fa / fb - 1):.3f} %** (criteria < 1 dB, < 0.5 %); {fa:.2f} -> {fb:.2f} -> {f4:.2f} Hz at 36 / 18 / 9 us.
A first-order term common to all cases is the rule g(0) = 0 of SPEC 3.5 applied to the rail: the omitted first
sample of the rail's moving kernel holds a share of its static compliance proportional to dt (g33[0] / sum g33 =
{100 * g0[DT][1]:.2f} / {100 * g0[DT / 2][1]:.2f} / {100 * g0[DT / 4][1]:.2f} %, g22: {100 * g0[DT][0]:.2f} /
{100 * g0[DT / 2][0]:.2f} / {100 * g0[DT / 4][0]:.2f} % at 36 / 18 / 9 us): the track is slightly stiffer at larger
dt, which matters most for modes of the wheelset on the track (tens of Hz), little for the kHz wheel modes.

**Reduced squealing model** (the fast test's: the C20's (2,0,a) and (3,0,a) modes with their shapes at
y^W = -32 mm, zeta = 1e-4, the analytic beam rail, the default contact): squeal at {qma['f_dominant']:.1f} Hz.

| dt (us) | stop | L_F2 (dB) | f (Hz) | F2 peak-to-peak (kN) | wall |
|---:|---|---:|---:|---:|---:|
{chr(10).join(red_rows)}

dL_F2 = **{abs(qma['L_F2'] - qmb['L_F2']):.2f} dB**, df/f = **{dfr:.3f} %**
(criteria: < 1 dB, < 0.5 %).

![squeal](validation/interaction_squeal.png)
"""


def _fundamental(F2, dt):
    """Lowest strong spectral peak: the dominant peak below 0.7 x the dominant frequency if it is at
    least 30 % of it, else the dominant one."""
    from solvers.spectra import amplitude_spectrum, dominant_frequency

    f, X = amplitude_spectrum(F2, dt)
    fd, ad = dominant_frequency(f, X, f_min=20.0)
    if fd > 40:
        fl, al = dominant_frequency(f, X, f_min=20.0, f_max=0.7 * fd)
        if al >= 0.3 * ad:
            return fl, al
    return fd, ad


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


def write_report(cache: dict | None = None) -> str:
    DOCS.mkdir(parents=True, exist_ok=True)
    cache = {} if cache is None else cache
    t0 = time.perf_counter()
    parts = [ramp_section(), norm_section(), default_section(cache), squeal_section(cache), kalker_section()]
    head = f"""## Wheel/rail interaction (time stepper)

Generated by `tests/interaction/test_validation_report.py` (`OMP_NUM_THREADS=1 .venv/bin/python -m
tests.interaction.test_validation_report`, also `pytest --validation`; {time.perf_counter() - t0:.0f} s on one core).
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
    (DOCS / "60_interaction.md").write_text(text)
    return text


@pytest.mark.validation
def test_validation_report():
    if not (CONTACT.exists() and RAIL.exists()):
        pytest.skip("needs the built default contact and BV50 rail (make contact rail)")
    cache: dict = {}
    text = write_report(cache)
    assert "### The default case" in text
    d = cache["default"]                     # issue 7: the default case squeals at an (n,0,a) mode ...
    # (its limit cycle within 8 s, issue 7's other statement, is asserted in tests/test_pipeline.py)
    assert d["L_F2"] > 10.0, d
    assert abs(d["off"]) < 0.01, d
    assert d["dL"] < 1.0 and d["df"] < 0.005, d   # ... and converges in dt
    assert d["dL_static"] < 1.0 and d["df_static"] < 0.005, d


if __name__ == "__main__":
    print(write_report())
