"""A user's curve and vehicle in a folder outside the repository (issue 33): `make curve CURVE=<path>`
runs it, leaves the work tree as it was (git status), and no provenance of its results says "-dirty"
when the tree was clean.  The curve is r75's, so its verdict must be r75's (a second run, compared with
the shipped curve's verdict.csv).  Reuses the built wheel modes, rail and caches; no what-ifs (~40 s)."""
from __future__ import annotations

import csv
import json
import shutil
import subprocess

import numpy as np

from pipeline.api import ROOT

NAME = "user_curve_outside"


def porcelain() -> str:
    return subprocess.run(["git", "status", "--porcelain"], cwd=ROOT, capture_output=True, text=True, check=True).stdout


def rows(path) -> dict:
    with open(path, newline="", encoding="utf-8") as fh:
        return {r["wheel"]: r for r in csv.DictReader(fh)}


def test_curve_outside_the_repository(tmp_path):
    project = tmp_path / "my_project"               # (Make cannot take a path with a space)
    project.mkdir()
    shutil.copy(ROOT / "pipeline/curves/r75.toml", project / f"{NAME}.toml")     # new mtime: Make runs it
    shutil.copy(ROOT / "geometry/vehicles/c20_metro.toml", project / "c20_metro.toml")   # the vehicle beside it
    subprocess.run(["make", "-s", "--no-print-directory", f"CURVE=r75", "curve"], cwd=ROOT, check=True,
                   capture_output=True)           # the shipped curve's verdict, to compare with
    before = porcelain()
    r = subprocess.run(["make", "--no-print-directory", "curve", f"CURVE={project / (NAME + '.toml')}", "NO_WHAT_IFS=1"],
                       cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    assert porcelain() == before, "the run changed the work tree"
    out = ROOT / "build" / "curves" / NAME
    got, ref = rows(out / "verdict.csv"), rows(ROOT / "build/curves/r75/verdict.csv")
    assert set(got) == set(ref) == {"a1o", "a1i", "a2o", "a2i"}
    for w in ref:
        for k in ("dy_wr", "gamma_y", "L_F2", "f_squeal", "squeals"):
            assert got[w][k] == ref[w][k], (w, k, got[w][k], ref[w][k])
    assert got["a1i"]["squeals"] == "1"
    if before == "":                                 # a clean tree: nothing may be recorded as dirty
        revs = [json.loads((out / "verdict.json").read_text())["__provenance__"]["git_revision"]]
        for f in sorted((ROOT / "build" / "cases" / NAME).glob("*/*.npz")):
            with np.load(f, allow_pickle=False) as z:
                if "__provenance__" in z.files:
                    revs.append(json.loads(str(z["__provenance__"]))["git_revision"])
        assert len(revs) > 8 and not [x for x in revs if "dirty" in x], revs
