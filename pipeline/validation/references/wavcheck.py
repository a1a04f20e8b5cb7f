"""Independent read-back of a listen.wav: the file through scipy.io.wavfile, the
calibration from the JSON sidecar, the limit-cycle part's level and dominant
frequency, and its 1/3-octave band levels from pyfar's IEC 61260-1 filter bank
(a time-domain second method for the stage's line-spectrum bands)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from scipy.io import wavfile

from solvers.spectra import amplitude_spectrum, dominant_frequency

P0 = 20e-6
FADE_S = 0.01  # the fade at the end of the file (postprocess.listening.audio.FADE_S), left out of the read-back


def read_calibrated(wav: Path, sidecar: Path):
    """(fs, pressure (Pa) of the whole file, pressure of its limit-cycle part, the sidecar's fields (flat,
    beside its ``__provenance__``))."""
    payload = json.loads(Path(sidecar).read_text())
    fs, x = wavfile.read(wav)
    assert x.dtype == np.int16 and x.ndim == 1
    p = x.astype(float) * payload["pa_per_count"]
    i0 = int(np.ceil(payload["limit_cycle_start_s"] * fs))
    return fs, p, p[i0:len(p) - int(round(FADE_S * fs))], payload


def level(p) -> float:
    return float(10 * np.log10(np.mean(np.asarray(p) ** 2) / P0**2))


def dominant(p, fs) -> float:
    f, X = amplitude_spectrum(p, 1 / fs)
    return dominant_frequency(f, X, f_min=20.0)[0]


def filter_bank_levels(p_whole, fs, start_s: float, stop_s: float, f_range=(10.0, 17000.0)):
    """(nominal band centres, band levels dB re 20 uPa) of the samples between start_s and
    stop_s after filtering the whole file (so the filters have settled) with pyfar's
    order-14 Butterworth 1/3-octave bank (energy preserving, IEC 61260-1 class 1 design);
    bands 10 Hz - 16 kHz (the 20 kHz band's upper edge is above the Nyquist frequency)."""
    import pyfar as pf  # lazy: brings in pyfar

    y = pf.dsp.filter.fractional_octave_bands(pf.Signal(np.asarray(p_whole, float), fs), 3,
                                              frequency_range=f_range)
    seg = y.time[:, 0, int(np.ceil(start_s * fs)):int(stop_s * fs)] if y.time.ndim == 3 else \
        y.time[:, int(np.ceil(start_s * fs)):int(stop_s * fs)]
    nominal = pf.constants.fractional_octave_frequencies_nominal(3, f_range)
    with np.errstate(divide="ignore"):
        return nominal, 10 * np.log10(np.mean(seg**2, axis=-1) / P0**2)


def filter_bank_from_lines(f, p2, fs, f_range=(10.0, 17000.0)):
    """Band levels (dB re 20 uPa) the same pyfar filter bank gives for a line spectrum: each component's
    mean square ``p2`` (Pa^2) at frequency ``f`` (Hz) weighted by every band filter's own |H_b(f)|^2
    (scipy.signal.sosfreqz of its second-order sections).  Exact for the tones of a stationary signal,
    so it carries the filters' skirts, which ideal band edges do not."""
    import pyfar as pf  # lazy: brings in pyfar
    from scipy.signal import sosfreqz  # lazy: brings in scipy

    sos = np.asarray(pf.dsp.filter.fractional_octave_bands(None, 3, sampling_rate=fs, frequency_range=f_range).coefficients)
    f = np.asarray(f, float)
    keep = (f > 0) & (f < fs / 2)
    out = np.array([np.sum(np.abs(sosfreqz(b, worN=f[keep], fs=fs)[1]) ** 2 * np.asarray(p2)[keep]) for b in sos])
    with np.errstate(divide="ignore"):
        return 10 * np.log10(out / P0**2)
