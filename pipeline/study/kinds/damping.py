"""Wheel modal damping study (SPEC 7), automated: solvers.study.damping_procedure decides which
simulations it needs (the full model, then the squealing mode alone with the suspension at
bisected damping values, ...); they run on Dask through the study runner and are stored in the
table under their labels, so a resumed study replays the procedure from the table and only
runs what is missing.

Outputs: table.csv (every simulation), steps.csv (per step: full-model L_F2 and frequency, the
squealing mode, its critical damping bracket), damping.png, summary.md.
"""
from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from pipeline.store import paths
from pipeline.config.loader import config_hash, Field
from pipeline.study.results_table import ResultsTable
from pipeline.progress import progress as progress_bar
from pipeline.study.runner import Task, pending, run_tasks
from pipeline.study.tasks import DampingTask, Simulation
from solvers.study import Outcome, damping_procedure
from pipeline.study.context import load_context
from postprocess.plots.study import damping_figure
from pipeline.store.artifacts import save_csv
from pipeline.store.atomic import save_figure, save_text
from pipeline.study.schemas import COMMON, OPERATING, SIMULATION

log = logging.getLogger("pipeline.study")

COLUMNS = {"step": int, "model": str, "mode": int, "zeta_mode": float, "n_modes": int, "L_F2": float,
           "f_dominant": float, "F2_pp": float, "F2_mean": float, "contact_loss": float, "stop_reason": str,
           "t_end": float, "L_W": float, "f_sound": float, "wall_s": float, "worker": str}
STEP_COLUMNS = ["step", "L_F2", "f_dominant", "mode", "label", "f_mode", "zeta_nominal", "zeta_lo", "zeta_hi",
                "bisection_model", "runs", "excluded", "note"]


# the study file's keys (pipeline/studies/<name>.toml with kind = "damping")
SCHEMA = COMMON | {
    "operating": OPERATING,
    "bisection": {
        "zeta_max": Field(float, min=1e-4, max=1.0, default=0.1,
                          doc="upper end of the bracket: a mode still squealing there ends the study"),
        "rel_tol": Field(float, min=1e-3, max=1.0, default=0.05,
                         doc="stop when zeta_hi / zeta_lo - 1 <= rel_tol (geometric bisection)"),
    },
    "procedure": {
        "max_steps": Field(int, min=1, max=30, default=8, doc="modes damped at most"),
        "mode_match": Field(float, min=0.001, max=0.5, default=0.05,
                            doc="the squeal frequency must be within this (relative) of the mode's"),
    },
    "simulation": SIMULATION,
}


def operating(spec: dict, ctx) -> tuple[float, float]:
    op = spec["operating"]
    return (ctx.mu if op["mu"] is None else op["mu"]), (ctx.gamma_y if op["gamma_y"] is None else op["gamma_y"])


def run(spec: dict, src: str, out: Path, *, quick: bool, client, progress: bool = True) -> dict:
    from pipeline.study.worker import damping_case  # lazy: brings in numba, rocket_fft, scipy

    case = spec["cases"][0]
    ctx = load_context(case, radiation=False, mus=[m for m in [spec["operating"]["mu"]] if m is not None])
    mu, gamma_y = operating(spec, ctx)
    sim, bis, proc = spec["simulation"], spec["bisection"], spec["procedure"]
    run_as = Simulation.of(sim)
    if quick:
        bis = bis | {"rel_tol": max(bis["rel_tol"], 0.25)}
    inputs = config_hash({"context": ctx.inputs, "simulation": sim, "mu": mu, "gamma_y": gamma_y})
    table = ResultsTable(out / "table.csv", COLUMNS)
    table.open({inputs})
    gen = damping_procedure(ctx.wheel["zeta"], ctx.wheel["f"], ctx.flexible, level=sim["squeal_level"],
                            zeta_max=bis["zeta_max"], rel_tol=bis["rel_tol"], max_steps=proc["max_steps"],
                            mode_match=proc["mode_match"])
    stats = {"total": 0, "done_before": 0, "submitted": 0}
    bar = progress_bar(unit="run", desc=spec["name"], enabled=progress)
    keys = []
    try:
        batch = next(gen)
        while True:
            tasks = [Task(r.label, inputs, case,
                          DampingTask(step=r.step, model=r.model, mode=r.mode, modes=tuple(r.modes),
                                      zeta=tuple(r.zeta), zeta_mode=r.zeta[r.mode] if r.mode >= 0 else float("nan"),
                                      mu=mu, gamma_y=gamma_y, sim=run_as))
                     for r in batch]
            todo = pending(tasks, table)
            stats["total"] += len(tasks)
            stats["done_before"] += len(tasks) - len(todo)
            stats["submitted"] += len(todo)
            if todo:
                run_tasks(tasks, damping_case, table, client.get(), {case: ctx}, desc=spec["name"], progress=False)
            bar.update(len(tasks))
            keys += [t.key for t in tasks]
            rows = [table.rows[t.key] for t in tasks]
            try:
                batch = gen.send([Outcome(r["L_F2"], r["f_dominant"]) for r in rows])
            except StopIteration as stop:
                result = stop.value
                break
    finally:
        bar.close()
    write_outputs(spec, src, out, quick, ctx, mu, gamma_y, bis, result, [table.rows[k] for k in keys])
    return stats


