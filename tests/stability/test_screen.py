"""solvers/stability/screen.py: the linearised time loop.  Checked against (1) the direct z-transform
sums of the kernels it replaces by closed forms, (2) the one-mode, full-slip closed form of the
interaction validation (kappa_r = Phi3 (Phi3 + mu Phi2)), and (3) growth rates MEASURED in the
time loop (numba driver, complex demodulation of F2), a second method that shares only the
inputs."""
import numpy as np
import pytest

from solvers.greens.kernels import modal_kernel
from solvers.timeloop.interaction import WheelModes, simulate
from solvers.stability.screen import (Basis, LinearModel, linearise, rail_receptance_z, screen, track_roots, wheel_receptance_z,
                               wheel_roots)
from pipeline.validation.references.interaction import DT, GAMMA_Y, PRELOAD, V, decay_rates, hertz_contact, reduced_squealer


def test_wheel_transform_is_the_modal_filters_kernel():
    """Closed-form Y^W(z) (lightly damped, critically and over-damped modes) = sum_k g[k] z^-k of
    the sampled modal kernel, at stable and unstable s."""
    f = np.array([430.0, 1150.0, 1586.0, 9.7, 60.0])
    m = np.array([40.0, 35.0, 30.0, 1000.0, 300.0])
    z = np.array([1e-2, 3e-3, 1.0, 2.0, 0.2])
    phi = np.array([[1, -0.1], [1, -0.05], [0.2, 1], [-0.5, 1], [0.3, 0.8]])
    K = 200_000
    g = modal_kernel(K, DT, f, m, z, phi)
    mod = LinearModel(f, m, z, phi, np.zeros((2, 2, 2)), DT, 1.0, 0.0, 0.0, 1.0, 0.0)
    for s in (complex(5, 2 * np.pi * 400), complex(-3, 2 * np.pi * 1000), complex(20, 2 * np.pi * 70)):
        Z = np.exp(s * DT)
        direct = np.einsum("k,kij->ij", Z ** (-np.arange(K, dtype=float)), g)
        assert np.abs(wheel_receptance_z(mod, Z) - direct).max() <= 1e-10 * np.abs(direct).max()


def test_rail_transform_skips_the_instantaneous_term():
    g = np.random.default_rng(1).normal(size=(64, 2, 2))
    z = np.exp(complex(3.0, 2 * np.pi * 200) * DT)
    assert np.allclose(rail_receptance_z(g, z), sum(g[k] * z ** -k for k in range(1, 64)), rtol=1e-12)


def test_one_mode_limit_is_the_closed_form():
    """One lightly damped mode on a rigid rail in full slip: m (w^2 - W^2 + 2i zeta w W) +
    kappa k_eff = 0 with k_eff = k_c (rigid rail, one mode): sigma = -zeta w - kappa Im(..)/2mw
    has Im k_eff = 0 here, so the root is the mode with stiffness k_c kappa added; the screen's
    root of the discrete loop matches the continuous one to O(w dt)^2."""
    f, m, zeta, mu, kc = 1000.0, 30.0, 1e-3, 0.35, 2e6
    phi = np.array([[1.0, -0.1]])
    lm = LinearModel(np.array([f]), np.array([m]), np.array([zeta]), phi, np.zeros((2, 2, 2)), 1e-6, kc, mu, 0.0,
                     PRELOAD, 0.0)
    r = wheel_roots(lm)[0]
    kap = phi[0, 1] * (phi[0, 1] + mu * phi[0, 0])
    w2 = (2 * np.pi * f) ** 2 + kap * kc / m
    # continuous closed loop: s^2 + 2 zeta w s + w2 = 0 (the contact spring adds kappa k_c)
    s = -zeta * 2 * np.pi * f + 1j * np.sqrt(w2 - (zeta * 2 * np.pi * f) ** 2)
    assert r.f_hz == pytest.approx(s.imag / (2 * np.pi), rel=2e-3)
    assert r.sigma == pytest.approx(s.real, rel=0.02)


