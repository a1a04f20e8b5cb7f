"""The rail writer's forced-response sections (docs/validation/40_rail.md, assembled by
``pipeline.validation.writers.rail``): receptances, transfer receptances, the analytic beams (``beam_data``,
``beam_ratios``: asserted by tests/rail/test_rail_validation.py), the local compliance, decay rates, mesh
convergence and the 60E1."""
from __future__ import annotations

import numpy as np

from solvers.constants import F_MAX_HZ

from geometry.rail import head_profile
from solvers.rail import response as rr, waveguide as wg

from pipeline.validation.references import beam
from pipeline.validation.references.rail import assembled, beam_params, rail_model
from pipeline.validation.writers import DOCS, pyplot, save_figure

KEYS = ("p", "asm", "mat", "tors", "E", "nu", "rho", "G_s", "model", "zc")   # the BV50 context (``rail.context``)


def db(G):
    return 20 * np.log10(np.abs(G))


def receptances(md: list, c: dict) -> None:
    plt = pyplot()
    p, asm, mat, tors, E, nu, rho, G_s, model, zc = (c[k] for k in KEYS)
    f = np.geomspace(25.0, F_MAX_HZ, 700)
    R = rr.receptances(model, f, [0.0])
    G = R["G"][:, 0]
    fig, axs = plt.subplots(3, 2, figsize=(11, 10), sharex=True)
    names = [("G33 (vertical point)", 1, 1), ("G22 (lateral point)", 0, 0), ("G23 (cross)", 0, 1)]
    for r_, (title, i, j) in enumerate(names):
        for ip, yp in enumerate(R["y"]):
            axs[r_, 0].semilogx(f, db(G[ip, :, i, j]), label=f"y^R = {yp * 1e3:+.0f} mm")
            axs[r_, 1].semilogx(f, np.degrees(np.angle(G[ip, :, i, j])))
        axs[r_, 0].set_ylabel(f"{title}\n|G| (dB re 1 m/N)")
        axs[r_, 1].set_ylabel("phase (deg)")
        axs[r_, 1].set_ylim(-185, 185)
        for a in axs[r_]:
            a.grid(alpha=0.3, which="both")
    axs[0, 0].legend(fontsize=8)
    for a in axs[-1]:
        a.set_xlabel("frequency (Hz)")
        a.set_xlim(25, F_MAX_HZ)
    fig.suptitle("BV50 on a continuous pad: point receptances at the three contact points (structural; "
                 "SPEC directions 2 lateral to the field side, 3 vertical downward)", fontsize=9)
    fig.tight_layout()
    save_figure(fig, DOCS / "rail_receptance.png", dpi=110)
    rows = ["| f (Hz) | " + " | ".join(f"G33 {y * 1e3:+.0f} | G22 {y * 1e3:+.0f} | G23 {y * 1e3:+.0f}" for y in R["y"]) + " |",
            "|---|" + "---|---|---|" * len(R["y"])]
    for fv in (25, 100, 300, 500, 1000, 2000, 4000, 6000):
        i_ = np.argmin(np.abs(f - fv))
        rows.append(f"| {fv} | " + " | ".join(
            f"{db(G[ip, i_, 1, 1]):.1f} | {db(G[ip, i_, 0, 0]):.1f} | {db(G[ip, i_, 0, 1]):.1f}" for ip in range(len(R["y"]))) + " |")
    md += ["### Receptances", "", "![BV50 receptances](validation/rail_receptance.png)", "",
           "Levels in dB re 1 m/N (structural receptance, local compliance excluded, see below):", "", *rows, ""]
    # transfer receptance vs distance
    xs = np.linspace(0.0, 10.0, 401)
    ft = np.array([100.0, 300.0, 1000.0, 3000.0])
    Rt = rr.receptances(model, ft, xs, points=[0.012])
    fig, axs = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for j, fv in enumerate(ft):
        axs[0].plot(xs, db(Rt["G"][0, :, j, 1, 1]), label=f"{fv:.0f} Hz")
        axs[1].plot(xs, db(Rt["G"][0, :, j, 0, 0]), label=f"{fv:.0f} Hz")
    axs[0].set_title("G33(x), vertical, y^R = +12 mm", fontsize=9)
    axs[1].set_title("G22(x), lateral, y^R = +12 mm", fontsize=9)
    for a in axs:
        a.set_xlabel("distance x along the rail (m)")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    axs[0].set_ylabel("|G| (dB re 1 m/N)")
    fig.tight_layout()
    save_figure(fig, DOCS / "rail_transfer.png", dpi=110)
    md += ["Transfer receptances (same point, distance x along the rail; the moving Green's functions of "
           "SPEC 3.4 sample these at x = v t):", "", "![BV50 transfer](validation/rail_transfer.png)", ""]


