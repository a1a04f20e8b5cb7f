"""Reduced wave families of the rail (SPEC 3.2): the projection of a waveguide family on a small
block basis, its waves at a frequency and their residue amplitudes (wave sums).

Eigenproblem in k at fixed w.  Because K1 couples only W with (U_y, U_z)
and K0, K2, M are block diagonal (see solvers/rail/waveguide.py), the
substitution W = k W' turns the quadratic problem into a LINEAR one in
lambda = k^2 of the original size:

    [K0_WW - w^2 M_WW + lambda K2_WW] W' + K1_WY V = 0
    lambda K1_YW W' + [K0_YY - w^2 M_YY + lambda K2_YY] V = 0,

i.e. (A0 + lambda A1) x = 0 with A1 = [[K2_WW, 0], [K1_YW, K2_YY]]
invertible; each lambda gives the pair +-k, and the member with Im k < 0 is
kept.  phi = (k W', V).

Model reduction.  The half-section has ~5000 dofs per wave family; a dense
eigenproblem per frequency at that size is far too slow.  Each family is
projected on a basis made of (a) its real-k waves below f_basis at a few
wavenumbers (SLEPc, solvers.rail.waveguide.eig_real_k) and (b) static
"attachment" responses A(k)^-1 f to the unit loads at the contact points at
a few real and imaginary wavenumbers (near field).  The basis is split into
its W and (U_y, U_z) parts, which keeps the block structure above (and the
k -> -k symmetry) exactly, and M-orthonormalised with truncation.  The
reduced problem (~70 dofs per family for BV50) is solved densely at every
frequency.  tests/rail/test_response.py checks it against the direct
wavenumber integral of the unreduced model (agreement 1e-4 .. 5e-4).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from solvers.rail import waveguide as wg


@dataclass
class ReducedFamily:
    """One wave family projected on a block basis B = diag(BW, BY).

    Dense complex arrays of the reduced model (with loss factors):
    K0W, K2W (mW x mW), K0Y, K2Y (mY x mY), K1WY (mW x mY);
    P, Q: C(w) = P + w^2 Q is the matrix whose eigenvalues are lambda = k^2;
    ``inputs`` (n_in x mY) and ``outputs`` (n_out x mY): load / response
    functionals restricted to the basis (rows of BY^T f)."""

    name: str
    BW: np.ndarray
    BY: np.ndarray
    K0W: np.ndarray
    K2W: np.ndarray
    K0Y: np.ndarray
    K2Y: np.ndarray
    K1WY: np.ndarray
    P: np.ndarray
    Q: np.ndarray
    inputs: np.ndarray
    outputs: np.ndarray
    in_names: list = field(default_factory=list)
    out_names: list = field(default_factory=list)

    @property
    def size(self):
        return self.BW.shape[1] + self.BY.shape[1]


def _orthonormal(S: np.ndarray, M: sp.spmatrix, rtol: float) -> np.ndarray:
    """M-orthonormal basis of the columns of S, dropping directions whose
    M-Gram eigenvalue is below rtol * largest."""
    nrm = np.sqrt(np.abs(np.einsum("ij,ij->j", S, M @ S)))
    S = S[:, nrm > 1e-300 * max(nrm.max(), 1e-300)] / nrm[nrm > 1e-300 * max(nrm.max(), 1e-300)][None, :]
    G = S.T @ (M @ S)
    w, U = np.linalg.eigh(0.5 * (G + G.T))
    keep = w > rtol * w.max()
    return S @ (U[:, keep] / np.sqrt(w[keep])[None, :])


def reduce_family(fam: wg.Family, loads: dict, responses: dict | None = None,
                  k_modes=(0.0, 1.5, 4.0, 8.0, 13.0, 20.0, 30.0, 45.0), f_basis: float = 10000.0,
                  k_static=(0.0, 25.0, 80.0, 250.0), kappa_static=(25.0, 80.0, 250.0),
                  rtol: float = 1e-8, snapshots=None) -> ReducedFamily:
    """Project one supported (or free) family on a reduced block basis.

    loads / responses: {name: vector over the family's free dofs} (a unit
    point load is a unit vector; responses default to the loads, i.e.
    point receptances).  k_modes: real wavenumbers (rad/m) whose waves
    below f_basis (Hz) enter the basis; k_static, kappa_static: real k and
    imaginary k = -i kappa at which the static responses to the loads are
    added.  ``snapshots`` may supply precomputed {k: (f, phi)} from
    eig_real_k (shared with the dispersion plot)."""
    responses = loads if responses is None else responses
    cols = []
    for k in k_modes:
        if snapshots is not None and k in snapshots:
            f, phi = snapshots[k]
            phi = phi[:, f <= f_basis]
        else:
            _, phi = wg.eig_real_k(fam, k, f_basis)
        cols.append(phi)
    F = np.column_stack(list(loads.values()))
    Wd = fam.dof_comp == 0
    for k in k_static:
        K = fam.K(k).tocsc()
        if not fam.supported and k == 0.0:
            K = K + 1e-6 * abs(K.diagonal()).max() * sp.identity(K.shape[0], format="csc")
        cols.append(splu(K).solve(F))
    Pw = sp.diags(Wd.astype(float))
    Py = sp.diags((~Wd).astype(float))
    K1 = fam.Ks[1] + (fam.Kp[1] if fam.supported else 0 * fam.Ks[1])
    K2 = fam.Ks[2] + (fam.Kp[2] if fam.supported else 0 * fam.Ks[2])
    K1i = Py @ K1 @ Pw - Pw @ K1 @ Py
    for kap in kappa_static:
        # imaginary k = -i kappa (near-field, evanescent): with W = i W~ the static
        # problem A(k) x = f is real (non-symmetric):
        # [K0 - kappa^2 K2]_WW W~ - kappa K1_WY V = 0,  kappa K1_YW W~ + [K0 - kappa^2 K2]_YY V = f
        K = (fam.K(0.0) - kap * kap * K2 + kap * K1i).tocsc()
        cols.append(splu(K).solve(F))
    S = np.column_stack(cols)
    Mw = fam.M[Wd][:, Wd]
    Yd = ~Wd
    My = fam.M[Yd][:, Yd]
    BW = _orthonormal(S[Wd], Mw, rtol)
    BY = _orthonormal(S[Yd], My, rtol)
    return _project(fam, BW, BY, loads, responses)


def _project(fam: wg.Family, BW, BY, loads, responses) -> ReducedFamily:
    Wd = fam.dof_comp == 0
    Yd = ~Wd
    fs, fp = 1 + 1j * fam.eta_s, 1 + 1j * fam.eta_p

    def red(j, rows, cols, A, B):
        Ks = fam.Ks[j][rows][:, cols]
        out = A.T @ (Ks @ B) * fs
        if fam.supported:
            out = out + A.T @ (fam.Kp[j][rows][:, cols] @ B) * fp
        return out

    K0W, K2W = red(0, Wd, Wd, BW, BW), red(2, Wd, Wd, BW, BW)
    K0Y, K2Y = red(0, Yd, Yd, BY, BY), red(2, Yd, Yd, BY, BY)
    K1WY = red(1, Wd, Yd, BW, BY)
    MW = BW.T @ (fam.M[Wd][:, Wd] @ BW)
    MY = BY.T @ (fam.M[Yd][:, Yd] @ BY)
    mW, mY = BW.shape[1], BY.shape[1]
    A1 = np.block([[K2W, np.zeros((mW, mY))], [K1WY.T, K2Y]])
    A0s = np.block([[K0W, K1WY], [np.zeros((mY, mW)), K0Y]])
    Mb = sl.block_diag(MW, MY).astype(complex)
    lu = sl.lu_factor(A1)
    P = -sl.lu_solve(lu, A0s)
    Q = sl.lu_solve(lu, Mb)
    Fin = np.array([BY.T @ v[Yd] for v in loads.values()])
    Fout = np.array([BY.T @ v[Yd] for v in responses.values()])
    return ReducedFamily(fam.name, BW, BY, K0W, K2W, K0Y, K2Y, K1WY, P, Q, Fin, Fout,
                         list(loads), list(responses))


def waves(rf: ReducedFamily, omega: float):
    """All waves of the reduced family at circular frequency omega.

    Returns k (m,) with Im k <= 0 (decaying / travelling in +x), the load
    and response projections fin (m, n_in), fout (m, n_out) of each wave's
    (y, z) shape, and its residue normaliser D = phi^T A'(k) phi (m,)."""
    lam, X = np.linalg.eig(rf.P + (omega * omega) * rf.Q)
    k = np.sqrt(lam.astype(complex))
    flip = (k.imag > 0) | ((k.imag == 0) & (k.real < 0))
    k = np.where(flip, -k, k)
    mW = rf.BW.shape[1]
    Wp, V = X[:mW], X[mW:]
    t1 = np.einsum("in,in->n", Wp, rf.K1WY @ V)
    t2W = np.einsum("in,in->n", Wp, rf.K2W @ Wp)
    t2Y = np.einsum("in,in->n", V, rf.K2Y @ V)
    D = 2 * k * t1 + 2 * k * (k * k * t2W + t2Y)
    fin = (rf.inputs @ V).T
    fout = (rf.outputs @ V).T
    return k, fin, fout, D


