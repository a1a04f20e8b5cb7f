"""The curve stage: from a curve and a vehicle to a verdict (``make curve CURVE=<name or path>``,
``python -m pipeline curve --curve <name or path>``; a path may lie outside the repository:
``pipeline.config.curve_inputs``).

1. the curve file is read once into a ``Curve`` (its ``Vehicle`` and ``FrictionLaw``), then steady
   curving of the leading bogie (``pipeline.curve.curving.solve_curve``): every wheel's
   ``WheelOperatingPoint``;
2. each wheel becomes a ``ResolvedCase`` in memory (``cases.py``), handed to the stages
   (``pipeline.config.case.given``); its case file ``$BUILD/curves/<curve>/cases/<wheel>.toml`` is
   written as a record (``make <stage> CASE=<curve>/<wheel>``), not read back;
3. contact, greens and the stability screen for every wheel (the screen through
   ``mitigation.CaseModels``, which also takes a wheel whose lateral creepage is positive, as the
   mirror image y -> -y of the point-contact loop: its cross receptances change sign);
4. the time loop (simulate) for every wheel with lateral creepage: it confirms or overrules the
   screen (squeal is L_F2 >= 10 dB, SPEC 6; a stable wheel's run decays within a second or two);
   for the squealing wheels radiate and listen, and the mitigation what-ifs (``mitigation.py``);
5. ``build/curves/<curve>/verdict.csv`` (one row per wheel), ``verdict.md`` (read first),
   ``bogie.png`` (the bogie in the curve with its contact points) and ``verdict.json`` (the rows
   with their provenance: the curve, vehicle and case configurations, git revision, versions),
   all written atomically.
"""
from __future__ import annotations

import logging
import math
import time
import csv

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure, save_text
from pipeline.progress import progress
from pipeline.config.nouns import OPERATING_FIELDS, Curve, WheelOperatingPoint
from pipeline.config.loader import ConfigError, issue_text
from pipeline.config.curve_inputs import read_curve
from pipeline.curve.curving import solve_curve
from pipeline.stages.greens import run_greens
from pipeline.stages.listen import run_listen, listen_files, receiver_tag
from pipeline.stages.radiate import run_radiate
from pipeline.stages.simulate import run_simulate
from solvers.stability.mitigation import growing_wheel_root
from pipeline.curve.what_ifs import CaseModels, damping_what_if, friction_what_if
from pipeline.curve.modifier import modifier_what_if
from solvers.study import nearest_mode, squeals
from pipeline.config.case import given
from pipeline.curve import figures as plot, verdict_report as report
from pipeline.curve.cases import wheel_case, write_case
from pipeline.curve import risk, train
from solvers.radiation.squeal_excess import climate_excess
from pipeline.curve.verdict_html import write_page

log = logging.getLogger("pipeline.curve")

COLUMNS = ["wheel", "dy_wr", "angle_of_attack", "gamma_x", "gamma_y", "spin", "y_wheel", "y_rail", "contact_angle",
           "wheel_load", "contact_points", "nadal", "screen_sigma", "screen_f", "screen_mode", "squeals", "f_squeal",
           "mode", "L_F2", "L_W", "L_pA", "mu_threshold", "zeta_needed", "wav"] + risk.COLUMNS + train.COLUMNS
UNITS = {"dy_wr": "m", "angle_of_attack": "rad", "spin": "1/m", "y_wheel": "m", "y_rail": "m", "contact_angle": "rad",
         "wheel_load": "N", "screen_sigma": "1/s", "screen_f": "Hz", "f_squeal": "Hz", "L_F2": "dB re 1 N",
         "L_W": "dB re 1 pW", "L_pA": "dB(A) re 20 uPa"}


def one_line(e):
    """A ConfigError with its problems on one line (file: key = value: expected range; ...)."""
    if not e.errors:
        return e
    return ConfigError(e.source, detail="; ".join(issue_text(*x) for x in e.errors))