def beam_data(c: dict) -> dict:
    """The FE point receptances at the head centre, +12 and -16 mm (25 Hz - 2 kHz) beside the analytic beams:
    TBOEF, the lateral-torsional beam's twist, lateral and cross receptances, the FE section mean."""
    p, asm, mat, tors, E, nu, rho, G_s, model, zc = (c[k] for k in KEYS)
    bp = beam_params(model)
    v = bp["vertical"]
    fb = np.geomspace(25.0, 2000.0, 300)
    Rb = rr.receptances(model, fb, [0.0], points=[0.0, 0.012, -0.016])
    Gt = beam.tboef_receptance(fb, [0.0], v["EI"], v["kGA"], v["m"], v["rhoI"], v["k_s"], v["eta_beam"],
                               v["eta_support"])[0]
    tw = {y: beam.lateral_torsion_receptance(fb, [0.0], bp["lateral"], out=("vertical", "vertical"), z_h=0.155,
                                             y_h=y)[0] for y in (0.012, -0.016)}
    zh = {y: float(head_profile(p, y)) for y in (0.0, 0.012, -0.016)}
    Gl = {y: beam.lateral_torsion_receptance(fb, [0.0], bp["lateral"], out=("lateral", "lateral"), z_h=zh[y])[0]
          for y in (0.0, 0.012)}
    G23b = beam.lateral_torsion_receptance(fb, [0.0], bp["lateral"], out=("lateral", "vertical"), z_h=zh[0.012],
                                           y_h=0.012)[0]
    bt = rr.beam_transfer(model, fb, y=0.0)
    return dict(fb=fb, Rb=Rb, Gt=Gt, tw=tw, Gl=Gl, G23b=G23b, bt=bt)


def beam_ratios(d: dict) -> tuple[list, float, float]:
    """(table rows, worst vertical deviation up to 500 Hz (G33 against TBOEF, + twist off the centre), worst
    lateral one (G22 against the lateral-torsional beam))."""
    fb, Rb, Gt, tw, Gl, G23b, bt = (d[k] for k in ("fb", "Rb", "Gt", "tw", "Gl", "G23b", "bt"))
    rows = ["| f (Hz) | G33 y=0 / TBOEF | G33 +12 / (TBOEF+twist) | G33 -16 / (TBOEF+twist) | section mean / TBOEF | "
            "G22 +12 / lat.-tors. beam | abs G23 +12 / beam |", "|---|---|---|---|---|---|---|"]
    worst_v = 0.0
    worst_l = 0.0
    for fv in (25, 50, 100, 200, 300, 400, 500, 700, 1000, 1500, 2000):
        i_ = np.argmin(np.abs(fb - fv))
        r0 = abs(Rb["G"][0, 0, i_, 1, 1]) / abs(Gt[i_])
        r1 = abs(Rb["G"][1, 0, i_, 1, 1]) / abs(Gt[i_] + tw[0.012][i_])
        r2 = abs(Rb["G"][2, 0, i_, 1, 1]) / abs(Gt[i_] + tw[-0.016][i_])
        rm = abs(bt["vertical"][i_]) / abs(Gt[i_])
        rl = abs(Rb["G"][1, 0, i_, 0, 0]) / abs(Gl[0.012][i_])
        rc = abs(Rb["G"][1, 0, i_, 0, 1]) / abs(G23b[i_])
        if fv <= 500:
            worst_v = max(worst_v, abs(r0 - 1), abs(r1 - 1), abs(r2 - 1))
            worst_l = max(worst_l, abs(rl - 1))
        rows.append(f"| {fv} | {r0:.3f} | {r1:.3f} | {r2:.3f} | {rm:.3f} | {rl:.3f} | {rc:.3f} |")
    return rows, worst_v, worst_l


