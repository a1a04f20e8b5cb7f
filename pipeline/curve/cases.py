"""A curve's wheels as resolved cases, built in memory: ``wheel_case(curve, point)`` is the
``pipeline.config.case.ResolvedCase`` named ``<curve>/<wheel>`` that the stages run, with the curve's
friction (resolved once, when the curve was read) and the case dict of the case schema
(``pipeline.config.input_schemas.CASE``).

From the wheel's operating point (``pipeline.config.nouns.WheelOperatingPoint.case_fields``):
``[contact] dy_wr, rolling_circle_y`` (and the profiles), ``[kinematics] gamma_y, gamma_x, spin,
speed`` (the curve's speed), ``[loading] preload`` = the tread contact's normal load,
``[friction]`` = the curve's friction table; the time step and duration as the default case
(SPEC 6); the wheel and rail files from the vehicle and the curve.  Keys the case schema does not
know (the contact angle, ...) stay in verdict.csv only.

``write_case`` writes the case as a record, ``$BUILD/curves/<curve>/cases/<wheel>.toml``, so that
``make <stage> CASE=<curve>/<wheel>`` can run a stage of the wheel alone; the curve stage itself
does not read it back.
"""
from __future__ import annotations

import tomli_w

from pipeline.store import paths
from pipeline.store.atomic import save_text
from pipeline.config.case import ResolvedCase, resolve_built
from pipeline.config.loader import ConfigError, validate
from pipeline.config.input_schemas import CASE
from pipeline.config.nouns import Curve, WheelOperatingPoint

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


def case_dict(curve: Curve, p: WheelOperatingPoint) -> dict:
    """The case dict of one wheel (as a case file holds it, before validation): the keys curving fixes
    (``p.case_fields()``: contact point, friction, kinematics, preload) over the curve's."""
    case = {
        "name": f"{curve.name}/{p.wheel}",
        "description": (f"{curve.vehicle.name} in curve {curve.name} (R = {curve.radius_m:g} m, "
                        f"{curve.speed_kmh:g} km/h), wheel {p.wheel}: written by the curve stage"),
        "wheel": curve.wheel, "rail": curve.rail,
        "contact": {"dy_wr": p.dy_wr, "model": "point", "normal": "table"},
        "friction": {k: v for k, v in curve.data["friction"].items() if v is not None and k != "climate"},
        "kinematics": {"gamma_y": p.gamma_y, "gamma_x": p.gamma_x, "spin": p.spin, "speed": curve.speed_kmh / 3.6},
        "loading": {"preload": p.wheel_load},
        "time": {"dt": DT, "duration": DURATION},
    }
    t = curve.vehicle.train                       # the listen stage's pass-by: this wheel in every car of the train
    case["listener"] = {"passby": {"n_bogies": t.cars, "bogie_spacing": t.car_length_m or t.bogie_spacing_m}}
    for k, v in p.case_fields().items():
        case[k] = dict(case.get(k, {}), **v) if isinstance(v, dict) else v
    case["kinematics"].setdefault("spin", p.spin)
    return fit_schema(case, CASE)


def wheel_case(curve: Curve, p: WheelOperatingPoint) -> ResolvedCase:
    """The ResolvedCase of one wheel (module notes).  A ConfigError names the curve file and the key
    when the operating point leaves a case's allowed range or its contact cannot be made."""
    case = case_dict(curve, p)
    where = str(curve.source)
    try:
        c = validate(case, CASE, where)
    except ConfigError as e:
        what = "; ".join(f"{k} = {v!r}: expected {a}" for k, v, a in e.errors) or str(e.detail)
        raise ConfigError(where, detail=f"steady curving puts wheel {p.wheel} outside a case's range: {what}") from None
    return resolve_built(case["name"], c, curve.friction, where)


def write_case(rc: ResolvedCase) -> str:
    """Write the wheel's case file atomically (a record, module notes: the validated case, defaults
    included, so that the file loads to ``rc.case``), unchanged files untouched (Make's timestamps);
    its path."""
    case = fit_schema(rc.case, CASE)
    path = paths.case_file(rc.name)
    text = "# written by the curve stage (make curve); edits are overwritten\n" + tomli_w.dumps(case)
    if not (path.exists() and path.read_text() == text):
        save_text(text, path)
    return str(path)
