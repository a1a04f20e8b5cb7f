"""The line study's input: its CSV of curves, validated like every input, and a curve file per row.

The CSV (``curves = "<file>.csv"`` of the study file: a path relative to the study file's folder,
pipeline/studies/, or an absolute one, anywhere): lines starting with ``#`` are comments; the header
names the columns (any order, each once):

| column | unit | allowed | meaning |
|---|---|---|---|
| ``id`` | - | non-empty text | the curve's name on the line (e.g. C07) |
| ``chainage_m`` | m | 0 .. 1e7 | where the curve starts along the line |
| ``radius_m`` | m | as a curve file's ``radius_m`` | curve radius |
| ``cant_mm`` | mm | as ``cant_mm`` | superelevation |
| ``length_m`` | m | 1 .. 20000 | curve length (the chainage plot) |
| ``speed_kmh`` | km/h | as ``speed_kmh`` | the vehicle's speed in the curve |
| ``vehicle`` | - | a file <vehicle>.toml beside the CSV, or geometry/vehicles/<vehicle>.toml | the vehicle |
| ``friction`` | - | ``dry``, ``wet`` (the study file's ``[friction] dry_mu``, ``wet_mu``), a Coulomb coefficient 0 < mu <= 1, a friction preset (e.g. ``hpf``) or ``base`` (the base curve's ``[friction]``, any law: ``line_friction``) | the friction condition |

A row is one curve, vehicle and friction condition (the same ``id`` may appear once per vehicle and
condition).  Every problem of every row is one line naming the file, the line, the column, the value
and what is allowed, all reported together before any work (``make check STUDY=<line>``).

Each row becomes a ``Curve`` in memory (``line_curves``: the study file's ``base_curve`` -- a shipped
name, or a curve file's path relative to the study file's folder -- with the row's vehicle, radius,
cant, speed and friction coefficient; validated by the curve schema), sent to the row's worker, and
its curve file is written as a record in ``build/studies/<line>/curves/``.
"""
from __future__ import annotations

import csv
import math
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

import tomli_w

from pipeline.store import paths
from pipeline.config.loader import ConfigError, Field, validate
from pipeline.config.curve_schemas import CURVE
from pipeline.config.nouns import Curve
from pipeline.study.line_risk import climate_cell
from pipeline.config.curve_inputs import curve_path, is_path, available_vehicles, curve_of, read_vehicle
from pipeline.store.atomic import save_text
from pipeline.study.line_friction import law_condition, allowed

COLUMNS = ("id", "chainage_m", "radius_m", "cant_mm", "length_m", "speed_kmh", "vehicle", "friction")
NUMERIC = {
    "chainage_m": Field(float, unit="m", min=0.0, max=1e7, doc="where the curve starts along the line"),
    "radius_m": CURVE["radius_m"],
    "cant_mm": CURVE["cant_mm"],
    "length_m": Field(float, unit="m", min=1.0, max=20000.0, doc="length of the curve"),
    "speed_kmh": CURVE["speed_kmh"],
}
MU = CURVE["friction"]["mu"]
CONDITIONS = ("dry", "wet")
# the CSV's columns as a schema (docs/inputs.md; the rows are checked by ``read_rows``)
ROW_SCHEMA = {
    "id": Field(str, doc="the curve's name on the line; one row per id, vehicle and friction condition"),
    **NUMERIC,
    "vehicle": Field(str, doc="<vehicle>.toml beside the CSV, else geometry/vehicles/<vehicle>.toml"),
    "friction": Field(str, doc="'dry' or 'wet' (the study file's [friction] dry_mu, wet_mu), a Coulomb "
                               "coefficient 0 < mu <= 1, a friction preset (e.g. 'hpf') or 'base' (the base curve's "
                               "[friction], any law)"),
}