def beams(md: list, c: dict) -> None:
    plt = pyplot()
    d = beam_data(c)
    fb, Rb, Gt, tw, Gl, G23b, bt = (d[k] for k in ("fb", "Rb", "Gt", "tw", "Gl", "G23b", "bt"))
    fig, axs = plt.subplots(2, 2, figsize=(11, 7), sharex=True, gridspec_kw={"height_ratios": [3, 1.3]})
    axs[0, 0].semilogx(fb, db(Rb["G"][0, 0, :, 1, 1]), label="FE G33, y = 0")
    axs[0, 0].semilogx(fb, db(Rb["G"][1, 0, :, 1, 1]), label="FE G33, y = +12 mm")
    axs[0, 0].semilogx(fb, db(Gt), "k--", label="Timoshenko beam on Winkler foundation")
    axs[0, 0].semilogx(fb, db(Gt + tw[0.012]), "k:", label="  + twist (lateral-torsional beam), y = +12 mm")
    axs[1, 0].semilogx(fb, np.abs(Rb["G"][0, 0, :, 1, 1]) / np.abs(Gt), label="y = 0 / TBOEF")
    axs[1, 0].semilogx(fb, np.abs(Rb["G"][1, 0, :, 1, 1]) / np.abs(Gt + tw[0.012]), label="y = +12 / (TBOEF + twist)")
    axs[1, 0].semilogx(fb, np.abs(bt["vertical"]) / np.abs(Gt), label="section mean / TBOEF")
    axs[0, 1].semilogx(fb, db(Rb["G"][1, 0, :, 0, 0]), label="FE G22, y = +12 mm")
    axs[0, 1].semilogx(fb, db(Gl[0.012]), "k--", label="lateral-torsional beam on pad springs")
    axs[0, 1].semilogx(fb, db(Rb["G"][1, 0, :, 0, 1]), label="FE G23, y = +12 mm")
    axs[0, 1].semilogx(fb, db(G23b), "k:", label="beam G23")
    axs[1, 1].semilogx(fb, np.abs(Rb["G"][1, 0, :, 0, 0]) / np.abs(Gl[0.012]), label="G22 FE / beam")
    axs[1, 1].semilogx(fb, np.abs(Rb["G"][1, 0, :, 0, 1]) / np.abs(G23b), label="|G23| FE / beam")
    for a in axs[0]:
        a.set_ylabel("|G| (dB re 1 m/N)")
        a.legend(fontsize=7)
        a.grid(alpha=0.3, which="both")
    for a in axs[1]:
        a.set_ylabel("ratio")
        a.set_ylim(0.5, 1.5)
        a.axhspan(0.9, 1.1, color="0.9")
        a.legend(fontsize=7)
        a.grid(alpha=0.3, which="both")
        a.set_xlabel("frequency (Hz)")
    fig.tight_layout()
    save_figure(fig, DOCS / "rail_beam_comparison.png", dpi=110)
    rows, worst_v, worst_l = beam_ratios(d)
    md += ["### Against analytic beams", "",
           "References (`pipeline/validation/references/beam.py`, exact residue sums, independent of the FE code): vertical "
           "Timoshenko beam on a Winkler foundation with EI, A, rho I of the mesh, kappa = 0.4 (the usual "
           "rail value; the free-rail FE dispersion agrees with it to 0.6 % up to k = 3 rad/m), "
           "k_s = k_pad (1 + i eta_pad), EI (1 + i eta_steel). Off the centre line a vertical load also twists "
           "the rail, so there the reference adds y^2 times the twist receptance of the lateral-torsional "
           "beam: Euler-Bernoulli lateral bending + Vlasov torsion (GJ, E Gamma from the FE warping "
           "function, shear centre and centroid heights, polar inertia about the centroid) on the pad's "
           "lateral and rocking stiffness (rigid-foot values of the calibrated pad layer, table above), "
           "load at the head point.", "",
           "![beam comparison](validation/rail_beam_comparison.png)", "", *rows, "",
           f"Up to 500 Hz: vertical within {100 * worst_v:.1f} % (test: 10 %), lateral within "
           f"{100 * worst_l:.1f} % (test: 15 %). The section-mean vertical displacement follows the TBOEF to "
           "~2 % over the whole range up to 2 kHz; at the head the FE point receptance is a little larger at "
           "low frequency (foot bending on the pad and web compression make the support under the web softer "
           "than the rigid-foot pad stiffness). Laterally the FE is up to ~10 % softer below 100 Hz (web "
           "bending and foot deformation under the lateral head load, absent from a rigid-section beam) and "
           "the beam misses the lateral web-bending wave (cut-on 1.4 kHz), so the models part above ~700 Hz; "
           "G23 agrees within ~15 % up to 300 Hz and then depends on the same cross-section deformation.", ""]


