"""The line study's speed (issue 27: "100 curves with one vehicle (400 wheels) run in under 5 min on 2
cores"; issue 32: the same with the friction climate's columns): `run() -> str` gives the markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks line --update

1. **100 curves.**  A line of 100 curves, R = 50-600 m log-spaced (every radius different), speed and
   cant from the radius study's design rule (``pipeline.study.radius.design``), the C20 metro on dry
   rail (mu = 0.4), run as a line study (``make study``'s code: the runner, a local Dask cluster of two
   single-threaded workers) in a fresh build folder.  That folder shares (hard links) the wheel's modes,
   the rail's section mesh and rail.npz and the running surface's wave table (``build/rails/<rail>/
   surface/``: built once per rail and time step, ~130 s; a cache, not per-curve work); every moving
   rail kernel (one per wheel: each curve has its own speed and contact points) and the wave tables of
   the rail file's listed points (``build/rails/<rail>/points/``) are built inside the timed run.
2. **Screen first against the curve stage, side by side.**  Four curves (16 wheels) in one process:
   the curve stage's verdict (``run_curve``: contact, greens and the time loop for every wheel, no
   what-ifs) and the screen-first verdict (``run_screen_first``), alternating, rail kernels warm for
   both; with the screen-first path's cost per part (curving, contact, wheel modal data, rail kernel,
   screen, the time loop of the unstable wheels).
3. **The onset scan by the count against every level's poles.**  The same four curves' climate columns
   (``line_risk.risk_columns``), the scan as it is and with every level's poles located, side by side.
"""
from __future__ import annotations

import math
import os
import shutil
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

N_CURVES = 100
R_MIN, R_MAX = 50.0, 600.0
MU = 0.4
SIDE_BY_SIDE = (60.0, 110.0, 250.0, 480.0)


def line_csv(n: int = N_CURVES) -> str:
    from pipeline.study.radius import design

    out = ["id,chainage_m,radius_m,cant_mm,length_m,speed_kmh,vehicle,friction"]
    x = 0.0
    for i, R in enumerate(np.geomspace(R_MIN, R_MAX, n)):
        R = round(float(R), 2)
        v, cant = design(R)
        out.append(f"B{i:03d},{x:g},{R:g},{1e3 * cant:.0f},{30 + 0.25 * R:.0f},{v:g},c20_metro,{MU:g}")
        x += 30 + 0.25 * R + 300
    return "\n".join(out) + "\n"


def _fresh_build(src: Path, dst: Path) -> None:
    """dst: the wheels and the rail's mesh, rail.npz and surface table of src, hard-linked."""
    shutil.copytree(src / "wheels", dst / "wheels", copy_function=os.link)
    for rail in (src / "rails").iterdir():
        (dst / "rails" / rail.name).mkdir(parents=True)
        for f in ("section.msh", "rail.npz"):
            if (rail / f).exists():
                os.link(rail / f, dst / "rails" / rail.name / f)
        if (rail / "surface").exists():
            shutil.copytree(rail / "surface", dst / "rails" / rail.name / "surface", copy_function=os.link)


LOAD_MID: list = []


class _LoadWatch:
    """The 1-min load average sampled every 10 s while the line runs (2 of it are the run's own workers)."""

    def __init__(self):
        self.samples, self.done = [], threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        while not self.done.wait(10.0):
            self.samples.append(os.getloadavg()[0])

    def stop(self) -> list:
        self.done.set()
        self.thread.join()
        return self.samples


def hundred_curves(tmp: Path) -> dict:
    from pipeline.store import paths
    from pipeline.study.stage import run_study

    build = tmp / "build"
    _fresh_build(paths.build(), build)
    studies = tmp / "studies"
    studies.mkdir()
    (studies / "bench_line.csv").write_text(line_csv())
    (studies / "bench_line.toml").write_text('name = "bench_line"\nkind = "line"\ncurves = "bench_line.csv"\n'
                                             'base_curve = "r150"\n')
    old = {k: os.environ.get(k) for k in ("SQUEAL_BUILD_DIR", "SQUEAL_STUDY_DIR")}
    os.environ.update(SQUEAL_BUILD_DIR=str(build), SQUEAL_STUDY_DIR=str(studies))
    load0 = os.getloadavg()
    t0 = time.perf_counter()
    watch = _LoadWatch()
    try:
        run_study("bench_line", workers=2, out=tmp / "out", progress=False)
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    wall = time.perf_counter() - t0
    LOAD_MID[:] = watch.stop()
    import csv

    rows = list(csv.DictReader(open(tmp / "out" / "line.csv")))
    tab = list(csv.DictReader(open(tmp / "out" / "table.csv")))
    return {"wall": wall, "load0": load0, "load1": os.getloadavg(), "rows": rows, "load_mid": LOAD_MID,
            "worker_s": sum(float(r["wall_s"]) for r in tab),
            "kernels": len(list((build / "rails").glob("*/moving/*.npz"))),
            "tables": len(list((build / "rails").glob("*/points/*.npz")))}


