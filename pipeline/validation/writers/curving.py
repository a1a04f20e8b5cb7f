"""Steady curving, the validation writer (`make validate`): the four checks of issue 25 with their
numbers, the creep forces against TANG and Kalker's table, the shift and angle of attack over
the radius for both shipped vehicles, and the C20 metro's bogie in the R = 150 m curve.
Writes docs/validation/90_curving.md with curving_radius.png and curving_bogie.png; the limits it states
are asserted by tests/curving/test_curving.py (the checks, the shipped curves' residuals, with
--validation the residuals of ``sweep`` here) and tests/curving/test_creep.py."""
from __future__ import annotations

import dataclasses
import math

from solvers.curving import solve

from pipeline.validation.references.curving import pure_rolling_shift
from pipeline.validation.references.curving_cases import RESIDUAL, independent_conicity, linear_case, metro
from pipeline.validation.writers import DOCS, pyplot, save_figure, save_fragment
from pipeline.curve.curving import build_problem, solve_curve
from postprocess.plots.curving import bogie_in_curve, radius_sweep
from solvers.curving.creep import kalker_coefficients
from pipeline.validation.references.kalker import creep_coefficient

RADII = (50.0, 75.0, 100.0, 150.0, 200.0, 300.0, 500.0, 750.0, 1000.0)


def _problem(curve, radius, a_unc=0.5):
    """The curve's problem at another radius, no cant, the speed that gives at most a_unc
    (m/s^2) of lateral acceleration (and at most the curve's speed)."""
    c, v, veh, trk, prof, law, names = build_problem(curve)
    V = min(trk.speed, math.sqrt(a_unc * radius))
    return veh, dataclasses.replace(trk, radius=radius, cant=0.0, speed=V), prof, law


def sweep(curve):
    """The curve's vehicle over ``RADII`` (no cant, the speed of ``_problem``): the leading and trailing
    wheelsets' shift and angle of attack, flange contact and the largest residual per radius."""
    s = dict(R=[], y1=[], y2=[], psi1=[], psi2=[], flange1=[], res=[])
    for R in RADII:
        veh, trk, prof, law = _problem(curve, R)
        sol = solve(prof, veh, trk, law)
        L, T = sol.wheelsets
        for k, v in zip(s, (R, L.y, T.y, L.psi, T.psi, L.flange != 0, sol.max_residual)):
            s[k].append(v)
    s.update(y_f=sol.flange_shift, a=veh.semi_wheelbase)
    return s