def local(md: list, c: dict) -> None:
    p, asm, mat, tors, E, nu, rho, G_s, model, zc = (c[k] for k in KEYS)
    locf = rr.local_compliance(model)
    rows = ["| head point |y^R| | family | C_yy (m/N) | C_zz (m/N) | C_yz (m/N) |", "|---|---|---|---|---|"]
    for (fname, yy), C in sorted(locf.items(), key=lambda t: (t[0][1], t[0][0])):
        rows.append(f"| {yy * 1e3:.0f} mm | {fname} | {C[0, 0].real:.2e} | {C[1, 1].real:.2e} | {C[0, 1].real:.2e} |")
    fsens = np.array([25.0, 300.0, 1000.0, 4000.0])
    sens = ["| k_local (rad/m) | " + " | ".join(f"G33 {fv:.0f} Hz | G22 {fv:.0f} Hz | G23 {fv:.0f} Hz" for fv in fsens) + " |",
            "|---|" + "---|---|---|" * len(fsens)]
    for kl in (20.0, 50.0, 100.0):
        Gs = rr.receptances(model, fsens, [0.0], points=[0.012], k_local=kl)["G"][0, 0]
        sens.append(f"| {kl:g} | " + " | ".join(f"{db(Gs[j, 1, 1]):.2f} | {db(Gs[j, 0, 0]):.2f} | {db(Gs[j, 0, 1]):.2f}"
                                                 for j in range(len(fsens))) + " |")
    Gk = np.array([rr.receptances(model, fsens, [0.0], points=[0.012], k_local=kl)["G"][0, 0]
                   for kl in (20.0, 50.0, 100.0)])
    dd = np.abs(np.diff(db(Gk), axis=0))
    dmax_main = max(dd[..., 0, 0].max(), dd[..., 1, 1].max(), np.abs(db(Gk[0]) - db(Gk[2]))[:, [0, 1], [0, 1]].max())
    dmax_23 = np.ptp(db(Gk[..., 0, 1]), axis=0).max()
    Gfe = rr.receptances(model, fsens, [0.0], points=[0.012], local="fe", local_C=locf)["G"][0, 0]
    d_fe33 = db(Gfe[0, 1, 1]) - db(Gk[0, 0, 1, 1])
    d_fe22 = db(Gfe[0, 0, 0]) - db(Gk[0, 0, 0, 0])
    sens.append("| FE nodal ('fe') | " + " | ".join(f"{db(Gfe[j, 1, 1]):.2f} | {db(Gfe[j, 0, 0]):.2f} | {db(Gfe[j, 0, 1]):.2f}"
                                                      for j in range(len(fsens))) + " |")
    sw = rr.static_wavenumbers(model)
    md += ["### Local compliance of the loaded zone", "",
           "A point load on a continuum has an infinite local compliance; on the mesh it is finite but "
           "depends on the element size at the load node. In the wave sum it is the static near field of "
           "the load: waves that at w = 0 decay within a few cm (|k| >= 25 rad/m here; the beam waves of the "
           "supported rail have |k| < 3 rad/m, the warping-torsion ones 6-15 rad/m). It is real (times "
           "1 + i eta_steel), frequency independent (test: to 2 % between 100 Hz and 3 kHz) and belongs to the "
           "contact model (half-space influence coefficients; SPEC 3.5 sets g(0) = 0, the contact compliance "
           "takes its place). `receptances(..., local='exclude')` (default) therefore subtracts the static "
           "near field of all waves with |k| > k_local = 20 rad/m; `local='fe'` gives the FE nodal point "
           "receptance of this mesh instead (`local_compliance(model)`: the high-k rest, integrated "
           f"numerically). Static wavenumbers |k| (rad/m) at w = 0: sym {np.round(sw['sym'][:6], 1).tolist()}, "
           f"anti {np.round(sw['anti'][:7], 1).tolist()}.", "",
           "Part of the FE nodal point compliance that the reduced model does not contain "
           "(`local_compliance`, per unit load on the half model; the full-section value is the mean of the "
           "two families):", "", *rows, "",
           "Sensitivity at y^R = +12 mm (dB re 1 m/N) to the cut k_local, and the FE nodal value:", "", *sens, "",
           f"G33 and G22 change by at most {dmax_main:.2f} dB for k_local = 20 ... 100 rad/m; the cross "
           f"receptance G23 is small near 1 kHz and moves there by up to {dmax_23:.1f} dB -- the split between "
           "'local' and 'structural' is not sharper than that. The FE nodal point receptance of this mesh "
           f"('fe') is {d_fe33:.1f} dB above the structural G33 at 25 Hz ({d_fe22:.1f} dB for G22) and flattens "
           "out above 1 kHz, where the mesh-dependent local compliance dominates it.", ""]


