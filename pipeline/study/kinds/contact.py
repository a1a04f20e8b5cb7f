"""Contact-model validation (SPEC 7), both parts in one table:

* in dynamic conditions: per selected wheel mode one simulation with only that mode kept
  (zeta_kept, the other flexible modes at zeta_others, the suspension modes and the rail as in
  the case), once with the point-contact model and once with Kalker's transient model; the same
  duration, kick and stop rule for both; F2 peak-to-peak and L_W (the radiate stage's model
  with the same damping) over the final stretch, and their relative differences;
* stand-alone: rigid, fixed wheel and rail, prescribed creepage gamma_y(t) = gamma_0 +
  amplitude sin(2 pi f t) over frequency; F2's mean, amplitude and phase at f.

Kalker's transient model costs ~0.5 ms (CPU) per time step, the point model ~1.5 us
(docs/benchmarks.md): every run may go to the SPEC's 8 s and stops at its limit cycle
(pipeline/studies/contact.toml gives the numbers).  Kalker's runs are submitted first (the
longest tasks first).

Outputs: table.csv, modes.csv and creepage.csv (point vs Kalker side by side), contact_modes.png,
contact_creepage.png, summary.md.
"""
from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

import numpy as np

from pipeline.store import paths
from pipeline.config.loader import config_hash, Field, ListOf
from pipeline.study.results_table import ResultsTable
from pipeline.study.runner import Task, pending, run_tasks
from pipeline.study.tasks import CreepageTask, ModeTask, Simulation
from solvers.study import single_mode_damping, relative_difference
from pipeline.stages.radiate import load_radiation_model
from pipeline.study.context import load_context
from postprocess.plots.study import contact_modes_figure, creepage_figure
from pipeline.store.artifacts import save_csv
from pipeline.store.atomic import save_figure, save_text
from pipeline.study.schemas import COMMON, OPERATING, SIMULATION
from solvers.constants import F_MAX_HZ

log = logging.getLogger("pipeline.study")

COLUMNS = {"case": str, "part": str, "model": str, "mode": int, "label": str, "f_mode": float, "f": float,
           "L_F2": float, "f_dominant": float, "F2_pp": float, "F2_mean": float, "F2_amplitude": float,
           "F2_phase": float, "L_W": float, "f_sound": float, "contact_loss": float, "stop_reason": str,
           "t_end": float, "wall_s": float, "worker": str}
MODELS = ("kalker", "point")           # Kalker first: the long tasks start first


# the study file's keys (pipeline/studies/<name>.toml with kind = "contact")
SCHEMA = COMMON | {
    "operating": OPERATING,
    "modes": {
        "classes": ListOf(Field(str, choices=["a", "r", "c"]), min_len=1, default=["a"],
                          doc="mode classes simulated one at a time"),
        "nodal_circles_max": Field(int, min=0, max=5, default=0),
        "f_min": Field(float, unit="Hz", min=0.0, max=20000.0, default=100.0),
        "f_max": Field(float, unit="Hz", min=0.0, max=20000.0, default=F_MAX_HZ),
        "zeta_kept": Field(float, min=0.0, max=1.0, default=1e-6, doc="damping of the mode kept (SPEC 7)"),
        "zeta_others": Field(float, min=0.0, max=10.0, default=1.0, doc="damping of the other flexible modes"),
        "kick": Field(float, unit="N s", min=0.0, max=100.0, default=0.01,
                      doc="lateral impulse at t = 0 (a larger one shortens the growth; the limit cycle does not depend on it)"),
    },
    "simulation": SIMULATION,
    "creepage": {
        "gamma_0": Field(float, min=-0.2, max=0.2, default=-0.003, doc="mean lateral creepage"),
        "amplitude": Field(float, min=0.0, max=0.2, default=0.001, doc="amplitude of the sinusoidal creepage"),
        "frequencies": ListOf(Field(float, unit="Hz", min=1.0, max=10000.0), min_len=1,
                              default=[100.0, 300.0, 1000.0, 3000.0]),
        "periods": Field(int, min=1, max=1000, default=3, doc="whole periods the response is measured over"),
        "settle": Field(float, unit="s", min=0.0, max=1.0, default=0.01,
                        doc="run-in before the measured periods (at least one period)"),
    },
    "quick": {
        "max_modes": Field(int, min=1, max=100, default=3, doc="--quick: the lowest modes only"),
        "duration": Field(float, unit="s", min=0.01, max=8.0, default=0.05),
        "frequencies": ListOf(Field(float, unit="Hz", min=1.0, max=10000.0), min_len=1, default=[1000.0]),
    },
}


def selected_modes(spec: dict, ctx, quick: bool) -> list[int]:
    m = spec["modes"]
    w = ctx.wheel
    sel = [i for i in np.argsort(w["f"]) if ctx.flexible[i] and w["cls"][i] in m["classes"]
           and w["m"][i] <= m["nodal_circles_max"] and m["f_min"] <= w["f"][i] <= m["f_max"]]
    return [int(i) for i in (sel[:spec["quick"]["max_modes"]] if quick else sel)]


