"""The study stage end to end on the default case's artifacts (in this process, a local Dask
cluster of one or two workers): the map at the default operating point reproduces the simulate
stage bit for bit; the damping and contact studies write their tables, figures and summaries;
bad study definitions are refused naming the file, key and value."""
import csv
import math
import subprocess
import sys

import numpy as np
import pytest

from pipeline.store import artifacts, paths
from pipeline.study import stage as study_stage
from pipeline.config.loader import ConfigError, load
from pipeline.config.input_schemas import CASE
from tests.study.conftest import ROOT


def _write(tmp_path, name, text):
    d = tmp_path / "studies"
    d.mkdir(exist_ok=True)
    (d / f"{name}.toml").write_text(text)
    return d


def _csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


@pytest.fixture()
def studies(tmp_path, monkeypatch, default_case):
    def make(name, text):
        monkeypatch.setenv("SQUEAL_STUDY_DIR", str(_write(tmp_path, name, text)))
        return tmp_path / f"out-{name}"
    return make


def _simulate_artifact(case="default"):
    from pipeline.stages.simulate import simulate_config

    cfg = simulate_config(case)[-1]
    path = paths.case_dir(case) / "simulate.npz"
    try:
        return artifacts.load_npz(path, "simulate", cfg)[0]
    except artifacts.ArtifactError:
        subprocess.run([sys.executable, "-m", "pipeline", "simulate", "--case", case, "-q"], cwd=ROOT, check=True)
        return artifacts.load_npz(path, "simulate", cfg)[0]


def test_map_at_the_default_case_equals_the_simulate_stage(studies):
    c = load(paths.case_file("default"), CASE)
    gy, mu = c["kinematics"]["gamma_y"], c["friction"]["mu"]
    out = studies("one", f"""name = "one"\nkind = "map"\ncases = ["default"]
[grid]\ngamma_y_first = {gy}\ngamma_y_last = {gy}\ngamma_y_step = 0.002\nmu_first = {mu}\nmu_last = {mu}\nmu_step = 0.05
[quick]\ngamma_y_step = 0.002\nmu_step = 0.05
[simulation]\nduration = {c['time']['duration']}\n""")
    sim = _simulate_artifact()
    study_stage.run_study("one", workers=1, out=out, progress=False)
    (row,) = _csv(out / "map.csv")
    assert float(row["gamma_y"]) == gy and float(row["mu"]) == mu
    for k in ("L_F2", "f_dominant"):
        a, b = float(row[k]), float(sim[k])
        assert (math.isnan(a) and not np.isfinite(b)) or a == b, (k, a, b)
    assert row["stop_reason"] == str(sim["stop_reason"]) and float(row["t_end"]) == pytest.approx(
        int(sim["n_steps"]) * c["time"]["dt"])
    assert (out / "map_default.png").stat().st_size > 10_000 and "1 of 1 cases done" in (out / "summary.md").read_text()


def test_damping_study_writes_its_succession(studies):
    out = studies("damp", """name = "damp"\nkind = "damping"\ncases = ["default"]
[bisection]\nrel_tol = 0.3\n[procedure]\nmax_steps = 2\n[simulation]\nduration = 1.0\n""")
    study_stage.run_study("damp", workers=2, out=out, progress=False)
    runs = _csv(out / "table.csv")
    steps = _csv(out / "steps.csv")
    assert len({r["key"] for r in runs}) == len(runs) >= 1
    full0 = [r for r in runs if r["key"].startswith("s0-full-")]
    assert len(full0) == 1 and steps[0]["step"] == "0" and steps[0]["L_F2"] == full0[0]["L_F2"]
    squealed = float(steps[0]["L_F2"]) >= 10
    assert (len(steps) > 1 or not squealed) and "**Result:" in (out / "summary.md").read_text()
    for s in steps:
        if s["zeta_hi"] not in ("", "nan"):
            assert float(s["zeta_hi"]) / float(s["zeta_lo"]) - 1 <= 0.3
    assert (out / "damping.png").exists()


