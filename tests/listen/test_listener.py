"""Propagation and levels (postprocess/listening/listener.py) against independent
references (pipeline/validation/references/listening.py): the IEC 61672-1 A-weighting table, the IEC 61260-1 band formulas,
ISO 9613-1's absorption formula, and the exact field of point monopoles over a
rigid plane (image sources summed here, with the source strength from its own
power formula; a dipole built from two monopoles, its power integrated over a
sphere)."""
import numpy as np
import pytest

from postprocess.listening import listener as L

from pipeline.validation.references.listening import (C0, IEC_61672_A, RHO, dipole_from_two_monopoles, iso_9613_alpha,
                                                      monopole_field)

def test_a_weighting_against_iec_61672_table():
    nominal = np.array(list(IEC_61672_A), float)
    table = np.array(list(IEC_61672_A.values()))
    x = np.arange(-20, 14)  # band numbers of 10 Hz .. 20 kHz
    exact = 1000.0 * 10 ** (0.1 * x)  # IEC 61672-1 / 61260-1 base-10 mid-band frequencies
    assert np.allclose(exact, nominal, rtol=0.03)
    dev = L.a_weighting(exact) - table
    # the table is rounded to 0.1 dB: at most half a step (plus the table's own last-digit rounding)
    assert np.abs(dev).max() <= 0.06, dict(zip(nominal, dev.round(3)))
    assert L.a_weighting(0.0)[0] == -np.inf


def test_third_octave_bands_are_iec_61260_base_10():
    b = L.third_octave_bands(10.0, 20000.0)
    np.testing.assert_array_equal(b.nominal, list(IEC_61672_A))
    G = 10 ** (3 / 10)  # IEC 61260-1 eq. (1): octave ratio, base 10
    x = np.arange(-20, 14)
    np.testing.assert_allclose(b.centre, 1000 * G ** (x / 3), rtol=1e-12)  # eq. (2), b = 3 (odd)
    np.testing.assert_allclose(b.lower, b.centre * G ** (-1 / 6), rtol=1e-12)  # eq. (3)
    np.testing.assert_allclose(b.upper, b.centre * G ** (1 / 6), rtol=1e-12)  # eq. (4)
    np.testing.assert_allclose(b.upper[:-1], b.lower[1:], rtol=1e-12)  # contiguous


def test_band_sums_conserve_energy():
    b = L.third_octave_bands()
    rng = np.random.default_rng(3)
    f = np.r_[np.sort(rng.uniform(1.0, 25000.0, 500)), b.lower[5], b.upper[-1]]
    x = rng.uniform(0, 1, f.size)
    bands, outside = L.band_sums(f, x, b)
    assert bands.sum() + outside == pytest.approx(x.sum(), rel=1e-12)
    inside = (f >= b.lower[0]) & (f < b.upper[-1])
    assert outside == pytest.approx(x[~inside].sum(), rel=1e-12)
    # a component on an edge belongs to the band above it
    assert bands[5] >= x[-2]
    for j in (0, 12, 33):
        sel = (f >= b.lower[j]) & (f < b.upper[j])
        assert bands[j] == pytest.approx(x[sel].sum(), rel=1e-12)


def test_air_absorption_iso_9613_1():
    f = np.array([63.0, 250.0, 1000.0, 1151.5, 4000.0, 8000.0])
    np.testing.assert_allclose(L.air_attenuation(f), iso_9613_alpha(f), rtol=1e-3)
    # ISO 9613-1 Table 1 at 20 degC, 70 % RH, 1 kHz: 4.98 dB/km (rounded: 5.0)
    assert L.air_attenuation(1000.0)[0] * 1e3 == pytest.approx(4.98, abs=0.05)
    assert L.air_attenuation([10.0, 30.0, 50.0]).tolist() == [L.air_attenuation(50.0)[0]] * 3


