"""``make check`` (``python -m pipeline check``): everything a later stage would refuse, found
before any work, each as one line naming the file, the key, the value and what is allowed.

Checked: the wheel and rail files (schema and geometry), the case file (schema), its friction
(law, parameters or preset: ``pipeline.caches.friction_curves.resolve_friction``), the profiles it names (in
the case, the wheel or the rail file: present, readable, of the right kind), the rigid contact
of the profiles at its wheelset offset (flange contact is refused, as the contact stage does),
the rail model's head node for its contact point (as the greens stage does), the second contact
zone of a two-point case (``pipeline.stages.second_point.second_zone``) and its time step
(``time_step_problem``).  Notes (not errors): an over-radial wheelset (negative angle of attack),
an outer wheel's positive lateral creepage.
"""
from __future__ import annotations

import logging
import math
import json

import numpy as np

from pipeline.store import paths
from pipeline.config.loader import ConfigError, load, named_file
from pipeline.config.case_profiles import read_profile, contact_geometry
from pipeline.caches.friction_curves import case_friction
from pipeline.stages.rail import load_rail_params
from pipeline.config.input_schemas import CASE
from pipeline.stages.wheel import load_wheel
from solvers.greens.grid import RAIL_NT, WHEEL_BAND_LIMIT

log = logging.getLogger("pipeline.config.check")


def profile_problems(case: str, c: dict, pw: dict, pr: dict) -> None:
    """ConfigError naming the file and key of the first profile that cannot be used: missing,
    invalid, or of the wrong kind (a rail profile for the wheel)."""
    wheel_file, rail_file = paths.wheels() / f"{c['wheel']}.toml", paths.rail_file(c["rail"])
    sources = [("wheel", "contact.wheel_profile", c["contact"].get("wheel_profile"), paths.case_file(case)),
               ("rail", "contact.rail_profile", c["contact"].get("rail_profile"), paths.case_file(case)),
               ("wheel", "running_surface.profile", pw.get("running_surface", {}).get("profile"), wheel_file),
               ("rail", "running_surface.profile", pr.get("running_surface", {}).get("profile"), rail_file)]
    for kind, key, name, src in sources:
        if not name:
            continue
        try:
            prof, _ = read_profile(name)
        except ConfigError as e:
            raise ConfigError(str(src), [(key, name, f"not a usable profile: {e}")]) from None
        if prof.kind != kind:
            raise ConfigError(str(src), [(key, name, f"not a {kind} profile (its kind is {prof.kind!r})")])


def outer_wheel(c: dict) -> bool:
    """Whether the case is a curve wheel on the outer rail (the curve stage names it ``<curve>/a<k>o``,
    ``pipeline.curve.operating.WHEELS``); an ordinary case file is, like the reference's, an inner wheel."""
    cw = paths.curve_wheel(str(c.get("name", "")))
    return cw is not None and cw[1].endswith("o")


def over_radial_note(c: dict) -> str | None:
    """An explanation when the case's wheelset is over-radial (negative angle of attack), else None.
    gamma_y is in the wheel's contact frame, direction 2 toward that wheel's field side (SPEC 2;
    ``solvers/curving/summary.py``): the yaw psi gives gamma_y ~ -psi at the inner wheel and ~ +psi at the
    outer wheel, so over-radial is gamma_y > 0 at an inner wheel and gamma_y < 0 at an outer wheel."""
    gy = c["kinematics"]["gamma_y"]
    if outer_wheel(c):
        if gy >= 0:
            return None
        return (f"gamma_y = {gy:+.4g} < 0 at an outer wheel: an over-radial wheelset (negative angle of attack, e.g. "
                f"a trailing axle or a wheelset steered past radial); the reference model (Zenzerovic 2014, SPEC 6) "
                f"studies under-radial leading wheelsets: results are outside the reference's validation")
    if gy <= 0:
        return None
    return (f"gamma_y = {gy:+g} > 0: an over-radial wheelset (negative angle of attack, e.g. a trailing axle or a "
            f"wheelset steered past radial), so the lateral creep force on the rail points to the gauge side; the "
            f"reference model (Zenzerovic 2014, SPEC 6) studies under-radial leading wheelsets, gamma_y < 0. The "
            f"chain computes it like any creepage (the friction curves are even in the slip), but the coupling "
            f"of lateral and vertical wheel motion that drives squeal acts with the opposite sign: results are "
            f"outside the reference's validation")


def outer_wheel_note(c: dict) -> str | None:
    """A short note for the outer wheel of an under-radial wheelset (gamma_y > 0 in its frame), else None."""
    gy = c["kinematics"]["gamma_y"]
    if not outer_wheel(c) or gy <= 0:
        return None
    return (f"gamma_y = {gy:+.4g} > 0 at an outer wheel of an under-radial wheelset (the creep force on the rail "
            f"points to its gauge side): the mirror image of the reference's inner wheel (gamma_y < 0), outside "
            f"its validation")


