"""What bounds the squeal limit cycle, and the reference's findings measured (issue 28).

    .venv/bin/python -m pipeline.validation.limit_cycle_runs        # ~1-3 min on one core (the cases' contact, greens built)

Runs the map study's simulation (``pipeline.study.worker``: the time loop from steady rolling plus
the lateral kick, early stop at the limit cycle, measures and L_W over the final 0.5 s; the map's
``[simulation]`` table) and the stability screen (``solvers.stability.screen``) at

* the limit cycle of each position at its case's settings (default: -15 mm; dy05, dy10; mu = 0.35,
  gamma_y = -0.014): records over the limit cycle, ``postprocess.limit_cycle_measures`` measures, the
  screen's root against the free mode (detuning), and the default case with the tangential
  compliance x 0.5 and x 2 (a sensitivity, the model unchanged);
* a scan of 4 creepages x 4 friction coefficients per position (growth rate beside amplitude);
* the slices of the reference's findings (5 creepages x 11 friction coefficients per position: the
  map's mu grid, its creepages -0.004, -0.012, -0.02, -0.04, -0.06), written as a map table
  (the map's columns) to build/studies/limit-cycle/slices.csv for tests/study/test_reference_behaviour.py.

Writes build/studies/limit-cycle/{cycles,scan,slices}.csv and docs/validation/68_limit_cycle.md with
its plots (``pipeline.validation.limit_cycle_doc``).
"""
from __future__ import annotations

import csv
import logging
import time
from pathlib import Path
import fcntl
import json

import numpy as np

from pipeline.store import paths, artifacts
from pipeline.study.kinds import load_study
from pipeline.study.tasks import Simulation
from pipeline.stages.stability import case_linear_model
from pipeline.study.context import load_context
from pipeline.caches.friction_curves import with_curves
from pipeline.study.screen import grid_roots, screen_rows
from pipeline.store.atomic import atomic_write, save_text
from pipeline.store.code_hash import code_key
from pipeline.validation.make import ensure_case
from pipeline.validation.limit_cycle_doc import write_doc

log = logging.getLogger("pipeline.validation.limit_cycle_runs")

CASES = ("dy05", "dy10", "default")
SCAN_GAMMAS = (-0.006, -0.014, -0.03, -0.05)
SCAN_MUS = (0.15, 0.3, 0.45, 0.6)
SLICE_GAMMAS = (-0.004, -0.012, -0.02, -0.04, -0.06)
SLICE_MUS = tuple(np.round(np.arange(0.10, 0.601, 0.05), 2))
COMPLIANCE_FACTORS = (0.5, 1.0, 2.0)


def out_dir() -> Path:
    return paths.build() / "studies" / "limit-cycle"


def simulation():
    spec, _ = load_study("map")
    return Simulation.of(spec["simulation"])


def run_point(ctx, sim, gamma_y: float, mu: float, contact=None):
    """(InteractionResult, the map's row, ``cycle_measures``) at (gamma_y, mu); ``contact``: another
    ContactModel than the case's curve for mu (a sensitivity)."""
    from postprocess.limit_cycle_measures import cycle_measures  # lazy: brings in numba, rocket_fft, scipy
    from solvers.timeloop.interaction import StopRule, simulate  # lazy: brings in numba, rocket_fft, scipy

    from pipeline.study.worker import _contact, _measures, _warm, _wheel  # lazy: brings in numba, rocket_fft, scipy

    cm = contact if contact is not None else _contact(ctx, mu)
    _warm(ctx, ctx.tangential)
    res = simulate(_wheel(ctx), ctx.rail_kernel, cm, dt=ctx.dt, v=ctx.v, gamma_y=gamma_y, gamma_x=ctx.gamma_x,
                   preload=ctx.preload, duration=sim.duration, tangential=ctx.tangential, normal=ctx.normal,
                   stop=StopRule(window=sim.window) if sim.early_stop else None,
                   store_every=max(1, int(round(0.01 / ctx.dt))), final=sim.final)
    row = {"case": ctx.case, "dy_wr": ctx.dy_wr, "gamma_y": gamma_y, "mu": mu} | _measures(ctx, res, sim)
    m = cycle_measures(res.F_final, res.slip_final, res.state_final, res.dt_final or res.dt, v=ctx.v,
                       gamma_y=gamma_y, s_nodes=cm.s_nodes, mu_nodes=cm.mu_nodes, slopes=cm.slopes, xi=res.xi_final)
    return res, row, m


