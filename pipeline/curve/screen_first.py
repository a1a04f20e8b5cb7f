"""The curve verdict screen first, in one process (the line study's path, issue 27).

``make curve`` (``stage.run_curve``) runs the contact and greens stages of every wheel, screens it and
runs the time loop for every wheel with lateral creepage.  Here, per wheel of the leading bogie:

1. the stability screen from arrays built in memory (``screen_context``): the contact stage's
   arrays (``stages.contact.build_contact``: the same NORM table, compliance and friction curve; not its
   measured interpolation error, which no solver reads), the
   wheel's modal data at the contact point (the greens stage's ``contact_shape`` and damping rule; the
   wheel kernel, which neither the screen nor the time loop uses, is not built) and the moving rail
   kernel from the rail's shared cache (``stages.greens.rail_greens``, built there when new).  No
   artifact and no figure is written for a wheel the screen finds stable; its screen numbers are the
   curve stage's, bit for bit (tests/verdict/test_screen_first.py);
2. only where the screen finds a growing wheel-mode pole: the time loop, as the simulate stage calls it
   (``time_loop_L_F2``: the same numbers, no files); where it squeals (L_F2 >= 10 dB, SPEC 6), the curve
   stage's own wheel verdict (``stage.wheel_verdict``: the contact, greens, simulate, radiate and listen
   stages), so a squealing wheel's numbers and files are ``make curve``'s.

The difference from ``make curve``: a wheel the screen calls stable is not run in the time loop (its
``L_F2`` is empty).  The time loop could still make such a wheel squeal (a finite disturbance the
linearisation does not see); how often that happens over the radius study is measured in
docs/validation (the line study's fragment).

Per process (a Dask worker runs many curves): the wheel's modes are loaded once per file state, the
rail's resolved cases and moving kernels come from ``pipeline.config.case`` (memoised) and the kernel cache.
"""
from __future__ import annotations

import contextlib
import logging
import os
import time
import importlib

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.config.case import ResolvedCase, loop_arguments, resolve_case, given
from geometry.wheel import tread_radius
from pipeline.config.rail_contact import rail_point
from pipeline.curve.rail_point import rail_arrays
from pipeline.study.context import CaseContext
from solvers.stability.mitigation import growing_wheel_root
from pipeline.curve.what_ifs import CaseModels
from pipeline.curve.stage import operating_row, COLUMNS, solve, wheel_verdict
from solvers.study import squeals
from pipeline.curve.cases import wheel_case, write_case
from pipeline.curve.verdict_report import cell

log = logging.getLogger("pipeline.curve")

_MODES: dict = {}
#: wall time per part of the screen-first verdict in this process (s), for the benchmark's breakdown
TIMES: dict = {}


def _tick(part: str, t0: float) -> float:
    t = time.perf_counter()
    TIMES[part] = TIMES.get(part, 0.0) + (t - t0)
    return t


def wheel_modes(wheel: str, pw: dict) -> dict:
    """The wheel's modes.npz (checked against the wheel file), loaded once per process and file state."""
    path = paths.wheel_dir(wheel) / "modes.npz"
    st = os.stat(path)
    key = (str(path), st.st_mtime_ns, st.st_size)
    if key not in _MODES:
        modes, _ = artifacts.load_npz(path, "wheel-modes", pw, make_target=f"modes WHEEL={wheel}")
        _MODES.clear()
        _MODES[key] = dict(modes)
    return _MODES[key]


def wheel_at_contact(pw: dict, modes: dict, y_w: float) -> dict:
    """f, modal mass, damping and the shapes at the tread point y^W: ``stages.greens.wheel_greens``'s
    modal data without its kernel (the same calls, the same numbers)."""
    from solvers.wheel.receptance import contact_point, contact_shape, modal_damping  # lazy: brings in scipy

    surface = np.unique(np.concatenate([modes["boundary_tread"], modes["boundary_flange"]]))
    where = contact_point(modes["points"], surface, y_w, pw["axle"]["rolling_circle_z"],
                          r_of_y=lambda y: tread_radius(pw, y), cells=modes["cells"])
    zeta = modal_damping(modes["n"], modes["m"], modes["cls"], modes["kind"], modes["zeta_suspension"])
    return {"wheel_f": modes["f_hz"], "wheel_mass": modes["modal_mass"], "wheel_zeta": zeta,
            "wheel_phi": contact_shape(modes["shapes"], where)}


def screen_context(case: "str | ResolvedCase"):
    """The ``pipeline.study.context.CaseContext`` of a case (a name or a ResolvedCase) from arrays
    computed here (module notes)."""
    from pipeline.stages.contact import build_contact  # lazy: brings in numba, rocket_fft, scipy

    t0 = time.perf_counter()
    rc = resolve_case(case)
    c, pw, pr, geo = rc.case, rc.wheel, rc.rail, rc.geometry
    if c["contact"].get("points", 1) != 1 or c["contact"].get("angle", "none") != "none":
        raise ValueError(f"{rc.name}: the screen-first verdict takes one contact point in the track's frame "
                         "(a curve wheel's case: [contact] points = 1, angle = 'none')")
    con = build_contact(c, pw, geo, frictions=[rc.friction], diagnostics=False)   # the NORM table's error check: the stage's job
    t0 = _tick("contact", t0)
    modes = wheel_modes(c["wheel"], pw)
    loop = loop_arguments(rc, con)
    dt, v = loop.dt, loop.v
    arrays = wheel_at_contact(pw, modes, geo.contact.y_wheel)
    t0 = _tick("wheel", t0)
    yr = rail_point(c["rail"], pr, geo.contact.y_rail, rc.name)
    rail = rail_arrays(pr, yr, v, dt)
    arrays["rail_kernel"] = rail["rail_kernel"]
    _tick("rail kernel", t0)
    wheel = {"f": arrays["wheel_f"], "mass": arrays["wheel_mass"], "zeta": arrays["wheel_zeta"],
             "phi": arrays["wheel_phi"], "n": modes["n"], "m": modes["m"], "cls": modes["cls"].astype(str),
             "kind": modes["kind"].astype(str)}
    return CaseContext(case=rc.name, inputs="", dy_wr=c["contact"]["dy_wr"], loop=loop, mu=rc.friction.mu,
                       friction=rc.friction, contact=con, wheel=wheel, rail_kernel=arrays["rail_kernel"],
                       radiation=None, radiation_note="not requested")


