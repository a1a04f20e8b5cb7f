"""Any friction law or preset in a curve file and a line study (issue 33): the curve's [friction] is
a case file's (the same schema, resolved once into a FrictionLaw), the wheel's screen and time loop
use the law's friction curve, the verdict's what-ifs include the friction modifier, and a bad
friction key is one line naming the file and the key."""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def run_cli(*args, env=None):
    e = dict(os.environ, OMP_NUM_THREADS="1", **(env or {}))
    return subprocess.run([sys.executable, "-m", "pipeline", *args], cwd=ROOT, capture_output=True, text=True,
                          env=e, timeout=1800)


def _curve(tmp_path, friction: str, name="fr") -> Path:
    text = (ROOT / "pipeline" / "curves" / "r75.toml").read_text()
    head, tail = text.split("[friction]")
    text = head + "[friction]\n" + friction + "\n\n[traction]" + tail.split("[traction]")[1]
    path = tmp_path / f"{name}.toml"
    path.write_text(text.replace('name = "r75"', f'name = "{name}"'))
    return path


@pytest.mark.parametrize("friction, key, words", [
    ('law = "exponential"\nfkin = 0.14\nfexp1 = 0.19', "friction.sabsh1", ["missing", "exponential", "mm/s"]),
    ('preset = "hpf"\nmu = 0.3', "friction.mu", ["preset = 'hpf'"]),
    ('law = "exponential"\nfkin = 0.14\nfexp1 = 0.19\nsabsh1 = -5.0', "friction.sabsh1", ["-5.0", "0 < value <= 10000000", "mm/s"]),
    ('preset = "hpff"', "friction.preset", ["'hpff'", "hpf", "polach_dry"]),
])
def test_bad_friction_key_is_one_line(tmp_path, friction, key, words):
    """A refused [friction] of a curve: one line naming the file, the key, the value and what is allowed."""
    path = _curve(tmp_path, friction)
    r = run_cli("curve", "--curve", str(path), env={"SQUEAL_BUILD_DIR": str(tmp_path / "build")})
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert str(path) in lines[0] and key in lines[0], lines[0]
    for w in words:
        assert w in lines[0], lines[0]
    assert not (tmp_path / "build" / "curves").exists()


def test_shipped_curves_resolve_their_law():
    """r75_hpf is the preset's law (mu 0.25 -> 0.35 over 0.5 m/s: CONTACT's linear law), r75_falling
    CONTACT's exponential law with the tractcurv parameters (fstat = fkin + fexp1 = 0.33); r75 stays
    Coulomb 0.35.  Each wheel's case carries the law, not a Coulomb mu."""
    from pipeline.config.curve_inputs import read_curve
    from pipeline.curve.cases import case_dict
    from pipeline.curve.curving import solve_curve
    from solvers.contact.friction_laws import preset

    hpf, fall, r75 = (read_curve(n) for n in ("r75_hpf", "r75_falling", "r75"))
    assert (hpf.friction.law, hpf.friction.preset) == ("linear", "hpf")
    assert hpf.friction.params == dict(preset("hpf").params)
    # the linear law by hand: fkin + flin1 (1 - s / (2 sabsh1)), sabsh1 = 250 mm/s
    law = hpf.friction.solver_law()
    for s in (0.0, 0.1, 0.5, 1.0):
        want = 0.35 - 0.10 * max(0.0, 1.0 - s / (2 * 0.25))
        assert law.mu(s) == pytest.approx(want, abs=1e-12)
    assert hpf.friction.mu == pytest.approx(0.25, abs=1e-12)
    assert fall.friction.law == "exponential" and fall.friction.mu == pytest.approx(0.14 + 0.19, abs=1e-12)
    assert fall.friction.solver_law().mu(1.25) == pytest.approx(0.14 + 0.19 / 2, abs=1e-12)   # halved at sabsh1
    assert r75.friction.coulomb_mu == 0.35
    sol = solve_curve(fall)
    case = case_dict(sol.curve, sol.wheels[1])
    assert case["friction"] == {"law": "exponential", "fkin": 0.14, "fexp1": 0.19, "sabsh1": 1250.0}
    # the wheel's case file (written as a record, `make <stage> CASE=<curve>/<wheel>`) resolves to the same law
    from pipeline.caches.friction_curves import resolve_friction
    from pipeline.config.input_schemas import CASE
    from pipeline.config.loader import validate

    for curve in (fall, hpf):
        sol = solve_curve(curve)
        for p in sol.wheels:
            c = validate(case_dict(sol.curve, p), CASE, "case")
            assert resolve_friction(c["friction"], "case") == curve.friction


