"""Simulate stage: the time-domain wheel/rail interaction of a case (SPEC 3.5,
4, 6) from its contact tables and Green's functions.

Artifact: build/cases/<case>/simulate.npz (force histories, measures) and
simulate.png (F2, F3 over the final stretch and the F2 spectrum).
"""
from __future__ import annotations

import logging
import time

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.progress import loop_time
from pipeline.store.atomic import save_figure
from pipeline.stages.greens import greens_inputs
from pipeline.config.case import loop_arguments, resolve_case

log = logging.getLogger("pipeline.simulate")


def simulate_config(case: str):
    """(case, contact config, greens config, this stage's config)."""
    from pipeline.stages.contact import contact_inputs  # lazy: brings in numba, rocket_fft, scipy

    c, _, _, ccfg = contact_inputs(case)
    gcfg = greens_inputs(case)[-1]
    # the receiver ([listener]) does not change the simulation
    return c, ccfg, gcfg, {"contact": ccfg, "greens": gcfg, "case": {k: v for k, v in c.items() if k != "listener"}}


def case_arrays(case: str):
    """(case, this stage's config, contact arrays, greens arrays, WheelModes) of a case, each artifact
    checked against the case's configuration (the simulate and stability stages' inputs)."""
    from solvers.timeloop.interaction import WheelModes  # lazy: brings in numba, rocket_fft, scipy

    c, ccfg, gcfg, cfg = simulate_config(case)
    out = paths.case_dir(case)
    con, _ = artifacts.load_npz(out / "contact.npz", "contact", ccfg, make_target=f"contact CASE={case}")
    gr, _ = artifacts.load_npz(out / "greens.npz", "greens", gcfg, make_target=f"greens CASE={case}")
    return c, cfg, con, gr, WheelModes(gr["wheel_f"], gr["wheel_mass"], gr["wheel_zeta"], gr["wheel_phi"])


def run_simulate(case: str) -> dict:
    from solvers.timeloop.interaction import contact_model, simulate  # lazy: brings in numba, rocket_fft, scipy


    t0 = time.perf_counter()
    c, cfg, con, gr, wheel = case_arrays(case)
    rc = resolve_case(case)
    out = paths.case_dir(case)
    cm = contact_model(con, rc.friction)
    if c["contact"].get("points", 1) == 2:  # [contact] points = 2: the two-point loop (pipeline/stages/simulate_two_point.py)
        from pipeline.stages.simulate_two_point import simulate_two_point_case  # here: Make's DEPS of the module's other entry points stay without it

        return simulate_two_point_case(case, c, con, gr, cm, wheel, cfg, plot_forces, t0)
    res = simulate(wheel, gr["rail_kernel"], cm, **loop_arguments(rc, con).simulate(store_every=10))
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
    from postprocess.plots.simulate import forces_figure  # here: Make's DEPS of the module's other entry points stay without it

    save_figure(forces_figure(res, m, case), path, dpi=90)
