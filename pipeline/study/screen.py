"""Stability map: the screen (``solvers.stability.screen``) at every (gamma_y, mu) of a map study's grid
and contact positions, in seconds; and its agreement with the time loop's map where that exists.

    python -m pipeline stability_map --study map [--quick]      (make stability-map STUDY=map [QUICK=1])

One ``Basis`` per position (the structures' transforms do not depend on friction or creepage),
one linearisation per mu (k_c, A2 from the normal contact, mu0 and the curve's slope per
creepage); roots by the first-order expansion about each pole and one grid Newton step for the
track roots (``polish=False``; tests/stability: unstable poles within 1e-3 1/s of the exact ones).

Outputs in the study's folder (build/studies/<study>[-quick]/): stability.csv (case, dy_wr, gamma_y,
mu, sigma_max (1/s), f_max (Hz), label_max ('track' or the wheel mode), sigma_lf (fastest track
root, NaN when none), label_na / sigma_na (fastest (n,0,a) mode)), stability_<case>.png and,
when the time loop's map.csv is there, stability_agreement.md.
"""
from __future__ import annotations

import logging
import time

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.stages.stability import case_linear_model
from pipeline.caches.friction_curves import with_curves
from pipeline.config.case import resolve_case
from pipeline.study.definition import grid_of
from pipeline.study.kinds import load_study
from pipeline.study.agreement import write_agreement
from postprocess.plots.stability import map_figure

log = logging.getLogger("pipeline.stability")
COLUMNS = ["case", "dy_wr", "gamma_y", "mu", "sigma_max", "f_max", "label_max", "sigma_lf", "label_na", "sigma_na"]


def grid_roots(lm0, con, v: float, gammas, mus, mu_lm0: float | None = None):
    """Yield (mu, gamma_y, roots) of the screen at every (gamma_y, mu): one ``Basis`` of ``lm0``'s
    structures, one linearisation per mu (``lm0`` itself at ``mu_lm0``), the operating point per
    creepage.  ``con``: the contact artifact's arrays; v: rolling speed (m/s)."""
    from solvers.timeloop.interaction import contact_model  # lazy: brings in numba, rocket_fft, scipy
    from solvers.stability.screen import Basis, linearise, operating_point, screen  # lazy: brings in numba

    basis = Basis(lm0)
    for mu in mus:
        cm = contact_model(con, float(mu))
        lm_mu = lm0 if mu == mu_lm0 else linearise(
            _wheel(lm0), lm0.rail_kernel, cm, dt=lm0.dt, v=v, gamma_y=float(gammas[0]), preload=lm0.F3)
        for gy in gammas:
            yield float(mu), float(gy), screen(operating_point(lm_mu, cm, v=v, gamma_y=float(gy)), basis, polish=False)


def screen_rows(case: str, gammas, mus) -> list[dict]:
    """The screen at every (gamma_y, mu) of one case's position."""
    c, lm0, labels, _ = case_linear_model(case)

    con, _ = artifacts.load_npz(paths.case_dir(case) / "contact.npz", "contact")
    con = with_curves(case, con, [float(m) for m in mus])
    lab = lambda r: "track" if r.mode < 0 else str(labels[r.mode])                      # noqa: E731
    rows = []
    for mu, gy, roots in grid_roots(lm0, con, c["kinematics"]["speed"], gammas, mus,
                                    resolve_case(case).friction.coulomb_mu):
        lf = [r for r in roots if r.mode < 0]
        na = [r for r in roots if r.mode >= 0 and lab(r).endswith(",0,a)")]
        rows.append({"case": case, "dy_wr": c["contact"]["dy_wr"], "gamma_y": gy, "mu": mu,
                     "sigma_max": roots[0].sigma, "f_max": roots[0].f_hz, "label_max": lab(roots[0]),
                     "sigma_lf": lf[0].sigma if lf else np.nan,
                     "label_na": lab(na[0]) if na else "", "sigma_na": na[0].sigma if na else np.nan})
    return rows


def _wheel(lm):
    from solvers.timeloop.interaction import WheelModes  # lazy: brings in numba, rocket_fft, scipy

    return WheelModes(lm.f_r, lm.modal_mass, lm.zeta, lm.phi)


def run_stability_map(study: str, quick: bool = False) -> str:
    spec, _ = load_study(study)
    gammas, mus = grid_of(spec, quick)
    out = paths.build() / "studies" / (study + ("-quick" if quick else ""))
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    rows = [r for case in spec["cases"] for r in screen_rows(case, gammas, mus)]
    wall = time.perf_counter() - t0
    fmt = lambda x: f"{x:.6g}" if isinstance(x, float) else str(x)                         # noqa: E731
    artifacts.save_csv(out / "stability.csv", COLUMNS, [[fmt(r[k]) for k in COLUMNS] for r in rows])
    for case in spec["cases"]:
        plot_map([r for r in rows if r["case"] == case], gammas, mus, out / f"stability_{case}.png", case)
    log.info("stability map %s: %d cases in %.2f s (%.1f ms per case) -> %s", study, len(rows), wall,
             1e3 * wall / max(len(rows), 1), out / "stability.csv")
    if (out / "map.csv").exists():
        write_agreement(out, rows, spec)
    return str(out / "stability.csv")


def plot_map(rows: list[dict], gammas, mus, path, case: str) -> None:
    """``postprocess.plots.stability.map_figure``, saved atomically to ``path``."""
    save_figure(map_figure(rows, gammas, mus, case), path, dpi=100)
