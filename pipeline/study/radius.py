"""The radius study: the metro vehicle on curves of radius 50 to 1000 m at its usual speeds, cant as
designed; the curve stage's verdict for each (screen for every wheel, time loop where unstable),
and the table of where squeal starts, which wheel squeals, its frequency and L_pA
(docs/validation/91_verdict.md with verdict_radius.png).

    .venv/bin/python -m pipeline.study.radius [--base r150] [--radii 50,75,...] [--no-docs] [--rerun]

Each radius is a Curve made from the base curve (``--base``, a shipped curve of the metro vehicle or
a curve file's path) with its radius, speed and cant replaced (``pipeline.curve.curvefiles``), its
curve file written as a record under ``build/studies/radius/curves/``; the Curve goes to the curve
stage in memory.  Its verdict lands in ``build/curves/<name>/`` and is reused while it is newer
than its curve file (``--rerun`` runs it again).

Speed and cant (a stated design rule, not a measured one): the speed is the metro's line speed
``V_MAX`` or, lower, the speed at which the lateral acceleration in the track plane reaches
``A_TOTAL`` (cant plus cant deficiency); the cant is designed for ``CANT_SHARE`` of that lateral
acceleration, at most ``CANT_MAX`` (the rest is cant deficiency).
"""
from __future__ import annotations

import argparse
import logging
import math
import sys
from pathlib import Path

import numpy as np
from pipeline.store import paths
from pipeline.config.curve_inputs import curve_name
from pipeline.curve.curvefiles import radius_curve
from pipeline.curve.stage import read_verdict, run_curve
from pipeline.store.atomic import save_figure, save_text
from pipeline.config.loader import ConfigError
from pipeline.progress import progress

RADII = (50.0, 75.0, 100.0, 150.0, 200.0, 300.0, 500.0, 1000.0)
V_MAX = 70.0             # km/h, metro line speed
A_TOTAL = 1.0            # m/s^2 lateral acceleration at the design speed (cant + deficiency)
CANT_SHARE = 2.0 / 3.0   # share of it the cant compensates
CANT_MAX = 0.150         # m
G = 9.81
TRACK = 1.5              # m between the rolling circles, for the cant's angle

log = logging.getLogger("pipeline.curve")


def design(radius: float) -> tuple[float, float]:
    """(speed km/h, cant m) of the design rule (module notes)."""
    v = min(V_MAX / 3.6, math.sqrt(A_TOTAL * radius))
    a = v * v / radius
    cant = min(CANT_MAX, CANT_SHARE * a * TRACK / G)
    return round(3.6 * v, 1), round(cant, 4)


def table_markdown(rows: list[dict]) -> str:
    """The study's table: one row per radius (the loudest wheel's verdict)."""
    out = ["| R (m) | V (km/h) | cant (mm) | wheels unstable (screen) | squealing wheels (time loop) | f (Hz) | mode | "
           "L_pA at 7.5 m (dB(A)) | mu below which it stops |", "|" + "---|" * 9]
    for r in rows:
        out.append(f"| {r['R']:g} | {r['V']:g} | {1e3 * r['cant']:.0f} | {r['unstable'] or '-'} | "
                   f"{r['squealing'] or 'none'} | {r['f']} | {r['mode']} | {r['L_pA']} | {r['mu_stop']} |")
    return "\n".join(out)


