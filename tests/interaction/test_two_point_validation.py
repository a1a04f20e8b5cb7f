"""Validation of the contact angle and the two contact points (issue 26): writes
docs/validation/34_two_points.md.

    OMP_NUM_THREADS=1 .venv/bin/python -m pytest tests/interaction/test_two_point_validation.py --validation -q

Needs the default, default_angle and flange cases built through stability
(`for s in contact greens simulate stability; do .venv/bin/python -m pipeline $s --case <case>; done`);
the unit tests it quotes are tests/interaction/test_two_point.py, tests/stability/test_two_point_screen.py
and tests/greens/test_contact_angle.py (their numbers are recomputed here).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from solvers.timeloop.interaction import WheelModes, contact_model, simulate
from solvers.timeloop.two_point_driver import SecondPoint, simulate_two
from pipeline.validation.references.interaction import DT, ROOT, V, beam_kernel, c20_modes

DOCS = ROOT / "docs" / "validation" / "34_two_points.md"
CASES = ROOT / "build" / "cases"


def load(case: str, name: str):
    p = CASES / case / f"{name}.npz"
    if not p.exists():
        pytest.skip(f"needs {p} (build the case through stability)")
    with np.load(p) as d:
        return {k: d[k] for k in d.files}


def case_settings(case: str) -> dict:
    from pipeline.config.loader import load as load_toml
    from pipeline.store.paths import case_file
    from pipeline.config.input_schemas import CASE

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
    assert (st["sigma"][k] > 0) == (str(sim["stop_reason"]) == "limit cycle"), case   # screen and loop agree
    aw, ar = float(gr.get("contact_angle_wheel", 0.0)), float(gr.get("contact_angle_rail", 0.0))
    angle = f"{math.degrees(aw):+.2f} ({math.degrees(ar):+.2f}) deg" if aw else "0 (none)"
    return (f"| {case} | {angle} | {float(con['preload_normal']) / 1e3:.2f} | {sim['stop_reason']} | "
            f"{float(sim['L_F2']):.2f} | {float(sim['f_dominant']):.2f} | {sound} | {st['label'][k]} "
            f"{st['f_hz'][k]:.1f} Hz, {st['sigma'][k]:+.2f}/s |")


@pytest.mark.validation
def test_two_points_and_contact_angle_report():
    from pipeline.validation.references.greens import test_contact_angle as tca
    from pipeline.validation.references.interaction import test_two_point as ttp
    from tests.stability import test_two_point_screen as tts

    lines = []
    # ---- unit-level numbers (recomputed)
    wheel, _ = c20_modes()
    structs = (wheel, beam_kernel(DT, V, n_lags=1024, n_t=4096))
    ttp.test_unloaded_second_point_reduces_to_the_one_point_loop(structs)
    ttp.test_two_identical_patches_are_one_patch_of_double_stiffness(structs)
    tts.test_unloaded_second_point_gives_the_one_point_roots(structs)
    tts.test_two_identical_patches_screen_as_one_double_patch(structs)
    r1 = ttp.test_unloaded_second_point_reduces_to_the_one_point_loop.numbers
    r2 = ttp.test_two_identical_patches_are_one_patch_of_double_stiffness.numbers
    s1 = tts.test_unloaded_second_point_gives_the_one_point_roots.numbers
    s2 = tts.test_two_identical_patches_screen_as_one_double_patch.numbers

    # ---- the default case: two-point loop with a never-reached second point, 8 s, real structures
    con, gr = load("default", "contact"), load("default", "greens")
    c = case_settings("default")
    w = WheelModes(gr["wheel_f"], gr["wheel_mass"], gr["wheel_zeta"], gr["wheel_phi"])
    cm = contact_model(con, c["friction"]["mu"])
    g = gr["rail_kernel"]
    kw = dict(dt=c["time"]["dt"], v=c["kinematics"]["speed"], gamma_y=c["kinematics"]["gamma_y"],
              preload=c["loading"]["preload"], duration=c["time"]["duration"], store_every=10)
    one = simulate(w, g, cm, **kw)
    two = simulate_two(w, (g, 0.5 * g, 0.5 * g, g), cm, SecondPoint(cm, w.phi[:, ::-1].copy(), separation=1e-3),
                       **kw)
    dmax = max(float(np.abs(getattr(two.a, k) - getattr(one, k)).max() / np.abs(getattr(one, k)).max())
               for k in ("F", "F_final", "slip_final", "xi_final"))
    bitwise = all(np.array_equal(getattr(two.a, k), getattr(one, k)) for k in ("F", "F_final", "xi_final"))
    m1, m2 = one.measures(), two.measures()
    assert dmax <= 1e-12 and one.stop_reason == two.a.stop_reason and one.n_steps == two.a.n_steps
    assert abs(m1["L_F2"] - 53.190321) < 1e-5 and abs(m1["f_dominant"] - 434.764102) < 1e-5   # the reference

    # ---- contact angle: the C20 kernel check and the default case in the contact plane
    wc = __import__("pipeline.validation.references.greens", fromlist=["wheel_case"]).wheel_case(-0.032)
    from solvers.greens.kernels import choose_grid, frequency_grid

    n_t = choose_grid(wc["f_hz"], wc["zeta"], DT, decay_db=120)
    tca.test_projected_kernel_reproduces_the_receptance_along_the_tilted_directions(
        (wc, n_t, frequency_grid(DT, n_t)))
    k_err = tca.test_projected_kernel_reproduces_the_receptance_along_the_tilted_directions.error
    ca_, ga_, sa_ = load("default_angle", "contact"), load("default_angle", "greens"), load("default_angle", "simulate")
    sta = load("default_angle", "stability")
    positions = [position_row(k) for k in ("dy05", "dy05_angle", "dy10", "dy10_angle", "default", "default_angle")]
    delta = float(ca_["contact_angle"])
    assert abs(float(ca_["preload_normal"]) * math.cos(delta) - c["loading"]["preload"]) < 1e-6
    assert float(ga_["contact_angle_wheel"]) == delta
    top_a = int(np.argmax(sta["sigma"]))
    fa_loop, fa_screen = float(sa_["f_dominant"]), float(sta["f_hz"][top_a])
    if str(sa_["stop_reason"]) == "limit cycle":                      # screen and loop: the same root grows
        assert sta["sigma"][top_a] > 0 and abs(fa_loop / fa_screen - 1) < 0.05, (fa_loop, fa_screen)

    # ---- the flange case: two patches, each in its contact plane
    cf, gf, sf, stf = (load("flange", k) for k in ("contact", "greens", "simulate", "stability"))
    csf = case_settings("flange")
    Q = csf["loading"]["preload"]
    da, db = float(cf["contact_angle"]), float(cf["b_contact_angle"])
    Na, Nb = (float(x) for x in sf["N_static"])
    assert abs(Na * math.cos(da) + Nb * math.cos(db) - Q) < 1e-6 * Q and Nb > 0
    recip = float(np.abs(gf["rail_kernel_ab"] - np.swapaxes(gf["rail_kernel_ba"], 1, 2)).max()
                  / np.abs(gf["rail_kernel_ab"]).max())
    assert recip < 1e-9
    # the same case with the tread patch alone (one-point loop, its normal force Q / cos delta_a)
    wf = WheelModes(gf["wheel_f"], gf["wheel_mass"], gf["wheel_zeta"], gf["wheel_phi"])
    cmf = contact_model(cf, csf["friction"]["mu"])
    kwf = dict(kw, preload=float(cf["preload_normal"]))
    alone = simulate(wf, gf["rail_kernel_aa"], cmf, **kwf)
    ma = alone.measures()
    top_f = int(np.argmax(stf["sigma"]))
    if str(sf["stop_reason"]) == "decayed":
        assert stf["sigma"][top_f] < 0                                # screen and loop agree: stable

    lines += [
        "## Contact angle and two contact points",
        "",
        "Test: `tests/interaction/test_two_point_validation.py` (validation suite; it reruns the unit tests "
        "`tests/interaction/test_two_point.py`, `tests/stability/test_two_point_screen.py`, "
        "`tests/greens/test_contact_angle.py` for their numbers). Issue 26: `[contact] angle = \"none\" | "
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
        f"(one-point: {m1['L_F2']:.6f} dB, {m1['f_dominant']:.6f} Hz; the reference 53.190321 dB, 434.764102 Hz). "
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
    DOCS.write_text("\n".join(lines), encoding="utf-8")