def write() -> str:
    from scipy.optimize import brentq  # lazy: brings in scipy

    pyplot()                                         # the Agg backend before the plots import pyplot


    out = ["## Steady curving (issue 25)", "",
           "Written by `pipeline/validation/writers/curving.py` (`make validate`; the asserted checks are "
           "`tests/curving/test_curving.py` and `tests/curving/test_creep.py`).  The model "
           "(`solvers/curving/`): the quasi-static equilibrium of the leading bogie's two wheelsets (lateral "
           "force, vertical force, roll moment, axle torque, yaw moment each) and its frame (lateral force, yaw "
           "moment) with the contact points of the actual profiles (tread and flange zone of the rigid contact), "
           "the creepages of a rigid wheelset turning with the curve, Kalker's linear creep coefficients computed "
           "with TANG on the Hertz ellipse and saturated as Shen, Hedrick & Elkins (1983), the primary "
           "suspension, the cant deficiency's lateral force and load transfer, and flange contact as a "
           "unilateral constraint (two-point contact at the flange shift, the flange's normal force the "
           "multiplier).", ""]
    # (1) free wheelset
    rows = ["| R (m) | y solver (mm) | y = r0 l0 / (lam R) (mm) | lam at y | difference |", "|---|---|---|---|---|"]
    for R in (600.0, 1000.0, 2000.0):
        veh, trk, prof, law = metro(R)
        sol = solve(prof, veh, dataclasses.replace(trk, speed=5.0), law, bogie=False)
        y = sol.wheelsets[0].y
        f = lambda v: v - pure_rolling_shift(veh.r0, *independent_conicity(prof, trk.c, veh.r0, veh.rolling_circle,  # noqa
                                                                           v)[::-1], R)
        yr = brentq(f, 0.2e-3, 14e-3, xtol=1e-12)
        lam = independent_conicity(prof, trk.c, veh.r0, veh.rolling_circle, yr)[0]
        rows.append(f"| {R:g} | {1e3 * y:.4f} | {1e3 * yr:.4f} | {lam:.4f} | {100 * (y / yr - 1):+.3f} % |")
    out += ["### (1) A free wheelset takes the pure-rolling shift", "",
            "C20 worn tread on BV50 worn head (1:30), no suspension.  Reference: y = r0 l0 / (lam R) with lam = "
            "(r_o - r_i) / (2 y) and l0 from the project's rigid contact search (`geometry.contact_point`) at "
            "that shift, solved for y independently of the curving solver.", "", *rows, ""]
    # (2) linear bogie
    rows = ["| k_x, k_y per box (MN/m) | R (m) | psi_1 solver / closed form (mrad) | y_1 (mm) | psi_2 (mrad) | "
            "psi_b (mrad) |", "|---|---|---|---|---|---|"]
    for kx, ky, R in [(1e6, 1e6, 5000.0), (5e6, 0.5e6, 8000.0), (0.3e6, 3e6, 6000.0)]:
        sol, (p1, y1, pb, y2) = linear_case(kx, ky, R)
        L, T = sol.wheelsets
        cell = lambda a, b, s=1e3: f"{s * a:.4f} / {s * b:.4f} ({100 * (a / b - 1):+.2f} %)"  # noqa: E731
        rows.append(f"| {kx / 1e6:g}, {ky / 1e6:g} | {R:g} | {cell(L.psi, p1)} | {cell(L.y, y1)} | "
                    f"{cell(-T.psi, p1)} | {cell(sol.frame_psi, pb)} |")
    out += ["### (2) A bogie with elastic primary yaw against the linear closed form", "",
            "Boocock (1969) and Wickens (2003, the steady curving of the bogie): linear creep (f11 = 8 MN, f22 = 7 MN), conical wheels "
            "(lam = 0.005 on a 300 mm round head: constant contact angle, no gravitational stiffness), balanced "
            "cant, a = 1.25 m, r0 = 0.45 m, per wheelset k_psi = 2 k_x b^2 and k_y = 2 k_y,box.  With "
            "psi_2 = -psi_1 and psi_b = 2 a f22 psi_1 / k_psi the six equations give",
            "", "    psi_1 = (a/R) / [1 + 4 f11 f22 l0 lam / (r0 k_psi) (a^2/k_psi + 1/k_y)]",
            "    y_1   = r0 l0 / (lam R) + r0 a f22 psi_1 / (lam f11 l0) + 2 f22 psi_1 (a^2/k_psi + 1/k_y)", "",
            "(`pipeline/validation/references/curving.py`).  The solver keeps what the theory drops (the roll moment of the "
            "lateral forces and the shifted lever arms move load between the wheels, whose normal forces then "
            "push sideways on the 1:200 cone; a 10 kN wheel load keeps that below 1 %):", "", *rows, ""]
    # (3) stiff bogie
    veh, trk, prof, law = metro(150.0, kx=1e8, ky=1e8)
    sol = solve(prof, veh, trk, law)
    L, T = sol.wheelsets
    a = veh.semi_wheelbase
    geo = a / trk.radius + (sol.flange_shift - T.y) / (2 * a)
    out += ["### (3) A stiff bogie in a tight curve flanges at the geometric angle of attack", "",
            f"C20 metro bogie with a primary 10 x the metro's (100 MN/m per box), R = 150 m, 50 km/h: the "
            f"leading outer wheel is in two-point contact (flange force {1e-3 * L.flange_force:.1f} kN at "
            f"{math.degrees([c for c in L.contacts if c.point.zone == 'flange'][0].point.angle):.1f} deg), the "
            f"leading wheelset at the flange shift y_1 = {1e3 * sol.flange_shift:.2f} mm, the trailing one at "
            f"y_2 = {1e3 * T.y:+.2f} mm.  A rigid bogie's leading angle of attack is a/R plus the clearance term "
            "(y_1 - y_2)/(2a): with a rigid frame y_i = y_b + x_i psi_b + x_i^2/(2R) and psi_i = psi_b + x_i/R, the flange-guided picture of curving that Boocock (1969) sets out from before his creep-guided theory:", "",
            "| | angle of attack (mrad) |", "|---|---|",
            f"| a/R | {1e3 * a / trk.radius:.3f} |",
            f"| a/R + (y_1 - y_2)/(2a) | {1e3 * geo:.3f} |",
            f"| a/R + y_1/(2a) (trailing wheelset centred) | {1e3 * (a / trk.radius + sol.flange_shift / (2 * a)):.3f} |",
            f"| a/R + y_1/a (trailing wheelset against the inner rail) | {1e3 * (a / trk.radius + sol.flange_shift / a):.3f} |",
            f"| solver | {1e3 * L.psi:.3f} ({100 * (L.psi / geo - 1):+.2f} % from a/R + (y_1 - y_2)/(2a)) |", ""]
    # creep
    rows = ["| a/b | C11 TANG / Kalker | C22 | C23 |", "|---|---|---|---|"]
    for r in (0.1, 0.3, 1.0, 3.33, 10.0):
        got = kalker_coefficients(r)
        ref = [creep_coefficient(n, r, 1.0, 0.3) for n in ("C11", "C22", "C23")]
        rows.append(f"| {r:g} | " + " | ".join(f"{g:.3f} / {k:.3f}" for g, k in zip(got, ref)) + " |")
    out += ["### Creep forces", "",
            "Kalker's no-slip coefficients computed by the project's steady TANG (40 x 40 elements on the Hertz "
            "pressure) against Kalker's Table E.3 (nu = 0.3, `pipeline/validation/references/data/kalker_creep_coefficients.csv`): "
            "1-3 % high (the grid), asserted within 3.5 %.  The Shen-Hedrick-Elkins saturation against steady "
            "TANG on the same patch (65 kN, 780 mm wheel on a 300 mm crown, mu = 0.35): within 0.03 mu N for "
            "pure lateral creepage, within 0.08 mu N with longitudinal creepage and a tread spin of 0.3 1/m "
            "(`tests/curving/test_creep.py`).", "", *rows, ""]
    # (4) residuals, sweep, shipped curves
    series = {"c20_metro (BV50 worn)": sweep("r150"), "y25_freight (BV50 new, 1:40 cone)": sweep("y25_r300")}
    worst = max(max(s["res"]) for s in series.values())
    shipped = {n: solve_curve(n) for n in ("r150", "r300", "r100_cant", "y25_r300")}
    worst = max(worst, *(s.max_residual for s in shipped.values()))
    assert worst < RESIDUAL
    save_figure(radius_sweep(series), DOCS / "curving_radius.png", dpi=90)
    s = shipped["r150"]
    save_figure(bogie_in_curve(s.solution, s.vehicle_model, s.track, s.profiles), DOCS / "curving_bogie.png", dpi=90)
    rows = ["| R (m) | " + " | ".join(f"{r:g}" for r in RADII) + " |", "|---" * (len(RADII) + 1) + "|"]
    for name, sr in series.items():
        rows.append(f"| {name}: y_1 (mm) | " + " | ".join(f"{1e3 * v:.1f}" for v in sr["y1"]) + " |")
        rows.append(f"| {name}: AoA_1 (mrad) | " + " | ".join(f"{1e3 * v:.1f}" + ("F" if f else "")
                                                            for v, f in zip(sr["psi1"], sr["flange1"])) + " |")
    w = {x.wheel: x for x in s.wheels}
    out += ["### (4) Residuals; both vehicles over the radius", "",
            f"Largest force or moment residual of every solution on this page and of the shipped curves: "
            f"{worst:.1e} of the wheel load (required: below 1e-8).  Leading wheelset over the radius, no cant, "
            "speed for at most 0.5 m/s^2 of lateral acceleration (F: leading outer flange in contact):", "",
            *rows, "", "![shift and angle of attack over the radius](validation/curving_radius.png)", "",
            f"The C20 metro in the R = 150 m curve (`pipeline/curves/r150.toml`): the leading inner wheel a1i "
            f"runs at dy_wr = {1e3 * w['a1i'].dy_wr:+.1f} mm with gamma_y = {w['a1i'].gamma_y:+.4f}, its contact at "
            f"y^W = {1e3 * w['a1i'].y_wheel:+.1f} mm, y^R = {1e3 * w['a1i'].y_rail:+.1f} mm (the default case, "
            "taken from the thesis: -15 mm, -0.014, +32 mm, +11 mm); the leading outer wheel a1o in two-point "
            f"contact (flange Y/Q = {w['a1o'].nadal:.2f}, Nadal's limit {w['a1o'].nadal_limit:.2f} at "
            f"{math.degrees(w['a1o'].flange_angle):.0f} deg).", "",
            "![the bogie in the curve and its four contacts](validation/curving_bogie.png)", ""]
    return save_fragment("90_curving.md", "\n".join(out) + "\n")


if __name__ == "__main__":
    write()
