"""The line study (``kind = "line"``, issue 27): every curve of a line, for its vehicle and friction
condition, through the curve verdict screen first (``pipeline.curve.screen_first``: the stability
screen for every wheel of the leading bogie, the time loop, radiation and listening only where the
screen finds a growing pole), on Dask (``runner``: a local cluster or ``--scheduler ADDR``), one row
per curve appended to ``table.csv`` as it finishes (resumable), and the comparison with the
CNOSSOS-EU and Schall 03 squeal penalties (``line_rules``).

Outputs in build/studies/<line>/: ``table.csv`` (as run), ``line.csv`` (the CSV's order, with the rules'
penalties; a value that does not exist, a band without sound (-inf dB) or a quiet curve's frequency and
levels (nan), is an empty cell), ``level_radius.png``, ``chainage.png``, ``lw_railway.csv`` (NoiseModelling's LW_RAILWAY
rows of the squealing curves) with ``lw_railway_sections.csv``, ``line.md`` (the verdict first) and
``summary.md`` (the same, for the report), ``curves/`` (a curve file per row, a record: the rows' Curves
go to the workers in memory); each curve's wheel cases and verdict.csv in build/curves/<curve>/.
"""
from __future__ import annotations

import logging
from pathlib import Path

from pipeline.store import paths
from pipeline.config.loader import config_hash, Field
from pipeline.study.line_input import LineRow, check as check_rows, line_curves, read_rows
from pipeline.study.line_worker import LineContext, LineTask, band_columns, line_case, prepare_worker
from pipeline.study.results_table import ResultsTable
from pipeline.study.runner import Task, pending, run_tasks
from pipeline.store.code_hash import code_key
from pipeline.study.line_outputs import write_outputs
from pipeline.study import line_risk
from pipeline.study.schemas import COMMON

log = logging.getLogger("pipeline.study")

# the code a row depends on (its syntax trees): the curving, the verdict and every stage it runs
ROW_FUNCTIONS = ("pipeline.study.line_worker:line_case",)

ROW_COLUMNS = {"id": str, "chainage_m": float, "radius_m": float, "cant_mm": float, "length_m": float,
               "speed_kmh": float, "vehicle": str, "friction": str, "mu": float}
RESULT_COLUMNS = {"curve": str, "squeals": int, "wheel": str, "f_squeal": float, "mode": str, "L_pA": float,
                  "L_W": float, "L_F2": float, "squealing_wheels": str, "unstable_wheels": str,
                  "time_loop_wheels": str, "aoa_mrad": float, "note": str}


# the study file's keys (pipeline/studies/<name>.toml with kind = "line")
SCHEMA = {
    "name": COMMON["name"],
    "kind": COMMON["kind"],
    "description": COMMON["description"],
    "curves": Field(str, doc="the line's curves: a CSV file, its path relative to the study file's folder "
                             "(pipeline/studies/<curves>) or absolute (anywhere), one row per curve, vehicle and "
                             "friction condition, columns id, chainage_m, radius_m, cant_mm, length_m, speed_kmh, "
                             "vehicle (a vehicle file beside the CSV, else geometry/vehicles/), friction "
                             "(pipeline/study/line_input.py)"),
    "base_curve": Field(str, default="r150", doc="pipeline/curves/<base_curve>.toml, or a curve file's path (relative "
                                                 "to the study file's folder): the rail, gauge, gauge widening and "
                                                 "traction of every curve of the line"),
    "friction": {
        "dry_mu": Field(float, min=0.05, max=1.0, default=0.4,
                        doc="Coulomb coefficient of the CSV's friction condition 'dry'"),
        "wet_mu": Field(float, min=0.05, max=1.0, default=0.15,
                        doc="Coulomb coefficient of the CSV's friction condition 'wet'"),
        "climate": Field(str, default=None, doc="friction climate of every curve's risk columns (issue 32): "
                                                "pipeline/climates/<name>.toml or a path relative to the study "
                                                "file's folder (default: 'default'; docs/friction_climate.md)"),
    },
    "what_ifs": Field(bool, default=False, doc="the curve verdict's mitigation what-ifs for every squealing wheel "
                                               "(friction threshold, modal damping; slower)"),
    "wheel_figures": Field(bool, default=False, doc="the stages' figures and the pass-by of each squealing wheel "
                                                    "(contact_rf.png, greens.png, simulate.png, radiate.png, the "
                                                    "listen PNG, passby_*; its npz, CSV, exports and listen WAV are "
                                                    "written either way)"),
    "quick": {
        "rows": Field(int, min=1, max=100000, default=3, doc="--quick: the CSV's first rows only"),
    },
    "export": {
        "passages_day": Field(float, unit="1/h", min=0.0, max=1000.0, default=1.0,
                              doc="squealing passages per hour in the LW_RAILWAY export's day period (D)"),
        "passages_evening": Field(float, unit="1/h", min=0.0, max=1000.0, default=1.0, doc="evening period (E)"),
        "passages_night": Field(float, unit="1/h", min=0.0, max=1000.0, default=1.0, doc="night period (N)"),
    },
}


