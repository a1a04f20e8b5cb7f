"""Waveguide FE matrices and dispersion of the BV50 rail.

Free rail (pad removed) at low wavenumber against beam theory, with the
section properties of the same mesh (area, second moments from the
polygon; J from the FE warping function -- tests/rail/test_section.py
checks that solver against the exact rectangle):
  vertical / lateral bending: Euler-Bernoulli for k <= 1 rad/m,
      Timoshenko (kappa = 0.4) for k <= 3 rad/m;
  extension: bar, w = k sqrt(E / rho);
  torsion: Saint-Venant, w = k sqrt(G J / (rho I_p)), I_p polar about the
      centroid (at these frequencies the lateral inertia dominates the
      lateral stiffness, so the section turns about its centroid, not the
      shear centre), for k <= 1 rad/m (warping adds E Gamma k^2 / GJ =
      1.5 % at k = 1).
All within 2 %.
"""
from __future__ import annotations

import numpy as np
import pytest

from solvers.rail import waveguide as wg
from pipeline.validation.references.beam import timoshenko_dispersion
from pipeline.validation.references.rail import assembled, rail_model


def _free(name):
    p, mesh, ct, ft, asm, mat, tors = assembled("bv50")
    return p, tors, wg.family(asm, mat, name, supported=False)


def test_matrices_symmetric_with_the_w_block_structure():
    p, mesh, ct, ft, asm, mat, tors = assembled("bv50")
    for name in ("sym", "anti"):
        fam = wg.family(asm, mat, name, supported=True)
        W = fam.dof_comp == 0
        for A in fam.Ks + fam.Kp + [fam.M]:
            assert abs(A - A.T).max() <= 1e-12 * abs(A).max()
        # K1 couples W with (U_y, U_z) only; K0, K2, M do not couple them
        K1 = fam.Ks[1] + fam.Kp[1]
        assert abs(K1[W][:, W]).max() == 0 and abs(K1[~W][:, ~W]).max() == 0
        for A in (fam.Ks[0], fam.Ks[2], fam.M, fam.Kp[0], fam.Kp[2]):
            assert abs(A[W][:, ~W]).max() == 0
        # K(k) positive definite for real k (stiffness): smallest eigenvalue of the supported rail > 0
        f, _ = wg.eig_real_k(fam, 5.0, 100.0, nev_min=2, vectors=False)
        assert len(f) == 0 or f.min() > 0


@pytest.mark.parametrize("k", [0.25, 0.5, 1.0])
def test_free_rail_low_k_matches_beam_theory(k):
    p, tors, sym = _free("sym")
    _, _, anti = _free("anti")
    E, nu, rho = p["material"]["E"], p["material"]["nu"], p["material"]["rho"]
    G = E / (2 * (1 + nu))
    A, Iv, Il = tors["area"], tors["I_vertical"], tors["I_lateral"]
    m = rho * A
    f, phi = wg.eig_real_k(sym, k, 2000.0)
    lab, _ = wg.classify(sym, phi, p, tors["z_centroid"], k)
    d = dict(zip(lab, f))
    two_pi = 2 * np.pi
    assert d["vertical bending"] == pytest.approx(k * k * np.sqrt(E * Iv / m) / two_pi, rel=0.02)
    assert d["extensional"] == pytest.approx(k * np.sqrt(E / rho) / two_pi, rel=0.02)
    f, phi = wg.eig_real_k(anti, k, 2000.0)
    lab, _ = wg.classify(anti, phi, p, tors["z_centroid"], k)
    d = dict(zip(lab, f))
    assert d["lateral bending"] == pytest.approx(k * k * np.sqrt(E * Il / m) / two_pi, rel=0.02)
    assert d["torsion"] == pytest.approx(k * np.sqrt(G * tors["J"] / (rho * (Iv + Il))) / two_pi, rel=0.02)


@pytest.mark.parametrize("k", [2.0, 3.0])
def test_free_rail_timoshenko(k):
    p, tors, sym = _free("sym")
    _, _, anti = _free("anti")
    E, nu, rho = p["material"]["E"], p["material"]["nu"], p["material"]["rho"]
    G = E / (2 * (1 + nu))
    A, Iv, Il = tors["area"], tors["I_vertical"], tors["I_lateral"]
    for fam, I, lab_ in ((sym, Iv, "vertical bending"), (anti, Il, "lateral bending")):
        f, phi = wg.eig_real_k(fam, k, 2000.0)
        lab, _ = wg.classify(fam, phi, p, tors["z_centroid"], k)
        fe = dict(zip(lab, f))[lab_]
        ti = timoshenko_dispersion(k, E * I, 0.4 * G * A, rho * A, rho * I) / (2 * np.pi)
        assert fe == pytest.approx(ti, rel=0.02), lab_


def test_reduced_model_reproduces_full_dispersion():
    """The reduced block basis (solvers.rail.response) gives the waves of the
    full model at wavenumbers that are not among its snapshots."""
    import scipy.linalg as sl

    model = rail_model("bv50")
    for name in ("sym", "anti"):
        fam, rf = model.families[name], getattr(model, name)
        W = fam.dof_comp == 0
        B = np.zeros((fam.M.shape[0], rf.size))
        B[W, :rf.BW.shape[1]] = rf.BW
        B[~W, rf.BW.shape[1]:] = rf.BY
        for k in (2.7, 11.0, 26.0):
            f_full, _ = wg.eig_real_k(fam, k, 6500.0, vectors=False)
            lam = sl.eigh(B.T @ (fam.K(k) @ B), B.T @ (fam.M @ B), eigvals_only=True)
            f_red = np.sqrt(np.abs(lam)) / (2 * np.pi)
            f_red = f_red[f_red <= 6500.0]
            assert len(f_red) == len(f_full)
            assert np.allclose(f_red, f_full, rtol=1e-3)


def test_wave_types_identified():
    """Supported rail at k = 2 rad/m: the expected wave types, in order."""
    p, mesh, ct, ft, asm, mat, tors = assembled("bv50")
    out = {}
    for name in ("sym", "anti"):
        fam = wg.family(asm, mat, name, supported=True)
        f, phi = wg.eig_real_k(fam, 2.0, 6500.0)
        out[name], _ = wg.classify(fam, phi, p, tors["z_centroid"], 2.0)
    assert out["sym"][:3] == ["vertical bending", "extensional", "foot flapping"]
    assert out["anti"][:4] == ["lateral bending", "torsion", "web", "web"]


def test_dispersion_branches():
    model = rail_model("bv50")
    p = model.rail
    zc = model.props["torsion"]["z_centroid"]
    d = wg.dispersion(model.families["sym"], np.linspace(0.0, 10.0, 6), 3000.0, p, zc)
    assert d["f"].shape[0] == 6
    vb = np.where(d["label"] == "vertical bending")[0]
    assert len(vb) == 1
    fv = d["f"][:, vb[0]]
    assert np.all(np.isfinite(fv)) and np.all(np.diff(fv) > 0)
    # on the pad the vertical bending wave starts at the rail-on-pad resonance sqrt(k_pad / m)
    f0 = np.sqrt(p["pad"]["stiffness"] / (p["material"]["rho"] * model.props["torsion"]["area"])) / (2 * np.pi)
    assert fv[0] == pytest.approx(f0, rel=0.02)
