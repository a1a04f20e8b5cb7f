"""docs/validation/94_line.md: the example line's rule comparison with its plots, and how often the
screen-first verdict could differ from ``make curve``'s (issue 27).

    .venv/bin/python -m pipeline.validation.line_doc [--study metro_line] [--radii 50,75,...]

Reads the line study (``make study STUDY=metro_line``, run through Make here: build/studies/<line>/line.csv and
its figures, copied beside the fragment) and runs the curve stage (every wheel screened and run in the time
loop, no what-ifs) over the radius study's curves (``pipeline.study.radius``: the metro on R = 50-1000 m at
its design speeds, cant as designed): a wheel the screen finds stable but the time loop makes squeal is one
the screen-first path would call quiet.
"""
from __future__ import annotations

import argparse
import csv
import math
import shutil
import sys
from pathlib import Path
import logging
from pipeline.store import paths
from pipeline.curve.curvefiles import radius_curve
from pipeline.study.radius import design
from pipeline.curve.stage import run_curve
from pipeline.store.atomic import save_text, atomic_write
from pipeline.validation.make import make_targets

FRAGMENT = "94_line.md"


def screen_against_time_loop(radii, base: str = "r150") -> list[dict]:
    """Per wheel of each radius: the screen's verdict (a growing wheel-mode pole) and the time loop's."""
    folder = paths.build() / "studies" / "radius" / "curves"
    out = []
    for R in radii:
        V, cant = design(R)
        curve = radius_curve(base, folder, R, V, cant, name=f"{base}-R{R:g}-V{V:g}-nowhatif")
        for r in run_curve(curve, progress_bar=False, what_ifs=False)["rows"]:
            out.append({"R": R, "V": V, "wheel": r["wheel"], "unstable": math.isfinite(r["screen_sigma"]),
                        "squeals": bool(r["squeals"]), "screen": r["screen_mode"], "L_F2": r["L_F2"],
                        "gamma_y": r["gamma_y"]})
    return out


def fragment(line: str, rows: list[dict], md: str, checks: list[dict]) -> str:
    missed = [c for c in checks if c["squeals"] and not c["unstable"]]
    overruled = [c for c in checks if c["unstable"] and not c["squeals"]]
    lgy = [c for c in checks if c["gamma_y"] != 0.0]
    radii = sorted({c["R"] for c in checks})
    line_unstable = sum(len(r["time_loop_wheels"].split()) for r in rows)
    line_squeal = sum(len(r["squealing_wheels"].split()) for r in rows)
    paras = [p.strip() for p in md.split("\n\n") if p.strip()]
    verdict = "\n\n".join(p for p in paras[1:3] if not p.startswith("The rules beside"))
    rules = md[md.index("The rules beside"):md.index("![level")] if "The rules beside" in md else ""
    dis = "; ".join(f"R = {c['R']:g} m {c['wheel']} (time loop L_F2 = {c['L_F2']:.1f} dB)" for c in missed) or "none"
    over = "; ".join(f"R = {c['R']:g} m {c['wheel']} ({c['screen']})" for c in overruled) or "none"
    return f"""## A line of curves against the noise-mapping rules (issue 27)

The example line study `pipeline/studies/{line}.toml` (`make study STUDY={line}`): a synthetic metro line, not a
real one (how its curves were chosen: the comments of `{line}.csv`: 30 radii log-spaced over 40-600 m in a
shuffled order, speeds and cant from the radius study's design rule), the C20 metro, every curve on dry and
on wet rail.  Each row is the curve verdict of `make curve`, screen first (`pipeline/curve/screen_first.py`).
The rules compared, by radius alone: CNOSSOS-EU (+8 dB for R <= 300 m, +5 dB for 300 < R <= 500 m on the
rolling noise, Directive (EU) 2015/996 Annex II 2.3 as amended by Delegated Directive (EU) 2021/1226; the
classes as the issue states them) and Schall 03 (16. BImSchV Anlage 2, 2014, section 4.9, Tabelle 11 rows 1-3,
"Kurvenfahrgeraeusch bei Eisenbahnstrecken": K_L = 8 dB for R < 300 m, 3 dB for 300 m to < 500 m, 0 from
500 m; read in the ordinance's text as published at lexcada.com/akn/de/act/1990-06-12/16._BImSchV).

{verdict}

{rules}
![the line: level against radius](validation/line_level_radius.png)

![the line along its chainage, with each rule's penalty](validation/line_chainage.png)

What this does and does not say: the rules add a fixed penalty to the rolling noise wherever the radius is
small; the physics says whether this vehicle squeals in this curve at this speed and friction, and how loud
(the squeal's own level, not a correction to rolling noise).  A rule's "penalised, quiet" is a curve the
model finds stable for this vehicle and friction; "missed" is one it finds squealing above the rule's radius
classes.  The model's limits apply (docs/physics.md; docs/validation.md "Against the field"): one vehicle,
Coulomb friction, the leading bogie only, no field data of this line.

**Screen first against the curve stage.**  The line runs the time loop only for the wheels the stability
screen finds unstable.  Over the radius study's curves (R = {', '.join(f'{r:g}' for r in radii)} m, the metro at
its design speeds, mu = 0.35; `make curve`'s verdict for every wheel, the time loop run for all), **{len(missed)}
of the {len(lgy)} wheels with lateral creepage squeal in the time loop while the screen calls them stable**
({dis}): those the screen-first path would call quiet.  {len(overruled)} wheels are unstable in the screen while
their time loop decays ({over}); the screen-first path runs their time loop and reports them quiet, as `make
curve` does.  On the example line itself, {line_unstable} wheels were unstable in the screen and run in the
time loop, {line_squeal} of them squeal.  The screen-first verdict of a squealing wheel is `make curve`'s own (the
same stages), and its screen numbers are `make curve`'s bit for bit (tests/verdict/test_screen_first.py).

Written by `.venv/bin/python -m pipeline.validation.line_doc` from build/studies/{line}/ (`make validate`, which
runs the study through Make; `tests/study/test_line_validation.py` asserts the line's table).
"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.validation.line_doc", description=__doc__.split("\n\n")[0])
    ap.add_argument("--study", default="metro_line")
    ap.add_argument("--radii", default="50,75,100,150,200,300,500,1000")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)


    out = paths.build() / "studies" / args.study
    make_targets("study", STUDY=args.study)           # run, or resumed when done (its rows are kept)
    rows = list(csv.DictReader(open(out / "line.csv")))
    docs = Path(paths.ROOT) / "docs" / "validation"
    for src, dst in (("level_radius.png", "line_level_radius.png"), ("chainage.png", "line_chainage.png")):
        with atomic_write(docs / dst) as tmp:
            shutil.copyfile(out / src, tmp)
    checks = screen_against_time_loop([float(r) for r in args.radii.split(",")])
    save_text(fragment(args.study, rows, (out / "line.md").read_text(), checks), docs / FRAGMENT)
    print(docs / FRAGMENT)
    return 0


if __name__ == "__main__":
    sys.exit(main())