def screen(case: "str | ResolvedCase", gamma_y: float):
    """(fastest growing wheel-mode pole or None, its mode label, the CaseContext or None) of a curve
    wheel, as ``stage.screen_wheel`` finds it, from ``screen_context``."""
    if gamma_y == 0.0:
        return None, "", None
    ctx = screen_context(case)
    t0 = time.perf_counter()
    models = CaseModels.of_context(ctx)
    r = growing_wheel_root(models.roots(ctx.mu))
    _tick("screen", t0)
    return r, (ctx.label(r.mode) if r is not None else ""), ctx


def time_loop_L_F2(case: "str | ResolvedCase", ctx) -> float:
    """L_F2 (dB re 1 N) of the simulate stage's time loop of the case, from the screen's arrays: the
    same call as ``stages.simulate.run_simulate`` (so the same number), without its files and figure."""
    from solvers.timeloop.interaction import WheelModes, contact_model, simulate  # lazy: brings in numba, rocket_fft, scipy

    w = ctx.wheel
    res = simulate(WheelModes(w["f"], w["mass"], w["zeta"], w["phi"]), ctx.rail_kernel,
                   contact_model(ctx.contact, ctx.friction),
                   **loop_arguments(resolve_case(case), ctx.contact).simulate(store_every=10))
    return float(res.measures()["L_F2"])


def quiet_row(p, root, label: str) -> dict:
    """A verdict.csv row of a wheel the time loop is not run for (``stage.COLUMNS``)."""
    row = operating_row(p)
    if root is not None:
        row |= {"screen_sigma": float(root.sigma), "screen_f": float(root.f_hz), "screen_mode": label}
    return row


# the stages' figure functions a squealing wheel's verdict draws (module, attribute): ``without_figures``
STAGE_FIGURES = (("pipeline.stages.contact", "plot_rf"), ("pipeline.stages.greens", "plot_kernels"), ("pipeline.stages.simulate", "plot_forces"),
                 ("pipeline.stages.radiate", "plot_radiation"), ("pipeline.stages.listen", "plot_listening"),
                 ("pipeline.stages.passby", "run_passby"))


@contextlib.contextmanager
def without_figures(skip: bool = True):
    """While it lasts (``skip``), the stages write their artifacts but draw no figure and the listen stage
    makes no pass-by (together about two thirds of a squealing wheel's stages' time; `python -m pipeline
    listen --case <curve>/<wheel>` makes them): those functions replaced by no-ops, restored after."""
    saved = []
    try:
        if skip:
            for mod, attr in STAGE_FIGURES:
                m = importlib.import_module(mod)
                saved.append((m, attr, getattr(m, attr)))
                setattr(m, attr, lambda *a, **k: None)
        yield
    finally:
        for m, attr, f in saved:
            setattr(m, attr, f)


def run_screen_first(curve, *, what_ifs: bool = False, write: bool = True, figures: bool = True) -> dict:
    """The verdict of ``curve`` (a Curve, a path to a curve file or a shipped name) screen first
    (module notes): {'rows': one per wheel (``stage.COLUMNS``, plus ``time_loop``: whether it ran, and
    ``context``: its screen's CaseContext or None, for the line's onset: ``pipeline.study.line_risk``),
    'info': the Curve}; ``write``: build/curves/<curve>/verdict.csv; ``figures``: the stages of a
    squealing wheel draw their figures (``without_figures`` otherwise)."""
    t0 = time.perf_counter()
    sol = solve(curve)
    info, points = sol.curve, sol.wheels
    cases = [wheel_case(info, p) for p in points]      # every operating point checked before any work
    for rc in cases:
        write_case(rc)
    t0 = _tick("curving", t0)
    rows = []
    with given(cases):
        for p, rc in zip(points, cases):
            root, label, ctx = screen(rc, p.gamma_y)
            if root is None:
                rows.append(quiet_row(p, root, label) | {"time_loop": False, "context": ctx})
                continue
            t0 = time.perf_counter()
            L_F2 = time_loop_L_F2(rc, ctx)
            t0 = _tick("time loop (unstable wheels)", t0)
            if not squeals(L_F2):                 # the time loop overrules the screen: quiet, no stage to run
                rows.append(quiet_row(p, root, label) | {"L_F2": L_F2, "time_loop": True, "context": ctx})
                continue
            with without_figures(not figures):
                rows.append(wheel_verdict(info, p, what_ifs=what_ifs) | {"time_loop": True, "context": ctx})
            _tick("stages of squealing wheels", t0)
    if write:
        artifacts.save_csv(paths.curve_dir(info.name) / "verdict.csv", COLUMNS,
                           ([cell(r[k]) for k in COLUMNS] for r in rows))
    return {"rows": rows, "info": info}
