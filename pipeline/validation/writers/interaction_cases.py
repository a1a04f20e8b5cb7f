"""The interaction writer's cases (docs/validation/60_interaction.md, assembled by
``pipeline.validation.writers.interaction``): the default case at dt, dt/2 and dt/4 (``default_runs``,
``convergence``: asserted by tests/interaction/test_interaction_validation.py) with its linear growth rates and
variants, and the squeal at dy_WR = -10 mm."""
from __future__ import annotations

import time

import numpy as np

from solvers.constants import F_MAX_HZ, thesis_contact_point
from solvers.timeloop.interaction import WheelModes, contact_model, simulate

from pipeline.store.paths import ROOT
from pipeline.validation.references.interaction import (DT, GAMMA_Y, PRELOAD, V, bv50_kernel, contact_stiffness,
                                                        decay_rates, default_contact, rail_point_receptance,
                                                        reduced_squealer, single_mode_growth)
from pipeline.validation.writers import DOCS, pyplot, save_figure
from solvers.contact.static import DY, static_contact
from pipeline.config.case_profiles import case_contact, contact_geometry
from solvers.contact.compliance import compliance_table
from solvers.contact.friction import rf_curve
from solvers.contact.norm import norm_table
from pipeline.validation.references.greens import wheel_case
from solvers.spectra import amplitude_spectrum, dominant_frequency

MU = 0.35
# dy_WR (mm) -> (y^W, y^R), SPEC 2: thesis [4.1] field-positive (its printed y^W negated, solvers.constants)
POSITIONS = {dy: thesis_contact_point(1e-3 * dy) for dy in (-15, -10)}


def build_contact(dy_mm: int, dt: float, mu: float = MU):
    """The contact of a nominal position at the grid dx = v dt: the contact stage's computation
    (pipeline/stages.contact.build_contact) for one friction coefficient."""
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
    w = wheel_case(y_w)
    return WheelModes(w["f_hz"], w["modal_mass"], w["zeta"], w["phi"]), w


def run_case(wheel, g, c, dt, **kw):
    t0 = time.perf_counter()
    r = simulate(wheel, g, c, dt=dt, v=V, gamma_y=kw.pop("gamma_y", GAMMA_Y), **kw)
    return r, time.perf_counter() - t0


def default_runs(dts=(DT, DT / 2, DT / 4), growth_phase: bool = True, greens: bool = True) -> dict:
    """The default case (SPEC 6) at each dt of ``dts`` (8 s, steady and static start; dt/4 keeps the contact of
    dt/2), the growth phase of the (n,0,a) modes (``growth_phase``) and the greens stage's own kernels
    (``greens``): dict of the wheel, its (n,0,a) indices, the runs, growth rates, table rows and rail kernels."""
    wheel, wc = wheel_at(POSITIONS[-15][0])
    an = [i for i in range(len(wheel.f_r)) if wc["cls"][i] == "a" and wc["m"][i] == 0 and wc["n"][i] >= 0]
    rows, runs, growth, kernels = [], {}, {}, {}
    contact_dt2 = None
    for dt in dts:
        if dt == DT:
            c = default_contact(MU)
        elif dt == DT / 2:
            c = contact_dt2 = build_contact(-15, dt)[0]
        else:                    # the contact of dt/2 (dx/2): its grid is not what converges here
            c = contact_dt2
        g = bv50_kernel(dt, V, y_rail=0.012)
        kernels[dt] = g
        for start in ("steady", "static"):
            r, wall = run_case(wheel, g, c, dt, duration=8.0, start=start)
            m = r.measures()
            runs[dt if start == "steady" else ("static", dt)] = (r, m, None)
            rows.append(f"| {1e6 * dt:.0f} | {c.dx * 1e3:.3f} | {g.shape[0]} | {start} | {r.stop_reason} at "
                        f"{r.duration:.2f} s | {m['L_F2']:.2f} | {m['f_dominant']:.2f} | {m['F2_pp'] / 1e3:.2f} | "
                        f"{100 * m['contact_loss_share']:.1f} % | {wall:.1f} s |")
        if growth_phase and dt > DT / 4:          # growth phase at full rate: complex demodulation near each (n,0,a) mode
            early, _ = run_case(wheel, g, c, dt, duration=0.45, stop=None, final=0.45)
            growth[dt] = decay_rates(early.F_final[:, 1], dt, wheel.f_r[an], t0=0.05, window=0.05)
    path = ROOT / "build" / "cases" / "default" / "greens.npz"
    if greens and path.exists():          # the greens stage's kernels (exact wave sum) at dt
        with np.load(path) as d:
            wg = WheelModes(d["wheel_f"], d["wheel_mass"], d["wheel_zeta"], d["wheel_phi"])
            gs = d["rail_kernel"]
        r, wall = run_case(wg, gs, default_contact(MU), DT, duration=8.0)
        m = r.measures()
        runs["greens"] = (r, m, None)
        rows.append(f"| 36 (greens.npz) | 0.500 | {gs.shape[0]} | steady | {r.stop_reason} at {r.duration:.2f} s | "
                    f"{m['L_F2']:.2f} | {m['f_dominant']:.2f} | {m['F2_pp'] / 1e3:.2f} | "
                    f"{100 * m['contact_loss_share']:.1f} % | {wall:.1f} s |")
    return dict(wheel=wheel, wc=wc, an=an, rows=rows, runs=runs, growth=growth, kernels=kernels)


