"""Creepage/friction map (SPEC 7): every (gamma_y, mu) of the grid at every contact position
(one case file per position), the full model; L_F2, the dominant force frequency, L_W and the
dominant sound frequency (sound power for L_F2 >= the squeal level, SPEC 6).

Outputs: table.csv (the runner's append-only table), map.csv (the same rows in grid order,
without the bookkeeping columns), map_<case>.png (colour maps over (gamma_y, mu)), summary.md.
"""
from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from pipeline.store import paths
from pipeline.config.loader import config_hash, Field
from pipeline.study.results_table import ResultsTable
from pipeline.study.runner import Task, pending, run_tasks
from pipeline.study.definition import grid_of
from pipeline.study.kinds import load_study
from pipeline.study.tasks import MapTask, Simulation
from pipeline.study.screen import screen_rows
from pipeline.study.context import load_context
from postprocess.plots.study import map_figure, mode_categories
from pipeline.store.artifacts import save_csv
from pipeline.store.atomic import save_figure, save_text
from pipeline.study.schemas import COMMON, GAMMA, MU, SIMULATION, STEP

log = logging.getLogger("pipeline.study")

COLUMNS = {"case": str, "dy_wr": float, "gamma_y": float, "mu": float, "L_F2": float, "f_dominant": float,
           "L_W": float, "f_sound": float, "F2_pp": float, "F2_mean": float, "contact_loss": float,
           "stop_reason": str, "t_end": float, "wall_s": float, "worker": str}
MEASURES = ("L_F2", "f_dominant", "L_W", "f_sound")


# the study file's keys (pipeline/studies/<name>.toml with kind = "map")
SCHEMA = COMMON | {
    "grid": {
        "gamma_y_first": Field(**GAMMA, doc="first lateral creepage"),
        "gamma_y_last": Field(**GAMMA),
        "gamma_y_step": Field(**STEP, max=0.1),
        "mu_first": Field(**MU, doc="friction coefficients (any: their curves are built on each case's contact and cached by value)"),
        "mu_last": Field(**MU),
        "mu_step": Field(**STEP, max=1.0),
    },
    "quick": {
        "gamma_y_step": Field(**STEP, max=0.1, doc="coarser grid of --quick (same first values)"),
        "mu_step": Field(**STEP, max=1.0),
    },
    "simulation": SIMULATION,
}


def map_mus(study: str = "map", quick: bool = False) -> np.ndarray:
    """The friction coefficients of a map study's grid (``pipeline/studies/map.toml``: the one
    home of the map's mu grid)."""
    return grid_of(load_study(study)[0], quick)[1]


def case_key(case: str, gamma_y: float, mu: float) -> str:
    return f"{case}|gamma_y={gamma_y:+.5f}|mu={mu:.3f}"


def screened(spec: dict, quick: bool) -> dict:
    """{case_key: sigma_max} of the stability screen over the grid (pipeline.study.screen), when the
    study sets simulation.screen_margin; else {}."""
    if spec["simulation"].get("screen_margin") is None:
        return {}

    gammas, mus = grid_of(spec, quick)
    return {case_key(r["case"], r["gamma_y"], r["mu"]): r["sigma_max"]
            for case in spec["cases"] for r in screen_rows(case, gammas, mus)}


def tasks_of(spec: dict, src: str, contexts: dict, quick: bool) -> list[Task]:
    gammas, mus = grid_of(spec, quick)
    sim = spec["simulation"]
    run_as = Simulation.of(sim)
    sigma = screened(spec, quick)
    tasks = []
    for case, ctx in contexts.items():
        inputs = config_hash({"context": ctx.inputs, "simulation": sim})
        for gy in gammas:
            for mu in mus:
                key = case_key(case, gy, mu)
                ruled_out = key in sigma and sigma[key] < -sim["screen_margin"]
                tasks.append(Task(key, inputs, case, MapTask(gamma_y=float(gy), mu=float(mu), sim=run_as,
                                                             screened=float(sigma[key]) if ruled_out else None)))
    return tasks


def run(spec: dict, src: str, out: Path, *, quick: bool, client, progress: bool = True) -> dict:
    from pipeline.study.worker import map_case  # lazy: brings in numba, rocket_fft, scipy

    gammas, mus = grid_of(spec, quick)
    lines = 0                                        # the table's lines so far (a header and a row per case)
    if (out / "table.csv").exists():
        with open(out / "table.csv") as fh:
            lines = sum(1 for _ in fh)
    if lines - 1 < len(gammas) * len(mus) * len(spec["cases"]):
        client.start()                               # cases to run: the cluster starts while their data load
    contexts = {case: load_context(case, mus=mus) for case in spec["cases"]}
    tasks = tasks_of(spec, src, contexts, quick)
    table = ResultsTable(out / "table.csv", COLUMNS)
    table.open({t.inputs for t in tasks})
    todo = pending(tasks, table)
    stats = {"total": len(tasks), "done_before": len(tasks) - len(todo), "submitted": len(todo)}
    if todo:
        r = run_tasks(tasks, map_case, table, client.get(), contexts, desc=spec["name"],
                      progress=progress)
        stats |= {"run_wall_s": round(r.wall, 3), "dask_workers": r.workers}
    write_outputs(spec, src, out, quick, contexts, tasks, table)
    return stats


def fields_of(rows: dict, case: str, gammas, mus) -> dict:
    """{measure: (len(mus), len(gammas)) array} of one position, NaN where missing."""
    out = {m: np.full((len(mus), len(gammas)), np.nan) for m in MEASURES + ("wall_s", "t_end")}
    for i, mu in enumerate(mus):
        for j, gy in enumerate(gammas):
            r = rows.get(case_key(case, gy, mu))
            if r is not None:
                for m in out:
                    out[m][i, j] = r[m]
    return out