@pytest.mark.parametrize("h_s,h_r,d", [(0.59, 1.4, 6.75), (0.59, 4.0, 24.25), (0.3, 0.3, 2.0)])
def test_monopole_over_rigid_ground_is_the_image_solution(h_s, h_r, d):
    f = np.array([200.0, 500.0, 1000.0, 1151.5, 2300.0, 3457.0, 6000.0])
    W = np.array([1.0, 0.3, 2e-3, 0.05, 1e-6, 0.8, 4e-2])
    g = L.Geometry(distance=d, h_source=h_s, h_receiver=h_r, ground="rigid", directivity="omni", air=False)
    model = L.mean_square_pressure(f, W, g)
    ref = []
    for fi, Wi in zip(f, W):
        k = 2 * np.pi * fi / C0
        Q = np.sqrt(4 * np.pi * Wi / (RHO * C0 * k**2))  # monopole power W = rho c k^2 Q^2 / (4 pi)
        rec = np.array([[0.0, d, h_r]])
        ref.append(abs(monopole_field(rec, [np.array([0, 0, h_s]), np.array([0, 0, -h_s])], [Q, Q], fi)[0]) ** 2)
    np.testing.assert_allclose(model, ref, rtol=1e-10)
    # free field: the image removed
    g0 = L.Geometry(distance=d, h_source=h_s, h_receiver=h_r, ground="none", directivity="omni", air=False)
    r = np.hypot(d, h_r - h_s)
    np.testing.assert_allclose(L.mean_square_pressure(f, W, g0), RHO * C0 * W / (4 * np.pi * r**2), rtol=1e-12)


def test_ground_limits_coherent_and_incoherent():
    # near grazing: the two paths coincide, +6 dB coherent, +3 dB incoherent; far above the
    # ground the band average of the coherent sum tends to the incoherent one
    f = np.array([500.0])
    g0 = L.Geometry(distance=50.0, h_source=1e-3, h_receiver=1e-3, ground="none", directivity="omni", air=False)
    g = L.Geometry(distance=50.0, h_source=1e-3, h_receiver=1e-3, ground="rigid", directivity="omni", air=False)
    p0 = L.mean_square_pressure(f, 1.0, g0)[0]
    assert L.level(L.mean_square_pressure(f, 1.0, g)[0]) - L.level(p0) == pytest.approx(6.0206, abs=1e-4)
    assert L.level(L.mean_square_pressure(f, 1.0, g, coherent=False)[0]) - L.level(p0) == pytest.approx(3.0103, abs=1e-4)
    fb = np.linspace(1000, 30000, 20001)  # ~20 interference fringes (c0 / (r_i - r_d) = 1.4 kHz apart)
    gh = L.Geometry(distance=6.75, h_source=0.59, h_receiver=1.4, ground="rigid", directivity="omni", air=False)
    coh, inc = L.mean_square_pressure(fb, 1.0, gh), L.mean_square_pressure(fb, 1.0, gh, coherent=False)
    assert coh.mean() / inc.mean() == pytest.approx(1.0, abs=0.02)
    assert coh.max() / inc.max() > 1.9 and coh.min() / inc.min() < 0.05  # interference peaks and dips


def test_dipole_along_the_axle_from_two_monopoles():
    model, ref = dipole_from_two_monopoles()
    assert model == pytest.approx(ref, rel=2e-3)
    f = 1151.5
    # on the axle's axis a dipole is 3x (4.8 dB) the omnidirectional source of the same power
    on_axis = [L.Geometry(distance=10.0, h_source=1.0, h_receiver=1.0, ground="none", directivity=k, air=False)
               for k in ("dipole", "omni")]
    assert L.level(L.mean_square_pressure(f, 1.0, on_axis[0])[0]) - L.level(
        L.mean_square_pressure(f, 1.0, on_axis[1])[0]) == pytest.approx(10 * np.log10(3), abs=1e-9)


def test_air_absorption_enters_each_path():
    f = np.array([4000.0, 8000.0])
    kw = dict(distance=50.0, h_source=0.5, h_receiver=1.5, ground="none", directivity="omni")
    dry = L.mean_square_pressure(f, 1.0, L.Geometry(**kw, air=False))
    wet = L.mean_square_pressure(f, 1.0, L.Geometry(**kw, air=True))
    r = np.hypot(50.0, 1.0)
    np.testing.assert_allclose(L.level(dry) - L.level(wet), iso_9613_alpha(f) * r, rtol=1e-3)


@pytest.mark.parametrize("kw", [dict(distance=-1.0), dict(h_receiver=0.0), dict(ground="soft"),
                                dict(directivity="monopole")])
def test_geometry_rejects_bad_values(kw):
    base = dict(distance=6.75, h_source=0.59, h_receiver=1.4)
    with pytest.raises(ValueError):
        L.Geometry(**{**base, **kw})
