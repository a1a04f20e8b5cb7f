"""A line row's squeal risk over the line's friction climate, as the field sees it (issue 32): the
curve verdict's own functions (``pipeline.curve.onset``, ``pipeline.curve.risk``, ``pipeline.curve.train``)
applied to the wheels the screen-first verdict (``pipeline.curve.screen_first``) has just screened.

* Climate: the line's ``[friction] climate`` (a name of pipeline/climates/ or a path relative to the
  study file's folder), else the shipped ``default`` climate (``risk.DEFAULT_CLIMATE``), written into
  each row's curve file as its ``[friction] climate`` so that ``risk.curve_climate`` reads it.
* Onset per wheel: ``onset.wheel_onset`` on the screen's CaseContext (the arrays the screen-first path
  built in memory).  Fast path: for a Coulomb law the scan stops at the first level of its grid at or
  above the climate's highest friction level (``above``): an onset below it is the full scan's, bit for
  bit (same grid, same bracket); a wheel quiet up to there is '>' that level and never squeals in the
  climate (p = 0 exactly).  Another law scans the whole range.
* p_squeal = P(mu in a window of friction where a wheel of the leading bogie squeals) (``risk.curve_risk``'s
  passages: one friction level per passage, exact from the climate's distribution; the windows from each
  wheel's onset scan continued up to the climate's top, ``onset.wheel_onset``'s ``top``: a wheel can be
  stable again above a window, e.g. the outer leading wheel at R = 330 m from mu ~ 0.27 up); their union
  as ``mu_squeal_range``; ``axles_p_squeal`` the expected share of axles.
* L_pAmax_7m5: the loudest wheel's median L_pA at 7.5 m when squealing (``risk.median_level``) from the
  time loop at the curve stage's levels above onset (``onset.LEVEL_STEPS``), the levels past the first
  one at or above the climate's highest level dropped (the median reads the table up to that level only,
  held constant beyond its ends: the same value as the curve stage's).
* Like the curve stage's, every column is conditional on the row's steady curving state, solved at the
  row's own friction level: the dry and wet rows of a curve share the climate but not the wheels'
  creepages, so their onsets can differ (R = 75 m: 0.337 dry at mu = 0.35, 0.291 at mu = 0.15).
* L_pAmax_rolling, L_pAeq_rolling: CNOSSOS-EU rolling noise of the train's pass-by at 7.5 m
  (``train.passby`` without squeal sources); dL_squeal: ``squeal_excess.climate_excess`` of the loudest
  L_pAmax_7m5 over it with the share of passages that squeal, as the curve stage's verdict.csv.
"""
from __future__ import annotations

import math
from pathlib import Path

from pipeline.config.case import given
from pipeline.config.climate import CLIMATES, climate_file, load_climate
from pipeline.config.loader import ConfigError
from pipeline.curve import risk
from pipeline.curve.risk import highest, top_level
from pipeline.curve.cases import wheel_case
from pipeline.curve.onset import LEVEL_STEPS, level_table, range_text, wheel_onset
from pipeline.curve.stage import solve
from pipeline.curve.train import REF_DISTANCE, passby
from pipeline.curve.what_ifs import CaseModels
from pipeline.store import paths
from solvers.radiation.squeal_excess import climate_excess

NAN = float("nan")
COLUMNS = {"climate": str, "mu_onset": str, "mu_squeal_range": str, "wheel_onset": str, "f_onset": float, "mode_onset": str,
           "p_squeal": float, "axles_p_squeal": float, "L_pAmax_7m5": float, "L_pAmax_rolling": float,
           "L_pAeq_rolling": float, "dL_squeal": float}
EMPTY = {"climate": "", "mu_onset": "", "mu_squeal_range": "", "wheel_onset": "", "f_onset": NAN, "mode_onset": "", "p_squeal": NAN,
         "axles_p_squeal": NAN, "L_pAmax_7m5": NAN, "L_pAmax_rolling": NAN, "L_pAeq_rolling": NAN,
         "dL_squeal": NAN}


