"""What a new user types (issue 26): every input a later stage would refuse is found by `make check`
(`python -m pipeline check`) with one line on stderr naming the file, the key, the value and what
is allowed, exit code 2 and nothing written; Ctrl-C ends a stage with one line and keeps the last
complete artifact; a positive gamma_y is explained."""
from __future__ import annotations

import math
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
DEFAULT = (ROOT / "pipeline" / "cases" / "default.toml").read_text()


def _case(tmp_path, name: str, text: str) -> dict:
    cases = tmp_path / "cases"
    cases.mkdir(exist_ok=True)
    (cases / f"{name}.toml").write_text(text)
    return dict(os.environ, SQUEAL_CASE_DIR=str(cases), SQUEAL_BUILD_DIR=str(tmp_path / "build"))


def _check(env, case):
    return subprocess.run([sys.executable, "-m", "pipeline", "check", "--case", case], cwd=ROOT, env=env,
                          capture_output=True, text=True)


def _refused(tmp_path, r, *words):
    """Exit 2, exactly one line on stderr holding ``words``, nothing written."""
    assert r.returncode == 2, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert not (tmp_path / "build").exists() or not any((tmp_path / "build").rglob("*.*"))


@pytest.mark.parametrize("friction,words", [
    ("mu = 0.33", None),                                                      # runs now (any value in range)
    ("mu = 7", ["friction.mu = 7", "0 < value <= 1"]),
    ('law = "stribeck"\nmu = 0.3', ["friction.law = 'stribeck'", "'coulomb', 'linear', 'rational', 'exponential', "
                                    "'polach'"]),
    ("mu = 0.3\nfkin = 0.2", ["friction.fkin = 0.2", "not a parameter of friction law 'coulomb'", "its parameters: mu"]),
    ('law = "polach"\nmu0 = 0.5\nA = 0.4', ["friction.B", "required key is missing for friction law 'polach'",
                                            "0 <= B <= 1000"]),
    ('preset = "hpf"\nmu = 0.3', ["friction.mu = 0.3", "no mu with friction.preset = 'hpf'"]),
    ('law = "linear"\nfkin = 0.9\nflin1 = 0.5\nsabsh1 = 250', ["friction = ", "mu(0) = 1.4 out of range 0 < mu <= 1"]),
    ('law = "exponential"\nfkin = 0.14\nfexp1 = 0.19\nsabsh1 = -3', ["friction.sabsh1 = -3", "in mm/s, 0 < value"]),
])
def test_friction_values_and_laws(tmp_path, friction, words):
    env = _case(tmp_path, "f", DEFAULT.replace("\nmu = 0.35\n", f"\n{friction}\n"))
    r = _check(env, "f")
    if words is None:
        assert r.returncode == 0 and "configuration OK" in r.stdout and "mu = 0.33" in r.stdout, r.stdout + r.stderr
        assert not (tmp_path / "build").exists()
    else:
        _refused(tmp_path, r, "f.toml", *words)


