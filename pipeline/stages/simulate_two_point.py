"""The simulate stage's part for ``[contact] points = 2`` (issue 26): the two-point time loop
(``solvers.timeloop.two_point_driver``) from the contact stage's ``b_*`` tables and the greens
stage's structures at both points.

Second point's creepages (rigid wheelset, no spin: ``solvers.timeloop`` has none yet):
longitudinal from the rolling radii, gamma_x,b = (1 + gamma_x) r_b / r_a - 1 (the wheel turns at
the rate that gives gamma_x at radius r_a); lateral, the same horizontal slip on the patch's
tilted tangent, gamma_y,b = gamma_y cos(delta_b) / cos(delta_a) (1 for angle "none").
Records: simulate.npz keeps the first point's histories under the one-point names (what radiate
and listen read: the first patch's forces), the second's as ``b_*``; ``L_F2`` and ``f_dominant``
are those of the summed tangential-lateral forces of both patches (each in its contact plane).
"""
from __future__ import annotations

import math
import logging
import time

import numpy as np
from pipeline.config.case import loop_arguments, resolve_case
from pipeline.store import artifacts, paths
from pipeline.progress import loop_time


def second_creepages(c: dict, con) -> tuple[float, float]:
    """(gamma_x, gamma_y) of the second point (module notes)."""
    gx, gy = c["kinematics"]["gamma_x"], c["kinematics"]["gamma_y"]
    r_a = 1.0 / (2.0 * float(con["curvature_A"]))
    r_b = float(con["b_rolling_radius"])
    if c["contact"].get("angle", "none") == "none":
        ca = cb = 1.0
    else:
        ca, cb = math.cos(float(con["contact_angle"])), math.cos(float(con["b_contact_angle"]))
    return (1.0 + gx) * r_b / r_a - 1.0, gy * cb / ca


def second_point(c: dict, con, gr, friction):
    """(SecondPoint, rail blocks) of a two-point case from its contact and greens arrays (``friction``:
    the case's resolved FrictionLaw)."""
    from solvers.timeloop.two_point_driver import SecondPoint  # lazy: brings in numba, rocket_fft, scipy

    from pipeline.stages.second_point import second_contact_model  # lazy: brings in scipy

    gx_b, gy_b = second_creepages(c, con)
    profiles = c["contact"].get("angle", "none") != "none"
    cos_a = math.cos(float(con["contact_angle"])) if profiles else 1.0
    cos_b = math.cos(float(con["b_contact_angle"])) if profiles else 1.0
    second = SecondPoint(second_contact_model(con, friction), np.asarray(gr["b_wheel_phi"], float),
                         float(con["b_separation"]), gamma_x=gx_b, gamma_y=gy_b, cos_a=cos_a, cos_b=cos_b)
    return second, tuple(gr[f"rail_kernel_{k}"] for k in ("aa", "ab", "ba", "bb"))


def run_two_point(rc, con, gr, cm, wheel, store_every: int = 10):
    """(TwoPointResult, simulate.npz arrays) of a two-point case (``rc``: its ResolvedCase)."""
    from solvers.timeloop.two_point_driver import simulate_two  # lazy: brings in numba, rocket_fft, scipy


    second, blocks = second_point(rc.case, con, gr, rc.friction)
    gx_b, gy_b = second.gamma_x, second.gamma_y
    res = simulate_two(wheel, blocks, cm, second, **loop_arguments(rc, con).two_point(store_every=store_every))
    m = res.measures()
    a, b = res.a, res.b
    arrays = {"t": a.t, "F": a.F, "slip": a.slip, "state": a.state, "t_final": a.t_final, "F_final": a.F_final,
              "slip_final": a.slip_final, "state_final": a.state_final, "L_F2": np.float64(m["L_F2"]),
              "f_dominant": np.float64(m["f_dominant"]), "stop_reason": np.array(a.stop_reason),
              "n_steps": np.int64(a.n_steps), "wall_s": np.float64(res.wall),
              "b_F": b.F, "b_slip": b.slip, "b_state": b.state, "b_F_final": b.F_final, "b_slip_final": b.slip_final,
              "b_state_final": b.state_final, "N_static": res.N_static, "xi3_static_points": res.xi3_static,
              "L_F2_a": np.float64(m["L_F2_a"]), "L_F2_b": np.float64(m["L_F2_b"]),
              "b_gamma": np.array([gx_b, gy_b])}
    return res, arrays


def simulate_two_point_case(case: str, c: dict, con, gr, cm, wheel, cfg: dict, plot_forces,
                            t0: float | None = None) -> dict:
    """The simulate stage of a two-point case: run, plot the first point's forces (``plot_forces``: the
    simulate stage's, which a verdict without figures replaces), save, log (``t0``: the stage's start,
    ``time.perf_counter``)."""
    t0 = time.perf_counter() if t0 is None else t0


    res, arrays = run_two_point(resolve_case(case), con, gr, cm, wheel)
    if "contact_angle_wheel" in gr:
        arrays["contact_angle_wheel"] = np.float64(gr["contact_angle_wheel"])
    out = paths.case_dir(case)
    m = res.measures()
    plot_forces(res.a, dict(res.a.measures(), L_F2=m["L_F2"], f_dominant=m["f_dominant"]), out / "simulate.png", case)
    artifacts.save_npz(out / "simulate.npz", "simulate", cfg, **arrays)
    logging.getLogger("pipeline.simulate").info(
        "simulate %s (two points): %d steps (%s) %s; static normal forces %.1f / %.1f kN; L_F2 = %.1f dB "
        "(patch a %.1f, b %.1f dB), dominant %.1f Hz -> %s", case, res.a.n_steps, res.a.stop_reason,
        loop_time(time.perf_counter() - t0, res.wall, res.a.n_steps),
        1e-3 * res.N_static[0], 1e-3 * res.N_static[1], m["L_F2"], m["L_F2_a"], m["L_F2_b"], m["f_dominant"],
        out / "simulate.npz")
    return arrays


def two_point_roots(rc, con, gr, wheel, cm) -> list:
    """The two-point screen's wheel roots of a case (``rc``: its ResolvedCase; ``solvers.stability.two_point``)."""
    from solvers.stability.two_point import linearise_two, wheel_roots  # lazy: brings in numba


    second, blocks = second_point(rc.case, con, gr, rc.friction)
    args = loop_arguments(rc, con).two_point()
    args.pop("duration")
    lm = linearise_two(wheel, blocks, cm, second, **args)
    return wheel_roots(lm)
