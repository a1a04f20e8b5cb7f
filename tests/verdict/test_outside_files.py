"""A user's curve file outside the clone (issue 33): ``make curve CURVE=<path>`` and the Python API
(``pipeline.api.curve_verdict(<path>)``) run it, the vehicle it names found beside it (a name geometry/vehicles/ does not have), its
results in build/curves/<file stem>/; the repository stays as it was (``git status``) and, from a clean tree,
the verdict's provenance is not "-dirty".  The curve is r300 (the C20 metro at 300 m) under other names,
so its wheels' operating points must be the shipped r300's."""
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from pipeline.api import curve_verdict
from pipeline.curve.curving import solve_curve

ROOT = Path(__file__).resolve().parents[2]
STEM = "t_outside_r300"


def _status() -> str:
    return subprocess.run(["git", "status", "--porcelain"], cwd=ROOT, capture_output=True, text=True,
                          check=True).stdout


@pytest.fixture
def project(tmp_path):
    """A project folder outside the clone: the curve and its vehicle side by side."""
    assert ROOT not in tmp_path.resolve().parents
    text = (ROOT / "pipeline/curves/r300.toml").read_text().replace('vehicle = "c20_metro"', 'vehicle = "my_metro"')
    (tmp_path / f"{STEM}.toml").write_text(text)
    (tmp_path / "my_metro.toml").write_text((ROOT / "geometry/vehicles/c20_metro.toml").read_text()
                                            .replace('name = "c20_metro"', 'name = "my_metro"'))
    yield tmp_path
    for d in (ROOT / "build" / "curves" / STEM, ROOT / "build" / "cases" / STEM):
        shutil.rmtree(d, ignore_errors=True)


def _verdict() -> tuple[dict, dict]:
    doc = json.loads((ROOT / "build" / "curves" / STEM / "verdict.json").read_text())
    return {r["wheel"]: r for r in doc["payload"]}, doc["__provenance__"]


def test_a_curve_file_outside_the_clone(project):

    before = _status()
    env = dict(os.environ, OMP_NUM_THREADS="1")
    r = subprocess.run(["make", "-s", "--no-print-directory", "curve", f"CURVE={project / f'{STEM}.toml'}",
                        "NO_WHAT_IFS=1"], cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
    assert r.returncode == 0, r.stderr[-3000:]
    rows, prov = _verdict()
    ref = {w.wheel: w for w in solve_curve("r300").wheels}             # the shipped curve and vehicle
    assert set(rows) == set(ref) == {"a1o", "a1i", "a2o", "a2i"}
    for w, row in rows.items():
        assert row["gamma_y"] == ref[w].gamma_y and row["dy_wr"] == ref[w].dy_wr
    assert prov["config"]["vehicle"]["name"] == "my_metro"
    cases = ROOT / "build" / "curves" / STEM / "cases"
    assert sorted(p.name for p in cases.glob("*.toml")) == [f"{b}{a}{s}.toml" for b in "ab" for a in "12" for s in "io"]
    # the Python API on the same file: Make finds its verdict up to date, the API reads it into a table
    v = curve_verdict(project / f"{STEM}.toml", what_ifs=False, quiet=True)
    assert v.csv == ROOT / "build" / "curves" / STEM / "verdict.csv" and list(v.table.wheel) == list(rows)
    assert [bool(x) for x in v.table.squeals] == [rows[w]["squeals"] for w in v.table.wheel]
    again, prov = _verdict()
    assert _status() == before                                       # nothing written in the repository
    if not before:                      # a clean clone: a clean provenance, the verdict's and every stage's
        revs = [prov["git_revision"]]
        for f in sorted((ROOT / "build" / "cases" / STEM).glob("*/*.npz")):
            with np.load(f, allow_pickle=False) as z:
                if "__provenance__" in z.files:
                    revs.append(json.loads(str(z["__provenance__"]))["git_revision"])
        assert len(revs) > 8 and not [x for x in revs if "dirty" in x], revs
