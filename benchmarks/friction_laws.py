"""Friction-law benchmarks (solvers/contact/friction_laws, tang.falling): `run() -> str` gives the
markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks friction_laws --update

The global curve rf_curve(p3, dx, dy, v, law) of each law side by side with the Coulomb curve of the
same contact, in one run (the ratio is what the numbers mean on a shared machine): the Hertzian
wheel/rail contact of benchmarks/contact.py (29 x 25 grid at dx = v dt = 0.5 mm, 353 contact
elements, v = 50 km/h), and one steady TANG solve at gamma_y = -0.003 (near the peak) with each law.
"""
from __future__ import annotations

import os

from benchmarks.contact import DX, V, transient_2925
from benchmarks.timing import min_time
from solvers.contact.friction import rf_curve
from solvers.contact.friction_laws import get_friction_law, preset
from solvers.contact.tang import tang_steady

CASES = (
    ("coulomb, mu = 0.3 (today's curve)", 0.3),
    ("exponential, CONTACT's tractcurv preset (0.14 + 0.19, 1250 mm/s)", "contact_tractcurv"),
    ("exponential, steep (0.2 + 0.15, 100 mm/s)", ("exponential", dict(fkin=0.2, fexp1=0.15, sabsh1=100.0))),
    ("rational (0.2 + 0.1 / 200 mm/s + 0.05 / 500 mm/s)",
     ("rational", dict(fkin=0.2, frat1=0.1, sabsh1=200.0, frat2=0.05, sabsh2=500.0))),
    ("polach_dry (Polach 2005)", "polach_dry"),
    ("hpf (rising: 0.25 -> 0.35)", "hpf"),
)


def _law(spec):
    if isinstance(spec, float):
        return spec
    if isinstance(spec, str):
        return preset(spec)
    return get_friction_law(spec[0], **spec[1])


def run() -> str:
    load0 = os.getloadavg()
    p3 = transient_2925()
    rows = []
    t_coulomb = None
    for label, spec in CASES:
        law = _law(spec)
        t = min_time(lambda: rf_curve(p3, DX, DX, V, law), 3, warm=1)
        c = rf_curve(p3, DX, DX, V, law)
        ts = min_time(lambda: tang_steady(p3, DX, DX, V, law, gamma_y=-0.003, full_output=False), 5, warm=1)
        t_coulomb = t if t_coulomb is None else t_coulomb
        rows.append(f"| {label} | {len(c.s)} | {c.mu_rf.max():.4f} / {c.mu_rf[-1]:.4f} | {1e3 * t:.0f} ms | "
                    f"{t / t_coulomb:.1f} | {1e3 * ts:.1f} ms |")
    load1 = os.getloadavg()
    return f"""## Friction laws: global curves

`benchmarks/friction_laws.py`: `rf_curve(p3, dx, dy, v, law)` of each law and one steady TANG solve (cold, gamma_y =
-0.003) on the Hertzian wheel/rail contact of the contact suite (29 x 25 grid, dx = 0.5 mm, 353 contact
elements, v = 50 km/h), one process, one core, the least of 3 (curves) or 5 (solves) runs after one warm-up.
A slip-speed dependent law runs CONTACT's slip-velocity iteration around the Coulomb solver
(`solvers/contact/tang/falling.py`) and has 31 nodes (12 on the falling branch) against Coulomb's 24.  Load
average of the shared 2-core machine: {load0[0]:.1f} at the start, {load1[0]:.1f} at the end (timings are noisy;
the ratio column is measured side by side in this run).  Target: under 1 s per curve.

| law | nodes | peak / end mu_RF | one curve | x Coulomb | one TANG solve |
|---|---:|---|---:|---:|---:|
{chr(10).join(rows)}
"""


if __name__ == "__main__":
    print(run())
