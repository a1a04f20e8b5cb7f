"""One resolved case: the only place a case is resolved and its contact point derived.

``resolve_case(name)`` turns a case name -- a file ``pipeline/cases/<name>.toml`` or a curve's
wheel ``<curve>/<wheel>`` (``pipeline.store.paths.case_file``) -- into a ``ResolvedCase``: the validated
case, wheel and rail parameters, the running surfaces and their rigid contact point
(``pipeline.config.case_profiles.ContactGeometry``), the friction (``pipeline.config.nouns.FrictionLaw``,
resolved here once) and what the contact depends on.  Every stage reads it instead of loading the
files again; it is memoised per process and per state of the files it read (case, wheel, rail,
profiles: a changed file is read again), so a stage that asks for the same case several times
(simulate: its contact and greens configurations; stability: the same and its own) derives the
contact point once.

A curve's wheel is built in memory (``resolve_built``: from the curve's operating point, with the
curve's friction, no file read); the curve stage hands its wheels to the stages it runs with
``given(cases)``: while it lasts, ``resolve_case`` of such a name is that object (the case file the
curve stage writes is a record for ``make CASE=<curve>/<wheel>``, not read back).

``loop_arguments(rc, contact)`` is the one translation of a case into the time loop's and the
linearisation's arguments (``solvers.timeloop.interaction.simulate``, ``solvers.stability.screen.linearise``,
the two-point loop and screen, the studies' ``CaseContext``).
"""
from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass, field
from pathlib import Path

from pipeline.store import paths
from pipeline.config.loader import ConfigError


from pipeline.config.nouns import FrictionLaw
from pipeline.caches.friction_curves import case_friction
from pipeline.config.case_profiles import profile_file, case_contact, contact_parts
from pipeline.config.check import time_step_problem


@dataclass(frozen=True)
class ResolvedCase:
    """A case ready for every stage (treat its dicts as read-only: they are shared).

    name: the case name; case: the validated case file (``pipeline.config.input_schemas.CASE``); wheel, rail:
    the validated wheel and rail parameters; geometry: the ContactGeometry (profiles in the track
    frame, the rigid contact point); friction: ``FrictionLaw``; config: what the contact point and
    contact depend on (the case's contact, kinematics, loading and time tables, the wheel's tyre,
    flange and material, the rail parameters, the running surfaces); files: the files read (with
    their state); source: the file an input error names (the case file, or a curve wheel's curve
    file)."""

    name: str
    case: dict
    wheel: dict
    rail: dict
    geometry: object
    friction: FrictionLaw
    config: dict
    files: tuple = field(default=(), repr=False)
    source: str = ""

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


def resolve_friction(c: dict, name: str | None = None) -> FrictionLaw:
    """The friction of a validated case (``pipeline.caches.friction_curves.case_friction``: its law and
    parameters, or preset; a one-line ConfigError naming the case file when they do not go
    together)."""
    return case_friction(c, name)


def _resolved(name: str, c: dict, pw: dict, pr: dict, geo, friction: FrictionLaw, case_files: list,
              source: str) -> ResolvedCase:
    """The ResolvedCase of a validated case dict and its wheel, rail and contact geometry (the time
    step checked as the greens stage would)."""
    problem = time_step_problem(c, c["rail"])
    if problem:
        raise ConfigError(source, [("time.dt", c["time"]["dt"], problem)])
    used = [profile_file(geo.config[k]) for k in ("wheel_name", "rail_name") if geo.config.get(k)]
    files = _stamp([*case_files, paths.wheel_file(c["wheel"]), paths.rail_file(c["rail"]), *used])
    case_cfg = {k: c[k] for k in ("contact", "kinematics", "loading", "time")}
    case_cfg["kinematics"] = {k: v for k, v in c["kinematics"].items() if k != "spin"}   # issue 26: not a contact input
    config = {"case": case_cfg,
              "wheel": {k: pw[k] for k in ("tyre", "flange", "material")}, "rail": pr,
              "running_surfaces": geo.config}
    return ResolvedCase(name, c, pw, pr, geo, friction, config, files, source)


