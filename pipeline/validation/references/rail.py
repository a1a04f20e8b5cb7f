"""The rail's shared model builders (cached: one mesh and model per rail and mesh scale in a temporary
folder) for tests/rail/, the rail writers and benchmarks, the analytic beams' parameters of an FE model
(``beam_params``, for ``references.beam``), and the direct numerical wavenumber integral of the UNREDUCED
waveguide model (``direct_receptance``: sparse solves on Gauss-Legendre panels along real k), the second
method the reduced wave sum is checked against."""
from __future__ import annotations

import atexit
import copy
import functools
import shutil
import tempfile
from pathlib import Path

import numpy as np
from scipy.sparse.linalg import splu

from solvers.rail import response as rr, waveguide as wg

from pipeline.store.paths import ROOT
from pipeline.stages.rail_io import load_rail, build_rail_model
from geometry.rail_mesh import mesh_rail
from geometry.mesher import read_msh

RAILS = ROOT / "geometry" / "rails"
_TMP = Path(tempfile.mkdtemp(prefix="rail_models_"))
atexit.register(shutil.rmtree, _TMP, ignore_errors=True)


def rail_params(name: str = "bv50", mesh_scale: float = 1.0) -> dict:
    p = load_rail(RAILS / f"{name}.toml")
    if mesh_scale != 1.0:
        p = copy.deepcopy(p)
        for k in ("size_head", "size_web", "size_foot"):
            p["mesh"][k] *= mesh_scale
    return p


@functools.lru_cache(maxsize=None)
def mesh_path(name: str = "bv50", mesh_scale: float = 1.0) -> str:
    path = _TMP / f"{name}_{mesh_scale:g}.msh"
    mesh_rail(rail_params(name, mesh_scale), str(path))
    return str(path)


@functools.lru_cache(maxsize=None)
def assembled(name: str = "bv50", mesh_scale: float = 1.0):
    """(params, mesh, cell_tags, facet_tags, Assembled, materials, torsion props)."""
    p = rail_params(name, mesh_scale)
    mesh, ct, ft = read_msh(mesh_path(name, mesh_scale))
    asm = wg.assemble(mesh, ct, ft)
    mat = wg.material_moduli(p, asm)
    tors = wg.torsion_properties(mesh, ct)
    return p, mesh, ct, ft, asm, mat, tors


@functools.lru_cache(maxsize=None)
def rail_model(name: str = "bv50", mesh_scale: float = 1.0):
    return build_rail_model(rail_params(name, mesh_scale), mesh_path(name, mesh_scale))


def beam_params(model) -> dict:
    """Section and support properties of the FE model for the analytic
    beams (pipeline/validation/references/beam.py): vertical TBOEF and lateral-torsional."""
    p = model.rail
    t = model.props["torsion"]
    pad = model.props["pad"]
    E, nu, rho = p["material"]["E"], p["material"]["nu"], p["material"]["rho"]
    G = E / (2 * (1 + nu))
    return {
        "vertical": dict(EI=E * t["I_vertical"], kGA=0.4 * G * t["area"], m=rho * t["area"],
                         rhoI=rho * t["I_vertical"], k_s=p["pad"]["stiffness"],
                         eta_beam=p["material"]["loss_factor"], eta_support=p["pad"]["loss_factor"]),
        "lateral": dict(EI_l=E * t["I_lateral"], GJ=G * t["J"], EGamma=E * t["Gamma"], m=rho * t["area"],
                        rhoI_l=rho * t["I_lateral"], rhoI_pc=rho * (t["I_lateral"] + t["I_vertical"]),
                        z_c=t["z_centroid"], z_s=t["z_shear_centre"], k_y=pad["k_lateral"], k_r=pad["k_rocking"],
                        eta_beam=p["material"]["loss_factor"], eta_support=p["pad"]["loss_factor"]),
    }


def gauss_panels(edges, n=8):
    t, w = np.polynomial.legendre.leggauss(n)
    a, b = edges[:-1, None], edges[1:, None]
    return (0.5 * (b - a) * t + 0.5 * (a + b)).ravel(), (0.5 * (b - a) * w).ravel()


def direct_receptance(model, fname, y, freq, x_pos):
    """(1/pi) int_0^inf H(k) cos(k x) dk on the unreduced family, for unit
    loads in y and z at head point |y|, at x = 0 and x = x_pos; returns
    {x: 2x2 (y, z) block}.  x = 0: panels to 3e5 rad/m plus the 1/k^2 tail;
    x > 0: panels up to K = n pi / x ~ 100 rad/m (sin(K x) = 0, so the
    leading tail term -H(K) sin(K x) / x vanishes; the next one,
    H'(K) cos(K x) / x^2, is added; beyond, the near field decays as
    exp(-|k| x))."""
    fam, rf = model.families[fname], getattr(model, fname)
    w = 2 * np.pi * freq
    comps = [c for c in ("y", "z") if (float(y), c) in rf.in_names]
    F = np.column_stack([rr.rf_loads_vec(fam, model, y, c) for c in comps]).astype(complex)
    k_w = rr.waves(rf, w)[0]
    K_end = np.pi * np.ceil(100.0 * x_pos / np.pi) / x_pos
    edges = [0.0, *np.linspace(0.0, K_end, 25)[1:], *np.geomspace(K_end, 3e5, 22)[1:]]
    for kp in k_w[(np.abs(k_w.imag) < 0.5 * np.abs(k_w.real)) & (np.abs(k_w.real) < K_end)]:
        a = abs(kp.imag)
        edges += list(kp.real + a * np.array([-30, -10, -3, -1, 0, 1, 3, 10, 30]))
    edges = np.unique(np.clip(edges, 0.0, None))
    ks, wts = gauss_panels(edges, 6)

    def H(k):
        X = splu((fam.K(k, complex_moduli=True) - w * w * fam.M).tocsc()).solve(F)
        return F.T @ X

    Hs = np.array([H(k) for k in ks])
    out0 = np.einsum("k,kij->ij", wts, Hs) + H(edges[-1]) * edges[-1]
    near = ks <= K_end
    outx = np.einsum("k,kij->ij", wts[near] * np.cos(ks[near] * x_pos), Hs[near])
    dk = 1e-3 * K_end
    dH = (H(K_end + dk) - H(K_end - dk)) / (2 * dk)
    outx += dH * np.cos(K_end * x_pos) / x_pos**2
    res = {}
    for xx, o in ((0.0, out0), (x_pos, outx)):
        G = np.zeros((2, 2), complex)
        for i, a in enumerate(comps):
            for j, b in enumerate(comps):
                G["yz".index(a), "yz".index(b)] = o[i, j] / np.pi
        res[xx] = G
    return res
