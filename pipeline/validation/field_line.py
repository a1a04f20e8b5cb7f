"""The example line against the field's statistics (issue 32): the section of docs/validation/
96_field_statistics.md on the shipped line study (``pipeline/studies/metro_line.toml``), its rows
(docs/validation/96_field_line.csv, what tests/verdict/test_field_line.py recomputes) and its plot.

    .venv/bin/python -m pipeline.validation.field_line     (this section alone, into the committed page)

``field_statistics_doc`` appends ``section(radius_rows)`` to the page it writes (``make validate``); run
alone, the radius study's points come from the committed 96_field_statistics.csv and the page's text
before this section is kept.  The line study is built through Make when its line.csv is missing.

Per radius class (``field_statistics.CLASSES``) and friction condition of the line's CSV (each condition
is the whole line once, under one climate; the row's own friction sets its steady curving only), over the
rows with a verdict: p and the axles' share (means of ``p_squeal``, ``axles_p_squeal``), dL (mean
``dL_squeal``, STUVA's method b), dL_when = L_train - L_roll of the rows that can squeal (p > 0; method a),
L_train = L_roll (+) ``L_pAmax_7m5`` (energy sum, against TEMA's 100-105 dB(A)), the rules' mean
penalties (line.csv's, Schall 03's rule by the vehicle file's ``category``).  Each against the field with
``field_statistics``' numbers and tolerance.  Nothing is fitted.
"""
from __future__ import annotations

import csv
import io
import math
import re
import sys

import numpy as np

from pipeline.config.climate import climate_file, load_climate
from pipeline.config.curve_inputs import read_vehicle
from pipeline.curve.onset import cell_onset, range_windows
from pipeline.curve.risk import curve_risk
from pipeline.store import paths
from pipeline.store.atomic import save_text
from pipeline.validation.docs import assemble_validation
from pipeline.validation import field_statistics as fs
from pipeline.validation.make import make_targets
from pipeline.validation.writers import DOCS, pyplot, save_figure
from solvers.radiation.rolling_cnossos import db_sum
from solvers.radiation.squeal_excess import climate_excess

LINE = "metro_line"
HEADING = "## The example line against the field's statistics"
ROWS_CSV = "96_field_line.csv"
FIGURE = "field_line_onset.png"
KEYS = ["id", "vehicle", "friction", "radius_m", "speed_kmh", "mu", "squeals", "time_loop_wheels", "mu_onset",
        "mu_squeal_range", "wheel_onset", "f_onset", "mode_onset", "p_squeal", "axles_p_squeal", "L_pAmax_7m5", "L_pAmax_rolling",
        "dL_squeal", "f_squeal", "cnossos_dB", "schall03_dB", "note"]
TEXT = ("id", "vehicle", "friction", "time_loop_wheels", "mu_onset", "mu_squeal_range", "wheel_onset", "mode_onset",
        "note")
LABELS = [c for c, _, _ in fs.CLASSES]


def line_csv(line: str = LINE):
    """build/studies/<line>/line.csv, the line study run through Make first when it is missing."""
    f = paths.build() / "studies" / line / "line.csv"
    if not f.exists():
        make_targets("study", STUDY=line)          # resumed where rows are kept (pipeline.study.kinds.line)
    return f


def parse(text_rows) -> list[dict]:
    """Rows of ``KEYS`` (text cells) -> typed rows: numbers as floats (empty or 'nan': NaN), ``squeals`` an
    int, ``onset`` the onset as a number (``field_statistics.onset_value``) and the row's radius class."""
    out = []
    for r in text_rows:
        r = {"mu_squeal_range": ""} | r             # rows written before the windows: the onset's own
        row = {k: (r[k] if k in TEXT else (int(r[k]) if k == "squeals" else float(r[k] or "nan"))) for k in KEYS}
        row["onset"] = fs.onset_value(row["mu_onset"])
        row["class"] = fs.radius_class(row["radius_m"])
        out.append(row)
    return out


