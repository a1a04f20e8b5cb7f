"""Write the standard profiles and calibrate the worn C20/BV50 pair
(``make calibrate``; ``python -m pipeline.validation.calibrate_profiles``; ``--standard``: only step 1).

1. Standard (new) profiles, generated from their published definitions:
   ``s1002.csv`` (EN 13715), ``c20_new.csv`` (the C20 wheel file's cone +
   worn flange), ``bv50_new.csv`` and ``60e1_new.csv`` (EN 13674-1 head arcs
   of the rail files).
2. The worn pair: the wear parameters of ``geometry.calibration`` fitted so
   that the rigid contact of the worn C20 on the worn BV50 (1:30 inclined,
   c from the thesis table) reproduces the wheel contact points of thesis
   [4.1] in the project's convention (y^W = -printed: -5, +4, +32 mm;
   ``solvers.constants.THESIS_CONTACT_POINTS_FIELD``); written to ``c20_worn.csv`` and ``bv50_worn.csv`` with a header
   saying what they were calibrated to, by what, and the fitted numbers.
   The fit is seeded: a rerun writes the same files.
"""
from __future__ import annotations

import logging
import time

import numpy as np
from geometry.standard_profiles import TABLE_DEPTH, rail_head_points, s1002_points, wheel_tread_points, rail_head_curve
from pipeline.config.case_profiles import write_profile
from geometry.calibration import THESIS_POSITIONS, FitProblem, fit, rolling_circle_offset, split
from geometry.profiles import GRID_STEP, build_profile
from geometry.wear import worn_rail, worn_wheel
from pipeline.stages.rail import load_rail_params
from pipeline.stages.wheel import load_wheel

log = logging.getLogger("pipeline.calibrate")
WHEEL, RAIL = "c20", "bv50"
STEP = 2.5e-4  # m between tabulated points of the generated files


def _resample(y, z, step=STEP):
    """Tabulate a fine curve every ``step`` (ends kept)."""
    t = np.r_[np.arange(y[0], y[-1], step), y[-1]]
    if t[-1] - t[-2] < 0.2 * step:
        t = np.r_[t[:-2], y[-1]]
    return t, np.interp(t, y, z)


def _resample_rail(y, z, step=STEP, steep_deg=75.0):
    """A rail table: every ``step`` in y where the head is flatter than
    ``steep_deg`` (``_resample``, unchanged for a head cut there), every
    ``step`` of arc length down the steeper gauge and field faces."""
    dy, dz = np.diff(y), np.diff(z)
    steep = np.abs(dz) > np.tan(np.radians(steep_deg)) * dy
    if not steep.any():
        return _resample(y, z, step)
    u = np.r_[0.0, np.cumsum(np.where(steep, np.hypot(dy, dz), dy))]  # y on the flat part, arc length on the faces
    t = np.r_[np.arange(0.0, u[-1], step), u[-1]]
    if t[-1] - t[-2] < 0.2 * step:
        t = np.r_[t[:-2], u[-1]]
    return np.interp(t, u, y), np.interp(t, u, z)


def write_standard(pw: dict, rails: dict) -> list:
    """The new-profile files; returns their paths."""
    out = [write_profile("s1002", {"kind": "wheel", "source": "EN 13715 (UIC 510-2) S1002, generated from its "
                                   "piecewise definition (sections A-G; geometry/standard_profiles.s1002)",
                                   "noise_mm": 0, "generated_by": "pipeline/validation/calibrate_profiles.py"},
                         *s1002_points())]
    y, z = wheel_tread_points(pw)
    out.append(write_profile("c20_new", {"kind": "wheel", "source": "C20 wheel file geometry/wheels/c20.toml: 1:40 "
                                         "cone + worn 23 mm flange (geometry.wheel.tread_profile vertices)",
                                         "noise_mm": 0, "generated_by": "pipeline/validation/calibrate_profiles.py"}, y, z))
    for name, pr in rails.items():
        y, z = rail_head_points(pr)
        hd = pr["head"]
        out.append(write_profile(f"{name}_new", {
            "kind": "rail", "source": f"EN 13674-1 head arcs R{1e3 * hd['crown_radius']:.0f}/R"
            f"{1e3 * hd['shoulder_radius']:.0f}/R{1e3 * hd['corner_radius']:.0f}, width {1e3 * hd['width']:.0f} mm "
            + (f"at the R{1e3 * hd['corner_radius']:.0f} tangent, head sides 1:{1 / hd['side_taper']:.0f} down to "
               f"{1e3 * TABLE_DEPTH:.0f} mm below the crown " if hd.get("side_taper", 0.0) > 0 else "")
            + f"(geometry/rails/{name}.toml; see its source caveat)", "noise_mm": 0,
            "generated_by": "pipeline/validation/calibrate_profiles.py"}, *_resample_rail(y, z)))
    return out


