"""The whole train in a curve (issue 32 "the whole train", issue 33 "the pass-by from the vehicle"):
every bogie's wheels, the share of axles that squeal, the pass-by with and without squeal at the
curve file's receivers, and squeal's excess over CNOSSOS-EU rolling noise.

* Bogies.  All cars are the same car in the same steady curve (coupler forces neglected), so the
  train has two bogie states: each car's leading bogie (wheels a1o ... a2i, the curve stage's) and
  its trailing bogie (b1o ... b2i: b1 its leading axle).  The curving model ties a bogie frame to the
  car body by the secondary yaw stiffness, the body's chord being at -s/(2R) to the leading bogie's
  radial line (``solvers.curving.solve``: ``pb - bogie_spacing / (2R)``); the trailing bogie, at the
  other end of the chord, sees +s/(2R): the same model with the bogie spacing negated.  Its wheels
  get their verdict from the curve stage's per-wheel machinery (``wheel_verdict``, passed in;
  without the what-ifs).  Share of axles that squeal: (axles with a squealing wheel) / 4, per car.
* Pass-by (``solvers.radiation.passby_train``): the train's axles (``Train.axle_positions_m``) at
  the curve's speed; receivers on the outer side of the curve, ``receivers_m`` of the curve file
  (default 7.5 m), 1.2 m above the rail head (ISO 3095:2013).  A squealing wheel is a point source at
  its wheel centre (height = rolling radius, 0.7175 m to its side of the track centre) whose power
  is the one that gives its L_pA at 7.5 m / 1.2 m (listen's, the verdict's L_pA) by free-field
  spreading: L_WA = L_pA + 20 lg r_ref + 11.  Omnidirectional, every car's same wheel alike.
* Rolling noise: CNOSSOS-EU (``pipeline.config.cnossos``) of one car (vehicle file's [cnossos], 4 axles)
  on the track of the curve file's [cnossos] at the curve's speed: L_W per band per car, A-weighted,
  shared by its 4 axles, each a point source on the track centre line 0.5 m above the rail head
  (source A; NoiseModelling's RailwayCnossos puts ROLLING at 0.5 m) with the horizontal dipole of
  (2.3.15).  Propagation: geometric spreading only (no ground, no air absorption).
* dL_squeal: L_pA,max of the pass-by with squeal minus without, at 7.5 m, at the curve's friction (passby.csv,
  verdict.md); verdict.csv's ``dL_squeal`` is the expectation over the friction climate (the curve stage:
  ``solvers.radiation.squeal_excess.climate_excess``).

Writes build/curves/<curve>/train.csv (every bogie's wheels), passby.csv (per receiver) and rolling.csv
(CNOSSOS-EU's sound power per 1/3 octave of one car: track, vehicle, total; per metre of train).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from pipeline.config import cnossos
from pipeline.config.case import given
from pipeline.config.nouns import Curve, WheelOperatingPoint
from pipeline.curve.cases import wheel_case, write_case
from pipeline.curve.curving import _point, build_problem
from pipeline.curve.verdict_report import cell
from pipeline.store import artifacts, paths
from solvers.radiation import passby_train as pt
from solvers.radiation import rolling_cnossos as rc
from solvers.radiation.squeal_excess import squeal_excess

HALF_TRACK = 0.7175          # m, a wheel's contact to the track centre line (half of 1435 mm)
RECEIVER_HEIGHT = 1.2        # m above the rail head, ISO 3095:2013
REF_DISTANCE = 7.5           # m, the verdict's L_pA receiver (listen's default)
COLUMNS = ["axles_squeal_share", "L_pAmax_rolling", "L_pAeq_rolling", "L_pAmax_train", "L_pAeq_train", "dL_squeal"]
TRAIN_COLUMNS = ["bogie", "wheel", "x_m", "angle_of_attack", "gamma_y", "squeals", "f_squeal", "mode", "L_F2", "L_pA"]
ROLLING_COLUMNS = ["f_hz", "L_W_track_dB", "L_W_vehicle_dB", "L_W_car_dB", "L_W_per_m_dB"]   # re 1 pW (per metre)
PASSBY_COLUMNS = ["receiver_m", "L_pAmax_rolling", "L_pAeq_rolling", "L_pAmax_train", "L_pAeq_train", "dL_squeal",
                  "T_p_s"]


def trailing_points(curve: Curve) -> list[WheelOperatingPoint]:
    """The operating points of a car's trailing bogie (wheels b1o, b1i, b2o, b2i; module notes)."""
    from solvers.curving import solve  # lazy: brings in numba, rocket_fft, scipy
    from solvers.curving.summary import wheel_points  # lazy: brings in numba, rocket_fft, scipy

    c, v, veh, trk, prof, law, names = build_problem(curve)
    sol = solve(prof, dataclasses.replace(veh, bogie_spacing=-veh.bogie_spacing), trk, law)
    extra = dict(rolling_circle_y=trk.c, speed=trk.speed, mu=law.mu, friction_law=c.friction.law,
                 wheel_file=names["wheel"], rail_file=names["rail"], wheel_profile=names["wheel_profile"],
                 rail_profile=names["rail_profile"])
    return [_point(dict(row, wheel="b" + row["wheel"][1:]), extra) for row in wheel_points(sol, law.mu)]