def write_outputs(spec, src, out: Path, quick, ctx, mu, gamma_y, bis, result, rows) -> None:
    level = spec["simulation"]["squeal_level"]
    steps = []
    for s in result.steps:
        d = dict(vars(s))
        d["mode"] = -1 if s.mode is None else s.mode
        d["label"] = ctx.label(s.mode) if s.mode is not None else ""
        d["f_mode"] = float(ctx.wheel["f"][s.mode]) if s.mode is not None else float("nan")
        d["excluded"] = " ".join(ctx.label(j) for j in s.excluded)
        steps.append(d)
    save_csv(out / "steps.csv", STEP_COLUMNS, ([d[c] for c in STEP_COLUMNS] for d in steps))
    labels = {i: ctx.label(i) for i in range(len(ctx.wheel["f"]))}
    title = (f"{ctx.case}: dy_WR = {1e3 * ctx.dy_wr:.0f} mm, mu = {mu:g}, gamma_y = {gamma_y:g}; "
             f"bisection to zeta_hi/zeta_lo - 1 <= {bis['rel_tol']:g}")
    save_figure(damping_figure(steps, rows, labels, title, level), out / "damping.png", dpi=90)
    lines = ["| step | full model L_F2 (dB) | f (Hz) | squealing mode | f_mode (Hz) | zeta before | critical zeta "
             "bracket | bisection in | runs | note |", "|---:|---:|---:|---|---:|---:|---|---|---:|---|"]
    def g(x, fmt):
        return format(x, fmt) if np.isfinite(x) else ""

    for d in steps:
        br = f"{d['zeta_lo']:.3g} .. {d['zeta_hi']:.3g}" if np.isfinite(d["zeta_hi"]) else ""
        lines.append(f"| {d['step']} | {g(d['L_F2'], '.1f')} | {g(d['f_dominant'], '.0f')} | {d['label']} | "
                     f"{g(d['f_mode'], '.0f')} | {g(d['zeta_nominal'], '.3g')} | {br} | {d['bisection_model']} | "
                     f"{d['runs']} | {d['note']}{' (taken out: ' + d['excluded'] + ')' if d['excluded'] else ''} |")
    crit = [d for d in steps if np.isfinite(d["zeta_hi"])]
    walls = np.array([r["wall_s"] for r in rows], float)
    text = f"""# Study `{spec['name']}`{' (quick)' if quick else ''}: wheel modal damping (SPEC 7)

{spec['description']}

Definition `{paths.shown(src)}`; case `{ctx.case}` (dy_WR = {1e3 * ctx.dy_wr:.0f} mm), mu = {mu:g}, gamma_y = {gamma_y:g}.
Procedure (solvers/study.py `damping_procedure`): simulate the full wheel model; if it squeals (L_F2 >= {level:g} dB)
at a wheel mode (dominant frequency within {100 * spec['procedure']['mode_match']:g} % of the mode's), find that
mode's squeal-critical damping with a wheel of only that mode plus the suspension modes (rail and contact as in the
case) by geometric bisection between its present damping and zeta_max = {bis['zeta_max']:g}, to the tolerance
zeta_hi / zeta_lo - 1 <= {bis['rel_tol']:g} (squeal at zeta_lo, none at zeta_hi); put zeta_hi into the full model
and repeat. When the mode does not squeal alone, or squeals again in the full model, the bisection runs in the full
model. {len(rows)} simulations (at most {spec['simulation']['duration']:g} s of rolling each), worker time
{walls.sum():.0f} s.

**Result: {result.end}.** Succession of squealing modes: {' -> '.join(d['label'] for d in steps if d['label']) or 'none'}.
Critical damping: {', '.join(f"{d['label']} {d['zeta_lo']:.3g} .. {d['zeta_hi']:.3g}" for d in crit) or 'none found'}.

{chr(10).join(lines)}

![damping study](damping.png)

Tables: `steps.csv` (this table), `table.csv` (every simulation: step, model, mode, zeta_mode, L_F2, ...).
"""
    save_text(text, out / "summary.md")