def read_line(path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        return parse(csv.DictReader(fh))


def save_line_rows(path) -> list[dict]:
    """The section's rows (``KEYS`` of line.csv, its cells as written) -> docs/validation/96_field_line.csv."""
    with open(path, newline="", encoding="utf-8") as fh:
        text = [{k: r[k] for k in KEYS} for r in csv.DictReader(fh)]
    buf = io.StringIO()
    w = csv.DictWriter(buf, KEYS, lineterminator="\n")
    w.writeheader()
    w.writerows(text)
    save_text(buf.getvalue(), DOCS / ROWS_CSV)
    return parse(text)


def committed_rows() -> list[dict]:
    return read_line(DOCS / ROWS_CSV)


def when(r: dict) -> float:
    """A squealing passage's excess L_train - L_roll (NaN where no wheel can squeal)."""
    return climate_excess(r["L_pAmax_rolling"], r["L_pAmax_7m5"], 1.0) if can(r) else math.nan


def can(r: dict) -> bool:
    return r["p_squeal"] > 0.0 and math.isfinite(r["L_pAmax_7m5"])


def class_stats(rows: list[dict]) -> dict:
    """{(class, condition): statistics} over the rows with a verdict (module notes), classes in radius order."""
    acc: dict = {}
    for r in rows:
        if not r["note"]:
            acc.setdefault((r["class"], r["friction"]), []).append(r)
    out = {}
    conds = list(dict.fromkeys(r["friction"] for r in rows))
    for c in LABELS:
        for f in conds:
            sel = acc.get((c, f))
            if not sel:
                continue
            sq = [r for r in sel if can(r)]
            mean = lambda xs: float(np.mean(xs)) if xs else math.nan  # noqa: E731
            out[(c, f)] = {"curves": len(sel), "squeal_now": sum(r["squeals"] for r in sel),
                           "p": mean([r["p_squeal"] for r in sel]), "axles": mean([r["axles_p_squeal"] for r in sel]),
                           "dL": mean([r["dL_squeal"] for r in sel]), "dL_when": mean([when(r) for r in sq]),
                           "L_train": mean([db_sum(r["L_pAmax_rolling"], r["L_pAmax_7m5"]) for r in sq]),
                           "cnossos": mean([r["cnossos_dB"] for r in sel]),
                           "schall03": mean([r["schall03_dB"] for r in sel]),
                           "radii": sorted({r["radius_m"] for r in sel})}
    return out


def windows(rows: list[dict]) -> list[dict]:
    """Rows whose wheels squeal in a window of friction only (``mu_squeal_range`` closes below the climate's
    top: the onset scan finds them stable again above it); their p_squeal is the climate's share of the window."""
    return [r for r in rows if not r["note"] and any(math.isfinite(b) for _, b in range_windows(r["mu_squeal_range"]))]


def state_bound(rows: list[dict]) -> list[tuple[dict, dict]]:
    """(row, other) pairs of one curve and vehicle: the row's onset lies below the other condition's friction,
    where the other row (its steady curving solved at that friction) is quiet and its own scan quiet beyond
    it -- the row's p_squeal holds for its own curving state only (``line_risk``'s notes)."""
    by = {(r["id"], r["vehicle"], r["friction"]): r for r in rows if not r["note"]}
    return [(r, s) for r in by.values() for s in by.values() if (s["id"], s["vehicle"]) == (r["id"], r["vehicle"])
            and s is not r and math.isfinite(r["onset"]) and r["onset"] < s["mu"] and not s["squeals"]
            and s["onset"] > s["mu"]]


def window_text(ws: list[dict]) -> str:
    return "; ".join(f"R = {r['radius_m']:g} m {r['friction']} (squeals for mu in {r['mu_squeal_range']}, "
                     + ("quiet" if not r["squeals"] else "squealing") + f" at its own mu = {r['mu']:g})" for r in ws)


def f(x, spec=".1f") -> str:
    return "-" if x is None or not math.isfinite(x) else f"{x:{spec}}"


def verdict(ok) -> str:
    return "n/a" if ok is None else ("agrees" if ok else "**disagrees**")


def comparison(rows: list[dict], stats: dict, category: str, fm) -> str:
    """The comparison table: every statistic and class, the line's conditions side by side."""
    conds = list(dict.fromkeys(r["friction"] for r in rows))
    top = max(c.hi for c in load_climate(climate_file(fs.CLIMATE)).conditions)
    win = windows(rows)
    t = ["| statistic | class (m) | field | " + " | ".join(f"line, {c} rows" for c in conds) +
         " | verdict (" + " / ".join(conds) + ") | mechanism |", "|" + "---|" * (5 + len(conds))]

    def row(stat, c, field, key, ok, mech, spec=".3f"):
        vals = [f(stats[(c, k)][key], spec) if (c, k) in stats else "-" for k in conds]
        oks = [ok(stats[(c, k)]) if (c, k) in stats else None for k in conds]
        w = [r for r in win if r["class"] == c]
        mech += ("" if not w or key not in ("p", "dL", "cnossos", "schall03") else
                 f" Instability window: {window_text(w)}; p_squeal counts the climate's share of the window only.")
        t.append(f"| {stat} | {c} | {field} | " + " | ".join(vals) + " | " + " / ".join(verdict(o) for o in oks)
                 + f" | {mech} |")

    present = [c for c in LABELS if any((c, k) in stats for k in conds)]
    for c in present:
        quiet = c in ("301-500", ">500") or (c == "201-300" and category == "tram")
        expect = None if c == "201-300" and category != "tram" else quiet
        onsets = "; ".join(f"{k}: " + (", ".join(f"{r['mu_onset']} ({r['radius_m']:g} m)" for r in rows
                                                 if r["class"] == c and r["friction"] == k and not r["note"]
                                                 and math.isfinite(r["onset"])) or "none") for k in conds)
        bound = [(r, s) for r, s in state_bound(rows) if r["class"] == c]
        onsets += ("" if not bound else "; curving state: " + ", ".join(
            f"{r['radius_m']:g} m {r['friction']} (onset {r['mu_onset']}; its {s['friction']} row quiet at "
            f"{s['mu']:g}, up to {s['mu_onset']})" for r, s in bound))
        row("line: share of passages that squeal, p", c,
            "no squeal above 300 m (JRC)" if c in ("301-500", ">500") else "trams none above 200 m; other vehicles "
            "sporadic (Thompson 2009)" if c == "201-300" else "squeal occurs (STUVA's class means > 0)", "p",
            lambda s: None if expect is None else (s["p"] == 0.0) == expect,
            f"onsets below the climate's highest level {top:g}: {onsets}. p = P(mu in a window where a wheel "
            "squeals: from its onset, up to where it is stable again) over the climate, 0 where every onset lies above it; a row's onset holds for its own steady curving (solved at its mu).")
        row("line: share of axles that squeal", c, "-", "axles", lambda s: None,
            "the leading bogie's axles (axles_p_squeal): the field reports passages, not axles.")
    for c in present:
        a, b = fs.STUVA_FREQ.get(c), fs.STUVA_WHEN.get(c)
        if a is None:
            continue
        row("line: mean excess counting how often (dL, STUVA b)", c, f"{a:g} dB(A)", "dL",
            lambda s, a=a: abs(s["dL"] - a) <= fs.TOL_DB, "dL = p x dL_when per curve: the class's p times the "
            "excess of its squealing passages; STUVA's b counts how often the field's curves squeal.", ".2f")
        row("line: mean excess when squealing (dL_when, STUVA a)", c, f"{b:g} dB(A)", "dL_when",
            lambda s, b=b: None if not math.isfinite(s["dL_when"]) else abs(s["dL_when"] - b) <= fs.TOL_DB,
            "one wheel's median squeal level over the train's CNOSSOS-EU rolling L_pA,max; STUVA's a is taken "
            "against Schall 03's straight-track calculation.", ".1f")
    lo, hi = fs.TEMA_LEVEL
    for c in present:
        row("line: L_pA,max at 7.5 m when squealing (train)", c, f"{lo:g}-{hi:g} dB(A) (TEMA)", "L_train",
            lambda s: None if not math.isfinite(s["L_train"]) else lo <= s["L_train"] <= hi,
            "the loudest wheel's median level at the climate's levels above onset, energy-added to the "
            "rolling noise; n/a where no curve of the class can squeal.", ".1f")
    freqs = sorted({round(r["f_onset"]) for r in rows if can(r) and math.isfinite(r["f_onset"])}
                   | {round(r["f_squeal"]) for r in rows if r["squeals"] and math.isfinite(r["f_squeal"])})
    lo_f, hi_f = fs.BAND_F
    ok_f = None if not freqs else any(lo_f <= x <= hi_f for x in freqs)
    t.append(f"| line: squeal frequencies (onset modes of the curves that can squeal, squeal at the rows' "
             f"friction) | all | {lo_f:g}-{hi_f:g} Hz (Czolbe et al.), about {fs.TEMA_F:g} Hz (TEMA) | "
             f"{', '.join(str(x) for x in freqs) or '-'} |" + " (all rows) |" * (len(conds) - 1) + f" {verdict(ok_f)} | the C20 "
             "wheel's own axial modes ((2,0,a) about 435 Hz, (3,0,a) about 1.15 kHz), not the TEMA vehicle's "
             "radial mode. |")
    fm_conds = [k for k in conds if re.search(r"fm|modifier", k, re.I)]
    p_fm = {c: float(np.mean([curve_risk(fm, {"w": cell_onset(r["onset"], r["mu_squeal_range"])})["passages"] for r in rows
                              if r["class"] == c and not r["note"]])) for c in present}
    lo_r, hi_r, mean_r = fs.FM_RANGE
    t.append(f"| line: friction-modifier reduction | all | {lo_r:g}-{hi_r:g} dB(A), mean {mean_r:g} (Eadie & "
             "Santoro) | " + " | ".join("-" for _ in conds) + " | " + " / ".join("n/a" for _ in conds) + " | "
             + (f"the line's conditions ({', '.join(conds)}) hold no friction modifier: not comparable; the "
                "`tor_fm` climate over the line's onsets would give p = " if not fm_conds else
                f"condition(s) {', '.join(fm_conds)} share the line's one climate: not comparable; the `tor_fm` "
                "climate over the line's onsets would give p = ")
             + ", ".join(f"{f(p_fm[c], '.3f')} ({c})" for c in present) + " (its level when squealing needs the "
             "wheels' level tables, not kept in line.csv). |")
    for c in present:
        for rule, key, field in (("CNOSSOS-EU", "cnossos", "+8 dB R <= 300 m, +5 dB to 500 m"),
                                 ("Schall 03", "schall03", "tram: 4 dB r < 200 m" if category == "tram" else
                                  "railway: 8 dB r < 300 m, 3 dB to < 500 m")):
            stuva = fs.STUVA_FREQ.get(c)
            row(f"line: {rule} penalty, penalised iff the line squeals (p > 0)", c, field, key,
                lambda s, key=key: (s[key] > 0) == (s["p"] > 0),
                "the rule penalises by radius alone; the line's excess follows its onsets against the climate"
                + ("" if stuva is None else f" (against STUVA b {stuva:g} dB(A): the rule " + ", ".join(
                    f"{f(stats[(c, k)][key] - stuva, '+.1f')} dB ({k})" for k in conds if (c, k) in stats) + ")")
                + ".", ".3g")
    return "\n".join(t)


def class_table(stats: dict) -> str:
    """The class numbers (what tests/verdict/test_field_line.py recomputes from the committed rows)."""
    t = ["| class (m) | friction | curves | radii (m) | squeal now | p | axles | dL (dB) | dL when (dB) | "
         "L_pA,max train when squealing (dB(A)) | CNOSSOS-EU (dB) | Schall 03 (dB) |", "|" + "---|" * 12]
    for (c, k), s in stats.items():
        t.append(f"| {c} | {k} | {s['curves']} | {', '.join(f'{x:g}' for x in s['radii'])} | {s['squeal_now']} | "
                 f"{f(s['p'], '.3f')} | {f(s['axles'], '.3f')} | {f(s['dL'], '.2f')} | {f(s['dL_when'])} | "
                 f"{f(s['L_train'])} | {f(s['cnossos'], '.3g')} | {f(s['schall03'], '.3g')} |")
    return "\n".join(t)


def figure(rows: list[dict], radius_rows: list[dict]) -> None:
    """Onset against radius: the line's curves (dry, wet) beside the radius study's metro."""
    plt = pyplot()
    climate = load_climate(climate_file(fs.CLIMATE))
    fig, ax = plt.subplots(figsize=(8.5, 4.0))
    colours = {"dry": "tab:orange", "humid": "tab:green", "wet": "tab:blue", "leaves": "tab:brown"}
    for c in climate.conditions:
        ax.axhspan(c.lo, c.hi, color=colours.get(c.name, "0.8"), alpha=0.15, label=f"climate: {c.name} ({c.share:g})")
    top = 0.8
    rs = sorted((r for r in radius_rows if r["vehicle"] == "metro"), key=lambda r: r["R"])
    if rs:
        R, mu = np.array([r["R"] for r in rs]), np.array([r["mu_onset"] for r in rs], float)
        ax.semilogx(R, np.where(np.isfinite(mu), mu, top), "-", color="0.5", lw=0.8)
        ax.plot(R, np.where(np.isfinite(mu), mu, top), "s", color="0.5", mfc="none",
                label="radius study, metro (its design speeds; > 0.8 drawn at 0.8)")
    for cond, mk, col in zip(dict.fromkeys(r["friction"] for r in rows), "oD^v", ("tab:red", "tab:purple", "k", "0.4")):
        sel = [r for r in rows if r["friction"] == cond and not r["note"]]
        R = np.array([r["radius_m"] for r in sel])
        mu = np.array([r["onset"] for r in sel])
        fin = np.isfinite(mu)
        ax.semilogx(R[fin], mu[fin], mk, ms=5, color=col, label=f"line, {cond} rows: onset (<0.1 drawn at 0.1)")
        lim = [float(r["mu_onset"].lstrip(">")) for r in sel if r["mu_onset"].startswith(">")]
        ax.plot(R[~fin], lim, mk, ms=5, mfc="none", color=col,
                label=f"line, {cond} rows: quiet up to (scan stops at the climate's top)")
        w = [r for r in windows(rows) if r["friction"] == cond]
        if w:
            ax.plot([r["radius_m"] for r in w], [r["onset"] for r in w], "kx", ms=9,
                    label=None if cond != "dry" else "a window: stable again above it (mu_squeal_range)")
    ax.set_xlabel("curve radius (m)")
    ax.set_ylabel("onset friction (Coulomb mu)")
    ticks = [25, 50, 100, 200, 300, 500]
    ax.set_xticks(ticks, [str(x) for x in ticks])
    ax.minorticks_off()
    ax.set_ylim(0, 0.85)
    ax.set_title(f"the example line ({LINE}) and the radius study: onset of the leading bogie's first wheel", fontsize=9)
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    save_figure(fig, DOCS / FIGURE, dpi=100)


def section(radius_rows: list[dict], line: str = LINE) -> str:
    """The page's section on the example line (module notes): rows saved, figure drawn, text returned."""
    src = line_csv(line)
    rows = save_line_rows(src)
    vehicles = sorted({r["vehicle"] for r in rows})
    cats = {v: read_vehicle(v).data["category"] for v in vehicles}
    category = "tram" if set(cats.values()) == {"tram"} else "railway"
    stats = class_stats(rows)
    fm = load_climate(climate_file(fs.MODIFIER))
    figure(rows, radius_rows)
    win = windows(rows)
    noted = [r for r in rows if r["note"]]
    bound = state_bound(rows)
    per = {}
    for r, s in bound:
        per.setdefault((r["friction"], s["friction"]), []).append(r)
    bound_text = "; ".join(f"{k[0]} rows below the {k[1]} rows' friction at R = " + ", ".join(
        f"{r['radius_m']:g}" for r in sorted(v, key=lambda r: r["radius_m"])) + " m" for k, v in per.items()) or "none"
    mus = {r["friction"]: r["mu"] for r in rows}
    dry_mu, wet_mu = (", ".join(f"{mus[k]:g}" for k in mus if k == w) or "-" for w in ("dry", "wet"))
    return f"""
{HEADING}

The shipped line study `pipeline/studies/{line}.toml` (`make study STUDY={line}`, built through Make by this writer
when `build/studies/{line}/line.csv` is missing): {len(rows)} rows ({len({r['id'] for r in rows})} curves, R =
{min(r['radius_m'] for r in rows):g}-{max(r['radius_m'] for r in rows):g} m, vehicle {', '.join(f'`{v}` ({cats[v]})'
for v in vehicles)}, conditions {', '.join(dict.fromkeys(r['friction'] for r in rows))}; {len(noted)} rows without a
verdict left out), each row's climate columns over the line's climate `default` (the leading bogie's onsets, the
train's CNOSSOS-EU rolling noise). The same statistics and verdicts as above, per radius class and condition of the
line's CSV (each condition is the whole line under the one climate; the row's own friction sets only its steady
curving, so a curve's dry and wet onsets can differ). Rows: `docs/validation/{ROWS_CSV}` (line.csv's columns);
class numbers recomputed by `tests/verdict/test_field_line.py`; Schall 03 by the vehicle file's `category`.

![the example line: onset against radius](validation/{FIGURE})

{class_table(stats)}

{comparison(rows, stats, category, fm)}

**Instability windows.** {len(win)} rows squeal in a window of friction only: {window_text(win) or 'none'}. There
the onset scan, continued up to the climate's highest level, finds the wheel unstable at low friction and stable
again above the window (a growth rate of a few 1/s at most), and the row's p_squeal is the climate's share of the
window, not of everything above the onset (docs/friction_climate.md, section 6).

**Dry rows against wet rows.** Each row's onset is scanned on its own steady curving state, solved at its own
friction (dry {dry_mu}, wet {wet_mu}). {len(bound)} rows have their onset below the friction of the same curve's other row, where
that row is quiet and its own scan quiet beyond it: {bound_text}. A passage of the climate curves at its own
friction, nearer one row's state or the other's; these rows' p_squeal (and the classes' p and dL built on them)
rest on the curving state of their condition, and the dry and wet columns above part where they occur.
"""


def main(argv=None) -> int:
    """This section alone into the committed page (the radius study's points from its committed rows)."""
    page = (DOCS / "96_field_statistics.md").read_text(encoding="utf-8")
    with open(DOCS / "96_field_statistics.csv", newline="", encoding="utf-8") as fh:
        radius_rows = [{"vehicle": r["vehicle"], "R": float(r["R"]), "mu_onset": float(r["mu_onset"])}
                       for r in csv.DictReader(fh)]
    head = page.split("\n" + HEADING, 1)[0].rstrip("\n") + "\n"
    save_text(head + section(radius_rows), DOCS / "96_field_statistics.md")
    assemble_validation()                          # docs/validation.md, as `make validate` ends
    print(f"wrote the example line's section of docs/validation/96_field_statistics.md ({ROWS_CSV}, {FIGURE})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
