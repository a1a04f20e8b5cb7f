"""Steady curving of a vehicle in a curve: from a Curve to the operating point of every wheel of
the leading bogie (issue 25).

API (stable; ``pipeline.curve`` builds ``make curve`` on it)::

    from pipeline.curve.curving import solve_curve
    sol = solve_curve("r150")            # a shipped name, a path to a curve file, or a Curve
    sol = solve_curve("r150", radius_m=300.0, mu=0.2)   # curve keys replaced (validated like the file)
    for w in sol.wheels:                 # WheelOperatingPoint (pipeline.config.nouns), a1o, a1i, a2o, a2i
        w.wheel, w.dy_wr, w.gamma_y, w.y_wheel, w.normal_load, w.nadal, ...

The curve and vehicle files are read by ``pipeline.config.curve_inputs`` (``read_curve``: the
Curve with its Vehicle and FrictionLaw); the solution is memoised per process and per content of
the curve and vehicle.

``CurveSolution``: name, curve (Curve), vehicle (Vehicle), wheel, rail, wheel_profile,
rail_profile (names), vehicle_model (``solvers.curving.Vehicle``), track
(``solvers.curving.Track``), profiles, solution (``solvers.curving.CurvingSolution``: both
wheelsets' y, psi, eps, flange side and force, contacts, residuals; the frame's y_b, psi_b),
flange_shift (m: the wheelset shift at which a flange touches), rolling_circle_y (m: c of
the curve wheels' cases), max_residual (relative to the wheel load), wheels.

Command line::

    python -m pipeline.curve.curving --curve r150      # (or a path) the table of the four wheels
"""
from __future__ import annotations

import argparse
import math
import sys
from dataclasses import asdict, dataclass

from pipeline.config.curve_inputs import available_curves, read_curve
from pipeline.config.loader import ConfigError, config_hash, named_file
from pipeline.config.nouns import OPERATING_FIELDS, Curve, Vehicle, WheelOperatingPoint
import numpy as np
from geometry.contact_point import TrackRail
from pipeline.config.case_profiles import case_profiles
from pipeline.stages.rail import load_rail_params
from pipeline.stages.wheel import load_wheel

G = 9.81
GAUGE_DEPTH = 0.014  # m below the crown top where the gauge is measured (EN 13848-1)


def gauge_face(rail_t) -> float:
    """Track-frame Y (m, from the rail centre, negative) of the gauge face: the gauge-side point
    GAUGE_DEPTH below the crown top, or the profile's deepest gauge-side point when it ends above."""
    Y = rail_t.y
    z = np.asarray(rail_t(Y), float)
    top = int(np.nanargmax(z))
    Yg, zg = Y[: top + 1], z[: top + 1]
    below = np.flatnonzero(zg <= z[top] - GAUGE_DEPTH)
    if below.size == 0:
        return float(Yg[0])
    i = below[-1]
    return float(np.interp(z[top] - GAUGE_DEPTH, [zg[i], zg[i + 1]], [Yg[i], Yg[i + 1]]))


@dataclass
class CurveSolution:
    name: str
    curve: Curve
    vehicle: Vehicle
    wheel: str
    rail: str
    wheel_profile: str
    rail_profile: str
    vehicle_model: object
    track: object
    profiles: object
    solution: object
    flange_shift: float
    rolling_circle_y: float
    max_residual: float
    wheels: list


def _profiles(curve: Curve):
    """(wheel params, rail params, wheel Profile, rail Profile, TrackRail, profile names); a missing wheel,
    rail or profile file is an error naming the file (vehicle or curve) and the key that asked for it."""
    vf, cf = curve.vehicle.source, curve.source
    pw, _ = named_file(vf, "wheel", curve.wheel, load_wheel)
    pr, _ = named_file(cf, "rail", curve.rail, load_rail_params)
    stub = {"contact": {"wheel_profile": curve.vehicle.bogie.wheel_profile, "rail_profile": curve.rail_profile}}
    wheel, rail, desc = case_profiles(stub, pw, pr, {"wheel": (vf, "wheel_profile"), "rail": (cf, "rail_profile")})
    inc = pr.get("running_surface", {}).get("inclination", 0.0) or 0.0
    return pw, pr, wheel, rail, TrackRail(rail, inc), desc