@pytest.fixture(scope="module")
def squealer_run():
    """The reduced squealer (C20 (2,0,a) + (3,0,a) at y^W = -5 mm on the beam rail, the analytic
    Hertzian contact table) in the time loop, its growth phase measured.  (With the default case's
    worn-profile contact table the time loop's (2,0,a) does not grow at one rate -- 6.7/s measured
    from 0.05 s, 0.7/s from 0.15 s -- against the screen's 11.5/s, while (3,0,a) grows at 17.0 against
    19.6/s: not explained yet; the screen's A2' term (the compliance following the approach) is
    included and negligible there.)"""
    wheel, g = reduced_squealer(DT)
    c = hertz_contact(0.35)
    r = simulate(wheel, g, c, dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD, duration=0.45, stop=None, final=0.45)
    rates, _ = decay_rates(r.F_final[:, 1], DT, wheel.f_r, t0=0.05, window=0.05)
    return wheel, g, c, rates


def test_screen_growth_rates_match_the_time_loop(squealer_run):
    wheel, g, c, measured = squealer_run
    lm = linearise(wheel, g, c, dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD)
    roots = {r.mode: r for r in wheel_roots(lm)}
    for i in range(len(wheel.f_r)):
        assert roots[i].sigma == pytest.approx(measured[i], rel=0.05, abs=0.2), (i, roots[i], measured)
    assert all(r.sigma < 0 for r in track_roots(lm, Basis(lm, f_hi=300.0)))


def test_shared_basis_roots_match_the_exact_roots(squealer_run):
    """The first-order expansion of the rest of Y about each pole (maps) against the exact roots:
    the unstable poles agree to 2e-4 of their growth rate and 1e-3 Hz."""
    wheel, g, c, _ = squealer_run
    lm = linearise(wheel, g, c, dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD)
    b = Basis(lm)
    exact = {r.mode: r for r in screen(lm, b)}
    for r in screen(lm, b, polish=False):
        if r.mode >= 0 and r.sigma > 0:
            assert abs(r.sigma - exact[r.mode].sigma) < 2e-4 * abs(r.sigma) and abs(r.f_hz - exact[r.mode].f_hz) < 1e-3


@pytest.fixture(scope="module")
def falling_squealer():
    """The reduced squealer with a falling law (Polach's, 0.35 -> 0.25, 1/B = 0.5 m/s: slope
    -0.13 s/m at the operating slip) and with traction and spin (gamma_x = 0.004, spin 0.5/m with
    spin lengths (0, 2.5 mm), the default contact's size)."""
    from solvers.contact.falling import scaled_curve
    from solvers.contact.friction_laws import get_friction_law

    wheel, g = reduced_squealer(DT)
    c = hertz_contact(0.35)
    s, m, d = scaled_curve(c.s_nodes, c.mu_nodes, c.slopes, c.mu,
                           get_friction_law("polach", mu0=0.35, A=0.25 / 0.35, B=2.0))
    return wheel, g, c._replace(s_nodes=s, mu_nodes=m, slopes=d, spin_length=np.array([0.0, 2.5e-3]))


@pytest.mark.parametrize("extra", [{}, {"gamma_x": 0.004, "spin": 0.5}], ids=["lateral", "traction+spin"])
def test_screen_carries_the_falling_slope(falling_squealer, extra):
    """A falling slope feeds energy in: the screen's growth rates rise against Coulomb's (the
    same modes, same creepages) and match those measured in the time loop (matrix pencil, pipeline/validation/references/growth.py)
    to 2 %; with traction and spin (both tangential directions, e1 != 0) as well."""
    from pipeline.validation.references.growth import linear_phase, pencil_growth

    wheel, g, c = falling_squealer
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD, **extra)
    lm = linearise(wheel, g, c, **kw)
    assert lm.dmu < -0.1 and (lm.e1 != 0.0) == bool(extra)
    coulomb = hertz_contact(0.35)._replace(spin_length=c.spin_length)
    coul = {r.mode: r.sigma for r in wheel_roots(linearise(wheel, g, coulomb, **kw))}
    r = simulate(wheel, g, c, duration=0.3, stop=None, final=0.3, kick=(1e-12, 0.0), **kw)
    F2 = linear_phase(r.F_final[:, 1])
    for root in wheel_roots(lm):
        assert root.sigma > coul[root.mode] + 10.0
        assert pencil_growth(F2, DT, root.f_hz) == pytest.approx(root.sigma, rel=0.02), root
