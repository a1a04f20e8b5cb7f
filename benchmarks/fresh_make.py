"""`make` on a fresh clone, the previous setup and stages against the current ones, side by side
(issue 15: under 90 s on 2 cores, system packages present, venv not).

Each round clones the repository at a commit into a temporary folder and times a plain `make`
there (the default case end to end: the venv, every stage, the report), the previous commit
(``OLD``, before the fast-setup work) and the current one alternately, so that both meet the
machine in the same state.  Every run gets an empty cache folder (``XDG_CACHE_HOME``): no pip or
uv download cache, no FFCx forms, no Mesa shaders, no matplotlib font list -- as on a new machine.
It needs git and the package registries (pip / uv download the venv's packages).
"""
from __future__ import annotations

import os
import resource
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OLD = "c9e4a02"        # main before issue 15's fresh-make work: pip setup, renders with 8x MSAA, 200 decay frequencies
ROUNDS = 2


def fresh_make(commit: str) -> tuple[float, float]:
    """(wall s, CPU s of make and its children) of `make` in a fresh clone at ``commit``."""
    with tempfile.TemporaryDirectory(prefix="fresh-make-") as d:
        repo = Path(d) / "repo"
        subprocess.run(["git", "clone", "-q", str(ROOT), str(repo)], check=True)
        subprocess.run(["git", "-C", str(repo), "checkout", "-q", commit], check=True)
        # a user's shell: not `make bench`'s variables (its OMP_NUM_THREADS=1 made the previous Makefile's
        # nproc, and so its make, serial)
        env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "CASE", "WHEEL",
                                                               "RAIL", "BUILD", "PY", "OMP_NUM_THREADS")}
        env["XDG_CACHE_HOME"] = str(Path(d) / "cache")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        out = subprocess.run(["make"], cwd=repo, env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if out.returncode != 0:
            raise RuntimeError(f"make at {commit} failed:\n{out.stdout[-2000:]}\n{out.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def run() -> str:
    new = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                         check=True).stdout.strip()
    rows = []
    for r in range(ROUNDS):
        for label, commit in (("previous", OLD), ("current", new)):
            wall, cpu = fresh_make(commit)
            rows.append((r + 1, label, commit, wall, cpu))
    table = "\n".join(f"| {r} | {label} ({c}) | {w:.1f} s | {cpu:.0f} s |" for r, label, c, w, cpu in rows)
    old_w = [w for _, label, _, w, _ in rows if label == "previous"]
    new_w = [w for _, label, _, w, _ in rows if label == "current"]
    return f"""## Fresh make (issue 15)

`make` on a fresh clone (the default case end to end, the venv included; system packages present,
every cache empty), the previous setup and stages ({OLD}) and the current ones alternately, {ROUNDS}
rounds (`benchmarks/fresh_make.py`); target under 90 s on 2 cores.

| round | commit | wall | CPU (user + sys) |
|---|---|---:|---:|
{table}

Current / previous, wall: {min(new_w):.1f} / {min(old_w):.1f} s at best ({min(old_w) / min(new_w):.2f}x),
{max(new_w):.1f} / {max(old_w):.1f} s at worst."""