def trailing_verdicts(curve: Curve, wheel_verdict) -> tuple[list[WheelOperatingPoint], list[dict]]:
    """(operating points, verdict rows) of the trailing bogie's wheels (``wheel_verdict(curve, point,
    what_ifs=False, passby=False)``: the curve stage's per-wheel verdict; their sound enters the train's
    pass-by, passby.csv, and the pass-by WAV is the leading bogie's loudest wheel's)."""
    points = trailing_points(curve)
    cases = [wheel_case(curve, p) for p in points]
    for c in cases:
        write_case(c)
    with given(cases):
        return points, [wheel_verdict(curve, p, what_ifs=False, passby=False) for p in points]


def axle_x(curve: Curve, wheel: str) -> list[float]:
    """x (m, backward from the train's front) of a wheel's axle in every car."""
    t = curve.vehicle.train
    off = {"a1": 0.0, "a2": t.wheelbase_m, "b1": t.bogie_spacing_m, "b2": t.bogie_spacing_m + t.wheelbase_m}[wheel[:2]]
    return [k * (t.car_length_m or 0.0) + off for k in range(t.cars)]


def train_length(curve: Curve) -> float:
    """m: the cars' length (one car: its axles' span plus a wheelbase at each end, ASSUMED)."""
    t = curve.vehicle.train
    return t.cars * t.car_length_m if t.car_length_m else t.bogie_spacing_m + 3.0 * t.wheelbase_m


def rolling_sources(curve: Curve) -> tuple[np.ndarray, float, dict]:
    """(x of every axle, A-weighted L_W per axle in dB re 1 pW, the CNOSSOS components of one car)."""
    ref = curve.vehicle.data.get("cnossos") or {}
    trk = curve.data.get("cnossos") or {}
    tables = cnossos.load_tables()
    veh = tables.vehicle_from_refs(roughness=ref.get("wheel_roughness", "5"), contact=ref.get("contact_filter", "4"),
                                   transfer=ref.get("transfer", "4"), n_axles=4.0, name=curve.vehicle.name)
    track = tables.track(trk.get("track_transfer", "4"), trk.get("rail_roughness", "4"), trk.get("impact") or None)
    comp = cnossos.rolling_power_components(veh, track, float(curve.speed_kmh))
    L_WA_car = pt.a_weighted_sum(rc.F_CENTRE_EXACT, comp["L_W_total"])
    x = np.asarray(curve.vehicle.train.axle_positions_m, float)
    return x, L_WA_car - 10.0 * math.log10(4.0), comp


def squeal_sources(curve: Curve, rows: list[dict], r0: float) -> tuple[np.ndarray, ...]:
    """(x, y, z, L_WA) of every squealing wheel of the train (module notes)."""
    r_ref = math.hypot(REF_DISTANCE - HALF_TRACK, RECEIVER_HEIGHT - r0)   # the outer wheel's; inner: below
    xs, ys, Ls = [], [], []
    for r in rows:
        if not (r["squeals"] and math.isfinite(r["L_pA"])):
            continue
        y = HALF_TRACK if r["wheel"].endswith("o") else -HALF_TRACK
        rr = math.hypot(REF_DISTANCE - y, RECEIVER_HEIGHT - r0) if y < 0 else r_ref
        for x in axle_x(curve, r["wheel"]):
            xs.append(x), ys.append(y), Ls.append(r["L_pA"] + 20.0 * math.log10(rr) + 11.0)
    n = len(xs)
    return np.asarray(xs, float), np.asarray(ys, float), np.full(n, r0), np.asarray(Ls, float)


