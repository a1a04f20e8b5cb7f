"""Validation of the contact sub-package (solvers/contact): measured numbers and plots for
docs/validation/30_contact.md and docs/validation/contact_*.png (the sections of
``contact_sections``, then spin and the dense TANG reference here).

    OMP_NUM_THREADS=1 .venv/bin/python -m pipeline.validation.writers.contact      # ~1 min on one core

A writer, run by `make validate`; the limits it states are asserted by tests/contact/ (test_hertz,
test_norm, test_tang, test_friction, test_compliance) on the same references.
"""
from __future__ import annotations

import time

import numpy as np

from solvers.contact.norm import approach_for_load
from solvers.contact.tang import TOL, tang_steady, tang_transient

from pipeline.validation.references.contact import DX, G, LOAD, V, carter_creepage, grid, hertz_case
from pipeline.validation.references.hertz import curvature_ratio, hertz
from pipeline.validation.references.kalker import creep_coefficient
from pipeline.validation.references.tang_dense import tang_dense
from pipeline.validation.writers import save_fragment
from pipeline.validation.writers.contact_sections import (carter_section, compliance_section,
                                                          full_slip_and_transient_section, linear_section,
                                                          normal_section, rf_section)


def _fastsim_case(m, offset, warm=None):
    """CONTACT's FASTSIM example, case 1, on m x m elements over 1.1 times the ellipse."""
    G28, NU28 = 82e9, 0.28
    E28 = 2 * G28 * (1 + NU28)
    dx, dy = 2 * 1.1 * 8e-3 / m, 2 * 1.1 * 4e-3 / m
    X, Y = grid(m, m, dx, dy)
    _, ns = approach_for_load(82e3, 0.8464 * X**2 + 2.406 * Y**2, dx, dy, E28, NU28)
    sol = tang_steady(ns.p, dx, dy, 30.0, 0.3, gamma_y=-6.25e-4, spin=0.625, E=E28, nu=NU28, w_offset=offset,
                      warm=warm, full_output=False)
    mz = (X * sol.p2 - Y * sol.p1).sum() * dx * dy * 1e3
    return ns, sol, sol.F2 / (0.3 * ns.F3), mz


def spin_section():
    offsets = (0.0, 1.0 / 6.0, 0.5)
    names = {0.0: "0 (element centre)", 1.0 / 6.0: "1/6 (Kalker, CONTACT; default)", 0.5: "1/2 (path midpoint)"}
    same = ["| w evaluated at x_I + f dx, f = | Fy / (mu Fn) | Mz (N mm) | adhesion / slip elements |",
            "|---|---:|---:|---:|", "| CONTACT (fastsim.ref_out, case 1) | -0.6074 | -4.821e+04 | 356 / 920 |"]
    res = {}
    for m in (22, 44, 88, 176):
        warm = None
        for f in offsets:
            ns, sol, fy, mz = _fastsim_case(m, f, warm)
            warm = sol
            res[m, f] = (fy, mz, int(sol.stick.sum()), int(sol.slip.sum()))
    for f in offsets:
        fy, mz, na, nsl = res[44, f]
        same.append(f"| {names[f]} | {fy:.4f} | {mz:.4e} | {na} / {nsl} |")
    ref = ["| elements | contact | " + " | ".join(f"Fy/(mu Fn), f = {n}" for n in ("0", "1/6", "1/2")) + " | "
           + " | ".join(f"Mz (1e4 N mm), f = {n}" for n in ("0", "1/6", "1/2")) + " |",
           "|---:|---:|" + "---:|" * 6]
    for m in (22, 44, 88, 176):
        nc = res[m, 0.0][2] + res[m, 0.0][3]
        ref.append(f"| {m} x {m} | {nc} | " + " | ".join(f"{res[m, f][0]:.4f}" for f in offsets) + " | "
                   + " | ".join(f"{res[m, f][1] / 1e4:.4f}" for f in offsets) + " |")
    lim_fy = {f: 2 * res[176, f][0] - res[88, f][0] for f in offsets}
    lim_mz = {f: 2 * res[176, f][1] - res[88, f][1] for f in offsets}
    ref.append("| limit (Richardson, first order, 88 and 176) | | " + " | ".join(f"{lim_fy[f]:.4f}" for f in offsets)
               + " | " + " | ".join(f"{lim_mz[f] / 1e4:.4f}" for f in offsets) + " |")
    fy_lim = float(np.mean(list(lim_fy.values())))
    mz_lim = float(np.mean(list(lim_mz.values())))
    err = {f: (100 * (res[44, f][0] / fy_lim - 1), 100 * (res[44, f][1] / mz_lim - 1)) for f in offsets}
    return "\n".join(same), "\n".join(ref), fy_lim, mz_lim, err


