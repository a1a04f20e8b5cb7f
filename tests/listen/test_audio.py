"""The sound (postprocess/listening/audio.py): the growth envelope against a known
exponential growth (also when the stored history aliases the tone), the
onset, the shaped noise's spectrum, the PCM calibration read back through
scipy.io.wavfile and the standard library's wave module."""
import io
import wave

import numpy as np
import pytest
from scipy.io import wavfile
from scipy.signal import welch

from postprocess.listening import audio as A


@pytest.mark.parametrize("f0", [1151.5, 1700.0])  # the second is above the history's Nyquist (1389 Hz): aliased
def test_growth_envelope_follows_exponential_growth(f0):
    dt = 360e-6  # the simulate stage's history: every 10th step of 36 us
    t = np.arange(0, 2.0, dt)
    sigma = 12.0  # 1/s: 104 dB/s
    t_sat = 1.2
    amp = np.exp(sigma * (np.minimum(t, t_sat) - t_sat))  # grows, then a limit cycle of amplitude 1
    x = 3000.0 + 500.0 * amp * np.sin(2 * np.pi * f0 * t + 0.3)
    te, env = A.growth_envelope(t, x)
    mid = (t > 0.2) & (t < 1.1)
    slope = np.polyfit(te[mid], np.log(env[mid]), 1)[0]
    assert slope == pytest.approx(sigma, rel=0.02)
    np.testing.assert_allclose(env[mid], amp[mid], rtol=0.05)
    assert env[t > 1.6].mean() == pytest.approx(1.0, abs=0.01)
    on = A.onset_from_history(te, env, onset=0.5, hold=1.0)
    # -1 dB of the limit cycle is reached ln(10^(1/20)) / sigma before saturation
    t_1db = t_sat - np.log(10 ** (1 / 20)) / sigma
    assert on.t_history == pytest.approx(t_1db - 0.5, abs=0.02)
    assert on.t_limit_cycle == pytest.approx(0.5 + A.ENVELOPE_WINDOW_S, abs=0.02)
    assert on.duration == pytest.approx(on.t_limit_cycle + 1.0)
    assert on.gain[-1] == on.gain[-2] == 1.0 and on.gain[0] == pytest.approx(np.exp(-sigma * 0.5) * 0.89, rel=0.1)


def test_growth_envelope_of_a_tone_aliased_near_zero():
    # the history's rate is 2777.8 Hz: a tone 12 Hz below it shows at 12 Hz; the window widens to 3 periods
    dt = 360e-6
    t = np.arange(0, 3.0, dt)
    f0 = 1 / dt - 12.0
    amp = np.exp(4.0 * (np.minimum(t, 2.0) - 2.0))
    x = -3000.0 + 500.0 * amp * np.cos(2 * np.pi * f0 * t)
    assert A.aliased(f0, 1 / dt) == pytest.approx(12.0)
    _, plain = A.growth_envelope(t, x)
    _, env = A.growth_envelope(t, x, f_tone=f0)
    mid = (t > 0.5) & (t < 1.6)
    assert np.polyfit(t[mid], np.log(env[mid]), 1)[0] == pytest.approx(4.0, rel=0.03)
    assert np.abs(np.log(plain[mid] / amp[mid])).max() > 0.5  # a 20 ms window alone would not see it
    with pytest.raises(ValueError, match="aliases to 2.00 Hz"):
        A.growth_envelope(t, x, f_tone=1 / dt - 2.0)


def test_growth_envelope_refuses_a_constant_force():
    t = np.arange(1000) * 360e-6
    with pytest.raises(ValueError, match="no oscillation"):
        A.growth_envelope(t, np.full(t.size, 5.0))


def test_shaped_noise_has_the_spectrum_and_mean_square():
    f = np.arange(1, 3251) * 2.0  # the residual's bins (2 Hz) up to 6.5 kHz
    p2 = np.where((f > 1000) & (f < 2000), 1e-4, 1e-7) * 2.0  # Pa^2 per 2 Hz bin
    n = 3 * A.FS
    x = A.shaped_noise(f, p2, n, seed=5)
    assert np.mean(x**2) == pytest.approx(p2.sum(), rel=1e-9)
    fw, P = welch(x, A.FS, nperseg=8192)
    band = (fw > 1200) & (fw < 1800)
    assert np.mean(P[band]) == pytest.approx(1e-4, rel=0.1)  # density Pa^2/Hz
    low = (fw > 3000) & (fw < 6000)
    assert np.mean(P[low]) == pytest.approx(1e-7, rel=0.1)
    assert np.mean(P[fw > 7000]) < 1e-9


def test_tones_and_onset():
    n = A.FS
    p = A.tones([1000.0, 2500.0], [1.0 * np.exp(0.5j), 0.1], n)
    assert np.mean(p**2) == pytest.approx(1.01, rel=1e-3)
    assert p[0] == pytest.approx(np.sqrt(2) * (np.cos(0.5) + 0.1))
    on = A.Onset(t=np.array([0.0, 0.5, 1.0]), gain=np.array([0.0, 1.0, 1.0]), t_limit_cycle=0.5, t_history=0.0,
                 duration=1.0)
    y = A.apply_onset(np.ones(n), on)
    assert y[0] == 0.0 and y[n // 4] == pytest.approx(0.5, abs=1e-3) and y[3 * n // 4] == 1.0 and y[-1] < 1e-3


def test_pcm_calibration_round_trip():
    """A 1 Pa RMS tone (94.0 dB SPL) through to_pcm16, wav_bytes and back through two WAV readers."""
    n = 2 * A.FS
    p = A.tones([1151.5], [1.0], n)
    pcm, ppc = A.to_pcm16(p)
    assert abs(int(np.abs(pcm).max()) - A.FULL_SCALE * 10 ** (-A.HEADROOM_DB / 20)) <= 1.5  # +- 1 LSB of dither
    # the tone's peak is HEADROOM_DB below full scale, so a full-scale sine is that much louder than it
    assert A.full_scale_sine_level(ppc) == pytest.approx(20 * np.log10(1 / 20e-6) + A.HEADROOM_DB, abs=1e-6)
    data = A.wav_bytes(pcm, A.FS, "0 dBFS sine = x dB SPL")
    fs, x = wavfile.read(io.BytesIO(data))
    assert fs == 44100 and x.dtype == np.int16
    np.testing.assert_array_equal(x, pcm)
    L = 10 * np.log10(np.mean((x * ppc) ** 2) / 20e-6**2)
    assert L == pytest.approx(20 * np.log10(1 / 20e-6), abs=0.01)  # 93.98 dB
    with wave.open(io.BytesIO(data)) as w:
        assert (w.getnchannels(), w.getsampwidth(), w.getframerate(), w.getnframes()) == (1, 2, 44100, n)
    assert A.wav_comment(data) == "0 dBFS sine = x dB SPL"
    assert data[:4] == b"RIFF" and int.from_bytes(data[4:8], "little") == len(data) - 8


def test_silent_pcm():
    pcm, ppc = A.to_pcm16(np.zeros(100))
    assert pcm.dtype == np.int16 and not pcm.any() and ppc == A.SILENT_FULL_SCALE_PA / A.FULL_SCALE
