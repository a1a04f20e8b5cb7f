"""The line study's risk per radius class (issue 32): line_classes.csv beside line.csv and its table in
line.md / verdict.html.

Classes of curve radius R (m), as STUVA's survey of urban curves groups them (docs/validation/92_field.md):
25-50, 51-100, 101-200, 201-300, 301-500 and > 500 m, each class (lower, upper]: 25 <= R <= 50,
50 < R <= 100, ..., R > 500 (a radius below 25 m: its own class '< 25').  One line per class and friction
condition of the line's CSV (each condition is the whole line once; the climate's columns do not depend on
the condition for a Coulomb one), over the rows with a verdict (a row with a ``note`` is left out):

* ``curves``: rows; ``squeal_now``: those squealing at the row's own friction (the screen-first verdict);
* ``p_squeal``, ``axles_p_squeal``: their means, the expected shares of the class's passages and (leading
  bogie) axles that squeal over the climate;
* ``L_pAmax_7m5``: the median over the class's rows that can squeal (p_squeal > 0) of their
  ``L_pAmax_7m5`` (each the loudest wheel's median when squealing); blank when none can;
* ``L_pAmax_rolling``, ``dL_squeal``: means (``dL_squeal`` is STUVA's mean increase of the maximum level
  "with how often it occurs"); ``cnossos_dB``, ``schall03_dB``: the rules' mean penalties over the same
  rows (``line_rules``), to read beside ``dL_squeal``.

No cell is -inf or NaN: a value that does not exist is an empty cell (``verdict_report.cell``).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pipeline.curve.verdict_report import cell
from pipeline.store.artifacts import save_csv

EDGES = (25.0, 50.0, 100.0, 200.0, 300.0, 500.0)
LABELS = ("25-50", "51-100", "101-200", "201-300", "301-500", "> 500")
COLUMNS = ["radius_class", "friction", "curves", "squeal_now", "p_squeal", "axles_p_squeal", "L_pAmax_7m5",
           "L_pAmax_rolling", "dL_squeal", "cnossos_dB", "schall03_dB"]


def radius_class(radius_m: float) -> str:
    """The class label of a radius (module notes)."""
    if radius_m < EDGES[0]:
        return "< 25"
    for upper, label in zip(EDGES[1:], LABELS):
        if radius_m <= upper:
            return label
    return LABELS[-1]


def _mean(xs) -> float:
    xs = [x for x in xs if math.isfinite(x)]
    return float(np.mean(xs)) if xs else math.nan


def class_rows(rows: list[dict]) -> list[dict]:
    """The table's lines (``COLUMNS``), classes in radius order, conditions in the CSV's order."""
    rows = [r for r in rows if not r.get("note")]
    conds = list(dict.fromkeys(r["friction"] for r in rows))
    order = ["< 25", *LABELS]
    out = []
    for label in order:
        for c in conds:
            sel = [r for r in rows if r["friction"] == c and radius_class(r["radius_m"]) == label]
            if not sel:
                continue
            can = [r["L_pAmax_7m5"] for r in sel if r["p_squeal"] > 0 and math.isfinite(r["L_pAmax_7m5"])]
            out.append({"radius_class": label, "friction": c, "curves": len(sel),
                        "squeal_now": sum(1 for r in sel if r["squeals"]),
                        "p_squeal": _mean(r["p_squeal"] for r in sel),
                        "axles_p_squeal": _mean(r["axles_p_squeal"] for r in sel),
                        "L_pAmax_7m5": float(np.median(can)) if can else math.nan,
                        "L_pAmax_rolling": _mean(r["L_pAmax_rolling"] for r in sel),
                        "dL_squeal": _mean(r["dL_squeal"] for r in sel),
                        "cnossos_dB": _mean(r["cnossos_dB"] for r in sel),
                        "schall03_dB": _mean(r["schall03_dB"] for r in sel)})
    return out


def write_classes(out: Path, rows: list[dict]) -> list[dict]:
    """line_classes.csv (atomic); returns its lines."""
    lines = class_rows(rows)
    save_csv(out / "line_classes.csv", COLUMNS, ([cell(r[k]) for k in COLUMNS] for r in lines))
    return lines


def _f(x, fmt=".1f") -> str:
    return "-" if not math.isfinite(x) else f"{x:{fmt}}"


def classes_markdown(lines: list[dict], climate: str) -> str:
    """line.md's section on the classes ('' without lines)."""
    if not lines:
        return ""
    md = [f"## Squeal per radius class over the friction climate `{climate}`\n",
          "Expected shares over the climate (one friction level per passage; the leading bogie's wheels), the "
          "loudest wheel's median L_pA,max at 7.5 m when squealing, CNOSSOS-EU rolling noise of the pass-by at "
          "7.5 m and squeal's expected excess over it (`line_classes.csv`; per curve in `line.csv`), beside the "
          "rules' penalties (means over the class's curves).  '-': no value (no curve of the class can squeal).\n",
          "| R (m) | friction | curves | squeal now | p_squeal | axles | L_pA,max when squealing (dB(A)) | "
          "rolling L_pA,max (dB(A)) | dL_squeal (dB) | CNOSSOS-EU (dB) | Schall 03 (dB) |", "|" + "---|" * 11]
    for r in lines:
        md.append(f"| {r['radius_class']} | {r['friction']} | {r['curves']} | {r['squeal_now']} | "
                  f"{_f(r['p_squeal'], '.3f')} | {_f(r['axles_p_squeal'], '.3f')} | {_f(r['L_pAmax_7m5'])} | "
                  f"{_f(r['L_pAmax_rolling'])} | {_f(r['dL_squeal'], '.2f')} | +{_f(r['cnossos_dB'], '.3g')} | "
                  f"+{_f(r['schall03_dB'], '.3g')} |")
    return "\n".join(md) + "\n\n"
