"""Steady TANG with a slip-speed dependent friction law (solvers.contact.tang.falling): the
fixed point is Coulomb's law with the local coefficient mu(|s|) of the local slip speed;
a float or the 'coulomb' law is today's solver bit for bit."""
import numpy as np
import pytest

from solvers.contact.friction import rf_curve
from solvers.contact.friction_laws import get_friction_law
from solvers.contact.norm import approach_for_load
from solvers.contact.tang import tang_steady, tang_transient
from pipeline.validation.references.contact import V, hertz_case

DXY = 1e-3


@pytest.fixture(scope="module")
def contact():
    X, Y, h, H = hertz_case(dx=DXY, dy=DXY)
    _, ns = approach_for_load(65e3, h, DXY, DXY)
    return ns


@pytest.mark.parametrize("gammas", [(0.0, -2e-3, 0.0), (3e-3, 0.0, 0.0), (1e-3, -1e-3, 0.8), (0.0, -0.02, 0.5)])
def test_fixed_point_is_the_local_law(contact, gammas):
    law = get_friction_law("exponential", fkin=0.2, fexp1=0.15, sabsh1=100.0)
    gx, gy, sp = gammas
    sol = tang_steady(contact.p, DXY, DXY, V, law, gamma_x=gx, gamma_y=gy, spin=sp)
    assert sol.converged
    p3 = contact.p
    speed = np.hypot(sol.s1, sol.s2)
    pabs = np.hypot(sol.p1, sol.p2)
    bound = law.mu(speed) * p3
    slip = sol.slip & (speed > 0)
    assert slip.any()
    # slip elements: |p| = mu(|s|) p3 (the outer iteration's tolerance), opposite to the slip
    assert np.abs(pabs[slip] - bound[slip]).max() <= 2e-6 * bound.max()
    cos = (sol.p1 * sol.s1 + sol.p2 * sol.s2)[slip] / (pabs * speed)[slip]
    assert cos.max() <= -1 + 1e-6
    # stick elements: no slip, within the static bound mu(0) p3
    assert np.all(pabs[sol.stick] <= law.mu_static * p3[sol.stick] * (1 + 1e-9))
    # falling friction: every slip element is below its static bound
    assert np.all(bound[slip] < law.mu_static * p3[slip])


def test_constant_law_is_coulomb(contact):
    flat = get_friction_law("linear", fkin=0.3, flin1=0.0, sabsh1=100.0)
    a = tang_steady(contact.p, DXY, DXY, V, flat, gamma_y=-2e-3, spin=0.3)
    b = tang_steady(contact.p, DXY, DXY, V, 0.3, gamma_y=-2e-3, spin=0.3)
    assert a.F2 == pytest.approx(b.F2, rel=1e-7) and a.F1 == pytest.approx(b.F1, rel=1e-6, abs=1e-6 * abs(b.F2))
    assert np.array_equal(a.stick, b.stick)


def test_coulomb_law_is_todays_path_bit_for_bit(contact):
    law = get_friction_law("coulomb", mu=0.3)
    a = tang_steady(contact.p, DXY, DXY, V, law, gamma_x=1e-3, gamma_y=-2e-3, spin=0.5)
    b = tang_steady(contact.p, DXY, DXY, V, 0.3, gamma_x=1e-3, gamma_y=-2e-3, spin=0.5)
    assert np.array_equal(a.p1, b.p1) and np.array_equal(a.p2, b.p2) and a.F2 == b.F2
    ca, cb = rf_curve(contact.p, DXY, DXY, V, law), rf_curve(contact.p, DXY, DXY, V, 0.3)
    assert np.array_equal(ca.mu_rf, cb.mu_rf) and np.array_equal(ca.slope, cb.slope) and ca.law == law


