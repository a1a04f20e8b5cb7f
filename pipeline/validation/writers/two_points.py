"""Validation of the contact angle and the two contact points (issue 26): writes docs/validation/34_two_points.md
(a writer, run by `make validate`: `.venv/bin/python -m pipeline.validation.writers.two_points`).

It builds the default, the *_angle and the flange cases through the stability stage with Make, and reports
the unit-level reductions of pipeline/validation/references/two_point.py (asserted by
tests/interaction/test_two_point.py, tests/stability/test_two_point_screen.py, tests/greens/test_contact_angle.py);
what it states of the built cases (``default_case``, ``angle_case``, ``flange_case``) is asserted by
tests/interaction/test_two_point_validation.py.
"""
from __future__ import annotations

import math

import numpy as np

from solvers.timeloop.interaction import WheelModes, contact_model, simulate
from solvers.timeloop.two_point_driver import SecondPoint, simulate_two

from pipeline.store.paths import ROOT, case_file
from pipeline.validation.make import make_targets
from pipeline.validation.references import two_point as tp
from pipeline.validation.references.interaction import DT
from pipeline.validation.writers import save_fragment
from pipeline.config.loader import load as load_toml
from pipeline.config.input_schemas import CASE
from solvers.greens.kernels import choose_grid, frequency_grid
from pipeline.validation.references.greens import wheel_case

CASES = ROOT / "build" / "cases"
POSITIONS = ("dy05", "dy05_angle", "dy10", "dy10_angle", "default", "default_angle")


def build() -> None:
    """The cases' contact, greens, simulate and stability artifacts, through Make."""
    for case in (*POSITIONS, "flange"):
        make_targets("simulate", "stability", CASE=case)


def load(case: str, name: str):
    with np.load(CASES / case / f"{name}.npz") as d:
        return {k: d[k] for k in d.files}


def case_settings(case: str) -> dict:
    return load_toml(case_file(case), CASE)


def position_row(case: str) -> str:
    """A row of the contact-angle table: the case's contact, greens, simulate, stability (and radiate
    when built) artifacts."""
    con, gr, sim, st = (load(case, k) for k in ("contact", "greens", "simulate", "stability"))
    rp = CASES / case / "radiate.npz"
    sound = "-"
    if rp.exists():
        with np.load(rp) as d:
            sound = f"{d['sound_mode_label']} {float(d['L_W']):.1f}"
    k = int(np.argmax(st["sigma"]))
    aw, ar = float(gr.get("contact_angle_wheel", 0.0)), float(gr.get("contact_angle_rail", 0.0))
    angle = f"{math.degrees(aw):+.2f} ({math.degrees(ar):+.2f}) deg" if aw else "0 (none)"
    return (f"| {case} | {angle} | {float(con['preload_normal']) / 1e3:.2f} | {sim['stop_reason']} | "
            f"{float(sim['L_F2']):.2f} | {float(sim['f_dominant']):.2f} | {sound} | {st['label'][k]} "
            f"{st['f_hz'][k]:.1f} Hz, {st['sigma'][k]:+.2f}/s |")


def unit_numbers() -> dict:
    """The reductions of the two-point loop and screen to one point, and the projected kernel's error."""
    structs = tp.structures()
    one, two = tp.loop_unloaded_second_point(*structs)
    r1 = dict(max_rel=max(tp.rel(getattr(two.a, k), getattr(one, k)) for k in
                          ("F", "slip", "xi", "F_final", "slip_final", "xi_final")),
              bitwise=bool(np.array_equal(two.a.F, one.F) and np.array_equal(two.a.xi, one.xi)), steps=one.n_steps)
    one, two = tp.loop_identical_patches(*structs)
    r2 = dict(max_rel=tp.rel(two.a.F + two.b.F, one.F))
    s1 = dict(zip(("roots", "max_rel"), tp.compare_roots(*tp.screen_unloaded_second_point(*structs))[:2]))
    s2 = dict(zip(("roots", "max_rel"), tp.compare_roots(*tp.screen_identical_patches(*structs))[:2]))
    s1["roots"], s2["roots"] = len(s1["roots"]), len(s2["roots"])
    wc = wheel_case(-0.032)
    n_t = choose_grid(wc["f_hz"], wc["zeta"], DT, decay_db=120)
    k_err = float(tp.projected_kernel(wc, n_t, frequency_grid(DT, n_t))["err"].max())
    return dict(r1=r1, r2=r2, s1=s1, s2=s2, k_err=k_err)