def run_check(case: str, wheel: str | None, rail: str | None) -> list[str]:
    """Check the case (and ``wheel``, ``rail`` when given apart); return the lines to print.
    Raises ConfigError (one line) at the first problem."""
    from pipeline.config.rail_contact import rail_point  # here: Make's DEPS of the module's other entry points stay without it

    if wheel:
        named_file("command line", "--wheel", wheel, load_wheel)
    if rail:
        named_file("command line", "--rail", rail, load_rail_params)
    try:
        case_path = paths.case_file(case)
    except ValueError as e:
        raise ConfigError("command line", detail=f"--case {case}: {e}") from None
    why = paths.missing_case(case)
    if why:
        raise ConfigError(str(case_path), detail=why)
    c = load(case_path, CASE)
    friction = case_friction(c, case)
    pw, _ = named_file(case_path, "wheel", c["wheel"], load_wheel)
    pr, _ = named_file(case_path, "rail", c["rail"], load_rail_params)
    profile_problems(case, c, pw, pr)
    geo = contact_geometry(case, c, pw, pr)                 # the rigid contact search (flange contact refused)
    where = f"case '{case}', dy_WR = {1e3 * c['contact']['dy_wr']:+.1f} mm (y^W = {1e3 * geo.contact.y_wheel:+.2f} mm)"
    rail_point(c["rail"], pr, geo.contact.y_rail, where)
    if c["contact"].get("points", 1) == 2:                  # the second zone, as the contact stage asks for it
        from pipeline.stages.second_point import second_zone  # lazy: brings in scipy

        second_zone(case, c, geo)
    problem = time_step_problem(c, c["rail"])
    if problem:
        raise ConfigError(str(case_path), [("time.dt", c["time"]["dt"], problem)])
    lines = [f"wheel {c['wheel']}, rail {c['rail']} and case {case}: configuration OK (friction {friction.text}; "
             f"contact at y^W = {1e3 * geo.contact.y_wheel:+.2f} mm, y^R = {1e3 * geo.contact.y_rail:+.2f} mm)"]
    for note in (over_radial_note(c), outer_wheel_note(c)):
        if note:
            lines.append(f"note: {note}")
    return lines


DECAY_DB = 60.0             # solvers.greens.kropp.decayed: the rail kernel's decay by N_t dt / 2
FOLD_DB = 20 * math.log10(2.0)   # an undecayed kernel folds back about doubled at N_t dt / 2 (solvers.greens.kropp.decayed)


def decay_time(g0, dt: float, tail: float = 0.05) -> float | None:
    """The shortest span T = n dt of a fixed-point Green's function sampled at dt (lags, any
    component axes) whose last ``tail`` fraction lies DECAY_DB + FOLD_DB below its peak (the
    greens stage's decay check on a grid of N_t = 2 T / dt, with the fold-back allowance); None
    when the samples do not reach it."""
    a = np.abs(np.asarray(g0)).reshape(len(g0), -1).max(axis=1)
    peak = a.max()
    for n in range(16, len(a) + 1):
        m = max(1, int(round(tail * n)))
        if 20 * np.log10(max(a[n - m:n].max(), 1e-300) / peak) <= -(DECAY_DB + FOLD_DB):
            return n * dt
    return None


def rail_decay_time(rail: str) -> tuple[float, float] | None:
    """(decay time T (s), the time step it was measured at) of the rail's fixed-point Green's
    function, from the moving kernels of this rail already built (build/rails/<rail>/moving/; the
    longest over them), or None when there is none."""
    best = None
    for f in sorted((paths.rail_dir(rail) / "moving").glob("*.npz")):
        try:
            st = f.stat()
            key = (str(f), st.st_mtime_ns, st.st_size)
            if key not in _DECAY:                   # each kernel file measured once per process (a line
                with np.load(f) as d:               # study's worker resolves hundreds of cases)
                    cfg = json.loads(str(d["__provenance__"])).get("config", {})
                    g0, dt0 = np.asarray(d["rail_fixed_kernel"]), float(cfg["dt"])
                _DECAY[key] = (decay_time(g0, dt0), dt0)
            T, dt0 = _DECAY[key]
        except (OSError, KeyError, ValueError, TypeError):
            continue
        if T is not None and (best is None or T > best[0]):
            best = (T, dt0)
    return best


_DECAY: dict = {}   # rail_decay_time's measure of each moving-kernel file (path, mtime, size)


def time_step_problem(c: dict, rail: str) -> str | None:
    """What the greens stage would refuse about the case's time step, as the allowed range and
    why, or None.  (1) The wheel's Green's function is fitted to the receptance up to the band of
    the models, WHEEL_BAND_LIMIT = 6.5 kHz (solvers.greens.band_fit), which must lie below the Nyquist
    frequency 1 / (2 dt).  (2) The rail's Green's function on Kropp's grid (N_t = RAIL_NT steps)
    must have decayed by 60 dB at N_t dt / 2 (pipeline.caches.rail_kernel); how fast the rail's response
    decays is measured on a moving kernel of this rail already built (``rail_decay_time``); without
    one there is nothing to measure and the greens stage checks it."""
    dt = c["time"]["dt"]
    hi = 0.5 / WHEEL_BAND_LIMIT
    decay = rail_decay_time(rail)
    lo = 2.0 * decay[0] / RAIL_NT if decay else None
    allowed = (f"{lo:.3g} <= dt < {hi:.3g}" if lo else f"dt < {hi:.3g}")
    if dt >= hi:
        return (f"{allowed}: the wheel's Green's function is fitted up to {WHEEL_BAND_LIMIT / 1e3:g} kHz (the band "
                f"of the models), which must lie below the Nyquist frequency 1 / (2 dt) = {0.5 / dt / 1e3:.2f} kHz")
    if lo and dt < lo:
        return (f"{allowed}: the rail's Green's function (Kropp's grid of N_t = {RAIL_NT} steps) must decay by "
                f"{DECAY_DB:.0f} dB within N_t dt / 2 = {1e3 * RAIL_NT * dt / 2:.0f} ms, and the {rail} rail takes "
                f"{1e3 * decay[0]:.0f} ms (its moving kernel at dt = {1e6 * decay[1]:.0f} us)")
    return None
