"""CNOSSOS-EU railway source tables (as NoiseModelling ships them) and the rolling sound power of a
vehicle on a track.

The tables live in ``pipeline/data/cnossos/`` (source, commit and licence in its README.md):

* ``RailwayCnossosEU_2020.json``: Appendix G of Directive 2002/49/EC Annex II (Directive (EU)
  2015/996 as amended by (EU) 2021/1226): ``Vehicle.WheelRoughness`` / ``Vehicle.ContactFilter``
  (35 wavelengths, 2000 ... 0.8 mm), ``Vehicle.Transfer`` (wheel L_H,VEH, 24 bands),
  ``Track.TrackTransfer`` (L_H,TR, 24 bands), ``Track.RailRoughness`` and ``Track.ImpactNoise``
  (35 wavelengths), each keyed by a reference ("0", "1", ...);
* ``RailwayVehiclesCnossos_2015.json``: named vehicle types, each with ``NbAxlePerVeh`` and its
  references ``RefRoughness``, ``RefContact``, ``RefTransfer`` into the first file.

A track type is the triple (track transfer, rail roughness, impact) of references, e.g.
``{"transfer": "7", "rail_roughness": "4"}`` (bi-block sleepers, medium pads, average network).

    f, L_W = rolling_power_bands("RMR-Cat-1", {"transfer": "7", "rail_roughness": "4"}, 120.0)

A missing or malformed entry raises ``ConfigError`` naming the file and the key.
"""
from __future__ import annotations

import functools
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pipeline.config.loader import ConfigError
from solvers.radiation import rolling_cnossos as rc

__all__ = ["DATA_DIR", "TABLES_FILE", "VEHICLES_FILE", "CnossosVehicle", "CnossosTrack", "CnossosTables",
           "load_tables", "rolling_power_bands", "rolling_power_components"]

DATA_DIR = Path(__file__).resolve().parent.parent / "data" / "cnossos"
TABLES_FILE = "RailwayCnossosEU_2020.json"
VEHICLES_FILE = "RailwayVehiclesCnossos_2015.json"


@dataclass(frozen=True)
class CnossosVehicle:
    """A CNOSSOS vehicle type: axles per vehicle, wheel roughness and contact filter per wavelength
    (``rolling_cnossos.WAVELENGTH_MM``), wheel transfer function per band (dB per axle)."""
    name: str
    n_axles: float
    wheel_roughness_db: tuple[float, ...]
    contact_filter_db: tuple[float, ...]
    transfer_db: tuple[float, ...]
    refs: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class CnossosTrack:
    """A CNOSSOS track type: track transfer function per band, rail roughness (and, with joints or
    switches, impact roughness for one per 100 m) per wavelength."""
    name: str
    transfer_db: tuple[float, ...]
    rail_roughness_db: tuple[float, ...]
    impact_db: tuple[float, ...] | None = None
    joint_density_per_m: float = rc.REFERENCE_JOINT_DENSITY


def _fail(path: Path, key: str, value, allowed: str):
    shown = repr(value)
    shown = shown if len(shown) <= 60 else shown[:57] + "..."
    raise ConfigError(str(path), detail=f"key {key!r}: value {shown}; allowed: {allowed}")


def _read(path: Path) -> dict:
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        raise ConfigError(str(path), detail="file not found (CNOSSOS tables, see pipeline/data/cnossos/README.md)") from None
    except json.JSONDecodeError as e:
        raise ConfigError(str(path), detail=f"not valid JSON: {e}") from None
    if not isinstance(data, dict):
        _fail(path, "<root>", type(data).__name__, "a JSON object")
    return data


def _node(path: Path, root: Mapping, keys: tuple[str, ...]):
    node = root
    for i, k in enumerate(keys):
        if not isinstance(node, Mapping) or k not in node:
            where = ".".join(keys[:i]) or "<root>"
            have = list(node) if isinstance(node, Mapping) else []
            _fail(path, ".".join(keys[:i + 1]), k, f"one of the keys of {where}: {', '.join(have[:20])}")
        node = node[k]
    return node


