"""Spectra and levels of contact-force histories (SPEC 5 and 6).

Pure functions on arrays.

Scaling of ``amplitude_spectrum`` (one-sided, mean removed, Hann window by
default), for x(t) = A cos(2 pi f0 t + p) sampled at dt, N samples, window w_k:

    X_k = c * sum_j w_j x_j exp(-i 2 pi k j / N),   f_k = k / (N dt),  k = 0..N/2

* ``scaling='amplitude'`` (default): c = 2 / sum(w) for 0 < f_k < f_Nyquist
  (1 / sum(w) at DC and Nyquist).  A sinusoid exactly on a bin gives
  |X_k| = A (the amplitude correction undoes the window's coherent gain,
  sum(w)/N = 1/2 for Hann).  Between bins the peak bin is low by the
  scalloping loss (up to 1.42 dB for Hann at half a bin);
  ``dominant_frequency`` interpolates it away.
* ``scaling='rms'``: the amplitude scaling divided by sqrt(2): a sinusoid on a
  bin gives |X_k| = A / sqrt(2), its RMS value.  This is the force amplitude
  ``solvers.radiation.thompson_jones.sound_power`` expects by default (the mean square
  [4.56] is then a time mean square).
* ``scaling='power'`` (the power-correct alternative): c = sqrt(2 / (N sum(w^2)))
  (1/sqrt(N sum w^2) at DC and Nyquist), so that sum_k |X_k|^2 equals the mean
  square of a stationary signal (Parseval with the window's incoherent power
  gain; for white noise on average, for a sinusoid whatever its frequency, to
  within end effects of order 1/N).  A Hann-windowed tone spreads over ~3
  bins, whose squared RMS-scaled values sum to 1.5 A^2/2 (+1.76 dB, the
  window's noise bandwidth 1.5 bins): sum power over bins
  (e.g. an overall L_W from a force spectrum) with 'power' scaling, read a
  tone's amplitude with 'amplitude' scaling.
"""
from __future__ import annotations

import numpy as np


def window_samples(name: str, N: int) -> np.ndarray:
    """The window of ``N`` samples: 'hann' the periodic (DFT-even) Hann, exact coherent gain
    1/2 and bin-spaced zeros; 'rect' (or None) ones.  (scipy's ``windows.hann(N, sym=False)``
    is the same window but rounds differently in the last bit, 5.6e-16; through the tone fit's
    cancellation that moves radiate's residual spectra by 1.3e-11 relative, so this formula
    stays, the one definition of the window.)"""
    if name in (None, "rect", "boxcar", "none"):
        return np.ones(N)
    if name == "hann":
        return 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(N) / N)
    raise ValueError(f"window: 'hann' or 'rect', got {name!r}")


def amplitude_spectrum(x, dt: float, *, window: str = "hann", scaling: str = "amplitude",
                       detrend: bool = True):
    """One-sided complex spectrum of the real history ``x`` sampled at ``dt``
    (mean removed when ``detrend``).  Returns (f (N//2+1,), X (N//2+1,) complex);
    see the module docstring for ``scaling`` ('amplitude', 'rms', 'power')."""
    x = np.asarray(x, dtype=float)
    if detrend:
        x = x - x.mean()
    N = x.size
    w = window_samples(window, N)
    X = np.fft.rfft(w * x)
    f = np.fft.rfftfreq(N, dt)
    edge = np.zeros(f.size, bool)
    edge[0] = True
    if N % 2 == 0:
        edge[-1] = True
    if scaling in ("amplitude", "rms"):
        c = np.where(edge, 1.0, 2.0) / w.sum()
        if scaling == "rms":
            c = c / np.sqrt(2.0)
    elif scaling == "power":
        c = np.sqrt(np.where(edge, 1.0, 2.0) / (N * np.sum(w**2)))
    else:
        raise ValueError(f"scaling: 'amplitude', 'rms' or 'power', got {scaling!r}")
    return f, c * X


def _hann_kernel(delta):
    """|W(delta)| / |W(0)| of the Hann window for a tone delta bins from a bin
    centre (large-N limit): sinc(delta) / (1 - delta^2)."""
    d = np.asarray(delta, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.sinc(d) / (1 - d**2)
    return np.where(np.isclose(np.abs(d), 1.0), 0.5, k)


def dominant_frequency(f, X, *, f_min: float | None = None, f_max: float | None = None,
                       window: str = "hann"):
    """Frequency and amplitude of the largest spectral peak of an amplitude
    spectrum ``(f, X)`` (from ``amplitude_spectrum``), optionally within
    [f_min, f_max].  The peak is located by a parabola through the log
    magnitudes of the largest bin and its neighbours (for a Hann window
    the log-magnitude parabola has a bias below 0.05 bin), and its
    amplitude is the peak bin divided by the window's response at the tone's
    offset from it (scalloping correction, offset from the two-bin ratio,
    exact for Hann; for 'rect' the parabola's peak value).
    Returns (f_peak, amplitude) in the units of X (amplitude scaling: A)."""
    f = np.asarray(f, float)
    mag = np.abs(np.asarray(X))
    sel = np.ones(f.size, bool)
    if f_min is not None:
        sel &= f >= f_min
    if f_max is not None:
        sel &= f <= f_max
    idx = np.flatnonzero(sel)
    if idx.size == 0:
        raise ValueError("no frequencies in the requested range")
    k = int(idx[np.argmax(mag[idx])])
    if k == 0 or k == f.size - 1 or mag[k] == 0:
        return float(f[k]), float(mag[k])
    a, b, c = np.log(np.maximum(mag[k - 1:k + 2], np.finfo(float).tiny))
    den = a - 2 * b + c
    delta = 0.5 * (a - c) / den if den < 0 else 0.0
    delta = float(np.clip(delta, -0.5, 0.5))
    df = f[1] - f[0]
    if window == "hann":
        # amplitude: the offset from the two largest bins' ratio, exact for the
        # Hann kernel (alpha = K(1 - d) / K(d) = (1 + d) / (2 - d)), then undo the
        # scalloping; the parabola's offset alone would leave up to ~0.7 %
        s = 1 if mag[k + 1] >= mag[k - 1] else -1
        alpha = mag[k + s] / mag[k]
        d_h = (2 * alpha - 1) / (1 + alpha)
        amp = mag[k] / float(_hann_kernel(np.clip(d_h, 0.0, 0.5)))
    else:
        amp = float(np.exp(b - 0.25 * (a - c) * delta))
    return float(f[k] + delta * df), float(amp)


def final_stretch(x, dt: float, duration: float | None):
    """The last ``duration`` seconds of ``x`` (all of it when None or longer)."""
    x = np.asarray(x)
    if duration is None:
        return x
    n = int(round(duration / dt))
    return x[-n:] if 0 < n < x.size else x


def rms(x) -> float:
    """Root mean square of x with its mean removed."""
    x = np.asarray(x, float)
    return float(np.sqrt(np.mean((x - x.mean()) ** 2)))


def force_level(F, dt: float | None = None, duration: float | None = None) -> float:
    """Squeal measure [6.3-6.4]: L_F = 20 log10(rms(F - mean) / 1 N) dB over the
    final stretch (the last ``duration`` s; all samples when None)."""
    F = final_stretch(F, dt, duration) if duration is not None else np.asarray(F, float)
    r = rms(F)
    return float(20 * np.log10(r)) if r > 0 else -np.inf
