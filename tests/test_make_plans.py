"""What ``make -n`` plans after a source or input changes (issue 14: rebuild correctness).

Each test works in a temporary copy of the repository's tracked sources, "built" with
``make -t`` (empty artifacts, in dependency order), so the real tree and build are never
touched.  Mtimes are set explicitly: sources old, artifacts newer, then the one file under
test newest -- what ``touch FILE && make -n all`` sees.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from pipeline.store import deps

ROOT = Path(__file__).resolve().parent.parent
ALL = {"mesh", "modes", "shapes", "rail", "contact", "greens", "simulate", "radiate", "stability", "report"}  # the report shows the stability screen (issue 27)
PLAN = re.compile(r"-m pipeline (\w+) --(wheel|rail|case) (\S+)")


def _sources() -> list[str]:
    try:
        out = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z"], capture_output=True, check=True)
        files = [f for f in out.stdout.decode().split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = [p.relative_to(ROOT).as_posix() for p in ROOT.rglob("*") if p.is_file()
                 and not {".git", ".venv", "build", "__pycache__"} & set(p.relative_to(ROOT).parts)]
    return sorted(files)


def make(tree: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("WHEEL", "RAIL", "CASE", "MAKEFLAGS", "MFLAGS")}
    return subprocess.run(["make", "--no-print-directory", f"STAMP={tree / 'stamp'}", f"PY={sys.executable}",
                           *args], cwd=tree, env=env, capture_output=True, text=True, check=check)


def plan(tree: Path, *args: str) -> list[tuple[str, str]]:
    """(stage, input) of every ``python -m pipeline`` command ``make -n`` would run."""
    out = make(tree, "-n", *args).stdout
    return [(m[1], m[3]) for m in PLAN.finditer(out)]


def set_mtimes(tree: Path, when: float, under: str = ".") -> None:
    for p in (tree / under).rglob("*"):
        if p.is_file():
            os.utime(p, (when, when))


def touch(path: Path) -> None:
    now = time.time()
    os.utime(path, (now, now))


def build(tree: Path, goal: str, case: str) -> None:
    """Pretend ``make goal CASE=case`` ran: every artifact exists, newer than every source."""
    wheel, rail = deps.case_inputs(tree / "pipeline" / "cases" / f"{case}.toml")
    for d in (f"wheels/{wheel}/shapes", f"rails/{rail}", f"cases/{case}", f"report/{case}", "curves/r75"):  # `make`'s curve
        (tree / "build" / d).mkdir(parents=True, exist_ok=True)
    make(tree, "-t", goal, f"CASE={case}")
    now = time.time()
    set_mtimes(tree, now - 200)
    set_mtimes(tree, now - 100, "build")
    (tree / "stamp").touch()
    assert plan(tree, goal, f"CASE={case}") == [], "a freshly built tree must plan nothing"


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    t = tmp_path_factory.mktemp("make") / "repo"
    for f in _sources():
        (t / f).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / f, t / f)
    other = (t / "pipeline/cases/default.toml").read_text()
    other = re.sub(r'(?m)^wheel = ".*"', 'wheel = "straight"', other)
    other = re.sub(r'(?m)^rail = ".*"', 'rail = "60e1"', other)
    (t / "pipeline/cases/other.toml").write_text(other)
    build(t, "all", "default")
    return t


@pytest.fixture
def built(tree) -> Path:
    """The built tree with every source older than every artifact again."""
    now = time.time()
    set_mtimes(tree, now - 200)
    set_mtimes(tree, now - 100, "build")
    (tree / "stamp").touch()
    return tree


def stages(steps) -> set[str]:
    return {s for s, _ in steps}


def test_schemas_plans_every_stage_it_configures(built):
    # pipeline/config/input_schemas.py shapes the wheel, rail and case configuration every stage loads;
    # before issue 14 this planned nothing but the report
    touch(built / "pipeline/config/input_schemas.py")
    assert stages(plan(built, "all")) == ALL


def test_config_module_plans_every_stage(built):
    touch(built / "pipeline/config/loader.py")
    assert stages(plan(built, "all")) == ALL


def _radiation_modules() -> list[str]:
    """The radiation modules (solvers/radiation/) that the radiate stage reaches."""
    mod, fn, _ = deps.ENTRIES["radiate"]
    found = [f for f in deps.stage_files(mod, fn) if f.startswith("solvers/radiation/") and not f.endswith("__init__.py")]
    assert found, "the radiate stage reaches no radiation module"
    return found


@pytest.mark.parametrize("module", _radiation_modules())
def test_radiation_module_plans_radiate_and_report_only(built, module):
    touch(built / module)
    assert plan(built, "all") == [("radiate", "default"), ("report", "default")]


def test_interaction_solver_plans_simulate_and_after(built):
    mod, fn, _ = deps.ENTRIES["simulate"]
    assert "solvers/timeloop/interaction.py" in deps.stage_files(mod, fn) or not (ROOT / "solvers/timeloop/interaction.py").exists()
    touch(built / "solvers/timeloop/interaction.py")
    assert stages(plan(built, "all")) == {"simulate", "stability", "radiate", "report"}  # the screen imports the loop's inputs


def test_mode_renderer_plans_shapes_and_report_only(built):
    # stages.wheel's run_shapes imports the renderer; run_mesh/run_modes (same module) do not
    mod, fn, _ = deps.ENTRIES["shapes"]
    renderer = [f for f in deps.stage_files(mod, fn) if f.startswith("postprocess/") and not f.endswith("__init__.py")]
    assert renderer
    for f in renderer:
        touch(built / f)
    assert stages(plan(built, "all")) == {"shapes", "report"}


def test_wheel_file_plans_the_wheel_chain(built):
    touch(built / "geometry/wheels/c20.toml")
    assert stages(plan(built, "all")) == ALL - {"rail"}


def test_test_files_plan_nothing(built):
    touch(built / "tests/test_config.py")
    assert plan(built, "all") == []


def test_case_on_another_wheel_plans_against_its_wheel_and_rail(built):
    steps = plan(built, "simulate", "CASE=other")
    # no rail stage: the greens stage meshes the rail section itself (rail.npz is the report's)
    assert sorted(steps) == sorted([("mesh", "straight"), ("modes", "straight"),
                                    ("contact", "other"), ("greens", "other"), ("simulate", "other")])
    assert ("rail", "60e1") in plan(built, "report", "CASE=other")
    # the C20/BV50 artifacts of the default case are not what it is planned against
    out = make(built, "-n", "simulate", "CASE=other").stdout
    assert "c20" not in out and "bv50" not in out


def test_case_on_another_wheel_tracks_its_wheel_file(tree, tmp_path):
    tree = Path(shutil.copytree(tree, tmp_path / "repo", symlinks=True))  # its own build
    build(tree, "simulate", "other")
    touch(tree / "geometry/wheels/c20.toml")
    assert plan(tree, "simulate", "CASE=other") == []
    touch(tree / "geometry/wheels/straight.toml")
    assert stages(plan(tree, "simulate", "CASE=other")) == {"mesh", "modes", "contact", "greens", "simulate"}


def test_wheel_variable_cannot_disagree_with_the_case(built):
    r = make(built, "-n", "simulate", "CASE=other", "WHEEL=c20", check=False)
    assert r.returncode != 0
    assert "names wheel straight" in r.stderr and "WHEEL=c20" in r.stderr
    # the wheel stages alone still take WHEEL=
    assert sorted(plan(built, "modes", "WHEEL=straight")) == [("mesh", "straight"), ("modes", "straight"),
                                                                ("shapes", "straight")]


def test_missing_case_is_a_clear_error(built):
    r = make(built, "-n", "simulate", "CASE=nosuchcase", check=False)
    assert r.returncode != 0 and "pipeline/cases/nosuchcase.toml" in r.stderr


def test_curve_wheel_without_its_case_file_asks_for_make_curve(built):
    r = make(built, "-n", "radiate", "CASE=r150/a1i", check=False)
    assert r.returncode != 0
    assert "build/curves/r150/cases/a1i.toml" in r.stderr and "run make curve CURVE=r150 first" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_curve_wheel_is_a_case(built):
    # the curve stage writes the wheel's case file into the build; Make runs the case chain on it
    cfile = built / "build/curves/r150/cases/a1i.toml"
    cfile.parent.mkdir(parents=True, exist_ok=True)
    try:
        cfile.write_text((built / "pipeline/cases/default.toml").read_text())
        assert plan(built, "radiate", "CASE=r150/a1i") == [("contact", "r150/a1i"), ("greens", "r150/a1i"),
                                                           ("simulate", "r150/a1i"), ("radiate", "r150/a1i")]
        # the case file is tracked like a case file: built, then touched, it plans the chain again
        (built / "build/cases/r150/a1i").mkdir(parents=True, exist_ok=True)
        make(built, "-t", "radiate", "CASE=r150/a1i")
        assert plan(built, "radiate", "CASE=r150/a1i") == []
        touch(cfile)
        assert stages(plan(built, "radiate", "CASE=r150/a1i")) == {"contact", "greens", "simulate", "radiate"}
        assert (built / "build/cases/r150/a1i/radiate.npz").exists()  # the artifacts' folder <curve>/<wheel>
    finally:
        shutil.rmtree(built / "build/curves", ignore_errors=True)
        shutil.rmtree(built / "build/cases/r150", ignore_errors=True)