def columns() -> dict:
    """The results table's columns: the row's inputs, the verdict, the bands, the bookkeeping."""
    return ROW_COLUMNS | RESULT_COLUMNS | line_risk.COLUMNS | {b: float for b in band_columns()} | {"wall_s": float,
                                                                                                  "worker": str}


def selected(spec: dict, quick: bool) -> list[LineRow]:
    rows = read_rows(spec)                           # every problem of the CSV, before any work
    return rows[: spec["quick"]["rows"]] if quick else rows


def inputs_hash(spec: dict, curve_text: str, curve) -> str:
    """What a row's result depends on: its curve file, the vehicle, wheel and rail files, the code."""
    files = [curve.vehicle.source, paths.wheel_file(curve.wheel), paths.rail_file(curve.rail)]
    return config_hash({"curve": curve_text, "files": [f.read_text() if f.exists() else "" for f in files],
                        "code": code_key(*ROW_FUNCTIONS, ignore_docs=True), "what_ifs": spec["what_ifs"],
                        "climate": line_risk.climate_path(spec).read_text(),
                        "figures": spec["wheel_figures"]})


def tasks_of(spec: dict, rows: list[LineRow], folder: Path) -> list[Task]:
    curves = line_curves(spec, rows, folder)
    return [Task(row.key, inputs_hash(spec, curves[row.key][1], curves[row.key][0]), "line",
                 LineTask(curves[row.key][0], tuple(row_inputs(row).items()))) for row in rows]


def row_inputs(row: LineRow) -> dict:
    return {"id": row.id, "chainage_m": row.chainage_m, "radius_m": row.radius_m, "cant_mm": row.cant_mm,
            "length_m": row.length_m, "speed_kmh": row.speed_kmh, "vehicle": row.vehicle,
            "friction": row.condition, "mu": row.mu}


def run(spec: dict, src: str, out: Path, *, quick: bool, client, progress: bool = True) -> dict:
    rows = selected(spec, quick)
    folder = out / "curves"
    tasks = tasks_of(spec, rows, folder)
    table = ResultsTable(out / "table.csv", columns())
    table.open({t.inputs for t in tasks})
    todo = pending(tasks, table)
    stats = {"total": len(tasks), "done_before": len(tasks) - len(todo), "submitted": len(todo)}
    if todo:
        dask = client.get()
        dask.run(prepare_worker)
        r = run_tasks(tasks, line_case, table, dask, {"line": LineContext(spec["what_ifs"], spec["wheel_figures"])},
                      desc=spec["name"], progress=progress)
        stats |= {"run_wall_s": round(r.wall, 3), "dask_workers": r.workers}
    write_outputs(spec, src, out, quick, rows, [table.rows.get(t.key) for t in tasks])
    return stats


def check(spec: dict) -> str:
    """``make check STUDY=``: every row of the line's CSV of curves and each row's curve file (ConfigError)."""
    line_risk.line_climate(spec)
    return f"{len(check_rows(spec))} curves from {spec['curves']}"
