"""Calibration of the primary vertical suspension damping (`make calibrate-suspension`).

The thesis gives no damping for the C20's primary suspension, and it decides the
low-frequency instability of the wheelset on the track (docs/validation, "Fidelity
diagnosis": the wheelset bouncing on the contact spring while the rail rocks, 60-90 Hz).
The reference model (thesis ch. 6) reports that instability at one place only: at
dy_WR = -5 mm for mu > 0.45, and gone when the vertical suspension damping is raised.

Target (the only one): at the -5 mm case, no low-frequency root of the stability screen
(``solvers.stability``) grows for mu <= ``MU_QUIET`` at any creepage of the map's grid.
The smallest damping that achieves it is found by Brent's method on
log(c_vertical) against the fastest low-frequency growth rate at ``MU_QUIET``; the check that it
was not fitted to: the instability still appears at the next friction coefficient (0.45) at
-5 mm, and the predictions -- the -10 mm position free of it, the modes that squeal -- are
measured by the map (docs/validation, "The map against the reference model's findings").

The rigid half-wheelset's bounce and roll modes carry the vertical damping
(``solvers.wheelset``): zeta = c / (2 sqrt(k m)) scales with c_vertical, so the screen
needs no new wheel solve.  ``--write`` puts the result into the wheel file.
"""
from __future__ import annotations

import argparse
import logging
import re

import numpy as np

from . import paths

log = logging.getLogger("pipeline.calibrate")

CASE = "dy05"           # the reference's only position with the low-frequency instability
MU_QUIET = 0.40         # no low-frequency instability up to here (the reference: only for mu > 0.45)
MU_LOUD = 0.45          # ... and it is there at 0.45 (checked, not fitted)
VERTICAL = ("bounce", "roll")


def lf_growth(case: str, c_ratio: float, mu: float, gammas) -> float:
    """Fastest growth rate (1/s) of a low-frequency (track) root over ``gammas`` at friction
    ``mu`` with the vertical suspension damping scaled by ``c_ratio``; -inf when none."""
    from solvers.interaction import contact_model
    from solvers.stability import Basis, operating_point, screen

    from . import artifacts
    from .stability_stage import case_linear_model

    c, lm, _, _ = case_linear_model(case, mu=mu)
    modes, _ = artifacts.load_npz(paths.wheel_dir(c["wheel"]) / "modes.npz", "wheel-modes")
    zeta = np.array(lm.zeta, float)
    vert = np.isin(np.asarray(modes["kind"]).astype(str), VERTICAL)
    zeta[vert] *= c_ratio
    lm = lm._replace(zeta=zeta)
    con, _ = artifacts.load_npz(paths.case_dir(case) / "contact.npz", "contact")
    cm = contact_model(con, mu)
    basis = Basis(lm)
    v = c["kinematics"]["speed"]
    worst = -np.inf
    for gy in gammas:
        roots = screen(operating_point(lm, cm, v=v, gamma_y=float(gy)), basis, polish=False)
        lf = [r.sigma for r in roots if r.mode < 0]
        worst = max([worst] + lf)
    return worst


def calibrate(study: str = "map", lo: float = 1.0, hi: float = 100.0) -> dict:
    """The smallest damping ratio c/c_file in [lo, hi] with no growing low-frequency root at
    MU_QUIET on the study's creepage grid; the growth at MU_LOUD as the check."""
    from scipy.optimize import brentq

    from .study.map import grid_of
    from .study.stage import load_study

    spec, _ = load_study(study)
    gammas, _ = grid_of(spec, quick=False)
    def f(log_ratio):   # the fastest low-frequency growth at MU_QUIET, floored (no root: -5/s)
        return max(lf_growth(CASE, float(np.exp(log_ratio)), MU_QUIET, gammas), -5.0) + 1e-3
    if f(np.log(lo)) < 0:
        ratio = lo
    else:
        ratio = float(np.exp(brentq(f, np.log(lo), np.log(hi), xtol=1e-3)))
    return {"ratio": ratio, "sigma_quiet": lf_growth(CASE, ratio, MU_QUIET, gammas),
            "sigma_loud": lf_growth(CASE, ratio, MU_LOUD, gammas)}


def write_back(path, key: str, value: float) -> None:
    """Set ``key`` in the [suspension] table of a wheel file, comments kept (atomic)."""
    from .artifacts import atomic_write

    text = path.read_text()
    sec = re.search(r"^\[suspension\]\s*$(.*?)(?=^\[|\Z)", text, flags=re.M | re.S)
    body = re.sub(rf"^({key}\s*=\s*)[-+0-9.eE]+", lambda m: f"{m.group(1)}{value:.4g}", sec.group(1),
                  count=1, flags=re.M)
    with atomic_write(path) as tmp:
        tmp.write_text(text[:sec.start(1)] + body + text[sec.end(1):])


def main(argv=None) -> None:
    from .config import load
    from .schemas import CASE as CASE_SCHEMA
    from .wheel_stage import load_wheel

    ap = argparse.ArgumentParser(prog="python -m pipeline.calibrate_suspension")
    ap.add_argument("--study", default="map")
    ap.add_argument("--write", action="store_true", help="write c_vertical into the case's wheel file")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    wheel = load(paths.case_file(CASE), CASE_SCHEMA)["wheel"]
    p, _ = load_wheel(wheel)
    r = calibrate(a.study)
    c_v = p["suspension"]["c_vertical"] * r["ratio"]
    print(f"c_vertical = {c_v:.4g} N s/m (x {r['ratio']:.3f}); fastest low-frequency growth at {CASE}: "
          f"{r['sigma_quiet']:+.2f} 1/s at mu = {MU_QUIET}, {r['sigma_loud']:+.2f} 1/s at mu = {MU_LOUD}")
    if a.write:
        write_back(paths.wheel_file(wheel), "c_vertical", c_v)


if __name__ == "__main__":
    main()