def coupled_root(case: str, ctx, mu: float, gamma_y: float, f_lc: float) -> dict:
    """The screen's root nearest the limit-cycle frequency (or its 1/2, 1/3), its free mode (f_r,
    zeta), and the detuning of f_lc from f_r (``postprocess.limit_cycle_measures.sdof_detuning``)."""
    from postprocess.limit_cycle_measures import sdof_detuning  # lazy: brings in numba, rocket_fft, scipy
    from solvers.stability.screen import screen  # lazy: brings in numba


    _, lm, labels, f_open = case_linear_model(case, mu=mu, gamma_y=gamma_y)
    roots = [r for r in screen(lm) if r.mode >= 0]
    cand = [(abs(r.f_hz - f_lc / k) / r.f_hz, k, r) for r in roots for k in (1, 2, 3)]
    _, k, r = min(cand, key=lambda c: c[0])
    f_r, zeta = float(f_open[r.mode]), float(ctx.wheel["zeta"][r.mode])
    d_bw, d_db = sdof_detuning(f_lc / k, f_r, zeta)
    return {"label": str(labels[r.mode]), "harmonic": k, "f_root": r.f_hz, "sigma": r.sigma, "f_r": f_r,
            "zeta": zeta, "detuning_bw": d_bw, "response_db": d_db, "f_lc": f_lc}


def limit_cycles(sim) -> tuple[list[dict], dict]:
    """Each position's limit cycle at its case's settings: rows of measures and the records."""
    rows, records = [], {}
    for case in CASES:
        ctx = load_context(case)
        res, row, m = run_point(ctx, sim, ctx.gamma_y, ctx.mu)
        cr = coupled_root(case, ctx, ctx.mu, ctx.gamma_y, row["f_dominant"])
        rows.append(row | m | cr)
        cm = _curve(ctx, ctx.mu)
        records[case] = {"t": res.t_final, "F": res.F_final, "slip": res.slip_final, "state": res.state_final,
                         "curve": (cm.s_nodes, cm.mu_nodes, cm.slopes), "row": rows[-1]}
    return rows, records


def _curve(ctx, mu):
    from pipeline.study.worker import _contact  # lazy: brings in numba, rocket_fft, scipy

    return _contact(ctx, mu)


def compliance_check(sim) -> list[dict]:
    """The default case with its tangential compliance A1, A2 scaled (the thesis' factor 2 on the
    compliance [4.32]-[4.35]; it reports the results insensitive to it)."""
    ctx = load_context("default")
    out = []
    for fac in COMPLIANCE_FACTORS:
        cm = _curve(ctx, ctx.mu)
        cm = cm._replace(A1_nodes=fac * cm.A1_nodes, A2_nodes=fac * cm.A2_nodes)
        _, row, m = run_point(ctx, sim, ctx.gamma_y, ctx.mu, contact=cm)
        out.append({"factor": fac} | row | m)
    return out


def curve_check(sim) -> list[dict]:
    """The default case with its friction curve recomputed by TANG (``rf_curve`` on the static
    pressure) at the contact stage's sampling (18 + 5 nodes) and at twice as many nodes (36 + 10):
    how much the curve's sampling and Hermite interpolation near saturation move the limit cycle."""
    from solvers.contact.friction import rf_curve  # lazy: brings in numba, rocket_fft, scipy


    ctx = load_context("default")
    con = ctx.contact
    out = []
    for n_bend, n_plateau in ((18, 5), (36, 10)):
        rf = rf_curve(con["p3_static"], float(con["dx"]), float(con["dy"]), ctx.v, ctx.mu, n_bend=n_bend,
                      n_plateau=n_plateau)
        cm = _curve(ctx, ctx.mu)._replace(s_nodes=rf.s, mu_nodes=rf.mu_rf, slopes=rf.slope)
        _, row, m = run_point(ctx, sim, ctx.gamma_y, ctx.mu, contact=cm)
        out.append({"nodes": len(rf.s)} | row | m)
    return out


def mode_growth(case: str, label: str, gammas, mus) -> list[dict]:
    """The screen's growth rate (1/s) and frequency of the root continuing mode ``label`` at every
    (gamma_y, mu) of one position (``pipeline.study.screen.grid_roots``)."""
    c, lm0, labels, _ = case_linear_model(case)
    con, _ = artifacts.load_npz(paths.case_dir(case) / "contact.npz", "contact")
    con = with_curves(case, con, [float(m) for m in mus])      # the curves at mus (the friction cache)
    rows = []
    for mu, gy, roots in grid_roots(lm0, con, c["kinematics"]["speed"], gammas, mus, c["friction"]["mu"]):
        r = [r for r in roots if r.mode >= 0 and labels[r.mode] == label]
        rows.append({"case": case, "dy_wr": c["contact"]["dy_wr"], "gamma_y": float(gy), "mu": float(mu),
                     "label": label, "sigma": r[0].sigma if r else np.nan, "f_hz": r[0].f_hz if r else np.nan})
    return rows


def knees() -> list[dict]:
    """s_knee (m/s) of every friction curve of every position."""
    from postprocess.limit_cycle_measures import knee_slip  # lazy: brings in numba, rocket_fft, scipy


    rows = []
    for case in CASES:
        ctx = load_context(case, radiation=False, mus=SLICE_MUS)
        for mu in SLICE_MUS:
            cm = _curve(ctx, float(mu))
            rows.append({"case": case, "dy_wr": ctx.dy_wr, "mu": float(mu),
                         "s_knee": knee_slip(cm.s_nodes, cm.mu_nodes, cm.slopes)})
    return rows


