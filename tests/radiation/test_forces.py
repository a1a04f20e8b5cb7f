"""Sound power of force histories (solvers/radiation/force_power.py through
pipeline.stages.radiate.sound_power_of_forces, the function the stage and the
studies call).

The key check: one mode driven at resonance by a sampled force history.  The
reference is computed in the time domain, directly from the modal velocity
(the steady state of m q'' + 2 zeta m w q' + m w^2 q = P(t) at w = w_r is
q' = P(t) / (2 zeta m w_r); confirmed here by integrating the ODE), the surface
velocities v = U_i q'(t) cos(n phi) averaged over time samples, angles and the
surface's nodes, times rho c0 sigma S with the efficiencies and areas written
out by hand.  No FFT, window, modal factor or Gram matrix is involved.
"""
import numpy as np
import pytest

from pipeline.stages.radiate import sound_power_of_forces
from solvers.radiation import surfaces as SF
from pipeline.validation.references import node_average as NA
from solvers.radiation.force_power import build_model, decompose_forces, harmonic_power, power_of_forces
from pipeline.validation.references.radiation import (BND, DT, N, PTS, RADII, SHAPE, flat_disc_segments,
                                                      modal_velocity_reference, one_mode_model)

PI = 3.141592653589793


def test_steady_state_modal_velocity_by_integration():
    # the reference's q' = P / (2 zeta m w_r) at resonance, checked against the ODE itself
    from scipy.integrate import solve_ivp

    f_r, m_r, zeta, A = 1000.37, 20.0, 1e-4, 500.0
    w = 2 * PI * f_r
    c = 2 * zeta * m_r * w
    # steady state: q = A/(c w) sin(w t), q' = A/c cos(w t)
    sol = solve_ivp(lambda t, y: [y[1], (A * np.cos(w * t) - c * y[1] - m_r * w * w * y[0]) / m_r], (0, 20 / f_r),
                    [0.0, A / c], rtol=1e-10, atol=1e-14, t_eval=np.linspace(0, 20 / f_r, 801), method="DOP853")
    np.testing.assert_allclose(sol.y[1], A / c * np.cos(w * sol.t), atol=1e-6 * A / c)


@pytest.mark.parametrize("n, A2, A3, theta", [(2, 800.0, 0.0, 0.0), (2, 800.0, 3000.0, 1.1), (0, 0.0, 2500.0, 0.0),
                                              (5, 300.0, 900.0, -2.0)])
@pytest.mark.parametrize("f_r", [1000.0, 1000.37, 437.3 + 1 / (2 * N * DT)])  # on a bin, between bins, half a bin
def test_single_mode_at_resonance(n, A2, A3, theta, f_r):
    m_r, zeta = 20.0, 1e-4 if n >= 2 else 1e-3
    model, _ = one_mode_model(n, f_r, m_r, zeta)
    t = np.arange(N) * DT
    F = np.column_stack([np.zeros(N), A2 * np.cos(2 * PI * f_r * t), 65e3 + A3 * np.cos(2 * PI * f_r * t + theta)])
    res = sound_power_of_forces(model, F, DT)
    W_ref = modal_velocity_reference(n, f_r, m_r, zeta, A2, A3, theta)
    assert res["W"].sum() == pytest.approx(W_ref, rel=1e-2)  # the criterion of issue 8
    assert res["W"].sum() == pytest.approx(W_ref, rel=1e-4)  # what it achieves
    assert res["L_W"] == pytest.approx(10 * np.log10(W_ref / 1e-12), abs=0.01)
    assert res["f_sound"] == pytest.approx(f_r, rel=1e-7)
    assert list(res["harmonics"]) == [n]
    # a bins-only evaluation of the same force misses the narrow peak by far where the bins miss f_r
    d = decompose_forces(F[:, 1], F[:, 2], DT)
    assert d.tone_f.size == 1 and d.tone_f[0] == pytest.approx(f_r, rel=1e-8)


def test_bins_alone_would_depend_on_the_bin_placement():
    # why tones are evaluated at their own frequency: the same tone at a zeta = 1e-4 mode, evaluated on
    # the power-scaled bins only, changes by many dB when f_r moves by half a bin; the tone path does not
    from solvers.spectra import amplitude_spectrum

    t = np.arange(N) * DT
    df = 1 / (N * DT)
    on, off = [], []
    for f_r in (1000 * df, 1000.5 * df):
        model, _ = one_mode_model(2, f_r, 20.0, 1e-4)
        x = 800.0 * np.cos(2 * PI * f_r * t)
        f, X = amplitude_spectrum(x, DT, scaling="power")
        on.append(harmonic_power(model, f[1:], X[1:], 0.0).sum())
        F = np.column_stack([np.zeros(N), x, np.zeros(N)])
        off.append(sound_power_of_forces(model, F, DT)["W_total"])
    assert abs(10 * np.log10(on[0] / on[1])) > 10
    assert abs(10 * np.log10(off[0] / off[1])) < 0.01