def climate_path(spec: dict) -> Path:
    """The climate file of a line (module notes); a ConfigError naming the study file and its key."""
    name = (spec.get("friction") or {}).get("climate") or risk.DEFAULT_CLIMATE
    f = climate_file(name)
    if f.parent != CLIMATES and not f.is_absolute():
        f = paths.study_file(spec["name"]).parent / f
    if not f.is_file():
        known = sorted(p.stem for p in CLIMATES.glob("*.toml"))
        raise ConfigError(str(paths.study_file(spec["name"])), [
            ("friction.climate", name, f"a climate of pipeline/climates/ ({', '.join(known)}) or a climate file's "
                                       f"path relative to the study file's folder ({f} does not exist)")])
    return f.resolve()


def climate_cell(spec: dict) -> str:
    """The row curve file's ``[friction] climate``: a shipped climate's name, else the file's absolute path."""
    f = climate_path(spec)
    return f.stem if f.parent == CLIMATES.resolve() else str(f)


def line_climate(spec: dict):
    """The line's Climate, checked (``make check STUDY=``)."""
    return load_climate(climate_path(spec))


def level_steps(mu_on: float, top: float) -> tuple:
    """The curve stage's levels above onset, cut after the first one at or above ``top``, the climate's
    highest level (module notes)."""
    out = []
    for s in LEVEL_STEPS:
        out.append(s)
        if mu_on + s >= top:
            break
    return tuple(out)


def wheel_risk(climate, top: float, case: str, ctx, gamma_y: float) -> tuple:
    """(WheelOnset, its level table) of one wheel from its screen's CaseContext (None: pure rolling)."""
    if ctx is None:
        return wheel_onset(None, 0.0), []
    models = CaseModels.of_context(ctx)
    on = wheel_onset(models, gamma_y, above=top if models.coulomb else math.inf, top=top)
    if not (math.isfinite(on.mu) and risk.p_windows(climate, on.windows) > 0.0):
        return on, []
    return on, level_table(models, case, on, steps=level_steps(on.mu, highest(climate)))


def risk_columns(curve, rows: list[dict]) -> dict:
    """The row's risk columns (``COLUMNS``) of ``curve`` whose screen-first verdict rows are ``rows`` (each
    with its screen's ``context``); call after ``run_screen_first``, in the same process."""
    climate = risk.curve_climate(curve)
    top = top_level(climate)
    sol = solve(curve)                       # memoised: the screen-first path's curving
    by = {r["wheel"]: r for r in rows}
    onsets, levels = {}, {}
    with given([wheel_case(sol.curve, p) for p in sol.wheels]):
        for p in sol.wheels:
            on, table = wheel_risk(climate, top, f"{sol.curve.name}/{p.wheel}", by[p.wheel].get("context"),
                                   p.gamma_y)
            onsets[p.wheel] = on
            levels[p.wheel] = risk.wheel_risk(climate, on.risk_onset, table)["L_pAmax_7m5"]
    shares = risk.curve_risk(climate, {w: on.risk_onset for w, on in onsets.items()})
    known = {w: on for w, on in onsets.items() if not math.isnan(on.mu)}
    worst = min(known, key=lambda w: known[w].mu) if known else ""
    loud = max((v for v in levels.values() if math.isfinite(v)), default=NAN)
    roll = passby(curve, [], 0.0, [REF_DISTANCE])[0]      # no squeal source: the wheel height is not used
    p = shares["passages"]
    ranges = risk.union(x for w in known for x in known[w].windows)
    return {"climate": climate.name, "mu_onset": onsets[worst].cell() if worst else "",
            "mu_squeal_range": range_text(ranges), "wheel_onset": worst,
            "f_onset": onsets[worst].f_hz if worst else NAN, "mode_onset": onsets[worst].mode if worst else "",
            "p_squeal": p, "axles_p_squeal": shares["axles"], "L_pAmax_7m5": loud,
            "L_pAmax_rolling": roll["L_pAmax_rolling"], "L_pAeq_rolling": roll["L_pAeq_rolling"],
            "dL_squeal": climate_excess(roll["L_pAmax_rolling"], loud, p if math.isfinite(p) else 0.0)}