def solve(curve):
    """The curving solution of ``curve`` (a Curve, a path to a curve file or a shipped name;
    pipeline.curve.curving; a bad curve or vehicle file: a ConfigError in one line)."""
    from solvers.curving import CurvingError  # lazy: brings in numba, rocket_fft, scipy

    try:
        curve = read_curve(curve)
        return solve_curve(curve)
    except ConfigError as e:
        raise one_line(e) from None
    except CurvingError as e:          # no equilibrium: the curve and vehicle are valid, the verdict has no input
        raise ConfigError(str(curve.source), detail=f"no steady curving state: {e}") from None


def operating_row(p: WheelOperatingPoint) -> dict:
    """A verdict.csv row of a wheel before its verdict: its operating point's columns, the rest empty."""
    row = {k: getattr(p, k) for k in COLUMNS if k in OPERATING_FIELDS}
    return row | {"screen_sigma": math.nan, "screen_f": math.nan, "screen_mode": "", "squeals": False,
                  "f_squeal": math.nan, "mode": "", "L_F2": math.nan, "L_W": math.nan, "L_pA": math.nan,
                  "mu_threshold": math.nan, "zeta_needed": "", "wav": ""} | risk.EMPTY | dict.fromkeys(train.COLUMNS, math.nan)


def run_stages(name: str, stages) -> None:
    """Run the pipeline stages ``stages`` for the case ``name`` in this process."""
    from pipeline.stages.contact import run_contact  # lazy: brings in numba, rocket_fft, scipy

    run = {"contact": run_contact, "greens": run_greens, "simulate": run_simulate, "radiate": run_radiate,
           "listen": lambda n: run_listen(n, allow_silent=True)}
    for s in stages:
        run[s](name)


def screen_wheel(name: str, gamma_y: float) -> tuple:
    """(models, fastest growing wheel-mode pole or None, label) of a curve wheel's case."""
    models = CaseModels(name)
    if gamma_y == 0.0:
        return models, None, ""
    r = growing_wheel_root(models.roots(models.ctx.mu))
    return models, r, (models.ctx.label(r.mode) if r is not None else "")


def wheel_verdict(curve: Curve, p: WheelOperatingPoint, *, what_ifs: bool = True, passby: bool = True) -> dict:
    """One verdict.csv row: contact, greens and the screen for the wheel's case; the time loop (the
    simulate stage) for every wheel with lateral creepage, confirming or overruling the screen; for a
    squealing wheel radiation, listening (its pass-by WAV when ``passby``) and the mitigation what-ifs.
    The wheel's ResolvedCase is the one handed to the stages (``pipeline.config.case.given``)."""
    name = f"{curve.name}/{p.wheel}"
    row = operating_row(p)
    run_stages(name, ["contact", "greens"])
    models, root, label = screen_wheel(name, p.gamma_y)
    if root is not None:
        row |= {"screen_sigma": float(root.sigma), "screen_f": float(root.f_hz), "screen_mode": label}
    if p.gamma_y == 0.0:                      # pure rolling: no lateral creep force, nothing to drive squeal
        return row
    run_stages(name, ["simulate"])            # the time loop confirms (or overrules) the screen's verdict
    d = paths.case_dir(name)
    sim = dict(np.load(d / "simulate.npz", allow_pickle=False))

    L_F2, f = float(sim["L_F2"]), float(sim["f_dominant"])
    row["squeals"] = squeals(L_F2)
    row |= {"L_F2": L_F2, "f_squeal": f if row["squeals"] else math.nan}
    if row["squeals"]:
        run_stages(name, ["radiate"])
        run_listen(name, allow_silent=True, passby=passby)
        rad = dict(np.load(d / "radiate.npz", allow_pickle=False))
        lis = dict(np.load(d / "listen.npz", allow_pickle=False))
        w = models.ctx.wheel
        i = nearest_mode(f, w["f"], models.ctx.flexible, 0.05, (1, 2, 3))

        wav = listen_files(name, receiver_tag(lis["distance"], lis["height"]))["wav"]   # listen_<receiver>.wav
        row |= {"mode": models.ctx.label(i) if i is not None else "", "L_W": float(rad["L_W"]),
                "L_pA": float(lis["L_pA"]), "wav": str(wav)}
        if what_ifs:
            fr = friction_what_if(models)
            row["mu_threshold"] = fr.threshold
            row["friction_what_if"] = fr
            dm = damping_what_if(models)
            final = {}
            for lab, fm, z0, z in dm.modes:          # a mode damped twice: its first nominal, its last need
                final[lab] = (fm, final.get(lab, (fm, z0, z))[1], z)
            row["zeta_needed"] = "; ".join(f"{lab} {z:.2g}" for lab, (fm, z0, z) in final.items())
            row["damping_what_if"] = dm
            row["modifier_what_if"] = modifier_what_if(models, row)   # the rail treated with a friction modifier
    return row


