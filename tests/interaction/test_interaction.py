"""The time stepper (solvers/timeloop/interaction.py): friction-curve ramp without structural dynamics,
decay of a stable case to the steady forces, a squealing reduced model and its convergence in
dt, per-step NORM against the table, the Python reference loop against the numba loop, loss
of contact, Kalker's transient TANG as the tangential model, the slip-velocity sign."""

import numpy as np
import pytest

from solvers.contact.friction import mu_rf
from solvers.contact.norm import table_force
from solvers.timeloop.interaction import WheelModes, refine_table, simulate
from pipeline.validation.references.interaction import (DT, GAMMA_Y, PRELOAD, ROOT, V, default_contact, hertz_contact, reduced_squealer)


@pytest.fixture(scope="module")
def contact():
    return default_contact(0.35)


@pytest.fixture(scope="module")
def squealer():
    return {dt: reduced_squealer(dt) for dt in (DT, DT / 2)}


def _ramp(duration, gamma_end=-0.05, dt=DT):
    n = int(round(duration / dt))
    return gamma_end * np.arange(n) / n


def test_ramp_reproduces_the_friction_curve(contact):
    """Zero kernels, the thesis' ramp gamma_y = -0.05 t / 2 s [4.36]: F2/F3 is mu_RF of the slip
    (to rounding); against the rigid slip |gamma_y| v it lags by the contact spring,
    s = w + A2 dF2/dt, to first order mu_RF(|w|) - mu_RF'(|w|) A2 dF2/dt; a four times slower
    ramp stays within 1e-3 of mu_RF(|gamma_y| v)."""
    c = contact
    gy = _ramp(2.0)
    r = simulate(None, None, c, dt=DT, v=V, gamma_y=gy, duration=2.0, stop=None, final=0)
    assert r.n_steps == len(gy) and np.all(np.isfinite(r.F))
    ratio = r.F[:, 1] / r.F[:, 2]
    own = np.array([mu_rf(s, c.s_nodes, c.mu_nodes, c.slopes) for s in np.hypot(*r.slip.T)])
    assert np.abs(ratio - own).max() < 1e-10
    assert np.abs(r.F[:, 2] - PRELOAD).max() < 1e-9 * PRELOAD and np.abs(r.F[:, 0]).max() == 0.0
    w = np.abs(gy) * V
    rigid = np.array([mu_rf(s, c.s_nodes, c.mu_nodes, c.slopes) for s in w])
    from solvers.timeloop.interaction import mu_and_slope
    from solvers.contact.compliance import table_compliance
    A2 = table_compliance(r.xi3_static, c.xi3_nodes, c.A2_nodes)
    dF2 = np.gradient(r.F[:, 1], DT)
    first = rigid - np.array([mu_and_slope(s, c.s_nodes, c.mu_nodes, c.slopes)[1] for s in w]) * A2 * dF2
    lag = np.abs(ratio - rigid)
    assert 1e-3 < lag.max() < 3e-3                       # the contact spring's lag at 2 s ramp time
    assert np.abs(ratio - first)[10:].max() < 0.05 * lag.max()
    slow = simulate(None, None, c, dt=DT, v=V, gamma_y=_ramp(8.0), duration=8.0, stop=None, final=0,
                    store_every=7)
    ws = np.abs(_ramp(8.0)[::7]) * V
    rigid = np.array([mu_rf(s, c.s_nodes, c.mu_nodes, c.slopes) for s in ws])
    assert np.abs(slow.F[:, 1] / slow.F[:, 2] - rigid).max() < 1e-3


@pytest.mark.parametrize("mu, gamma_y", [(0.35, -GAMMA_Y), (0.35, -0.002)])
def test_stable_case_decays_to_the_steady_force(squealer, mu, gamma_y):
    """Creepage of the opposite sign (full slip with F2 < 0: the coupling kappa = Phi_3 (Phi_3 -
    mu Phi_2) > 0 turns stabilising) or small creepage (the
    micro-slip slope damps the lateral motion): the kick dies out, the run stops as 'decayed'
    at F2 = -sign(gamma_y) mu_RF(|gamma_y| v) F3, F3 = preload."""
    wheel, g = squealer[DT]
    c = default_contact(mu)
    r = simulate(wheel, g, c, dt=DT, v=V, gamma_y=gamma_y, duration=8.0, kick=(0.025, 0.025))
    assert r.stop_reason == "decayed", r.windows[-3:]
    assert r.duration < 8.0 and r.lost_steps == 0
    F2s = -np.sign(gamma_y) * mu_rf(abs(gamma_y) * V, c.s_nodes, c.mu_nodes, c.slopes) * PRELOAD
    last = r.F_final[-1]
    assert abs(last[1] - F2s) < 1e-5 * PRELOAD and abs(last[2] - PRELOAD) < 1e-5 * PRELOAD
    assert abs(r.F_ref[1] - F2s) < 1e-9 * PRELOAD
    assert r.windows[-1, 2] < 1e-6 * PRELOAD < r.windows[0, 2]