def decay(md: list, c: dict) -> None:
    plt = pyplot()
    p, asm, mat, tors, E, nu, rho, G_s, model, zc = (c[k] for k in KEYS)
    fd = np.geomspace(25.0, F_MAX_HZ, 200)
    D = rr.decay_rates(model, fd)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.loglog(fd, D["vertical"], label="vertical (G33 at the head centre)")
    ax.loglog(fd, D["lateral"], label="lateral (G22 at the head centre)")
    ax.loglog(fd, D["min_wave_sym"], ":", color="C0", lw=1, label="least-attenuated wave, sym family")
    ax.loglog(fd, D["min_wave_anti"], ":", color="C1", lw=1, label="least-attenuated wave, anti family")
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("decay rate (dB/m)")
    ax.set_xlim(25, F_MAX_HZ)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title("BV50 track decay rates, DR = 4.343 |G(0)|^2 / int_0^inf |G(x)|^2 dx (exact from the waves)",
                 fontsize=9)
    fig.tight_layout()
    save_figure(fig, DOCS / "rail_decay.png", dpi=110)
    rows = ["| 1/3-octave centre (Hz) | vertical (dB/m) | lateral (dB/m) |", "|---|---|---|"]
    for fc in (31.5, 63, 125, 250, 400, 500, 630, 1000, 1600, 2000, 3150, 4000, 5000, 6300):
        i_ = np.argmin(np.abs(fd - fc))
        rows.append(f"| {fc:g} | {D['vertical'][i_]:.2f} | {D['lateral'][i_]:.2f} |")
    md += ["### Decay rates", "",
           "The EN 15461 track decay rate, computed exactly from the wave sum (the integral of |G(x)|^2 over "
           "x > 0 is a double sum over the waves). As expected for a rail on a pad: high (~13 dB/m vertical, "
           "~7 dB/m lateral) below the rail-on-pad cut-on frequencies, where no wave propagates, falling to "
           "~0.7-1 dB/m above them (bending waves damped by eta_steel = 0.02 and the pad); the lateral decay "
           "rises again above the web-bending cut-on (1.4 kHz), the vertical one near the foot-flapping "
           "cut-on (5.5 kHz), where a slowly propagating wave appears.", "",
           "![BV50 decay rates](validation/rail_decay.png)", "", *rows, ""]


