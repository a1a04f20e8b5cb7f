"""A cache's code key covers exactly the code its results come from (issue 34).

Every cache names the functions whose results it keeps; ``code_key`` hashes the files they reach through
the imports (``pipeline.store.deps``, the analysis that also writes Make's dependencies).  Two checks:

- touching a file (a code change, in a copy of the repository) changes the key of every cache whose
  functions reach it -- the rail's moving kernel, its surface table and surface kernel, the friction
  curves, the study rows, the line rows, and Make's stage artifacts -- and of no other;
- the reach is complete, measured by a second method: the Python functions that actually run while a
  cached result is computed (a profiler hook on a real computation) all lie in files of its key.
"""
from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from pipeline.caches import friction_curves, rail_kernel, rail_surface_table
from pipeline.store import deps
from pipeline.store.code_hash import code_key, reached_files
from pipeline.study import context
from pipeline.study.kinds import line
from pipeline.validation.make import ensure_case

ROOT = Path(__file__).resolve().parents[2]
CACHES = {
    "rail moving kernel": (rail_kernel.KERNEL_FUNCTIONS, False),
    "rail surface table": (rail_surface_table.TABLE_FUNCTIONS, False),
    "rail surface kernel": (rail_surface_table.KERNEL_FUNCTIONS, False),
    "friction curve": (friction_curves.CURVE_FUNCTIONS, False),
    "study row": (context.ROW_FUNCTIONS, True),
    "line row": (line.ROW_FUNCTIONS, True),
}
TOUCHED = ["solvers/contact/friction.py", "solvers/rail/moving_static.py", "solvers/rail/surface.py",
           "solvers/radiation/thompson_jones.py", "solvers/curving/creep.py", "solvers/timeloop/kernel.py",
           "solvers/stability/screen.py", "geometry/rail.py", "postprocess/listening/listener.py"]


@pytest.fixture(scope="module")
def copy(tmp_path_factory) -> Path:
    """The repository's packages copied (the keys are computed there, the files touched there)."""
    root = tmp_path_factory.mktemp("repo")
    for pkg in deps.repo_packages(ROOT) - {"tests", "benchmarks"}:
        shutil.copytree(ROOT / pkg, root / pkg, ignore=shutil.ignore_patterns("__pycache__", "*.npz", "*.csv"))
    return root


@pytest.fixture(scope="module")
def make_deps(copy) -> dict:
    """Make's dependencies of every stage in the copy (``DEPS_<stage>``)."""
    return {stage: deps.stage_files(module, function, copy) for stage, (module, function, _) in deps.ENTRIES.items()}


def _keys(root: Path, make_deps: dict) -> dict:
    out = {name: code_key(*fns, ignore_docs=docs, root=root) for name, (fns, docs) in CACHES.items()}
    for stage, files in make_deps.items():   # Make's artifacts: what Make compares, the stage's DEPS files
        out[f"make {stage}"] = tuple((f, (root / f).read_bytes()) for f in files)
    return out


def _reaches(root: Path, make_deps: dict, name: str, rel: str) -> bool:
    if name.startswith("make "):
        return rel in make_deps[name[5:]]
    return rel in reached_files(tuple(sorted(CACHES[name][0])), root)


@pytest.mark.parametrize("rel", TOUCHED)
def test_touching_a_file_invalidates_what_reaches_it_and_nothing_else(copy, make_deps, rel):
    before = _keys(copy, make_deps)
    path = copy / rel
    text = path.read_text()
    try:
        path.write_text(text + "\n_TOUCHED = 1  # a code change\n")
        after = _keys(copy, make_deps)
    finally:
        path.write_text(text)
    changed = {k for k in before if before[k] != after[k]}
    expected = {k for k in before if _reaches(copy, make_deps, k, rel)}
    assert changed == expected, f"touching {rel}: changed {sorted(changed)}, expected {sorted(expected)}"
    assert expected, f"no cache reaches {rel}: pick a file some cache depends on"


def test_a_docstring_keeps_the_rows_and_changes_the_artifacts(copy, make_deps):
    """Study and line rows hash syntax trees without docstrings; the artifacts hash the bytes."""
    rel = "solvers/timeloop/kernel.py"
    before = _keys(copy, make_deps)
    path = copy / rel
    text = path.read_text()
    try:
        path.write_text(text.replace('"""', '"""Edited. ', 1))
        after = _keys(copy, make_deps)
    finally:
        path.write_text(text)
    assert before["study row"] == after["study row"] and before["line row"] == after["line row"]
    assert before["make simulate"] != after["make simulate"]


TRACE = r"""
import json, sys
root = sys.argv[1]
PACKAGES = ("pipeline", "solvers", "postprocess", "geometry")
seen = set()
def hook(frame, event, arg):
    f = frame.f_code.co_filename
    if event == "call" and f.startswith(root + "/") and f[len(root) + 1:].split("/")[0] in PACKAGES:
        seen.add(f[len(root) + 1:])
{setup}
sys.setprofile(hook)
{call}
sys.setprofile(None)
print(json.dumps(sorted(seen)))
"""

FRICTION = dict(setup="""
import numpy as np
from pipeline.caches.friction_curves import Friction, compute_curve
x, y = np.meshgrid(np.linspace(-1, 1, 21), np.linspace(-1, 1, 15), indexing="ij")
p3 = 1e9 * np.sqrt(np.clip(1 - x**2 - y**2, 0, None))""",
                call="compute_curve(p3, 0.5e-3, 0.5e-3, 10.0, Friction(params={'mu': 0.3}), 210e9, 0.3)")
ROW = dict(setup="""
from pipeline.study.context import load_context
from pipeline.study.tasks import MapTask, Simulation
from pipeline.study import worker
ctx = load_context("default", radiation=True)
task = MapTask(-0.01, 0.35, Simulation(duration=0.05, early_stop=True, final=0.02, window=0.02, level=10.0), None)""",
           call="worker.map_case(ctx, task)")


def _traced(code: dict) -> set[str]:
    r = subprocess.run([sys.executable, "-c", TRACE.format(**code), str(ROOT)], cwd=ROOT, capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    return set(json.loads(r.stdout.splitlines()[-1]))


def test_a_friction_curve_runs_only_code_of_its_key():
    ran = _traced(FRICTION)
    assert "solvers/contact/friction.py" in ran                 # the tracer sees the computation
    missing = ran - set(reached_files(friction_curves.CURVE_FUNCTIONS))
    assert not missing, f"code run for a friction curve but not in its key: {sorted(missing)}"


def test_a_study_row_runs_only_code_of_its_key():
    ensure_case("default")
    ran = _traced(ROW)
    assert "solvers/timeloop/driver.py" in ran
    missing = ran - set(reached_files(tuple(sorted(context.ROW_FUNCTIONS))))
    assert not missing, f"code run for a study row but not in its key: {sorted(missing)}"
