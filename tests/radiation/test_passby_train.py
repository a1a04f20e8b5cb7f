"""The train's pass-by of incoherent point sources (solvers/radiation/passby_train.py) against
closed forms: one source, two close sources (the maximum at their midpoint), sources far apart (the
maximum at a source, the others' 1/r^2 added), a long uniform row against the infinite line source
L = L_W' - 10 lg(4 d) (with and without CNOSSOS-EU's horizontal dipole, factor 0.01 + 0.99/2), the
exposure int dt / r^2 = pi / (d v); the A-weighting against IEC 61672-1's table; squeal's excess."""
import math

import numpy as np
import pytest

from solvers.radiation import passby_train as pt
from solvers.radiation.squeal_excess import climate_excess, squeal_excess

D, H, V = 7.5, 1.2, 10.0


def test_one_source():
    r = pt.passby_levels([0.0], 0.0, H, 100.0, speed=V, d=D, h=H, length=20.0)
    assert r["L_max"] == pytest.approx(100.0 - 20 * math.log10(D) - 10 * math.log10(4 * math.pi), abs=1e-4)
    assert r["X_max"] == pytest.approx(0.0, abs=D / 300)
    assert r["L_E"] == pytest.approx(100.0 - 10 * math.log10(4 * D * V), abs=1e-9)   # W/(4 pi) * pi/(d v)
    assert r["L_eq"] == pytest.approx(r["L_E"] - 10 * math.log10(2.0), abs=1e-9)      # T_p = 20 m / 10 m/s


def test_two_close_sources_peak_between():
    s = 2.0                                       # s/2 < d/sqrt(3): the sum's maximum is at the midpoint
    r = pt.passby_levels([0.0, s], [0.0, 0.0], H, [90.0, 90.0], speed=V, d=D, h=H, length=10.0)
    want = 90.0 - 11.0 + 10 * math.log10(2.0 / (D ** 2 + (s / 2) ** 2)) + 11.0 - 10 * math.log10(4 * math.pi)
    assert r["L_max"] == pytest.approx(want, abs=1e-4)
    assert r["X_max"] == pytest.approx(s / 2, abs=0.05)


def test_sources_far_apart_peak_at_a_source():
    x = np.array([0.0, 100.0, 200.0, 300.0])
    r = pt.passby_levels(x, 0.0, H, 95.0, speed=V, d=D, h=H, length=300.0)
    at = [10 * math.log10(sum(10 ** 9.5 / (4 * math.pi * (D ** 2 + (xj - xk) ** 2)) for xj in x)) for xk in x]
    assert r["L_max"] == pytest.approx(max(at), abs=1e-3)
    assert r["L_E"] == pytest.approx(95.0 + 10 * math.log10(4) - 10 * math.log10(4 * D * V), abs=1e-9)


@pytest.mark.parametrize("dipole", [False, True])
def test_long_row_is_the_line_source(dipole):
    """A row 400 m long of sources 0.5 m apart (W' = W / dx): its L_eq over T_p is the infinite line's,
    its L_max (centred) the finite line's: W'/(4 pi) int g(x) / r^2 dx over +-a, u = a / d:
    omni (2/d) atan u; dipole 0.01 (2/d) atan u + 0.99 (1/d) (atan u + u / (1 + u^2))."""
    dx, n, Lw1 = 0.5, 801, 80.0
    x = np.arange(n) * dx
    r = pt.passby_levels(x, 0.0, H, Lw1, speed=V, d=D, h=H, length=n * dx, dipole=dipole)
    Lw_m = Lw1 - 10 * math.log10(dx)                              # per metre
    factor = 0.01 + 0.99 / 2 if dipole else 1.0
    assert r["L_eq"] == pytest.approx(Lw_m - 10 * math.log10(4 * D) + 10 * math.log10(factor), abs=1e-9)
    u = 0.5 * n * dx / D
    g = (0.01 * 2 * math.atan(u) + 0.99 * (math.atan(u) + u / (1 + u * u))) if dipole else 2 * math.atan(u)
    assert r["L_max"] == pytest.approx(Lw_m + 10 * math.log10(g / (4 * math.pi * D)), abs=1e-3)


def test_a_weighting_iec_table():
    f = np.array([100.0, 1000.0, 4000.0])
    for fi, a in zip(f, (-19.1, 0.0, 1.0)):                       # IEC 61672-1 Table 3
        assert pt.a_weighted_sum([fi], [0.0]) == pytest.approx(a, abs=0.05)


def test_squeal_excess():
    assert squeal_excess([80.0, 84.0], 70.0, 0.5) == pytest.approx(6.0)
    assert squeal_excess([80.0, 84.0], 70.0, 1.0, energetic=True) == pytest.approx(
        10 * math.log10((1e8 + 10 ** 8.4) / 2) - 70.0)
    assert squeal_excess([], 70.0, 0.3) == 0.0
    with pytest.raises(ValueError, match="must be in"):
        squeal_excess([80.0], 70.0, 1.5)


def test_climate_excess_closed_form():
    """Squeal as loud as rolling noise adds 10 lg 2 = 3.01 dB when it occurs; in 30 % of the passages the
    expectation is 0.3 x 3.01 dB; no squeal anywhere in the climate: 0 dB."""
    assert abs(climate_excess(70.0, 70.0, 1.0) - 10 * np.log10(2.0)) < 1e-12
    assert abs(climate_excess(70.0, 70.0, 0.3) - 0.3 * 10 * np.log10(2.0)) < 1e-12
    assert abs(climate_excess(69.4, 90.0, 1.0) - (10 * np.log10(10 ** 6.94 + 10 ** 9.0) - 69.4)) < 1e-12
    assert climate_excess(70.0, float("nan"), 0.5) == 0.0
