"""Falling friction in the regularized point contact (solvers/contact/falling.py, the tail of
friction.mu_and_slope): the curve against the law it is built from (full slip: the law itself;
an exponential tail equals an exponential law exactly), the derivative against finite
differences everywhere (the Newton solve and the screen use it), the point contact's solution
against its defining equations, and Coulomb curves unchanged."""
import numpy as np
import pytest

from solvers.contact.falling import is_falling, scaled_curve, tail_decay, tang_curve, with_tail
from solvers.contact.friction import monotone_slopes, mu_and_slope, mu_rf
from solvers.contact.friction_laws import get_friction_law
from solvers.timeloop.interaction import point_contact, simulate, static_approach, steady_forces
from pipeline.validation.references.interaction import CONTACT, DT, GAMMA_Y, PRELOAD, V, default_contact, hertz_contact

LAW = get_friction_law("polach", mu0=0.35, A=0.25 / 0.35, B=2.0)     # 0.35 -> 0.25, decay velocity 0.5 m/s


@pytest.fixture(scope="module")
def falling():
    c = hertz_contact(0.35)
    s, m, d = scaled_curve(c.s_nodes, c.mu_nodes, c.slopes, c.mu, LAW)
    return c, c._replace(s_nodes=s, mu_nodes=m, slopes=d)


def test_curve_is_the_law_in_full_slip_and_beyond_its_last_node(falling):
    """The Hertz stand-in's Coulomb curve is saturated from s = 0.1 m/s on: there the falling
    curve is mu_law(s) (to rounding), on the nodes, between them and on the tail up to 50 m/s."""
    c, f = falling
    assert is_falling(f.s_nodes) and not is_falling(c.s_nodes)
    s = np.concatenate([np.linspace(0.1, 0.7, 61), np.geomspace(0.7, 50.0, 40)])
    m = np.array([mu_rf(x, f.s_nodes, f.mu_nodes, f.slopes) for x in s])
    on_nodes = np.isin(s, f.s_nodes)
    assert np.abs(m - LAW.mu(s))[s >= 0.7].max() < 1e-9           # the tail: the law's exponential exactly
    assert np.abs(m - LAW.mu(s))[~on_nodes].max() < 2e-4           # Hermite between the nodes
    assert tail_decay(f.s_nodes, f.mu_nodes, f.slopes) == pytest.approx(0.5, rel=1e-9)


def test_derivative_is_the_slope_of_the_curve(falling):
    """d mu_RF / ds of mu_and_slope against central differences of mu_RF: rising branch, peak,
    falling branch, across the last finite node and on the tail."""
    _, f = falling
    s = np.concatenate([np.linspace(1e-4, 0.69, 300), [0.7 - 1e-7, 0.7 + 1e-7], np.geomspace(0.71, 20.0, 50)])
    h = 1e-7
    for x in s:
        d = mu_and_slope(x, f.s_nodes, f.mu_nodes, f.slopes)[1]
        num = (mu_rf(x + h, f.s_nodes, f.mu_nodes, f.slopes) - mu_rf(x - h, f.s_nodes, f.mu_nodes, f.slopes)) / (2 * h)
        assert abs(d - num) < 1e-5 * max(1.0, abs(num)), (x, d, num)


def test_shape_preserving_rise_peak_fall(falling):
    """No overshoot: the interpolant stays within the node values' range on every interval,
    rises up to the largest node and falls after it (PCHIP keeps the data's shape)."""
    _, f = falling
    s, m = f.s_nodes[:-1], f.mu_nodes[:-1]
    k = int(np.argmax(m))
    x = np.linspace(0.0, s[-1], 4001)
    y = np.array([mu_rf(t, f.s_nodes, f.mu_nodes, f.slopes) for t in x])
    assert y.max() <= m[k] + 1e-15
    assert np.all(np.diff(y[x <= s[k]]) >= -1e-15) and np.all(np.diff(y[x >= s[k]]) <= 1e-15)


def test_coulomb_curve_unchanged():
    """A Coulomb curve (no node at +inf) is constant with slope 0 beyond its last node, and the
    Hermite part is the former formula (same slopes with end_slope 0)."""
    c = hertz_contact(0.35)
    assert np.array_equal(monotone_slopes(c.s_nodes, c.mu_nodes), monotone_slopes(c.s_nodes, c.mu_nodes, 0.0))
    for x in (0.7, 0.71, 5.0, 1e6):
        assert mu_and_slope(x, c.s_nodes, c.mu_nodes, c.slopes) == (c.mu_nodes[-1], 0.0)


def test_tail_needs_a_falling_end():
    with pytest.raises(ValueError):
        with_tail([0.0, 0.1], [0.0, 0.3], 0.1, 0.2)