def default_kw() -> dict:
    """The default case's time-loop settings."""
    c = case_settings("default")
    return dict(dt=c["time"]["dt"], v=c["kinematics"]["speed"], gamma_y=c["kinematics"]["gamma_y"],
                preload=c["loading"]["preload"], duration=c["time"]["duration"], store_every=10)


def default_case() -> dict:
    """The default case through the two-point loop with a never-reached second point, 8 s, its own
    greens and contact, beside the one-point loop."""
    con, gr = load("default", "contact"), load("default", "greens")
    w = WheelModes(gr["wheel_f"], gr["wheel_mass"], gr["wheel_zeta"], gr["wheel_phi"])
    cm = contact_model(con, case_settings("default")["friction"]["mu"])
    g = gr["rail_kernel"]
    kw = default_kw()
    one = simulate(w, g, cm, **kw)
    two = simulate_two(w, (g, 0.5 * g, 0.5 * g, g), cm, SecondPoint(cm, w.phi[:, ::-1].copy(), separation=1e-3),
                       **kw)
    dmax = max(float(np.abs(getattr(two.a, k) - getattr(one, k)).max() / np.abs(getattr(one, k)).max())
               for k in ("F", "F_final", "slip_final", "xi_final"))
    bitwise = all(np.array_equal(getattr(two.a, k), getattr(one, k)) for k in ("F", "F_final", "xi_final"))
    return dict(one=one, two=two, dmax=dmax, bitwise=bitwise, m1=one.measures(), m2=two.measures(), kw=kw)


def angle_case() -> dict:
    """default_angle's contact, greens, simulate and stability arrays, and the preload the case asks."""
    return dict(contact=load("default_angle", "contact"), greens=load("default_angle", "greens"),
                simulate=load("default_angle", "simulate"), stability=load("default_angle", "stability"),
                preload=case_settings("default")["loading"]["preload"])


def flange_case(kw: dict | None = None) -> dict:
    """The flange case (two patches, each in its contact plane) and its tread patch alone (one-point loop at
    its normal force Q / cos delta_a, the default case's time settings ``kw``)."""
    cf, gf, sf, stf = (load("flange", k) for k in ("contact", "greens", "simulate", "stability"))
    csf = case_settings("flange")
    recip = float(np.abs(gf["rail_kernel_ab"] - np.swapaxes(gf["rail_kernel_ba"], 1, 2)).max()
                  / np.abs(gf["rail_kernel_ab"]).max())
    wf = WheelModes(gf["wheel_f"], gf["wheel_mass"], gf["wheel_zeta"], gf["wheel_phi"])
    cmf = contact_model(cf, csf["friction"]["mu"])
    alone = simulate(wf, gf["rail_kernel_aa"], cmf, **dict(kw or default_kw(), preload=float(cf["preload_normal"])))
    return dict(cf=cf, gf=gf, sf=sf, stf=stf, Q=csf["loading"]["preload"], recip=recip, alone=alone)


