"""The cases of the studies as run on a Dask worker: ``fn(context, params) -> row`` (a dict of
scalars) for the study runner.  The context (pipeline.study.context.CaseContext) arrives once
per worker process; what derives from it (the contact model of each mu) is cached per process,
and numba is warmed once per process before the first case is timed.

Every case simulates with solvers.timeloop.interaction.simulate from the steady rolling state plus a
lateral kick (SPEC 3.5; the simulation's default 0.01 N s unless the task sets one), at most
``duration`` s, stopping early at a limit cycle or after decay unless ``early_stop`` is false;
squeal measures over the final stretch (``final``, 0.5 s as SPEC 6 by default); sound power
(L_W, its dominant frequency) with the radiate stage's model for squealing cases only
(L_F2 >= the squeal level, SPEC 6).
"""
from __future__ import annotations

import math

import numpy as np

from solvers.timeloop.interaction import StopRule, WheelModes, contact_model, simulate
from solvers.study import harmonic_response, periodic_creepage, squeals

from pipeline.study.tasks import CreepageTask, DampingTask, MapTask, ModeTask, Simulation
from solvers.timeloop.inputs import curve_label
from pipeline.stages.radiate import sound_power_of_forces

_CONTACT: dict = {}
_WARM: set = set()
NAN = float("nan")
CASE_MODEL = object()      # _measures: the context's own radiation model


def _contact(ctx, mu):
    """The contact model of ``ctx`` with the curve of ``mu`` (a Coulomb coefficient or a law)."""
    key = (ctx.case, ctx.inputs, curve_label(mu))
    if key not in _CONTACT:
        _CONTACT[key] = contact_model(ctx.contact, mu)
    return _CONTACT[key]


def _warm(ctx, tangential: str) -> None:
    """Compile (or load from numba's cache) the time loop once per process, outside the timing."""
    if tangential in _WARM:
        return
    cm = _contact(ctx, ctx.mu if ctx.friction is None else ctx.friction)
    simulate(_wheel(ctx), ctx.rail_kernel, cm, dt=ctx.dt, v=ctx.v, gamma_y=ctx.gamma_y, preload=ctx.preload,
             duration=20 * ctx.dt, tangential=tangential, normal=ctx.normal, stop=None, final=0)
    _WARM.add(tangential)


def _wheel(ctx, zeta=None, modes=None) -> WheelModes:
    w = ctx.wheel
    z = np.asarray(w["zeta"] if zeta is None else zeta, float)
    idx = np.arange(len(w["f"])) if modes is None else np.asarray(modes, int)
    return WheelModes(w["f"][idx], w["mass"][idx], z[idx], w["phi"][idx])


def _run(ctx, wheel, mu: float, gamma_y: float, sim: Simulation, *, tangential=None, kick=None):
    cm = _contact(ctx, mu)
    tangential = tangential or ctx.tangential
    _warm(ctx, tangential)
    return simulate(wheel, ctx.rail_kernel, cm, dt=ctx.dt, v=ctx.v, gamma_y=gamma_y, gamma_x=ctx.gamma_x,
                    preload=ctx.preload, duration=sim.duration, tangential=tangential, normal=ctx.normal,
                    stop=StopRule(window=sim.window) if sim.early_stop else None, kick=kick,
                    store_every=max(1, int(round(0.01 / ctx.dt))), final=sim.final)


def _measures(ctx, res, sim: Simulation, radiation=CASE_MODEL) -> dict:
    """Squeal measures; L_W and f_sound (radiate stage) when the case squeals and a model exists."""
    m = res.measures()
    row = {"L_F2": m["L_F2"], "f_dominant": m["f_dominant"], "F2_pp": m["F2_pp"], "F2_mean": m["F2_mean"],
           "contact_loss": m["contact_loss_share"], "stop_reason": res.stop_reason, "t_end": res.duration,
           "L_W": NAN, "f_sound": NAN}
    model = ctx.radiation if radiation is CASE_MODEL else radiation
    if model is not None and squeals(m["L_F2"], sim.level):
        s = sound_power_of_forces(model, res.F_final, res.dt_final or res.dt)
        row["L_W"], row["f_sound"] = float(s["L_W"]), float(s["f_sound"])
    if not math.isfinite(row["L_F2"]):
        row["L_F2"] = NAN
    return row