def side_by_side() -> dict:
    from pipeline.study.line_input import LineRow, line_curves
    from pipeline.study.kinds import load_study
    from pipeline.curve import screen_first
    from pipeline.study.radius import design
    from pipeline.curve.stage import run_curve
    from pipeline.study.line_risk import risk_columns

    spec, _ = load_study("metro_line")
    spec = dict(spec, name="bench_side")
    folder = Path(tempfile.mkdtemp(prefix="bench_side_"))
    rows = []
    for i, R in enumerate(SIDE_BY_SIDE):
        v, cant = design(R)
        rows.append(LineRow(i, f"S{i}", 0.0, R, round(1e3 * cant), 50.0, v, "c20_metro", "dry", MU))
    curves = [c for c, _ in line_curves(spec, rows, folder).values()]
    t = {"curve stage": 0.0, "screen first": 0.0}
    parts: dict = {}
    agree, n_tl, n_unstable, same, risk = 0, 0, 0, 0, {}
    try:
        for curve in curves:                                # warm: kernels, curving, numba, modes
            screen_first.run_screen_first(curve, write=False)
        from pipeline.curve.curving import clear

        for curve in curves:
            clear()                                         # both paths solve the curving (memoised per process)
            t0 = time.perf_counter()
            full = {r["wheel"]: r for r in run_curve(curve, progress_bar=False, what_ifs=False)["rows"]}
            t1 = time.perf_counter()
            clear()
            screen_first.TIMES.clear()
            first = screen_first.run_screen_first(curve, write=False)["rows"]
            t2 = time.perf_counter()
            t["curve stage"] += t1 - t0
            t["screen first"] += t2 - t1
            for k, s in screen_first.TIMES.items():
                parts[k] = parts.get(k, 0.0) + s
            for r in first:
                agree += r["squeals"] == full[r["wheel"]]["squeals"]
                n_tl += bool(r["time_loop"])
                n_unstable += math.isfinite(r["screen_sigma"])
            for label, skip in (("count", True), ("roots", False)):
                t0 = time.process_time()
                risk[label] = risk_columns(curve, first) if skip else _every_level_located(curve, first)
                t[label] = t.get(label, 0.0) + time.process_time() - t0
            same += _same(risk["count"], risk["roots"])
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return {"t": t, "parts": parts, "wheels": 4 * len(curves), "agree": agree, "time_loop": n_tl, "same": same}


def _every_level_located(curve, rows) -> dict:
    """The row's risk columns with the onset scan locating the poles at every level (the scan before
    it read the count alone where no pole grows: ``pipeline.curve.onset.Screen.quiet``)."""
    from pipeline.curve.onset import Screen
    from pipeline.study.line_risk import risk_columns

    quiet = Screen.quiet
    Screen.quiet = lambda self, mu: False
    try:
        return risk_columns(curve, rows)
    finally:
        Screen.quiet = quiet


def _same(a: dict, b: dict) -> bool:
    return all(a[k] == b[k] or (isinstance(a[k], float) and math.isnan(a[k]) and math.isnan(b[k])) for k in a)