def test_reduced_model_squeals_and_converges_in_dt(contact, squealer):
    """Halving dt (dx = v dt, wheel filters and rail kernel rebuilt): L_F2 within 1 dB and the
    squeal frequency within 0.5 %; early stop at a limit cycle; decimated storage."""
    out = {}
    for dt in (DT, DT / 2):
        wheel, g = squealer[dt]
        r = simulate(wheel, g, contact, dt=dt, v=V, gamma_y=GAMMA_Y, duration=4.0)
        assert r.stop_reason == "limit cycle" and r.duration < 3.0
        m = r.measures()
        assert m["L_F2"] > 40 and np.all(np.isfinite(r.F_final))
        out[dt] = m
    a, b = out[DT], out[DT / 2]
    assert abs(a["L_F2"] - b["L_F2"]) < 1.0
    assert abs(a["f_dominant"] / b["f_dominant"] - 1) < 5e-3
    wheel = squealer[DT][0]                        # at one of its two modes
    assert np.abs(a["f_dominant"] / wheel.f_r - 1).min() < 0.01, (a["f_dominant"], wheel.f_r)
    # decimated history: the same run, every 10th step kept, the final stretch at full rate
    wheel, g = squealer[DT]
    full = simulate(wheel, g, contact, dt=DT, v=V, gamma_y=GAMMA_Y, duration=1.0, stop=None, final=0.2)
    dec = simulate(wheel, g, contact, dt=DT, v=V, gamma_y=GAMMA_Y, duration=1.0, stop=None, final=0.2,
                   store_every=10)
    assert np.array_equal(dec.F, full.F[::10]) and np.array_equal(dec.F_final, full.F_final)
    assert np.array_equal(dec.F_final, full.F[-len(dec.F_final):]) and len(dec.F_final) == round(0.2 / DT)
    assert np.allclose(dec.t_final, full.t[-len(dec.t_final):])


def test_python_reference_loop_equals_the_numba_loop(contact, squealer):
    wheel, g = squealer[DT]
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=300 * DT, stop=None, kick=(0.07, 0.18))
    a = simulate(wheel, g, contact, **kw)
    b = simulate(wheel, g, contact, driver="python", **kw)
    assert np.abs(a.F - b.F).max() < 1e-9 * PRELOAD
    assert np.abs(a.xi - b.xi).max() < 1e-9 * np.abs(a.xi).max()


def test_table_and_per_step_norm_agree(contact, squealer):
    """Per-step NORM (Python reference loop) against the table: to the table's interpolation error,
    ~1e-5 with the contact stage's 41 nodes, < 1e-6 with the table refined over the visited range
    (node step 5e-4 of the static approach: with 1e-3, the step where a grid element enters the
    patch left 1.4e-6 on the refitted C20's contact)."""
    if contact.gap is None:
        pytest.skip("needs the built contact (gap)")
    wheel, g = squealer[DT]
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=120 * DT, stop=None, kick=(0.07, 0.18))
    a = simulate(wheel, g, contact, **kw)
    n = simulate(wheel, g, contact, normal="norm", **kw)
    app = a.xi3_static - a.xi[:, 1]
    assert app.max() - app.min() > 2e-3 * a.xi3_static           # F3 varies by ~1 %
    assert np.abs(n.F[:, 2] - a.F[:, 2]).max() < 1e-4 * PRELOAD
    x0 = a.xi3_static
    fine = refine_table(contact, np.linspace(0.97 * x0, 1.03 * x0, 121))
    a2 = simulate(wheel, g, fine, **kw)
    n2 = simulate(wheel, g, fine, normal="norm", **kw)
    rel = np.abs(n2.F[:, 2] - a2.F[:, 2]) / a2.F[:, 2]
    assert rel.max() < 1e-6
    assert abs(table_force(x0, fine.xi3_nodes, fine.q_nodes) / PRELOAD - 1) < 1e-6


def test_loss_of_contact_gives_zero_force_and_recontact():
    """A vertical blow (72 N s) lifts a one-mode wheel off the rail: F = 0 exactly while the approach is
    negative, no NaN, contact found again."""
    c = hertz_contact(0.35)
    wheel = WheelModes(np.array([100.0]), np.array([50.0]), np.array([0.05]), np.array([[0.3, 1.0]]))
    r = simulate(wheel, None, c, dt=DT, v=V, gamma_y=GAMMA_Y, duration=0.3, stop=None, final=0.3,
                 kick=(0.0, 72.0))
    F, st = r.F_final, r.state_final
    assert np.all(np.isfinite(F)) and np.all(np.isfinite(r.slip_final)) and np.all(np.isfinite(r.xi_final))
    lost = st == 0
    assert lost.sum() > 50 and r.lost_steps == lost.sum()
    assert np.all(F[lost] == 0.0)
    assert np.all(F[~lost, 2] > 0)
    app = r.xi3_static - r.xi_final[:, 1]
    assert np.all(app[lost] <= c.xi3_nodes[0]) and np.all(app[~lost] > c.xi3_nodes[0])
    back = np.flatnonzero(np.diff(lost.astype(int)) == -1)        # re-contact events
    assert len(back) >= 1 and not lost[-1]


