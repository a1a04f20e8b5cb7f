"""The wheel kernel the greens stage stores (solvers/wheel/modal_band.py): the closed-form spectrum of the
modal kernel against the FFT of the long sampled kernel (a second method), and the corrected
kernel's spectrum against the receptance, pointwise at every grid point from 5 Hz to 6.5 kHz, for
the C20 at the default contact point (issue 5's criterion: 1 % to 2 kHz, 5 % to 6.5 kHz; reached:
0.1 %)."""
import numpy as np
import scipy.fft as sfft

from solvers.greens.kernels import choose_grid, frequency_grid, green_from_receptance, modal_kernel
from solvers.wheel.modal_band import corrected_modal_kernel, decay_db, spectrum
from solvers.wheel.modal_filter import modal_kernel_dtft
from solvers.wheel.receptance import wheel_receptance
from pipeline.validation.references.greens import DT, pointwise_error, wheel_case


def test_closed_form_spectrum_is_the_fft_of_the_long_kernel():
    """Under-, critically and over-damped modes: the geometric-sum spectrum equals the FFT of the
    sampled kernel (2^22 lags, decayed to < 1e-100) to 1e-11 of its peak."""
    rng = np.random.default_rng(0)
    fr = np.array([30.0, 400.0, 1200.0, 800.0, 3000.0, 5000.0])
    m = np.array([100.0, 20.0, 10.0, 30.0, 20.0, 5.0])
    z = np.array([0.01, 0.002, 0.05, 1.0, 2.5, 0.003])
    phi = rng.standard_normal((6, 2))
    n = 1 << 22
    g = modal_kernel(n, DT, fr, m, z, phi)
    assert np.abs(g[-1000:]).max() < 1e-100 * np.abs(g).max()
    F = sfft.rfft(g, axis=0)
    idx = np.arange(10, n // 2, 9973)
    D = modal_kernel_dtft(idx / (n * DT), DT, fr, m, z, phi)
    assert np.abs(D - F[idx]).max() < 1e-11 * np.abs(F[idx]).max()


def test_c20_corrected_modal_kernel_reproduces_the_receptance_pointwise():
    w = wheel_case(-0.032)
    n_t = choose_grid(w["f_hz"], w["zeta"], DT, decay_db=120)
    modal = (DT, w["f_hz"], w["modal_mass"], w["zeta"], w["phi"])
    g, fit = corrected_modal_kernel(1 << 15, *modal, n_t, 6500.0)
    assert fit.taps == 16 and fit.n_fit == 2000 and np.all(fit.fit_error <= 1e-3 * (1 + 1e-9))
    plain = modal_kernel(1 << 15, *modal)
    np.testing.assert_array_equal(g[16:], plain[16:])                  # only the first 16 samples change
    assert decay_db(g, n_t, *modal) < -120.0
    f = frequency_grid(DT, n_t)
    f = f[(f >= 5.0) & (f <= 6500.0)]
    G = wheel_receptance(f, w["f_hz"], w["modal_mass"], w["n"], w["phi"], w["zeta"])
    Gd = spectrum(fit.correction, f, *modal)
    for i, j in ((0, 0), (1, 1), (0, 1)):
        (e2, _), (e65, f65) = pointwise_error(f, Gd[:, i, j], G[:, i, j])
        assert e2 < 0.01 and e65 < 0.05                                  # the criterion
        assert e65 < 1.1e-3, (i, j, e65, f65)                           # what it reaches (0.1 %)
    # Kropp's corrected kernel (the stage's before): the same but for the first samples
    gk = green_from_receptance(lambda x: wheel_receptance(x, w["f_hz"], w["modal_mass"], w["n"], w["phi"], w["zeta"]),
                               DT, n_t, band_limit=6500.0)[: 1 << 15]
    peak = np.abs(gk).max()
    assert np.abs(g[:16] - gk[:16]).max() < 2e-3 * peak
    assert np.abs(g[16:] - gk[16:]).max() < 1e-4 * peak