def test_line_accepts_a_preset_and_the_base_curves_law(tmp_path):
    """A line's CSV names a preset (hpf) or 'base' (its base curve's [friction]: r75_falling's
    falling law): the rows' curves carry those laws; a typo is one line listing what is allowed."""
    from pipeline.config.loader import ConfigError
    from pipeline.study.line_input import line_curves, read_rows

    spec = {"name": "t_fric", "curves": str(tmp_path / "t.csv"), "base_curve": "r75_falling",
            "friction": {"dry_mu": 0.4, "wet_mu": 0.15}}
    head = "id,chainage_m,radius_m,cant_mm,length_m,speed_kmh,vehicle,friction\n"
    (tmp_path / "t.csv").write_text(head + "A,0,75,100,50,31,c20_metro,hpf\nA,0,75,100,50,31,c20_metro,base\n"
                                    "A,0,75,100,50,31,c20_metro,dry\n")
    rows = read_rows(spec)
    assert [r.condition for r in rows] == ["hpf", "base:exponential", "dry"]
    assert [r.mu for r in rows] == pytest.approx([0.25, 0.33, 0.4], abs=1e-12)
    curves = line_curves(spec, rows, tmp_path / "curves")
    laws = [curves[r.key][0].friction for r in rows]
    assert (laws[0].law, laws[0].preset) == ("linear", "hpf")
    assert laws[1].law == "exponential" and laws[1].params["sabsh1"] == 1250.0
    assert laws[2].coulomb_mu == 0.4
    (tmp_path / "t.csv").write_text(head + "A,0,75,100,50,31,c20_metro,hpf2\n")
    with pytest.raises(ConfigError) as e:
        read_rows(spec)
    assert "friction = 'hpf2'" in str(e.value) and "'base'" in str(e.value) and "hpf" in str(e.value)


def test_screen_uses_the_law_at_the_working_creepage():
    """The falling-law wheel a1i of r75_falling: the friction curve the screen and the time loop
    take (``contact_model`` of the screen's context) is the law's, not a Coulomb one -- in full
    sliding (creepage well above its saturation) mu_RF(gamma) = mu(gamma v) of the law's formula
    fkin + fexp1 2^(-s/sabsh1), and its slope falls: d mu_RF / d gamma = v dmu/ds < 0."""
    from pipeline.config.case import given
    from pipeline.curve.cases import wheel_case
    from pipeline.curve.curving import solve_curve
    from pipeline.curve.screen_first import screen_context
    from solvers.timeloop.interaction import contact_model

    sol = solve_curve("r75_falling")
    p = next(w for w in sol.wheels if w.wheel == "a1i")
    rc = wheel_case(sol.curve, p)
    with given([rc]):
        ctx = screen_context(rc)
    assert ctx.friction.law == "exponential" and ctx.mu == pytest.approx(0.33)
    cm = contact_model(ctx.contact, ctx.friction)
    v = ctx.v
    g = abs(p.gamma_y)
    # the curve's abscissa: s_nodes (slip speed gamma v, m/s: solvers.contact.friction.rf_curve)
    s = g * v
    mu_curve = float(np.interp(s, cm.s_nodes, cm.mu_nodes))
    mu_law = 0.14 + 0.19 * 2.0 ** (-s / 1.25)
    gamma_sat = float(ctx.contact["rf_gamma_sat"][0]) if np.ndim(ctx.contact["rf_gamma_sat"]) else math.nan
    print(f"a1i gamma_y = {p.gamma_y:.5f}, v = {v:.3f} m/s, s = {s:.4f} m/s, gamma_sat = {gamma_sat:.5f}: "
          f"mu_RF = {mu_curve:.5f}, law mu(s) = {mu_law:.5f}")
    assert mu_curve == pytest.approx(mu_law, rel=0.02)
    # the slope the screen linearises with (d mu_RF / ds), against the law's derivative -fexp1 ln2 / sabsh1 2^(-s/sabsh1)
    slope_curve = float(np.interp(s, cm.s_nodes, cm.slopes))
    slope_law = -0.19 * math.log(2.0) / 1.25 * 2.0 ** (-s / 1.25)
    print(f"slope: curve {slope_curve:.5f} s/m, law {slope_law:.5f} s/m")
    assert slope_curve == pytest.approx(slope_law, rel=0.1)
    assert mu_curve < ctx.mu - 0.01                           # below the static 0.33: the law, not Coulomb