def wave_amplitudes(rf: ReducedFamily, omegas: np.ndarray, pairs: list[tuple[int, int]],
                    k_local: float | None = None):
    """k (nf, m) and residue amplitudes a (nf, m, n_pairs) with
    G_pair(x, w) = sum_n a_n exp(-i k_n |x|) for the (output, input) index pairs.

    k_local (rad/m): if given, the static (w = 0) near field of the load --
    the waves with |k| > k_local at w = 0, i.e. all but the beam-like
    waves -- is subtracted by appending those static waves with negated
    amplitudes (so the result stays a plain wave sum, valid for every x).
    This removes the frequency-independent local compliance of the loaded
    zone, which depends on the element size at the load node and is the
    contact model's business (SPEC 3.5); see ``receptances``."""
    m = rf.size
    o_idx = np.array([p[0] for p in pairs])
    i_idx = np.array([p[1] for p in pairs])

    def amp(w):
        k, fin, fout, D = waves(rf, w)
        return k, -1j * fout[:, o_idx] * fin[:, i_idx] / D[:, None]

    extra_k = np.zeros(0, complex)
    extra_a = np.zeros((0, len(pairs)), complex)
    if k_local is not None:
        k0, a0 = amp(0.0)
        hi = np.abs(k0) > k_local
        extra_k, extra_a = k0[hi], -a0[hi]
    ne = len(extra_k)
    K = np.empty((len(omegas), m + ne), complex)
    A = np.empty((len(omegas), m + ne, len(pairs)), complex)
    for j, w in enumerate(omegas):
        k, a = amp(w)
        K[j, :m], A[j, :m] = k, a
        K[j, m:], A[j, m:] = extra_k, extra_a
    return K, A


