"""TANG (SPEC 4.5) against exact theory: Carter's 2D rolling solution, Kalker's linear
theory, full slip; Coulomb's law per element; transient -> steady state."""
import numpy as np
import pytest

from solvers.contact.norm import approach_for_load
from solvers.contact.tang import tang_steady, tang_transient
from pipeline.validation.references.hertz import curvature_ratio, hertz
from pipeline.validation.references.contact import G, V, carter_creepage, carter_traction, grid, hertz_case
from pipeline.validation.references.kalker import creep_coefficient

MU = 0.3


def elongated_contact(a_over_b=0.1, n_x=30, n_y=25, extra=5):
    """Hertz pressure on a long lateral strip (a/b = 0.1): the rolling-cylinder limit.
    extra odd: an element centre on x = 0; even: an element edge on x = 0."""
    H = hertz(1.0, curvature_ratio(1 / a_over_b), 1e5)      # B/A < 1: a (along x) short
    dx, dy = 2 * H.a / n_x, 2 * H.b / n_y
    X, Y = grid(n_x + extra, n_y + 4, dx, dy)
    return H, dx, dy, X, Y, H.pressure(X, Y)


@pytest.mark.parametrize("c_over_a,extra", [(0.3, 5), (0.7, 5), (0.5, 4)])
def test_carter_2d(c_over_a, extra):
    H, dx, dy, X, Y, p3 = elongated_contact(extra=extra)
    gx = carter_creepage(c_over_a, H.p0, MU, direction=1)
    sol = tang_steady(p3, dx, dy, V, MU, gamma_x=gx)
    assert sol.converged
    j0 = X.shape[1] // 2                                   # centre line y = 0
    x = X[:, j0]
    q = sol.p1[:, j0]
    ref = -carter_traction(x, H.a, H.p0, MU, c_over_a * H.a)
    inside = np.abs(x) < H.a
    rms = np.sqrt(np.mean((q - ref)[inside] ** 2)) / (MU * H.p0)
    force = q.sum() / (-MU * H.p0 * np.pi / 2 * H.a * (1 - c_over_a**2) / dx)
    assert rms < 0.03
    assert force == pytest.approx(1.0, abs=0.03)
    # slip zone at the trailing edge (x < 0): |p| = mu p3 there
    trailing = inside & (x < H.a - 2 * c_over_a * H.a - dx)
    assert sol.slip[trailing, j0].all()


@pytest.mark.parametrize("b_over_a", [0.5, 2.0])
def test_linear_theory_c22(b_over_a):
    """Initial slope of F2(gamma_y) = -c^2 G C22 (Kalker's table at nu = 0.3)."""
    H = hertz(1.0, curvature_ratio(b_over_a), 65e3)
    ne = 24
    dx, dy = 2 * H.a / ne, 2 * H.b / ne
    X, Y = grid(ne + 5, ne + 5, dx, dy)
    p3 = H.pressure(X, Y)
    s1 = tang_steady(p3, dx, dy, V, MU, gamma_y=1e-8)
    s2 = tang_steady(p3, dx, dy, V, MU, gamma_y=2e-8, warm=s1)
    assert s2.F2 / s1.F2 == pytest.approx(2.0, rel=1e-5)   # still the linear (no-slip) regime
    slope = (s2.F2 - s1.F2) / 1e-8
    C22 = creep_coefficient("C22", H.a, H.b, 0.3)
    assert -slope / (H.c**2 * G * C22) == pytest.approx(1.0, abs=0.05)


@pytest.fixture(scope="module")
def hertz_1mm():
    X, Y, h, H = hertz_case(dx=1e-3, dy=1e-3)
    _, ns = approach_for_load(65e3, h, 1e-3, 1e-3)
    return ns


