"""The radius study's onsets checked by the time loop (issue 32):

    .venv/bin/python -m pipeline.validation.onset_radius [--bases r150,y25_r300,tram_r100] [--radii 25,50,...]

For each base curve's vehicle (``--bases``: shipped curve names; the metro's r150, the freight wagon's
y25_r300, the tram's tram_r100) at each radius (speed and cant from the vehicle's design rule,
``pipeline.validation.radius_design.design_of``: the radius study's, a street track's for the tram;
curves made by ``pipeline.curve.curvefiles.radius_curve``), every wheel
of the leading bogie: its onset (``pipeline.curve.onset.wheel_onset``: the stability screen's growth
rate over mu 0.1-0.8, then brentq) and the time loop 0.02 above it (should squeal) and 0.02 below it
(should be quiet); a wheel without onset in the range: the time loop at 0.78 (should be quiet).  The
screen's arrays are built in memory (``pipeline.curve.screen_first.screen_context``), no stage artifact
is written.  Writes build/studies/onset_radius/onset.csv and prints a markdown table with every
disagreement listed.  Cost: a new speed builds the rail's moving kernel (minutes the first time,
cached after); each quiet time-loop run rolls up to 8 s.
"""
from __future__ import annotations

import argparse
import logging
import math
import subprocess

from pipeline.config.case import given
from pipeline.curve.cases import wheel_case
from pipeline.curve.curvefiles import radius_curve
from pipeline.curve.curving import solve_curve
from pipeline.curve.onset import MU_HI, level_row, wheel_onset
from pipeline.curve.screen_first import screen_context
from pipeline.curve.what_ifs import CaseModels
from pipeline.store import artifacts, paths
from pipeline.validation.radius_design import design_of

RADII = (25.0, 50.0, 75.0, 100.0, 150.0, 200.0, 300.0, 400.0, 600.0)
BASES = ("r150", "y25_r300", "tram_r100")
DELTA = 0.02
COLUMNS = ["base", "R", "V", "cant_mm", "wheel", "mu_onset", "mode_onset", "f_onset", "mu_below", "L_F2_below",
           "mu_above", "L_F2_above", "agrees"]


def check_curve(base: str, radius: float) -> list[dict]:
    """The rows (``COLUMNS``) of one curve of the study."""
    V, cant = design_of(base, radius)
    folder = paths.build() / "studies" / "onset_radius" / "curves"
    curve = radius_curve(base, folder, radius, V, cant, name=f"{base}-R{radius:g}-V{V:g}")
    sol = solve_curve(curve)
    # the wheel's modes and the rail's tables, built by Make when missing (as `make curve` does)
    subprocess.run(["make", "-s", "--no-print-directory", f"build/wheels/{sol.curve.wheel}/modes.npz",
                    f"build/rails/{sol.curve.rail}/rail.npz", f"WHEEL={sol.curve.wheel}", f"RAIL={sol.curve.rail}",
                    "CASE=default"], cwd=paths.ROOT, check=True)
    cases = [wheel_case(sol.curve, p) for p in sol.wheels]
    rows = []
    with given(cases):
        for p, rc in zip(sol.wheels, cases):
            row = {"base": base, "R": radius, "V": V, "cant_mm": 1e3 * cant, "wheel": p.wheel}
            if p.gamma_y == 0.0:
                rows.append(row | {"mu_onset": ">0.8", "agrees": "pure rolling"})
                continue
            models = CaseModels.of_context(screen_context(rc))
            on = wheel_onset(models, p.gamma_y)
            row |= {"mu_onset": on.cell(), "mode_onset": on.mode, "f_onset": on.f_hz}
            if math.isfinite(on.mu):
                lo, hi = level_row(models, max(on.mu - DELTA, 0.01), None), level_row(models, on.mu + DELTA, None)
                ok = (not lo["squeals"]) and hi["squeals"]
            else:
                lo, hi = level_row(models, MU_HI - DELTA, None), {"mu": math.nan, "L_F2": math.nan}
                ok = not lo["squeals"]
            rows.append(row | {"mu_below": lo["mu"], "L_F2_below": lo["L_F2"], "mu_above": hi["mu"],
                               "L_F2_above": hi["L_F2"], "agrees": "yes" if ok else "NO"})
            logging.getLogger("pipeline.onset").info("%s R = %g m %s: onset %s, %s", base, radius, p.wheel,
                                                      on.cell(), rows[-1]["agrees"])
    return rows


def markdown(rows: list[dict]) -> str:
    f = lambda x, s=".1f": "-" if not isinstance(x, float) or not math.isfinite(x) else f"{x:{s}}"  # noqa: E731
    out = ["| vehicle base | R (m) | V (km/h) | wheel | mu_onset | mode | f (Hz) | L_F2 below / above (dB) | agrees |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['base']} | {r['R']:g} | {r['V']:g} | {r['wheel']} | {r['mu_onset']} | "
                   f"{r.get('mode_onset') or '-'} | {f(r.get('f_onset'), '.0f')} | {f(r.get('L_F2_below'))} / "
                   f"{f(r.get('L_F2_above'))} | {r['agrees']} |")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.validation.onset_radius", description=__doc__.split("\n\n")[0])
    ap.add_argument("--bases", default=",".join(BASES))
    ap.add_argument("--radii", default=",".join(f"{r:g}" for r in RADII))
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    rows = []
    out = paths.build() / "studies" / "onset_radius" / "onset.csv"
    cell = lambda x: f"{x:.6g}" if isinstance(x, float) and math.isfinite(x) else ("" if isinstance(x, float) else x)  # noqa: E731
    for base in args.bases.split(","):
        for R in (float(x) for x in args.radii.split(",")):
            rows += check_curve(base, R)           # the table so far, after every curve (a long run)
            artifacts.save_csv(out, COLUMNS, ([cell(r.get(k, "")) for k in COLUMNS] for r in rows))
    print(markdown(rows))
    bad = [r for r in rows if r["agrees"] == "NO"]
    print(f"\n{len(rows)} wheels, {len(bad)} disagreements -> {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