def test_kalker_transient_as_the_tangential_model(contact, squealer):
    """Kalker's transient TANG per step (reference model) against the point model on a short
    run in full slip (they share the steady state: the friction curve is TANG's)."""
    if contact.pressure_nodes is None:
        pytest.skip("needs the built contact (pressure fields)")
    wheel, g = squealer[DT]
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=25 * DT, stop=None, kick=(0.07, 0.07))
    p = simulate(wheel, g, contact, **kw)
    k = simulate(wheel, g, contact, tangential="kalker", **kw)     # its cost: make bench ("Interaction")
    assert np.all(np.isfinite(k.F)) and np.all(k.state == 2)       # full slip throughout
    assert abs(k.F_ref[1] / p.F_ref[1] - 1) < 1e-3
    assert np.abs(k.F[:, 1] - p.F[:, 1]).max() < 1e-3 * p.F_ref[1]
    assert np.abs(k.F[:, 2] - p.F[:, 2]).max() < 1e-3 * PRELOAD


def test_kalker_compiled_steps_are_the_python_steps(contact, squealer, monkeypatch):
    """The reference driver's compiled Kalker steps (timeloop/kalker.py) give the records of its
    Python step bit for bit (the Python driver taking every step)."""
    if contact.pressure_nodes is None:
        pytest.skip("needs the built contact (pressure fields)")
    from solvers.timeloop import reference
    wheel, g = squealer[DT]
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=300 * DT, stop=None, kick=(0.07, 0.07), tangential="kalker")
    k = simulate(wheel, g, contact, **kw)
    monkeypatch.setattr(reference, "kalker_steps", lambda n, *args: (n, None, 0, None, None, 0))
    py = simulate(wheel, g, contact, **kw)
    for a, b in ((k.F, py.F), (k.slip, py.slip), (k.xi, py.xi), (k.state, py.state)):
        assert np.array_equal(a, b)
    assert k.newton == py.newton


@pytest.mark.parametrize("sign, grows", [(1.0, False), (-1.0, True)])
def test_slip_sign_energy_argument(sign, grows):
    """A lightly damped purely lateral wheel mode in micro-slip (gamma_y = -0.002, rising mu_RF):
    with the structural term entering the slip like the contact deformation (+, default) the
    friction slope damps it; with the sign printed in [4.30] (-) it is a negative damper."""
    c = hertz_contact(0.35)
    wheel = WheelModes(np.array([1161.4]), np.array([35.3]), np.array([1e-4]), np.array([[0.8, 0.0]]))
    r = simulate(wheel, None, c, dt=DT, v=V, gamma_y=-0.002, duration=0.02, stop=None, final=0.02,
                 kick=(2e-3, 0.0), slip_sign=sign)
    x = r.F_final[:, 1]
    early, later = np.std(x[:50]), np.std(x[400:450])      # rates of about +-300 1/s
    assert (later > 10 * early) == grows and (later < 0.1 * early) == (not grows)


def test_argument_checks(contact):
    with pytest.raises(ValueError):
        simulate(None, None, contact, dt=DT, v=V, gamma_y=GAMMA_Y, duration=8.5)
    with pytest.raises(ValueError):
        simulate(None, None, contact, dt=DT, v=V, gamma_y=GAMMA_Y, duration=0.01, tangential="tang")
    with pytest.raises(ValueError):
        simulate(None, None, contact, dt=DT, v=V, gamma_y=np.zeros(5), duration=0.01)
    with pytest.raises(ValueError):
        simulate(None, np.zeros((10, 3)), contact, dt=DT, v=V, gamma_y=GAMMA_Y, duration=0.01)


GREENS = ROOT / "build" / "cases" / "default" / "greens.npz"


@pytest.mark.skipif(not GREENS.exists(), reason="needs build/cases/default/greens.npz (make greens)")
def test_partitioned_rail_convolution_equals_direct_in_the_default_case(contact):
    """The default case (C20 modes, BV50 moving kernel of 4096 lags) squealing: the rail's
    partitioned FFT convolution (the default) and the direct sum (rail_block=None) give the same
    force histories to 1e-9 and the same squeal measures."""
    with np.load(GREENS) as d:
        wheel = WheelModes(d["wheel_f"], d["wheel_mass"], d["wheel_zeta"], d["wheel_phi"])
        g = d["rail_kernel"]
    kw = dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=0.6, stop=None, final=0.2, kick=(0.5, 0.0))
    fast = simulate(wheel, g, contact, **kw)
    direct = simulate(wheel, g, contact, rail_block=None, **kw)
    scale = np.abs(direct.F_final[:, 1] - direct.F_final[:, 1].mean()).max()
    assert scale > 1.0                                    # the squeal has started: a real test
    assert np.abs(fast.F - direct.F).max() < 1e-9 * PRELOAD
    assert np.abs(fast.xi - direct.xi).max() < 1e-9 * np.abs(direct.xi).max()
    a, b = fast.measures(), direct.measures()
    assert abs(a["L_F2"] - b["L_F2"]) < 1e-6 and abs(a["f_dominant"] - b["f_dominant"]) <= 1e-12 * b["f_dominant"]