@dataclass(frozen=True)
class LineRow:
    """One validated row of the line's CSV (SI where the unit says so; ``condition``: dry, wet or mu=<x>)."""
    line: int
    id: str
    chainage_m: float
    radius_m: float
    cant_mm: float
    length_m: float
    speed_kmh: float
    vehicle: str
    condition: str
    mu: float
    table: tuple = ()      # the curve's [friction] items for a preset or 'base' (line_friction), () for Coulomb

    @property
    def key(self) -> str:
        return f"{self.id}|{self.vehicle}|{self.condition}"

    def curve_name(self, line: str) -> str:
        """The name of its curve file (and its build folders): safe characters only."""
        return re.sub(r"[^A-Za-z0-9_.-]", "_", f"{line}-{self.id}-{self.vehicle}-{self.condition}")


def _allowed(f: Field) -> str:
    return f"a number in [{f.min:g}, {f.max:g}] {f.unit}".rstrip()


def _range_ok(f: Field, x: float) -> bool:
    return math.isfinite(x) and f.min <= x <= f.max


def curves_file(spec: dict) -> Path:
    """The line's CSV: ``curves`` relative to the study folder, or absolute."""
    return paths.studies() / Path(spec["curves"]).expanduser()


def base_curve_file(spec: dict) -> Path:
    """The base curve: a shipped name, or a path relative to the study folder (or absolute)."""
    base = spec["base_curve"]
    return paths.studies() / Path(base).expanduser() if is_path(base) else curve_path(base)


def read_rows(spec: dict, path: Path | None = None) -> list[LineRow]:
    """The validated rows of the study's CSV (module notes); a ConfigError lists every problem."""
    path = Path(path or curves_file(spec))
    if not path.exists():
        raise ConfigError(str(paths.study_file(spec["name"])), [("curves", spec["curves"], f"a CSV file in "
                                                                 f"{paths.studies()} (no such file)")])
    problems, rows = [], []
    text = path.read_text(encoding="utf-8").splitlines()
    lines = [(i + 1, t) for i, t in enumerate(text) if t.strip() and not t.lstrip().startswith("#")]
    if not lines:
        raise ConfigError(str(path), detail="no header line (columns: " + ", ".join(COLUMNS) + ")")
    head_no, head = lines[0]
    header = [h.strip() for h in next(csv.reader([head]))]
    missing = [c for c in COLUMNS if c not in header]
    unknown = [h for h in header if h not in COLUMNS]
    if missing or unknown or len(set(header)) != len(header):
        raise ConfigError(str(path), [(f"line {head_no}, header", head, "the columns " + ", ".join(COLUMNS) +
                                       " once each (units in the names: chainage_m, radius_m, cant_mm, length_m, "
                                       "speed_kmh)")])
    vehicles = available_vehicles(path.parent)            # beside the CSV, then geometry/vehicles/
    mus = {"dry": spec["friction"]["dry_mu"], "wet": spec["friction"]["wet_mu"]}
    seen = {}
    for no, t in lines[1:]:
        cells = next(csv.reader([t]))
        where = f"line {no}"
        if len(cells) != len(header):
            problems.append((where, t, f"{len(header)} comma-separated fields ({', '.join(header)})"))
            continue
        r = {h: c.strip() for h, c in zip(header, cells)}
        vals, ok = {}, True
        for col, f in NUMERIC.items():
            try:
                x = float(r[col])
            except ValueError:
                x = math.nan
            if not _range_ok(f, x):
                problems.append((f"{where}, {col}", r[col], _allowed(f)))
                ok = False
            vals[col] = x
        if not r["id"]:
            problems.append((f"{where}, id", r["id"], "a non-empty name"))
            ok = False
        if r["vehicle"] not in vehicles:
            problems.append((f"{where}, vehicle", r["vehicle"], f"one of {vehicles} (beside the CSV or in "
                                                                "geometry/vehicles/)"))
            ok = False
        cond = r["friction"].lower()
        law = None if cond in mus else law_condition(cond, base_curve_file(spec))   # a preset or 'base'
        if cond in mus:
            mu = mus[cond]
        elif law is not None:
            cond, mu, _ = law
        else:
            try:
                mu = float(r["friction"])
            except ValueError:
                mu = math.nan
            if not (math.isfinite(mu) and 0.0 < mu <= MU.max):
                problems.append((f"{where}, friction", r["friction"], allowed()))
                ok = False
            cond = f"mu={mu:g}"
        if not ok:
            continue
        row = LineRow(no, r["id"], vals["chainage_m"], vals["radius_m"], vals["cant_mm"], vals["length_m"],
                      vals["speed_kmh"], r["vehicle"], cond, float(mu), law[2] if law else ())
        if row.key in seen:
            problems.append((f"{where}, id", r["id"], f"one row per id, vehicle and friction (line {seen[row.key]} "
                                                      "has the same)"))
            continue
        seen[row.key] = no
        rows.append(row)
    if not rows and not problems:
        problems.append((f"line {head_no + 1}", "", "at least one curve"))
    if problems:
        raise problems_error(path, problems)
    return rows