def test_mu_033_reaches_the_time_loop(tmp_path):
    """mu = 0.33 passed check and died in simulate (`no friction curve for mu = 0.33`, a traceback):
    the contact stage now builds its curve, and simulate's selection (contact_model with the case's
    resolved friction) finds it, plateau at 0.33."""
    from pipeline.config.case import clear
    from pipeline.caches.friction_curves import case_friction
    from solvers.timeloop.inputs import contact_model

    env = _case(tmp_path, "m33", DEFAULT.replace("\nmu = 0.35\n", "\nmu = 0.33\n"))
    r = subprocess.run([sys.executable, "-m", "pipeline", "contact", "--case", "m33"], cwd=ROOT, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with np.load(tmp_path / "build" / "cases" / "m33" / "contact.npz") as d:
        con = {k: d[k] for k in d.files}
    assert list(con["rf_label"]) == ["coulomb(mu=0.33)"]
    assert len(list((tmp_path / "build" / "cases" / "m33" / "friction").glob("*.npz"))) == 1
    import tomllib

    c = tomllib.loads((tmp_path / "cases" / "m33.toml").read_text())
    cm = contact_model(con, case_friction(c, "m33"))
    assert cm.mu == 0.33 and abs(cm.mu_nodes[-1] - 0.33) < 1e-4
    clear()


def test_presets_and_laws_resolve_to_the_registry():
    """A preset resolves to its law and parameters (the registry's), a law with defaults to its
    full parameter set: the curve's label is the registry's law's."""
    from pipeline.caches.friction_curves import resolve_friction
    from solvers.contact.friction_laws import PRESETS, get_friction_law
    from solvers.timeloop.inputs import curve_label

    f = resolve_friction({"preset": "hpf", "law": None}, "x.toml")
    assert (f.name, dict(f.params), f.preset) == ("linear", get_friction_law("hpf").params, "hpf")
    assert f.label == curve_label(get_friction_law("linear", **PRESETS["hpf"]["params"]))
    g = resolve_friction({"law": "exponential", "fkin": 0.14, "fexp1": 0.19, "sabsh1": 1250.0}, "x.toml")
    assert dict(g.params)["sabsh2"] == 10000.0 and g.mu == pytest.approx(0.33)       # fstat = fkin + fexp1
    assert resolve_friction({"mu": 0.35}, "x.toml").solver_law() == 0.35                    # Coulomb: the float, as before


@pytest.mark.parametrize("line,words", [
    ('wheel_profile = "nope"', ["contact.wheel_profile = 'nope'", "no such profile 'nope'", "available:"]),
    ('rail_profile = "c20_worn"', ["contact.rail_profile = 'c20_worn'", "not a rail profile (its kind is 'wheel')"]),
])
def test_missing_or_invalid_profile(tmp_path, line, words):
    env = _case(tmp_path, "p", DEFAULT.replace("dy_wr = -0.015", f"dy_wr = -0.015\n{line}"))
    _refused(tmp_path, _check(env, "p"), "p.toml", *words)


def test_contact_points_found_by_check(tmp_path):
    """The rigid contact search runs in check: a wheelset pushed into flange contact is refused
    there, as the contact stage would refuse it."""
    env = _case(tmp_path, "fl", DEFAULT.replace("dy_wr = -0.015", "dy_wr = 0.020"))
    _refused(tmp_path, _check(env, "fl"), "fl.toml", "dy_WR = +20.0 mm", "flange contact", "contact angle +71 deg")


def test_decay_time_of_an_exponential():
    """decay_time against the analytic answer: |g| = exp(-t / tau) has its last 5 % window
    (max at its start, 0.95 T) 66.02 dB below the peak at T = 66.02 tau / (0.95 * 8.686)."""
    from pipeline.config.check import DECAY_DB, FOLD_DB, decay_time

    dt, tau = 36e-6, 0.01
    t = np.arange(4096) * dt
    T = decay_time(np.exp(-t / tau)[:, None], dt)
    exact = (DECAY_DB + FOLD_DB) / (20 * math.log10(math.e)) * tau / 0.95
    assert abs(T - exact) < 0.03 * exact
    assert decay_time(np.exp(-t / 1.0)[:, None], dt) is None                # never decays within the samples


def _moving_kernel(build: Path, tau: float, dt0: float = 36e-6) -> float:
    """A cached rail kernel whose fixed-point kernel decays as exp(-t / tau); its decay time."""
    from pipeline.store.artifacts import save_npz
    from pipeline.config.check import decay_time

    g0 = np.exp(-np.arange(4096) * dt0 / tau)[:, None, None] * np.ones((1, 2, 2))
    save_npz(build / "rails" / "bv50" / "moving" / "k.npz", "rail-moving", {"dt": dt0}, rail_fixed_kernel=g0)
    return decay_time(g0, dt0)


def test_time_step_the_rail_kernel_cannot_decay_in(tmp_path):
    """dt = 20e-6: the greens stage stopped with a traceback (the rail Green's function on Kropp's
    8192 steps had decayed by 47 dB only, not 60, at N_t dt / 2 = 82 ms); check refuses it with
    the reason and the allowed range, from the rail's decay measured on its cached kernel."""
    from solvers.greens.grid import RAIL_NT

    env = _case(tmp_path, "dt", DEFAULT.replace("dt = 36e-6", "dt = 20e-6"))
    T = _moving_kernel(tmp_path / "build", tau=0.0145)
    kernel = list((tmp_path / "build").rglob("*.npz"))
    r = _check(env, "dt")
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert f"time.dt = 2e-05 (float): expected {2 * T / RAIL_NT:.3g} <= dt < 7.69e-05" in r.stderr, r.stderr
    assert "decay by 60 dB within N_t dt / 2 = 82 ms" in r.stderr
    assert list((tmp_path / "build").rglob("*.npz")) == kernel                  # nothing written
    for stage in ("contact", "greens"):                      # the stages refuse it the same way
        s = subprocess.run([sys.executable, "-m", "pipeline", stage, "--case", "dt"], cwd=ROOT, env=env,
                           capture_output=True, text=True)
        assert s.returncode == 2 and s.stderr.strip().splitlines() == r.stderr.strip().splitlines(), s.stderr
    assert list((tmp_path / "build").rglob("*.npz")) == kernel
    env = _case(tmp_path, "ok", DEFAULT.replace("dt = 36e-6", f"dt = {1.01 * 2 * T / RAIL_NT:.4g}"))
    assert _check(env, "ok").returncode == 0


def test_time_step_above_the_models_band(tmp_path):
    """dt = 1e-4 (in the schema's range): the greens stage stopped with a traceback (the wheel
    kernel's band-limited fit up to 6.5 kHz above the Nyquist frequency of 5 kHz); check refuses
    it naming the band and the Nyquist frequency."""
    env = _case(tmp_path, "big", DEFAULT.replace("dt = 36e-6", "dt = 1e-4"))
    _refused(tmp_path, _check(env, "big"), "big.toml", "time.dt = 0.0001 (float): expected dt < 7.69e-05",
             "fitted up to 6.5 kHz", "Nyquist frequency 1 / (2 dt) = 5.00 kHz")


def test_positive_gamma_y_is_explained(tmp_path):
    from pipeline.config.check import over_radial_note

    env = _case(tmp_path, "pos", DEFAULT.replace("gamma_y = -0.014", "gamma_y = 0.014"))
    r = _check(env, "pos")
    assert r.returncode == 0 and "note: gamma_y = +0.014 > 0: an over-radial wheelset" in r.stdout, r.stdout
    assert over_radial_note({"kinematics": {"gamma_y": -0.014}}) is None


def test_ctrl_c_during_greens_keeps_the_last_artifact(tmp_path):
    """SIGINT to a real `python -m pipeline greens` while it computes: one line on stderr, exit
    code 130, the greens.npz of before untouched and no temporary file left."""
    src = ROOT / "build"
    need = [src / "wheels" / "c20" / "modes.npz", src / "rails" / "bv50" / "section.msh",
            src / "cases" / "default" / "greens.npz"]
    if not all(p.exists() for p in need):
        pytest.skip("needs the default case built (make greens)")
    build = tmp_path / "build"
    for p in need:
        (build / p.relative_to(src)).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(p, build / p.relative_to(src))
    before = (build / "cases" / "default" / "greens.npz").read_bytes()
    env = dict(os.environ, SQUEAL_BUILD_DIR=str(build))
    log = tmp_path / "stderr.txt"
    with open(log, "w") as errf:                    # the rail kernel is not in the copied build: greens builds it
        proc = subprocess.Popen([sys.executable, "-m", "pipeline", "greens", "--case", "default"], cwd=ROOT, env=env,
                                stdout=subprocess.DEVNULL, stderr=errf, text=True)
        deadline = time.time() + 120
        while time.time() < deadline and proc.poll() is None and "building it" not in log.read_text():
            time.sleep(0.05)                        # until it logs the start of the kernel's build (seconds of work)
        time.sleep(0.5)
        assert proc.poll() is None, log.read_text()
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=120)
    err = "\n".join(line for line in log.read_text().splitlines() if not line.startswith(("INFO ", "DEBUG ")))
    assert proc.returncode == 130, err
    assert err.strip().splitlines() == ["interrupted: greens stopped; the artifacts it had finished are kept, "
                                        "nothing half-written"], err
    assert (build / "cases" / "default" / "greens.npz").read_bytes() == before
    assert not [p for p in build.rglob("*") if p.is_file() and ".tmp" in p.name]