def convergence(d: dict) -> dict:
    """Of ``default_runs``: the changes of L_F2 and the frequency when dt is halved (steady and static start),
    the squealing (n,0,a) mode (its eigenfrequency or a harmonic nearest the dominant frequency) and the
    frequency's offset from it."""
    wheel, wc, an, runs = d["wheel"], d["wc"], d["an"], d["runs"]
    (ra, ma, _), mb = runs[DT], runs[DT / 2][1]
    dL = abs(ma["L_F2"] - mb["L_F2"])
    df = abs(ma["f_dominant"] / mb["f_dominant"] - 1)
    sa, sb = (runs[("static", dt)][1] for dt in (DT, DT / 2))
    dLs, dfs = abs(sa["L_F2"] - sb["L_F2"]), abs(sa["f_dominant"] / sb["f_dominant"] - 1)
    k_sq, h_sq = min(((i, h) for i in an for h in (1, 2, 3)),
                     key=lambda ih: abs(ma["f_dominant"] / (ih[1] * wheel.f_r[ih[0]]) - 1))
    off = ma["f_dominant"] / (h_sq * wheel.f_r[k_sq]) - 1
    return dict(dL=dL, df=df, dL_static=dLs, df_static=dfs, off=off, L_F2=ma["L_F2"], f=ma["f_dominant"],
                stop=ra.stop_reason, label=(int(wc["n"][k_sq]), 0, "a"), k_sq=k_sq, h_sq=h_sq)