def test_full_slip(hertz_1mm):
    ns = hertz_1mm
    for gx, gy in [(0.0, -0.05), (0.0, 0.03), (0.02, -0.03)]:
        sol = tang_steady(ns.p, 1e-3, 1e-3, V, MU, gamma_x=gx, gamma_y=gy)
        F = np.hypot(sol.F1, sol.F2)
        assert F == pytest.approx(MU * ns.F3, rel=2e-4)
        assert not sol.stick.any()
        # force on the rail opposes the rigid slip
        assert np.dot([sol.F1, sol.F2], [gx, gy]) / (F * np.hypot(gx, gy)) < -0.999


def test_coulomb_law_per_element(hertz_1mm):
    ns = hertz_1mm
    for gy in (2e-4, 0.002, -0.004):
        sol = tang_steady(ns.p, 1e-3, 1e-3, V, MU, gamma_x=3e-4, gamma_y=gy)
        pt = np.hypot(sol.p1, sol.p2)
        assert (pt <= MU * ns.p * (1 + 1e-8) + 1e-9).all()
        assert np.array_equal(sol.stick | sol.slip, ns.contact) and not (sol.stick & sol.slip).any()
        assert np.all(sol.s1[sol.stick] == 0) and np.all(sol.s2[sol.stick] == 0)
        sl = sol.slip
        assert np.allclose(pt[sl], MU * ns.p[sl], rtol=1e-8)
        cos = (sol.p1 * sol.s1 + sol.p2 * sol.s2)[sl] / (pt[sl] * np.hypot(sol.s1, sol.s2)[sl])
        assert (cos < -0.99999).all()                      # slip opposite to traction
        assert np.sign(sol.F2) == -np.sign(gy)             # force on the rail against the creepage


def test_spin_sign_and_magnitude():
    H = hertz(1.0, curvature_ratio(0.5), 65e3)
    ne = 24
    dx, dy = 2 * H.a / ne, 2 * H.b / ne
    X, Y = grid(ne + 5, ne + 5, dx, dy)
    phi = 1e-6 / H.c
    sol = tang_steady(H.pressure(X, Y), dx, dy, V, 1e6, spin=phi)
    C23 = -sol.F2 / (H.c**3 * G * phi)
    # the spin coefficient converges slowly with the grid (about -8 % at 24 elements)
    assert C23 / creep_coefficient("C23", H.a, H.b) == pytest.approx(1.0, abs=0.15)


def test_transient_converges_to_steady(hertz_1mm):
    ns = hertz_1mm
    args = (ns.p, 1e-3, 1e-3, V, MU)
    steady = tang_steady(*args, gamma_x=0.001, gamma_y=-0.002)
    state, errs = None, []
    for _ in range(80):
        state = tang_transient(*args, gamma_x=0.001, gamma_y=-0.002, state=state)
        errs.append(max(np.abs(state.p1 - steady.p1).max(), np.abs(state.p2 - steady.p2).max()))
    errs = np.array(errs) / (MU * ns.p.max())
    assert errs[0] > 0.3                          # the first step is far from steady state
    assert errs[-1] < 1e-5 and errs[-1] < errs[40] < errs[10]
    assert state.F2 == pytest.approx(steady.F2, rel=1e-5)


def test_transient_step_is_exact_for_its_own_kinematics(hertz_1mm):
    """One transient step: s = w + (u(t) - u(x + dx, t - dt)) / dt with u = A p."""
    ns = hertz_1mm
    dx = 1e-3
    prev = tang_steady(ns.p, dx, dx, V, MU, gamma_y=-0.001)
    sol = tang_transient(ns.p, dx, dx, V, MU, gamma_y=-0.003, state=prev)
    dt = dx / V
    ahead = np.vstack([prev.u2[1:], np.zeros((1, prev.u2.shape[1]))])   # u2(x + dx, t - dt)
    s2 = -0.003 * V + (sol.u2 - ahead) / dt
    c = ns.contact & (np.arange(ns.p.shape[0]) < ns.p.shape[0] - 1)[:, None]
    assert np.allclose(sol.s2[c], s2[c], rtol=0, atol=1e-8 * V * 0.003)


