"""The contact writer's sections on Hertz, Carter, Kalker's linear theory, full slip, transient rolling,
the regularized friction curves and the tangential compliance (``pipeline.validation.writers.contact``
assembles them into docs/validation/30_contact.md); each returns its Markdown rows and draws its plot."""
from __future__ import annotations

import time

import numpy as np

from solvers.contact.compliance import contact_compliance
from solvers.contact.friction import mu_rf, rf_curve
from solvers.contact.norm import approach_for_load, norm, norm_table, table_midpoint_error
from solvers.contact.tang import tang_steady, tang_transient

from pipeline.validation.references.contact import (DX, E, G, LOAD, NU, V, carter_creepage, carter_traction,
                                                    ellipse_fit, grid, hertz_case)
from pipeline.validation.references.hertz import curvature_ratio, ellipsoidal_traction_compliance, hertz
from pipeline.validation.references.kalker import creep_coefficient
from pipeline.validation.writers import DOCS, pyplot, save_figure

MUS = np.round(np.arange(0.1, 0.6001, 0.05), 2)


def normal_section():
    H = hertz_case()[3]
    rows = ["| dx = dy (mm) | grid | contact elements | a (mm) | b (mm) | p0 (GPa) | approach at 65 kN (um) | "
            "F3 at Hertz approach (kN) | active-set its | CG steps |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    rows.append(f"| Hertz | | | {H.a * 1e3:.4f} | {H.b * 1e3:.4f} | {H.p0 / 1e9:.4f} | {H.delta * 1e6:.3f} | 65.000 | | |")
    fields = None
    for d in (1.0e-3, 0.5e-3, 0.35e-3, 0.25e-3):
        X, Y, h, _ = hertz_case(dx=d, dy=d)
        xi3, sol = approach_for_load(LOAD, h, d, d)
        a, b, p0 = ellipse_fit(sol.p, X, Y)
        at = norm(h, H.delta, d, d)
        e = lambda v, r: f"{100 * (v / r - 1):+.2f} %"
        rows.append(f"| {d * 1e3:.2f} | {h.shape[0]} x {h.shape[1]} | {sol.contact.sum()} | {a * 1e3:.4f} ({e(a, H.a)}) | "
                    f"{b * 1e3:.4f} ({e(b, H.b)}) | {sol.p.max() / 1e9:.4f} ({e(sol.p.max(), H.p0)}) | "
                    f"{xi3 * 1e6:.3f} ({e(xi3, H.delta)}) | {at.F3 / 1e3:.3f} ({e(at.F3, LOAD)}) | {at.iterations} | "
                    f"{at.cg_iterations} |")
        if d == DX:
            fields = (X, Y, sol)
    # Hertz profiles plot
    plt = pyplot()
    X, Y, sol = fields
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.6))
    i0, j0 = X.shape[0] // 2, X.shape[1] // 2
    xs = np.linspace(-1.2 * H.a, 1.2 * H.a, 400)
    ys = np.linspace(-1.2 * H.b, 1.2 * H.b, 400)
    ax[0].plot(xs * 1e3, H.pressure(xs, 0) / 1e9, "k-", label="Hertz")
    ax[0].plot(X[:, j0] * 1e3, sol.p[:, j0] / 1e9, "o", ms=4, label="NORM, y = 0")
    ax[0].plot(ys * 1e3, H.pressure(0, ys) / 1e9, "k--", label="Hertz (y)")
    ax[0].plot(Y[i0] * 1e3, sol.p[i0] / 1e9, "s", ms=4, mfc="none", label="NORM, x = 0")
    ax[0].set_xlabel("x or y (mm)")
    ax[0].set_ylabel("p3 (GPa)")
    ax[0].legend(fontsize=8)
    ax[0].set_title("wheel R 0.39 m on crown R 0.3 m, 65 kN, dx = 0.5 mm", fontsize=9)
    # two-lobed non-Hertzian gap
    dx = 0.5e-3
    X2, Y2 = grid(30, 56, dx, dx)
    h2 = X2**2 / (2 * 0.39) + np.minimum((Y2 + 4e-3) ** 2 / (2 * 0.05), (Y2 - 4e-3) ** 2 / (2 * 0.08) + 5e-6)
    xi2, s2 = approach_for_load(LOAD, h2, dx, dx)
    im = ax[1].pcolormesh(Y2 * 1e3, X2 * 1e3, s2.p / 1e9, shading="nearest", cmap="viridis")
    ax[1].set_aspect("equal")
    ax[1].set_xlabel("y (mm)")
    ax[1].set_ylabel("x (mm)")
    ax[1].set_title("two-lobed gap, 65 kN", fontsize=9)
    fig.colorbar(im, ax=ax[1], label="p3 (GPa)")
    fig.tight_layout()
    save_figure(fig, DOCS / "contact_norm.png", dpi=110)
    lobes = (f"Two-lobed gap (lobes 8 mm apart, crown radii 50 and 80 mm, the second 5 um lower), 65 kN: "
             f"{s2.contact.sum()} contact elements in two patches, converged in {s2.iterations} active-set "
             f"iterations; min p = {s2.p.min():.0f} Pa, min d = {s2.d.min():.1e} m, max |p d| / (p_max xi3) = "
             f"{np.abs(s2.p * s2.d).max() / (s2.p.max() * (s2.F3 > 0) * xi2):.1e}; loss of contact (xi3 below first "
             f"contact) returns F3 = 0 exactly.")
    # table interpolation
    X, Y, h, _ = hertz_case(dx=DX, dy=DX, margin=1.6)
    trows = ["| nodes over 0..1.6 approach(65 kN) | max force error (all / xi3 > delta/2) | max pressure error / p0 (xi3 > delta/2) | rms pressure error / p0 (xi3 > delta/2) |",
             "|---:|---:|---:|---:|"]
    for n in (9, 17, 33):
        tab = norm_table(h, np.linspace(0, 1.6 * H.delta, n), DX, DX)
        err = table_midpoint_error(tab, h, DX, DX)
        w = err["xi3"] > 0.5 * H.delta
        trows.append(f"| {n} | {100 * np.nanmax(err['force']):.2f} % / {100 * err['force'][w].max():.3f} % | "
                     f"{100 * err['pressure'][w].max():.1f} % | {100 * err['pressure_rms'][w].max():.2f} % |")
    return "\n".join(rows), lobes, "\n".join(trows)


