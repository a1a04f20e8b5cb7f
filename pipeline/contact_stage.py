"""Contact stage: everything the time loop needs about the contact of a case
(SPEC 4), computed with Kalker's discretised half-space theory.

For the case's contact position (SPEC 2 table) it builds the undeformed gap
from the wheel tread and rail-head profiles on the grid dx = v dt, the NORM
table F3(xi3) with pressures (and its measured interpolation error), the
tangential compliance A_tau over the approach, and the regularized friction
curves mu_RF(s) for mu = 0.10 .. 0.60 (step 0.05) at the static preload.

Artifact: build/cases/<case>/contact.npz (keys in the README) and
contact_rf.png.
"""
from __future__ import annotations

import logging
import time

import numpy as np

from solvers.constants import THESIS_CONTACT_POSITIONS

from . import artifacts, paths
from .atomic import save_figure
from .config import load
from .schemas import CASE

log = logging.getLogger("pipeline.contact")

MU_VALUES = np.round(np.arange(0.10, 0.6001, 0.05), 2)
DY = 0.5e-3  # lateral element size (m)


def contact_position(dy_wr: float) -> tuple[float, float]:
    """(y^W on the tread, y^R on the rail head) in m of the wheelset lateral offset
    dy_WR (m), as printed in the thesis (SPEC 2, [4.1]; ``solvers.constants``).  The
    rail head profiles here are symmetric, so the sign convention of y^R does not
    change the gap.  The one place a case's contact point is read."""
    key = round(float(dy_wr), 3)
    if key not in THESIS_CONTACT_POSITIONS:
        raise ValueError(f"dy_WR = {dy_wr} m is not one of the thesis' positions {sorted(THESIS_CONTACT_POSITIONS)}")
    return THESIS_CONTACT_POSITIONS[key]


def contact_inputs(case: str) -> tuple[dict, dict, dict, dict]:
    """(case, wheel, rail, resolved config) of a case; validated."""
    from .rail_stage import load_rail_params
    from .wheel_stage import load_wheel

    c = load(paths.case_file(case), CASE)
    pw, _ = load_wheel(c["wheel"])
    pr, _ = load_rail_params(c["rail"])
    cfg = {"case": {k: c[k] for k in ("contact", "kinematics", "loading", "time")},
           "wheel": {k: pw[k] for k in ("tyre", "flange", "material")}, "rail": pr, "mu_values": MU_VALUES.tolist(),
           "dy": DY}
    return c, pw, pr, cfg


def profiles(pw: dict, pr: dict):
    from geometry.rail import head_profile
    from geometry.wheel import tread_profile

    prof = tread_profile(pw)["points"]
    top = prof[np.argmax(prof[:, 1]):]  # flange top -> field face: r single-valued in y
    ys, rs = top[:, 0], top[:, 1]

    def r_wheel(y):
        return np.interp(y, ys, rs, left=np.nan, right=np.nan)

    def z_rail(y):
        return head_profile(pr, y)

    return r_wheel, z_rail


