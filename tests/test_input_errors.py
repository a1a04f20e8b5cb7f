"""Input errors as issue 33 found them, each one line naming the file and the key that asked:

* a vehicle naming a wheel file that is not there: Make stopped with its own `No rule to make target
  'geometry/wheels/c21.toml'`; `make check CURVE=` did not look at the curve at all;
* a vehicle whose `name` is not its file's name was accepted silently (a study's too, issue 32's session 15);
* a missing wheel, rail, vehicle or profile file was named without the file and key that asked for it;
* `make study STUDY=<no such study>` printed a stray `sed: can't read ...` first;
* a refused study left an empty output folder holding a `.lock`.

Make runs in a copy of the repository's tracked files (as tests/test_make_plans.py), so the real tree
and build are never touched."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.test_make_plans import _sources

ROOT = Path(__file__).resolve().parent.parent
METRO = (ROOT / "geometry" / "vehicles" / "c20_metro.toml").read_text()
R150 = (ROOT / "pipeline" / "curves" / "r150.toml").read_text()
DEFAULT = (ROOT / "pipeline" / "cases" / "default.toml").read_text()


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    """The tracked files, plus a vehicle naming wheel c21 (no such file), a vehicle whose name is not its
    file's and a curve on each."""
    t = tmp_path_factory.mktemp("errors") / "repo"
    for f in _sources():
        (t / f).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / f, t / f)
    vehicles, curves = t / "geometry" / "vehicles", t / "pipeline" / "curves"
    (vehicles / "bad_metro.toml").write_text(METRO.replace('wheel = "c20"', 'wheel = "c21"')
                                             .replace('name = "c20_metro"', 'name = "bad_metro"'))
    (vehicles / "misnamed.toml").write_text(METRO.replace('name = "c20_metro"', 'name = "c20_metro_copy"'))
    for curve, vehicle in (("badw", "bad_metro"), ("badname", "misnamed")):
        (curves / f"{curve}.toml").write_text(R150.replace('vehicle = "c20_metro"', f'vehicle = "{vehicle}"')
                                              .replace('name = "r150"', f'name = "{curve}"'))
    for stamp in (".apt-stamp", ".core-stamp", ".render-stamp", "stamp"):     # set up: nothing to install
        (t / stamp).touch()
    return t


def make(tree: Path, *args: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("WHEEL", "RAIL", "CASE", "CURVE", "STUDY", "MAKEFLAGS",
                                                            "MFLAGS", "MAKELEVEL")}   # a user's top-level make
    return subprocess.run(["make", "--no-print-directory", f"STAMP={tree / 'stamp'}", f"PY={sys.executable}", *args],
                          cwd=tree, env=env, capture_output=True, text=True, timeout=600)


def lines(text: str) -> list[str]:
    return [ln for ln in text.splitlines() if ln.strip()]


@pytest.mark.parametrize("goal", ["curve", "check"])
def test_vehicle_naming_a_missing_wheel_is_one_line(tree, goal):
    r = make(tree, goal, "CURVE=badw")
    assert r.returncode != 0
    err = lines(r.stderr)
    assert len(err) == 1, r.stderr
    assert "No rule to make target" not in r.stderr
    for part in ("geometry/vehicles/bad_metro.toml", "wheel = 'c21'", "'c20'", "'straight'"):
        assert part in err[0], (part, err[0])
    assert not (tree / "build" / "curves").exists() and not (tree / "build" / "wheels").exists()   # no work


@pytest.mark.parametrize("goal", ["curve", "check"])
def test_vehicle_named_unlike_its_file_is_refused(tree, goal):
    r = make(tree, goal, "CURVE=badname")
    assert r.returncode != 0
    err = lines(r.stderr)
    assert len(err) == 1 and "misnamed.toml" in err[0] and "name = 'c20_metro_copy'" in err[0], r.stderr
    assert not (tree / "build" / "curves").exists()


def test_vehicle_named_unlike_its_file_is_refused_in_python(tmp_path):
    from pipeline.config.curve_inputs import read_vehicle
    from pipeline.config.loader import ConfigError

    (tmp_path / "misnamed.toml").write_text(METRO.replace('name = "c20_metro"', 'name = "c20_metro_copy"'))
    with pytest.raises(ConfigError) as e:
        read_vehicle("misnamed", beside=tmp_path)          # a user's vehicle beside their curve file
    assert "misnamed.toml" in str(e.value) and "name = 'c20_metro_copy'" in str(e.value)
    assert len(str(e.value).splitlines()) == 1


@pytest.mark.parametrize("goal", ["check", "study"])
def test_study_named_unlike_its_file_is_refused(tree, goal):
    """A copy of the example line under another file name: one line naming the copy, `name` and the file's name,
    before any work (no build/studies/ folder)."""
    studies = tree / "pipeline" / "studies"
    (studies / "bad_line.toml").write_text((studies / "metro_line.toml").read_text())
    r = make(tree, goal, "STUDY=bad_line")
    assert r.returncode != 0
    err = [ln for ln in lines(r.stderr) if not ln.startswith("make: ***")]     # Make's own 'Error 2' aside
    assert len(err) == 1 and "bad_line.toml: " in err[0] and "name = 'metro_line'" in err[0], r.stderr
    assert "'bad_line'" in err[0], err[0]
    assert not (tree / "build" / "studies").exists()