# ----------------------------------------------------------------------------------------------
# the cases of each study
# ----------------------------------------------------------------------------------------------

def map_case(ctx, t: MapTask) -> dict:
    """Creepage/friction map (SPEC 7): the full wheel model at (gamma_y, mu)."""
    row = {"case": ctx.case, "dy_wr": ctx.dy_wr, "gamma_y": t.gamma_y, "mu": t.mu}
    if t.screened is not None:          # the stability screen found every pole decaying: not simulated
        return row | {k: NAN for k in ("L_F2", "f_dominant", "F2_pp", "F2_mean", "contact_loss", "L_W", "f_sound")} | {
            "stop_reason": f"screened (sigma_max {t.screened:+.2f}/s)", "t_end": 0.0}
    return row | _measures(ctx, _run(ctx, _wheel(ctx), t.mu, t.gamma_y, t.sim), t.sim)


def damping_case(ctx, t: DampingTask) -> dict:
    """Wheel modal damping study (SPEC 7): the wheel of modes ``t.modes`` with damping
    ``t.zeta`` (full-length vector)."""
    res = _run(ctx, _wheel(ctx, t.zeta, t.modes), t.mu, t.gamma_y, t.sim)
    row = {"step": t.step, "model": t.model, "mode": t.mode, "zeta_mode": t.zeta_mode, "n_modes": len(t.modes)}
    return row | _measures(ctx, res, t.sim, radiation=None)


def mode_case(ctx, t: ModeTask) -> dict:
    """Contact-model validation in dynamic conditions (SPEC 7): every mode kept, damping
    ``t.zeta`` (one flexible mode lightly damped, the others at zeta = 1), rail kept; point
    contact or Kalker's transient model (``t.model``).  Sound power with the radiation model
    of the same damping (ctx.extra['radiation'][mode], when there)."""
    res = _run(ctx, _wheel(ctx, t.zeta), t.mu, t.gamma_y, t.sim, tangential=t.model, kick=t.kick)
    return _measures(ctx, res, t.sim, radiation=ctx.extra.get("radiation", {}).get(t.mode))


def creepage_case(ctx, t: CreepageTask) -> dict:
    """Stand-alone contact validation (SPEC 7): rigid, fixed wheel and rail, prescribed creepage
    gamma_y(t) = g0 + ga sin(2 pi f t); F2 over the last ``periods`` periods: mean, amplitude and
    phase at f, peak-to-peak."""
    n = int(round(t.duration / ctx.dt))
    gy = periodic_creepage(t.gamma_0, t.amplitude, t.f, ctx.dt, n)
    cm = _contact(ctx, t.mu)
    _warm(ctx, t.model)
    res = simulate(None, None, cm, dt=ctx.dt, v=ctx.v, gamma_y=gy, gamma_x=ctx.gamma_x, preload=ctx.preload,
                   duration=n * ctx.dt, tangential=t.model, normal=ctx.normal, stop=None, kick=0.0,
                   final=t.duration)
    h = harmonic_response(res.F_final[:, 1], res.dt_final or ctx.dt, t.f, t.periods)
    return {"F2_mean": h["mean"], "F2_amplitude": h["amplitude"], "F2_phase": h["phase"], "F2_pp": h["pp"]}


def contact_case(ctx, t: ModeTask | CreepageTask) -> dict:
    """Contact-model validation: a mode case or a prescribed-creepage case, with its identity."""
    if isinstance(t, ModeTask):
        row = {"case": ctx.case, "part": "mode", "model": t.model}
        return row | {"mode": t.mode, "label": t.label, "f_mode": t.f_mode} | mode_case(ctx, t)
    row = {"case": ctx.case, "part": "creepage", "model": t.model}
    return row | {"f": t.f} | creepage_case(ctx, t)