def carter_section():
    plt = pyplot()
    H = hertz(1.0, curvature_ratio(10.0), 1e5)          # a/b = 0.1: long lateral strip
    mu = 0.3
    rows = ["| direction | c/a | elements across 2a x 2b | grid alignment | rms error / (mu p0) | max error / (mu p0) | force per length num/exact |",
            "|---|---:|---|---|---:|---:|---:|"]
    fig, ax = plt.subplots(figsize=(7, 3.8))
    cases = [(1, 30, 5, (0.3, 0.5, 0.7)), (1, 30, 4, (0.5,)), (1, 40, 5, (0.3, 0.5, 0.7)),
             (2, 30, 5, (0.3, 0.5, 0.7)), (2, 30, 4, (0.5,))]
    for direction, n_x, extra, cas in cases:
        dx, dy = 2 * H.a / n_x, 2 * H.b / 25
        X, Y = grid(n_x + extra, 29, dx, dy)
        p3 = H.pressure(X, Y)
        for ca in cas:
            g = carter_creepage(ca, H.p0, mu, direction)
            sol = tang_steady(p3, dx, dy, V, mu, gamma_x=g * (direction == 1), gamma_y=g * (direction == 2))
            x = X[:, 14]
            q = (sol.p1 if direction == 1 else sol.p2)[:, 14]
            ref = -carter_traction(x, H.a, H.p0, mu, ca * H.a)
            ins = np.abs(x) < H.a
            rms = np.sqrt(np.mean((q - ref)[ins] ** 2)) / (mu * H.p0)
            mx = np.abs(q - ref).max() / (mu * H.p0)
            fl = q.sum() / (-mu * H.p0 * np.pi / 2 * H.a * (1 - ca**2) / dx)
            name = "longitudinal (Carter, plane strain)" if direction == 1 else "lateral (anti-plane analogue)"
            align = "element centre on x = 0" if extra % 2 else "element edge on x = 0"
            rows.append(f"| {name} | {ca} | {n_x} x 25 | {align} | {100 * rms:.2f} % | {100 * mx:.2f} % | {fl:.4f} |")
            if direction == 1 and n_x == 30 and extra == 5:
                xf = np.linspace(-H.a, H.a, 500)
                line, = ax.plot(xf / H.a, carter_traction(xf, H.a, H.p0, mu, ca * H.a) / (mu * H.p0), "-")
                ax.plot(x[ins] / H.a, -q[ins] / (mu * H.p0), "o", ms=4, color=line.get_color(),
                        label=f"c/a = {ca}")
    ax.plot(xf / H.a, np.sqrt(1 - (xf / H.a) ** 2), "k:", lw=0.8, label="mu p3")
    ax.set_xlabel("x / a (rolling direction; leading edge at +1)")
    ax.set_ylabel("-p1 / (mu p0)")
    ax.set_title("steady TANG (dots) vs Carter (lines), a/b = 0.1, centre line", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, DOCS / "contact_carter.png", dpi=110)
    return "\n".join(rows)