def convergence(md: list) -> None:
    rows = ["| mesh size factor | dofs sym/anti | J (cm^4) | web-bending cut-on (Hz) | foot-flapping cut-on (Hz) | "
            "G33 +12, 300 Hz (dB) | G22 +12, 1 kHz (dB) | G23 +12, 2 kHz (dB) |", "|---|---|---|---|---|---|---|---|"]
    for scale in (1.5, 1.0, 0.7):
        pm, meshm, ctm, ftm, asmm, matm, torm = assembled("bv50", scale)
        mm = rail_model("bv50", scale)
        cut = {}
        for name in ("sym", "anti"):
            fam = wg.family(asmm, matm, name, supported=True)
            f_, phi_ = wg.eig_real_k(fam, 0.0, F_MAX_HZ)
            lab_, _ = wg.classify(fam, phi_, pm, torm["z_centroid"], 0.0)
            for ff, ll in zip(f_, lab_):
                cut.setdefault((name, ll), ff)
        Gm = rr.receptances(mm, np.array([300.0, 1000.0, 2000.0]), [0.0], points=[0.012])["G"][0, 0]
        rows.append(f"| {scale} | {mm.families['sym'].M.shape[0]}/{mm.families['anti'].M.shape[0]} | "
                    f"{torm['J'] * 1e8:.2f} | {cut.get(('anti', 'web'), np.nan):.0f} | "
                    f"{cut.get(('sym', 'foot flapping'), np.nan):.0f} | {db(Gm[0, 1, 1]):.2f} | "
                    f"{db(Gm[1, 0, 0]):.2f} | {db(Gm[2, 0, 1]):.2f} |")
    md += ["### Mesh convergence (P2)", "", "Element sizes scaled from the parameter file's (3.5 mm head, 5 mm web "
           "and foot):", "", *rows, ""]


def second_rail(md: list) -> None:
    m60 = rail_model("60e1")
    bp60 = beam_params(m60)
    v6 = bp60["vertical"]
    f6 = np.array([50.0, 100.0, 300.0, 500.0])
    G6 = rr.receptances(m60, f6, [0.0], points=[0.0])["G"][0, 0, :, 1, 1]
    Gt6 = beam.tboef_receptance(f6, [0.0], v6["EI"], v6["kGA"], v6["m"], v6["rhoI"], v6["k_s"], v6["eta_beam"],
                                v6["eta_support"])[0]
    D6 = rr.decay_rates(m60, np.array([100.0, 1000.0, 2000.0]))
    md += ["### Second rail: 60E1", "",
           "Same pad (200 MN/m^2, eta 0.25). Vertical point receptance at the head centre / TBOEF at "
           + ", ".join(f"{fv:.0f} Hz: {abs(a) / abs(b):.3f}" for fv, a, b in zip(f6, G6, Gt6))
           + f"; vertical decay rate {D6['vertical'][0]:.1f} dB/m at 100 Hz, {D6['vertical'][1]:.2f} at 1 kHz, "
           f"{D6['vertical'][2]:.2f} at 2 kHz.", ""]


def sections(md: list, c: dict) -> None:
    receptances(md, c)
    beams(md, c)
    local(md, c)
    decay(md, c)
    convergence(md)
    second_rail(md)