def test_periodic_force_tones_and_residual():
    rng = np.random.default_rng(3)
    t = np.arange(N) * DT
    f0 = 1156.73
    noise = 5.0 * rng.standard_normal((N, 2))
    F2 = 1800 * np.cos(2 * PI * f0 * t + 0.2) + 250 * np.cos(2 * PI * 2 * f0 * t - 1.0) + noise[:, 0]
    F3 = 65e3 + 900 * np.cos(2 * PI * f0 * t + 2.0) + 120 * np.cos(2 * PI * 3 * f0 * t) + noise[:, 1]
    d = decompose_forces(F2, F3, DT)
    np.testing.assert_allclose(d.tone_f, [f0, 2 * f0, 3 * f0], rtol=1e-7)
    assert d.fundamentals == [pytest.approx(f0, rel=1e-7)]
    # complex RMS amplitudes: A e^{i p} / sqrt 2 relative to t = 0
    np.testing.assert_allclose(d.tone_F2[:2], np.array([1800 * np.exp(0.2j), 250 * np.exp(-1j)]) / np.sqrt(2),
                               rtol=2e-3)
    np.testing.assert_allclose(d.tone_F3[[0, 2]], np.array([900 * np.exp(2j), 120]) / np.sqrt(2), rtol=5e-3)
    # the residual is the noise: its power-scaled bins sum to its variance (25 N^2 per channel, < 6.5 kHz share)
    share = 6500 / (0.5 / DT)
    assert np.sum(np.abs(d.R2) ** 2) == pytest.approx(25.0 * share, rel=0.08)


def test_subharmonic_fundamental_and_second_series():
    t = np.arange(N) * DT
    # F2's largest peak is the 2nd harmonic of 612.4 Hz; an incommensurate tone at 2871.1 Hz
    F2 = 100 * np.cos(2 * PI * 612.4 * t) + 900 * np.cos(2 * PI * 1224.8 * t) + 400 * np.cos(2 * PI * 2871.1 * t)
    d = decompose_forces(F2, np.zeros(N), DT)
    assert d.fundamentals[0] == pytest.approx(612.4, rel=1e-7)
    assert any(abs(f - 2871.1) < 1e-3 for f in d.fundamentals)
    for f, a in ((612.4, 100), (1224.8, 900), (2871.1, 400)):
        k = int(np.argmin(np.abs(d.tone_f - f)))
        assert d.tone_f[k] == pytest.approx(f, rel=1e-7) and abs(d.tone_F2[k]) * np.sqrt(2) == pytest.approx(a, rel=1e-4)
    assert np.sum(np.abs(d.R2) ** 2) < 1e-8 * 900**2


def test_broadband_force_is_the_library_on_bins():
    # no tone stands out of white noise: everything is residual, and the power equals
    # radiation.sound_power (node averages) on the same power-scaled bins
    rng = np.random.default_rng(7)
    modes = {"f_hz": np.array([700.0, 1300.0, 2100.0]), "n": np.array([2, 2, 3]), "m": np.array([0, 1, 0]),
             "cls": np.array(["a", "a", "a"]), "kind": np.array(["flexible"] * 3), "modal_mass": np.array([20.0, 9.0, 12.0]),
             "shapes": np.stack([SHAPE, SHAPE[:, [1, 0, 2]], 0.5 * SHAPE]), "zeta_suspension": np.full(3, np.nan)}
    s = SF.radiation_surfaces(RADII, flat_disc_segments())
    nodes = SF.surface_nodes(PTS, BND, s)
    zeta = np.array([1e-3, 2e-3, 1e-3])
    phi = modes["shapes"][:, 0, [1, 0]]
    model = build_model(modes, s, nodes, phi, zeta)
    F = np.column_stack([np.zeros(N), 50 * rng.standard_normal(N), 65e3 + 80 * rng.standard_normal(N)])
    res = power_of_forces(model, F[:, 1], F[:, 2], DT)
    d = res["decomposition"]
    assert d.tone_f.size == 0 and not res["is_tone"].any()
    ref = NA.sound_power(d.f, d.R2, d.R3, modes, s, nodes, contact=0, zeta=zeta)
    np.testing.assert_allclose(res["W"], ref.W, rtol=1e-9)
    assert res["L_W"] == pytest.approx(ref.L_W, abs=1e-9)


def test_constant_force_and_input_errors():
    model, _ = one_mode_model(2, 1000.0, 20.0, 1e-4)
    F = np.column_stack([np.zeros(N), np.full(N, -3e3), np.full(N, 65e3)])
    res = sound_power_of_forces(model, F, DT)
    assert res["L_W"] == -np.inf and np.isnan(res["f_sound"]) and res["W_total"] == 0.0
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        sound_power_of_forces(model, F[:, :2], DT)
    F[5, 1] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        sound_power_of_forces(model, F, DT)
    with pytest.raises(ValueError, match="dt"):
        sound_power_of_forces(model, np.zeros((N, 3)), 0.0)
    with pytest.raises(ValueError, match="zeta"):
        model.with_damping([1e-3, 1e-3])
    assert model.with_damping([1e-3]).zeta[0] == 1e-3 and model.zeta[0] == 1e-4
