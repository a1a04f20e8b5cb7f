"""A curve's wheels as ordinary case files: ``$BUILD/curves/<curve>/cases/<wheel>.toml`` (the case
schema, ``pipeline.config.input_schemas.CASE``), so every stage runs them by the name ``<curve>/<wheel>``.

From the wheel's operating point: ``[contact] dy_wr``, ``[kinematics] gamma_y, gamma_x, spin, speed``
(the curve's speed), ``[loading] preload`` = the wheel load, ``[friction]`` = the curve's
friction table; the time step and duration as the default case (SPEC 6); the wheel and rail
files from the vehicle and the curve.  Keys the case schema does not know (spin, the contact
angle) stay in verdict.csv only.
"""
from __future__ import annotations

import tomli_w

from pipeline.store import paths
from pipeline.store.atomic import save_text
from pipeline.config.loader import ConfigError, validate
from pipeline.config.input_schemas import CASE
from pipeline.curve.operating import CurveInfo, WheelPoint

DT = 36e-6          # s, the default case's time step (SPEC 6)
DURATION = 8.0      # s of rolling at most (SPEC 6)


def fit_schema(data: dict, schema: dict) -> dict:
    """``data`` without the keys ``schema`` does not know and without None values (a key curving
    fixes that the case schema does not have yet stays in verdict.csv only)."""
    out = {}
    for k, v in data.items():
        if k not in schema or v is None:
            continue
        out[k] = fit_schema(v, schema[k]) if isinstance(v, dict) and isinstance(schema[k], dict) else v
    return out


def wheel_case(info: CurveInfo, p: WheelPoint) -> dict:
    """The case dict of one wheel (validated against the case schema: a ConfigError names the
    curve and the key when the operating point leaves a case's allowed range).  The keys curving
    fixes (``p.case``: contact point, friction, kinematics, preload = the tread contact's normal
    load) when it gives them, else the operating point's values."""
    case = {
        "name": f"{info.name}/{p.wheel}",
        "description": (f"{info.vehicle} in curve {info.name} (R = {info.radius:g} m, {info.speed_kmh:g} km/h), "
                        f"wheel {p.wheel}: written by the curve stage"),
        "wheel": info.wheel, "rail": info.rail,
        "contact": {"dy_wr": p.dy_wr, "model": "point", "normal": "table"},
        "friction": dict(info.friction),
        "kinematics": {"gamma_y": p.gamma_y, "gamma_x": p.gamma_x, "spin": p.spin, "speed": info.speed_kmh / 3.6},
        "loading": {"preload": p.wheel_load},
        "time": {"dt": DT, "duration": DURATION},
    }
    for k, v in (p.case or {}).items():
        case[k] = dict(case.get(k, {}), **v) if isinstance(v, dict) else v
    case["kinematics"].setdefault("spin", p.spin)
    case = fit_schema(case, CASE)
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
