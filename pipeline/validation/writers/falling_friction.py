"""Validation report (issue 26): what a falling friction law, spin and traction (gamma_x) each change
in the squeal of the default case and the three contact positions -- occurrence, mode, L_F2, L_W --
against the later literature: docs/validation/67_falling_friction.md; and the default case in Kalker's loop
against the point-contact loop with spin and a falling law: docs/validation/67_falling_friction_kalker.md.

    OMP_NUM_THREADS=1 .venv/bin/python -m pipeline.validation.writers.falling_friction

A writer, run by `make validate`; what the fragments state as asserted is asserted by
tests/interaction/test_falling_validation.py on ``case_rows`` and ``kalker_runs`` here.

Each variant changes one thing of the case (its Coulomb curve, creepages and everything else kept):
the time loop (numba, point contact, 8 s at most with the early stop of the simulate stage), the
dominant force frequency's mode (fundamental or 2nd/3rd harmonic, 1 %), L_F2 over the final stretch,
L_W of the wheel under those forces (the radiate stage's model), and the screen's fastest pole.
The cases' contact and greens are built through Make.
"""
from __future__ import annotations

import numpy as np

from pipeline.validation.cached import cached
from pipeline.validation.make import ensure_case
from pipeline.validation.references.falling import falling_contact, falling_law
from pipeline.validation.writers import save_fragment
from pipeline.store import paths
from pipeline.stages.radiate import load_radiation_model, sound_power_of_forces
from pipeline.stages.stability import case_linear_model
from solvers.constants import SQUEAL_LEVEL_DB
from solvers.study import nearest_mode
import time

CASES = ("dy05", "dy10", "default")
LAWS = {"falling (mild: 0.35 -> 0.30, s_ref 1 m/s)": (0.35, 0.30, 1.0),
        "falling (moderate: 0.35 -> 0.25, s_ref 0.5 m/s)": (0.35, 0.25, 0.5)}
GAMMA_X = 0.003            # traction / braking creepage of a curving wheel (|gamma_x| of a few 1e-3)
WHEEL_RADIUS = 0.39        # m, the C20's rolling radius (geometry/wheels/c20.toml)


def variants(contact_angle: float):
    """(label, law or None, extra settings): the reference, each falling law, spin of the contact's
    own angle (|phi| = sin|delta| / r0, both signs), traction and braking."""
    phi = abs(np.sin(contact_angle)) / WHEEL_RADIUS
    out = [("reference (Coulomb, case settings)", None, {})]
    out += [(name, law, {}) for name, law in LAWS.items()]
    out += [(f"spin {s * phi:+.3f}/m", None, {"spin": s * phi}) for s in (1, -1)]
    out += [(f"gamma_x = {s * GAMMA_X:+.3f}", None, {"gamma_x": s * GAMMA_X}) for s in (1, -1)]
    return out


def _inputs(case: str) -> list:
    return [paths.case_dir(case) / "contact.npz", paths.case_dir(case) / "greens.npz",
            paths.wheel_dir("c20") / "modes.npz"]


def case_rows(case: str) -> list[dict]:
    """Per variant of the case (``variants``): the time loop's outcome, mode, L_F2, L_W and the screen's
    fastest pole; computed once per code and artifacts (``pipeline.validation.cached``: the writer and
    tests/interaction/test_falling_validation.py share it)."""
    ensure_case(case)
    return cached(f"falling_rows_{case}", lambda: _case_rows(case),
                  ("pipeline.validation.writers.falling_friction:_case_rows",), _inputs(case))


def _case_rows(case: str):
    from solvers.timeloop.interaction import WheelModes, contact_model, simulate  # lazy: brings in numba, rocket_fft, scipy
    from solvers.stability.screen import linearise, screen  # lazy: brings in numba

    c, lm, labels, f_open = case_linear_model(case)
    con = np.load(paths.case_dir(case) / "contact.npz")
    cm = contact_model(con, c["friction"]["mu"])
    wheel = WheelModes(lm.f_r, lm.modal_mass, lm.zeta, lm.phi)
    model = load_radiation_model(case)
    rows = []
    for label, law, extra in variants(float(con["contact_angle"])):
        cf = cm if law is None else falling_contact(cm, law, c["kinematics"]["speed"], lm.F3)
        kw = dict(dt=lm.dt, v=c["kinematics"]["speed"], gamma_y=c["kinematics"]["gamma_y"], preload=lm.F3, **extra)
        res = simulate(wheel, lm.rail_kernel, cf, duration=c["time"]["duration"], **kw)
        m = res.measures()
        f = m["f_dominant"]
        squeals = m["L_F2"] >= SQUEAL_LEVEL_DB
        j = nearest_mode(f, f_open, rel_tol=0.01, harmonics=(1, 2, 3)) if squeals and f >= 200 else None
        mode = ("-" if not squeals else "track" if f < 200 else str(labels[j]) if j is not None else f"{f:.0f} Hz")
        L_W = sound_power_of_forces(model, res.F_final, res.dt_final)["L_W"] if squeals else np.nan
        top = screen(linearise(wheel, lm.rail_kernel, cf, **kw))[0]
        fastest = "track" if top.mode < 0 else str(labels[top.mode])
        rows.append(dict(case=case, variant=label, squeals=squeals, mode=mode, L_F2=m["L_F2"], f=f, L_W=L_W,
                         stop=res.stop_reason, fastest=fastest, sigma=top.sigma))
    return rows