@pytest.mark.parametrize("gammas", [(0.0, -2e-3, 0.0), (1e-3, -3e-3, 0.5)])
def test_transient_rolling_settles_on_the_steady_solution(contact, gammas):
    # transient TANG (CG, the bounds iterated per step) at constant creepage rolls into the steady
    # state that the steady solver (GMRES) finds: a second method for the same fixed point
    law = get_friction_law("polach", mu0=0.5, A=0.4, B=0.6)
    gx, gy, sp = gammas
    steady = tang_steady(contact.p, DXY, DXY, V, law, gamma_x=gx, gamma_y=gy, spin=sp)
    st = None
    for _ in range(100):
        st = tang_transient(contact.p, DXY, DXY, V, law, gamma_x=gx, gamma_y=gy, spin=sp, state=st)
    assert st.converged
    scale = np.abs(np.hypot(steady.p1, steady.p2)).max()
    assert np.abs(st.p1 - steady.p1).max() < 1e-6 * scale and np.abs(st.p2 - steady.p2).max() < 1e-6 * scale
    assert np.array_equal(st.stick, steady.stick)


def test_transient_coulomb_law_is_todays_path(contact):
    law = get_friction_law("coulomb", mu=0.3)
    a = b = None
    for k in range(5):
        a = tang_transient(contact.p, DXY, DXY, V, law, gamma_y=-2e-3 * (1 + 0.1 * k), state=a)
        b = tang_transient(contact.p, DXY, DXY, V, 0.3, gamma_y=-2e-3 * (1 + 0.1 * k), state=b)
    assert np.array_equal(a.p1, b.p1) and np.array_equal(a.p2, b.p2)


def test_falling_curve_rises_to_a_peak_and_falls(contact):
    law = get_friction_law("exponential", fkin=0.2, fexp1=0.15, sabsh1=100.0)
    c = rf_curve(contact.p, DXY, DXY, V, law)
    k = int(np.argmax(c.mu_rf))
    assert 0 < k < len(c.s) - 5
    assert np.all(np.diff(c.mu_rf[: k + 1]) > 0) and np.all(np.diff(c.mu_rf[k:]) < 0)
    assert c.mu_rf[k] < law.mu_static
    # at the ramp's end the contact slides whole: F2/F3 is the law's coefficient near the rigid
    # slip speed |gamma| v (the elastic part of the slip is small there)
    assert c.stick_fraction[-1] == 0.0
    assert c.mu_rf[-1] == pytest.approx(float(law.mu(c.s[-1])), rel=0.02)
    assert c.slope[-1] < 0 and c.law == law


def test_friction_memory_relaxes_exponentially_along_x():
    # CONTACT's memory in steady rolling: from the leading edge (high x, mu = mu(0)) the coefficient
    # relaxes towards mu_s(|s|) by the factor theta = d_c / (d_c + dt max(|s|, s_0)) per element
    from solvers.contact.tang.falling import coefficients

    law = get_friction_law("exponential", fkin=0.1, fexp1=0.25, sabsh1=20.0, memdst=0.003, mem_s0=1.0)
    nx, ny, dt, s = 12, 3, 2e-5, 0.05
    ix, iy = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    ix, iy = ix.ravel(), iy.ravel()
    mu = coefficients(law, np.full(ix.size, s), ix, iy, dt).reshape(nx, ny)
    theta = 3e-6 / (3e-6 + dt * s)
    k = nx - np.arange(nx)                    # elements passed since the leading edge, 1 at i = nx - 1
    mus = float(law.mu(s))
    want = mus + (law.mu_static - mus) * theta ** k
    np.testing.assert_allclose(mu, np.repeat(want[:, None], ny, axis=1), rtol=1e-13)
    # without memory: the law itself
    plain = get_friction_law("exponential", fkin=0.1, fexp1=0.25, sabsh1=20.0)
    assert np.array_equal(coefficients(plain, np.full(ix.size, s), ix, iy, dt), plain.mu(np.full(ix.size, s)))
    with pytest.raises(ValueError, match="transient TANG takes the instantaneous law"):
        tang_transient(np.ones((3, 3)), 1e-3, 1e-3, V, law, gamma_y=-1e-3)