def linear_section():
    rows = ["| contact | elements across each axis | C11 num / Kalker | C22 num / Kalker | C23 num / Kalker |",
            "|---|---:|---:|---:|---:|"]
    cases = [("b/a = 0.5", hertz(1.0, curvature_ratio(0.5), LOAD)), ("a/b = 0.5", hertz(1.0, curvature_ratio(2.0), LOAD)),
             ("wheel/rail Hertz (b/a = 0.84)", hertz_case()[3])]
    for name, H in cases:
        for ne in (16, 24):
            dx, dy = 2 * H.a / ne, 2 * H.b / ne
            X, Y = grid(ne + 5, ne + 5, dx, dy)
            p3 = H.pressure(X, Y)
            g = 1e-8
            c = []
            for kw, cname, scale in (({"gamma_x": g}, "C11", H.c**2), ({"gamma_y": g}, "C22", H.c**2),
                                     ({"spin": g / H.c}, "C23", H.c**2)):
                sol = tang_steady(p3, dx, dy, V, 1e6, **kw)
                F = sol.F1 if cname == "C11" else sol.F2
                num = -F / (scale * G * g)
                ref = creep_coefficient(cname, H.a, H.b, NU)
                c.append(f"{num:.3f} / {ref:.3f} ({100 * (num / ref - 1):+.1f} %)")
            rows.append(f"| {name} | {ne} | " + " | ".join(c) + " |")
    return "\n".join(rows)


def full_slip_and_transient_section():
    plt = pyplot()
    X, Y, h, H = hertz_case()
    _, ns = approach_for_load(LOAD, h, DX, DX)
    rows = ["| gamma_x | gamma_y | \\|F\\| / (mu F3) | cos(F, w) |", "|---:|---:|---:|---:|"]
    for gx, gy in ((0.0, -0.05), (0.0, -0.01), (0.02, -0.03)):
        s = tang_steady(ns.p, DX, DX, V, 0.3, gamma_x=gx, gamma_y=gy)
        F = np.hypot(s.F1, s.F2)
        rows.append(f"| {gx} | {gy} | {F / (0.3 * ns.F3):.6f} | {np.dot([s.F1, s.F2], [gx, gy]) / (F * np.hypot(gx, gy)):.6f} |")
    steady = tang_steady(ns.p, DX, DX, V, 0.3, gamma_x=0.001, gamma_y=-0.003)
    st, err, F2 = None, [], []
    for _ in range(100):
        st = tang_transient(ns.p, DX, DX, V, 0.3, gamma_x=0.001, gamma_y=-0.003, state=st)
        err.append(max(np.abs(st.p1 - steady.p1).max(), np.abs(st.p2 - steady.p2).max()) / (0.3 * ns.p.max()))
        F2.append(st.F2)
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.5))
    n = np.arange(1, 101)
    ax[0].semilogy(n, err)
    ax[0].set_xlabel("time step (one element = 0.5 mm of rolling)")
    ax[0].set_ylabel("max |p - p_steady| / (mu p0)")
    ax[0].set_title("transient TANG from rest, constant creepage", fontsize=9)
    ax[1].plot(n, np.array(F2) / 1e3, label="transient")
    ax[1].axhline(steady.F2 / 1e3, color="k", ls="--", label="steady")
    ax[1].set_xlabel("time step")
    ax[1].set_ylabel("F2 (kN)")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, DOCS / "contact_transient.png", dpi=110)
    contact_len = ns.contact.any(axis=1).sum()
    trans = (f"Transient TANG from a traction-free start, gamma_x = 0.001, gamma_y = -0.003, mu = 0.3, Hertzian "
             f"contact at dx = 0.5 mm ({contact_len} elements along the rolling direction): the largest traction "
             f"difference to the steady solution is {err[contact_len - 1]:.1e} (x mu p0) after {contact_len} steps "
             f"(one contact length rolled), {err[2 * contact_len - 1]:.1e} after {2 * contact_len} steps and "
             f"{err[-1]:.1e} after 100; "
             f"F2 = {F2[-1]:.2f} N vs {steady.F2:.2f} N steady.")
    return "\n".join(rows), trans