def build_contact(c: dict, pw: dict, pr: dict, n_table: int = 41) -> dict:
    """The contact arrays of one case (pure computation, no I/O)."""
    from solvers.contact.compliance import compliance_table
    from solvers.contact.friction import rf_curve
    from solvers.contact.norm import approach_for_load, norm_table, table_midpoint_error
    from solvers.contact.surfaces import contact_gap, contact_grid, curvatures

    E, nu = pw["material"]["E"], pw["material"]["nu"]
    yw, yr = contact_position(c["contact"]["dy_wr"])
    v, dt, F_L = c["kinematics"]["speed"], c["time"]["dt"], c["loading"]["preload"]
    dx = v * dt  # SPEC 4.1: the contact moves one element per step
    r_wheel, z_rail = profiles(pw, pr)
    A, B = curvatures(r_wheel, z_rail, yw, yr)
    if B <= 0:
        raise ValueError(f"the profiles are not convex against each other at y^W = {yw}, y^R = {yr} "
                         f"(lateral gap curvature {B:.3g} 1/m)")
    # Hertz-like size estimate for the grid (equivalent radius, Johnson 4.2x)
    Estar = E / (2 * (1 - nu**2))
    Re = 0.5 / np.sqrt(A * B)
    c_eq = (3 * F_L * Re / (4 * Estar)) ** (1 / 3)
    a_est, b_est = c_eq * (B / A) ** (1 / 3), c_eq * (A / B) ** (1 / 3)
    x, y = contact_grid(a_est, b_est, dx, DY)
    gap = contact_gap(r_wheel, z_rail, yw, yr, x, y)
    xi_static, static = approach_for_load(F_L, gap, dx, DY, E, nu)
    if static.touches_edge:
        raise RuntimeError("the static contact reaches the edge of the potential contact area; enlarge the margin")
    xi_nodes = np.linspace(0.0, 2.0 * xi_static, n_table)
    table = norm_table(gap, xi_nodes, dx, DY, E, nu)
    err = table_midpoint_error(table, gap, dx, DY, E, nu)
    A1_nodes, A2_nodes = compliance_table(xi_nodes, table.p, dx, DY, E, nu)
    curves = [rf_curve(static.p, dx, DY, v, mu, E, nu) for mu in MU_VALUES]
    ns = max(len(k.s) for k in curves)

    def pad(arrs):
        return np.array([np.pad(a, (0, ns - len(a)), mode="edge") for a in arrs])

    return {
        "x": x, "y": y, "dx": np.float64(dx), "dy": np.float64(DY), "gap": gap,
        "y_wheel": np.float64(yw), "y_rail": np.float64(yr), "curvature_A": np.float64(A), "curvature_B": np.float64(B),
        "xi3_static": np.float64(xi_static), "p3_static": static.p,
        "xi3_nodes": xi_nodes, "F3_nodes": table.F3, "q_nodes": table.q, "pressure_nodes": table.p,
        "table_error_xi3": err["xi3"], "table_error_F3": err["force"], "table_error_p": err["pressure"],
        "A1_nodes": A1_nodes, "A2_nodes": A2_nodes,
        "mu_values": MU_VALUES, "rf_n": np.array([len(k.s) for k in curves]),
        "rf_s": pad([k.s for k in curves]), "rf_mu": pad([k.mu_rf for k in curves]),
        "rf_slope": pad([k.slope for k in curves]), "rf_gamma_sat": np.array([k.gamma_sat for k in curves]),
    }


def run_contact(case: str) -> dict:
    c, pw, pr, cfg = contact_inputs(case)
    t0 = time.perf_counter()
    arrays = build_contact(c, pw, pr)
    out = paths.case_dir(case)
    plot_rf(arrays, out / "contact_rf.png", f"{case}: dy_WR = {1e3 * c['contact']['dy_wr']:.0f} mm")
    artifacts.save_npz(out / "contact.npz", "contact", cfg, **arrays)
    err = np.nanmax(arrays["table_error_F3"][arrays["table_error_xi3"] > 0.5 * arrays["xi3_static"]])
    log.info("contact %s: grid %d x %d (dx = %.3g mm), static approach %.1f um, NORM table error %.2g %% "
             "near the working point, %d RF curves in %.1f s -> %s", case, len(arrays["x"]), len(arrays["y"]),
             1e3 * arrays["dx"], 1e6 * arrays["xi3_static"], 100 * err, len(MU_VALUES), time.perf_counter() - t0,
             out / "contact.npz")
    return arrays


def plot_rf(a: dict, path, title: str) -> None:
    """``postprocess.plots.contact.friction_curves_figure``, saved atomically to ``path``."""
    from postprocess.plots.contact import friction_curves_figure

    save_figure(friction_curves_figure(a, title), path, dpi=100)