def resolve_case(case: "str | ResolvedCase") -> ResolvedCase:
    """The ResolvedCase of ``case`` (a name; a ResolvedCase is returned as it is).  A case given to
    the stages in memory (``given``) is that object; otherwise memoised: the files are read and the
    contact point derived once per process unless a file it read has changed since.  A missing case
    file, a malformed name, bad parameters or a contact the profiles cannot make are a one-line
    ConfigError."""
    if isinstance(case, ResolvedCase):
        return case
    name = case
    if name in _GIVEN:
        return _GIVEN[name]
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

    c, pw, pr, geo = case_contact(name)
    rc = _resolved(name, c, pw, pr, geo, resolve_friction(c, name), [path], str(path))
    RESOLVED[name] = RESOLVED.get(name, 0) + 1
    _MEMO[key] = rc
    return rc


def resolve_built(name: str, c: dict, friction: FrictionLaw, source: str) -> ResolvedCase:
    """The ResolvedCase of a case built in memory (a curve's wheel: ``pipeline.curve.cases``): ``c``
    the validated case dict, ``friction`` already resolved (the curve's), ``source`` the file its
    input errors name.  Nothing is read but the wheel, rail and profile files."""
    pw, pr, geo = contact_parts(name, c, source)
    return _resolved(name, c, pw, pr, geo, friction, [], source)


#: cases handed to the stages in memory (``given``), by name
_GIVEN: dict = {}


@contextlib.contextmanager
def given(cases):
    """While it lasts, ``resolve_case(rc.name)`` is ``rc`` for each of ``cases`` (ResolvedCase): the
    curve stage runs the stages of its wheels on the cases it built, not on their written files."""
    saved = {rc.name: _GIVEN.get(rc.name) for rc in cases}
    _GIVEN.update({rc.name: rc for rc in cases})
    try:
        yield
    finally:
        for n, old in saved.items():
            if old is None:
                _GIVEN.pop(n, None)
            else:
                _GIVEN[n] = old


@dataclass(frozen=True)
class LoopArguments:
    """What the time loop and the linearisation take from a case (SI): the time step dt (s), speed v
    (m/s), creepages gamma_y, gamma_x (-), spin (1/m), the static normal force preload (N: the contact
    stage's, resolved in the contact plane, when the contact arrays are given; else the case's),
    the case's vertical preload_vertical (N: the two-point loop splits it between its patches),
    duration (s), the tangential and normal contact models."""
    dt: float
    v: float
    gamma_y: float
    gamma_x: float
    spin: float
    preload: float
    preload_vertical: float
    duration: float
    tangential: str
    normal: str

    def simulate(self, **extra) -> dict:
        """``solvers.timeloop.interaction.simulate``'s keyword arguments (``extra`` added or replacing)."""
        return dict(dt=self.dt, v=self.v, gamma_y=self.gamma_y, gamma_x=self.gamma_x, spin=self.spin,
                    preload=self.preload, duration=self.duration, tangential=self.tangential,
                    normal=self.normal) | extra

    def linearise(self, **extra) -> dict:
        """``solvers.stability.screen.linearise``'s keyword arguments."""
        return dict(dt=self.dt, v=self.v, gamma_y=self.gamma_y, gamma_x=self.gamma_x, spin=self.spin,
                    preload=self.preload) | extra

    def two_point(self, **extra) -> dict:
        """``solvers.timeloop.two_point_driver.simulate_two``'s (and ``linearise_two``'s, without
        ``duration``) keyword arguments: the vertical preload, no spin (the two-point loop has none)."""
        return dict(dt=self.dt, v=self.v, gamma_y=self.gamma_y, gamma_x=self.gamma_x,
                    preload=self.preload_vertical, duration=self.duration) | extra


def loop_arguments(case: "str | ResolvedCase", contact=None) -> LoopArguments:
    """The one translation of a case into the time loop's arguments (``LoopArguments``); ``contact``:
    the case's contact arrays (contact.npz or ``build_contact``'s), whose ``preload_normal`` is the
    static normal force when it holds one."""
    c = resolve_case(case).case
    k = c["kinematics"]
    preload = c["loading"]["preload"]
    if contact is not None:
        keys = contact.files if hasattr(contact, "files") else contact
        if "preload_normal" in keys:
            preload = float(contact["preload_normal"])
    return LoopArguments(dt=c["time"]["dt"], v=k["speed"], gamma_y=k["gamma_y"], gamma_x=k["gamma_x"],
                         spin=k.get("spin", 0.0), preload=preload, preload_vertical=c["loading"]["preload"],
                         duration=c["time"]["duration"], tangential=c["contact"]["model"],
                         normal=c["contact"]["normal"])


def clear() -> None:
    """Forget every resolved case (tests that change the environment's folders)."""
    _MEMO.clear()
