"""Running-surface profiles of a case and its contact point (the one
function every stage uses for the contact position: ``case_contact``).

Which profiles: the case's ``contact.wheel_profile`` / ``contact.rail_profile``
when given, else the wheel file's and the rail file's
``running_surface.profile`` (a file ``geometry/profiles/<name>.csv``), else
the parametric running surface of the wheel file (cone + flange) or the rail
file (head arcs).  The rail is turned by ``running_surface.inclination`` into
the track frame; the wheel's rolling circle lies at c + dy_WR over the rail
centre (c = ``contact.rolling_circle_y``; y^W and y^R both + toward the field
side, ``geometry.contact_point.wheel_shift``), and the contact point is the rigid
contact of the two profiles there (``geometry.contact_point``).

Command line (import a measured profile into the project's format)::

    python -m pipeline.config.case_profiles import measured.whl --kind wheel --name my_wheel [--mirror-y] [--flip-z]
        [--y0 MM] [--z0 MM] [--noise MM]
    python -m pipeline.config.case_profiles check <name>   # load it, print the smoothing and the extent
"""
from __future__ import annotations

import argparse
import hashlib
import os
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.config.loader import ConfigError, MissingInput, named_file, load
from geometry.profiles import ProfileError, profile_from_text, build_profile, format_profile, check_points
from geometry.standard_profiles import rail_head_points, wheel_tread_points
from geometry.contact_point import FlangeContact, TrackRail, rigid_contact, wheel_shift
from pipeline.stages.rail import load_rail_params
from pipeline.stages.wheel import load_wheel
from pipeline.config.input_schemas import CASE
from geometry.miniprof import parse_miniprof, parse_plain, to_convention

PROFILES = Path(os.environ.get("SQUEAL_PROFILE_DIR", paths.ROOT / "geometry" / "profiles"))


def profile_file(name: str) -> Path:
    return PROFILES / f"{name}.csv"


def read_profile(name: str):
    """The Profile geometry/profiles/<name>.csv (validated, smoothed) and the
    file's hash; a bad file is a ConfigError naming the file and line."""
    path = profile_file(name)
    if not path.exists():
        have = sorted(p.stem for p in PROFILES.glob("*.csv"))
        raise MissingInput(path, "profile", have, detail=f"no such profile {name!r}; available: {have}")
    text = path.read_text(encoding="utf-8", errors="replace")
    try:
        prof = profile_from_text(text, str(path), name)
    except ProfileError as e:
        raise ConfigError(str(path), detail=(f"line {e.line}: " if e.line else "") + e.reason) from None
    return prof, hashlib.sha256(text.encode()).hexdigest()[:16]


def case_profiles(c: dict, pw: dict, pr: dict, asked: dict | None = None):
    """(wheel Profile, rail Profile, description for the config hash).  ``asked``: {'wheel': (file,
    key), 'rail': (file, key)}: where ``c``'s ``contact.<kind>_profile`` comes from; a profile the wheel
    or rail file names is asked by that file's ``running_surface.profile``.  A missing profile file is
    an error naming the file and key that asked for it."""
    desc = {}
    asked = asked or {}

    def asker(kind, params):
        if c["contact"].get(f"{kind}_profile"):
            return asked.get(kind, ("the case", f"contact.{kind}_profile"))
        own = paths.wheel_file(params["name"]) if kind == "wheel" else paths.rail_file(params["name"])
        return own, "running_surface.profile"

    def surface(kind, name, params, points, source):
        """The named profile file (checked to be a ``kind`` profile), else the parametric one."""
        if name:
            where, key = asker(kind, params)
            prof, desc[f"{kind}_profile"] = named_file(where, key, name, read_profile)
            if prof.kind != kind:
                raise ConfigError(str(profile_file(name)), detail=f"kind is {prof.kind!r}, a {kind} profile is needed")
            return prof
        desc[f"{kind}_profile"] = "parametric"
        return build_profile(*points(params), kind, f"{params['name']} (parametric)", source)

    wname = c["contact"].get("wheel_profile") or pw.get("running_surface", {}).get("profile")
    rname = c["contact"].get("rail_profile") or pr.get("running_surface", {}).get("profile")
    wheel = surface("wheel", wname, pw, wheel_tread_points, "wheel file: cone + flange (geometry.wheel.tread_profile)")
    rail = surface("rail", rname, pr, rail_head_points, "rail file: head arcs (geometry.rail.crown_arcs)")
    desc.update(wheel_name=wname or "", rail_name=rname or "")
    return wheel, rail, desc


@dataclass
class ContactGeometry:
    """The case's running surfaces in the track frame and their contact point.

    r_wheel(y^W): rolling radius (m); z_rail(Y): rail height in the track
    frame (m); contact: ``geometry.contact_point.RigidContact``; config:
    what the contact depends on (profile hashes, c, inclination, offset)."""

    wheel: object
    rail: object
    rail_track: object
    r0: float
    contact: object
    config: dict

    def r_wheel(self, y):
        return self.r0 + self.wheel(y)

    def z_rail(self, Y):
        return self.rail_track(Y)