def run(spec: dict, src: str, out: Path, *, quick: bool, client, progress: bool = True) -> dict:
    from pipeline.study.worker import contact_case  # lazy: brings in numba, rocket_fft, scipy

    sim, mset, cr = spec["simulation"], spec["modes"], spec["creepage"]
    duration = spec["quick"]["duration"] if quick else sim["duration"]
    freqs = spec["quick"]["frequencies"] if quick else cr["frequencies"]
    contexts, tasks = {}, []
    for case in spec["cases"]:
        ctx = load_context(case, radiation=False, mus=[m for m in [spec["operating"]["mu"]] if m is not None])
        mu = ctx.mu if spec["operating"]["mu"] is None else spec["operating"]["mu"]
        gy = ctx.gamma_y if spec["operating"]["gamma_y"] is None else spec["operating"]["gamma_y"]
        modes = selected_modes(spec, ctx, quick)
        zetas = {i: single_mode_damping(ctx.wheel["zeta"], i, ctx.flexible, mset["zeta_kept"], mset["zeta_others"])
                 for i in modes}
        rad = {i: load_radiation_model(case, dict(enumerate(z.tolist()))) for i, z in zetas.items()}
        ctx = dataclasses.replace(ctx, extra={"radiation": rad}, radiation_note="")
        contexts[case] = ctx
        inputs = config_hash({"context": ctx.inputs, "simulation": sim, "duration": duration, "modes": mset,
                              "creepage": cr, "mu": mu, "gamma_y": gy, "radiation": bool(rad)})
        run_as = Simulation.of(sim).but(duration=duration, final=min(sim["final"], duration))
        for model in MODELS:
            for i in modes:
                tasks.append(Task(f"{case}|mode={i}|{model}", inputs, case, ModeTask(
                    case=case, model=model, mode=i, label=ctx.label(i), f_mode=float(ctx.wheel["f"][i]),
                    zeta=tuple(zetas[i].tolist()), mu=mu, gamma_y=gy, kick=mset["kick"], sim=run_as)))
            for f in freqs:
                n_per = int(np.ceil(cr["settle"] * f - 1e-9))
                tasks.append(Task(f"{case}|f={f:g}|{model}", inputs, case, CreepageTask(
                    case=case, model=model, f=float(f), mu=mu, gamma_0=cr["gamma_0"], amplitude=cr["amplitude"],
                    periods=cr["periods"], duration=(max(n_per, 1) + cr["periods"]) / f)))
    table = ResultsTable(out / "table.csv", COLUMNS)
    table.open({t.inputs for t in tasks})
    todo = pending(tasks, table)
    stats = {"total": len(tasks), "done_before": len(tasks) - len(todo), "submitted": len(todo)}
    if todo:
        r = run_tasks(tasks, contact_case, table, client.get(), contexts, desc=spec["name"], progress=progress)
        stats |= {"run_wall_s": round(r.wall, 3), "dask_workers": r.workers}
    write_outputs(spec, src, out, quick, contexts, tasks, table, duration)
    return stats


def paired(rows: list, part: str, by: str) -> list[dict]:
    """Point and Kalker rows of one part side by side, keyed by ``by`` ('mode' or 'f')."""
    out = {}
    for r in rows:
        if r["part"] == part:
            out.setdefault((r["case"], r[by]), {})[r["model"]] = r
    res = []
    for (case, k), d in sorted(out.items(), key=lambda kv: (kv[0][0], kv[1].get("point", kv[1].get("kalker"))
                                                             ["f_mode" if by == "mode" else "f"])):
        if set(d) != {"point", "kalker"}:
            continue
        p, q = d["point"], d["kalker"]
        row = {"case": case, by: k}
        if part == "mode":
            row |= {"label": p["label"], "f_mode": p["f_mode"], "F2_pp_point": p["F2_pp"], "F2_pp_kalker": q["F2_pp"],
                    "d_F2_pp": relative_difference(p["F2_pp"], q["F2_pp"]), "L_W_point": p["L_W"],
                    "L_W_kalker": q["L_W"], "d_L_W": p["L_W"] - q["L_W"], "L_F2_point": p["L_F2"],
                    "L_F2_kalker": q["L_F2"], "f_point": p["f_dominant"], "f_kalker": q["f_dominant"],
                    "stop_point": p["stop_reason"], "stop_kalker": q["stop_reason"], "wall_point": p["wall_s"],
                    "wall_kalker": q["wall_s"], "t_end": q["t_end"]}
        else:
            dphi = float(np.angle(np.exp(1j * (p["F2_phase"] - q["F2_phase"]))))
            row |= {"amp_point": p["F2_amplitude"], "amp_kalker": q["F2_amplitude"],
                    "d_amp": relative_difference(p["F2_amplitude"], q["F2_amplitude"]),
                    "phase_point": p["F2_phase"], "phase_kalker": q["F2_phase"], "d_phase": dphi,
                    "mean_point": p["F2_mean"], "mean_kalker": q["F2_mean"],
                    "d_mean": relative_difference(p["F2_mean"], q["F2_mean"]), "wall_point": p["wall_s"],
                    "wall_kalker": q["wall_s"], "t_end": q["t_end"]}
        res.append(row)
    return res


