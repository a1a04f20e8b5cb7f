"""The curve's operating points as the verdict reads them: one ``WheelPoint`` per wheel of the
leading bogie and a ``CurveInfo`` of the curve and vehicle, taken from
``pipeline.curve.curving.solve_curve(curve) -> CurveSolution`` (the curving helper's module; this is
the only place that reads its objects, so a change there is adapted here).

Sign conventions (BRIEF, "Sign conventions of a curve wheel"): track lateral y positive toward
the outer rail; dy_wr positive toward the field side of that wheel's rail; creepages in the
contact frame of SPEC 2 (1 in the travel direction, 2 toward that rail's field side).  Wheel
ids ``a1o``, ``a1i``, ``a2o``, ``a2i``: axle 1 the leading axle of the leading bogie, o/i the
outer/inner rail.  Units SI (lengths m, angles rad, forces N).
"""
from __future__ import annotations

import math
from typing import Any, NamedTuple

WHEELS = ("a1o", "a1i", "a2o", "a2i")
CONTACT_SPACING = 1.5    # m between the rolling circles of a standard-gauge wheelset (the plot's scale only)

# the verdict's columns from curving, in verdict.csv's order
POINT_KEYS = ("dy_wr", "angle_of_attack", "gamma_x", "gamma_y", "spin", "y_wheel", "y_rail", "contact_angle",
              "wheel_load", "contact_points")


class WheelPoint(NamedTuple):
    wheel: str               # a1o, a1i, a2o, a2i
    dy_wr: float             # m
    angle_of_attack: float   # rad (positive: under-radial)
    gamma_x: float
    gamma_y: float
    spin: float              # 1/m
    y_wheel: float           # m, contact point on the wheel (y^W)
    y_rail: float            # m, on the rail head (y^R)
    contact_angle: float     # rad
    wheel_load: float        # N
    contact_points: int      # 1, or 2 with flange contact
    nadal: float = math.nan  # lateral/vertical force ratio of a flange contact
    case: dict | None = None  # the case-file keys curving fixes for this wheel (``case_fields()``), if any


class CurveInfo(NamedTuple):
    name: str
    radius: float            # m
    speed_kmh: float
    cant: float              # m
    gauge: float             # m (with widening)
    wheel: str               # geometry/wheels/<wheel>.toml
    rail: str                # geometry/rails/<rail>.toml
    vehicle: str
    friction: dict           # the case file's [friction] table
    wheelbase: float         # bogie wheelbase (m)
    contact_spacing: float   # lateral distance of the two rolling circles (m)
    sources: tuple = ()      # the curve and vehicle files


def _get(obj: Any, key: str, default=None):
    if isinstance(obj, dict):
        return obj.get(key, default)
    return getattr(obj, key, default)


def wheel_points(solution) -> list[WheelPoint]:
    """The leading bogie's wheels of a ``CurveSolution`` (``.wheels``: a mapping wheel id ->
    operating point, or a sequence of points with a ``wheel`` id), in ``WHEELS`` order."""
    wheels = _get(solution, "wheels")
    items = wheels.items() if hasattr(wheels, "items") else ((_get(w, "wheel", _get(w, "id")), w) for w in wheels)
    out = {}
    for wid, w in items:
        vals = {k: _get(w, k) for k in POINT_KEYS}
        missing = [k for k, v in vals.items() if v is None]
        if missing:
            raise ValueError(f"curving's operating point of wheel {wid} lacks {missing}")
        fields = getattr(w, "case_fields", None)
        out[str(wid)] = WheelPoint(str(wid), *(float(vals[k]) for k in POINT_KEYS[:-1]),
                                   int(vals["contact_points"]), float(_get(w, "nadal", math.nan) or math.nan),
                                   fields() if callable(fields) else None)
    return [out[w] for w in WHEELS if w in out]


def curve_info(name: str, solution) -> CurveInfo:
    """The curve and vehicle data the verdict needs, from the solution's ``curve`` and ``vehicle``
    (the validated curve and vehicle files, ``pipeline.config.curve_schemas``: lengths in the units their
    key names state)."""
    from pipeline.curve.curving import curve_file, vehicle_file

    c, v = _get(solution, "curve"), _get(solution, "vehicle")
    mm = 1e-3
    vehicle = str(c["vehicle"])
    return CurveInfo(name=name, radius=float(c["radius_m"]), speed_kmh=float(c["speed_kmh"]),
                     cant=mm * float(c.get("cant_mm") or 0.0),
                     gauge=mm * (float(c["gauge_mm"]) + float(c.get("gauge_widening_mm") or 0.0)),
                     wheel=str(_get(solution, "wheel") or v["wheel"]), rail=str(_get(solution, "rail") or c["rail"]),
                     vehicle=vehicle, friction=dict(c["friction"]), wheelbase=float(v["bogie"]["wheelbase_m"]),
                     contact_spacing=CONTACT_SPACING, sources=(str(curve_file(name)), str(vehicle_file(vehicle))))
