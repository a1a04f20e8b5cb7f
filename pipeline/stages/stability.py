"""Stability stage: the frequency-domain stability screen of a case (``solvers.stability.screen``).

Linearises the case's time loop about steady rolling (its friction, creepage, preload, contact
tables and Green's functions) and lists the closed-loop poles near every lightly damped wheel
mode and of the wheelset on the track (20-400 Hz): frequency, growth rate, mode label.

Artifacts: build/cases/<case>/stability.npz (keys: ``f_hz``, ``sigma`` (1/s), ``mode`` (index
into modes.npz, -1 for a track root), ``label``, ``f_open`` (open-loop frequency, NaN for track
roots), ``kc``, ``mu0``, ``dmu``, ``A2``, ``wall_s``), stability.csv (the same table sorted by
growth rate) and stability.png (growth rate against frequency, unstable poles marked).
"""
from __future__ import annotations

import logging
import time

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.config.case import loop_arguments, resolve_case
from pipeline.stages.simulate import case_arrays, simulate_config
from pipeline.caches.friction_curves import with_curves
from postprocess.plots.stability import screen_figure
from pipeline.stages.simulate_two_point import two_point_roots

log = logging.getLogger("pipeline.stability")


def case_linear_model(case: str, mu: float | None = None, gamma_y: float | None = None):
    """(case dict, LinearModel, mode labels, modes' open-loop frequencies) of a case, optionally at
    another friction coefficient or creepage than the case's."""
    from solvers.timeloop.interaction import contact_model  # lazy: brings in numba, rocket_fft, scipy
    from solvers.stability.screen import linearise  # lazy: brings in numba


    c, _, con, gr, wheel = case_arrays(case)
    rc = resolve_case(case)
    modes, _ = artifacts.load_npz(paths.wheel_dir(c["wheel"]) / "modes.npz", "wheel-modes")
    labels = np.array([f"({n},{m},{k})" for n, m, k in zip(modes["n"], modes["m"], modes["cls"])])
    if mu is None:
        mu = rc.friction
    else:
        con = with_curves(case, con, [mu])
    args = loop_arguments(rc, con).linearise(**({} if gamma_y is None else {"gamma_y": gamma_y}))
    lm = linearise(wheel, gr["rail_kernel"], contact_model(con, mu), **args)
    return c, lm, labels, np.asarray(gr["wheel_f"], float)


def run_stability(case: str) -> dict:
    from solvers.stability.screen import screen  # lazy: brings in numba


    t0 = time.perf_counter()
    c, lm, labels, f_open = case_linear_model(case)
    roots = screen(lm)
    if c["contact"].get("points", 1) == 2:  # [contact] points = 2: the two-point screen
        roots = case_two_point_roots(case)
    wall = time.perf_counter() - t0
    mode = np.array([r.mode for r in roots], np.int64)
    arrays = {"f_hz": np.array([r.f_hz for r in roots]), "sigma": np.array([r.sigma for r in roots]),
              "mode": mode, "label": np.array([labels[m] if m >= 0 else "track" for m in mode]),
              "f_open": np.array([f_open[m] if m >= 0 else np.nan for m in mode]),
              "kc": np.float64(lm.kc), "mu0": np.float64(lm.mu0), "dmu": np.float64(lm.dmu),
              "A2": np.float64(lm.A2), "wall_s": np.float64(wall)}
    out = paths.case_dir(case)
    cfg = {"simulate": simulate_config(case)[-1]}
    artifacts.save_csv(out / "stability.csv", ["f_hz", "sigma_per_s", "mode", "label", "f_open_hz"],
                       [(f"{f:.3f}", f"{s:.4f}", m, lab, f"{fo:.3f}") for f, s, m, lab, fo in
                        zip(arrays["f_hz"], arrays["sigma"], mode, arrays["label"], arrays["f_open"])])
    plot_screen(arrays, out / "stability.png", case, c)
    artifacts.save_npz(out / "stability.npz", "stability", cfg, **arrays)
    top = roots[0] if roots else None
    log.info("stability %s: %d poles in %.2f s; fastest growing %s at %.1f Hz, sigma = %+.2f 1/s -> %s", case,
             len(roots), wall, arrays["label"][0] if top else "-", top.f_hz if top else np.nan,
             top.sigma if top else np.nan, out / "stability.npz")
    return arrays


def plot_screen(a: dict, path, case: str, c: dict) -> None:
    """``postprocess.plots.stability.screen_figure``, saved atomically to ``path``."""
    save_figure(screen_figure(a, case, c), path, dpi=100)


def case_two_point_roots(case: str) -> list:
    """The two-point screen's wheel roots of a case from its artifacts (``simulate_two_point.two_point_roots``)."""
    from solvers.timeloop.interaction import contact_model  # lazy: brings in numba, rocket_fft, scipy


    c, _, con, gr, wheel = case_arrays(case)
    rc = resolve_case(case)
    return two_point_roots(rc, con, gr, wheel, contact_model(con, rc.friction))