def checked_cases(info: Curve, points) -> list:
    """Every wheel's case (``cases.wheel_case``: its operating point inside a case's range) and the friction
    climate's file (issue 32), checked before any work: what the stage and ``make check CURVE=`` refuse."""
    cases = [wheel_case(info, p) for p in points]
    risk.curve_climate(info)
    return cases


def run_curve(curve, *, progress_bar: bool = True, what_ifs: bool = True) -> dict:
    """The verdict of ``curve`` (a Curve, a path to a curve file or a shipped name; module notes).
    Returns {'rows', 'info' (the Curve), 'paths'}."""
    t0 = time.perf_counter()
    sol = solve(curve)
    info, points = sol.curve, sol.wheels
    cases = checked_cases(info, points)
    for rc in cases:
        write_case(rc)
    rows = []
    with given(cases):
        for p in progress(points, enabled=progress_bar, desc=f"curve {info.name}", unit="wheel"):
            rows.append(wheel_verdict(info, p, what_ifs=what_ifs))
        risk_md, shares = risk.add_risk(info, points, rows)  # onset, level tables, climate (issue 32)
    whole = train.train_verdict(info, rows, wheel_verdict)   # the trailing bogie, the pass-by, rolling noise
    loudest = max((r["L_pAmax_7m5"] for r in rows if math.isfinite(r["L_pAmax_7m5"])), default=math.nan)
    whole["columns"]["dL_squeal"] = climate_excess(whole["columns"]["L_pAmax_rolling"], loudest, shares["passages"]
                                                   if math.isfinite(shares["passages"]) else 0.0)
    for r in rows:
        r |= whole["columns"]
    out = paths.curve_dir(info.name)
    artifacts.save_csv(out / "verdict.csv", COLUMNS, ([report.cell(r[k]) for k in COLUMNS] for r in rows))
    save_figure(plot.bogie_figure(info, points, rows), out / "bogie.png", dpi=110)
    md = report.verdict_markdown(info, points, rows, wall=time.perf_counter() - t0) + "\n" + whole["text"]
    md = md.replace("| wheel |", risk_md + "| wheel |", 1)        # onset and risk before the table (issue 32)
    save_text(md, out / "verdict.md")
    page = write_page(out, info, rows, md)        # verdict.html and headline.txt (`make` prints it last)
    cfg = {"curve": info.data, "vehicle": info.vehicle.data, "cases": [rc.case for rc in cases], "what_ifs": what_ifs}
    artifacts.save_json(out / "verdict.json", "curve-verdict", cfg,
                        [{k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                          for k, v in r.items() if k in COLUMNS} for r in rows])
    loud = report.loudest(rows)
    log.info("curve %s: %s -> %s", info.name, f"{loud['wheel']} squeals at {loud['f_squeal']:.0f} Hz, "
             f"L_pA = {loud['L_pA']:.1f} dB(A)" if loud else "no wheel squeals", out / "verdict.md")
    return {"rows": rows, "info": info, "paths": {"csv": out / "verdict.csv", "md": out / "verdict.md",
                                                 "png": out / "bogie.png", "html": page}}


def read_verdict(path) -> list[dict]:
    """The rows of a verdict.csv (floats, NaN for empty cells; ``squeals`` bool; ``contact_points`` int)."""
    text = {"wheel", "screen_mode", "mode", "zeta_needed", "wav", "mu_onset", "mu_squeal_range", "mode_onset"}
    rows = []
    with open(path, newline="", encoding="utf-8") as fh:
        for r in csv.DictReader(fh):
            row = {k: (v if k in text else (float(v) if v != "" else math.nan)) for k, v in r.items()}
            row["squeals"] = bool(int(r["squeals"]))
            row["contact_points"] = int(r["contact_points"])
            rows.append(row)
    return rows
