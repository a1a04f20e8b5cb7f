"""Curve and vehicle files -> the nouns ``Curve`` and ``Vehicle`` (``pipeline.config.nouns``), each
validated once (``pipeline.config.curve_schemas``) where its file is read.

Where the files are (issue 33, a user's files outside the repository):

* a curve given as a path (it holds a ``/`` or ends in ``.toml``) is that file, anywhere; a bare
  name is the shipped ``pipeline/curves/<name>.toml``.  The curve's name is the file's stem: its
  results land in ``build/curves/<stem>/``;
* the vehicle a curve names (``vehicle = "<name>"``) is ``<name>.toml`` beside the curve file
  when there is one, else the shipped ``geometry/vehicles/<name>.toml``.

No environment variable chooses these folders: the caller passes a path (or a Curve).
"""
from __future__ import annotations

import os
from pathlib import Path

from pipeline.store import paths
from pipeline.config.curve_schemas import CURVE, VEHICLE
from pipeline.config.loader import ConfigError, load, validate
from pipeline.config.nouns import Bogie, Curve, FrictionLaw, Vehicle
from pipeline.config.train_inputs import train_of
from pipeline.caches.friction_curves import resolve_friction


def shipped_curves() -> Path:
    return paths.ROOT / "pipeline" / "curves"


def shipped_vehicles() -> Path:
    return paths.ROOT / "geometry" / "vehicles"


def is_path(where: str | os.PathLike) -> bool:
    """A curve (or CSV) given as a file rather than a shipped name: a Path, or text with a
    directory separator or a file suffix."""
    if isinstance(where, os.PathLike):
        return True
    return "/" in where or os.sep in where or where.endswith((".toml", ".csv"))


def curve_path(where: str | os.PathLike) -> Path:
    """The file of a curve given by path or by shipped name (module notes)."""
    if is_path(where):
        return Path(where).expanduser()
    return shipped_curves() / f"{where}.toml"


def curve_name(where: str | os.PathLike) -> str:
    """The curve's name (its build folder): the file's stem."""
    return curve_path(where).stem


def available_curves() -> list[str]:
    return paths.available(shipped_curves())


def available_vehicles(beside: Path | None = None) -> list[str]:
    """The vehicles a curve in folder ``beside`` can name: those beside it, then the shipped ones."""
    have = paths.available(Path(beside)) if beside is not None and Path(beside).is_dir() else []
    return sorted(set(have) | set(paths.available(shipped_vehicles())))


def vehicle_path(name: str, beside: Path | None = None) -> Path:
    """``<beside>/<name>.toml`` when it exists, else ``geometry/vehicles/<name>.toml`` (which may not)."""
    if beside is not None:
        local = Path(beside) / f"{name}.toml"
        if local.exists():
            return local
    return shipped_vehicles() / f"{name}.toml"


def vehicle_of(data: dict, source: Path) -> Vehicle:
    """The Vehicle of a validated vehicle file; exactly one of load.wheel_load_kN, load.axle_load_kN; its ``name``
    that of its file (a curve, a line's CSV and the build's folders name a vehicle by its file)."""
    if data["name"] != Path(source).stem:
        raise ConfigError(str(source), [("name", data["name"], f"the file's name {Path(source).stem!r} (a vehicle is "
                                         "named by its file: rename one to match the other)")])
    ld = data["load"]
    if (ld["wheel_load_kN"] is None) == (ld["axle_load_kN"] is None):
        given = ld["wheel_load_kN"] if ld["wheel_load_kN"] is not None else ld["axle_load_kN"]
        raise ConfigError(str(source), [("load.wheel_load_kN", given, "exactly one of load.wheel_load_kN and "
                                         "load.axle_load_kN (kN)")])
    b, w, p = data["bogie"], data["wheelset"], data["primary"]
    bogie = Bogie(wheel=data["wheel"], wheel_profile=data["wheel_profile"], wheelbase_m=b["wheelbase_m"],
                  back_to_back_mm=b["back_to_back_mm"], wheelset_mass_kg=w["mass_kg"],
                  wheelset_yaw_inertia_kgm2=w["yaw_inertia_kgm2"], primary_kx_MN_per_m=p["kx_MN_per_m"],
                  primary_ky_MN_per_m=p["ky_MN_per_m"], box_half_spacing_m=p["box_half_spacing_m"],
                  secondary_yaw_kNm_per_rad=data["secondary"]["yaw_stiffness_kNm_per_rad"])
    load_N = 1e3 * (ld["wheel_load_kN"] if ld["wheel_load_kN"] is not None else 0.5 * ld["axle_load_kN"])
    return Vehicle(name=data["name"], description=data["description"], source=Path(source), bogie=bogie,
                   train=train_of(data, source), wheel_load_N=load_N,
                   cg_height_m=ld["cg_height_m"], data=data)


