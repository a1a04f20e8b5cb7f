"""Stability-screen benchmarks (solvers/stability/screen.py, pipeline/stability_map.py): `run() -> str`.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks stability

The default case's linear model (build/cases/default: contact and greens artifacts) loaded once;
then, side by side: the screen of one case (basis + roots polished on the exact characteristic
function, the `make stability` path), the screen sharing a basis without polishing (the map path),
and one position's map (the 330 (gamma_y, mu) cases of the map study) against the time loop's cost
for the same cases (the study's measured median per case, when its table exists).
"""
from __future__ import annotations

import csv
import time

import numpy as np

from benchmarks.timing import median_time
from pipeline.store import paths
from pipeline.stages.stability import case_linear_model
from solvers.stability.screen import Basis, screen


def run() -> str:
    from pipeline.study.screen import screen_rows
    from pipeline.study.definition import grid_of
    from pipeline.study.kinds import load_study

    _, lm, _, _ = case_linear_model("default")
    t_basis = median_time(lambda: Basis(lm), 5, warm=1)
    b = Basis(lm)
    t_exact = median_time(lambda: screen(lm, b), 5, warm=1)
    t_fast = median_time(lambda: screen(lm, b, polish=False), 10, warm=1)
    spec, _ = load_study("map")
    gammas, mus = grid_of(spec, False)
    t0 = time.perf_counter()
    rows = screen_rows("default", gammas, mus)
    t_map = time.perf_counter() - t0
    tl = ""
    table = paths.build() / "studies" / "map" / "map.csv"
    if table.exists():
        with open(table, newline="") as fh:
            w = [float(r["wall_s"]) for r in csv.DictReader(fh) if r.get("wall_s") not in (None, "", "nan")]
        if w:
            tl = (f"| time loop, same 330 cases (study's median {np.median(w):.2f} s per case, one core) | "
                  f"{330 * np.median(w):.0f} s | {330 * np.median(w) / t_map:.0f}x the screen |\n")
    return f"""## Stability screen

`python -m benchmarks stability`: default case (C20 on BV50, dy_WR = -15 mm, 38 wheel modes, 4096-lag rail
kernel), one core.

| what | time | note |
|---|---:|---|
| basis (transforms at every pole, LF grid of {b.Ygrid.shape[0]} x {b.Ygrid.shape[1]}) | {1e3 * t_basis:.0f} ms | once per structure |
| screen of the default case, exact roots (`make stability`) | {1e3 * (t_basis + t_exact):.0f} ms | basis + {1e3 * t_exact:.0f} ms |
| screen with a shared basis, first-order roots (maps) | {1e3 * t_fast:.1f} ms | per case |
| map of one position: {len(rows)} cases (`make stability-map`) | {t_map:.2f} s | {1e3 * t_map / len(rows):.1f} ms per case, linearisation per mu included |
{tl}"""
