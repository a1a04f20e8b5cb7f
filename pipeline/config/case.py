"""One resolved case: the only place a case file is loaded and its contact point derived.

``resolve_case(name)`` turns a case name -- a file ``pipeline/cases/<name>.toml`` or a curve's
wheel ``<curve>/<wheel>`` (``pipeline.store.paths.case_file``) -- into a ``ResolvedCase``: the validated
case, wheel and rail parameters, the running surfaces and their rigid contact point
(``pipeline.config.case_profiles.ContactGeometry``), the friction and what the contact depends on.  Every
stage reads it instead of loading the files again; it is memoised per process and per state
of the files it read (case, wheel, rail, profiles: a changed file is read again), so a stage
that asks for the same case several times (simulate: its contact and greens configurations;
stability: the same and its own) derives the contact point once.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from pipeline.store import paths
from pipeline.config.loader import ConfigError


from pipeline.caches.friction_curves import Friction  # noqa: E402  (the resolved [friction]: law, params, preset, mu)


@dataclass(frozen=True)
class ResolvedCase:
    """A case ready for every stage (treat its dicts as read-only: they are shared).

    name: the case name; case: the validated case file (``pipeline.config.input_schemas.CASE``); wheel, rail:
    the validated wheel and rail parameters; geometry: the ContactGeometry (profiles in the track
    frame, the rigid contact point); friction: ``Friction``; config: what the contact point and
    contact depend on (the case's contact, kinematics, loading and time tables, the wheel's tyre,
    flange and material, the rail parameters, the running surfaces); files: the files read."""

    name: str
    case: dict
    wheel: dict
    rail: dict
    geometry: object
    friction: Friction
    config: dict
    files: tuple = field(default=(), repr=False)

    @property
    def contact(self):
        """The rigid contact point (``geometry.contact_point.RigidContact``)."""
        return self.geometry.contact

    @property
    def case_file(self) -> Path:
        return paths.case_file(self.name)


_MEMO: dict = {}
#: how many times each case was resolved from its files in this process (the memo's misses)
RESOLVED: dict = {}


def _stamp(files) -> tuple:
    out = []
    for f in files:
        try:
            s = os.stat(f)
            out.append((str(f), s.st_mtime_ns, s.st_size))
        except OSError:
            out.append((str(f), None, None))
    return tuple(out)


def resolve_friction(c: dict, name: str | None = None) -> Friction:
    """The friction of a validated case (``pipeline.caches.friction_curves.case_friction``: its law and
    parameters, or preset; a one-line ConfigError naming the case file when they do not go
    together)."""
    from pipeline.caches.friction_curves import case_friction

    return case_friction(c, name)


def resolve_case(name: str) -> ResolvedCase:
    """The ResolvedCase of ``name`` (memoised: the files are read and the contact point derived
    once per process unless a file it read has changed since).  A missing case file, a malformed
    name, bad parameters or a contact the profiles cannot make are a one-line ConfigError."""
    try:
        path = paths.case_file(name)
    except ValueError as e:
        raise ConfigError("command line", detail=f"--case {name}: {e}") from None
    key = (name, str(path), str(paths.wheels()), str(paths.rails()))
    hit = _MEMO.get(key)
    if hit is not None and hit.files == _stamp(f for f, _, _ in hit.files):
        return hit
    why = paths.missing_case(name)
    if why:
        raise ConfigError(str(path), detail=why)
    from pipeline.config.case_profiles import case_contact, profile_file

    c, pw, pr, geo = case_contact(name)
    from pipeline.config.check import time_step_problem              # a time step the greens stage would refuse: one line

    problem = time_step_problem(c, c["rail"])
    if problem:
        raise ConfigError(str(path), [("time.dt", c["time"]["dt"], problem)])
    RESOLVED[name] = RESOLVED.get(name, 0) + 1
    used = [profile_file(geo.config[k]) for k in ("wheel_name", "rail_name") if geo.config.get(k)]
    files = _stamp([path, paths.wheel_file(c["wheel"]), paths.rail_file(c["rail"]), *used])
    case_cfg = {k: c[k] for k in ("contact", "kinematics", "loading", "time")}
    case_cfg["kinematics"] = {k: v for k, v in c["kinematics"].items() if k != "spin"}   # issue 26: not a contact input
    config = {"case": case_cfg,
              "wheel": {k: pw[k] for k in ("tyre", "flange", "material")}, "rail": pr,
              "running_surfaces": geo.config}
    rc = ResolvedCase(name, c, pw, pr, geo, resolve_friction(c, name), config, files)
    _MEMO[key] = rc
    return rc


def clear() -> None:
    """Forget every resolved case (tests that change the environment's folders)."""
    _MEMO.clear()
