"""The line study's outputs (``pipeline.study.kinds.line``): line.csv, the two figures, the NoiseModelling
export of the squealing curves and line.md / summary.md, the verdict first."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pipeline.store import paths
from pipeline.study.line_rules import AGREE_QUIET, AGREE_SQUEAL, MISSED, OVER, RULES, SOURCES, TITLES, rule_columns
from pipeline.study.line_worker import band_columns
from postprocess.exports import lw_railway_columns, lw_railway_record
from pipeline.store.artifacts import save_csv
from postprocess.plots.line import chainage_figure, level_radius_figure
from pipeline.store.atomic import save_figure, save_text
from pipeline.curve.verdict_report import cell
from pipeline.study.line_html import write_page
from pipeline.study import line_classes, line_risk
from pipeline.config.curve_inputs import read_vehicle
from pipeline.study.line_input import curves_file

OUT_COLUMNS = ["id", "chainage_m", "radius_m", "cant_mm", "length_m", "speed_kmh", "vehicle", "friction", "mu",
               "squeals", "wheel", "f_squeal", "mode", "L_pA", "L_W", "L_F2", "squealing_wheels", "unstable_wheels",
               "time_loop_wheels", "cnossos_dB", "cnossos_vs_physics", "schall03_dB", "schall03_vs_physics", "curve",
               "note"]


def _f(x, fmt=".1f") -> str:
    return "-" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f"{x:{fmt}}"


def categories(spec: dict, done: list[dict]) -> dict[str, str]:
    """{vehicle: its file's ``category``} (railway or tram: Schall 03's rule) of the rows' vehicles, looked up
    beside the line's CSV first as the rows' curves were."""
    beside = curves_file(spec).parent
    return {v: read_vehicle(v, beside).data["category"] for v in sorted({r["vehicle"] for r in done})}


def full_rows(done: list[dict], category: dict | None = None) -> list[dict]:
    """The finished rows with the rules' columns (a row without a verdict, its ``note`` set: the rules'
    penalties, compared with nothing); ``category``: {vehicle: railway or tram} (default railway)."""
    out = []
    for r in done:
        cols = rule_columns(r["radius_m"], bool(r["squeals"]), (category or {}).get(r["vehicle"], "railway"))
        if r.get("note"):
            cols = {k: (v if k.endswith("_dB") else "not computed") for k, v in cols.items()}
        out.append(r | cols)
    return out


def write_export(spec: dict, out: Path, rows: list[dict]) -> tuple[Path, int]:
    """lw_railway.csv: one LW_RAILWAY row (``postprocess.exports``) per squealing row, its loudest wheel's
    band L_W at the row's speed and the study's passages per hour; lw_railway_sections.csv maps its
    PK_SECTION to the row.  An empty table (header only) when nothing squeals."""
    e = spec["export"]
    flows = {"D": e["passages_day"], "E": e["passages_evening"], "N": e["passages_night"]}
    bands = band_columns()
    cols = lw_railway_columns()
    recs, secs = [], []
    for i, r in enumerate((r for r in rows if r["squeals"]), start=1):
        L = np.array([r[b] for b in bands], float)
        L = np.where(np.isfinite(L), L, -99.0)
        rec = lw_railway_record(L, r["speed_kmh"], flows, pk_section=i)
        recs.append([rec[c] for c in cols])
        secs.append([i, r["id"], r["chainage_m"], r["length_m"], r["vehicle"], r["friction"], r["wheel"]])
    path = save_csv(out / "lw_railway.csv", cols, recs)
    save_csv(out / "lw_railway_sections.csv", ["PK_SECTION", "id", "chainage_m", "length_m", "vehicle", "friction",
                                               "wheel"], secs)
    return path, len(recs)


def rule_table(rows: list[dict], rule: str, which: str) -> str:
    sel = [r for r in rows if r[f"{rule}_vs_physics"] == which]
    if not sel:
        return "none.\n"
    lines = ["| curve | chainage (m) | R (m) | V (km/h) | friction | penalty (dB) | physics |", "|" + "---|" * 7]
    for r in sel:
        phys = (f"squeals: {r['wheel']} {_f(r['f_squeal'], '.0f')} Hz {r['mode']}, L_pA {_f(r['L_pA'])} dB(A)"
                if r["squeals"] else "no squeal" + (f" (screen unstable: {r['unstable_wheels']}; the time loop "
                                                    "decays)" if r["unstable_wheels"] else ""))
        lines.append(f"| {r['id']} | {r['chainage_m']:g} | {r['radius_m']:g} | {r['speed_kmh']:g} | {r['friction']} | "
                     f"{r[f'{rule}_dB']:g} | {phys} |")
    return "\n".join(lines) + "\n"


def markdown(spec: dict, src: str, quick: bool, every: list[dict], total: int, n_export: int) -> str:
    rows = [r for r in every if not r.get("note")]
    noted = [r for r in every if r.get("note")]
    sq = [r for r in rows if r["squeals"]]
    conds = sorted({r["friction"] for r in rows})
    head = f"# Line `{spec['name']}`{' (quick: first rows)' if quick else ''}: which curves squeal\n\n"
    if len(every) < total:
        head += f"**{len(every)} of {total} rows done** (rerun `make study STUDY={spec['name']}` to resume).\n\n"
    by = "; ".join(f"{c}: {sum(1 for r in sq if r['friction'] == c)} of {sum(1 for r in rows if r['friction'] == c)}"
                   for c in conds)
    if sq:
        loud = max(sq, key=lambda r: r["L_pA"] if math.isfinite(r["L_pA"]) else -1e9)
        verdict = (f"**{len(sq)} of {len(rows)} curve conditions squeal** ({by}).  Loudest: curve **{loud['id']}** "
                   f"(R = {loud['radius_m']:g} m, {loud['speed_kmh']:g} km/h, {loud['friction']}), wheel {loud['wheel']} "
                   f"at {_f(loud['f_squeal'], '.0f')} Hz ({loud['mode']}), L_pA = **{_f(loud['L_pA'])} dB(A)** at 7.5 m, "
                   f"L_W = {_f(loud['L_W'])} dB.  Squeal up to R = {max(r['radius_m'] for r in sq):g} m.\n\n")
    else:
        verdict = f"**No curve squeals** ({by} squeal).\n\n"
    rules = []
    for rule in RULES:
        n = {k: sum(1 for r in rows if r[f"{rule}_vs_physics"] == k) for k in (AGREE_SQUEAL, AGREE_QUIET, MISSED, OVER)}
        rules.append(f"- **{TITLES[rule]}** ({SOURCES[rule]}): agrees on {n[AGREE_SQUEAL] + n[AGREE_QUIET]} of "
                     f"{len(rows)} ({n[AGREE_SQUEAL]} squeal and penalised, {n[AGREE_QUIET]} quiet and not); "
                     f"**misses {n[MISSED]}** squealing curve conditions; **penalises {n[OVER]}** that do not squeal.")
    if noted:
        why = {}
        for r in noted:
            reason = r["note"].split(": ", 1)[-1]
            reason = reason.split(" (")[0] if "did not converge" in reason else reason
            why.setdefault(reason, []).append(f"{r['id']} ({r['radius_m']:g} m, {r['friction']})")
        verdict += (f"Not computed ({len(noted)} rows, left out below; the whole message in line.csv's `note`): "
                    + "; ".join(f"{', '.join(v)}: {k}" for k, v in why.items()) + ".\n\n")
    parts = [head, verdict, "The rules beside the physics (a rule sees the radius only, not the vehicle, speed or "
             "friction):\n\n" + "\n".join(rules) + "\n",
             "![level against radius](level_radius.png)\n", "![the line along its chainage](chainage.png)\n"]
    for rule in RULES:
        parts.append(f"## {TITLES[rule]}: squeal the rule misses\n\n" + rule_table(rows, rule, MISSED))
        parts.append(f"## {TITLES[rule]}: penalised, but no squeal\n\n" + rule_table(rows, rule, OVER))
    lines = ["| curve | chainage (m) | R (m) | cant (mm) | V (km/h) | vehicle | friction | screen unstable | squeals | f (Hz) "
             "| mode | L_pA (dB(A)) | L_W (dB) | CNOSSOS | Schall 03 |", "|" + "---|" * 15]
    for r in rows:
        lines.append(f"| {r['id']} | {r['chainage_m']:g} | {r['radius_m']:g} | {r['cant_mm']:g} | {r['speed_kmh']:g} | "
                     f"{r['vehicle']} | {r['friction']} | {r['unstable_wheels'] or '-'} | "
                     f"{r['squealing_wheels'] or 'no'} | {_f(r['f_squeal'], '.0f')} | {r['mode'] or '-'} | "
                     f"{_f(r['L_pA'])} | {_f(r['L_W'])} | +{r['cnossos_dB']:g} | +{r['schall03_dB']:g} |")
    parts.append("## Every curve\n\n" + "\n".join(lines) + "\n")
    walls = np.array([r["wall_s"] for r in rows], float)
    parts.append(
        f"Definition `{paths.shown(src)}`, curves `{spec['curves']}` ({total} rows).  Each row: the curve verdict "
        "(`make curve`) screen first: steady curving of the leading bogie, the stability screen for its four wheels, "
        "the time loop (L_F2 >= 10 dB re 1 N: squeal) and radiation and listening (7.5 m, 1.2 m) only for the wheels "
        "the screen finds unstable.  The level is the loudest squealing wheel's.  Tables: `line.csv` (with L_W per "
        "1/3-octave band, 50 Hz-10 kHz; an empty cell is a value that does not exist: a band without "
        "sound, -inf dB, or a quiet curve's frequency and levels), `table.csv` (as run); NoiseModelling's "
        f"LW_RAILWAY rows of the {n_export} squealing rows: `lw_railway.csv` (its PK_SECTION -> curve: `lw_railway_sections.csv`; "
        "the source layout and convention: `postprocess/exports.py`).  "
        + (f"Worker time per row: median {np.median(walls):.1f} s, {walls.sum():.0f} s in all.\n" if walls.size else ""))
    return "\n".join(parts)


def write_outputs(spec: dict, src: str, out: Path, quick: bool, line_rows, done) -> None:
    done = [line_risk.EMPTY | r for r in done if r is not None]     # rows without the climate's: blank
    every = full_rows(done, categories(spec, done))
    rows = [r for r in every if not r.get("note")]
    cols = OUT_COLUMNS + list(line_risk.COLUMNS) + band_columns()   # the climate's columns (issue 32)
    save_csv(out / "line.csv", cols, ([cell(r[c]) if not isinstance(r[c], int) else r[c] for c in cols]
                                      for r in every))
    _, n_export = write_export(spec, out, rows)
    if rows:
        arr = {k: [r[k] for r in rows] for k in ("radius_m", "L_pA", "squeals", "friction", "chainage_m", "length_m",
                                                 "id")}
        bands = [(1.0, 300.0, "R <= 300 m: CNOSSOS-EU +8 dB, Schall 03 +8 dB (R < 300 m)"),
                 (300.0, 500.0, "300-500 m: CNOSSOS-EU +5 dB (to 500), Schall 03 +3 dB (300 to < 500)")]
        save_figure(level_radius_figure(arr["radius_m"], arr["L_pA"], arr["squeals"], arr["friction"], bands),
                    out / "level_radius.png", dpi=100)
        save_figure(chainage_figure(arr["chainage_m"], arr["length_m"], arr["radius_m"], arr["L_pA"], arr["squeals"],
                                    arr["friction"], {TITLES[k]: [r[f"{k}_dB"] for r in rows] for k in RULES},
                                    ids=arr["id"]), out / "chainage.png", dpi=100)
    md = markdown(spec, src, quick, every, len(line_rows), n_export)
    classes = line_classes.classes_markdown(line_classes.write_classes(out, rows), line_risk.climate_cell(spec))
    md = md.replace("## Every curve", classes + "## Every curve", 1)    # per radius class (issue 32)
    save_text(md, out / "line.md")
    save_text(md, out / "summary.md")
    write_page(out, md, every, spec["name"])      # verdict.html: the page to open (issue 33)