def _f(x, fmt: str) -> str:
    """Format a number, '-' for NaN (e.g. L_W of a case that does not squeal)."""
    return "-" if not np.isfinite(x) else format(x, fmt)


def write_outputs(spec, src, out: Path, quick, contexts, tasks, table, duration) -> None:
    rows = [table.rows[t.key] for t in tasks if t.key in table.rows]
    modes = paired(rows, "mode", "mode")
    creep = paired(rows, "creepage", "f")
    if modes:
        save_csv(out / "modes.csv", list(modes[0]), ([r[k] for k in modes[0]] for r in modes))
        save_figure(contact_modes_figure(modes, "point contact vs Kalker's transient model, one mode kept"),
                    out / "contact_modes.png", dpi=90)
    if creep:
        save_csv(out / "creepage.csv", list(creep[0]), ([r[k] for k in creep[0]] for r in creep))
        cr = spec["creepage"]
        save_figure(creepage_figure([r for r in rows if r["part"] == "creepage"],
                                    f"prescribed creepage gamma_y = {cr['gamma_0']:g} + {cr['amplitude']:g} "
                                    f"sin(2 pi f t), rigid structures"), out / "contact_creepage.png", dpi=90)
    sim, m, cr = spec["simulation"], spec["modes"], spec["creepage"]
    level = sim["squeal_level"]
    ml = ["| case | mode | f (Hz) | F2 pp point (N) | F2 pp Kalker (N) | rel. diff | L_W point (dB) | L_W Kalker (dB) "
          "| diff (dB) | f point / Kalker (Hz) | ended (point / Kalker) | wall point / Kalker (s) |",
          "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---|---|"]
    for r in modes:
        ml.append(f"| {r['case']} | {r['label']} | {r['f_mode']:.0f} | {r['F2_pp_point']:.4g} | {r['F2_pp_kalker']:.4g} "
                  f"| {_f(100 * r['d_F2_pp'], '+.1f')} % | {_f(r['L_W_point'], '.1f')} | {_f(r['L_W_kalker'], '.1f')} | "
                  f"{_f(r['d_L_W'], '+.1f')} | {_f(r['f_point'], '.0f')} / {_f(r['f_kalker'], '.0f')} | "
                  f"{r['stop_point']} / {r['stop_kalker']} | "
                  f"{r['wall_point']:.1f} / {r['wall_kalker']:.1f} |")
    cl = ["| case | f (Hz) | F2 amplitude point (N) | Kalker (N) | rel. diff | phase diff (deg) | F2 mean rel. diff | "
          "wall point / Kalker (s) |", "|---|---:|---:|---:|---:|---:|---:|---|"]
    for r in creep:
        cl.append(f"| {r['case']} | {r['f']:g} | {r['amp_point']:.4g} | {r['amp_kalker']:.4g} | {100 * r['d_amp']:+.1f} % "
                  f"| {np.degrees(r['d_phase']):+.1f} | {100 * r['d_mean']:+.2f} % | {r['wall_point']:.2f} / "
                  f"{r['wall_kalker']:.1f} |")
    notes = [c.radiation_note for c in contexts.values() if c.radiation_note]
    text = f"""# Study `{spec['name']}`{' (quick)' if quick else ''}: contact-model validation (SPEC 7)

{spec['description']}

Definition `{paths.shown(src)}`; {len(rows)} of {len(tasks)} simulations done.

## In dynamic conditions: one wheel mode kept

Modes: flexible, classes {m['classes']}, at most {m['nodal_circles_max']} nodal circles, {m['f_min']:g}-{m['f_max']:g} Hz
{'(the lowest ' + str(spec['quick']['max_modes']) + ' only, --quick)' if quick else ''}; the mode kept at zeta = {m['zeta_kept']:g},
the other flexible modes at zeta = {m['zeta_others']:g}, suspension modes and rail as in the case. Both contact
models start from their own steady state with a lateral impulse of {m['kick']:g} N s and run {duration:g} s
{'(or to a limit cycle / decay)' if sim['early_stop'] else '(no early stop)'}; F2 peak-to-peak and L_W over the final
{min(sim['final'], duration):g} s; L_W (sound power of the wheel with the same damping) only where L_F2 >= {level:g} dB.
Relative differences are (point - Kalker) / Kalker.{(' ' + '; '.join(notes) + '.') if notes else ''}

{chr(10).join(ml)}

![modes](contact_modes.png)

## Stand-alone: prescribed creepage

Rigid, fixed wheel and rail; gamma_y(t) = {cr['gamma_0']:g} + {cr['amplitude']:g} sin(2 pi f t); F2 over the last
{cr['periods']} periods after a run-in of at least {cr['settle']:g} s (whole periods): mean, and amplitude and phase of the
component at f.

{chr(10).join(cl)}

![creepage](contact_creepage.png)

Tables: `modes.csv`, `creepage.csv` (side by side), `table.csv` (every simulation).
"""
    save_text(text, out / "summary.md")