def _values(path: Path, root: Mapping, keys: tuple[str, ...], n: int) -> tuple[float, ...]:
    v = _node(path, root, keys)
    ok = isinstance(v, list) and len(v) == n and all(
        isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in v)
    if not ok:
        _fail(path, ".".join(keys), v, f"a list of {n} finite numbers (dB)")
    return tuple(float(x) for x in v)


@dataclass(frozen=True)
class CnossosTables:
    """The two JSON files, read once; look-ups return typed, validated objects."""
    tables_path: Path
    vehicles_path: Path
    tables: Mapping
    vehicles: Mapping

    def vehicle_names(self) -> list[str]:
        return list(self.vehicles)

    def vehicle(self, name: str) -> CnossosVehicle:
        """The named vehicle type of the vehicles file, its references resolved in the tables file."""
        if name not in self.vehicles:
            _fail(self.vehicles_path, name, name, f"a vehicle type of the file ({len(self.vehicles)} types, "
                  f"e.g. {', '.join(list(self.vehicles)[:6])})")
        row = self.vehicles[name]
        refs = {}
        for key in ("RefRoughness", "RefContact", "RefTransfer", "NbAxlePerVeh"):
            refs[key] = _node(self.vehicles_path, self.vehicles, (name, key))
        n_axles = refs["NbAxlePerVeh"]
        if isinstance(n_axles, bool) or not isinstance(n_axles, (int, float)) or not n_axles > 0:
            _fail(self.vehicles_path, f"{name}.NbAxlePerVeh", n_axles, "a number of axles > 0")
        desc = row.get("Description", "") if isinstance(row, Mapping) else ""
        return self.vehicle_from_refs(roughness=refs["RefRoughness"], contact=refs["RefContact"],
                                      transfer=refs["RefTransfer"], n_axles=float(n_axles),
                                      name=f"{name} ({desc})" if desc else name)

    def vehicle_from_refs(self, *, roughness, contact, transfer, n_axles: float, name: str = "custom") -> CnossosVehicle:
        """A vehicle type assembled from table references (wheel roughness, contact filter, transfer)."""
        p, t = self.tables_path, self.tables
        if isinstance(n_axles, bool) or not (isinstance(n_axles, (int, float)) and n_axles > 0):
            _fail(p, f"{name}.n_axles", n_axles, "a number of axles > 0")
        return CnossosVehicle(
            name=name, n_axles=float(n_axles),
            wheel_roughness_db=_values(p, t, ("Vehicle", "WheelRoughness", str(roughness), "Values"), rc.N_WAVELENGTHS),
            contact_filter_db=_values(p, t, ("Vehicle", "ContactFilter", str(contact), "Values"), rc.N_WAVELENGTHS),
            transfer_db=_values(p, t, ("Vehicle", "Transfer", str(transfer), "Spectre"), rc.N_BANDS),
            refs=(("RefRoughness", str(roughness)), ("RefContact", str(contact)), ("RefTransfer", str(transfer))))

    def track(self, transfer, rail_roughness, impact=None) -> CnossosTrack:
        """A track type from references: ``Track.TrackTransfer``, ``Track.RailRoughness`` and optionally
        ``Track.ImpactNoise`` (an entry whose ``JoinDensity`` is null means no joints, as in NoiseModelling)."""
        p, t = self.tables_path, self.tables
        imp = None
        if impact not in (None, ""):
            node = _node(p, t, ("Track", "ImpactNoise", str(impact)))
            if not (isinstance(node, Mapping) and "JoinDensity" in node and node["JoinDensity"] is None):
                imp = _values(p, t, ("Track", "ImpactNoise", str(impact), "Values"), rc.N_WAVELENGTHS)
        return CnossosTrack(
            name=f"TrackTransfer {transfer} / RailRoughness {rail_roughness} / ImpactNoise {impact}",
            transfer_db=_values(p, t, ("Track", "TrackTransfer", str(transfer), "Spectre"), rc.N_BANDS),
            rail_roughness_db=_values(p, t, ("Track", "RailRoughness", str(rail_roughness), "Values"), rc.N_WAVELENGTHS),
            impact_db=imp)


