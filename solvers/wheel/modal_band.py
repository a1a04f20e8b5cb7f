"""The wheel kernel the greens stage stores: the sampled modal impulse response (``modal_kernel``,
what the recursive modal filters reproduce) with the band-limited correction of its first samples
(the procedure of ``solvers.greens.band_fit``, notes in ``solvers.greens.kernels``), fitted against the closed-form
spectrum of the whole modal kernel (``modal_kernel_dtft``) instead of the FFT of Kropp's kernel on
N_t ~ 2.8e6 samples: the same fit frequencies (pairs of points of Kropp's grid up to the band
limit), weights and tolerance, no transform of the long grid.  The whole corrected kernel's spectrum
then reproduces the receptance [4.10] pointwise in the band to the fit tolerance (measured for the
C20 at every grid point from 5 Hz to 6.5 kHz: tests/greens/test_modal_band.py).  The two kernels
differ only in their first samples (< 1e-4 of the peak beyond 20 samples, test_filters.py)."""
from __future__ import annotations

import numpy as np

from solvers.greens.band_fit import BandFit, band_index, fit_edges, fit_taps
from solvers.greens.kropp import frequency_grid
from solvers.wheel.modal_filter import modal_kernel, modal_kernel_at, modal_kernel_dtft


def band_receptance(f_hz, f_r, modal_mass, zeta, phi, chunk: int = 1 << 15) -> np.ndarray:
    """G22, G33, G23 (nf, 3) complex m/N: the modal sum [4.10] as ``solvers.wheel.receptance.wheel_receptance``
    (the same H_r = 1 / (m_r (w_r^2 - W^2 + 2 i zeta_r w_r W))), in real arithmetic: the modal factors'
    real and imaginary parts times the real shape products (equal to rounding, 3x faster)."""
    f_hz = np.asarray(f_hz, float)
    w = 2 * np.pi * f_r
    P = np.stack([phi[:, 0] * phi[:, 0], phi[:, 1] * phi[:, 1], phi[:, 0] * phi[:, 1]], axis=1)   # (M, 3)
    out = np.empty((len(f_hz), 3), complex)
    for a in range(0, len(f_hz), chunk):
        W = 2 * np.pi * f_hz[a:a + chunk, None]
        re = w * w - W * W
        im = 2.0 * zeta * w * W
        den = modal_mass * (re * re + im * im)
        out[a:a + chunk].real = (re / den) @ P
        out[a:a + chunk].imag = -(im / den) @ P
    return out


def corrected_modal_kernel(n_lags: int, dt: float, f_r, modal_mass, zeta, phi, n_t: int, band_limit: float,
                           taps: int = 16, fit_tol: float = 1e-3, n_fit: int = 2000) -> tuple[np.ndarray, BandFit]:
    """g (n_lags, 2, 2) m/N: ``modal_kernel`` with g[:taps] corrected so that the spectrum of the whole
    kernel equals the modal receptance at the fit frequencies up to ``band_limit`` (relative to |G|,
    ``fit_tol``; fit frequencies and weights on Kropp's grid ``frequency_grid(dt, n_t)``)."""
    f_r, modal_mass, zeta = (np.atleast_1d(np.asarray(a, float)) for a in (f_r, modal_mass, zeta))
    modal = (dt, f_r, modal_mass, zeta, phi)
    kb = band_index(band_limit, dt, n_t)
    f = frequency_grid(dt, n_t)[: kb + 1]
    phi = np.asarray(phi, float).reshape(len(f_r), 2)
    G = band_receptance(f, f_r, modal_mass, zeta, phi)                  # G22, G33, G23 (G32 = G23)
    edges = fit_edges(kb, n_fit)
    k0 = edges[:-1]
    three = [0, 3, 1]                                                    # (2, 2) flattened: 22, 33, 23
    E0 = G[k0] - modal_kernel_dtft(f[k0], *modal).reshape(-1, 4)[:, three]
    E1 = G[k0 + 1] - modal_kernel_dtft(f[k0 + 1], *modal).reshape(-1, 4)[:, three]
    h3, err3 = fit_taps(np.abs(G), E0, E1, edges, n_t, int(taps), float(fit_tol))
    four = [0, 2, 2, 1]                                                  # back to 22, 23, 32, 33
    fit = BandFit(float(band_limit), int(taps), h3[:, four].reshape(int(taps), 2, 2), err3[four].reshape(2, 2),
                  len(k0))
    g = modal_kernel(n_lags, *modal)
    g[:taps] += fit.correction
    return g, fit


def spectrum(correction: np.ndarray, f_hz, dt: float, f_r, modal_mass, zeta, phi) -> np.ndarray:
    """The spectrum (nf, 2, 2) of the whole corrected kernel: the modal kernel's closed form plus the
    DFT of the correction (taps, 2, 2) of its first samples."""
    f_hz = np.atleast_1d(np.asarray(f_hz, float))
    taps = len(correction)
    D = modal_kernel_dtft(f_hz, dt, f_r, modal_mass, zeta, phi)
    return D + np.einsum("kf,kij->fij", np.exp(-2j * np.pi * np.outer(np.arange(taps), f_hz) * dt), correction)


def decay_db(g: np.ndarray, n_t: int, dt: float, f_r, modal_mass, zeta, phi, tail: float = 0.05) -> float:
    """Level (dB) of the modal kernel over the last ``tail`` of the lags up to N_t/2 against the peak of
    ``g`` (its first lags), as ``solvers.greens.kernels.decayed`` measures Kropp's kernel."""
    m = max(1, int(round(tail * (n_t // 2 + 1))))
    end = np.abs(modal_kernel_at(np.arange(n_t // 2 + 1 - m, n_t // 2 + 1), dt, f_r, modal_mass, zeta, phi)).max()
    return float(20 * np.log10(max(end, 1e-300) / np.abs(g).max()))