def write_outputs(spec, src, out: Path, quick: bool, contexts: dict, tasks: list, table: ResultsTable) -> None:
    gammas, mus = grid_of(spec, quick)
    level = spec["simulation"]["squeal_level"]
    keys = [t.key for t in tasks]
    rows = {k: table.rows[k] for k in keys if k in table.rows}
    cols = [c for c in COLUMNS if c != "worker"]
    save_csv(out / "map.csv", cols, ([rows[k][c] for c in cols] for k in keys if k in rows))
    parts = [f"# Study `{spec['name']}`{' (quick grid)' if quick else ''}: creepage/friction map (SPEC 7)\n",
             f"{spec['description']}\n",
             f"Definition `{paths.shown(src)}`; {len(gammas)} creepages gamma_y = {gammas[0]:g} .. {gammas[-1]:g} x {len(mus)} "
             f"friction coefficients mu = {mus[0]:g} .. {mus[-1]:g} at {len(contexts)} contact position(s): "
             f"{len(rows)} of {len(keys)} cases done. Each case: the full model from the case's artifacts, at most "
             f"{spec['simulation']['duration']:g} s of rolling"
             f"{' (early stop at a limit cycle or after decay)' if spec['simulation']['early_stop'] else ''}; "
             f"measures over the final {spec['simulation']['final']:g} s; squeal when L_F2 >= {level:g} dB, "
             f"sound power only then. Tables: `table.csv` (as run), `map.csv` (grid order).\n"]
    walls = np.array([r["wall_s"] for r in rows.values()], float)
    if walls.size:
        parts.append(f"Cost per case (worker wall time): median {np.median(walls):.2f} s, mean {walls.mean():.2f} s, "
                     f"max {walls.max():.2f} s; {walls.sum():.0f} s of worker time in all.\n")
    for case, ctx in contexts.items():
        F = fields_of(rows, case, gammas, mus)
        title = f"{case}: dy_WR = {1e3 * ctx.dy_wr:.0f} mm, v = {3.6 * ctx.v:.0f} km/h"
        modes = (np.asarray(ctx.wheel["f"], float), [ctx.label(i) for i in range(len(ctx.wheel["f"]))])
        save_figure(map_figure(gammas, mus, F, title, level, modes=modes), out / f"map_{case}.png", dpi=90)
        L = F["L_F2"]
        sq = np.isfinite(L) & (L >= level)
        reasons = {}
        for r in rows.values():
            if r["case"] == case:
                reasons[r["stop_reason"]] = reasons.get(r["stop_reason"], 0) + 1
        parts.append(f"## {title}\n")
        if ctx.radiation is None:
            parts.append(f"Sound power not computed: {ctx.radiation_note}.\n")
        parts.append(f"![map {case}](map_{case}.png)\n")
        parts.append(f"{int(sq.sum())} of {int(np.isfinite(L).sum())} cases squeal; runs ended: "
                     + ", ".join(f"{n} {k}" for k, n in sorted(reasons.items())) + ".\n")
        if sq.any():
            i, j = np.unravel_index(np.nanargmax(np.where(sq, L, -np.inf)), L.shape)
            parts.append(f"Loudest: gamma_y = {gammas[j]:g}, mu = {mus[i]:g}: L_F2 = {L[i, j]:.1f} dB at "
                         f"{F['f_dominant'][i, j]:.0f} Hz, L_W = {F['L_W'][i, j]:.1f} dB at {F['f_sound'][i, j]:.0f} Hz.\n")
        head = "| gamma_y \\ mu | " + " | ".join(f"{m:g}" for m in mus) + " |"
        lines = ["L_F2 (dB re 1 N; **bold**: squeal, f in Hz):\n", head, "|---:|" + "---:|" * len(mus)]
        for j, gy in enumerate(gammas):
            cells = []
            for i in range(len(mus)):
                v = L[i, j]
                if not np.isfinite(v):
                    cells.append("")
                elif sq[i, j]:
                    cells.append(f"**{v:.0f}** ({F['f_dominant'][i, j]:.0f})")
                else:
                    cells.append(f"{v:.0f}")
            lines.append(f"| {gy:g} | " + " | ".join(cells) + " |")
        parts.append("\n".join(lines) + "\n")
        parts.append(lw_table(F, gammas, mus, level, modes))
    save_text("\n".join(parts), out / "summary.md")


def lw_table(F: dict, gammas, mus, level: float, modes) -> str:
    """The sound power over the grid: L_W (dB re 1e-12 W) and the squealing mode where the case
    squeals (the wheelset's oscillations below 200 Hz marked 'LF'), blank otherwise."""
    cat, names = mode_categories(F, *modes, level)
    lines = ["L_W (dB re 1e-12 W) and the squealing mode (LF: the wheelset's oscillation below 200 Hz, not "
             "squeal):\n", "| gamma_y \\ mu | " + " | ".join(f"{m:g}" for m in mus) + " |", "|---:|" + "---:|" * len(mus)]
    for j, gy in enumerate(gammas):
        cells = []
        for i in range(len(mus)):
            k, lw = cat[i, j], F["L_W"][i, j]
            cells.append("" if k < 0 else "LF" if k == 0 else
                         f"{lw:.0f} {names[k].split()[0]}" if np.isfinite(lw) else names[k].split()[0])
        lines.append(f"| {gy:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
