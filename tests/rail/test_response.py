"""Forced response of the supported BV50 rail (solvers/rail/response.py).

1. The reduced wave sum against the direct wavenumber integral of the
   UNREDUCED waveguide model (sparse solves on Gauss-Legendre panels along
   real k; coarse mesh to keep it fast): transfer receptance at x = 0.3 m,
   and at x = 0 once the local (contact-zone) compliance, frequency
   independent, is added.
2. Reciprocity G23 = G32 and the mirror rule between y^R = -12 and +12 mm.
3. Below 500 Hz the vertical point receptance (structural: local
   compliance excluded) agrees within 10 % with the Timoshenko beam on a
   Winkler foundation of the same EI, kappa G A (kappa = 0.4), m, rho I and
   pad stiffness, loss factors as complex moduli.
4. Lateral point receptance vs the lateral-torsional beam on the pad's
   lateral and rocking stiffness: within 15 % up to 500 Hz (measured
   +-11 %, the FE is softer at the lowest frequencies -- web bending and
   foot deformation under the lateral head load, which the rigid-section
   beam lacks); the web-bending wave (cut-on 1.4 kHz) makes them part above.
5. Track decay rates: high below the rail-on-pad cut-on, low above.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.sparse.linalg import splu

from solvers.rail import response as rr
from pipeline.validation.references import beam
from pipeline.validation.references.rail import beam_params, direct_receptance, rail_model


def test_wave_sum_equals_direct_wavenumber_integral():
    model = rail_model("bv50", 2.0)  # coarse mesh: ~1300 dofs per family
    y, x = 0.012, 0.3
    local = rr.local_compliance(model, points=[y], n=50)
    for fname, freq in (("sym", 2500.0), ("anti", 400.0)):
        rf = getattr(model, fname)
        idx = rr._pairs_for(rf, y)
        K, A = rr.wave_amplitudes(rf, np.array([2 * np.pi * freq]), idx)
        D = direct_receptance(model, fname, y, freq, x)
        for xx in (x, 0.0):
            g = rr.evaluate(K, A, [xx])[:, 0, 0]  # yy, zz, yz, zy
            G = np.array([[g[0], g[2]], [g[3], g[1]]])
            if xx == 0:
                G = G + local[(fname, y)]
            scale = np.abs(D[xx]).max()
            assert np.abs(G - D[xx]).max() < 0.01 * scale, (fname, freq, xx, G, D[xx])


def test_local_compliance_is_frequency_independent():
    """The part the structural receptance leaves out: the static near field
    of the load (k_local) -- compare the full wave sum minus the structural
    one at two frequencies."""
    model = rail_model("bv50")
    f = np.array([100.0, 3000.0])
    for fname in ("sym", "anti"):
        rf = getattr(model, fname)
        pr = [p for p in rr._pairs_for(rf, 0.012) if p is not None]
        K1, A1 = rr.wave_amplitudes(rf, 2 * np.pi * f, pr)
        K2, A2 = rr.wave_amplitudes(rf, 2 * np.pi * f, pr, k_local=20.0)
        d = A1.sum(axis=1) - A2.sum(axis=1)  # (nf, npairs)
        assert np.allclose(d[0], d[1], rtol=0.02, atol=1e-3 * np.abs(d).max())


def test_reciprocity_and_mirror():
    model = rail_model("bv50")
    f = np.linspace(25.0, 6500.0, 60)
    x = np.array([0.0, 0.05, 0.5, 2.0])
    R = rr.receptances(model, f, x, points=[-0.016, -0.012, 0.012])
    G = R["G"]
    g23, g32 = G[..., 0, 1], G[..., 1, 0]
    assert np.abs(g23 - g32).max() <= 1e-6 * np.abs(g23).max()
    # mirror images: y = -12 mm and +12 mm
    assert np.allclose(G[1, ..., 0, 0], G[2, ..., 0, 0]) and np.allclose(G[1, ..., 1, 1], G[2, ..., 1, 1])
    assert np.allclose(G[1, ..., 0, 1], -G[2, ..., 0, 1])
    # passivity: the imaginary part of a point receptance is negative for exp(+i w t) (energy absorbed)
    assert np.all(G[:, 0, :, 0, 0].imag < 0) and np.all(G[:, 0, :, 1, 1].imag < 0)


def test_full_model_reciprocity_with_complex_moduli():
    """A(k) is complex symmetric: the lateral response to a vertical unit
    load equals the vertical response to a lateral one, on the unreduced
    model, at any real k and frequency."""
    model = rail_model("bv50")
    fam = model.families["sym"]
    Fy = rr.rf_loads_vec(fam, model, 0.012, "y")
    Fz = rr.rf_loads_vec(fam, model, 0.012, "z")
    for k, f in ((0.5, 100.0), (7.0, 2000.0), (30.0, 6000.0)):
        A = (fam.K(k, complex_moduli=True) - (2 * np.pi * f) ** 2 * fam.M).tocsc()
        lu = splu(A)
        a = Fy @ lu.solve(Fz.astype(complex))
        b = Fz @ lu.solve(Fy.astype(complex))
        assert abs(a - b) <= 1e-9 * abs(a)


@pytest.mark.parametrize("y", [0.0, 0.012, -0.016])
def test_vertical_point_receptance_vs_tboef(y):
    """Off the centre line a vertical load also twists the rail: the beam
    reference is then TBOEF + y^2 x (twist per torque) of the lateral-
    torsional beam (its 'vertical'-'vertical' receptance)."""
    model = rail_model("bv50")
    bp = beam_params(model)
    v = bp["vertical"]
    f = np.linspace(25.0, 500.0, 40)
    G33 = rr.receptances(model, f, [0.0], points=[y])["G"][0, 0, :, 1, 1]
    Gb = beam.tboef_receptance(f, [0.0], v["EI"], v["kGA"], v["m"], v["rhoI"], v["k_s"],
                               v["eta_beam"], v["eta_support"])[0]
    if y != 0.0:
        Gb = Gb + beam.lateral_torsion_receptance(f, [0.0], bp["lateral"], out=("vertical", "vertical"),
                                                  z_h=0.155, y_h=y)[0]
    assert np.abs(np.abs(G33) / np.abs(Gb) - 1).max() < 0.10
    # and the section-mean (beam) displacement under a head-centre load: within 3 %
    bt = rr.beam_transfer(model, f, y=0.0)["vertical"]
    Gc = beam.tboef_receptance(f, [0.0], v["EI"], v["kGA"], v["m"], v["rhoI"], v["k_s"],
                               v["eta_beam"], v["eta_support"])[0]
    assert np.abs(np.abs(bt) / np.abs(Gc) - 1).max() < 0.03


def test_lateral_point_receptance_vs_lateral_torsional_beam():
    from geometry.rail import head_profile

    model = rail_model("bv50")
    bp = beam_params(model)["lateral"]
    f = np.linspace(25.0, 500.0, 40)
    y = 0.012
    G22 = rr.receptances(model, f, [0.0], points=[y])["G"][0, 0, :, 0, 0]
    Gb = beam.lateral_torsion_receptance(f, [0.0], bp, out=("lateral", "lateral"),
                                         z_h=float(head_profile(model.rail, y)))[0]
    ratio = np.abs(G22) / np.abs(Gb)
    assert np.abs(ratio - 1).max() < 0.15


def test_decay_rates_plausible():
    model = rail_model("bv50")
    f = np.array([50.0, 100.0, 150.0, 1000.0, 2000.0, 3000.0, 30.0, 500.0])
    d = rr.decay_rates(model, f)
    assert np.all(d["vertical"][:3] > 8.0)  # below the rail-on-pad cut-on (~320 Hz)
    assert np.all(d["vertical"][3:6] < 2.0)  # free-ish bending waves above it
    assert d["lateral"][6] > 5.0  # lateral: cut-on ~ 80 Hz
    assert d["lateral"][7] < 2.0  # (above the web-bending cut-on, 1.4 kHz, the lateral decay rises again)
    assert np.all(np.isfinite(d["vertical"])) and np.all(d["vertical"] > 0)


def test_stage_arrays_consistent():
    from pipeline.stages.rail_io import stage_arrays

    model = rail_model("bv50")
    f = np.array([60.0, 700.0, 3000.0])
    x = np.array([0.0, 0.4, 3.0])
    A = stage_arrays(model, f, x, ks=np.array([0.0, 2.0, 10.0]))
    assert A["G"].shape == (3, 3, 3, 2, 2)
    # the decay rates, from the head centre's waves in the same table: decay_rates' own wave sums
    d = rr.decay_rates(model, f)
    assert np.allclose(A["decay_vertical_db_per_m"], d["vertical"], rtol=1e-9, atol=0)
    assert np.allclose(A["decay_lateral_db_per_m"], d["lateral"], rtol=1e-9, atol=0)
    # the wave table reproduces G at any distance
    G = np.einsum("fnpij,fnx->pxfij", A["wave_a"], np.exp(-1j * A["wave_k"][:, :, None] * x[None, None, :]))
    assert np.allclose(G, A["G"], rtol=1e-12, atol=0)
    assert np.all(A["wave_k"].imag <= 0)
    for s in ("free", "supported"):
        for fam in ("sym", "anti"):
            F = A[f"disp_{s}_{fam}_f_hz"]
            assert F.shape[0] == 3 and A[f"disp_{s}_{fam}_label"].shape == (F.shape[1],)
    assert A["section_mass_per_m"] == pytest.approx(model.rail["reference"]["mass_per_m"], rel=0.03)
    assert np.nanmax(A["head_z_m"]) == pytest.approx(model.rail["section"]["height"])