def evaluate(K: np.ndarray, A: np.ndarray, x: np.ndarray, block: int = 64) -> np.ndarray:
    """G (n_pairs, nx, nf) = sum_n A[f, n, p] exp(-i K[f, n] |x|)."""
    x = np.abs(np.asarray(x, float))
    nf, m, npair = A.shape
    out = np.empty((npair, len(x), nf), complex)
    for s in range(0, nf, block):
        e = np.exp(-1j * K[s:s + block, :, None] * x[None, None, :])  # (b, m, nx)
        out[:, :, s:s + block] = np.einsum("fmp,fmx->pxf", A[s:s + block], e, optimize=True)
    return out


def decay_integral(K: np.ndarray, A: np.ndarray) -> np.ndarray:
    """int_0^inf |G(x)|^2 dx for each frequency and pair, exactly from the
    wave sum: sum_nm a_n conj(a_m) / (i (k_n - conj(k_m)))."""
    nf, m, npair = A.shape
    out = np.empty((npair, nf))
    for j in range(nf):
        kk = K[j]
        den = 1j * (kk[:, None] - np.conj(kk)[None, :])
        for p in range(npair):
            a = A[j, :, p]
            out[p, j] = np.real(np.sum(np.outer(a, np.conj(a)) / den))
    return out


def reduced_H(rf: ReducedFamily, k: float, omega: float, io: list[int], ii: list[int]) -> np.ndarray:
    """Wavenumber-domain receptance of the reduced family at real k."""
    mW = rf.BW.shape[1]
    mY = rf.BY.shape[1]
    A = np.block([[rf.K0W + k * k * rf.K2W - omega**2 * np.eye(mW), k * rf.K1WY],
                  [k * rf.K1WY.T, rf.K0Y + k * k * rf.K2Y - omega**2 * np.eye(mY)]])
    rhs = np.vstack([np.zeros((mW, len(ii))), rf.inputs[ii].T])
    X = np.linalg.solve(A, rhs)
    return rf.outputs[io] @ X[mW:]
