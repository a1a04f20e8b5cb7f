"""Sound power [4.38] with the velocities [4.54]-[4.57]: a single mode driven at
resonance against rho c0 sigma S <v^2> from the analytic SDOF response, the
harmonic separation, the mean-square factors and the band integral."""
import numpy as np
import pytest

from solvers.radiation.thompson_jones import C0, RHO_AIR, frequency_grid, sigma_axial, sigma_radial
from solvers.wheel.receptance import modal_damping, modal_frf
from pipeline.validation.references.node_average import sound_power, unit_force_power
from pipeline.validation.references.radiation import SHAPE, setup

PI = np.pi


def test_single_mode_at_resonance_lateral():
    modes, s, nodes, zeta = setup(zeta=1e-4)
    assert modal_damping(modes["n"], [0], modes["cls"], modes["kind"], modes["zeta_suspension"]) == pytest.approx(1e-4)
    f_r, m_r, w = 1000.0, 20.0, 2 * PI * 1000.0
    res = sound_power([f_r], 1.0, 0.0, modes, s, nodes, contact=0)
    # analytic SDOF response at resonance: v_i = i w U_i U_c F / (m i 2 zeta w^2) = U_i U_c F / (2 m zeta w)
    amp = 1.0 * 1.0 / (2 * m_r * zeta * w)  # U_c,z = 1, F2 = 1 N
    # annuli of the flat disc: [0.10,0.1575) node 1; [0.1575,0.215) node 2; [0.215,0.2725) node 3;
    # [0.2725,0.33) node 4; [0.33,0.40] node 5 (axial velocity U_z); radial: nodes 0 and 6 (U_r)
    v2a = 0.5 * (amp * np.array([0.05, 0.2, 0.5, 0.8, 0.9])) ** 2  # n = 2: circumferential mean 1/2
    v2r = 0.5 * (amp**2) * (0.3**2 + 0.25**2) / 2
    W = RHO_AIR * C0 * (sigma_axial(2, f_r, 0.40) * np.dot(s.S_a, v2a) + sigma_radial(2, f_r, 0.40, s.gamma) * s.S_r * v2r)
    assert res.W[0] == pytest.approx(W, rel=1e-2)
    assert res.W[0] == pytest.approx(W, rel=1e-9)  # the modal sum is exact for one mode
    np.testing.assert_allclose(res.v2_axial[0, :, 0], v2a, rtol=1e-9)
    assert res.L_W == pytest.approx(10 * np.log10(W / 1e-12), abs=1e-9)
    assert res.f_dominant == f_r


def test_single_mode_vertical_force_and_n0_factor():
    modes, s, nodes, zeta = setup(n=0, zeta=None)
    f_r, m_r, w = 1000.0, 20.0, 2 * PI * 1000.0
    z0 = modal_damping([0], [0], ["a"], ["flexible"], [np.nan])[0]
    assert z0 == 1e-3
    res = sound_power([f_r], 0.0, 2.0, modes, s, nodes, contact=0)
    amp = 0.3 * 2.0 / (2 * m_r * z0 * w)  # U_c,r = 0.3, F3 = 2 N
    v2a = (amp * np.array([0.05, 0.2, 0.5, 0.8, 0.9])) ** 2  # n = 0: factor 1
    v2r = amp**2 * (0.3**2 + 0.25**2) / 2
    W = RHO_AIR * C0 * (sigma_axial(0, f_r, 0.40) * np.dot(s.S_a, v2a) + sigma_radial(0, f_r, 0.40, s.gamma) * s.S_r * v2r)
    assert res.W[0] == pytest.approx(W, rel=1e-9)
    peak = sound_power([f_r], 0.0, 2.0, modes, s, nodes, contact=0, force_amplitude="peak")
    assert peak.W[0] == pytest.approx(W / 2, rel=1e-12)


def test_only_modes_of_the_same_harmonic():
    # a second mode of another harmonic at the same frequency leaves harmonic 2's part unchanged
    extra = {"f_hz": np.array([1000.0]), "n": np.array([3]), "cls": np.array(["a"]), "kind": np.array(["flexible"]),
             "modal_mass": np.array([5.0]), "shapes": SHAPE[None] * 2, "zeta_suspension": np.array([np.nan])}
    one = sound_power([900.0, 1000.0], 1.0, 0.5, *setup()[:3], contact=0)
    two = sound_power([900.0, 1000.0], 1.0, 0.5, *setup(extra=extra)[:3], contact=0)
    assert list(two.harmonics) == [2, 3]
    np.testing.assert_allclose(two.W_n[0], one.W_n[0], rtol=1e-12)
    np.testing.assert_allclose(two.W, two.W_n.sum(axis=0), rtol=1e-12)
    np.testing.assert_allclose(two.W_n, two.W_axial + two.W_radial, rtol=1e-12)


