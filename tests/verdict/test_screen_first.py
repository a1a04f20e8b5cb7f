"""The screen-first verdict (pipeline/curve/screen_first.py) against the curve stage: the same
screen numbers for every wheel, the same time-loop verdict where it runs; its rail kernels are the
greens stage's, bit for bit (a listed point's from its cached wave table against
``rail_kernel.build_kernel``; a surface point's against ``rail_surface.point_waves``)."""
import math

import numpy as np
import pytest

from pipeline.config.loader import config_hash
from solvers.greens.grid import RAIL_F_MAX, RAIL_F_TAPER, RAIL_LAGS, RAIL_NT, rail_taper
from pipeline.stages.rail import load_rail_params

GRID = {"n_t": RAIL_NT, "n_lags": RAIL_LAGS, "f_max": RAIL_F_MAX, "f_taper": RAIL_F_TAPER}
DT = 36e-6


def _same(a: dict, b: dict):
    for k in ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance"):
        assert np.array_equal(np.asarray(a[k]), np.asarray(b[k])), k
    assert float(a["rail_decay_db"]) == float(b["rail_decay_db"])


def test_surface_point_kernel_is_the_greens_stages():
    from pipeline.caches import rail_surface_table as rail_surface
    from pipeline.curve import rail_point

    pr, _ = load_rail_params("bv50")
    h = config_hash(pr)
    y_r, v = -0.00733, 47.3 / 3.6                    # a point off contact.y, a speed no case uses
    k, a = rail_surface.point_waves(pr, h, abs(y_r), DT, GRID)
    ref = rail_surface.kernel_from_waves(k, a, v, DT, GRID, rail_taper)
    from solvers.rail.moving_kernel import mirror

    ref = {key: (mirror(x) if key in ("rail_kernel", "rail_fixed_kernel", "rail_point_receptance") else x)
           for key, x in ref.items()}
    got = rail_point.surface_arrays(pr, h, y_r, v, DT, GRID, rail_taper)
    _same(got, ref)


def test_listed_point_kernel_is_build_kernels():
    from pipeline.caches import rail_kernel
    from pipeline.curve import rail_point

    pr, _ = load_rail_params("bv50")
    h = config_hash(pr)
    v = 33.3 / 3.6
    ref = rail_kernel.build_kernel(pr, 0.012, v, DT, GRID, rail_taper)
    got = rail_point.kernel_from_table(rail_point.point_table(pr, h, 0.012, DT, GRID), v, DT, GRID, rail_taper)
    _same(got, ref)


def test_screen_first_equals_the_curve_stage(monkeypatch):
    """r300 (the metro at 300 m, mu = 0.35): the curve stage screens and runs the time loop for all four
    wheels; screen first, the same screen numbers, and no wheel run in the time loop: the screen finds
    no growing pole at any of them (certified: solvers/stability/nyquist.py), and the curve stage's time
    loop finds all four quiet.  Neither path reads a wheel's case file back
    (its ResolvedCase is handed to the stages in memory)."""
    import pipeline.config.case_profiles as P
    from pipeline.curve.screen_first import run_screen_first
    from pipeline.curve.stage import run_curve

    monkeypatch.setattr(P, "case_contact", lambda name: pytest.fail(f"case file of {name} read back"))

    full = {r["wheel"]: r for r in run_curve("r300", progress_bar=False, what_ifs=False)["rows"]}
    first = {r["wheel"]: r for r in run_screen_first("r300", write=False)["rows"]}
    assert set(full) == set(first) == {"a1o", "a1i", "a2o", "a2i"}
    for w, r in first.items():
        f = full[w]
        for k in ("screen_sigma", "screen_f"):
            assert (math.isnan(r[k]) and math.isnan(f[k])) or r[k] == f[k], (w, k)
        assert r["screen_mode"] == f["screen_mode"]
        assert r["time_loop"] == math.isfinite(f["screen_sigma"])
        assert r["squeals"] == f["squeals"]
        if r["time_loop"]:
            assert r["L_F2"] == pytest.approx(f["L_F2"], abs=1e-9)
        else:
            assert math.isnan(r["L_F2"]) and f["L_F2"] < 10.0      # the curve stage's time loop: quiet too
    # exactly which wheels run the time loop: none.  The old secant search returned growing poles that are
    # no zeros of the characteristic function, a2o's (6,0,a) at +28.3 1/s (|D| = 8.8 there) and, with some
    # kernels' last digits, a1o's (4,0,a)/(5,0,a) (issue 34); all four wheels are quiet in the time loop.
    assert [w for w, r in first.items() if r["time_loop"]] == []
    assert all(math.isnan(r["screen_sigma"]) for r in first.values())


def test_a1o_verdict_robust_to_the_kernels_last_digits():
    """r300/a1o (the over-radial leading outer wheel, y^R = -10.3 mm off the rail file's list): no growing
    pole with its rail kernel times 1 +- 1e-7 and with every entry perturbed by up to 1e-7 at random
    (the old search's spurious (4,0,a) pole at +114 1/s came with an 8e-8 change); the count of growing
    poles is 0 with a Rouche margin far above 1e-7 (no kernel within it can change the verdict); the time
    loop (SPEC 6) agrees: quiet."""
    import dataclasses

    from pipeline.curve.cases import wheel_case
    from pipeline.curve.what_ifs import CaseModels
    from pipeline.curve.screen_first import screen_context, time_loop_L_F2
    from pipeline.curve.stage import solve
    from solvers.stability.screen import linearise, screen
    from solvers.stability.nyquist import Contour, certify

    sol = solve("r300")
    a1o = next(p for p in sol.wheels if p.wheel == "a1o")
    rc = wheel_case(sol.curve, a1o)                    # built in memory (any test order)
    ctx = screen_context(rc)
    spin = float(ctx.spin)
    g = np.asarray(ctx.rail_kernel, float)
    rng = np.random.default_rng(34)
    for k in (g, g * (1 + 1e-7), g * (1 - 1e-7), g * (1 + 1e-7 * rng.uniform(-1, 1, g.shape))):
        models = CaseModels.of_context(dataclasses.replace(ctx, rail_kernel=k))
        assert [r for r in models.roots(ctx.mu) if r.sigma > 0 and r.mode >= 0] == []
    # the certificate of the screen's linear model (a1o's gamma_y > 0: its mirror image, as CaseModels.roots)
    assert ctx.gamma_y > 0
    w = CaseModels.of_context(ctx).wheel()
    phi = np.array(w.phi, float)
    phi[:, 0] *= -1.0
    km = g.copy()
    km[:, 0, 1] *= -1.0
    km[:, 1, 0] *= -1.0
    lm = linearise(w._replace(phi=phi), km, CaseModels.of_context(ctx).contact(ctx.mu),
                   dt=ctx.dt, v=ctx.v, gamma_y=-ctx.gamma_y, preload=ctx.preload, gamma_x=ctx.gamma_x, spin=-spin)
    _, cert = certify(lm, screen(lm, certify=False), Contour(lm))
    assert cert.n_unstable == 0 and cert.resolved and cert.eps_kernel > 1e-4
    assert time_loop_L_F2(rc, ctx) < 10.0
