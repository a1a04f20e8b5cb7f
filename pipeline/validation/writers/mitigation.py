"""Validation fragment docs/validation/93_mitigation.md: the verdict's what-ifs against independent
references (default case): the Coulomb curve at a new mu against a direct TANG run, the friction
threshold's bisection against a direct scan of the screen, the damping the procedure finds against
the screen's first-order estimate, and the time loop on both sides of each.

A writer, run by `make validate`; ``measure()`` is what tests/verdict/test_mitigation.py asserts
(--validation: the bisection brackets the scan's first unstable mu, the scaled curve within 1e-4 of
TANG, both time-loop confirmations).
"""
import time

import numpy as np

from pipeline.validation.make import ensure_case
from pipeline.validation.writers import save_fragment
from pipeline.curve.what_ifs import CaseModels, damping_what_if, friction_what_if
from solvers.stability.mitigation import coulomb_curve_at, first_squeal, growing_wheel_root


def measure() -> dict:
    from solvers.contact.friction import rf_curve  # lazy: brings in numba, rocket_fft, scipy

    from pipeline.validation.references.contact import hertz_pressure  # lazy: brings in scipy

    ensure_case("default")
    p3, d = hertz_pressure()
    gam = np.array([0.0005, 0.001, 0.002, 0.004, 0.008])
    ref = rf_curve(p3, d, d, 13.9, 0.25, gammas=gam)
    _, m, _ = coulomb_curve_at(ref.s, ref.mu_rf, ref.slope, 0.25, 0.27)
    direct = rf_curve(p3, d, d, 13.9, 0.27, gammas=gam * 0.27 / 0.25)
    err = float(np.max(np.abs(m - direct.mu_rf)))

    models = CaseModels("default")
    t0 = time.perf_counter()
    fr = friction_what_if(models)
    t_fr = time.perf_counter() - t0
    scan = np.round(np.arange(0.10, 0.3501, 0.005), 3)
    t0 = time.perf_counter()
    first = first_squeal(models.unstable, scan)
    t_scan = time.perf_counter() - t0
    dm = damping_what_if(models)
    r = growing_wheel_root(models.roots(models.ctx.mu))
    z0 = float(models.ctx.wheel["zeta"][r.mode])
    estimate = z0 + r.sigma / (2 * np.pi * r.f_hz)
    need = {}
    for lab, f, a, z in dm.modes:
        need[lab] = (f, need.get(lab, (f, a, z))[1], z)
    return dict(err=err, fr=fr, t_fr=t_fr, scan=scan, first=first, t_scan=t_scan, dm=dm, r=r, estimate=estimate,
                need=need)


def render(err, fr, t_fr, scan, first, t_scan, dm, r, estimate, need) -> str:
    rows = "\n".join(f"| {lab} | {f:.1f} | {a:.2g} | {z:.3g} |" for lab, (f, a, z) in need.items())
    text = f"""## The verdict's mitigation what-ifs (default case)

`make curve` answers "what would stop it" for every squealing wheel (`pipeline/curve/what_ifs.py`,
`solvers/stability/mitigation.py`); here on the default case (C20/BV50, dy_WR = -15 mm, gamma_y = -0.014, mu = 0.35).

* **Friction curve at any mu.** Kalker's steady problem with Coulomb friction is homogeneous in (mu,
  creepage, traction), so the curve at mu is the one at mu_ref scaled. Against a direct TANG run at
  mu = 0.27 (Hertzian pressure on a 0.5 mm grid, 5 creepages up to full slip): largest difference in
  mu_RF {err:.1e}.
* **Friction threshold.** Bisection of the stability screen's verdict over mu (to 0.005): quiet at
  mu = {fr.mu_quiet:.4f}, unstable at {fr.mu_squeal:.4f} ({fr.screens} screens, {t_fr:.1f} s with both
  time-loop runs); a direct scan in steps of 0.005 from 0.10 finds the first unstable mu at {first:.3f}
  ({len(scan)} screens, {t_scan:.1f} s). The time loop: mu = {fr.below['mu']:.3f} quiet (L_F2 =
  {fr.below['L_F2']:.1f} dB), mu = {fr.above['mu']:.3f} squeals (L_F2 = {fr.above['L_F2']:.1f} dB at
  {fr.above['f']:.1f} Hz).
* **Damping.** The damping study's procedure (`solvers.study.damping_procedure`) answered by the screen
  ({dm.screens} screens; {dm.end}):

| mode | f (Hz) | nominal zeta | zeta that stops it |
|---|---|---|---|
{rows}

  The screen's first-order estimate for the squealing mode, zeta0 + sigma / omega = {estimate:.4f}
  ({r.sigma:.2f} 1/s at {r.f_hz:.1f} Hz). With the damping applied the time loop is quiet (L_F2 =
  {dm.confirm['L_F2']:.1f} dB).

Timings on the shared 2-core machine under load (noisy). Written by
`pipeline/validation/writers/mitigation.py` (`make validate`); asserted by `tests/verdict/test_mitigation.py`.
"""
    return text


def write() -> str:
    return save_fragment("93_mitigation.md", render(**measure()))


if __name__ == "__main__":
    write()
