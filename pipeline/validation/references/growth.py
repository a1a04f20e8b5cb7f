"""Growth rates measured in a time history, independent of the screen: the matrix pencil method
(Hua and Sarkar, IEEE Trans. ASSP 38, 1990) on the history demodulated at a frequency f,
low-passed (zero-phase Butterworth, +-half_band Hz) and decimated.  Every pole inside the band
is fitted at once, so a faster-growing neighbour or a decaying transient at a nearby frequency
does not bias the rate at f as it biases a windowed demodulation (whose sidelobes a pole growing
e^10 faster overwhelms; ``measured_growth``, the windowed demodulation, is kept beside it for comparison)."""
from __future__ import annotations

import numpy as np


def pencil_poles(x, dt: float, f: float, half_band: float = 60.0, t0: float = 0.02, tol: float = 1e-7):
    """The poles s (1/s + 2 pi i Hz, absolute frequency) of x[n] - x[0] near f, from t0 on."""
    from scipy.signal import butter, sosfiltfilt  # lazy: brings in scipy

    n0 = int(round(t0 / dt))
    y = np.asarray(x[n0:], float) - x[0]
    yb = y * np.exp(-2j * np.pi * f * np.arange(len(y)) * dt)
    sos = butter(8, half_band, fs=1.0 / dt, output="sos")
    yb = sosfiltfilt(sos, yb.real) + 1j * sosfiltfilt(sos, yb.imag)
    q = max(1, int(1.0 / (dt * 8 * half_band)))
    trim = len(yb) // 10                                     # the zero-phase filter's edge transients
    z = yb[trim:len(yb) - trim:q]
    H = np.lib.stride_tricks.sliding_window_view(z, len(z) // 3 + 1)
    _, S, Vh = np.linalg.svd(H, full_matrices=False)
    V = Vh[:int(np.sum(S > tol * S[0]))].conj().T
    lam = np.linalg.eigvals(np.linalg.pinv(V[:-1]) @ V[1:])
    return np.log(lam) / (q * dt) + 2j * np.pi * f


def pencil_growth(x, dt: float, f: float, max_df: float = 5.0, **kw) -> float:
    """Growth rate (1/s) of the pole of x nearest to f (within max_df Hz; NaN if none)."""
    s = pencil_poles(x, dt, f, **kw)
    if len(s) == 0:
        return float("nan")
    j = int(np.argmin(np.abs(s.imag / (2 * np.pi) - f)))
    return float(s[j].real) if abs(s[j].imag / (2 * np.pi) - f) <= max_df else float("nan")


def linear_phase(F2: np.ndarray, rel: float = 1e-4) -> np.ndarray:
    """F2 until it departs from its first value by ``rel`` (the linear growth phase)."""
    dev = np.abs(F2 - F2[0]) > rel * abs(F2[0])
    return F2[:int(np.argmax(dev))] if dev.any() else F2


def measured_growth(x: np.ndarray, dt: float, f: float, t0: float = 0.02, window: float = 0.05) -> float:
    """Growth rate (1/s) of the component of x at frequency f: complex demodulation in
    Blackman-Harris windows (sidelobes -92 dB: the faster low-frequency root does not leak into
    the wheel modes' bins), least squares on log|A|."""
    from scipy.signal import windows  # lazy: brings in scipy

    n0, nw = int(round(t0 / dt)), int(round(window / dt))
    nb = (len(x) - n0) // nw
    if nb < 3:
        return np.nan
    t = np.arange(nw) * dt
    seg = (x[n0:n0 + nb * nw] - x[0]).reshape(nb, nw)
    A = np.abs((seg * windows.blackmanharris(nw)) @ np.exp(-2j * np.pi * f * t))
    return float(np.polyfit(t0 + (np.arange(nb) + 0.5) * window, np.log(A), 1)[0])