def write() -> str:
    build()
    u, d = unit_numbers(), default_case()
    r1, r2, s1, s2, k_err = (u[k] for k in ("r1", "r2", "s1", "s2", "k_err"))
    one, m1, m2, dmax, bitwise = (d[k] for k in ("one", "m1", "m2", "dmax", "bitwise"))
    positions = [position_row(k) for k in POSITIONS]
    fl = flange_case(d["kw"])
    cf, sf, stf, recip, alone = (fl[k] for k in ("cf", "sf", "stf", "recip", "alone"))
    da, db = float(cf["contact_angle"]), float(cf["b_contact_angle"])
    Na, Nb = (float(x) for x in sf["N_static"])
    ma = alone.measures()
    top_f = int(np.argmax(stf["sigma"]))
    lines = []
    lines += [
        "## Contact angle and two contact points",
        "",
        "Written by `pipeline/validation/writers/two_points.py` (`make validate`); the unit-level numbers are "
        "asserted by `tests/interaction/test_two_point.py`, `tests/stability/test_two_point_screen.py`, "
        "`tests/greens/test_contact_angle.py` (the runs: `pipeline/validation/references/two_point.py`), the "
        "built cases' by `tests/interaction/test_two_point_validation.py`. Issue 26: `[contact] angle = \"none\" | "
        "\"profiles\"` and `[contact] points = 1 | 2` (`solvers/contact/frame.py`, `solvers/timeloop/two_point.py`, "
        "`solvers/stability/two_point.py`, `pipeline/stages/second_point.py`, `pipeline/stages/greens_two_point.py`).",
        "",
        "**Reduction to one point.** The two-point loop with a second patch that is never reached (1 mm above the "
        "first, its own tables, shapes and rail blocks non-zero) against the one-point loop:",
        "",
        "| check | steps | max relative difference of the first point's records | bit for bit |",
        "|---|---:|---:|---|",
        f"| C20 modes, analytic beam rail (unit test, 0.3 s) | {r1['steps']:,} | {r1['max_rel']:.1e} | "
        f"{'yes' if r1['bitwise'] else 'no'} |",
        f"| the default case's greens and contact, 8 s with the stop rule ({one.stop_reason}) | {one.n_steps:,} | "
        f"{dmax:.1e} | {'yes' if bitwise else 'no'} |",
        "",
        f"The default case through the two-point loop: L_F2 = {m2['L_F2']:.6f} dB, {m2['f_dominant']:.6f} Hz "
        f"(one-point: {m1['L_F2']:.6f} dB, {m1['f_dominant']:.6f} Hz; the recorded reference results, tests/reference/reference_results.json). "
        f"Two identical coincident patches (same shapes, every rail block the same kernel) are one patch of twice the "
        f"normal stiffness (NORM table F3 doubled, compliances halved): summed forces equal to {r2['max_rel']:.1e} "
        f"relative over 0.3 s. The two-point screen (6 x 6: dF1, dF2, dF3 per patch, 4 x 4 structures) with the "
        f"second patch unloaded gives the one-point screen's roots ({s1['roots']} modes, max relative difference "
        f"{s1['max_rel']:.1e}); with two identical patches the doubled patch's ({s2['roots']} modes, "
        f"{s2['max_rel']:.1e}).",
        "",
        "**Contact angle.** The contact plane of the profiles: normal tilted by the rigid contact's angle delta "
        "(rail slope, + rising toward the field side); the wheel's shapes and kernels projected by delta, the rail's "
        "by delta - alpha (rail inclination, the rail model's axes are the section's), G' = R^T G R; the preload Q "
        "carried by the normal force, N = Q / cos delta (frictionless static contact). The projected band-limited "
        f"C20 kernel's DFT against the receptance of the modal sum taken along the tilted directions (-21 deg): "
        f"{100 * k_err:.3f} % (Frobenius norm, pointwise up to 6.5 kHz; the unprojected kernel's accuracy). "
        "The three positions of SPEC 2 with the default case's settings, as the reference (angle \"none\") and in "
        "their contact planes (`pipeline/cases/*_angle.toml`; radiate's L_W where built):",
        "",
        "| case | angle: wheel (rail) | N (kN) | outcome | L_F2 (dB) | f (Hz) | sound mode, L_W (dB) | "
        "fastest screen root |",
        "|---|---:|---:|---|---:|---:|---|---|",
        *positions,
        "",
        "The angle changes the outcome at two of the three positions, and loop and screen agree at each: at -5 mm "
        "(+7.8 deg) the squeal disappears (the (2,0,a) root turns stable); at -15 mm (-5.1 deg) the (2,0,a) squeal "
        "gives way to a root of the wheelset on the track near 74 Hz, because the tilted normal couples the wheel's "
        "large low-frequency vertical receptance (its suspension modes) into the contact plane's lateral direction "
        "(the suspension damping was calibrated, `make calibrate-suspension`, without the angle; whether that root is "
        "physical or an artefact of the calibration is open); at -10 mm (+5.0 deg) the (3,0,a) squeal stays, with a "
        "lower force level. The thesis names the contact angle as possibly significant for squeal (ch. 7); "
        "the reference's cases keep angle \"none\".",
        "",
        f"**A flange case** (`pipeline/cases/flange.toml`, dy_WR = +17.86 mm): tread contact at y^W = "
        f"{1e3 * float(cf['y_wheel']):+.2f} mm (delta = {math.degrees(da):+.1f} deg) and a second zone on the flange "
        f"face at y^W = {1e3 * float(cf['b_y_wheel']):+.2f} mm, {1e6 * float(cf['b_separation']):.1f} um higher "
        f"(delta = {math.degrees(db):+.1f} deg, rail y^R = {1e3 * float(cf['b_y_rail']):+.2f} mm). Static state "
        f"(vertical approach common, Q = N_a cos delta_a + N_b cos delta_b): N_a = {Na / 1e3:.2f} kN, N_b = "
        f"{Nb / 1e3:.2f} kN. The flange patch at the full load would be {1e3 * (cf['b_x'][-1] - cf['b_x'][0]):.1f} x "
        f"{1e3 * (cf['b_y'][-1] - cf['b_y'][0]):.1f} mm (grid extent; longitudinal relative curvature "
        f"{float(cf['b_curvature_A']):.3f} 1/m = cos delta_b / (2 r_b)). Rail blocks reciprocal to {recip:.0e}. "
        f"Second patch's creepages: gamma_x = {float(sf['b_gamma'][0]):+.4f} (rolling radius "
        f"{1e3 * float(cf['b_rolling_radius']):.1f} mm against {1e3 / (2 * float(cf['curvature_A'])):.1f} mm), "
        f"gamma_y = {float(sf['b_gamma'][1]):+.4f}.",
        "",
        "| run | outcome | L_F2 (dB) | f (Hz) | fastest screen root |",
        "|---|---|---:|---:|---|",
        f"| two points (tread + flange) | {sf['stop_reason']} after {float(sf['n_steps']) * DT:.2f} s | "
        f"{float(sf['L_F2']):.1f} (a {float(sf['L_F2_a']):.1f}, b {float(sf['L_F2_b']):.1f}) | "
        f"{float(sf['f_dominant']):.1f} | {stf['label'][top_f]} {stf['f_hz'][top_f]:.1f} Hz, "
        f"{stf['sigma'][top_f]:+.2f}/s |",
        f"| the tread patch alone (one-point loop) | {alone.stop_reason} after {alone.n_steps * DT:.2f} s | "
        f"{ma['L_F2']:.1f} | {ma['f_dominant']:.1f} | |",
        "",
        "Limits of the flange patch (stated, not checked against CONTACT here; the peer's two-patch normal problem "
        "is the check): a half-space contact in the flange's tangent plane (profiles turned by -delta_b about the "
        "zone; the rail profile, which ends at the head's widest point, continued along its end curvature); "
        "Kalker's half-space theory wants the patch small against the radii, which a flange's few-mm lateral radius "
        "is not, and conformal flange contact is outside it; the two patches do not interact through the "
        "half-space (two tread zones whose ridge is lower than the approach are one conformal patch, which the "
        "one-point NORM on the combined gap already covers: `points = 2` is for separated patches); the rail "
        "model's head points lie on the crown and shoulder arcs, so the gauge-corner point's receptances are the "
        "outermost shoulder node's (9.6 mm away, rail file `bv50_flange`); no spin and no longitudinal structural "
        "dynamics at either patch; radiate and listen use the first patch's forces.",
        "",
    ]
    return save_fragment("34_two_points.md", "\n".join(lines))


if __name__ == "__main__":
    write()
