"""Simulate stage: the time-domain wheel/rail interaction of a case (SPEC 3.5,
4, 6) from its contact tables and Green's functions.

Artifact: build/cases/<case>/simulate.npz (force histories, measures) and
simulate.png (F2, F3 over the final stretch and the F2 spectrum).
"""
from __future__ import annotations

import logging

import numpy as np

from . import artifacts, paths
from .atomic import save_figure

log = logging.getLogger("pipeline.simulate")


def simulate_config(case: str):
    """(case, contact config, greens config, this stage's config)."""
    from .contact_stage import contact_inputs
    from .greens_stage import greens_inputs

    c, _, _, ccfg = contact_inputs(case)
    gcfg = greens_inputs(case)[-1]
    # the receiver ([listener]) does not change the simulation
    return c, ccfg, gcfg, {"contact": ccfg, "greens": gcfg, "case": {k: v for k, v in c.items() if k != "listener"}}


def case_preload(c: dict, con) -> float:
    """The static normal force: the contact stage's (resolved in the contact plane, [contact] angle), or
    the case's preload in a contact artifact without it."""
    files = con.files if hasattr(con, "files") else con
    return float(con["preload_normal"]) if "preload_normal" in files else c["loading"]["preload"]


def case_arrays(case: str):
    """(case, this stage's config, contact arrays, greens arrays, WheelModes) of a case, each artifact
    checked against the case's configuration (the simulate and stability stages' inputs)."""
    from solvers.interaction import WheelModes

    c, ccfg, gcfg, cfg = simulate_config(case)
    out = paths.case_dir(case)
    con, _ = artifacts.load_npz(out / "contact.npz", "contact", ccfg, make_target=f"contact CASE={case}")
    gr, _ = artifacts.load_npz(out / "greens.npz", "greens", gcfg, make_target=f"greens CASE={case}")
    return c, cfg, con, gr, WheelModes(gr["wheel_f"], gr["wheel_mass"], gr["wheel_zeta"], gr["wheel_phi"])


def seconds(t: float) -> str:
    """A duration for the log, 2 significant digits below 10 s ('0.047 s', '1.3 s', '42 s')."""
    return f"{t:.2g} s" if t < 10 else f"{t:.0f} s"


def loop_time(t_stage: float, t_loop: float, n_steps: int) -> str:
    """'in <stage> (time loop <loop>, <us> us/step)': the stage's wall time (loading, the loop, its figure,
    writing) and the time loop's own (``InteractionResult.wall``; numba, microseconds a step)."""
    return (f"in {seconds(t_stage)} (time loop {seconds(t_loop)}, {1e6 * t_loop / max(n_steps, 1):.2g} us/step)")


def run_simulate(case: str) -> dict:
    import time

    from solvers.interaction import contact_model, simulate

    from .friction import case_friction

    t0 = time.perf_counter()
    c, cfg, con, gr, wheel = case_arrays(case)
    out = paths.case_dir(case)
    cm = contact_model(con, case_friction(c, case))
    if c["contact"].get("points", 1) == 2:  # [contact] points = 2: the two-point loop (pipeline/two_point_simulate.py)
        from .two_point_simulate import simulate_two_point_case

        return simulate_two_point_case(case, c, con, gr, cm, wheel, cfg, t0)
    res = simulate(wheel, gr["rail_kernel"], cm, dt=c["time"]["dt"], v=c["kinematics"]["speed"],
                   gamma_y=c["kinematics"]["gamma_y"], gamma_x=c["kinematics"]["gamma_x"],
                   spin=c["kinematics"].get("spin", 0.0),
                   preload=case_preload(c, con), duration=c["time"]["duration"],
                   tangential=c["contact"]["model"], normal=c["contact"]["normal"], store_every=10)
    m = res.measures()
    arrays = {"t": res.t, "F": res.F, "slip": res.slip, "state": res.state, "t_final": res.t_final,
              "F_final": res.F_final, "slip_final": res.slip_final, "state_final": res.state_final,
              "L_F2": np.float64(m["L_F2"]), "f_dominant": np.float64(m["f_dominant"]),
              "stop_reason": np.array(res.stop_reason), "n_steps": np.int64(res.n_steps),
              "wall_s": np.float64(res.wall)}
    if "contact_angle_wheel" in gr:  # forces in the contact plane ([contact] angle): its angle at the wheel
        arrays["contact_angle_wheel"] = np.float64(gr["contact_angle_wheel"])
    plot_forces(res, m, out / "simulate.png", case)
    artifacts.save_npz(out / "simulate.npz", "simulate", cfg, **arrays)
    log.info("simulate %s: %d steps (%.2f s rolling, %s) %s; L_F2 = %.1f dB, dominant %.1f Hz -> %s",
             case, res.n_steps, res.duration, res.stop_reason, loop_time(time.perf_counter() - t0, res.wall,
                                                                         res.n_steps),
             m["L_F2"], m["f_dominant"], out / "simulate.npz")
    return arrays


def plot_forces(res, m: dict, path, case: str) -> None:
    """``postprocess.plots.simulate.forces_figure``, saved atomically to ``path``."""
    from postprocess.plots.simulate import forces_figure

    save_figure(forces_figure(res, m, case), path, dpi=90)