def build_problem(curve: Curve | str, **overrides):
    """(Curve, Vehicle, solvers' Vehicle, Track, Profiles, CreepLaw, names) of a curve (a Curve, a
    path or a shipped name; ``overrides`` as in ``pipeline.config.curve_inputs.read_curve``)."""
    from solvers.curving import CreepLaw, Profiles, Track, Vehicle as VehicleModel, flange_edge  # lazy: brings in numba, rocket_fft, scipy

    c = read_curve(curve, **overrides)
    v, b = c.vehicle, c.vehicle.bogie
    pw, pr, wheel, rail, rail_t, desc = _profiles(c)
    r0 = pw["tyre"]["rolling_radius"]
    l_w = 0.5e-3 * b.back_to_back_mm + pw["tyre"]["back_offset"]
    b_r = 0.5e-3 * (c.gauge_mm + c.gauge_widening_mm) - gauge_face(rail_t)
    veh = VehicleModel(semi_wheelbase=b.semi_wheelbase, bogie_spacing=v.train.bogie_spacing_m,
                       wheel_load=v.wheel_load_N, wheelset_mass=b.wheelset_mass_kg,
                       kx=1e6 * b.primary_kx_MN_per_m, ky=1e6 * b.primary_ky_MN_per_m,
                       box_half_spacing=b.box_half_spacing_m, secondary_yaw=1e3 * b.secondary_yaw_kNm_per_rad,
                       cg_height=v.cg_height_m, r0=r0, rolling_circle=l_w)
    trk = Track(radius=c.radius_m, cant=1e-3 * c.cant_mm, speed=c.speed_kmh / 3.6, rail_centre=b_r,
                c=l_w - b_r, tractive_force=1e3 * c.traction_force_kN)
    prof = Profiles(wheel, rail_t, flange_edge(wheel))
    law = CreepLaw(kind="kalker", mu=c.friction.mu, E=pw["material"]["E"], nu=pw["material"]["nu"])
    names = dict(wheel=b.wheel, rail=c.rail, wheel_profile=desc["wheel_name"] or None,
                 rail_profile=desc["rail_name"] or None)
    return c, v, veh, trk, prof, law, names


_MEMO: dict = {}


def _key(c: Curve) -> str:
    """What a solution depends on besides the wheel, rail and profile files: the curve and vehicle."""
    return config_hash({"name": c.name, "source": str(c.source), "curve": c.data, "vehicle": c.vehicle.data,
                        "vehicle_source": str(c.vehicle.source)})


def solve_curve(curve: Curve | str, **overrides) -> CurveSolution:
    """Solve the leading bogie's steady curving of ``curve`` (a Curve, a path to a curve file or a
    shipped name) with its vehicle, wheel, rail and profiles.  ``overrides``: curve keys replaced
    (radius_m=..., speed_kmh=..., mu=...; validated like the file).  ConfigError for bad input (one
    line per problem, nothing solved); solvers.curving.CurvingError when no equilibrium is found."""
    c = read_curve(curve, **overrides)
    key = _key(c)
    if key not in _MEMO:
        if len(_MEMO) >= 64:
            _MEMO.pop(next(iter(_MEMO)))
        _MEMO[key] = _solve(c)
    return _MEMO[key]


def clear() -> None:
    """Forget the memoised solutions (benchmarks timing the curving)."""
    _MEMO.clear()


def _point(row: dict, extra: dict) -> WheelOperatingPoint:
    """A WheelOperatingPoint of Python scalars (the solver's rows may hold numpy floats)."""
    conv = {"wheel": str, "side": str, "axle": int, "contact_points": int}
    return WheelOperatingPoint(**{k: conv.get(k, float)(v) for k, v in row.items()}, **extra)


