"""NORM (SPEC 4.1 [4.16-4.24]) against Hertz theory and the contact conditions."""
import numpy as np
import pytest

from solvers.contact.norm import (approach_for_load, norm, norm_table, table_force, table_midpoint_error,
                                  table_pressure)
from pipeline.validation.references.hertz import hertz, load_for_approach
from solvers.contact.influence import dense_matrix, normal_kernel
from pipeline.validation.references.contact import DX, E, LOAD, NU, ellipse_fit, grid, hertz_case


@pytest.fixture(scope="module")
def wheel_rail():
    """Wheel radius 0.39 m on a 0.3 m rail crown, 65 kN, dx = dy = 0.35 mm."""
    X, Y, h, H = hertz_case(dx=0.35e-3, dy=0.35e-3)
    xi3, sol = approach_for_load(LOAD, h, 0.35e-3, 0.35e-3)
    return X, Y, h, H, xi3, sol


def test_hertz_semi_axes_peak_and_approach(wheel_rail):
    X, Y, h, H, xi3, sol = wheel_rail
    a, b, p0 = ellipse_fit(sol.p, X, Y)
    assert sol.converged and not sol.touches_edge
    assert a == pytest.approx(H.a, rel=0.02)
    assert b == pytest.approx(H.b, rel=0.02)
    assert sol.p.max() == pytest.approx(H.p0, rel=0.02)
    assert p0 == pytest.approx(H.p0, rel=0.02)
    assert xi3 == pytest.approx(H.delta, rel=0.02)
    assert sol.F3 == pytest.approx(LOAD, rel=1e-8)


def test_approach_load_relation_at_several_loads(wheel_rail):
    X, Y, h, H, _, _ = wheel_rail
    A, B = 1 / (2 * 0.39), 1 / (2 * 0.3)
    for load in (20e3, 45e3, 65e3, 90e3):
        delta = hertz(A, B, load).delta
        sol = norm(h, delta, 0.35e-3, 0.35e-3)
        assert sol.F3 == pytest.approx(load_for_approach(A, B, delta), rel=0.02)
        assert not sol.touches_edge or load > 80e3


def test_complementarity(wheel_rail):
    X, Y, h, H, xi3, sol = wheel_rail
    tol = 1e-8 * xi3
    assert (sol.p >= 0).all() and np.isfinite(sol.p).all()
    assert sol.d.min() >= -tol and sol.d[~sol.contact].min() > 0
    assert np.all(sol.p[~sol.contact] == 0) and np.abs(sol.d[sol.contact]).max() <= tol
    assert (sol.p[sol.contact] > 0).all()
    assert np.abs(sol.p * sol.d).max() <= tol * sol.p.max()


def test_loss_of_contact_gives_zero_force():
    X, Y, h, H = hertz_case(dx=1e-3, dy=1e-3)
    for xi3 in (-1e-4, -1e-9, 0.0):
        sol = norm(h + 1e-6, xi3, 1e-3, 1e-3)    # first contact at xi3 = 1e-6
        assert sol.F3 == 0.0 and not sol.contact.any()
        assert np.isfinite(sol.p).all() and np.isfinite(sol.d).all() and (sol.p == 0).all()
    sol = norm(h + 1e-6, 1e-6 + 1e-12, 1e-3, 1e-3)   # barely touching
    assert sol.converged and 0 <= sol.F3 < 1.0 and np.isfinite(sol.p).all()


def test_non_hertzian_two_lobes():
    """Two rail-head lobes 8 mm apart, the right one 5 um lower (touches later)."""
    dx = dy = 0.5e-3
    X, Y = grid(30, 56, dx, dy)
    h = X**2 / (2 * 0.39) + np.minimum((Y + 4e-3) ** 2 / (2 * 0.05), (Y - 4e-3) ** 2 / (2 * 0.08) + 5e-6)
    A = dense_matrix(normal_kernel(30, 56, dx, dy, E, NU))
    for xi3 in (3e-6, 2e-5, 5e-5):
        sol = norm(h, xi3, dx, dy)
        assert sol.converged
        # complementarity with u = A p from the dense influence matrix (not the solver's FFT)
        u = (A @ sol.p.ravel()).reshape(h.shape)
        d = h - xi3 + u
        assert (sol.p >= 0).all() and d.min() >= -1e-8 * xi3
        assert np.abs(sol.p * d).max() <= 1e-8 * xi3 * sol.p.max()
        assert np.allclose(d, sol.d, rtol=0, atol=1e-10 * xi3)
        assert sol.F3 == pytest.approx(sol.p.sum() * dx * dy)
        left, right = sol.p[:, Y[0] < 0].sum(), sol.p[:, Y[0] > 0].sum()
        assert left > 0 and (right > 0) == (xi3 > 5e-6)
        assert np.all(u[sol.contact] > 0)
    # the force rises monotonically with the approach
    F = [norm(h, x, dx, dy).F3 for x in np.linspace(0, 6e-5, 7)]
    assert np.all(np.diff(F) > 0)


def test_warm_start_gives_same_answer():
    X, Y, h, H = hertz_case(dx=0.5e-3, dy=0.5e-3)
    cold = norm(h, 0.8 * H.delta, DX, DX)
    warm = norm(h, 0.8 * H.delta, DX, DX, warm=norm(h, 0.75 * H.delta, DX, DX))
    assert np.array_equal(cold.contact, warm.contact)
    assert np.allclose(cold.p, warm.p, rtol=0, atol=1e-7 * cold.p.max())


def test_norm_table_interpolation():
    X, Y, h, H = hertz_case(dx=0.5e-3, dy=0.5e-3, margin=1.6)
    xs = np.linspace(0.0, 1.6 * H.delta, 17)
    tab = norm_table(h, xs, DX, DX)
    assert tab.F3[0] == 0 and np.all(np.diff(tab.F3) > 0)
    assert table_force(-1e-6, tab.xi3, tab.q) == 0.0
    for k in range(len(xs)):
        assert table_force(tab.xi3[k], tab.xi3, tab.q) == pytest.approx(tab.F3[k], rel=1e-12)
    err = table_midpoint_error(tab, h, DX, DX)
    assert np.nanmax(err["force"]) < 0.015                # F3^(2/3) is nearly linear in xi3
    work = err["xi3"] > 0.5 * H.delta                    # around the operating point
    assert err["force"][work].max() < 0.001              # docs/validation/30_contact.md: better than 0.1 %
    assert err["pressure"][work].max() < 0.15            # edge elements switch on between nodes
    assert err["pressure_rms"][work].max() < 0.03
    p = table_pressure(tab, err["xi3"][8])
    assert (p >= 0).all()