def write_variants() -> str:
    lines = []
    for case in CASES:
        for r in case_rows(case):
            lw = f"{r['L_W']:.1f}" if np.isfinite(r["L_W"]) else "-"
            lines.append(f"| {case} | {r['variant']} | {'yes' if r['squeals'] else 'no'} | {r['mode']} | "
                         f"{r['L_F2']:.1f} | {r['f']:.1f} | {lw} | {r['fastest']} ({r['sigma']:+.1f}/s) | {r['stop']} |")
    text = f"""## Falling friction, spin and traction: what each changes (issue 26)

Written by `pipeline/validation/writers/falling_friction.py` (`make validate`); asserted by
`tests/interaction/test_falling_validation.py`. Per contact position (cases dy05, dy10,
default, each at its own settings: mu = 0.35, gamma_y = -0.014, 50 km/h) one thing changed at a time: the
friction law (Polach's falling law mu_s ((1 - A) exp(-s / s_ref) + A), mild 0.35 -> 0.30 with s_ref = 1 m/s,
moderate 0.35 -> 0.25 with s_ref = 0.5 m/s; its global curve by TANG with the local law on the case's contact,
`solvers.contact.falling.tang_curve`), spin
of the contact's own angle (|phi| = sin|delta| / r0, r0 = {WHEEL_RADIUS} m, both signs; the point contact takes
it as equivalent creepages from Kalker's linear theory on the contact's grid, `solvers.contact.spin`), or a
longitudinal creepage gamma_x = +-{GAMMA_X} (traction or braking; the structures have no longitudinal
direction: gamma_x acts through the contact only, tilting the slip and sharing the friction limit). The time
loop (point contact, at most 8 s with the stage's early stop), the squeal's mode (dominant force frequency,
fundamental or 2nd/3rd harmonic within 1 %), L_F2 (dB re 1 N) over the final stretch, L_W (dB re 1e-12 W) of
the wheel under those forces (the radiate stage's model) and the stability screen's fastest pole. "Squeals":
L_F2 >= 10 dB.

| case | variant | squeals | mode | L_F2 (dB) | f dominant (Hz) | L_W (dB) | screen's fastest pole | stop |
|---|---|---|---|---|---|---|---|---|
""" + "\n".join(lines) + """

What the literature reports, and what the model shows:

* **Falling friction.** A negative slope of the creep curve is the classical squeal mechanism (Rudd, JSV 46,
  1976; Heckl and Abrahams, JSV 229, 2000); with it the squeal amplitude follows from the energy balance over
  the falling part of the curve (Meehan and Liu, JSV 413, 2018), and it combines with mode coupling (Meehan, JSV
  465, 2020). Here the slope at the operating slip (-0.04 and -0.13 s/m) acts as negative damping on the lateral
  motion: every position squeals, more axial modes grow (docs/validation, the screen with a falling law), and
  the level rises with the slope; with the moderate law the limit cycle is strongly nonlinear (its largest
  force peak can be a harmonic) and the mode it settles in may change.
* **Spin.** Zenzerovic, Kropp and Pieringer ("Influence of spin creepage and contact angle on curve squeal: a
  numerical approach", JSV, 2016) found spin to change the squeal amplitude, not its occurrence: asserted here
  (same occurrence as the reference at every position with either sign of a tread contact's spin).
* **Traction and braking.** A longitudinal creepage turns the slip direction away from the lateral: across the
  slip the regularized law is a positive, viscous-like stiffness F3 mu_RF / |w|, along it the curve's slope, so
  a part of the lateral motion is damped instead of driven (the screen's K matrix, `solvers/stability/screen.py`). Here
  gamma_x = +-0.003 beside gamma_y = -0.014 silences the default case and dy05 and weakens dy10's (3,0,a) by
  9 dB; both signs act alike, because the loop has no longitudinal structural direction (the wheel's
  circumferential and torsional motion and the rail's longitudinal receptance are not modelled: F1 only loads
  the contact's own compliance). The reference model lists longitudinal creepage and dynamics as future work
  (Zenzerovic's thesis, ch. 7); this result is the model's, not checked against a published one, and with the
  longitudinal dynamics the damping across the slip would be shared with the wheel's torsional motion.
"""
    return save_fragment("67_falling_friction.md", text)