def test_friction_modifier_what_if_in_the_verdict():
    """r75's squealing wheel a1i (Coulomb 0.35) with the rail treated by the friction modifier (preset
    hpf): its friction curve, built on the wheel's own contact, is the preset's law in full sliding
    (0.35 - 0.10 (1 - s / 0.5 m/s) at s = |gamma_y| v, by hand), the time loop runs with it, and
    verdict.md's "What would stop it" names the outcome: quiet, or its L_pA."""
    from pipeline.config.case import given
    from pipeline.curve.cases import wheel_case
    from pipeline.curve.curving import solve_curve
    from pipeline.curve.modifier import modifier_what_if, modifier_law
    from pipeline.curve.stage import operating_row, run_stages
    from pipeline.curve.verdict_report import verdict_markdown
    from pipeline.curve.what_ifs import CaseModels
    from pipeline.caches.friction_curves import with_curves
    from solvers.timeloop.interaction import contact_model

    sol = solve_curve("r75")
    p = next(w for w in sol.wheels if w.wheel == "a1i")
    rc = wheel_case(sol.curve, p)
    with given([rc]):
        run_stages(rc.name, ["contact", "greens"])      # up to date after `make curve CURVE=r75`: nothing to do
        models = CaseModels(rc.name)
        law = modifier_law()
        cm = contact_model(with_curves(rc.name, models.ctx.contact, [law]), law)
        s = abs(p.gamma_y) * models.ctx.v
        want = 0.35 - 0.10 * max(0.0, 1.0 - s / 0.5)
        got = float(np.interp(s, cm.s_nodes, cm.mu_nodes))
        print(f"a1i: s = {s:.4f} m/s, hpf mu_RF = {got:.5f}, law {want:.5f}")
        assert got == pytest.approx(want, rel=0.02)
        row = operating_row(p) | {"squeals": True, "f_squeal": 435.297, "L_F2": 49.977, "L_W": 104.29,
                                  "L_pA": 78.3374, "mode": "(2,0,a)", "wav": "listen_7.5m.wav"}
        mod = modifier_what_if(models, row)
    print(mod)
    assert mod.run and mod.run["mu"] == pytest.approx(0.25)
    row["modifier_what_if"] = mod
    md = verdict_markdown(sol.curve, sol.wheels, [row], wall=1.0)
    stop = next(ln for ln in md.splitlines() if ln.startswith("What would stop it"))
    assert "with a friction modifier (preset hpf): " in stop
    if mod.quiet:
        assert "**quiet**" in stop and f"L_F2 = {mod.run['L_F2']:.1f} dB" in stop
    else:
        assert "still squeals" in stop
        assert math.isnan(mod.L_pA) or f"{mod.L_pA:.1f} dB(A)" in stop