@functools.lru_cache(maxsize=4)
def load_tables(data_dir: str | Path = DATA_DIR, tables_file: str = TABLES_FILE,
                vehicles_file: str = VEHICLES_FILE) -> CnossosTables:
    """Read the tables and vehicle files (cached per path)."""
    tp, vp = Path(data_dir) / tables_file, Path(data_dir) / vehicles_file
    tables, vehicles = _read(tp), _read(vp)
    for sec in ("Vehicle", "Track"):
        _node(tp, tables, (sec,))
    return CnossosTables(tp, vp, tables, vehicles)


def _resolve(vehicle, track, tables: CnossosTables | None) -> tuple[CnossosVehicle, CnossosTrack]:
    tables = tables if tables is not None else load_tables()
    veh = tables.vehicle(vehicle) if isinstance(vehicle, str) else vehicle
    if isinstance(track, Mapping):
        unknown = set(track) - {"transfer", "rail_roughness", "impact"}
        if unknown or not {"transfer", "rail_roughness"} <= set(track):
            _fail(tables.tables_path, "track", dict(track), "a mapping with keys transfer, rail_roughness [, impact]")
        track = tables.track(track["transfer"], track["rail_roughness"], track.get("impact"))
    if not isinstance(veh, CnossosVehicle) or not isinstance(track, CnossosTrack):
        raise TypeError("vehicle: a vehicle type name or CnossosVehicle; track: a CnossosTrack or a reference mapping")
    return veh, track


def rolling_power_components(vehicle, track, speed_kmh: float, *, tables: CnossosTables | None = None) -> dict:
    """Everything of the rolling-noise chain for one vehicle (see ``rolling_power_bands``): the total
    effective roughness per wavelength and per band, and the track (2.3.8), vehicle (2.3.9) and total
    sound power per vehicle per band (dB re 1 pW)."""
    veh, trk = _resolve(vehicle, track, tables)
    if not (isinstance(speed_kmh, (int, float)) and math.isfinite(speed_kmh) and speed_kmh > 0):
        raise ValueError(f"speed_kmh = {speed_kmh!r}: must be a number > 0 (km/h)")
    r_lambda = rc.total_roughness_wavelength(trk.rail_roughness_db, veh.wheel_roughness_db, veh.contact_filter_db,
                                             trk.impact_db, trk.joint_density_per_m)
    r_f = rc.roughness_to_frequency(r_lambda, float(speed_kmh))
    power = rc.rolling_power(r_f, trk.transfer_db, veh.transfer_db, veh.n_axles)
    return {"vehicle": veh, "track": trk, "speed_kmh": float(speed_kmh), "f_centre": rc.F_CENTRE_NOMINAL.copy(),
            "roughness_lambda": r_lambda, "roughness_f": r_f, **{f"L_W_{k}": v for k, v in power.items()}}


def rolling_power_bands(vehicle, track, speed_kmh: float, *, vehicles_per_hour: float | None = None,
                        tables: CnossosTables | None = None) -> tuple[np.ndarray, np.ndarray]:
    """CNOSSOS-EU rolling sound power of one vehicle of ``vehicle`` type (a name of the vehicles file or
    a ``CnossosVehicle``) at ``speed_kmh`` on ``track`` (a ``CnossosTrack`` or a reference mapping).

    Returns the nominal 1/3-octave centres (50 Hz ... 10 kHz) and L_W,0 per vehicle (dB re 1 pW,
    source A at 0.5 m, no directivity); with ``vehicles_per_hour`` the sound power per metre of line
    L_W',eq,line of (2.3.2) instead (dB re 1 pW/m)."""
    comp = rolling_power_components(vehicle, track, speed_kmh, tables=tables)
    level = comp["L_W_total"]
    if vehicles_per_hour is not None:
        level = rc.line_power_per_metre(level, vehicles_per_hour, speed_kmh)
    return comp["f_centre"], level