def calibrate(seed: int = 1) -> dict:
    """Fit the wear and write c20_worn.csv, bv50_worn.csv; returns the fit."""
    pw, _ = load_wheel(WHEEL)
    pr, _ = load_rail_params(RAIL)
    pr60, _ = load_rail_params("60e1")
    write_standard(pw, {RAIL: pr, "60e1": pr60})
    new = build_profile(*wheel_tread_points(pw), "wheel", "c20_new", "c20")
    inc = pr["running_surface"]["inclination"]
    c = rolling_circle_offset()
    targets = {dy: yw for dy, (yw, _) in THESIS_POSITIONS.items()}
    prob = FitProblem(new.y, new.z, rail_head_curve(pr), inc, c, targets)
    t0 = time.perf_counter()
    res = fit(prob, seed=seed)
    ww, rw = split(res["x"])
    pars = ", ".join(f"{k} = {1e3 * v:.3f} mm" for k, v in res["params"].items())
    found = ", ".join(f"{1e3 * dy:+.0f} mm -> {1e3 * y:+.2f} mm (moves {1e3 * res['moves'][dy]:.1f} mm for +-0.5 mm "
                      f"of offset; other zones >= {1e3 * res['margins'][dy]:.2f} mm higher)"
                      for dy, y in res["contacts"].items())
    common = {"calibrated_by": "pipeline/validation/calibrate_profiles.py (make calibrate), geometry/calibration.py",
              "calibrated_to": "thesis [4.1] wheel contact points y^W = -5, +4, +32 mm (field-positive: the printed "
                               "+5, -4, -32 negated) at dy_WR = -5, -10, -15 mm (rigid contact, Y = y^W + c + dy_WR, "
                               "c = -17/3 mm, BV50 inclined 1:30); NOT to the rail points y^R, NOT to patch sizes",
              "wear_parameters": pars, "fit_contact_points": found,
              "fit_objective": f"{res['objective']:.4f} (seed {seed}, {res['evaluations']} evaluations); worn head "
                               f"curvature <= {res['rail_kappa_max']:+.3f} 1/m on |y| < 22 mm (kept convex)",
              "noise_mm": 0}
    yw, zw = worn_wheel(new.y, new.z, ww)
    write_profile("c20_worn", {"kind": "wheel", "source": "C20 (c20_new) with calibrated hollow tread wear "
                               "(geometry.wear.WheelWear)", **common}, *_resample(yw, zw))
    yr, zr = worn_rail(rail_head_curve(pr), rw)
    write_profile("bv50_worn", {"kind": "rail", "source": "BV50 (bv50_new) with calibrated top and gauge-face wear "
                                "(geometry.wear.RailWear)", **common}, *_resample(yr, zr))
    log.info("calibrated in %.0f s (grid %.2f mm): %s; contacts %s; objective %.4f", time.perf_counter() - t0,
             1e3 * GRID_STEP, pars, found, res["objective"])
    return res


if __name__ == "__main__":
    import sys

    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    if "--standard" in sys.argv[1:]:  # only the new-profile files (no wear fit)
        from pipeline.stages.rail import load_rail_params
        from pipeline.stages.wheel import load_wheel

        write_standard(load_wheel(WHEEL)[0], {r: load_rail_params(r)[0] for r in (RAIL, "60e1")})
    else:
        calibrate()