def rf_section():
    plt = pyplot()
    X, Y, h, H = hertz_case()
    _, ns = approach_for_load(LOAD, h, DX, DX)
    rows = ["| mu | gamma_sat = 3 mu F3 / k | full slip (no stick element) at \\|gamma_y\\| | s at 90 % of mu (m/s) | s at 99 % of mu (m/s) | mu_RF at \\|gamma_y\\| = 0.05 / mu | time (s) |",
            "|---:|---:|---:|---:|---:|---:|---:|"]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    cmap = plt.get_cmap("viridis")
    curves = []
    for i, mu in enumerate(MUS):
        t = time.perf_counter()
        c = rf_curve(ns.p, DX, DX, V, mu)
        dt = time.perf_counter() - t
        curves.append(c)
        s = np.linspace(0, c.s[-1], 40001)
        m = np.array([mu_rf(si, c.s, c.mu_rf, c.slope) for si in s])
        full = c.gamma[np.argmax(c.stick_fraction == 0)]
        rows.append(f"| {mu:.2f} | {c.gamma_sat:.5f} | {full:.5f} | {s[np.argmax(m >= 0.9 * mu)]:.4f} | "
                    f"{s[np.argmax(m >= 0.99 * mu)]:.4f} | {c.mu_rf[-1] / mu:.5f} | {dt:.2f} |")
        sm = np.linspace(0, 0.12, 600)
        col = cmap(i / (len(MUS) - 1))
        ax[0].plot(sm, [mu_rf(x, c.s, c.mu_rf, c.slope) for x in sm], color=col, label=f"mu = {mu:.2f}")
        ax[0].plot(c.s[c.s <= 0.12], c.mu_rf[c.s <= 0.12], ".", color=col, ms=3)
        ax[1].semilogx(c.s[1:], c.mu_rf[1:], ".-", color=col, ms=3, lw=0.8)
    ax[0].set_xlabel("slip velocity s = |gamma_y| v (m/s)")
    ax[0].set_ylabel("mu_RF = F2 / F3")
    ax[0].set_title("regularized friction, Hertzian contact 65 kN, v = 50 km/h", fontsize=9)
    ax[0].legend(fontsize=7, ncol=2)
    ax[1].axvline(0.006 * V, color="grey", ls=":", lw=0.8)
    ax[1].text(0.006 * V, 0.02, " |gamma_y| = 0.006", fontsize=7)
    ax[1].set_xlabel("s (m/s), log scale; dots = steady TANG solves")
    ax[1].set_ylabel("F2 / F3")
    ax[1].set_title("full ramp range |gamma_y| <= 0.05", fontsize=9)
    fig.tight_layout()
    save_figure(fig, DOCS / "contact_rf_curves.png", dpi=110)
    c3 = curves[list(MUS).index(0.3)]
    return "\n".join(rows), c3, ns


def compliance_section():
    X, Y, h, H = hertz_case()
    _, ns = approach_for_load(LOAD, h, DX, DX)
    A1, A2 = contact_compliance(ns.p, (1e3, 1e4), DX, DX)
    q1, q2 = ellipsoidal_traction_compliance(H.a, H.b, E, NU)
    mind = (2 - NU) / (4 * G * H.c)
    C11, C22 = creep_coefficient("C11", H.a, H.b), creep_coefficient("C22", H.a, H.b)
    L1, L2 = 8 * H.a / (3 * G * C11), 8 * H.a / (3 * G * C22)
    f1, f2 = L1 / (np.pi * H.a * H.b), L2 / (np.pi * H.a * H.b)
    Rc = 0.3
    Hc = hertz(1 / (2 * Rc), 1 / (2 * Rc), LOAD)
    dxc = Hc.a / 15
    Xc, Yc = grid(37, 37, dxc, dxc)
    c1, c2 = contact_compliance(Hc.pressure(Xc, Yc), (1.0, 0.0), dxc, dxc)
    mc = (2 - NU) / (4 * G * Hc.a)
    rows = ["| estimate | A1 (m/N) | A2 (m/N) | A1 ratio | A2 ratio |", "|---|---:|---:|---:|---:|",
            f"| thesis [4.32-4.35], NORM pressure, dx = 0.5 mm (this code) | {A1:.4e} | {A2:.4e} | 1 | 1 |",
            f"| same recipe in the continuum (Cerruti quadrature, pipeline/validation/references/hertz.py) | {q1:.4e} | {q2:.4e} | {A1 / q1:.4f} | {A2 / q2:.4f} |",
            f"| Mindlin no-slip compliance (2 - nu)/(4 G c), circle of radius c = sqrt(ab) | {mind:.4e} | {mind:.4e} | {A1 / mind:.3f} | {A2 / mind:.3f} |",
            f"| linear theory via Kalker's simplified theory: L/(pi a b), L = 8a/(3 G C) | {f1:.4e} | {f2:.4e} | {A1 / f1:.3f} | {A2 / f2:.3f} |",
            f"| circular contact (R = 0.3 m both ways), Hertz pressure, 30 elements across: this code vs (2 - nu)/(4 G a) | {c1:.4e} | {c2:.4e} | {c1 / mc:.4f} | {c2 / mc:.4f} |"]
    return "\n".join(rows)
