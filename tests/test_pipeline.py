"""Pipeline behaviour through its real entry points: the CLI and Make."""
from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
C20 = ROOT / "geometry" / "wheels" / "c20.toml"


def cli(*args, env=None, **kw):
    return subprocess.run([sys.executable, "-m", "pipeline", *args], cwd=ROOT, env=env, capture_output=True,
                          text=True, **kw)


def make(*args, build, timeout=600):
    env = dict(os.environ)
    return subprocess.run(["make", "--no-print-directory", f"BUILD={build}", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=timeout)


def _env(tmp_path, wheels):
    env = dict(os.environ, SQUEAL_BUILD_DIR=str(tmp_path / "build"), SQUEAL_WHEEL_DIR=str(wheels))
    return env


@pytest.mark.parametrize("line,new,key,allowed", [
    ("rolling_radius", "rolling_radius = -0.39", "tyre.rolling_radius", "0.15 < value <= 0.7"),
    ("rolling_radius", 'rolling_radius = "big"', "tyre.rolling_radius", "a float"),
    ("depth", "", "tyre.depth", "required key is missing"),
    # geometric consistency, checked before meshing: web thicker than the hub, bore outside the hub
    ("y_outboard", "y_outboard = -0.110", "web.thickness_hub", "a web thinner than the hub width"),
    ("bore_radius", "bore_radius = 0.149", "hub.bore_radius", "bore_radius < hub.outer_radius"),
])
def test_invalid_wheel_is_named_and_writes_nothing(tmp_path, line, new, key, allowed):
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    text, count = re.subn(rf"(?m)^{line} = .*$", new, C20.read_text())
    assert count == 1
    (wheels / "bad.toml").write_text(text)
    r = cli("mesh", "--wheel", "bad", env=_env(tmp_path, wheels))
    assert r.returncode == 2
    assert "bad.toml" in r.stderr and key in r.stderr and allowed in r.stderr, r.stderr
    if new and new.startswith(key.split(".")[1]):
        assert new.split("=")[1].strip().strip('"') in r.stderr
    assert not (tmp_path / "build").exists() or not any((tmp_path / "build").rglob("*.*"))


def test_invalid_case_friction_seven(tmp_path):
    cases = tmp_path / "cases"
    cases.mkdir()
    text = (ROOT / "pipeline" / "cases" / "default.toml").read_text().replace("mu = 0.35", "mu = 7")
    (cases / "bad.toml").write_text(text)
    env = dict(os.environ, SQUEAL_CASE_DIR=str(cases), SQUEAL_BUILD_DIR=str(tmp_path / "build"))
    r = cli("check", "--case", "bad", env=env)
    assert r.returncode == 2
    assert "bad.toml" in r.stderr and "friction.mu = 7" in r.stderr and "0 < value <= 1" in r.stderr
    assert not (tmp_path / "build").exists()


def seed_wheel_and_rail(build: Path) -> None:
    """The C20 wheel's and the BV50 rail's artifacts made (or found up to date) by Make in build/, then
    copied into ``build`` with their times (so Make finds them up to date there too), the rail's caches
    linked: a private build then runs the case and the curve without repeating the wheel's eigensolution
    and the rail's tables (those stages run from nothing in build/ on a fresh clone, and the modes stage
    once more, killed, in test_killed_stage_leaves_no_complete_artifact)."""
    r = subprocess.run(["make", "-s", "--no-print-directory", "modes", "rail"], cwd=ROOT, capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    shutil.copytree(ROOT / "build" / "wheels" / "c20", build / "wheels" / "c20", symlinks=True)
    rail = build / "rails" / "bv50"
    rail.mkdir(parents=True)
    for p in (ROOT / "build" / "rails" / "bv50").iterdir():
        if p.is_dir():
            (rail / p.name).symlink_to(p)          # the caches (moving kernels, surface tables), shared
        else:
            shutil.copy2(p, rail / p.name)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The default case (c20, bv50) and the default curve built once by Make into a private build folder
    (the wheel and rail seeded from build/)."""
    build = tmp_path_factory.mktemp("build")
    seed_wheel_and_rail(build)
    r = make("all", build=build)
    assert r.returncode == 0, r.stdout + r.stderr
    # `make` ends with the default curve's headline (issue 33): the page to open last
    assert r.stdout.strip().splitlines()[-1] == f"Open the verdict: {build / 'curves' / 'r75' / 'verdict.html'}"
    return build


def test_make_builds_wheel_artifacts(built):
    w = built / "wheels" / "c20"
    for f in ("section.msh", "mesh.json", "modes.npz", "modes.csv", "shapes/gallery.png"):
        assert (w / f).exists(), f
    header = (w / "modes.csv").read_text().splitlines()[0].split(",")
    assert header[:4] == ["f_hz", "n", "m", "class"]


def _default_result(built, n_min: int):
    with np.load(built / "cases" / "default" / "simulate.npz") as s, \
            np.load(built / "wheels" / "c20" / "modes.npz") as w:
        stop, L, f = str(s["stop_reason"]), float(s["L_F2"]), float(s["f_dominant"])
        sel = (w["cls"] == "a") & (w["m"] == 0) & (w["n"] >= n_min) & (w["kind"] == "flexible")
        return stop, L, f, w["f_hz"][sel]


def test_default_case_squeals_at_an_axial_mode(built):
    """`make` runs the default case end to end and it squeals (L_F2 >= 10 dB, SPEC 6) at an (n,0,a)
    wheel mode: the dominant F2 frequency within 1 % of the eigenfrequency of such a mode or of one
    of its harmonics."""
    stop, L, f, f_modes = _default_result(built, 0)
    assert L >= 10.0, (stop, L)
    assert np.abs(f / np.outer(f_modes, [1, 2, 3]) - 1).min() < 0.01, (f, f_modes)


def test_default_case_reaches_a_limit_cycle_at_a_mode_with_nodal_diameters(built):
    """Issue 7's statement: a limit cycle at an (n >= 2, 0, a) mode or one of its harmonics."""
    stop, L, f, f_modes = _default_result(built, 2)
    assert stop == "limit cycle" and L >= 10.0, (stop, L)
    assert np.abs(f / np.outer(f_modes, [1, 2, 3]) - 1).min() < 0.01, (f, f_modes)


def test_nothing_reruns_when_nothing_changed(built):
    assert make("-q", "all", build=built).returncode == 0


def _stages_after_touching(path, built):
    # -W: 'what if this file were newer' (same as touch, without touching the tree)
    r = make("-n", "-W", path, "all", build=built)
    lines = [ln for ln in r.stdout.splitlines() if ln.strip()]
    assert not any("pip install" in ln or "apt-get" in ln for ln in lines)
    return [ln.split("-m pipeline ")[1].split()[0] for ln in lines if "-m pipeline " in ln]


def test_touching_wheel_file_rebuilds_only_wheel_stages_and_dependents(built):
    assert _stages_after_touching("geometry/wheels/c20.toml", built) == [
        "mesh", "modes", "greens", "contact", "shapes", "simulate", "radiate", "stability", "report", "curve"]


def test_touching_rail_file_rebuilds_only_rail_stages_and_dependents(built):
    assert _stages_after_touching("geometry/rails/bv50.toml", built) == [
        "rail", "greens", "contact", "simulate", "radiate", "stability", "report", "curve"]


def test_touching_radiation_source_rebuilds_only_radiate_and_report(built):
    assert _stages_after_touching("solvers/radiation/thompson_jones.py", built) == ["radiate", "report", "curve"]


def test_make_builds_radiate_artifacts(built):
    c = built / "cases" / "default"
    for f in ("radiate.npz", "radiate.png", "radiate_harmonics.csv"):
        assert (c / f).exists(), f
    assert (c / "radiate_harmonics.csv").read_text().splitlines()[0] == "n,W_W,L_W_dB,share,f_peak_hz,mode,mode_f_hz"
    assert "## Sound radiation" in (built / "report" / "default" / "report.md").read_text()


def test_killed_stage_leaves_no_complete_artifact(built, tmp_path):
    """SIGKILL the modes stage mid-run: no modes.npz appears, Make still
    sees the target as out of date and the loader refuses."""
    build = tmp_path / "b"
    shutil.copytree(built / "wheels" / "c20", build / "wheels" / "c20")
    target = build / "wheels" / "c20" / "modes.npz"
    target.unlink()
    env = dict(os.environ, SQUEAL_BUILD_DIR=str(build))
    p = subprocess.Popen([sys.executable, "-m", "pipeline", "modes", "--wheel", "c20", "--workers", "1"],
                         cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    time.sleep(2.0)  # mid-run (the stage takes 4-9 s here: imports, FFCx forms, the eigen solves)
    assert p.poll() is None, "the modes stage finished before it could be killed: kill it sooner"
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    assert not target.exists()
    assert make("-q", "modes", build=build).returncode != 0
    sys.path.insert(0, str(ROOT))
    from pipeline.store.artifacts import ArtifactError, load_npz

    with pytest.raises(ArtifactError):
        load_npz(target, "wheel-modes")


def test_make_listen_then_report(built, tmp_path):
    """Issue 16: `make listen` writes the sound and its calibration, a receiver from the command line
    reruns it (and the next plain run restores the case's receiver), the report embeds the section.
    On a copy of the built folder: a listen.npz beside the case puts the listen stage in Make's plans,
    which the other tests of the module read."""
    built = Path(shutil.copytree(built, tmp_path / "build", symlinks=True))
    c = built / "cases" / "default"
    r = make("listen", build=built)
    assert r.returncode == 0, r.stdout + r.stderr
    for f in ("listen.npz", "listen_7.5m.npz", "listen_7.5m.wav", "listen_7.5m.json", "listen_7.5m.png"):
        assert (c / f).exists(), f
    assert make("-q", "listen", build=built).returncode == 0
    r = make("listen", "DISTANCE=20", "HEIGHT=3", build=built)
    assert r.returncode == 0 and "--distance 20 --height 3" in r.stdout, r.stdout + r.stderr
    assert make("-q", "listen", build=built).returncode != 0
    assert make("listen", build=built).returncode == 0 and make("-q", "listen", build=built).returncode == 0
    r = make("report", build=built)
    assert r.returncode == 0, r.stdout + r.stderr
    text = (built / "report" / "default" / "report.md").read_text()
    assert "## What a listener hears" in text and "Receiver 7.5m: 7.5 m from the track centre" in text
    assert (built / "report" / "default" / "figures" / "default_listen_7.5m.wav").exists()
    assert (c / "listen_20m_3m.npz").exists()      # the command line's receiver kept beside the case's
    assert (c / "passby_7.5m.npz").exists() and (c / "passby_20m_3m.npz").exists()
    html = (built / "report" / "default" / "report.html").read_text()
    assert html.index("SQUEALS") < html.index("<h2") and html.count("<audio") == 2 and "data:image/png;base64" in html
    assert (built / "report" / "default" / "vtk" / "ods.pvd").exists()
    assert make("-q", "all", build=built).returncode == 0
