"""CONTACT as the peer (docs/validation/33_contact_peer.md with contact_peer_creep.png and
contact_peer_transient.png): steady creep curves with falling friction, transient rolling with a law and two
patches on one grid against Vollebregt's CONTACT (its printed numbers and inputs:
pipeline/validation/references/contact_peer.py), and the cost of a global curve per law.  A writer, run by
`make validate`; tests/contact/test_falling_friction.py and test_two_patch.py assert its limits."""
import time

import numpy as np

from pipeline.validation.references.contact_peer import (CONTACT_CREEP, CONTACT_TRANSIENT, CONTACT_TWO_PATCH, CREEP,
                                                         GEOMETRIES, LAWS, SETS, TRANSIENT_LAW, creep_curves,
                                                         deviations, hertz_contact, patch_forces, transient_run)
from pipeline.validation.writers import DOCS, pyplot, save_figure, save_fragment
from solvers.contact.friction import rf_curve
from solvers.contact.friction_laws import get_friction_law, preset
from solvers.contact.norm import approach_for_load
from pipeline.validation.references.contact import V as V_RF, hertz_case


def write() -> str:
    plt = pyplot()

    contact = hertz_contact()
    res, rows, times = {}, [], []
    for name in CONTACT_CREEP:
        t0 = time.perf_counter()
        ours = creep_curves(name, contact)
        el = time.perf_counter() - t0
        ref = np.array(CONTACT_CREEP[name])
        force, mz = deviations(ours, ref)
        res[name] = ours
        for s, (label, *_) in enumerate(SETS):
            sl = slice(s * len(CREEP), (s + 1) * len(CREEP))
            mag = np.hypot(ref[sl, 0], ref[sl, 1])
            rows.append(f"| {name} | {label} | {mag.max():.4f} at {CREEP[int(np.argmax(mag))]:g} | {mag[-1]:.4f} | "
                        f"{100 * force[sl].max():.3f} % | {100 * mz[sl].max():.3f} % | "
                        f"{int(np.abs(ours[sl, 3] - ref[sl, 3]).max())} |")
        times.append(f"{name} {el:.1f} s")

    fig, axes = plt.subplots(1, 4, figsize=(15, 3.6), sharey=True)
    for s, (label, ix, iy, _) in enumerate(SETS):
        ax = axes[s]
        sl = slice(s * len(CREEP), (s + 1) * len(CREEP))
        for (name, ours), col in zip(res.items(), ("C0", "C1", "C2", "C3", "C4")):
            ref = np.array(CONTACT_CREEP[name])
            comp = 0 if ix else 1
            sign = -1.0 if ix else 1.0
            ax.semilogx(CREEP, sign * ours[sl, comp], "-", color=col, label=f"TANG, {name}")
            ax.semilogx(CREEP, sign * ref[sl, comp], "o", mfc="none", color=col, label=f"CONTACT, {name}")
        ax.set_title(label)
        ax.set_xlabel("creepage |c| [-]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("F / (f_stat F_N) along the creepage\n(-FX longitudinal, FY lateral)")
    axes[0].legend(fontsize=6)
    fig.tight_layout()
    save_figure(fig, DOCS / "contact_peer_creep.png", dpi=90)

    tr = transient_run(TRANSIENT_LAW, contact)
    tr_c = transient_run(0.33, contact)
    tr_ref = np.array(CONTACT_TRANSIENT)
    tr_dev = np.abs(tr[:, :2] - tr_ref[:, :2]).max(axis=1) / np.hypot(tr_ref[:, 0], tr_ref[:, 1])
    tr_cdev = np.abs(tr_c[:, :2] - tr_ref[:, :2]).max(axis=1) / np.hypot(tr_ref[:, 0], tr_ref[:, 1])
    fig, ax = plt.subplots(figsize=(7, 3.4))
    steps = np.arange(1, len(tr) + 1)
    for comp, sign, col, lab in ((1, 1.0, "C0", "FY"), (0, -1.0, "C3", "-FX")):
        ax.plot(steps, sign * tr[:, comp], "-", color=col, label=f"{lab}, TANG with the law")
        ax.plot(steps, sign * tr_ref[:, comp], "o", mfc="none", color=col, label=f"{lab}, CONTACT")
        ax.plot(steps, sign * tr_c[:, comp], ":", color=col, label=f"{lab}, TANG Coulomb mu = 0.33")
    ax.set_xlabel("time step (dx = 0.4 mm)")
    ax.set_ylabel("F / (f_stat F_N)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=6)
    fig.tight_layout()
    save_figure(fig, DOCS / "contact_peer_transient.png", dpi=90)

    patch_rows = []
    for (geometry, F3), (cl, cr, cn, cxi) in CONTACT_TWO_PATCH.items():
        left, right, n, xi = patch_forces(geometry, F3)
        patch_rows.append(f"| {geometry} | {F3 / 1e3:.0f} | {cl:.2f} / {cr:.2f} | {left:.2f} / {right:.2f} | "
                          f"{100 * max(abs(left / cl - 1), abs(right / cr - 1)):.1e} % | {cn} / {n} | "
                          f"{cxi:.4g} / {1e3 * xi:.4g} |")

    # cost of a global curve per law (the thesis' wheel/rail contact, 0.5 mm grid)
    X, Y, h, H = hertz_case(dx=5e-4, dy=5e-4)
    _, ns = approach_for_load(65e3, h, 5e-4, 5e-4)
    rf_curve(ns.p, 5e-4, 5e-4, V_RF, 0.3)
    cost = []
    for label, law in (("coulomb mu = 0.3", 0.3), ("contact_tractcurv (exponential)", preset("contact_tractcurv")),
                       ("polach_dry", preset("polach_dry")), ("hpf (rising, linear)", preset("hpf")),
                       ("exponential 0.2 + 0.15, 100 mm/s", get_friction_law("exponential", fkin=0.2, fexp1=0.15,
                                                                              sabsh1=100.0))):
        t0 = time.perf_counter()
        c = rf_curve(ns.p, 5e-4, 5e-4, V_RF, law)
        el = time.perf_counter() - t0
        k = int(np.argmax(c.mu_rf))
        cost.append(f"| {label} | {len(c.s)} | {c.mu_rf[k]:.4f} at s = {c.s[k]:.3f} m/s | {c.mu_rf[-1]:.4f} | "
                    f"{el:.2f} |")

    geo = "; ".join(f"{g}: lobes at y = {q['yl']:g} / {q['yr']:g} mm, lateral radii {q['rl']:g} / {q['rr']:g} mm, "
                    f"the second {1e3 * q['dz']:g} um lower, RM = {q['rm']:g} mm" for g, q in GEOMETRIES.items())
    laws = "; ".join(f"{n}: " + ", ".join(f"{k.upper()} = {v:g}" for k, v in p.items()) for n, (_, p) in LAWS.items())
    text = f"""## CONTACT as the peer: falling friction and two patches

Written by `pipeline/validation/writers/contact_peer.py` (`make validate`); the tests
`tests/contact/test_falling_friction.py` and `tests/contact/test_two_patch.py` assert its limits (0.5 % for the
creep curves and the transient run, 1 % for the patch forces) against the same CONTACT numbers.  The peer is E.A.H. Vollebregt's open-source CONTACT
(github.com/eve70a/CONTACT, commit d431cdb of 2025-07-23, Revision 2707), compiled with gfortran outside this
repository (its code is not part of the project); its printed results and every input are in
`pipeline/validation/references/contact_peer.py`.

### Creep curves with falling friction (steady rolling, Hertz)

Inputs (CONTACT module 3, T=3, N=1, IPOTCN=-3): semi-axes 8 x 4 mm (curvatures 0.8464e-3 and 2.406e-3 /mm),
FN = 82 kN, G = 82 GPa and nu = 0.28 for both bodies, 44 x 44 elements over 1.1 times the ellipse (dx = 0.4 mm,
dy = 0.2 mm), rolling step DQ = 0.4 mm, VELOC = 30 m/s.  Laws (CONTACT's names, SABSH in mm/s, MEMDST in mm,
MEM_S0 in mm/s): {laws}.  Without a MEMDST the law is instantaneous (MEMDST = 0); the last two sets use CONTACT's
friction memory (MEMDST = 0.003 mm, its tractcurv example's value); slip velocity approximated from below
(INISLP = 1), every case from scratch.  Creepages {", ".join(f"{c:g}" for c in CREEP)}: lateral CETA = -c, longitudinal CKSI = +c,
without spin and with spin CPHI = 6.25e-4 rad/mm.  The project: NORM for FN on the same grid, then steady TANG
with the local coefficient mu(|s|) at each element's slip speed (`solvers.contact.tang.falling`: CONTACT's
slip-velocity iteration, User guide for CONTACT, 'The slip velocity iteration', around Kalker's active-set
Newton method), `tang_steady(..., law, ...)`.

Deviation: per case the largest force component's difference relative to CONTACT's creep force |(FX, FY)|;
Mz relative to the curve's largest |Mz|; adhesion elements: the largest difference in count.

| law | creepage | CONTACT peak F/(fstat FN) | at c = 0.04 | max force deviation | max Mz deviation | adhesion elements |
|---|---|---|---|---|---|---|
{chr(10).join(rows)}

Time for a law's 32 cases (each from scratch, 44 x 44 grid): {", ".join(times)}.

The curves rise to a peak below the static coefficient (the stick zone vanishes while the slipping part of the
patch already has a lower coefficient) and fall with the slip speed along the law; spin shifts the lateral
curve (negative lateral force at small creepage) and adds a lateral force to the longitudinal one.  Agreement
is to CONTACT's printed digits (4): the two codes solve the same discrete problem (piecewise-constant
influence coefficients, rigid slip at x + dx/6, the same fixed point of the slip-velocity iteration).  The
steep law (mu from 0.35 to 0.1, halved every 20 mm/s of slip: its fall lies within the micro-slip range) differs
most, 0.2 % at the smallest creepage with spin, where CONTACT's stop of the slip-velocity iteration (the rms
change of the slip velocity below 0.001 of its rms) is the looser of the two; without the memory this law's
iteration does not converge at small creepage (the coefficient jumps where an element enters the slip area),
the case CONTACT's friction memory is made for.

![creep curves, TANG (lines) and CONTACT (circles)](validation/contact_peer_creep.png)

### Transient rolling with falling friction

CONTACT's transient rolling in contact-fixed coordinates (T=2) on the same contact, grid and L4 law, one case
per time step (DQ = dx = 0.4 mm), the slip velocity of the previous case as the start (INISLP = 0): step 1
from no previous tractions (P=2), steps 1-20 CETA = -0.002, steps 21-40 CKSI = 0.001, CETA = -0.006 and
spin CPHI = 6.25e-4 rad/mm.  The project: `tang_transient(..., law, state=...)` (the bounds iterated per
step, `tang.falling.transient_falling`).  Largest force deviation over the 40 steps {100 * tr_dev.max():.3f} %
(adhesion elements within {int(np.abs(tr[:, 3] - tr_ref[:, 3]).max())}); Coulomb friction at the static
coefficient 0.33 instead of the law misses CONTACT by up to {100 * tr_cdev.max():.1f} %.

![transient rolling, TANG with the law (lines), CONTACT (circles), Coulomb (dotted)](validation/contact_peer_transient.png)

### Two patches on one grid (static normal problem)

Inputs (CONTACT module 3, N=1, IPOTCN=3, IBASE=2): 44 x 64 elements of 0.5 mm centred on the origin,
h = p(y) + x^2/(2 RM) with p(y) = min((y - yl)^2/(2 rl), (y - yr)^2/(2 rr) + dz) given at the element centres;
{geo}; G = 80.77 GPa, nu = 0.3 (E = 210 GPa).  CONTACT's patch forces are its element pressures (the .mat
output, 6 digits) summed over y < 0 and y > 0.  The project: `approach_for_load` (NORM) for the same FN on
the same gap; the two patches interact through the half-space in both (each lobe alone at the same approach
carries more than 1 % more, `test_the_patches_interact`).

| geometry | FN (kN) | CONTACT patches (N) | NORM patches (N) | max deviation | elements CONTACT / NORM | approach (mm) CONTACT / NORM |
|---|---|---|---|---|---|---|
{chr(10).join(patch_rows)}

### Global curves of the laws (rf_curve)

`solvers.contact.friction.rf_curve(p3, dx, dy, v, law_or_mu)` on the thesis' Hertzian wheel/rail contact (R =
0.39 m on a 0.3 m crown, 65 kN, 0.5 mm grid, v = 50 km/h): Coulomb as before (bit for bit); a slip-speed
dependent law with the same bend nodes placed by mu(0) and {12} nodes on the falling branch up to the ramp's end,
no monotone guard.  Time per curve (one run on the shared 2-core machine under load: noisy):

| law | nodes | peak mu_RF | mu_RF at the ramp's end | time (s) |
|---|---|---|---|---|
{chr(10).join(cost)}
"""
    return save_fragment("33_contact_peer.md", text)


if __name__ == "__main__":
    write()
