"""The curving solver's creep forces: Hertz's ellipse against pipeline/validation/references/hertz.py, Kalker's
coefficients (computed with TANG) against Kalker's Table E.3, the Shen-Hedrick-Elkins
saturation against steady TANG on the same patch."""
from __future__ import annotations

import math

import numpy as np
import pytest

from solvers.contact.tang import tang_steady
from solvers.curving.creep import CreepLaw, creep_forces, kalker_coefficients
from solvers.curving.hertz import hertz_semi_axes
from pipeline.validation.references.kalker import creep_coefficient

MU, N = 0.35, 65e3
A, B = 0.5 / 0.39, 0.5 / 0.3  # a 780 mm wheel on a 300 mm crown


@pytest.mark.parametrize("A,B", [(1.0, 1.0), (0.5 / 0.39, 0.5 / 0.3), (1.3, 20.0), (12.0, 1.3)])
def test_hertz_semi_axes(A, B):
    from pipeline.validation.references.hertz import hertz

    a, b = hertz_semi_axes(A, B, N)
    ref = hertz(A, B, N)
    assert (a, b) == pytest.approx((ref.a, ref.b), rel=1e-6)


@pytest.mark.parametrize("ratio", [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0])
def test_tang_coefficients_against_kalkers_table(ratio):
    """Kalker's no-slip coefficients from TANG on a 40 x 40 grid: within 3.5 % of Table E.3
    (the grid's discretisation error; 1-3 %, larger for elongated patches)."""
    got = kalker_coefficients(ratio)
    ref = [creep_coefficient(n, ratio, 1.0, 0.3) for n in ("C11", "C22", "C23")]
    assert got == pytest.approx(ref, rel=0.035)


def _patch():
    a, b = hertz_semi_axes(A, B, N)
    n = 40
    dx, dy = 2 * a / n, 2 * b / n
    x = (np.arange(n) - 0.5 * (n - 1)) * dx
    y = (np.arange(n) - 0.5 * (n - 1)) * dy
    p3 = np.sqrt(np.clip(1 - (x[:, None] / a) ** 2 - (y[None, :] / b) ** 2, 0.0, None))
    return p3 * N / (p3.sum() * dx * dy), dx, dy


@pytest.mark.parametrize("g", [0.0005, 0.001, 0.002, 0.003, 0.005, 0.008, 0.02])
def test_saturation_against_tang(g):
    """Pure lateral creepage: within 0.03 mu N of steady TANG; with longitudinal creepage and a
    tread spin of 0.3 1/m within 0.08 mu N (Shen-Hedrick-Elkins treats spin linearly)."""
    p3, dx, dy = _patch()
    law = CreepLaw(mu=MU)
    t = tang_steady(p3, dx, dy, 10.0, MU, gamma_y=g)
    f = creep_forces(law, N, A, B, 0.0, g, 0.0)
    assert abs(f.F2 - t.F2) < 0.03 * MU * N
    t = tang_steady(p3, dx, dy, 10.0, MU, gamma_x=g, gamma_y=g, spin=0.3)
    f = creep_forces(law, N, A, B, g, g, 0.3)
    assert math.hypot(f.F1 - t.F1, f.F2 - t.F2) < 0.08 * MU * N