def _cli(env: dict, *args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "pipeline", *args], cwd=ROOT, env=dict(os.environ, **env),
                          capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("what", ["vehicle wheel", "curve vehicle", "curve rail", "case wheel", "case rail",
                                  "case profile", "wheel-file profile"])
def test_missing_file_names_the_key_that_asked(tmp_path, what):
    """The stage's (and the check's) message names the file that asked, its key and the value."""
    d = {k: tmp_path / k for k in ("cases", "curves", "vehicles", "wheels")}
    for p in d.values():
        p.mkdir()
    shutil.copy2(ROOT / "geometry" / "vehicles" / "c20_metro.toml", d["curves"])     # beside the curve file
    for w in ("c20", "straight"):
        shutil.copy2(ROOT / "geometry" / "wheels" / f"{w}.toml", d["wheels"])
    env = {"SQUEAL_BUILD_DIR": str(tmp_path / "build"), "SQUEAL_CASE_DIR": str(d["cases"]),
           "SQUEAL_WHEEL_DIR": str(d["wheels"])}
    case, curve = DEFAULT, R150
    if what == "vehicle wheel":
        (d["curves"] / "c20_metro.toml").write_text(METRO.replace('wheel = "c20"', 'wheel = "c21"'))
        src, key, value = d["curves"] / "c20_metro.toml", "wheel", "c21"
    elif what == "curve vehicle":
        curve = R150.replace('vehicle = "c20_metro"', 'vehicle = "tram9"')
        src, key, value = d["curves"] / "t.toml", "vehicle", "tram9"
    elif what == "curve rail":
        curve = R150.replace('rail = "bv50"', 'rail = "bv51"')
        src, key, value = d["curves"] / "t.toml", "rail", "bv51"
    elif what == "case wheel":
        case = DEFAULT.replace('wheel = "c20"', 'wheel = "c21"')
        src, key, value = d["cases"] / "t.toml", "wheel", "c21"
    elif what == "case rail":
        case = DEFAULT.replace('rail = "bv50"', 'rail = "bv51"')
        src, key, value = d["cases"] / "t.toml", "rail", "bv51"
    elif what == "case profile":
        case = DEFAULT.replace('normal = "table"', 'normal = "table"\nwheel_profile = "c99_worn"')
        src, key, value = d["cases"] / "t.toml", "contact.wheel_profile", "c99_worn"
    else:
        text = (ROOT / "geometry" / "wheels" / "c20.toml").read_text()
        assert 'profile = "c20_worn"' in text
        (d["wheels"] / "c20.toml").write_text(text.replace('profile = "c20_worn"', 'profile = "c20_gone"'))
        src, key, value = d["wheels"] / "c20.toml", "running_surface.profile", "c20_gone"
    (d["cases"] / "t.toml").write_text(case)
    (d["curves"] / "t.toml").write_text(curve.replace('name = "r150"', 'name = "t"'))
    t = str(d["curves"] / "t.toml")                        # a curve file outside the repository, by its path
    runs = ([("curve", "--curve", t), ("check", "--curve", t)] if src.parent.name in ("curves", "vehicles")
            else [("contact", "--case", "t"), ("check", "--case", "t")])
    for args in runs:
        r = _cli(env, *args)
        assert r.returncode == 2, (args, r.stderr[-2000:])
        err = lines(r.stderr)
        assert len(err) == 1 and "Traceback" not in r.stderr, (args, r.stderr)
        assert f"{src}: " in err[0] and f"{key} = {value!r}" in err[0], (args, err[0])
    assert not (tmp_path / "build" / "curves").exists()


def test_missing_study_has_no_stray_sed_message(tree):
    r = make(tree, "study", "STUDY=nosuch")
    assert r.returncode != 0
    assert "sed" not in r.stderr and "can't read" not in r.stderr, r.stderr
    assert "nosuch.toml: no such study" in r.stderr


def test_refused_study_leaves_nothing(tmp_path):
    """A line study whose CSV is refused: no output folder, no .lock, at the default place or --out."""
    studies = tmp_path / "studies"
    studies.mkdir()
    (studies / "bad.toml").write_text('name = "bad"\nkind = "line"\ncurves = "bad.csv"\nbase_curve = "r150"\n'
                                      '[friction]\ndry_mu = 0.35\nwet_mu = 0.15\n')
    (studies / "bad.csv").write_text("id,chainage_m,radius_m,cant_mm,length_m,speed_kmh,vehicle,friction\n"
                                     "C1,0,12,0,50,30,c20_metro,dry\n")
    env = {"SQUEAL_STUDY_DIR": str(studies), "SQUEAL_BUILD_DIR": str(tmp_path / "build"), "OMP_NUM_THREADS": "1"}
    for extra in ((), ("--out", str(tmp_path / "out" / "bad"))):
        r = _cli(env, "study", "--study", "bad", "--no-progress", *extra)
        assert r.returncode == 2 and "radius_m = '12'" in r.stderr, r.stderr
    assert not (tmp_path / "build" / "studies").exists()
    assert not (tmp_path / "out").exists()