def kalker_runs() -> dict:
    """The default case in Kalker's loop (transient TANG every step, the spin as its rigid slip field, the
    falling law local in every element) and in the point-contact loop (spin as equivalent creepages, the
    law's global curve): dict of the run labels, the measures per "label|loop" and the table rows; computed
    once per code and artifacts (shared with tests/interaction/test_falling_validation.py)."""
    ensure_case("default")
    return cached("falling_kalker", _kalker_runs, ("pipeline.validation.writers.falling_friction:_kalker_runs",),
                  _inputs("default"))


def _kalker_runs() -> dict:
    from solvers.timeloop.interaction import WheelModes, contact_model, simulate  # lazy: brings in numba, rocket_fft, scipy

    case = "default"
    c, lm, labels, f_open = case_linear_model(case)
    cm = contact_model(np.load(paths.case_dir(case) / "contact.npz"), c["friction"]["mu"])
    wheel = WheelModes(lm.f_r, lm.modal_mass, lm.zeta, lm.phi)
    v = c["kinematics"]["speed"]
    mild = (0.35, 0.30, 1.0)
    spin = abs(np.sin(float(np.load(paths.case_dir(case) / "contact.npz")["contact_angle"]))) / WHEEL_RADIUS
    runs = (("reference (Coulomb)", cm, {}), (f"spin {spin:+.3f}/m", cm, {"spin": spin}),
            ("falling (mild)", falling_contact(cm, mild, v, lm.F3)._replace(law=falling_law(*mild)), {}))
    rows, out = [], {}
    for label, con, extra in runs:
        for tg in ("point", "kalker"):
            t0 = time.perf_counter()
            r = simulate(wheel, lm.rail_kernel, con, dt=lm.dt, v=v, gamma_y=c["kinematics"]["gamma_y"], preload=lm.F3,
                         duration=c["time"]["duration"], tangential=tg, store_every=10, **extra)
            m = r.measures()
            out[f"{label}|{tg}"] = m
            rows.append(f"| {label} | {tg} | {m['L_F2']:.2f} | {m['f_dominant']:.1f} | {r.stop_reason} after "
                        f"{r.n_steps * lm.dt:.2f} s | {time.perf_counter() - t0:.0f} s |")
    return {"labels": [r[0] for r in runs], "measures": out, "rows": rows}


def write_kalker() -> str:
    rows = kalker_runs()["rows"]
    text = """## Falling friction and spin in Kalker's loop (issue 26)

Written by `pipeline/validation/writers/falling_friction.py` (`make validate`); asserted by
`tests/interaction/test_falling_validation.py`. The default case in the time loop with Kalker's transient TANG every step (the reference model's
contact: the spin as its rigid slip field phi (-y, x) v, the falling law as the local coefficient of every
element at its own slip speed, peer `tang.falling`) against the regularized point contact (spin as
equivalent creepages, the law's global curve with its tail), each at most 8 s with the stage's early stop.
Asserted for Coulomb friction and spin: the same dominant frequency (1 %), L_F2 within 3 dB, and the change
from the Coulomb reference of the same sign in both loops; with the falling law: both loops squeal. With the
falling law the largest peak of the force spectrum may sit at another mode in the two loops (see the
table): in Kalker's loop the law acts element by element at the local slip speeds, which in transient
rolling vary over the patch and along the cycle, while the point loop applies the global curve's slope at
the global slip. The point loop's linear growth rates are checked by the screen (above); which mode a local
falling law selects in the nonlinear limit cycle is not resolved here (Kalker's loop with a law runs TANG's
Python step, minutes per case). (Wall times on the shared machine under load; Kalker's loop with a law runs
TANG's Python step.)

| variant | tangential contact | L_F2 (dB) | f dominant (Hz) | stop | wall |
|---|---|---|---|---|---|
""" + "\n".join(rows) + "\n"
    return save_fragment("67_falling_friction_kalker.md", text)


def write() -> None:
    write_variants()
    write_kalker()


if __name__ == "__main__":
    write()
