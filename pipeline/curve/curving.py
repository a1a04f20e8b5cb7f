"""Steady curving of a vehicle in a curve: from a curve file to the operating point of every
wheel of the leading bogie (issue 25).

API (stable; ``pipeline.curve`` builds ``make curve`` on it)::

    from pipeline.curve.curving import solve_curve
    sol = solve_curve("r150")            # -> CurveSolution (memoised per process and file contents)
    sol = solve_curve("r150", radius_m=300.0, mu=0.2)   # curve keys replaced (validated like the file)
    for w in sol.wheels:                 # WheelOperatingPoint, ids a1o, a1i, a2o, a2i
        w.wheel, w.dy_wr, w.gamma_y, w.y_wheel, w.normal_load, w.nadal, ...
        w.case_fields()                  # the keys of an ordinary case file for this wheel

    load_vehicle(name) -> dict           # geometry/vehicles/<name>.toml, validated (pipeline.config.curve_schemas)
    load_curve(name, **overrides) -> dict   # pipeline/curves/<name>.toml, validated
    curve_file(name), vehicle_file(name), available_curves(), available_vehicles()

``CurveSolution``: name, curve and vehicle (validated dicts), wheel, rail, wheel_profile,
rail_profile (names), vehicle_model (``solvers.curving.Vehicle``), track
(``solvers.curving.Track``), profiles, solution (``solvers.curving.CurvingSolution``: both
wheelsets' y, psi, eps, flange side and force, contacts, residuals; the frame's y_b, psi_b),
flange_shift (m: the wheelset shift at which a flange touches), rolling_circle_y (m: c of
the curve wheels' cases), max_residual (relative to the wheel load), wheels.

``WheelOperatingPoint`` (SI; angles in rad; sign conventions of BRIEF/SPEC 2): wheel id, axle,
side ('outer'/'inner'), dy_wr (+y outer, -y inner), rolling_circle_y, angle_of_attack (the
wheelset's yaw, + under-radial), gamma_x, gamma_y, spin (1/m) of the tread contact in its
contact frame, y_wheel (y^W), y_rail (y^R), contact_angle, rolling_radius, wheel_load (N,
vertical force of all its contacts on the rail), lateral_force (N, toward the field side),
normal_load (N, the tread contact's normal force: the case's preload), F1, F2 (N, tread creep
forces on the rail), creep_use (|F| / (mu N)), patch_a, patch_b (m, Hertz semi-axes),
contact_points (1 or 2), nadal (Y/Q of the flange contact, NaN without), nadal_limit,
flange_y_wheel, flange_y_rail, flange_angle, flange_load, speed (m/s), mu, friction_law,
wheel_file, rail_file, wheel_profile, rail_profile.

Command line::

    python -m pipeline.curve.curving --curve r150      # the table of the four wheels
"""
from __future__ import annotations

import argparse
import functools
import math
import os
import sys
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from pipeline.store import paths
from pipeline.config.loader import ConfigError, MissingInput, load, named_file
from pipeline.config.curve_schemas import CURVE, VEHICLE

G = 9.81
GAUGE_DEPTH = 0.014  # m below the crown top where the gauge is measured (EN 13848-1)


def vehicle_dir() -> Path:
    return Path(os.environ.get("SQUEAL_VEHICLE_DIR", paths.ROOT / "geometry" / "vehicles"))


def curve_dir() -> Path:
    return Path(os.environ.get("SQUEAL_CURVE_DIR", paths.ROOT / "pipeline" / "curves"))


def vehicle_file(name: str) -> Path:
    return vehicle_dir() / f"{name}.toml"


def curve_file(name: str) -> Path:
    return curve_dir() / f"{name}.toml"


def available_vehicles() -> list[str]:
    return paths.available(vehicle_dir())


def available_curves() -> list[str]:
    return paths.available(curve_dir())


def _load_named(path: Path, schema: dict, kind: str, have: list[str]) -> dict:
    if not path.exists():
        raise MissingInput(path, kind, have, detail=f"no such {kind} {path.stem!r}; available: {have}")
    return load(path, schema)


def load_vehicle(name: str) -> dict:
    """The validated vehicle file; exactly one of load.wheel_load_kN, load.axle_load_kN; its ``name``
    that of its file (a curve, a line's CSV and the build's folders name a vehicle by its file)."""
    path = vehicle_file(name)
    v = _load_named(path, VEHICLE, "vehicle", available_vehicles())
    if v["name"] != path.stem:
        raise ConfigError(str(path), [("name", v["name"], f"the file's name {path.stem!r} (a vehicle is named "
                                                          "by its file: rename one to match the other)")])
    ld = v["load"]
    if (ld["wheel_load_kN"] is None) == (ld["axle_load_kN"] is None):
        given = ld["wheel_load_kN"] if ld["wheel_load_kN"] is not None else ld["axle_load_kN"]
        raise ConfigError(str(path), [("load.wheel_load_kN", given, "exactly one of load.wheel_load_kN and "
                                       "load.axle_load_kN (kN)")])
    return v


