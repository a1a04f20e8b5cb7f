"""Contact benchmarks (solvers/contact): `run() -> str` gives the markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks.contact

Wall-clock medians after warm-up (numba compiled, FFT plans and influence operators
cached), one process; the Hertzian wheel/rail contact of the validation report
(wheel R 0.39 m on a 0.3 m rail crown, 65 kN, steel), v = 50 km/h, dx = v dt = 0.5 mm.
"""
from __future__ import annotations

import time

import numpy as np

from benchmarks.timing import median_time

from solvers.contact.compliance import contact_compliance
from solvers.contact.friction import mu_rf, rf_curve
from solvers.contact.norm import approach_for_load, norm, table_force
from solvers.contact.tang import tang_steady, tang_transient

V = 50 / 3.6
DX = V * 36e-6
A, B = 1 / (2 * 0.39), 1 / (2 * 0.3)


def _gap(nx, ny, dx):
    x = (np.arange(nx) - 0.5 * (nx - 1)) * dx
    y = (np.arange(ny) - 0.5 * (ny - 1)) * dx
    X, Y = np.meshgrid(x, y, indexing="ij")
    return A * X**2 + B * Y**2


def run() -> str:
    rows = []
    # NORM on a 32 x 32 potential area (1024 elements) at the standard dx
    h = _gap(32, 32, DX)
    xi3, sol = approach_for_load(65e3, h, DX, DX)
    t_cold = median_time(lambda: norm(h, xi3, DX, DX), 100, warm=3)
    prev = norm(h, 0.99 * xi3, DX, DX)
    t_warm = median_time(lambda: norm(h, xi3, DX, DX, warm=prev), 100, warm=3)
    rows.append(f"| NORM, 32 x 32 = 1024 elements (dx = 0.5 mm, {sol.contact.sum()} in contact), cold start | "
                f"{1e3 * t_cold:.2f} ms |")
    rows.append(f"| NORM, same, warm start from the solution at 0.99 xi3 (time loop) | {1e3 * t_warm:.2f} ms |")
    # NORM with ~1000 elements IN contact
    d = 0.3e-3
    h2 = _gap(47, 41, d)
    xi2, s2 = approach_for_load(65e3, h2, d, d)
    t2 = median_time(lambda: norm(h2, xi2, d, d), 30, warm=3)
    rows.append(f"| NORM, 47 x 41 = 1927 elements (dx = 0.3 mm, {s2.contact.sum()} in contact), cold start | "
                f"{1e3 * t2:.2f} ms |")
    t_app = median_time(lambda: approach_for_load(65e3, h, DX, DX), 10, warm=1)
    rows.append(f"| approach_for_load(65 kN), 1024 elements | {1e3 * t_app:.1f} ms |")
    # TANG steady, contact of the 32 x 32 grid
    p3 = sol.p
    n = int(sol.contact.sum())
    for g in (0.001, 0.003, 0.02):
        t = median_time(lambda: tang_steady(p3, DX, DX, V, 0.3, gamma_y=-g), 5, warm=1)
        s = tang_steady(p3, DX, DX, V, 0.3, gamma_y=-g)
        rows.append(f"| TANG steady, {n} contact elements, mu = 0.3, gamma_y = -{g} ({s.stick.sum()} stick), cold start "
                    f"| {1e3 * t:.0f} ms |")
    w = tang_steady(p3, DX, DX, V, 0.3, gamma_y=-0.0029)
    t = median_time(lambda: tang_steady(p3, DX, DX, V, 0.3, gamma_y=-0.003, warm=w), 5, warm=1)
    rows.append(f"| TANG steady, gamma_y = -0.003, warm start from gamma_y = -0.0029 | {1e3 * t:.0f} ms |")
    # transient time loop: constant creepage, and creepage oscillating at 1 kHz (stick-slip-like)
    dt = DX / V
    for label, gam in (("constant gamma_y = -0.003", lambda k: -0.003),
                       ("gamma_y = -0.003 (1 + 0.3 sin 2 pi 1 kHz t)", lambda k: -0.003 * (1 + 0.3 * np.sin(2e3 * np.pi * k * dt)))):
        st = None
        for k in range(40):
            st = tang_transient(p3, DX, DX, V, 0.3, gamma_y=gam(k), state=st)
        t0 = time.perf_counter()
        for k in range(40, 140):
            st = tang_transient(p3, DX, DX, V, 0.3, gamma_y=gam(k), state=st)
        rows.append(f"| TANG transient, mean per time step over steps 40-140, {label} | "
                    f"{1e3 * (time.perf_counter() - t0) / 100:.0f} ms |")
    t = median_time(lambda: rf_curve(p3, DX, DX, V, 0.3), 1, warm=1)
    rows.append(f"| one RF curve (mu = 0.3, 23 steady TANG solves + creep stiffness) | {t:.2f} s |")
    t = median_time(lambda: contact_compliance(p3, (1e3, 1e4), DX, DX), 50, warm=3)
    rows.append(f"| contact compliance A1, A2 [4.32-4.35], 1024 elements | {1e3 * t:.2f} ms |")
    c = rf_curve(p3, DX, DX, V, 0.3, n_plateau=1)
    se = np.linspace(0, 0.1, 1000)
    t = median_time(lambda: [mu_rf(si, c.s, c.mu_rf, c.slope) for si in se], 20, warm=3) / 1000
    xs, qs, xe = np.linspace(0, 1e-4, 17), np.linspace(0, 1e3, 17), np.linspace(0, 1e-4, 1000)
    t_f = median_time(lambda: [table_force(x, xs, qs) for x in xe], 20, warm=3) / 1000
    rows.append(f"| mu_rf(s) / table_force(xi3) njit evaluation, per call from Python | {1e6 * t:.1f} / {1e6 * t_f:.1f} us |")
    return ("## Contact\n\nHertzian wheel/rail contact (R 0.39 m on a 0.3 m crown, 65 kN), v = 50 km/h, "
            "dx = dy = 0.5 mm unless stated; medians of repeated solves after warm-up, one process "
            "(`benchmarks/contact.py`). Issue target: one NORM solve on ~1000 elements < 5 ms.\n\n"
            "| what | time |\n|---|---:|\n" + "\n".join(rows) + "\n")


if __name__ == "__main__":
    print(run())
