"""`make` on a minimal Debian 12 (debootstrap's minbase, a container image): no python3 until the Debian
packages are installed (docs/benchmarks.md, session 15).  Make's parse-time input checks run
pipeline/store/deps.py with /usr/bin/python3; they stopped `make` at once (`CASE=default: .`) before the
rule that installs the packages could run.  Now they wait: the packages (.apt-stamp) come first, as a
prerequisite of build/deps.mk, and Make restarts with python3 there.

Make runs in a copy of the repository's tracked files (as tests/test_make_plans.py) whose
debian-packages.txt lists nothing, so the package rule only writes its stamp; DEPS_PY names a python3
that is not there, as on such a machine.
"""
from __future__ import annotations

import os
import shutil
import subprocess

from tests.test_make_plans import ROOT, _sources


def test_make_installs_the_debian_packages_before_its_python_checks(tmp_path):
    tree = tmp_path / "repo"
    for f in _sources():
        (tree / f).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / f, tree / f)
    (tree / "debian-packages.txt").write_text("# nothing missing here\n")
    python3 = tmp_path / "usr/bin/python3"  # not there yet: the Debian packages bring it
    env = {k: v for k, v in os.environ.items() if k not in ("WHEEL", "RAIL", "CASE", "CURVE", "MAKEFLAGS", "MFLAGS")}
    r = subprocess.run(["make", "--no-print-directory", "-n", f"DEPS_PY={python3}", f"PY={tree / '.venv/bin/python'}"],
                       cwd=tree, env=env, capture_output=True, text=True)
    assert "CASE=default" not in r.stderr, r.stderr  # the parse-time check did not stop it
    assert (tree / ".apt-stamp").exists(), r.stdout + r.stderr  # the package rule ran...
    assert f"{python3} pipeline/store/deps.py" in r.stdout + r.stderr, r.stdout + r.stderr  # ...then deps.mk's
