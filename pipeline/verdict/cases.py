"""A curve's wheels as ordinary case files: ``$BUILD/curves/<curve>/cases/<wheel>.toml`` (the case
schema, ``pipeline.schemas.CASE``), so every stage runs them by the name ``<curve>/<wheel>``.

From the wheel's operating point: ``[contact] dy_wr``, ``[kinematics] gamma_y, gamma_x, speed``
(the curve's speed), ``[loading] preload`` = the wheel load, ``[friction]`` = the curve's
friction table; the time step and duration as the default case (SPEC 6); the wheel and rail
files from the vehicle and the curve.  Keys the case schema does not know (spin, the contact
angle) stay in verdict.csv only.
"""
from __future__ import annotations

import tomli_w

from .. import paths
from ..atomic import save_text
from ..config import ConfigError, validate
from ..schemas import CASE
from .operating import CurveInfo, WheelPoint

DT = 36e-6          # s, the default case's time step (SPEC 6)
DURATION = 8.0      # s of rolling at most (SPEC 6)


def wheel_case(info: CurveInfo, p: WheelPoint) -> dict:
    """The case dict of one wheel (validated against the case schema: a ConfigError names the
    curve and the key when the operating point leaves a case's allowed range)."""
    case = {
        "name": f"{info.name}/{p.wheel}",
        "description": (f"{info.vehicle} in curve {info.name} (R = {info.radius:g} m, {info.speed_kmh:g} km/h), "
                        f"wheel {p.wheel}: written by the curve stage"),
        "wheel": info.wheel, "rail": info.rail,
        "contact": {"dy_wr": round(p.dy_wr, 9), "model": "point", "normal": "table"},
        "friction": dict(info.friction),
        "kinematics": {"gamma_y": round(p.gamma_y, 12), "gamma_x": round(p.gamma_x, 12),
                       "speed": info.speed_kmh / 3.6},
        "loading": {"preload": round(p.wheel_load, 3)},
        "time": {"dt": DT, "duration": DURATION},
    }
    where = paths.case_file(case["name"])
    try:
        validate(case, CASE, str(where))
    except ConfigError as e:
        what = "; ".join(f"{k} = {v!r}: expected {a}" for k, v, a in e.errors) or str(e.detail)
        raise ConfigError(info.sources[0] if info.sources else info.name,
                          detail=f"steady curving puts wheel {p.wheel} outside a case's range: {what}") from None
    return case


def write_case(case: dict) -> str:
    """Write the case file atomically, unchanged files untouched (Make's timestamps); its path."""
    path = paths.case_file(case["name"])
    text = "# written by the curve stage (make curve); edits are overwritten\n" + tomli_w.dumps(case)
    if not (path.exists() and path.read_text() == text):
        save_text(text, path)
    return str(path)