def test_point_contact_on_the_falling_branch_solves_its_equations(falling):
    """s_tau = b_tau + c_tau F_tau and F = -mu_RF(|s|) F3 s / |s| at slips on the falling branch,
    with c_1 != c_2 (traction and lateral creepage)."""
    _, f = falling
    c1, c2, F3 = 1.26e-9 / DT, 1.15e-9 / DT, PRELOAD
    for b1, b2 in ((0.0, -0.3), (0.05, -0.25), (-0.2, -0.6), (0.4, -0.05), (0.0, -2.0)):
        F1, F2, s1, s2, sig, it, nb = point_contact(b1, b2, c1, c2, F3, f.s_nodes, f.mu_nodes, f.slopes, 0.0, 0.0)
        m = mu_rf(sig, f.s_nodes, f.mu_nodes, f.slopes)
        assert sig == pytest.approx(np.hypot(s1, s2), rel=1e-12)
        assert s1 == pytest.approx(b1 + c1 * F1, abs=1e-12) and s2 == pytest.approx(b2 + c2 * F2, abs=1e-12)
        assert F1 == pytest.approx(-m * F3 * s1 / sig, abs=1e-6) and F2 == pytest.approx(-m * F3 * s2 / sig, abs=1e-6)


def test_steady_rolling_with_a_falling_law_is_an_equilibrium(falling):
    """Without structures and kick the loop stays at the steady forces of the falling curve, with
    traction (gamma_x) and lateral creepage: F1, F2 = -mu_RF(|w|) F3 w / |w|."""
    _, f = falling
    r = simulate(None, None, f, dt=DT, v=V, gamma_y=GAMMA_Y, gamma_x=0.004, preload=PRELOAD, duration=0.01,
                 stop=None, kick=0.0)
    ref = steady_forces(f, V, 0.004, GAMMA_Y, PRELOAD)
    assert np.abs(r.F - ref).max() < 1e-6 * PRELOAD
    assert ref[1] > 0 and ref[0] < 0


def test_tang_curve_and_the_scaled_approximation():
    """On the default contact: TANG's global curve of the falling law (friction.rf_curve with the
    law, the tail from the law) against the Coulomb curve scaled by mu_law(s) / mu: within 0.003 in
    mu_RF, and the falling branch's slope within 5 % from the peak on (0.12 m/s) -- the operating
    slip of the default case is 0.19 m/s; both continue with the law beyond the last node."""
    if not CONTACT.exists():
        pytest.skip("needs build/cases/default/contact.npz (make contact)")
    from solvers.contact.norm import NormTable, table_pressure

    c = default_contact(0.35)
    p3 = table_pressure(NormTable(c.xi3_nodes, c.F3_nodes, c.q_nodes, c.pressure_nodes, c.pressure_nodes > 0),
                        static_approach(c, PRELOAD))
    t = tang_curve(p3, c.dx, c.dy, V, LAW)
    a = scaled_curve(c.s_nodes, c.mu_nodes, c.slopes, c.mu, LAW)
    assert is_falling(t[0]) and is_falling(a[0])
    for x in np.concatenate([np.linspace(0.005, 0.69, 60), [1.0, 2.0, 5.0]]):
        mt, dt_ = mu_and_slope(x, *t)
        ma, da = mu_and_slope(x, *a)
        assert abs(mt - ma) < 3e-3, (x, mt, ma)
        if x >= 0.12:
            assert da == pytest.approx(dt_, rel=0.05), (x, dt_, da)


def test_kalker_loop_needs_the_law_of_a_falling_curve(falling):
    """Without its law a falling curve would run Coulomb friction in Kalker's TANG: refused."""
    _, f = falling
    with pytest.raises(ValueError, match="friction law of a falling curve"):
        simulate(None, None, f, dt=DT, v=V, gamma_y=GAMMA_Y, duration=0.001, tangential="kalker")


def test_kalker_loop_with_a_falling_law_starts_in_steady_state():
    """Kalker's loop with the law (ContactModel.law, as contact_model sets it): transient TANG with
    the local falling law, started from steady TANG with the law, stays there (no structures, no
    kick), with traction and spin."""
    if not CONTACT.exists():
        pytest.skip("needs build/cases/default/contact.npz (make contact)")
    from solvers.contact.norm import NormTable, table_pressure
    from solvers.contact.tang import tang_steady

    c = default_contact(0.35)
    app = static_approach(c, PRELOAD)
    p3 = table_pressure(NormTable(c.xi3_nodes, c.F3_nodes, c.q_nodes, c.pressure_nodes, c.pressure_nodes > 0), app)
    f = c._replace(law=LAW)
    kw = dict(gamma_x=0.002, gamma_y=GAMMA_Y, spin=0.5)
    r = simulate(None, None, f, dt=DT, v=V, preload=PRELOAD, duration=20 * DT, stop=None, kick=0.0,
                 tangential="kalker", **kw)
    sol = tang_steady(p3, c.dx, c.dy, V, LAW, full_output=False, **kw)
    coul = tang_steady(p3, c.dx, c.dy, V, 0.35, full_output=False, **kw)
    assert np.abs(r.F[:, 1] - sol.F2).max() < 2e-3 * PRELOAD and np.abs(r.F[:, 0] - sol.F1).max() < 2e-3 * PRELOAD
    assert abs(sol.F2 - coul.F2) > 0.02 * PRELOAD          # the law acts (Coulomb's force is 0.35 F3)