def agreement_section():
    """The FFT-based solver against the dense reference (the former solver's algorithm)."""
    rows = ["| case | contact elements | max \\|p - p_dense\\| / max \\|p_dense\\| | F rel. diff | stick sets equal | "
            "time FFT / dense (s) |", "|---|---:|---:|---:|---|---:|"]

    def add(name, p3, dx, dy, mu, kw, sol_fn):
        t0 = time.perf_counter()
        sol = sol_fn()
        t1 = time.perf_counter()
        P1, P2, St = tang_dense(p3, dx, dy, V, mu, **kw)
        t2 = time.perf_counter()
        dp = max(np.abs(sol.p1 - P1).max(), np.abs(sol.p2 - P2).max()) / np.hypot(P1, P2).max()
        F = np.hypot(P1.sum(), P2.sum()) * dx * dy
        dF = np.hypot(sol.F1 - P1.sum() * dx * dy, sol.F2 - P2.sum() * dx * dy) / F
        rows.append(f"| {name} | {int((p3 > 0).sum())} | {dp:.1e} | {dF:.1e} | {'yes' if np.array_equal(sol.stick, St) else 'NO'} "
                    f"| {t1 - t0:.3f} / {t2 - t1:.2f} |")

    X, Y, h, H = hertz_case()
    _, ns = approach_for_load(LOAD, h, DX, DX)
    for kw in (dict(gamma_y=-0.001), dict(gamma_y=-0.003), dict(gamma_x=0.001, gamma_y=-0.003),
               dict(gamma_y=-0.01), dict(gamma_y=-0.002, spin=0.3)):
        label = ", ".join(f"{k} = {v:g}" for k, v in kw.items())
        add(f"wheel/rail Hertz, 0.5 mm, mu = 0.3, steady, {label}", ns.p, DX, DX, 0.3, kw,
            lambda: tang_steady(ns.p, DX, DX, V, 0.3, **kw))
    Hc = hertz(1.0, curvature_ratio(10.0), 1e5)
    dx, dy = 2 * Hc.a / 30, 2 * Hc.b / 25
    Xc, Yc = grid(35, 29, dx, dy)
    pc = Hc.pressure(Xc, Yc)
    gx = carter_creepage(0.5, Hc.p0, 0.3, direction=1)
    add("Carter strip a/b = 0.1, c/a = 0.5, steady", pc, dx, dy, 0.3, dict(gamma_x=gx),
        lambda: tang_steady(pc, dx, dy, V, 0.3, gamma_x=gx))
    Hl = hertz(1.0, curvature_ratio(0.5), LOAD)
    dx, dy = 2 * Hl.a / 24, 2 * Hl.b / 24
    Xl, Yl = grid(29, 29, dx, dy)
    pl = Hl.pressure(Xl, Yl)
    add("linear theory b/a = 0.5, 24 elements, gamma_y = 1e-8 (no slip)", pl, dx, dy, 1e6, dict(gamma_y=1e-8),
        lambda: tang_steady(pl, dx, dy, V, 1e6, gamma_y=1e-8))
    # transient: 12 steps from rest under a varying creepage, compared step by step
    st, prev, worst, wF, same = None, None, 0.0, 0.0, True
    t_new = t_old = 0.0
    for k in range(12):
        gy = -0.003 * (1 + 0.5 * np.sin(0.5 * k))
        t0 = time.perf_counter()
        st = tang_transient(ns.p, DX, DX, V, 0.3, gamma_x=0.001, gamma_y=gy, state=st)
        t1 = time.perf_counter()
        P1, P2, St = tang_dense(ns.p, DX, DX, V, 0.3, gamma_x=0.001, gamma_y=gy, steady=False, prev=prev)
        t2 = time.perf_counter()
        t_new, t_old = t_new + t1 - t0, t_old + t2 - t1
        prev = (P1, P2)
        worst = max(worst, max(np.abs(st.p1 - P1).max(), np.abs(st.p2 - P2).max()) / np.hypot(P1, P2).max())
        wF = max(wF, abs(st.F2 - P2.sum() * DX * DX) / abs(P2.sum() * DX * DX))
        same &= bool(np.array_equal(st.stick, St))
    rows.append(f"| wheel/rail Hertz, 0.5 mm, transient, 12 steps from rest, gamma_y = -0.003 (1 + 0.5 sin 0.5 k) | "
                f"{int(ns.contact.sum())} | {worst:.1e} | {wF:.1e} | {'yes' if same else 'NO'} | {t_new:.3f} / {t_old:.2f} |")
    return "\n".join(rows)