def coupling() -> list[dict]:
    """The one-mode full-slip threshold of every (n,0,a) mode at every position: with F2 = mu F3
    the mode's vertical-lateral coupling destabilises it when kappa = Phi3 (Phi3 + mu Phi2) < 0
    (``solvers.stability.screen`` notes), i.e. for mu > mu_c = -Phi3 / Phi2 (Phi at the contact point,
    lateral positive toward the field side, vertical toward the ground)."""
    rows = []
    for case in CASES:
        w = load_context(case, radiation=False).wheel
        for i in range(len(w["f"])):
            if int(w["m"][i]) == 0 and str(w["cls"][i]) == "a" and 2 <= int(w["n"][i]) <= 5:
                p2, p3 = (float(x) for x in w["phi"][i])
                rows.append({"case": case, "label": f"({int(w['n'][i])},0,a)", "f_hz": float(w["f"][i]),
                             "phi2": p2, "phi3": p3, "mu_c": -p3 / p2 if p2 * p3 < 0 else np.inf})
    return rows


def scan(sim, gammas=SCAN_GAMMAS, mus=SCAN_MUS, with_screen: bool = True) -> list[dict]:
    """(gamma_y, mu) per position: the map's row, the limit-cycle measures and (``with_screen``) the
    screen's largest growth rate."""
    rows = []
    for case in CASES:
        ctx = load_context(case, mus=mus)          # the curves at mus: the friction cache
        scr = {(round(r["gamma_y"], 6), round(r["mu"], 3)): r for r in screen_rows(case, gammas, mus)} \
            if with_screen else {}
        for gy in gammas:
            for mu in mus:
                _, row, m = run_point(ctx, sim, float(gy), float(mu))
                s = scr.get((round(float(gy), 6), round(float(mu), 3)), {})
                rows.append(row | m | {"sigma_max": s.get("sigma_max", np.nan), "label_max": s.get("label_max", "")})
    return rows


def save_csv(path: Path, rows: list[dict]) -> None:
    keys = list(rows[0])
    with atomic_write(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


TABLES = ("cycles.csv", "compliance.csv", "scan.csv", "slices.csv", "curve.csv", "growth.csv", "knees.csv",
          "coupling.csv")


def run_key() -> dict:
    """What the tables depend on: the code ``main`` reaches (``pipeline.store.code_hash``), the map study's
    file (its simulation settings) and the cases' contact and greens artifacts (size and time: a rebuilt
    artifact is a new input)."""
    files = [paths.ROOT / "pipeline" / "studies" / "map.toml"]
    files += [paths.case_dir(c) / f"{n}.npz" for c in CASES for n in ("contact", "greens")]
    return {"code": code_key("pipeline.validation.limit_cycle_runs:main"),
            "inputs": {str(f): [f.stat().st_size, f.stat().st_mtime_ns] for f in files}}


def tables() -> Path:
    """The folder of the tables (build/studies/limit-cycle/), run again (``main``) when they are missing or
    their key (``run_key``) changed; the cases' contact and greens are built through Make first.  One run
    at a time (a lock file): a second caller waits and then finds them up to date."""
    for case in CASES:
        ensure_case(case)
    out = out_dir()
    out.mkdir(parents=True, exist_ok=True)
    with open(out / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        key = out / "key.json"
        fresh = key.exists() and json.loads(key.read_text()) == run_key() and all((out / t).exists() for t in TABLES)
        if not fresh:
            log.info("limit-cycle tables missing or stale: running them (%s)", out)
            _run()
    return out


def main() -> int:
    """Run the tables and write docs/validation/68_limit_cycle.md (always; ``tables()`` reuses them)."""
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    for case in CASES:
        ensure_case(case)
    out_dir().mkdir(parents=True, exist_ok=True)
    with open(out_dir() / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        _run()
    return 0


def _run() -> None:
    t0 = time.perf_counter()
    sim = simulation()
    out = out_dir()
    out.mkdir(parents=True, exist_ok=True)
    cycles, records = limit_cycles(sim)
    save_csv(out / "cycles.csv", cycles)
    comp = compliance_check(sim)
    save_csv(out / "compliance.csv", comp)
    sc = scan(sim)
    save_csv(out / "scan.csv", sc)
    sl = scan(sim, SLICE_GAMMAS, SLICE_MUS, with_screen=False)
    save_csv(out / "slices.csv", sl)
    curves = curve_check(sim)
    save_csv(out / "curve.csv", curves)
    growth = (mode_growth("dy05", "(2,0,a)", (-0.004, -0.02), (0.1, 0.15))
              + mode_growth("default", "(2,0,a)", (-0.012, -0.04), (0.2, 0.25, 0.3)))
    save_csv(out / "growth.csv", growth)
    save_csv(out / "knees.csv", knees())
    save_csv(out / "coupling.csv", coupling())
    write_doc(cycles, records, comp, sc, sl, curves)
    save_text(json.dumps(run_key(), indent=1), out / "key.json")
    log.info("limit cycle study in %.0f s -> %s, docs/validation/68_limit_cycle.md", time.perf_counter() - t0, out)


if __name__ == "__main__":
    raise SystemExit(main())