def run() -> str:
    load = os.getloadavg()
    sb = side_by_side()
    with tempfile.TemporaryDirectory(prefix="bench_line_") as d:
        h = hundred_curves(Path(d))
    rows = h["rows"]
    sq = [r for r in rows if r["squeals"] == "1"]
    noted = [r for r in rows if r["note"]]
    tl = sum(len(r["time_loop_wheels"].split()) for r in rows)
    n = len(rows)
    wheels = 4 * (n - len(noted))
    parts = sb["parts"]
    total = sum(parts.values())
    per = ", ".join(f"{k} {1e3 * v / sb['wheels']:.0f} ms" for k, v in parts.items())
    ratio = sb["t"]["curve stage"] / sb["t"]["screen first"]
    p = [float(r["p_squeal"]) for r in rows if r.get("p_squeal")]
    mid = h["load_mid"]
    return f"""## Line study: 100 curves, screen first (issue 27)

`benchmarks/line.py` (`python -m benchmarks line --update`); load average {load[0]:.1f} at the start ({'no other job running' if load[0] < 1.5 else '2 cores shared with other jobs: the times are those of a loaded machine'}).

**100 curves, 400 wheels, 2 Dask workers: {h['wall']:.0f} s wall** ({h['wall'] / 60:.1f} min; the target, 5 min,
{'met' if h['wall'] <= 300 else 'not met'}) for
{n} curves (R = {R_MIN:g}-{R_MAX:g} m, the C20 metro, mu = {MU:g}, speeds and cant of the radius study's design rule)
of which {len(noted)} have no steady curving state (recorded, not computed) and {len(sq)} squeal; {tl} of the
{wheels} wheels were unstable in the screen and run in the time loop (and radiate and listen where they squeal).
Every row with the friction climate's columns (issue 32, `pipeline/study/line_risk.py`: the default climate, every
wheel's onset scanned to the climate's top, the time loop's levels above onset where p_squeal > 0, CNOSSOS-EU rolling
noise and the expected excess): {sum(x > 0 for x in p)} curves can squeal in the climate (p_squeal > 0, mean
{(sum(p) / max(len(p), 1)):.3f}).  Before these columns (one friction value only): 304 s.
Load average {h['load0'][0]:.1f} before, {h['load1'][0]:.1f} after{f", {min(mid):.1f}-{max(mid):.1f} during the run (2 of it are its workers)" if mid else ""}.  Worker time {h['worker_s']:.0f} s in all
({h['worker_s'] / max(n, 1):.1f} s per curve); {h['kernels']} moving rail kernels and {h['tables']} listed-point
wave tables built inside the run (the running surface's table, built once per rail, ~130 s, was there: a cache).
The wall time includes starting the cluster and writing the outputs (table, figures, export).

**Screen first against the curve stage** ({len(SIDE_BY_SIDE)} curves, R = {', '.join(f'{r:g}' for r in SIDE_BY_SIDE)} m,
{sb['wheels']} wheels, one process, rail kernels warm for both): the curve stage (every wheel's contact, greens,
time loop, with the stages' files and figures) {sb['t']['curve stage']:.1f} s, screen first
{sb['t']['screen first']:.1f} s: **{ratio:.1f}x**; {sb['time_loop']} of {sb['wheels']} wheels run in the time loop,
the same squeal verdict at {sb['agree']} of {sb['wheels']} wheels.  Screen first per wheel ({1e3 * total / sb['wheels']:.0f} ms):
{per}.

**The climate's columns: the onset scan by the count against locating every level's poles** (the same
{len(SIDE_BY_SIDE)} curves, one process, CPU time): {sb['t']['count']:.1f} s against {sb['t']['roots']:.1f} s
(**{sb['t']['roots'] / sb['t']['count']:.1f}x**); the columns equal in every digit for {sb['same']} of
{len(SIDE_BY_SIDE)} curves.  Below its bracket the scan reads only the sign of the growth rate, so a level where
the argument principle counts no growing pole is passed on that count (`nyquist.no_growing_pole`: the winding
number of P on the unit circle) without the secant's roots and the Rouche margin; brentq evaluates the
bracket's ends itself, as before (the level's growth rate is kept per wheel, so they are not located twice).

How it was cut (cProfile first): the curve's rigid contact search memoised per shift (the bogie's Newton
asks for the same contact ~4 times in 5: 3x faster curving, the same numbers); the screen from arrays built
in memory (no wheel kernel, no files or figures for a stable wheel); a listed rail point's wave table
cached (a new speed: ~1 s instead of ~15 s); the running surface's table files held per worker; the rail
kernels' decay check reading each kernel file once per process (it read every kernel of the rail for every
case: quadratic in a line's length).
"""