def _solve(c: Curve) -> CurveSolution:
    from solvers.curving import solve  # lazy: brings in numba, rocket_fft, scipy
    from solvers.curving.summary import wheel_points  # lazy: brings in numba, rocket_fft, scipy

    c, v, veh, trk, prof, law, names = build_problem(c)
    sol = solve(prof, veh, trk, law)
    extra = dict(rolling_circle_y=trk.c, speed=trk.speed, mu=law.mu, friction_law=c.friction.law,
                 wheel_file=names["wheel"], rail_file=names["rail"], wheel_profile=names["wheel_profile"],
                 rail_profile=names["rail_profile"])
    wheels = [_point(row, extra) for row in wheel_points(sol, law.mu)]
    return CurveSolution(c.name, c, v, names["wheel"], names["rail"], names["wheel_profile"], names["rail_profile"],
                         veh, trk, prof, sol, sol.flange_shift, trk.c, sol.max_residual, wheels)


def table(sol: CurveSolution) -> str:
    """A text table of the wheels (engineers' units)."""
    head = (f"curve {sol.name}: {sol.vehicle.name}, R = {sol.track.radius:g} m, cant {sol.curve.cant_mm:g} mm, "
            f"{sol.curve.speed_kmh:g} km/h, mu = {sol.wheels[0].mu:g}; flange contact at a shift of "
            f"{1e3 * sol.flange_shift:.2f} mm (c = {1e3 * sol.rolling_circle_y:+.2f} mm); frame y = "
            f"{1e3 * sol.solution.frame_y:+.2f} mm, yaw {1e3 * sol.solution.frame_psi:+.2f} mrad; "
            f"largest residual {sol.max_residual:.1e} of the wheel load")
    cols = ("wheel", "dy_wr mm", "AoA mrad", "gamma_x", "gamma_y", "spin 1/m", "y^W mm", "y^R mm", "angle deg",
            "Q kN", "N kN", "points", "Y/Q flange")
    rows = [cols]
    for w in sol.wheels:
        rows.append((w.wheel, f"{1e3 * w.dy_wr:+.2f}", f"{1e3 * w.angle_of_attack:+.2f}", f"{w.gamma_x:+.5f}",
                     f"{w.gamma_y:+.5f}", f"{w.spin:+.3f}", f"{1e3 * w.y_wheel:+.2f}", f"{1e3 * w.y_rail:+.2f}",
                     f"{math.degrees(w.contact_angle):+.1f}", f"{1e-3 * w.wheel_load:.1f}",
                     f"{1e-3 * w.normal_load:.1f}", str(w.contact_points),
                     "-" if math.isnan(w.nadal) else f"{w.nadal:.2f} (limit {w.nadal_limit:.2f})"))
    width = [max(len(r[k]) for r in rows) for k in range(len(cols))]
    lines = ["  ".join(s.rjust(n) for s, n in zip(r, width)) for r in rows]
    return "\n".join([head, *lines, *(f"note: {n}" for n in sol.solution.notes)])


def as_dict(w: WheelOperatingPoint) -> dict:
    return asdict(w)


FIELDS = OPERATING_FIELDS


def main(argv=None) -> int:
    from solvers.curving import CurvingError  # lazy: brings in numba, rocket_fft, scipy

    ap = argparse.ArgumentParser(prog="python -m pipeline.curve.curving",
                                 description="steady curving of a curve file's vehicle: every wheel of the leading bogie")
    ap.add_argument("--curve", required=True, help=f"a curve file's path, or a shipped curve pipeline/curves/<name>.toml "
                                                       f"(available: {available_curves()})")
    args = ap.parse_args(argv)
    try:
        print(table(solve_curve(args.curve)))
    except ConfigError as e:
        print(f"error: {' '.join(str(e).split())}", file=sys.stderr)
        return 2
    except CurvingError as e:
        print(f"error: curve {args.curve}: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