def read_vehicle(name: str, beside: Path | None = None, asked_by: tuple[str, str] | None = None) -> Vehicle:
    """The validated vehicle ``name`` (``vehicle_path``); a missing file is a one-line ConfigError
    naming the file and key that asked for it (``asked_by``: (file, key)) when given."""
    path = vehicle_path(name, beside)
    if not path.exists():
        where = f"beside the curve file ({beside}) or in geometry/vehicles/" if beside is not None else \
            "in geometry/vehicles/"
        text = f"no such vehicle {name!r} {where}; available: {available_vehicles(beside)}"
        if asked_by is not None:
            raise ConfigError(asked_by[0], detail=f"{asked_by[1]} = {name!r}: {text}")
        raise ConfigError(str(path), detail=text)
    return vehicle_of(load(path, VEHICLE), path)


def curve_of(data: dict, source: Path, name: str | None = None, vehicle: Vehicle | None = None) -> Curve:
    """The Curve of a validated curve dict read from (or written beside) ``source``: its vehicle
    looked up beside ``source`` first (or ``vehicle``), its friction resolved once."""
    source = Path(source)
    if vehicle is None:
        vehicle = read_vehicle(data["vehicle"], source.parent, asked_by=(str(source), "vehicle"))
    friction: FrictionLaw = resolve_friction({k: v for k, v in data["friction"].items() if k != "climate"}, str(source))
    return Curve(name=name or source.stem, description=data["description"], source=source, vehicle=vehicle,
                 rail=data["rail"], rail_profile=data["rail_profile"], radius_m=data["radius_m"],
                 cant_mm=data["cant_mm"], gauge_mm=data["gauge_mm"], gauge_widening_mm=data["gauge_widening_mm"],
                 speed_kmh=data["speed_kmh"], friction=friction, traction_force_kN=data["traction"]["force_kN"],
                 data=data)


def read_curve_data(where: str | os.PathLike) -> tuple[dict, Path]:
    """(validated curve dict, its file) of a curve given by path or shipped name."""
    path = curve_path(where)
    if not path.exists():
        if is_path(where):
            raise ConfigError(str(path), detail="no such curve file")
        raise ConfigError(str(path), detail=f"no such curve {path.stem!r}; available: {available_curves()} "
                                            "(or give a path to a curve file)")
    return load(path, CURVE), path


def with_overrides(data: dict, source: str, **overrides) -> dict:
    """``data`` with top-level keys (radius_m, speed_kmh, cant_mm, ...) and ``mu`` (the friction's
    coefficient) replaced, validated again (what-ifs and studies)."""
    if not overrides:
        return data
    new = {k: v for k, v in data.items() if v is not None}
    new["friction"] = {k: v for k, v in data["friction"].items() if v is not None}
    for k, v in overrides.items():
        if k == "mu":
            new["friction"]["mu"] = v
        else:
            new[k] = v
    what = ", ".join(f"{k} = {v!r}" for k, v in overrides.items())
    return validate(new, CURVE, f"{source} with {what}")


def read_curve(where: str | os.PathLike | Curve, **overrides) -> Curve:
    """The Curve of a file (path or shipped name, module notes), or of a Curve, with ``overrides``
    (``with_overrides``).  Every problem is a ConfigError naming the file and key."""
    if isinstance(where, Curve):
        if not overrides:
            return where
        return curve_of(with_overrides(where.data, str(where.source), **overrides), where.source, where.name,
                        where.vehicle if "vehicle" not in overrides else None)
    data, path = read_curve_data(where)
    return curve_of(with_overrides(data, str(path), **overrides), path)
