"""The pass-by (postprocess/listening/passby.py): a single steady tone passing at constant speed against the
closed-form time integrals of 1/r^2 (monopole) and 3 y^2 / r^4 (dipole along the axle), the Doppler
shift, and L_AFmax against IEC 61672-1's F time weighting on tone bursts (the standard's reference
responses 10 lg(1 - e^{-T_b / tau}), its Table 4)."""
from __future__ import annotations

import numpy as np
import pytest

from postprocess.listening.listener import P_REF, Geometry
from postprocess.listening.passby import (Train, components, emission_time, exposure_dipole, exposure_monopole, f_weighted,
                                levels, passby_signal)

FS = 44100.0


@pytest.mark.parametrize("directivity", ["omni", "dipole"])
@pytest.mark.parametrize("speed_kmh", [50.0, 120.0])
def test_single_tone_exposure_matches_the_closed_form(directivity, speed_kmh):
    v, W, f0 = speed_kmh / 3.6, 0.05, 434.7
    geo = Geometry(distance=6.75, h_source=0.59, h_receiver=1.4, ground="none", directivity=directivity, air=False)
    train = Train(n_bogies=1, bogie_spacing=0.0, speed=v, window=40.0)
    t, p = passby_signal([f0], [W], train, geo, FS, weighted=False)
    E = np.sum(p**2) / FS
    d = np.hypot(6.75, 1.4 - 0.59)
    ref = exposure_monopole(W, d, v, 40.0) if directivity == "omni" else exposure_dipole(W, d, 6.75, v, 40.0)
    assert abs(10 * np.log10(E / ref)) < 0.5
    assert abs(10 * np.log10(E / ref)) < 0.05          # in fact (the O(M) Jacobian and the window's ends)
    L = levels(p, FS)
    assert L["T"] == pytest.approx(80.0 / v, abs=2 / FS)
    assert L["L_Aeq"] == pytest.approx(10 * np.log10(ref / L["T"] / P_REF**2), abs=0.05)   # unweighted here
    # A-weighted: the tone's A(f0) (IEC 61672-1 Table 3 at 400/500 Hz: -4.8/-3.2 dB; at 434.7 Hz -4.2 dB)
    # plus the analytic level, the Doppler shift of +-M f0 moving A by < 0.1 dB
    from postprocess.listening.listener import a_weighting

    _, pA = passby_signal([f0], [W], train, geo, FS, weighted=True)
    A0 = float(a_weighting(f0)[0])
    assert -4.4 < A0 < -4.0
    assert levels(pA, FS)["L_Aeq"] == pytest.approx(10 * np.log10(ref / L["T"] / P_REF**2) + A0, abs=0.5)
    assert levels(pA, FS)["L_Aeq"] == pytest.approx(10 * np.log10(ref / L["T"] / P_REF**2) + A0, abs=0.1)


def test_doppler_shift_and_emission_time():
    v, c0, f0 = 30.0, 343.0, 1000.0
    t = np.array([-1.0, 0.0, 1.0])
    te = emission_time(t, 0.0, 49.0, v, c0)
    r = np.sqrt((v * te) ** 2 + 49.0)
    np.testing.assert_allclose(te + r / c0, t, atol=1e-12)
    geo = Geometry(distance=7.0, h_source=1.0, h_receiver=1.0, ground="none", directivity="omni", air=False)
    train = Train(n_bogies=1, bogie_spacing=0.0, speed=v, window=200.0)
    tt, p = passby_signal([f0], [1e-3], train, geo, FS, weighted=False)
    for sl, expect in ((slice(0, 2**15), f0 / (1 - v / c0)), (slice(-2**15, None), f0 / (1 + v / c0))):
        x = p[sl] * np.hanning(2**15)
        spec = np.abs(np.fft.rfft(x, 2**19))
        f = np.fft.rfftfreq(2**19, 1 / FS)
        assert f[np.argmax(spec)] == pytest.approx(expect, rel=2e-3)   # far away: cos alpha ~ +-1


@pytest.mark.parametrize("T_b_ms,table_db", [(1000, 0.0), (500, -0.1), (200, -1.0), (100, -2.6), (50, -4.8),
                                             (20, -8.3), (10, -11.1), (5, -14.1), (2, -18.0), (1, -21.0),
                                             (0.5, -24.0), (0.25, -27.0)])
def test_f_time_weighting_on_4khz_tone_bursts(T_b_ms, table_db):
    """IEC 61672-1 (2013) Table 4, time weighting F: the maximum response to a 4 kHz tone burst of
    duration T_b, relative to the steady tone's level (reference delta_ref = 10 lg(1 - e^{-T_b/tau}))."""
    fs, f0, A = 192000.0, 4000.0, 1.0
    n_b = int(round(T_b_ms * 1e-3 * fs))
    t = np.arange(int(0.5 * fs) + n_b) / fs
    x = np.where(t < n_b / fs, A * np.sin(2 * np.pi * f0 * t), 0.0)
    steady = 10 * np.log10(A**2 / 2 / P_REF**2)
    burst = 10 * np.log10(f_weighted(x**2, fs).max() / P_REF**2)
    assert burst - steady == pytest.approx(table_db, abs=0.1)
    assert burst - steady == pytest.approx(10 * np.log10(1 - np.exp(-T_b_ms * 1e-3 / 0.125)), abs=0.05)


def test_components_keep_tones_and_the_strongest_residual():
    f = np.array([100.0, 200.0, 434.7, 500.0, 869.4])
    W = np.array([1e-6, 1e-9, 0.05, 1e-3, 1e-4])
    tone = np.array([False, False, True, False, True])
    fk, Wk, share = components(f, W, tone, share=0.99)
    assert list(fk) == [434.7, 500.0, 869.4] and share == pytest.approx((0.05 + 1e-3 + 1e-4) / W.sum())
