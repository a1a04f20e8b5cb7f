"""Where the C20's axial modes must couple vertical and lateral motion (`make calibrate-coupling`):
the target of the wheel-section fit (pipeline/validation/calibrate_wheel.py), chosen with the stability screen.

The C20 drawing is not public, and the thesis gives its wheel only through the 34
eigenfrequencies (Table 4.1) and plots of the receptances (Fig. 4.4): nothing fixes where on
the tread the (n,0,a) modes have no vertical-lateral coupling.  On a tread line the ratio
Phi_3/Phi_2 of an axial mode is close to linear in y^W (the tyre rotates about a point of its
section), Phi_3/Phi_2 = s_n (y^W - y0_n), and in full slip a mode is destabilised when
-mu < Phi_3/Phi_2 < 0 (solvers/stability/screen.py notes).  So the zero points y0_n of the (2,0,a) and
(3,0,a) modes decide which of them squeals at each contact point.

This script scans (y0_2, y0_3) on a grid, keeping the slopes s_n of the current wheel at the three
cases' contact points (their greens.npz), and for each pair runs the screen over the map study's
grid at the three positions; it reports the share of unstable cases whose fastest pole is the
reference's mode ((2,0,a) at -5 mm for mu < 0.45 and at -15 mm, (3,0,a) at -10 mm; thesis ch. 6).
The pair with the best worst-position share is the calibration target.  This CALIBRATES the mode
selection: docs/validation ("Calibration") lists it as calibrated, not predicted.
"""
from __future__ import annotations

import argparse
import itertools

import numpy as np
from pipeline.store import artifacts, paths
from pipeline.stages.stability import case_linear_model
from pipeline.study.definition import grid_of
from pipeline.study.kinds import load_study
from pipeline.study.screen import grid_roots

CASES = {"dy05": "(2,0,a)", "dy10": "(3,0,a)", "default": "(2,0,a)"}
MU_LF = 0.45     # at -5 mm the reference's mode is stated for mu < 0.45 (above: the suspension instability)
GRID_MM = (-25.0, -20.0, -17.5, -15.0, -12.5, -10.0, -5.0)


def case_models(study: str = "map"):
    """{case: (LinearModel, labels, contact artifact, case dict, y^W)} and the study grid."""
    spec, _ = load_study(study)
    gammas, mus = grid_of(spec, quick=False)
    out = {}
    for case in CASES:
        c, lm, labels, _ = case_linear_model(case)
        con, _ = artifacts.load_npz(paths.case_dir(case) / "contact.npz", "contact")
        gr, _ = artifacts.load_npz(paths.case_dir(case) / "greens.npz", "greens")
        out[case] = (lm, [str(x) for x in labels], con, c, float(gr["y_wheel"]))
    return out, gammas, mus


def share(lm, labels, con, c, target: str, gammas, mus, mu_max: float = np.inf) -> float:
    """Share of the grid's unstable cases (mu < mu_max) whose fastest pole is ``target``."""
    fastest = [roots[0] for _, _, roots in grid_roots(lm, con, c["kinematics"]["speed"], gammas,
                                                      [mu for mu in mus if mu < mu_max])]
    unstable = [r for r in fastest if r.sigma > 0]
    return sum(r.mode >= 0 and labels[r.mode] == target for r in unstable) / len(unstable) if unstable else np.nan


def scan(study: str = "map", grid_mm=GRID_MM) -> list[tuple[float, float, dict]]:
    """[(y0_2 mm, y0_3 mm, {case: share})] over the grid (module notes)."""
    models, gammas, mus = case_models(study)
    lab = models["default"][1]
    idx = {m: lab.index(m) for m in ("(2,0,a)", "(3,0,a)")}
    y = {k: v[4] for k, v in models.items()}
    phi = {k: np.asarray(v[0].phi, float) for k, v in models.items()}
    slope = {m: (phi["default"][i, 1] / phi["default"][i, 0] - phi["dy05"][i, 1] / phi["dy05"][i, 0])
             / (y["default"] - y["dy05"]) for m, i in idx.items()}
    out = []
    for y2, y3 in itertools.product(grid_mm, grid_mm):
        shares = {}
        for case, (lm, labels, con, c, yw) in models.items():
            p = phi[case].copy()
            for m, y0 in (("(2,0,a)", 1e-3 * y2), ("(3,0,a)", 1e-3 * y3)):
                p[idx[m], 1] = slope[m] * (yw - y0) * p[idx[m], 0]
            shares[case] = share(lm._replace(phi=p), labels, con, c, CASES[case], gammas, mus,
                                 MU_LF if case == "dy05" else np.inf)
        out.append((y2, y3, shares))
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(prog="python -m pipeline.validation.calibrate_coupling")
    ap.add_argument("--study", default="map")
    a = ap.parse_args(argv)
    rows = scan(a.study)
    print("y0(2,0,a) mm  y0(3,0,a) mm  " + "  ".join(f"{c:>8s}" for c in CASES))
    for y2, y3, s in rows:
        print(f"{y2:12.1f}  {y3:12.1f}  " + "  ".join(f"{100 * s[c]:7.0f}%" for c in CASES))
    best = max(rows, key=lambda r: min(r[2].values()))
    print(f"best worst-position share: y0(2,0,a) = {best[0]} mm, y0(3,0,a) = {best[1]} mm: {best[2]}")


if __name__ == "__main__":
    main()