def test_loss_of_contact_and_no_friction(hertz_1mm):
    ns = hertz_1mm
    zero = tang_transient(np.zeros_like(ns.p), 1e-3, 1e-3, V, MU, gamma_y=-0.003)
    assert zero.F1 == 0 and zero.F2 == 0 and not zero.stick.any() and not zero.slip.any()
    after = tang_transient(ns.p, 1e-3, 1e-3, V, MU, gamma_y=-0.003, state=zero)
    assert after.converged and after.F2 > 0
    free = tang_steady(ns.p, 1e-3, 1e-3, V, 0.0, gamma_y=-0.003)
    assert free.F2 == 0 and free.slip.sum() == ns.contact.sum()
    assert np.allclose(free.s2[ns.contact], -0.003 * V)


# ----------------------------------------------------------------------------------------------
# the FFT-based solver against the dense reference, its operator, window and predictor
# ----------------------------------------------------------------------------------------------

def _small_contact(n=13):
    H = hertz(1.0, curvature_ratio(0.7), 65e3)
    dx, dy = 2.2 * H.a / n, 2.2 * H.b / n
    X, Y = grid(n, n, dx, dy)
    return H.pressure(X, Y), dx, dy


@pytest.mark.parametrize("kw", [dict(gamma_y=-0.002), dict(gamma_x=0.001, gamma_y=0.0015),
                                dict(gamma_y=-6e-4, spin=0.6 / 5.4e-3), dict(gamma_y=-0.02)])
def test_fft_solver_matches_dense_reference_steady(kw):
    from pipeline.validation.references.tang_dense import tang_dense

    p3, dx, dy = _small_contact()
    sol = tang_steady(p3, dx, dy, V, MU, tol=1e-12, **kw)
    P1, P2, St = tang_dense(p3, dx, dy, V, MU, **kw)
    scale = MU * p3.max()
    assert sol.converged
    assert np.abs(sol.p1 - P1).max() < 1e-8 * scale and np.abs(sol.p2 - P2).max() < 1e-8 * scale
    assert np.array_equal(sol.stick, St)


def test_fft_solver_matches_dense_reference_transient():
    from pipeline.validation.references.tang_dense import tang_dense

    p3, dx, dy = _small_contact()
    st, prev = None, None
    for k in range(6):
        gy = -0.003 * (1 + 0.5 * np.sin(k))
        st = tang_transient(p3, dx, dy, V, MU, gamma_x=2e-4, gamma_y=gy, state=st, tol=1e-12)
        P1, P2, St = tang_dense(p3, dx, dy, V, MU, gamma_x=2e-4, gamma_y=gy, steady=False, prev=prev)
        prev = (P1, P2)
        scale = MU * p3.max()
        assert np.abs(st.p1 - P1).max() < 1e-8 * scale and np.abs(st.p2 - P2).max() < 1e-8 * scale
        assert np.array_equal(st.stick, St)


def test_operator_products_equal_dense_matrices():
    """The FFT product gives A p on the grid and one row ahead, A(x + dx) p."""
    from solvers.contact.influence import dense_matrix, tangential_kernels
    from solvers.contact.tang import tangential_operator

    nx, ny, dx, dy = 9, 7, 0.5e-3, 0.4e-3
    rng = np.random.default_rng(3)
    P = rng.standard_normal((2, nx, ny))
    u = np.array(tangential_operator((nx, ny), dx, dy).displacements(P))
    for shift, rows in ((0, u[:, :nx]), (1, u[:, 1:])):
        K = [dense_matrix(k) for k in tangential_kernels(nx, ny, dx, dy, 210e9, 0.3, shift_x=shift)]
        ref1 = K[0] @ P[0].ravel() + K[1] @ P[1].ravel()
        ref2 = K[1] @ P[0].ravel() + K[2] @ P[1].ravel()
        assert np.allclose(rows[0].ravel(), ref1, rtol=0, atol=1e-12 * np.abs(ref1).max())
        assert np.allclose(rows[1].ravel(), ref2, rtol=0, atol=1e-12 * np.abs(ref2).max())


