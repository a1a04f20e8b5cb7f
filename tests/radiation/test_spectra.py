"""Force spectra and levels (solvers/spectra.py): a sinusoid of known
amplitude and frequency is recovered; L_F2 of a sinusoid is 20 log10(A/sqrt 2)."""
import numpy as np
import pytest

from solvers.spectra import amplitude_spectrum, dominant_frequency, final_stretch, force_level, rms

DT = 36e-6  # SPEC 6 time step


@pytest.mark.parametrize("f0", [437.3, 1000.0, 720.5 / (20000 * DT), 2876.91])  # 720.5 bins: worst, half a bin
@pytest.mark.parametrize("phase", [0.0, 1.3])
def test_sinusoid_recovered(f0, phase):
    N, A = 20000, 2.5e3  # 0.72 s, bin 1.39 Hz
    t = np.arange(N) * DT
    x = 6.5e4 + A * np.cos(2 * np.pi * f0 * t + phase)  # static preload plus a squeal tone
    f, X = amplitude_spectrum(x, DT)
    fp, amp = dominant_frequency(f, X)
    assert fp == pytest.approx(f0, rel=1e-3)  # 0.1 %
    assert amp == pytest.approx(A, rel=1e-2)  # 1 %
    # tighter than asked: the interpolation leaves < 0.1 bin and < 0.01 %
    assert abs(fp - f0) < 0.1 * (f[1] - f[0])
    assert amp == pytest.approx(A, rel=1e-4)


def test_amplitude_scaling_on_bin_and_alternatives():
    N, A = 10000, 3.0
    df = 1 / (N * DT)
    f0 = 250 * df  # exactly on bin 250
    x = A * np.sin(2 * np.pi * f0 * np.arange(N) * DT)
    f, X = amplitude_spectrum(x, DT)
    assert f[1] == pytest.approx(df)
    assert abs(X[250]) == pytest.approx(A, rel=1e-10)  # amplitude correction of the Hann window
    assert abs(X[249]) == pytest.approx(A / 2, rel=1e-8)  # Hann: neighbours at -6 dB
    _, Xr = amplitude_spectrum(x, DT, scaling="rms")
    assert abs(Xr[250]) == pytest.approx(A / np.sqrt(2), rel=1e-10)
    # power-correct scaling: the bins' squares sum to the mean square A^2/2, whatever the frequency
    for f1 in (f0, f0 + 0.37 * df):
        xs = A * np.sin(2 * np.pi * f1 * np.arange(N) * DT)
        _, Xp = amplitude_spectrum(xs, DT, scaling="power")
        assert np.sum(np.abs(Xp) ** 2) == pytest.approx(A**2 / 2, rel=2e-3)
    # amplitude-scaled RMS bins summed over the tone overestimate the power by 1.5 (noise bandwidth of Hann)
    assert np.sum(np.abs(Xr) ** 2) == pytest.approx(1.5 * A**2 / 2, rel=1e-6)
    # rectangular window, on bin: exact amplitude
    _, Xb = amplitude_spectrum(x, DT, window="rect")
    assert abs(Xb[250]) == pytest.approx(A, rel=1e-9)
    assert dominant_frequency(*amplitude_spectrum(x, DT, window="rect"), window="rect")[1] == pytest.approx(A, rel=1e-6)


def test_mean_removed_and_range():
    N = 5000
    t = np.arange(N) * DT
    x = 100.0 + 1.0 * np.cos(2 * np.pi * 300 * t) + 5.0 * np.cos(2 * np.pi * 3000 * t)
    f, X = amplitude_spectrum(x, DT)
    assert abs(X[0]) < 1e-9
    assert dominant_frequency(f, X)[0] == pytest.approx(3000, rel=1e-3)
    fp, amp = dominant_frequency(f, X, f_max=1000)
    assert fp == pytest.approx(300, rel=1e-3) and amp == pytest.approx(1.0, rel=1e-2)


def test_force_level_of_a_sinusoid():
    A = 1000.0
    n_per = 400  # whole periods: 2 kHz tone, 1/(2 kHz) = 500 us = 13.9 dt -> use dt' = 25 us (20 samples/period)
    dt = 25e-6
    t = np.arange(n_per * 20) * dt
    F2 = -3000.0 + A * np.sin(2 * np.pi * 2000 * t + 0.3)
    assert rms(F2) == pytest.approx(A / np.sqrt(2), rel=1e-10)
    assert force_level(F2) == pytest.approx(20 * np.log10(A / np.sqrt(2)), abs=1e-9)  # 56.99 dB
    assert force_level(F2) == pytest.approx(56.9897, abs=1e-4)
    # final stretch: a decaying start is ignored
    G = np.concatenate([np.zeros(1000), F2])
    assert force_level(G, dt, duration=len(F2) * dt) == pytest.approx(force_level(F2), abs=1e-12)
    assert final_stretch(G, dt, None) is G or np.array_equal(final_stretch(G, dt, None), G)
    # SPEC 6 time step, non-integer periods on a long stretch: within 0.01 dB
    t = np.arange(int(0.5 / DT)) * DT
    assert force_level(A * np.cos(2 * np.pi * 1234.5 * t)) == pytest.approx(20 * np.log10(A / np.sqrt(2)), abs=0.01)
    assert force_level(np.full(10, 3.0)) == -np.inf
