"""Case names and the one resolved case (issue 25): ``pipeline.store.paths`` for curve wheels
``<curve>/<wheel>``, ``pipeline.config.case.resolve_case``."""
from __future__ import annotations

import pytest

from pipeline.store import paths


def test_curve_wheel_paths(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    assert paths.case_file("r150/a1i") == tmp_path / "curves" / "r150" / "cases" / "a1i.toml"
    assert paths.case_dir("r150/a1i") == tmp_path / "cases" / "r150" / "a1i"
    assert paths.case_file("default") == paths.cases() / "default.toml"
    assert paths.case_dir("default") == tmp_path / "cases" / "default"
    assert paths.curve_wheel("r150/a1i") == ("r150", "a1i") and paths.curve_wheel("default") is None


@pytest.mark.parametrize("bad", ["a/b/c", "/a1i", "r150/", "../x", "r150/.."])
def test_malformed_curve_wheel_names(bad):
    with pytest.raises(ValueError, match="<curve>/<wheel>"):
        paths.case_file(bad)


def test_missing_curve_wheel_asks_for_make_curve(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    assert paths.missing_case("r150/a1i") == "no case file for the curve wheel r150/a1i: run make curve CURVE=r150 first"
    assert "available" in paths.missing_case("nosuchcase")
    assert paths.missing_case("default") is None
    f = paths.case_file("r150/a1i")
    f.parent.mkdir(parents=True)
    f.write_text("")
    assert paths.missing_case("r150/a1i") is None


def test_resolved_default_case():
    from pipeline.config.case import resolve_case

    rc = resolve_case("default")
    assert rc.name == "default" and rc.case["wheel"] == "c20" and rc.wheel["name"] == "c20" and rc.rail["name"] == "bv50"
    assert (rc.friction.law, rc.friction.params, rc.friction.mu) == ("coulomb", {"mu": 0.35}, 0.35)
    # thesis [4.1] at -15 mm: y^W = +32 mm, y^R = +12 mm (the worn profiles were fitted to them, within 1.5 mm)
    assert abs(rc.contact.y_wheel - 0.032) < 1.5e-3 and abs(rc.contact.y_rail - 0.012) < 1.5e-3
    assert rc.config["running_surfaces"]["dy_wr"] == -0.015
    assert resolve_case("default") is rc  # memoised


def test_resolved_once_per_process_and_again_when_a_file_changes(tmp_path, monkeypatch):
    from pipeline.config import case as C

    calls = []
    real = C.case_contact
    monkeypatch.setattr(C, "case_contact", lambda name: calls.append(name) or real(name))  # case.py's name for it
    monkeypatch.setenv("SQUEAL_CASE_DIR", str(tmp_path))
    text = (paths.ROOT / "pipeline/cases/default.toml").read_text()
    (tmp_path / "mine.toml").write_text(text)
    a = C.resolve_case("mine")
    assert C.resolve_case("mine") is a and calls == ["mine"]
    (tmp_path / "mine.toml").write_text(text.replace("dy_wr = -0.015", "dy_wr = -0.010"))
    b = C.resolve_case("mine")
    assert calls == ["mine", "mine"] and b.case["contact"]["dy_wr"] == -0.010 and b.contact.y_wheel != a.contact.y_wheel


def test_missing_and_malformed_cases_are_one_line_errors(tmp_path, monkeypatch):
    from pipeline.config.case import resolve_case
    from pipeline.config.loader import ConfigError

    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    with pytest.raises(ConfigError, match="run make curve CURVE=r150 first") as e:
        resolve_case("r150/a1i")
    assert "\n" not in str(e.value)
    with pytest.raises(ConfigError, match="<curve>/<wheel>"):
        resolve_case("a/b/c")


def test_every_stage_of_a_case_derives_its_contact_point_once(monkeypatch):
    """simulate's configuration (its contact's and its greens') and stability's (which also asks
    for simulate's) derived the contact point 2 and 4 times before the resolved case; now once."""
    from pipeline.config import case as C
    from pipeline.stages.simulate import simulate_config

    C.clear()
    calls = []
    real = C.case_contact
    monkeypatch.setattr(C, "case_contact", lambda name: calls.append(name) or real(name))  # case.py's name for it
    simulate_config("default")
    simulate_config("default")
    from pipeline.stages.contact import contact_inputs
    from pipeline.stages.greens import greens_inputs

    contact_inputs("default")
    greens_inputs("default")
    assert calls == ["default"]


def test_default_artifacts_stay_valid():
    """What Make calls up to date, the stages load: build/cases/default's contact.npz and greens.npz, made
    (or found current) by Make, load against today's resolved configuration."""
    import subprocess

    from pipeline.store import artifacts
    from pipeline.stages.contact import contact_inputs
    from pipeline.stages.greens import greens_inputs

    subprocess.run(["make", "-s", "--no-print-directory", "build/cases/default/greens.npz"], cwd=paths.ROOT, check=True,
                   capture_output=True)
    artifacts.load_npz(paths.case_dir("default") / "contact.npz", "contact", contact_inputs("default")[3])
    artifacts.load_npz(paths.case_dir("default") / "greens.npz", "greens", greens_inputs("default")[-1])


def test_one_stage_table_for_the_command_line_and_make():
    import subprocess
    import sys

    from pipeline import __main__ as cli
    from pipeline.store import deps
    from pipeline.stages import STAGES

    assert set(deps.ENTRIES) == {n for n, s in STAGES.items() if s.make}
    assert {"contact", "greens", "simulate", "radiate", "stability", "listen", "report"} <= set(deps.ENTRIES)
    assert cli.NUMBA_STAGES == {n for n, s in STAGES.items() if s.numba}
    for name, (module, function, takes) in deps.ENTRIES.items():
        assert function in deps.Graph().load(module).defs, name
    # deps.py and the table need the standard library only (no site-packages: Make runs it before the venv)
    r = subprocess.run([sys.base_prefix + "/bin/python3", "-I", "-S", "pipeline/store/deps.py", "--case",
                        "pipeline/cases/default.toml"], cwd=paths.ROOT, capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.split() == ["c20", "bv50"], r.stderr


@pytest.mark.validation
@pytest.mark.parametrize("case", ["dy30", "straight"])
def test_off_list_contact_cases_run_end_to_end(case):
    """A copy of the default case at dy_WR = -30 mm (y^R = +4.1 mm) and one on the straight-web
    wheel (y^R = -5.2 mm): neither contact point is on the BV50 file's contact.y list; both run
    `make radiate` with no file edited (the rail from the running surface's wave table).  Slow
    (the surface table once, minutes; the straight wheel's modes)."""
    import subprocess

    import numpy as np

    r = subprocess.run(["make", "--no-print-directory", "radiate", f"CASE={case}"], cwd=paths.ROOT,
                       capture_output=True, text=True, timeout=3600)
    assert r.returncode == 0, r.stderr[-2000:]
    with np.load(paths.case_dir(case) / "greens.npz") as g, np.load(paths.case_dir(case) / "radiate.npz") as w:
        assert abs(float(g["y_rail"]) - float(g["y_rail_contact"])) < 1e-12  # the point itself, not a node near it
        assert float(w["L_F2"]) > 10.0 and np.isfinite(float(w["L_W"]))


def test_a_curve_wheel_runs_through_the_cli(tmp_path):
    """A curve wheel's case file (as the curve stage writes it) is a case for every stage:
    `check` and `contact --case r150/a1i` put the artifact in build/cases/r150/a1i/."""
    import os
    import subprocess
    import sys

    f = tmp_path / "curves" / "r150" / "cases" / "a1i.toml"
    f.parent.mkdir(parents=True)
    f.write_text((paths.ROOT / "pipeline/cases/default.toml").read_text().replace('name = "default"', 'name = "a1i"'))
    env = dict(os.environ, SQUEAL_BUILD_DIR=str(tmp_path), OMP_NUM_THREADS="1")
    for stage in ("check", "contact"):
        r = subprocess.run([sys.executable, "-m", "pipeline", stage, "--case", "r150/a1i"], cwd=paths.ROOT, env=env,
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
    assert (tmp_path / "cases" / "r150" / "a1i" / "contact.npz").exists()
    r = subprocess.run([sys.executable, "-m", "pipeline", "contact", "--case", "r150/a2o"], cwd=paths.ROOT, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 2 and r.stderr.strip().endswith("run make curve CURVE=r150 first")
    assert len(r.stderr.strip().splitlines()) == 1


def test_loop_arguments_are_the_one_translation():
    """``loop_arguments``: the time loop's arguments of the default case are its file's values (read here
    with tomllib, apart from the pipeline), the static normal force the contact arrays' when they hold
    one, the vertical preload for the two-point loop."""
    import tomllib

    from pipeline.config.case import loop_arguments, resolve_case

    raw = tomllib.loads((paths.ROOT / "pipeline/cases/default.toml").read_text())
    a = loop_arguments("default")
    assert (a.dt, a.v, a.gamma_y, a.preload) == (raw["time"]["dt"], raw["kinematics"]["speed"],
                                                 raw["kinematics"]["gamma_y"], raw["loading"]["preload"])
    assert a.simulate(store_every=10)["store_every"] == 10 and set(a.linearise()) == {
        "dt", "v", "gamma_y", "gamma_x", "spin", "preload"}
    b = loop_arguments(resolve_case("default"), {"preload_normal": 70e3})   # N = Q / cos(delta) of an angled contact
    assert b.preload == 70e3 and b.two_point()["preload"] == raw["loading"]["preload"] and "spin" not in b.two_point()


def test_a_given_case_is_not_read_from_its_file(tmp_path, monkeypatch):
    """A curve's wheel built in memory (``pipeline.curve.cases.wheel_case``) is what the stages resolve while
    the curve stage hands it to them (``given``): no case file is read (there is none here), the stage's
    configuration is derived from the object; outside ``given`` the name needs its file."""
    from pipeline.config import case as C
    from pipeline.config.loader import ConfigError
    from pipeline.curve.cases import wheel_case
    from pipeline.curve.curving import solve_curve
    from pipeline.stages.contact import contact_inputs

    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    sol = solve_curve("r150")
    rc = wheel_case(sol.curve, sol.wheels[1])
    monkeypatch.setattr(C, "case_contact", lambda name: (_ for _ in ()).throw(AssertionError(f"read {name}")))
    with C.given([rc]):
        assert C.resolve_case("r150/a1i") is rc
        c, pw, pr, cfg = contact_inputs("r150/a1i")
        assert c is rc.case and cfg["friction"] == sol.curve.friction.config()
    assert not paths.case_file("r150/a1i").exists()
    with pytest.raises(ConfigError, match="run make curve CURVE=r150 first"):
        C.resolve_case("r150/a1i")


def test_friction_law_mu_is_a_field():
    """FrictionLaw's mu is set where the law is resolved: the Coulomb coefficient, or for another law its
    coefficient at zero slip (the registry's mu_static), not parsed from a curve label."""
    import dataclasses

    from pipeline.caches.friction_curves import resolve_friction
    from solvers.contact.friction_laws import get_friction_law

    c = resolve_friction({"law": "coulomb", "mu": 0.123456789}, "x.toml")
    assert "mu" in {f.name for f in dataclasses.fields(c)} and c.mu == 0.123456789 and c.coulomb_mu == c.mu
    g = resolve_friction({"law": "exponential", "fkin": 0.14, "fexp1": 0.19, "sabsh1": 1250.0}, "x.toml")
    assert g.mu == get_friction_law("exponential", fkin=0.14, fexp1=0.19, sabsh1=1250.0).mu_static
    assert g.mu == pytest.approx(0.14 + 0.19) and g.coulomb_mu is None