def summarise(R: float, V: float, cant: float, verdict_rows: list[dict]) -> dict:
    """One study row from a curve's verdict rows."""
    sq = [r for r in verdict_rows if r["squeals"]]
    loud = max(sq, key=lambda r: r["L_pA"] if math.isfinite(r["L_pA"]) else -1e9) if sq else None
    fmt = lambda x, s: "-" if x is None or not math.isfinite(x) else f"{x:{s}}"   # noqa: E731
    return {"R": R, "V": V, "cant": cant,
            "unstable": ", ".join(r["wheel"] for r in verdict_rows if math.isfinite(r["screen_sigma"])),
            "squealing": ", ".join(r["wheel"] for r in sq),
            "f": fmt(loud["f_squeal"], ".0f") if loud else "-", "mode": loud["mode"] if loud else "-",
            "L_pA": fmt(loud["L_pA"], ".1f") if loud else "-",
            "mu_stop": fmt(loud["mu_threshold"], ".3f") if loud else "-",
            "L_pA_value": loud["L_pA"] if loud else math.nan,
            "aoa": max((abs(r["angle_of_attack"]) for r in verdict_rows), default=math.nan),
            "gamma_y_a1i": next((r["gamma_y"] for r in verdict_rows if r["wheel"] == "a1i"), math.nan),
            "gamma_x_a1i": next((r["gamma_x"] for r in verdict_rows if r["wheel"] == "a1i"), math.nan),
            "disagree": ", ".join(
                f"{r['wheel']}: gamma_y = {r['gamma_y']:+.5f}, gamma_x = {r['gamma_x']:+.5f}; screen "
                + (f"{r['screen_mode']} {r['screen_sigma']:+.1f} 1/s" if math.isfinite(r["screen_sigma"]) else "stable")
                + f", time loop L_F2 = {r['L_F2']:.1f} dB" for r in verdict_rows
                if math.isfinite(r["screen_sigma"]) != bool(r["squeals"]))}


def figure(rows: list[dict]):
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.8))
    R = np.array([r["R"] for r in rows])
    ax.semilogx(R, [1e3 * r["aoa"] for r in rows], "o-", label="largest |angle of attack| (mrad)")
    ax.semilogx(R, [-1e3 * r["gamma_y_a1i"] for r in rows], "s-", label="-gamma_y of a1i (x1e-3)")
    ax.semilogx(R, [-1e3 * r["gamma_x_a1i"] for r in rows], "^-", label="-gamma_x of a1i (x1e-3)")
    ax.set_xlabel("curve radius (m)")
    ax.legend(fontsize=8)
    ax.set_title("steady curving of the leading bogie", fontsize=9)
    lpa = np.array([r["L_pA_value"] for r in rows], float)
    bx.semilogx(R, np.where(np.isfinite(lpa), lpa, np.nan), "o-", color="crimson")
    for r, l in zip(R, lpa):
        if not np.isfinite(l):
            bx.plot(r, 0, "x", color="0.4")
    bx.set_ylim(bottom=0)
    bx.set_xlabel("curve radius (m)")
    bx.set_ylabel("L_pA of the loudest wheel at 7.5 m (dB(A))")
    bx.set_title("verdict (x: no squeal)", fontsize=9)
    fig.tight_layout()
    return fig


def curve_verdict(base: str, folder: Path, radius: float, speed_kmh: float | None = None, *,
                  reuse: bool = True, cant_m: float | None = None) -> dict:
    """The verdict rows of the base curve's vehicle at ``radius`` (speed: given, or the design rule's;
    cant: the design rule's), from build/curves/<name>/verdict.csv when it is newer than its curve
    file (``reuse``), else by running the curve stage.  {'name', 'R', 'V', 'cant', 'rows'}."""
    V, cant = design(radius)
    V = V if speed_kmh is None else float(speed_kmh)
    cant = cant if cant_m is None else float(cant_m)          # another vehicle's design rule (field statistics)
    curve = radius_curve(base, folder, radius, V, cant, name=f"{curve_name(base)}-R{radius:g}-V{V:g}")
    csv = paths.curve_dir(curve.name) / "verdict.csv"
    if reuse and csv.exists() and csv.stat().st_mtime > curve.source.stat().st_mtime:
        rows = read_verdict(csv)
    else:
        rows = run_curve(curve)["rows"]
    return {"name": curve.name, "R": radius, "V": V, "cant": cant, "rows": rows}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.study.radius", description=__doc__.split("\n\n")[0])
    ap.add_argument("--base", default="r150", help="the metro curve the radii are made from (pipeline/curves/)")
    ap.add_argument("--radii", default=",".join(f"{r:g}" for r in RADII))
    ap.add_argument("--no-docs", action="store_true", help="do not write docs/validation/91_verdict.md")
    ap.add_argument("--rerun", action="store_true", help="run every curve again (default: reuse newer verdicts)")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")

    folder = paths.build() / "studies" / "radius" / "curves"
    rows = []
    try:
        for R in progress([float(x) for x in args.radii.split(",")], desc="radius study", unit="curve"):
            v = curve_verdict(args.base, folder, R, reuse=not args.rerun)
            rows.append(summarise(R, v["V"], v["cant"], v["rows"]))
            log.info("radius %g m: %s", R, rows[-1]["squealing"] or "no squeal")
    except ConfigError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    table = table_markdown(rows)
    save_text(table + "\n", paths.build() / "studies" / "radius" / "table.md")
    if not args.no_docs:
        docs = Path(paths.ROOT) / "docs" / "validation"
        save_figure(figure(rows), docs / "verdict_radius.png", dpi=100)
        save_text(doc_fragment(args.base, table, rows), docs / "91_verdict.md")
    print(table)
    return 0