def passby(curve: Curve, rows: list[dict], r0: float, receivers) -> list[dict]:
    """Per receiver distance: the pass-by's levels without and with squeal (PASSBY_COLUMNS)."""
    xr, LWr, _ = rolling_sources(curve)
    xs, ys, zs, LWs = squeal_sources(curve, rows, r0)
    n = xr.size
    x = np.concatenate([xr, xs])
    y = np.concatenate([np.zeros(n), ys])
    z = np.concatenate([np.full(n, rc.SOURCE_HEIGHT_M), zs])
    L = np.concatenate([np.full(n, LWr), LWs])
    dip = np.concatenate([np.ones(n, bool), np.zeros(xs.size, bool)])
    out = []
    for d in receivers:
        kw = dict(speed=curve.speed, d=float(d), h=RECEIVER_HEIGHT, length=train_length(curve))
        roll = pt.passby_levels(xr, 0.0, rc.SOURCE_HEIGHT_M, LWr, dipole=True, **kw)
        both = pt.passby_levels(x, y, z, L, dipole=dip, **kw)
        out.append({"receiver_m": float(d), "L_pAmax_rolling": roll["L_max"], "L_pAeq_rolling": roll["L_eq"],
                    "L_pAmax_train": both["L_max"], "L_pAeq_train": both["L_eq"],
                    "dL_squeal": squeal_excess([both["L_max"]], roll["L_max"], 1.0 if xs.size else 0.0),
                    "T_p_s": roll["T_p"]})
    return out


def train_verdict(curve: Curve, rows: list[dict], wheel_verdict) -> dict:
    """The trailing bogie's verdicts, the pass-by and rolling noise of ``curve`` whose leading bogie's
    verdict rows are ``rows``; writes train.csv and passby.csv; returns {'columns' (COLUMNS, at 7.5 m:
    for every verdict.csv row), 'trailing' (rows), 'passby' (per receiver), 'text' (verdict.md's lines)}."""
    from solvers.curving import CurvingError  # lazy: brings in numba, rocket_fft, scipy

    try:
        _, trailing = trailing_verdicts(curve, wheel_verdict)
        note = ""
    except CurvingError as e:         # the leading bogie solved, the trailing one not: the train without it
        trailing = []
        note = f"  The trailing bogie has no steady curving state ({e}): left out."
    r0 = build_problem(curve)[2].r0   # m, nominal rolling radius: the squealing wheels' centre height
    every = rows + trailing
    axles = {r["wheel"][:2] for r in every if r["squeals"]}
    share = len(axles) / 4.0
    receivers = list(curve.data.get("receivers_m") or [REF_DISTANCE])
    levels = passby(curve, every, r0, sorted(set(receivers) | {REF_DISTANCE}))
    at = {lv["receiver_m"]: lv for lv in levels}
    ref = at[REF_DISTANCE]
    columns = {"axles_squeal_share": share, **{k: ref[k] for k in COLUMNS[1:]}}
    out = paths.curve_dir(curve.name)
    artifacts.save_csv(out / "train.csv", TRAIN_COLUMNS, (
        [cell(v) for v in ("leading" if r["wheel"][0] == "a" else "trailing", r["wheel"], axle_x(curve, r["wheel"])[0],
                           *(r[k] for k in TRAIN_COLUMNS[3:]))] for r in every))
    _, _, comp = rolling_sources(curve)
    per_m = -10.0 * math.log10(curve.vehicle.train.car_length_m or train_length(curve))
    artifacts.save_csv(out / "rolling.csv", ROLLING_COLUMNS, ([cell(float(v)) for v in row] for row in zip(
        comp["f_centre"], comp["L_W_track"], comp["L_W_vehicle"], comp["L_W_total"], comp["L_W_total"] + per_m)))
    artifacts.save_csv(out / "passby.csv", PASSBY_COLUMNS,
                       ([cell(at[d][k]) for k in PASSBY_COLUMNS] for d in receivers))
    t = curve.vehicle.train
    sq = ", ".join(r["wheel"] for r in every if r["squeals"]) or "none"
    lines = [f"**The train** ({t.cars} car{'s' if t.cars > 1 else ''} of {t.car_length_m or 0:g} m, bogies "
             f"{t.bogie_spacing_m:g} m apart, {len(t.axle_positions_m)} axles, {curve.speed_kmh:g} km/h): squealing "
             f"wheels {sq} (b: each car's trailing bogie), share of axles that squeal {share:.2f}.  Pass-by "
             f"(train.csv, passby.csv; free field, CNOSSOS-EU rolling noise):"]
    for d in receivers:
        lv = at[d]
        lines.append(f"at {d:g} m L_pA,max = {lv['L_pAmax_train']:.1f} dB(A) (rolling alone "
                     f"{lv['L_pAmax_rolling']:.1f}: +{lv['dL_squeal']:.1f} dB), L_pAeq over {lv['T_p_s']:.1f} s = "
                     f"{lv['L_pAeq_train']:.1f} dB(A) (rolling {lv['L_pAeq_rolling']:.1f})")
    return {"columns": columns, "trailing": trailing, "passby": levels, "text": lines[0] + " " + "; ".join(lines[1:])
            + "." + note + "\n"}
