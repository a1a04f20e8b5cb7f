"""Steady creep curves with falling friction against CONTACT (Vollebregt's open-source CONTACT,
its printed numbers and every input in tests/contact/contact_peer.py): force vs creepage,
lateral and longitudinal, with and without spin, on a Hertzian contact, for CONTACT's
exponential (L=4), rational (L=3) and linear (L=2) falling laws.  The project's steady TANG
with the local coefficient mu(|s|) (solvers.contact.tang.falling) agrees within 0.5 %.
Transient rolling with the law against CONTACT step by step.  The validation test writes
docs/validation/33_contact_peer.md (with the two-patch
comparison of test_two_patch.py)."""
import time
from pathlib import Path

import numpy as np
import pytest

from tests.contact.contact_peer import (CONTACT_CREEP, CONTACT_TRANSIENT, CONTACT_TWO_PATCH, CREEP, GEOMETRIES, LAWS,
                                        SETS, TRANSIENT_LAW, creep_curves, hertz_contact, patch_forces,
                                        transient_run)

DOCS = Path(__file__).resolve().parents[2] / "docs" / "validation"


@pytest.fixture(scope="module")
def contact():
    return hertz_contact()


def deviations(ours, ref):
    """Per case: the largest force component's deviation relative to the creep force |(FX, FY)|
    (CONTACT's, normalised by fstat FN), and |Mz - Mz_CONTACT| relative to the curve's largest
    |Mz| (the moment passes through zero along the curves)."""
    ref = np.asarray(ref)
    force = np.abs(ours[:, :2] - ref[:, :2]).max(axis=1) / np.hypot(ref[:, 0], ref[:, 1])
    mz_scale = np.repeat([np.abs(ref[k:k + len(CREEP), 2]).max() for k in range(0, len(ref), len(CREEP))],
                         len(CREEP))
    mz = np.abs(ours[:, 2] - ref[:, 2]) / np.maximum(mz_scale, 1.0)
    return force, mz


@pytest.mark.parametrize("name", list(CONTACT_CREEP))
def test_creep_curves_match_contact(contact, name):
    ours = creep_curves(name, contact)
    ref = np.array(CONTACT_CREEP[name])
    force, mz = deviations(ours, ref)
    assert force.max() < 5e-3                       # done-when: within 0.5 %
    assert force.max() < 2.5e-3                     # as measured: <= 0.04 %, 0.2 % for the steep law
    assert mz[np.abs(ref[:, 2]) > 0].max() < 5e-3
    assert np.abs(ours[:, 3] - ref[:, 3]).max() <= 2     # adhesion elements
    # the curves fall: beyond the peak the force decreases with creepage (all laws, all sets)
    for k in range(0, len(ref), len(CREEP)):
        mag = np.hypot(ours[k:k + len(CREEP), 0], ours[k:k + len(CREEP), 1])
        assert mag[-1] < 0.85 * mag.max()


def test_transient_rolling_matches_contact(contact):
    # transient TANG with the law, step by step, against CONTACT's transient run (T=2)
    ours = transient_run(TRANSIENT_LAW, contact)
    ref = np.array(CONTACT_TRANSIENT)
    force = np.abs(ours[:, :2] - ref[:, :2]).max(axis=1) / np.hypot(ref[:, 0], ref[:, 1])
    assert force.max() < 5e-3 and force.max() < 1e-3
    assert np.abs(ours[:, 3] - ref[:, 3]).max() <= 2
    assert np.abs(ours[:, 2] - ref[:, 2]).max() < 5e-3 * np.abs(ref[:, 2]).max()
    # the law matters here: Coulomb friction at the static coefficient misses CONTACT by more
    coulomb = transient_run(0.33, contact)
    assert np.abs(coulomb[:, :2] - ref[:, :2]).max(axis=1).max() / np.hypot(*ref[-1, :2]) > 0.01


@pytest.mark.validation
def test_contact_peer_report(contact):
    """Creep curves and the two-patch problem against CONTACT, with a plot:
    docs/validation/33_contact_peer.md."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pipeline.store.atomic import save_text
    from solvers.contact.friction import rf_curve
    from solvers.contact.friction_laws import get_friction_law, preset
    from solvers.contact.norm import approach_for_load
    from tests.contact.cases import V as V_RF, hertz_case

    res, rows, times = {}, [], []
    for name in CONTACT_CREEP:
        t0 = time.perf_counter()
        ours = creep_curves(name, contact)
        el = time.perf_counter() - t0
        ref = np.array(CONTACT_CREEP[name])
        force, mz = deviations(ours, ref)
        assert force.max() < 5e-3
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
    fig.savefig(DOCS / "contact_peer_creep.png", dpi=90)
    plt.close(fig)

    tr = transient_run(TRANSIENT_LAW, contact)
    tr_c = transient_run(0.33, contact)
    tr_ref = np.array(CONTACT_TRANSIENT)
    tr_dev = np.abs(tr[:, :2] - tr_ref[:, :2]).max(axis=1) / np.hypot(tr_ref[:, 0], tr_ref[:, 1])
    tr_cdev = np.abs(tr_c[:, :2] - tr_ref[:, :2]).max(axis=1) / np.hypot(tr_ref[:, 0], tr_ref[:, 1])
    assert tr_dev.max() < 5e-3
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
    fig.savefig(DOCS / "contact_peer_transient.png", dpi=90)
    plt.close(fig)

    patch_rows = []
    for (geometry, F3), (cl, cr, cn, cxi) in CONTACT_TWO_PATCH.items():
        left, right, n, xi = patch_forces(geometry, F3)
        assert abs(left / cl - 1) < 0.01 and abs(right / cr - 1) < 0.01
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

Generated by `tests/contact/test_falling_friction.py::test_contact_peer_report` (`.venv/bin/python -m pytest
tests/contact/test_falling_friction.py --validation`); the fast tests `test_falling_friction.py` and
`test_two_patch.py` assert the same numbers.  The peer is E.A.H. Vollebregt's open-source CONTACT
(github.com/eve70a/CONTACT, commit d431cdb of 2025-07-23, Revision 2707), compiled with gfortran outside this
repository (its code is not part of the project); its printed results and every input are in
`tests/contact/contact_peer.py`.

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
    save_text(text, DOCS / "33_contact_peer.md")