def test_contact_study_point_and_kalker_side_by_side(studies):
    out = studies("cv", """name = "cv"\nkind = "contact"\ncases = ["default"]
[modes]\nf_min = 400.0\nf_max = 500.0\n[simulation]\nduration = 0.01\nfinal = 0.01
[creepage]\nfrequencies = [1000.0]\nsettle = 0.005\n""")
    study_stage.run_study("cv", workers=2, out=out, progress=False)
    (m,) = _csv(out / "modes.csv")
    assert m["label"] == "(2,0,a)" and 400 < float(m["f_mode"]) < 500
    assert float(m["F2_pp_point"]) > 0 and float(m["F2_pp_kalker"]) > 0
    (cr,) = _csv(out / "creepage.csv")
    # partial slip under a 1 kHz creepage oscillation: the point model within 20 % of Kalker's
    # transient theory in amplitude, 0.5 % in the mean force, 30 degrees in phase
    assert abs(float(cr["d_amp"])) < 0.2 and abs(float(cr["d_mean"])) < 5e-3
    assert abs(math.degrees(float(cr["d_phase"]))) < 30
    assert float(cr["amp_kalker"]) > 100                            # a real oscillation, not noise
    for f in ("contact_modes.png", "contact_creepage.png", "summary.md"):
        assert (out / f).exists()


@pytest.mark.parametrize("text,key,value", [
    ('kind = "maps"', "kind", "maps"),
    ("gamma_y_step = 0.0", "grid.gamma_y_step", "0.0"),
    ('cases = ["nowhere"]', "cases", "nowhere"),
    ("mu_first = 1.2", "grid.mu_first", "1.2"),               # any mu in (0, 1] has its curve built
])
def test_bad_definitions_are_named(studies, text, key, value):
    good = {"kind": 'kind = "map"', "gamma_y_step": "gamma_y_step = 0.002", "cases": 'cases = ["default"]',
            "mu_first": "mu_first = 0.1"}
    body = f"""name = "bad"\n{good['kind']}\n{good['cases']}
[grid]\ngamma_y_first = -0.002\ngamma_y_last = -0.004\n{good['gamma_y_step']}\n{good['mu_first']}\nmu_last = 0.2\nmu_step = 0.05
[quick]\ngamma_y_step = 0.002\nmu_step = 0.05\n"""
    field = text.split(" =")[0]
    body = body.replace(good[field], text)
    out = studies("bad", body)
    with pytest.raises(ConfigError) as e:
        study_stage.run_study("bad", workers=1, out=out, progress=False)
    msg = str(e.value)
    assert "bad.toml" in msg and key.split("/")[0] in msg and value in msg
    assert not (out / "table.csv").exists() or (out / "table.csv").read_text().count("\n") <= 1


def test_unknown_study_lists_the_available(studies):
    studies("x", 'name = "x"\n')
    with pytest.raises(ConfigError, match=r"no such study; available: \['x'\]"):
        study_stage.run_study("nope", progress=False)


def test_one_run_per_output_folder(studies):
    import fcntl

    from pipeline.store.artifacts import ArtifactError

    out = studies("lock", 'name = "lock"\nkind = "damping"\ncases = ["default"]\n')
    out.mkdir(parents=True)
    with open(out / ".lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        with pytest.raises(ArtifactError, match="another run of this study"):
            study_stage.run_study("lock", workers=1, out=out, progress=False)
    assert not (out / "table.csv").exists()


def test_a_waiting_run_goes_on_when_the_other_ends(studies, monkeypatch):
    """SQUEAL_STUDY_WAIT=1 (validation writers asking Make for the same study at once): the second run waits
    at the lock and then runs (here to a stub kind that says it got there), instead of being refused."""
    import fcntl
    import threading
    import types

    class Reached(Exception):
        pass

    def run(*args, **kwargs):
        raise Reached

    out = studies("wait", 'name = "wait"\nkind = "damping"\ncases = ["default"]\n')
    out.mkdir(parents=True)
    monkeypatch.setenv(study_stage.WAIT, "1")
    monkeypatch.setattr(study_stage, "kind_module", lambda kind: types.SimpleNamespace(run=run))
    got = []

    def second():
        try:
            study_stage.run_study("wait", workers=1, out=out, progress=False)
        except Reached:
            got.append("ran")

    with open(out / ".lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        t = threading.Thread(target=second)
        t.start()
        t.join(1.0)
        assert t.is_alive() and not got             # waiting at the lock
    t.join(30.0)
    assert got == ["ran"]