def problems_error(path, problems) -> ConfigError:
    """One ConfigError with one line per problem, each naming the file, the line and column, the value
    and what is allowed."""
    lines = [f"{k} = {v!r}: expected {a}" for k, v, a in problems]
    return ConfigError(str(path), detail=f"\n{path}: ".join(lines))


def curve_data(spec: dict, row: LineRow, name: str) -> dict:
    """The curve file of ``row`` (the base curve's keys with the row's; validated: a ConfigError names
    the CSV line)."""
    base = base_curve_file(spec)
    if not base.exists():
        raise ConfigError(str(paths.study_file(spec["name"])), [("base_curve", spec["base_curve"],
                                                                 "a curve of pipeline/curves/ or a curve file's "
                                                                 "path (no such file)")])
    data = tomllib.loads(base.read_text())
    data.update(name=name, vehicle=row.vehicle, radius_m=row.radius_m, cant_mm=row.cant_mm, speed_kmh=row.speed_kmh,
                description=f"line {spec['name']}, curve {row.id} at {row.chainage_m:g} m ({row.length_m:g} m long), "
                            f"{row.vehicle}, friction {row.condition}")
    data["friction"] = dict(row.table) if row.table else {"law": "coulomb", "mu": row.mu}
    data["friction"]["climate"] = climate_cell(spec)                # the risk columns' climate (line_risk)
    try:
        validate(data, CURVE, f"{curves_file(spec)}: line {row.line}")
    except ConfigError as e:
        raise problems_error(curves_file(spec), [(f"line {row.line}, {k}", v, a) for k, v, a in e.errors]) from None
    return data


def line_curves(spec: dict, rows: list[LineRow], folder: Path) -> dict[str, tuple[Curve, str]]:
    """{row key: (its Curve, its curve file's text)}: each row's curve built in memory (module notes),
    its vehicle looked up beside the CSV first, and its curve file written into ``folder`` as a record
    (unchanged files untouched)."""
    folder.mkdir(parents=True, exist_ok=True)
    beside = curves_file(spec).parent
    vehicles, out = {}, {}
    for row in rows:
        name = row.curve_name(spec["name"])
        data = curve_data(spec, row, name)
        text = (f"# written by the line study {spec['name']} (pipeline/study/line_input.py) from "
                f"{spec['curves']} line {row.line}\n" + tomli_w.dumps(data))
        path = folder / f"{name}.toml"
        if not (path.exists() and path.read_text() == text):
            save_text(text, path)
        if row.vehicle not in vehicles:
            vehicles[row.vehicle] = read_vehicle(row.vehicle, beside, asked_by=(str(curves_file(spec)), "vehicle"))
        out[row.key] = (curve_of(validate(data, CURVE, str(path)), path, name, vehicles[row.vehicle]), text)
    return out


def check(spec: dict) -> list[LineRow]:
    """Everything the line study would refuse, without computing: the CSV and each row's curve."""
    rows = read_rows(spec)
    for row in rows:
        curve_data(spec, row, row.curve_name(spec["name"]))
    return rows