def default_section() -> str:
    """The default case at dt, dt/2 and dt/4: squeal, its convergence in dt, and the linear growth rates of the
    (n,0,a) modes against those measured in the time loop."""
    d = default_runs()
    cv = convergence(d)
    wheel, wc, an, runs, growth, rows = (d[k] for k in ("wheel", "wc", "an", "runs", "growth", "rows"))
    (ra, ma, _), mb = runs[DT], runs[DT / 2][1]
    dL, df, dLs, dfs, off, k_sq, h_sq = (cv[k] for k in ("dL", "df", "dL_static", "df_static", "off", "k_sq", "h_sq"))
    sa, sb, sc = (runs[("static", dt)][1] for dt in (DT, DT / 2, DT / 4))
    sl = np.hypot(*ra.slip_final.T)

    def label(f):              # the (n,0,a) mode whose eigenfrequency or a harmonic is nearest f
        i, h = min(((i, h) for i in an for h in (1, 2, 3)), key=lambda ih: abs(f / (ih[1] * wheel.f_r[ih[0]]) - 1))
        return f"({wc['n'][i]},0,a)" + ("" if h == 1 else f" (harmonic {h})")

    attractors = "; ".join(f"{1e6 * dt:.0f} us: steady start {label(runs[dt][1]['f_dominant'])}, static start "
                           f"{label(runs[('static', dt)][1]['f_dominant'])}" for dt in (DT, DT / 2, DT / 4))
    c = default_contact(MU)
    kc = contact_stiffness(c, c.xi3_nodes[np.argmin(np.abs(c.F3_nodes - PRELOAD))])
    lin = single_mode_growth(wheel, rail_point_receptance(0.012), kc, MU, 1.0)
    trows = []
    for k, i in enumerate(an):
        kap = wheel.phi[i, 1] * (wheel.phi[i, 1] + MU * wheel.phi[i, 0])
        trows.append(f"| ({wc['n'][i]},0,a) | {wheel.f_r[i]:.1f} | {wheel.phi[i, 0]:+.3f} | {wheel.phi[i, 1]:+.4f} | "
                     f"{kap:+.1e} | {-wheel.zeta[i] * 2 * np.pi * wheel.f_r[i]:.2f} | {lin[i]:+.2f} | "
                     f"{growth[DT][0][k]:+.2f} | {growth[DT / 2][0][k]:+.2f} |")
    g = d["kernels"][DT]
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
    plt = pyplot()

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
    ax[2].set_xlim(0, F_MAX_HZ)
    ax[0].set(xlabel="t (s)", ylabel="F2 (kN)", title="growth into the limit cycle")
    ax[1].set(xlabel="t (ms, end of the run)", ylabel="F2 (kN)", title="limit cycle")
    ax[2].set(xlabel="f (Hz)", ylabel="amplitude (N)", title="F2 spectrum; grey: (n,0,a) modes")
    for a in ax:
        a.legend(fontsize=7)
        a.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, DOCS / "interaction_default.png", dpi=90)
    n_sq = int(wc["n"][k_sq])
    harm = "" if h_sq == 1 else f" (harmonic {h_sq})"
    return f"""### The default case (SPEC 6): C20 at y^W = {1e3 * POSITIONS[-15][0]:+.0f} mm, BV50 at y^R = +12 mm, mu = 0.35, gamma_y = -0.014

50 km/h, 65 kN, the C20 with its {len(wheel.f_r)} modes below 7 kHz (rigid half wheelset on the primary
suspension included, damping [4.11]) at the contact point, the BV50 moving Green's function at the head point
(`references.interaction.bv50_kernel`: the rail stage's transfer receptances on Kropp's grid), the case's contact;
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
`references.interaction.single_mode_growth`, rail point receptance at x = 0) against the rates measured in the
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


def minus_10_runs():
    """dy_WR = -10 mm with the real wheel and rail at dt and dt/2 (the contact built at each dx), 8 s each:
    {dt: (run, measures, the limit cycle's fundamental, contact, contact info, wall s)}."""
    wheel, _ = wheel_at(POSITIONS[-10][0])
    out = {}
    for dt in (DT, DT / 2):
        c, info = build_contact(-10, dt)
        g = bv50_kernel(dt, V, y_rail=-0.012)
        r, wall = run_case(wheel, g, c, dt, duration=8.0)
        out[dt] = (r, r.measures(), _fundamental(r.F_final[:, 1], dt)[0], c, info, wall)
    return out


def squeal_section() -> str:
    wheel, wc = wheel_at(POSITIONS[-10][0])
    rows, res = [], {}
    for dt, (r, m, f0, c, info, wall) in minus_10_runs().items():      # c: dt/2's contact at the end
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
    plt = pyplot()

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
    save_figure(fig, DOCS / "interaction_squeal.png", dpi=90)
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
    f, X = amplitude_spectrum(F2, dt)
    fd, ad = dominant_frequency(f, X, f_min=20.0)
    if fd > 40:
        fl, al = dominant_frequency(f, X, f_min=20.0, f_max=0.7 * fd)
        if al >= 0.3 * ad:
            return fl, al
    return fd, ad