def doc_fragment(base: str, table: str, rows: list[dict]) -> str:
    radii = ", ".join(f"{r['R']:g}" for r in rows)
    sq = [r for r in rows if r["squealing"]]
    quiet_above = [r for r in rows if not r["squealing"] and sq and r["R"] > max(x["R"] for x in sq)]
    if sq and quiet_above:
        start = (f"Squeal starts between R = {min(x['R'] for x in quiet_above):g} m (quiet) and "
                 f"{max(x['R'] for x in sq):g} m (squeals): at {max(x['R'] for x in sq):g} m and below the "
                 f"wheels {', '.join(sorted({w for x in sq for w in x['squealing'].split(', ')}))} squeal")
    elif sq:
        start = "Every radius squeals"
    else:
        start = "No radius squeals"
    dis = [f"{r['R']:g} m ({r['disagree']})" for r in rows if r["disagree"]]
    agree = ("The screen and the time loop agree at every wheel of every radius" if not dis else
             "The screen and the time loop disagree at " + "; ".join(dis) + " (squeal needs the time loop's "
             "L_F2 >= 10 dB: the time loop's verdict is the one reported)")
    return (f"## The verdict over curve radius (metro vehicle)\n\n"
            f"The curve stage's verdict (`make curve`) for the metro vehicle of `pipeline/curves/{base}.toml` (C20 "
            f"wheel, BV50, mu = 0.35) on radii {radii} m at its usual speeds, cant as designed (speed: "
            f"{V_MAX:g} km/h or less so that the lateral acceleration stays {A_TOTAL:g} m/s^2, cant for "
            f"{CANT_SHARE:.2f} of it, at most {1e3 * CANT_MAX:g} mm: `pipeline/study/radius.py`).  Every wheel of "
            f"the leading bogie is screened and run in the time loop (squeal: L_F2 >= 10 dB re 1 N, SPEC 6); the "
            f"squealing ones radiate and are heard at 7.5 m, 1.2 m.  {start}.  {agree}.\n\n{table}\n\n"
            "![verdict over radius](validation/verdict_radius.png)\n\n"
            "Why not above: the curving wheelset's longitudinal creepage.  The inner leading wheel's lateral "
            "creepage grows as the radius shrinks (left), but it rolls with a longitudinal creepage too (the "
            "rolling-radius difference does not match the curve); in full slip the creep force follows the slip's "
            "direction, and a lateral slip oscillation then turns the force instead of sliding it along the "
            "falling-free Coulomb curve.  At R = 150 m (`make curve CURVE=r150`, 50 km/h) the wheel a1i has "
            "gamma_y = -0.0114, gamma_x = -0.0053, spin -0.24 1/m: the screen finds every mode decaying and the "
            "time loop decays (L_F2 = -53 dB); the same wheel with gamma_x and spin set to zero has a (2,0,a) pole "
            "growing at +11.5 1/s and squeals in the time loop (L_F2 = 50.9 dB at 434.8 Hz), as the thesis' "
            "default case (gamma_x = 0) does.\n\n"
            "Written by `.venv/bin/python -m pipeline.study.radius` (nothing fitted; the friction is the base "
            "curve's).\n")


if __name__ == "__main__":
    sys.exit(main())