def test_modal_frf_modal_sum():
    # [4.10] by hand: G_ij = sum_r U_ri U_rj / (m_r (w_r^2 - W^2 + 2 i zeta_r w_r W))
    U = np.array([[1.0, 0.5], [0.2, -1.0]])  # (modes, nodes)
    f = np.array([50.0, 300.0])
    H = modal_frf(f, [100.0, 200.0], [2.0, 3.0], [0.01, 0.02])  # (freqs, modes)
    G = (H * np.array([1.0, 0.2])[None, :]) @ U  # driven at a point with U_c = (1.0, 0.2)
    w1, w2, W = 2 * PI * 100, 2 * PI * 200, 2 * PI * f
    h1 = 1 / (2.0 * (w1**2 - W**2 + 2j * 0.01 * w1 * W))
    h2 = 1 / (3.0 * (w2**2 - W**2 + 2j * 0.02 * w2 * W))
    np.testing.assert_allclose(G[:, 0], 1.0 * 1.0 * h1 + 0.2 * 0.2 * h2, rtol=1e-12)
    np.testing.assert_allclose(G[:, 1], 0.5 * 1.0 * h1 - 1.0 * 0.2 * h2, rtol=1e-12)


def test_damping_rules():
    # [4.11] and thesis 4.2.1: only the (1,0,r) mode (one nodal diameter, NO nodal circle) is damped by
    # the axle (zeta = 1); a (1,1,r) mode keeps the n = 1 value; the rigid half-wheelset modes take the
    # suspension's damping ratio, and a rigid mode without one is an error, not a free-wheel value
    n = [0, 1, 2, 5, 1, 1, 1, 0]
    m = [0, 0, 0, 0, 0, 1, 0, 0]
    cls = ["a", "a", "a", "r", "r", "r", "s", "s"]
    kind = ["flexible"] * 6 + ["bounce", "lateral"]
    zs = [np.nan] * 6 + [0.2, 0.08]
    np.testing.assert_allclose(modal_damping(n, m, cls, kind, zs), [1e-3, 1e-2, 1e-4, 1e-4, 1.0, 1e-2, 0.2, 0.08])
    with pytest.raises(ValueError, match="zeta_suspension"):
        modal_damping(n, m, cls, kind, [np.nan] * 8)


def test_unit_force_band_integral_single_mode():
    # int_0^inf |v|^2 df of an SDOF (F = 1) = 1 / (8 zeta w_r m^2): the band power of a mode
    # with slowly varying sigma is rho c0 sigma S <U^2> U_c^2 / (8 zeta w_r m^2) * (1/2 for n > 0)
    zeta = 1e-3
    modes, s, nodes, _ = setup(zeta=zeta)
    modes["zeta_suspension"] = np.array([np.nan])
    f_r, m_r = 1000.0, 20.0
    f = frequency_grid(500.0, 2000.0, [f_r], [zeta], per_decade=2000, per_peak=201, span=200)
    u = unit_force_power(f, modes, s, nodes, 0, "lateral", zeta=[zeta])
    wr = 2 * PI * f_r
    k = 0.5 / (8 * zeta * wr * m_r**2)
    U2a = np.array([0.05, 0.2, 0.5, 0.8, 0.9]) ** 2
    U2r = (0.3**2 + 0.25**2) / 2
    expect = RHO_AIR * C0 * k * (sigma_axial(2, f_r, 0.40) * np.dot(s.S_a, U2a)
                                 + sigma_radial(2, f_r, 0.40, s.gamma) * s.S_r * U2r)
    assert u.W_band == pytest.approx(expect, rel=0.02)
    assert u.f_peak == pytest.approx(f_r, rel=1e-6)
    assert u.table[0]["n"] == 2 and u.table[0]["share"] == pytest.approx(1.0)


def test_frequency_grid_resolves_peaks():
    f = frequency_grid(100, 6500, [434.0, 7000.0], [1e-4, 1e-4])
    assert f[0] == 100 and f[-1] == pytest.approx(6500)
    assert 434.0 in f
    inside = f[np.abs(f - 434.0) <= 434.0 * 1e-4]  # the -3 dB band
    assert inside.size >= 5