def contact_geometry(name: str, c: dict, pw: dict, pr: dict, source: str | None = None) -> ContactGeometry:
    """Profiles and rigid contact point of a loaded case; flange contact or
    profiles that do not meet are a one-line ConfigError naming the case
    (its file, or ``source``), its offset and why."""
    wheel, rail, desc = case_profiles(c, pw, pr, {k: (paths.case_file(name), f"contact.{k}_profile")
                                                  for k in ("wheel", "rail")})
    inc = pr.get("running_surface", {}).get("inclination", 0.0) or 0.0
    cc, dy = c["contact"]["rolling_circle_y"], c["contact"]["dy_wr"]
    track = TrackRail(rail, inc)
    try:
        rc = rigid_contact(wheel, track, wheel_shift(cc, dy))
    except FlangeContact as e:
        raise ConfigError(source or str(paths.case_file(name)), detail=(
            f"case '{name}', dy_WR = {1e3 * dy:+.1f} mm (wheel profile {wheel.name}, rail profile {rail.name}, "
            f"c = {1e3 * cc:.2f} mm): {e}; c (contact.rolling_circle_y) places the wheel on the rail and "
            f"depends on the wheel and the track")) from None
    cfg = dict(desc, inclination=float(inc), rolling_circle_y=float(cc), dy_wr=float(dy))
    return ContactGeometry(wheel, rail, track, pw["tyre"]["rolling_radius"], rc, cfg)


def contact_parts(name: str, c: dict, source: str | None = None):
    """(wheel params, rail params, ContactGeometry) of a validated case dict ``c`` (a case file's or
    one built in memory: ``source`` names it in errors)."""
    pw, _ = named_file(source or name, "wheel", c["wheel"], load_wheel)   # a missing file: named with the key
    pr, _ = named_file(source or name, "rail", c["rail"], load_rail_params)
    return pw, pr, contact_geometry(name, c, pw, pr, source)


def case_contact(name: str):
    """(case, wheel params, rail params, ContactGeometry) of a case file:
    the contact point every stage uses (contact, greens, radiate)."""
    path = paths.case_file(name)
    c = load(path, CASE)
    return (c, *contact_parts(name, c, str(path)))


def write_profile(name: str, meta: dict, y, z) -> Path:
    """Write geometry/profiles/<name>.csv atomically (y, z in m)."""
    path = profile_file(name)
    with artifacts.atomic_write(path) as tmp:
        Path(tmp).write_text(format_profile(meta, y, z), encoding="utf-8")
    return path


def import_profile(src: str, kind: str, name: str, mirror_y=False, flip_z=False, y0=0.0, z0=None,
                   noise=None) -> Path:
    """Convert a measured MiniProf .ban/.whl or plain (y, z) CSV file (mm)
    into geometry/profiles/<name>.csv; validated like every profile."""
    text = Path(src).read_text(encoding="utf-8", errors="replace")
    try:
        if Path(src).suffix.lower() in (".ban", ".whl"):
            header, y, z, lines = parse_miniprof(text, src)
            what = f"MiniProf export {Path(src).name} (ColumnDef {header.get('ColumnDef', 'X,Y')})"
        else:
            header, (y, z, lines) = {}, parse_plain(text, src)
            what = f"plain y,z file {Path(src).name}"
        y, z, lines = to_convention(y, z, lines, kind, src, mirror_y, flip_z, y0, z0)

        check_points(y, z, src, lines, "mm")
        build_profile(1e-3 * y, 1e-3 * z, kind, name, what, noise)  # smoothing must succeed too
    except ProfileError as e:
        raise ConfigError(src, detail=(f"line {e.line}: " if e.line else "") + e.reason) from None
    meta = {"kind": kind, "source": f"{what}, imported by pipeline.config.case_profiles", "noise_mm":
            "gcv" if noise is None else f"{noise:g}",
            "import": f"mirror_y={mirror_y} flip_z={flip_z} y0={y0:g} mm z0={'auto' if z0 is None else z0} mm"}
    meta.update({f"miniprof_{k}": v for k, v in header.items() if k in ("Date", "Time", "Side", "WheelID", "Rail",
                                                                        "Line", "Track", "Chainage", "Comment")})
    return write_profile(name, meta, 1e-3 * y, 1e-3 * z)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.config.case_profiles", description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    im = sub.add_parser("import", help="convert a measured profile into geometry/profiles/<name>.csv")
    im.add_argument("file")
    im.add_argument("--kind", choices=["wheel", "rail"], required=True)
    im.add_argument("--name", required=True)
    im.add_argument("--mirror-y", action="store_true", help="y -> -y (profile measured on the other side)")
    im.add_argument("--flip-z", action="store_true", help="z -> -z (z measured downward)")
    im.add_argument("--y0", type=float, default=0.0, help="file y of the rolling circle / rail centre (mm)")
    im.add_argument("--z0", type=float, default=None, help="file z of the datum (mm; default automatic)")
    im.add_argument("--noise", type=float, default=None, help="measurement noise (mm) for the smoothing "
                    "(default: generalized cross-validation)")
    ck = sub.add_parser("check", help="load a profile and describe it")
    ck.add_argument("name")
    args = ap.parse_args(argv)
    try:
        if args.cmd == "import":
            print(import_profile(args.file, args.kind, args.name, args.mirror_y, args.flip_z, args.y0, args.z0,
                                 args.noise))
        else:
            p, h = read_profile(args.name)
            print(f"{args.name}: {p.kind}, {1e3 * p.y[0]:+.2f} .. {1e3 * p.y[-1]:+.2f} mm, "
                  f"z {1e3 * np.nanmin(p.z):+.3f} .. {1e3 * np.nanmax(p.z):+.3f} mm; {p.smoothing}; "
                  f"source: {p.source}; hash {h}")
    except (ConfigError, OSError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