def test_window_output_and_predictor_do_not_change_the_answer(hertz_1mm):
    ns = hertz_1mm
    args = (ns.p, 1e-3, 1e-3, V, MU)
    full = tang_steady(*args, gamma_y=-0.003)
    win = tang_steady(*args, gamma_y=-0.003, full_output=False)
    assert np.abs(full.p2 - win.p2).max() < 1e-7 * MU * ns.p.max()
    i0, i1, j0, j1 = win.window
    assert np.allclose(win.u2[i0:i1 + 1, j0:j1 + 1], full.u2[i0:i1 + 1, j0:j1 + 1], rtol=0,
                       atol=1e-6 * np.abs(full.u2).max())
    # transient with the extrapolating predictor vs the same steps started from the plain previous state
    st = None
    for k in range(30):
        gy = -0.003 * (1 + 0.3 * np.sin(0.4 * k))
        st = tang_transient(*args, gamma_y=gy, state=st, tol=1e-10)
        plain = tang_transient(*args, gamma_y=-0.003 * (1 + 0.3 * np.sin(0.4 * (k + 1))),
                               state=st._replace(history=None), tol=1e-10)
        pred = tang_transient(*args, gamma_y=-0.003 * (1 + 0.3 * np.sin(0.4 * (k + 1))), state=st, tol=1e-10)
        assert abs(pred.F2 - plain.F2) <= 1e-8 * abs(plain.F2)
        assert np.abs(pred.p2 - plain.p2).max() < 1e-8 * MU * ns.p.max()


def test_spin_matches_contact_fastsim_case():
    """CONTACT's published FASTSIM example, case 1 (Vollebregt's CONTACT, examples/fastsim.inp and
    fastsim.ref_out): Hertz a = 8 mm, b = 4 mm, 82 kN, G = 82 GPa, nu = 0.28, mu = 0.3, steady rolling
    with eta = -6.25e-4 and spin 6.25e-4 /mm on 44 x 44 elements over 1.1 times the ellipse.  CONTACT
    (the exact theory, NORM + steady TANG): Fy / (mu Fn) = -0.6074, Mz = -4.821e4 N mm, 356 adhesion
    and 920 slip elements of 1276.  The rigid slip at x + dx/6 (W_OFFSET) is CONTACT's discretisation."""
    G28, NU28 = 82e9, 0.28
    E28 = 2 * G28 * (1 + NU28)
    m = 44
    dx, dy = 2 * 1.1 * 8e-3 / m, 2 * 1.1 * 4e-3 / m
    X, Y = grid(m, m, dx, dy)
    _, ns = approach_for_load(82e3, 0.8464 * X**2 + 2.406 * Y**2, dx, dy, E28, NU28)
    assert ns.contact.sum() == 1276
    sol = tang_steady(ns.p, dx, dy, 30.0, 0.3, gamma_y=-6.25e-4, spin=0.625, E=E28, nu=NU28)
    fy = sol.F2 / (0.3 * ns.F3)
    mz = (X * sol.p2 - Y * sol.p1).sum() * dx * dy * 1e3           # N mm
    assert fy == pytest.approx(-0.6074, rel=5e-3)
    assert mz == pytest.approx(-4.821e4, rel=5e-3)
    assert abs(int(sol.stick.sum()) - 356) <= 4 and abs(sol.F1) < 1e-6 * ns.F3


def test_slip_median_is_numpys():
    # the preconditioner's median of D over the slip elements (tang.kernels._median, a quickselect):
    # numpy's median exactly, for odd and even counts, ties and sorted input
    from solvers.contact.tang.kernels import _median

    rng = np.random.default_rng(7)
    for n in [*range(1, 30), 100, 101, 1000]:
        for rep in range(12):
            v = rng.standard_normal(n)
            v = np.round(v, 1) if rep % 3 == 0 else (np.sort(v) if rep % 3 == 1 else v)
            assert _median(v.copy()) == np.median(v)