def build() -> str:
    t0 = time.perf_counter()
    nrm, lobes, tab = normal_section()
    carter = carter_section()
    lin = linear_section()
    fs, trans = full_slip_and_transient_section()
    rf, c3, ns = rf_section()
    comp = compliance_section()
    spin_same, spin_ref, fy_lim, mz_lim, spin_err = spin_section()
    agree = agreement_section()
    total = time.perf_counter() - t0
    H = hertz_case()[3]
    return f"""## Contact mechanics

Written by `pipeline/validation/writers/contact.py` (`make validate`; {total:.0f} s on one core). The tests in
`tests/contact/` assert its limits on the same references (some on smaller grids). Steel E = 210 GPa, nu = 0.3 (both bodies; combined
wheel + rail half-space compliance), v = 50 km/h, dx = v dt = 0.5 mm (SPEC 6) unless stated. References are
independent of the solver: Hertz theory with the exact elliptic-integral relations (`pipeline/validation/references/hertz.py`),
Carter's 2D rolling solution, Kalker's linear-theory table (`pipeline/validation/references/data/kalker_creep_coefficients.csv`,
interpolated quadratically in 1/C to nu = 0.3), Mindlin's tangential compliance. Sign convention: tractions and
forces act on the rail (SPEC 2), u = u(rail) - u(wheel), s = slip of the rail relative to the wheel, so
F2 = -c^2 G C22 gamma_y and the thesis' ramp gamma_y < 0 gives F2 > 0.

### NORM vs Hertz (SPEC 4.1)

Wheel rolling radius 0.39 m on a rail crown radius 0.3 m, 65 kN (gap h = x^2/(2 * 0.39) + y^2/(2 * 0.3)); grid
1.25 times the Hertz ellipse. Semi-axes and peak from a least-squares fit of p^2 = p0^2 (1 - x^2/a^2 - y^2/b^2) over
the contact elements; p0 column is the largest element pressure. The approach column is
`approach_for_load(65 kN)`; the F3 column is NORM at the Hertz approach.

{nrm}

Pressures are never negative, the deformed distance is zero in the contact set and positive outside (to the
solver tolerance, 1e-9 of the approach), and every solve reported a converged contact set. The element-count area overestimates pi a b (elements cut by the ellipse edge count whole)
by 4 % at 0.5 mm, 1 % at 0.25 mm; the pressure fit is not affected. {lobes}

![NORM vs Hertz and a two-lobed contact](validation/contact_norm.png)

Interpolation of `norm_table` (nodes uniform in xi3, F3 interpolated linearly in F3^(2/3), pressure fields linearly
and rescaled to the interpolated force), checked at the midpoints between nodes against NORM itself:

{tab}

The force is interpolated to better than 0.1 % around the operating point (to 1.5 % in the first interval, where
the contact is a few elements; `tests/contact/test_norm.py` asserts both); the pointwise pressure error comes from edge elements that enter the contact
between two nodes (a direct NORM solve costs ~2 ms, see the benchmarks).

### Steady TANG vs Carter (2D limit)

Hertz pressure on an elongated ellipse a/b = 0.1 (long lateral strip: a rolling cylinder), creepage from Carter's
relation gamma = K mu p0 (1 - c/a), K = 2(1 - nu)/G (plane strain) for longitudinal creepage; traction on the
centre line y = 0 against Carter's q = mu p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - (x - d)^2/c^2)], mu = 0.3.
The lateral rows use the anti-plane analogue (K = 2/G); their extra deviation is the 3D effect, which is larger
for lateral creepage (Kalker's C22 at a/b = 0.1 is 2 % above the strip limit pi^2/4).

{carter}

The slip zone is exact. The remaining deviation is the discretisation: the first-order transport difference
u_I - u_(I+dx) evaluates the kinematics half an element ahead, and the edge elements decide the effective contact
length to a fraction of an element. The two effects partly cancel with an element centre on x = 0 (outermost
contact elements at +-(a - dx)) and add up with an element edge on x = 0. The largest pointwise deviation sits at
the stick/slip boundary, where Carter's traction has a square-root kink, and for the edge-aligned lateral case at
the leading-edge element.

![Carter](validation/contact_carter.png)

### Steady TANG vs Kalker's linear theory

No-slip creep coefficients from F1 = -c^2 G C11 gamma_x, F2 = -c^2 G C22 gamma_y and F2 = -c^3 G C23 spin
(tiny creepage, Hertz pressure on the grid, equal numbers of elements across both semi-axes):

{lin}

The creep stiffness of the contact used for the RF curves (NORM pressure, 0.5 mm grid, {int((ns.p > 0).sum())} contact elements)
is k = {c3.creep_stiffness / 1e6:.3f} MN against c^2 G C22 = {H.c**2 * G * creep_coefficient('C22', H.a, H.b) / 1e6:.3f} MN
({100 * (c3.creep_stiffness / (H.c**2 * G * creep_coefficient('C22', H.a, H.b)) - 1):+.1f} %). C11 and C22 converge
to within a few percent at 24 elements; the spin coefficient converges more slowly (first order: the rigid slip
of spin varies along x, see "Spin" below; with the rigid slip at the element centre instead of x + dx/6 it was
about 4 % further below Kalker's value at 24 elements).

### Spin: where the rigid slip is evaluated

CONTACT's published FASTSIM example, case 1 (Vollebregt's open-source CONTACT, `examples/fastsim.inp`, reference
output `examples/fastsim.ref_out`; the exact theory, NORM + steady TANG): Hertz semi-axes a = 8 mm, b = 4 mm
(curvatures 0.8464 and 2.406 1/m), Fn = 82 kN, G = 82 GPa, nu = 0.28, mu = 0.3, steady rolling with eta = -6.25e-4
and spin 6.25e-4 /mm, 44 x 44 elements over 1.1 times the ellipse (dx = 0.4 mm, dy = 0.2 mm; 1276 contact
elements, as in CONTACT). The only term of the discretisation that differs with spin is the rigid slip w, which
varies along x (w2 = (eta + spin x) v): the transport difference u_I - u_(I+dx) is the deformation a particle
collects on its way from x_I + dx to x_I during the step, and the rigid slip evaluated at x_I + f dx shifts the
spin's contribution by the equivalent of a lateral creepage spin f dx. This code evaluated it at the element
centre (f = 0); Kalker, and CONTACT after him, at x_I + dq/6 ("compensates for the rolling distance traversed in
a time step", CONTACT's user guide, rigid shift in rolling); the midpoint of the particle's path is f = 1/2.
On the same grid:

{spin_same}

With f = 1/6, now the default (`solvers.contact.tang.W_OFFSET`, argument `w_offset`), the code reproduces
CONTACT to the printed digits (the test `test_spin_matches_contact_fastsim_case` asserts 0.5 %). Grid refinement
shows that the three choices are consistent discretisations of the same continuum problem, converging at first
order to one limit:

{spin_ref}

Limit (mean of the three extrapolations): Fy / (mu Fn) = {fy_lim:.4f}, Mz = {mz_lim:.4e} N mm. On the 44 x 44 grid
the errors against it are {spin_err[0.0][0]:+.1f} % / {spin_err[0.0][1]:+.1f} % (Fy / Mz) at f = 0,
{spin_err[1.0 / 6.0][0]:+.1f} % / {spin_err[1.0 / 6.0][1]:+.1f} % at f = 1/6 and {spin_err[0.5][0]:+.1f} % /
{spin_err[0.5][1]:+.1f} % at f = 1/2: the offset removes part of the O(dx) error of the first-order transport
difference, whose centre lies at x_I + dx/2; the midpoint removes more of it for this case. Without spin (w
constant) the offset has no effect, which is why the non-spin results agreed with CONTACT before. The default
follows CONTACT (the independent reference the project validates against); `w_offset=0.5` gives the midpoint.

### TANG: the FFT-based solver against the dense reference

The solver (FFT products, Newton-Krylov, O(n log n) per iteration) against the former solver's algorithm
kept as a test oracle (`pipeline/validation/references/tang_dense.py`: the same equations with the influence matrix of the contact
elements formed and every Newton system factorised densely, O(n^3)), default tolerance {TOL:g} for the FFT solver,
1e-12 for the dense one. The differences are within the FFT solver's tolerance:

{agree}

### Full slip

{fs}

### Transient TANG

{trans}

![transient](validation/contact_transient.png)

### Regularized friction curves mu_RF(s) (SPEC 4.4)

Hertzian contact above (65 kN, NORM pressure at dx = 0.5 mm), v = 50 km/h, steady TANG at 23 creepages per
curve (18 clustered below 1.25 gamma_sat, 5 on the plateau up to the ramp's |gamma_y| = 0.05), each warm-started
from the previous one: the same points the slow ramp gamma_y = -0.05 t / 2 s passes in steady state.

{rf}

All curves rise monotonically from 0 to mu; the transition length grows in proportion to mu (without spin the
problem is self-similar: mu_RF(s; mu) = mu f(s / mu), the tests check it). For mu = 0.3 the last stick element
disappears at |gamma_y| = {c3.gamma[np.argmax(c3.stick_fraction == 0)]:.4f} (thesis: full slip near 0.006).
Between the last stick element and |gamma_y| = 0.05 mu_RF still rises by {(c3.mu_rf[-1] - c3.mu_rf[np.argmax(c3.stick_fraction == 0)]) / c3.mu:.1e} mu
(the slip direction is not exactly lateral everywhere; full slip proper means |F| -> mu F3 as in the table above).

![RF curves](validation/contact_rf_curves.png)

### Tangential contact compliance A_tau (SPEC 4.3)

The thesis' recipe [4.32-4.35] on the wheel/rail Hertzian contact (a = {H.a * 1e3:.3f} mm along x, b =
{H.b * 1e3:.3f} mm), compared with independent estimates (ratio = this code / estimate):

{comp}

For a circle the recipe (ellipsoidal traction, 2/3 of the peak displacement) equals Mindlin's no-slip
compliance exactly, and the code reproduces it within 0.2 % (`tests/contact/test_compliance.py`). The flexibility of Kalker's simplified theory,
fitted to the linear-theory creep forces, is about half as compliant (ratio 1.8-2.1): about the factor of 2 the
SPEC says does not matter (thesis 4.3.3, Fig. 4.10).
"""


def write() -> str:
    return save_fragment("30_contact.md", build())


if __name__ == "__main__":
    write()