def load_curve(name: str, **overrides) -> dict:
    """The validated curve file; ``overrides``: top-level keys (radius_m, speed_kmh, cant_mm,
    gauge_widening_mm, ...) and ``mu`` replaced before validation (what-ifs and studies)."""
    c = _load_named(curve_file(name), CURVE, "curve", available_curves())
    if not overrides:
        return c
    from pipeline.config.loader import validate

    data = {k: v for k, v in c.items() if v is not None}
    data["friction"] = {k: v for k, v in c["friction"].items() if v is not None}
    for k, v in overrides.items():
        if k == "mu":
            data["friction"]["mu"] = v
        else:
            data[k] = v
    what = ", ".join(f"{k} = {v!r}" for k, v in overrides.items())
    return validate(data, CURVE, f"{curve_file(name)} with {what}")


def wheel_load_N(v: dict) -> float:
    ld = v["load"]
    return 1e3 * (ld["wheel_load_kN"] if ld["wheel_load_kN"] is not None else 0.5 * ld["axle_load_kN"])


def gauge_face(rail_t) -> float:
    """Track-frame Y (m, from the rail centre, negative) of the gauge face: the gauge-side point
    GAUGE_DEPTH below the crown top, or the profile's deepest gauge-side point when it ends above."""
    import numpy as np

    Y = rail_t.y
    z = np.asarray(rail_t(Y), float)
    top = int(np.nanargmax(z))
    Yg, zg = Y[: top + 1], z[: top + 1]
    below = np.flatnonzero(zg <= z[top] - GAUGE_DEPTH)
    if below.size == 0:
        return float(Yg[0])
    i = below[-1]
    return float(np.interp(z[top] - GAUGE_DEPTH, [zg[i], zg[i + 1]], [Yg[i], Yg[i + 1]]))


@dataclass(frozen=True)
class WheelOperatingPoint:
    """One wheel of the leading bogie in the curve (see the module docstring for the fields)."""

    wheel: str
    axle: int
    side: str
    dy_wr: float
    rolling_circle_y: float
    angle_of_attack: float
    gamma_x: float
    gamma_y: float
    spin: float
    y_wheel: float
    y_rail: float
    contact_angle: float
    rolling_radius: float
    wheel_load: float
    lateral_force: float
    normal_load: float
    F1: float
    F2: float
    creep_use: float
    patch_a: float
    patch_b: float
    contact_points: int
    nadal: float
    nadal_limit: float
    flange_y_wheel: float
    flange_y_rail: float
    flange_angle: float
    flange_load: float
    speed: float
    mu: float
    friction_law: str
    wheel_file: str
    rail_file: str
    wheel_profile: str
    rail_profile: str

    def case_fields(self) -> dict:
        """The keys of an ordinary case file (pipeline.config.input_schemas.CASE) that this wheel fixes;
        the caller adds name, time and listener."""
        contact = {"dy_wr": self.dy_wr, "rolling_circle_y": self.rolling_circle_y}
        contact.update({k: v for k, v in (("wheel_profile", self.wheel_profile), ("rail_profile", self.rail_profile))
                        if v})
        friction = {"mu": self.mu} if self.friction_law == "coulomb" else {"law": self.friction_law, "mu": self.mu}
        return {"wheel": self.wheel_file, "rail": self.rail_file, "contact": contact, "friction": friction,
                "kinematics": {"gamma_y": self.gamma_y, "gamma_x": self.gamma_x, "speed": self.speed},
                "loading": {"preload": self.normal_load}}


@dataclass
class CurveSolution:
    name: str
    curve: dict
    vehicle: dict
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


def _profiles(v: dict, c: dict, files: tuple = ("the vehicle file", "the curve file")):
    """(wheel params, rail params, wheel Profile, rail Profile, TrackRail, profile names); ``files``:
    the vehicle and curve files (a missing wheel, rail or profile is an error naming the one that asked)."""
    from geometry.contact_point import TrackRail

    from pipeline.config.case_profiles import case_profiles
    from pipeline.stages.rail import load_rail_params
    from pipeline.stages.wheel import load_wheel

    vf, cf = files
    pw, _ = named_file(vf, "wheel", v["wheel"], load_wheel)
    pr, _ = named_file(cf, "rail", c["rail"], load_rail_params)
    stub = {"contact": {"wheel_profile": v["wheel_profile"], "rail_profile": c["rail_profile"]}}
    wheel, rail, desc = case_profiles(stub, pw, pr, {"wheel": (vf, "wheel_profile"), "rail": (cf, "rail_profile")})
    inc = pr.get("running_surface", {}).get("inclination", 0.0) or 0.0
    return pw, pr, wheel, rail, TrackRail(rail, inc), desc


