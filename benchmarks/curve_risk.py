"""One curve's risk verdict (issue 32: under 30 s on 2 cores once the rail's tables exist), the commit before
this work's speed-ups and the current one side by side.

The curve is r75 under another name (its file copied to a temporary folder as ``bench_r75.toml``): the
C20 metro at 75 m, 31 km/h, the shipped ``default`` friction climate (its conditions' quantiles on
``pipeline.curve.risk.N_QUANTILES`` = 200 friction levels per condition), four wheels of the leading
bogie and four of the trailing one, every verdict column: onset friction, the stability screen, the
time loop, sound power, listening, the what-ifs, the risk, the whole train's pass-by with rolling noise.
Each commit runs in its own worktree (``git worktree add``) on the repository's build/ (the wheel's modes,
the rail's model and its kernel and surface-table caches, keyed by code: a first, untimed round builds what
a commit's keys lack and compiles its numba caches); the timed rounds remove the curve's folders first, so
that every stage of the curve runs.
"""
from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OLD = "3bbe3d3"   # main before the onset scan read the count of growing poles alone below its bracket
#                   (1e9bd0c -> 244246b, the parse caches and the pass-by in one pass: 44 -> 31 s CPU, docs/benchmarks.md)
ROUNDS = 2
NAME = "bench_r75"


def _run(repo: Path, curve: Path) -> tuple[float, float]:
    """(wall s, CPU s) of the curve stage of ``repo`` on ``curve``, its results removed first."""
    for sub in ("curves", "cases"):
        shutil.rmtree(ROOT / "build" / sub / NAME, ignore_errors=True)
    env = dict(os.environ, OMP_NUM_THREADS="1", SQUEAL_BUILD_DIR=str(ROOT / "build"))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "pipeline", "curve", "--curve", str(curve), "--no-progress"], cwd=repo,
                       env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        raise RuntimeError(f"the curve stage at {repo} failed:\n{r.stderr[-2000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def run() -> str:
    load = os.getloadavg()
    new = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                         check=True).stdout.strip()
    subprocess.run(["make", "-s", "--no-print-directory", "modes", "rail"], cwd=ROOT, check=True)
    rows = []
    with tempfile.TemporaryDirectory(prefix="curve-risk-") as d:
        curve = Path(d) / f"{NAME}.toml"
        shutil.copy(ROOT / "pipeline" / "curves" / "r75.toml", curve)
        trees = {}
        for label, commit in (("previous", OLD), ("current", new)):
            tree = Path(d) / label
            subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "-q", "--detach", str(tree), commit], check=True)
            trees[label] = (commit, tree)
        try:
            for label, (commit, tree) in trees.items():
                _run(tree, curve)                                 # untimed: the caches of the commit's keys
            for r in range(ROUNDS):
                for label, (commit, tree) in trees.items():
                    rows.append((r + 1, label, commit, *_run(tree, curve)))
        finally:
            for _, tree in trees.values():
                subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tree)], check=False)
            for sub in ("curves", "cases"):
                shutil.rmtree(ROOT / "build" / sub / NAME, ignore_errors=True)
    table = "\n".join(f"| {r} | {label} ({c}) | {w:.1f} s | {cpu:.1f} s |" for r, label, c, w, cpu in rows)
    best = {lab: min(w for _, label, _, w, _ in rows if label == lab) for lab in ("previous", "current")}
    return f"""## One curve's risk verdict (issue 32)

r75 (`pipeline/curves/r75.toml`, as `{NAME}`) through the curve stage with the shipped default friction
climate, both bogies, every column, the rail's tables built (`benchmarks/curve_risk.py`); the commit before
this work's speed-ups ({OLD}) and the current one alternately, {ROUNDS} timed rounds after an untimed one
each; target under 30 s on 2 cores.

| round | commit | wall | CPU (user + sys) |
|---|---|---:|---:|
{table}

Current / previous, wall at best: {best['current']:.1f} / {best['previous']:.1f} s
({best['previous'] / best['current']:.2f}x); load average {load[0]:.1f} at the start, {os.getloadavg()[0]:.1f} at the end
(the stage runs on one core: its wall time is about its CPU time on an idle machine).  Since {OLD} the onset scan
passes a level where no pole grows on the argument principle's count alone, and goes on above the onset up to the
climate's highest level for the windows of friction where a wheel squeals (more work, in less time)."""
