"""Study benchmarks (pipeline/study_*.py): `run() -> str` gives the markdown section.

    .venv/bin/python -m benchmarks.study [quick]

The creepage/friction map of SPEC 7 at one contact position (the default case, dy_WR = -15 mm:
30 creepages x 11 friction coefficients = 330 cases, the full model, at most 8 s of rolling
each) through the study runner on a local Dask cluster, from a fresh start (cluster start-up,
loading the case's artifacts, all cases, the outputs):

* as the study runs it (early stop at a limit cycle or after decay), with 1 and 2 workers;
* the worst case, every case the full 8 s of rolling (no early stop), with 1 and 2 workers.

Per-case cost: the worker's wall time of each case (the `wall_s` column of the table).  The
outputs go to a temporary folder (build/studies/ is left alone).  ``quick``: the --quick grid
(48 cases), for trying the benchmark itself.
"""
from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from pathlib import Path
from unittest import mock

import numpy as np

TARGET = 600.0            # s: the target for the 330-case map on 2 cores

def _study_text() -> str:
    """The benchmark's study file: the grid and the quick steps of pipeline/studies/map.toml (the one
    home of the map's grid), at the default case only."""
    import tomllib

    from pipeline.store import paths

    spec = tomllib.loads((paths.ROOT / "pipeline" / "studies" / "map.toml").read_text())
    lines = ['name = "bench"', 'kind = "map"', 'cases = ["default"]', "[grid]"]
    lines += [f"{k} = {v!r}" for k, v in spec["grid"].items()]
    lines += ["[quick]"] + [f"{k} = {v!r}" for k, v in spec["quick"].items()]
    return "\n".join(lines + ["[simulation]", "duration = 8.0", "early_stop = {early}", ""])


def _run(tmp: Path, early: bool, workers: int, quick: bool) -> dict:
    import csv

    import os

    from pipeline.study import stage as study_stage

    name = f"bench_{'early' if early else 'full'}"
    (tmp / f"{name}.toml").write_text(_study_text().replace('"bench"', f'"{name}"').format(early=str(early).lower()))
    os.environ["SQUEAL_STUDY_DIR"] = str(tmp)
    out = tmp / f"out_{name}_{workers}"
    t0 = time.perf_counter()
    study_stage.run_study(name, quick=quick, workers=workers, out=out, progress=False)
    wall = time.perf_counter() - t0
    run = json.loads((out / "runs.jsonl").read_text().splitlines()[-1])
    with open(out / "table.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    w = np.array([float(r["wall_s"]) for r in rows])
    t = np.array([float(r["t_end"]) for r in rows])
    reasons = {}
    for r in rows:
        reasons[r["stop_reason"]] = reasons.get(r["stop_reason"], 0) + 1
    return {"wall": wall, "tasks": run.get("run_wall_s", float("nan")), "n": len(rows), "median": float(np.median(w)),
            "mean": float(w.mean()), "max": float(w.max()), "sum": float(w.sum()), "rolling": float(t.sum()),
            "per_s": float(w.sum() / t.sum()), "reasons": reasons, "squeal": sum(float(r["L_F2"]) >= 10 for r in rows)}


def run(quick: bool = False) -> str:
    from benchmarks.__main__ import machine
    from pipeline.validation.make import ensure_case

    os.environ.setdefault("OMP_NUM_THREADS", "1")
    ensure_case("default")
    res = {}
    # _run points SQUEAL_STUDY_DIR at the temporary folder; the environment is restored for the next suites
    with mock.patch.dict(os.environ), tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for early in (True, False):
            for workers in (1, 2):
                res[early, workers] = r = _run(tmp, early, workers, quick)
                print(f"study bench: early_stop={early}, {workers} worker(s): {r['n']} cases in {r['wall']:.0f} s",
                      file=sys.stderr)
    load = " / ".join(f"{x:.1f}" for x in os.getloadavg())
    rows = []
    for (early, workers), r in res.items():
        rows.append(f"| {'early stop (as the study runs)' if early else 'every case 8 s (no early stop)'} | {workers} | "
                    f"{r['n']} | {r['wall']:.0f} s | {r['tasks']:.0f} s | {r['median']:.2f} / {r['mean']:.2f} / "
                    f"{r['max']:.2f} s | {r['rolling']:.0f} s | {1e3 * r['per_s']:.0f} ms |")
    full2 = res[False, 2]
    sc = {e: res[e, 1]["wall"] / res[e, 2]["wall"] for e in (True, False)}
    ends = ", ".join(f"{n} {k}" for k, n in sorted(res[True, 2]["reasons"].items()))
    n = res[True, 1]["n"]
    return f"""## Studies

`pipeline/study_*.py` on a local Dask cluster (`benchmarks/study.py`; one single-threaded worker process per
core, OMP_NUM_THREADS=1). The creepage/friction map of SPEC 7 at one contact position: the default case
(dy_WR = -15 mm), {n} cases{' (--quick grid)' if quick else ' (30 creepages x 11 friction coefficients)'}, the full
model (C20 modes below 7 kHz, BV50 moving kernel of 4096 lags), at most 8 s of rolling each; measured from a
fresh start: cluster start-up, loading the case's artifacts, all cases, the outputs (table, maps, summary).
Per case: the worker's wall time (median / mean / max); rolling: simulated time summed over the cases.
Machine: {machine()}; load average {load} at the end of the run.

| runs | workers | cases | wall time | of which the tasks | per case | rolling | worker time per s of rolling |
|---|---:|---:|---:|---:|---:|---:|---:|
{chr(10).join(rows)}

Target: the full map of one position (up to 8 s of rolling per case) in under {TARGET / 60:.0f} minutes on 2 cores:
**{'met' if full2['wall'] < TARGET else 'NOT met'}** even with every case rolling the full 8 s
({full2['wall']:.0f} s). Scaling from 1 to 2 workers: {sc[False]:.2f}x with 8 s cases, {sc[True]:.2f}x with early
stop (fixed costs: cluster start-up, loading the artifacts, numba loading its cache once per worker, the outputs:
{res[True, 2]['wall'] - res[True, 2]['tasks']:.0f} s). As the study runs (early stop) the runs ended: {ends};
{res[True, 2]['squeal']} of {n} cases squeal (L_F2 >= 10 dB) with the artifacts of this run.
"""


if __name__ == "__main__":
    print(run(quick="quick" in sys.argv[1:]))