def build_problem(name: str, **overrides):
    """(curve, vehicle, Vehicle, Track, Profiles, CreepLaw, names) of a curve file (``overrides``
    as in ``load_curve``)."""
    from solvers.curving import CreepLaw, Profiles, Track, Vehicle, flange_edge

    c = load_curve(name, **overrides)
    v = named_file(curve_file(name), "vehicle", c["vehicle"], load_vehicle)
    pw, pr, wheel, rail, rail_t, desc = _profiles(v, c, (vehicle_file(c["vehicle"]), curve_file(name)))
    r0 = pw["tyre"]["rolling_radius"]
    l_w = 0.5e-3 * v["bogie"]["back_to_back_mm"] + pw["tyre"]["back_offset"]
    b_r = 0.5e-3 * (c["gauge_mm"] + c["gauge_widening_mm"]) - gauge_face(rail_t)
    veh = Vehicle(semi_wheelbase=0.5 * v["bogie"]["wheelbase_m"], bogie_spacing=v["bogie"]["bogie_spacing_m"],
                  wheel_load=wheel_load_N(v), wheelset_mass=v["wheelset"]["mass_kg"],
                  kx=1e6 * v["primary"]["kx_MN_per_m"], ky=1e6 * v["primary"]["ky_MN_per_m"],
                  box_half_spacing=v["primary"]["box_half_spacing_m"],
                  secondary_yaw=1e3 * v["secondary"]["yaw_stiffness_kNm_per_rad"], cg_height=v["load"]["cg_height_m"],
                  r0=r0, rolling_circle=l_w)
    trk = Track(radius=c["radius_m"], cant=1e-3 * c["cant_mm"], speed=c["speed_kmh"] / 3.6, rail_centre=b_r,
                c=l_w - b_r, tractive_force=1e3 * c["traction"]["force_kN"])
    prof = Profiles(wheel, rail_t, flange_edge(wheel))
    law = CreepLaw(kind="kalker", mu=c["friction"]["mu"], E=pw["material"]["E"], nu=pw["material"]["nu"])
    names = dict(wheel=v["wheel"], rail=c["rail"], wheel_profile=desc["wheel_name"] or None,
                 rail_profile=desc["rail_name"] or None)
    return c, v, veh, trk, prof, law, names


def _file_key(name: str) -> tuple:
    """What solve_curve's memo depends on: the curve and vehicle files' contents."""
    c = curve_file(name)
    out = [c.read_bytes() if c.exists() else b""]
    try:
        out.append(vehicle_file(load_curve(name)["vehicle"]).read_bytes())
    except (ConfigError, OSError):
        pass
    return tuple(out)


def solve_curve(name: str, **overrides) -> CurveSolution:
    """Load the curve ``name``, its vehicle, wheel, rail and profiles, and solve the leading
    bogie's steady curving.  ``overrides``: curve keys replaced (radius_m=..., speed_kmh=...,
    mu=...; validated like the file).  ConfigError for bad input (one line per problem,
    nothing solved); solvers.curving.CurvingError when no equilibrium is found."""
    return _solve_cached(name, _file_key(name), tuple(sorted(overrides.items())))


@functools.lru_cache(maxsize=64)
def _solve_cached(name: str, key: tuple, overrides: tuple) -> CurveSolution:
    from solvers.curving import solve
    from solvers.curving.summary import wheel_points

    c, v, veh, trk, prof, law, names = build_problem(name, **dict(overrides))
    sol = solve(prof, veh, trk, law)
    extra = dict(rolling_circle_y=trk.c, speed=trk.speed, mu=law.mu, friction_law=c["friction"]["law"],
                 wheel_file=names["wheel"], rail_file=names["rail"], wheel_profile=names["wheel_profile"],
                 rail_profile=names["rail_profile"])
    wheels = [WheelOperatingPoint(**row, **extra) for row in wheel_points(sol, law.mu)]
    return CurveSolution(name, c, v, names["wheel"], names["rail"], names["wheel_profile"], names["rail_profile"],
                         veh, trk, prof, sol, sol.flange_shift, trk.c, sol.max_residual, wheels)


def table(sol: CurveSolution) -> str:
    """A text table of the wheels (engineers' units)."""
    head = (f"curve {sol.name}: {sol.curve['vehicle']}, R = {sol.track.radius:g} m, cant {sol.curve['cant_mm']:g} mm, "
            f"{sol.curve['speed_kmh']:g} km/h, mu = {sol.wheels[0].mu:g}; flange contact at a shift of "
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


FIELDS = [f.name for f in fields(WheelOperatingPoint)]


def main(argv=None) -> int:
    from solvers.curving import CurvingError

    ap = argparse.ArgumentParser(prog="python -m pipeline.curve.curving",
                                 description="steady curving of a curve file's vehicle: every wheel of the leading bogie")
    ap.add_argument("--curve", required=True, help=f"pipeline/curves/<name>.toml (available: {available_curves()})")
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
