"""Forced response of the continuously supported rail: point and transfer
receptances by the wave expansion (residues of the wavenumber integral).

SPEC 3.2 / 3.4.  For a harmonic load F exp(i w t) at x = 0 the response of
the waveguide (``solvers.waveguide``) at distance x is the wavenumber
integral

    u(x) = 1/(2 pi) int A(k)^-1 F exp(-i k x) dk,    A(k) = K0 + k K1 + k^2 K2 - w^2 M,

with complex moduli E (1 + i eta) for steel and pad (so A is complex
SYMMETRIC, not Hermitian).  For x >= 0 the contour is closed in the lower
half plane, where the waves decaying in +x live (Im k < 0); with right
eigenvectors phi_n of A(k_n) phi_n = 0, which are also the left ones
because A = A^T,

    G_ij(x) = -i sum_{Im k_n < 0} phi_n,i phi_n,j exp(-i k_n x) / (phi_n^T A'(k_n) phi_n),
    A'(k) = K1 + 2 k K2.

The sum is exact for the discretised section (no k-grid, no truncation of
the integral, valid at x = 0 because A^-1 = O(k^-2)); it is preferred to an
FFT of the wavenumber integral because lightly damped waves (eta = 0.02)
would need a very fine k grid and the sum gives every distance at no extra
cost.

Eigenproblem in k at fixed w.  Because K1 couples only W with (U_y, U_z)
and K0, K2, M are block diagonal (see solvers/waveguide.py), the
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
wavenumbers (SLEPc, solvers.waveguide.eig_real_k) and (b) static
"attachment" responses A(k)^-1 f to the unit loads at the contact points at
a few real and imaginary wavenumbers (near field).  The basis is split into
its W and (U_y, U_z) parts, which keeps the block structure above (and the
k -> -k symmetry) exactly, and M-orthonormalised with truncation.  The
reduced problem (~70 dofs per family for BV50) is solved densely at every
frequency.  tests/rail/test_response.py checks it against the direct
wavenumber integral of the unreduced model (agreement 1e-4 .. 5e-4).

Half model.  Loads and responses are on the half section (y >= 0); the
full-section receptance at a head point is (G_sym + G_anti) / 2.

Local compliance.  A point load on a continuum has an infinite local
compliance; on the mesh it is finite, real (x (1 + i eta)), frequency
independent and mesh dependent -- at the head nodes it is as large as the
whole track receptance at low frequency.  It is the static near field of
the load (waves with |k| >> the beam wavenumbers at w = 0) and belongs to
the contact model (SPEC 3.5: g(0) = 0, the contact compliance takes its
place).  ``receptances`` subtracts it by default (``local='exclude'``,
waves with |k| > k_local = 20 rad/m at w = 0); ``local='fe'`` returns the
FE nodal receptance instead (``local_compliance``).

Directions and signs (SPEC 2): 2 = lateral y^R toward the field side,
3 = vertical positive DOWN (toward the ground), while the section's z is up:
G22 = G_yy, G33 = G_zz, G23 = -G_yz, G32 = -G_zy.  Points with y^R < 0 are
mirror images of |y^R|: G22 and G33 are the same, G23 and G32 change sign.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from . import waveguide as wg

DB_PER_NEPER = 20.0 / np.log(10.0)  # 8.686 dB per neper


# --------------------------------------------------------------------------- reduced family
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


# --------------------------------------------------------------------------- the rail model
@dataclass
class RailModel:
    """Everything the forced response needs, built once per rail: the two
    reduced families with unit point loads/responses in y and z at the
    contact nodes (|y^R| of each contact point) and at the head centre,
    plus section-mean responses (beam kinematics) for validation."""

    rail: dict
    point_y: np.ndarray  # |y| of the loaded head nodes (m)
    point_z: np.ndarray
    sym: ReducedFamily
    anti: ReducedFamily
    families: dict  # the unreduced wg.Family objects ('sym', 'anti')
    props: dict  # section, torsion and pad properties
    snapshots: dict  # {family: {k: (f_hz, phi)}} real-k waves used for the basis
    asm: wg.Assembled = None  # unconstrained matrices (for other families, e.g. the free rail)
    materials: dict = None  # wg.material_moduli output


def _head_nodes(fam: wg.Family, rail: dict, ys) -> tuple[np.ndarray, np.ndarray, list[int]]:
    from geometry.rail import head_profile

    ys = np.unique(np.round(np.abs(np.asarray(ys, float)), 10))
    zs = head_profile(rail, ys)
    nodes = [fam.node_at(y, z, tol=2e-6) for y, z in zip(ys, zs)]
    return ys, zs, nodes


def section_functionals(fam: wg.Family, zc: float) -> dict:
    """Mass-weighted section means over the steel (beam kinematics):
    'mean_z' (vertical), 'mean_y' (lateral), 'rot_x' (rotation about the
    longitudinal axis through the centroid, positive from +y toward +z)."""
    rail = fam.node_region[fam.dof_node] == wg.RAIL_TAG
    y, z = fam.nodes[fam.dof_node, 0], fam.nodes[fam.dof_node, 1] - zc
    mask = sp.diags(rail.astype(float))
    Ms = mask @ fam.M @ mask
    ones_y = ((fam.dof_comp == 1) & rail).astype(float)
    ones_z = ((fam.dof_comp == 2) & rail).astype(float)
    out = {}
    if fam.name == "sym":
        m = ones_z @ (Ms @ ones_z)
        out["mean_z"] = (Ms @ ones_z) / m
    else:
        m = ones_y @ (Ms @ ones_y)
        out["mean_y"] = (Ms @ ones_y) / m
        rot = np.where(fam.dof_comp == 1, -z, 0.0) + np.where(fam.dof_comp == 2, y, 0.0)
        rot = rot * rail
        Ip = rot @ (Ms @ rot)
        out["rot_x"] = (Ms @ rot) / Ip
    return out


def build_rail_model(rail: dict, msh_path, contact_y=None, basis: dict | None = None,
                     with_centre: bool = True, verbose: bool = False) -> RailModel:
    """Read the half-section mesh written by geometry.rail.mesh_rail,
    assemble, calibrate the pad, build both supported families and their
    reduced models with unit loads in y and z at the contact nodes (and at
    the head centre, y = 0, for decay rates).  ``basis`` overrides the
    keyword arguments of reduce_family."""
    import time

    from geometry.mesher import read_msh

    t0 = time.perf_counter()
    mesh, ct, ft = read_msh(msh_path)
    asm = wg.assemble(mesh, ct, ft)
    calib = wg.pad_calibration(asm, rail["pad"]["poisson"])
    mat = wg.material_moduli(rail, calib=calib)
    tors = wg.torsion_properties(mesh, ct)
    if contact_y is None:
        contact_y = rail.get("contact", {}).get("y", [])
    ys = list(np.abs(contact_y)) + ([0.0] if with_centre else [])
    fams = {n: wg.family(asm, mat, n, supported=True) for n in ("sym", "anti")}
    py, pz, _ = _head_nodes(fams["sym"], rail, ys)
    basis = dict(basis or {})
    red = {}
    snaps = {}
    for name, fam in fams.items():
        loads = {}
        for y, z in zip(py, pz):
            nd = fam.node_at(y, z, tol=2e-6)
            for c, lab in ((1, "y"), (2, "z")):
                try:
                    d = fam.dof(nd, c)
                except KeyError:  # constrained on the symmetry line for this family
                    continue
                e = np.zeros(fam.M.shape[0])
                e[d] = 1.0
                loads[(float(y), lab)] = e
        resp = dict(loads)
        for key, vec in section_functionals(fam, tors["z_centroid"]).items():
            resp[key] = vec
        kw = dict(basis)
        k_modes = kw.pop("k_modes", (0.0, 1.5, 4.0, 8.0, 13.0, 20.0, 30.0, 45.0))
        f_basis = kw.pop("f_basis", 10000.0)
        snaps[name] = {k: wg.eig_real_k(fam, k, f_basis) for k in k_modes}
        red[name] = reduce_family(fam, loads, resp, k_modes=k_modes, f_basis=f_basis,
                                  snapshots=snaps[name], **kw)
        if verbose:
            print(f"family {name}: {fam.M.shape[0]} dofs -> {red[name].size} "
                  f"({red[name].BW.shape[1]} W + {red[name].BY.shape[1]} yz), {time.perf_counter() - t0:.1f} s")
    props = {"torsion": tors, "pad": mat["pad"], "steel": mat["rail"], "calibration": calib}
    return RailModel(rail, py, pz, red["sym"], red["anti"], fams, props, snaps, asm, mat)


def _pairs_for(rf: ReducedFamily, y: float):
    """(out, in) index pairs for (yy, zz, yz, zy) at head point |y| in this
    family, None where the dof is constrained (symmetry line)."""
    idx_in = {key: i for i, key in enumerate(rf.in_names)}
    idx_out = {key: i for i, key in enumerate(rf.out_names)}
    out = []
    for a, b in (("y", "y"), ("z", "z"), ("y", "z"), ("z", "y")):
        ko, ki = (float(y), a), (float(y), b)
        out.append((idx_out[ko], idx_in[ki]) if (ko in idx_out and ki in idx_in) else None)
    return out


def wave_table(model: RailModel, freqs, points=None, local: str = "exclude", k_local: float = 20.0) -> dict:
    """The receptances of the head points as wave sums, for any distance:

        G[p, i, j](x, f) = sum_n a[f, n, p, i, j] exp(-i k[f, n] |x|)

    (both families and, with local='exclude', the subtracted static near
    field merged into one list of M waves).  i, j index the SPEC directions
    (0 = 2 lateral to the field side, 1 = 3 vertical downward).  Compact
    (nf x M x np x 4 numbers, M ~ 150) and exact at every x: the natural
    input for the moving Green's functions (SPEC 3.4, x = v t).

    Returns {'k': (nf, M) complex rad/m (Im k <= 0), 'a': (nf, M, np, 2, 2)
    complex m/N, 'f', 'y', 'z'}."""
    if local not in ("exclude", "fe"):
        raise ValueError("local must be 'exclude' or 'fe'")
    freqs = np.asarray(freqs, float)
    if points is None:
        points = model.rail.get("contact", {}).get("y", [])
    points = np.asarray(points, float)
    missing = [y for y in points if not np.any(np.isclose(abs(y), model.point_y, atol=1e-9))]
    if missing:
        raise ValueError(f"head points {missing} are not loaded in this model (available |y^R|: "
                         f"{model.point_y.tolist()}); rebuild it with build_rail_model(..., contact_y=...)")
    omegas = 2 * np.pi * freqs
    uniq = np.unique(np.round(np.abs(points), 10))
    zmap = dict(zip(np.round(model.point_y, 10), model.point_z))
    ij = ((0, 0), (1, 1), (0, 1), (1, 0))
    Ks, As = [], []
    for fname in ("sym", "anti"):
        rf = getattr(model, fname)
        pairs, slots = [], []
        for yy in uniq:
            for s, pr in enumerate(_pairs_for(rf, yy)):
                if pr is not None:
                    pairs.append(pr)
                    slots.append((yy, s))
        Kf, Af = wave_amplitudes(rf, omegas, pairs, k_local=k_local if local == "exclude" else None)
        a = np.zeros(Kf.shape + (len(points), 2, 2), complex)
        for q, (yy, s) in enumerate(slots):
            for ip, yp in enumerate(points):
                if np.isclose(abs(yp), yy):
                    sign_mirror = -1.0 if (yp < 0 and s >= 2) else 1.0
                    # z-up section -> SPEC direction 3 downward: yz and zy flip sign
                    sign_dir = -1.0 if s >= 2 else 1.0
                    i, j = ij[s]
                    a[:, :, ip, i, j] += 0.5 * sign_mirror * sign_dir * Af[:, :, q]
        Ks.append(Kf)
        As.append(a)
    return {"k": np.concatenate(Ks, axis=1), "a": np.concatenate(As, axis=1), "f": freqs, "y": points,
            "z": np.array([zmap[np.round(abs(p), 10)] for p in points])}


def evaluate_table(table: dict, distances, block: int = 32) -> np.ndarray:
    """G (np, nx, nf, 2, 2) from a wave_table at distances x (|x| used)."""
    x = np.abs(np.asarray(distances, float))
    K, a = table["k"], table["a"]
    nf, M, npt = a.shape[:3]
    G = np.empty((npt, len(x), nf, 2, 2), complex)
    for s in range(0, nf, block):
        e = np.exp(-1j * K[s:s + block, :, None] * x[None, None, :])  # (b, M, nx)
        G[:, :, s:s + block] = np.einsum("fnpij,fnx->pxfij", a[s:s + block], e, optimize=True)
    return G


def receptances(model: RailModel, freqs, distances, points=None, local: str = "exclude",
                k_local: float = 20.0, local_C: dict | None = None) -> dict:
    """Point (x = 0) and transfer receptances at the rail-head points.

    freqs (nf,) Hz, distances (nx,) m (|x| is used; G is even in x),
    points: y^R of the head points (default: the rail's contact points;
    they must be among the model's loaded points, model.point_y).

    local: what to do with the static near field of the loaded zone (the
    frequency-independent local compliance, ~5e-9 m/N at a head node, as
    large as the whole track receptance at low frequency and growing
    without bound as the mesh is refined -- a point load on a continuum):
      'exclude' (default): subtract it (waves with |k| > k_local rad/m at
          w = 0; the beam waves of the supported rail have |k| < 3 rad/m
          there, the section's near field |k| > 25 rad/m) -> the structural
          receptance; the local deformation is the contact model's
          (half-space influence coefficients, SPEC 3.5: g(0) = 0);
      'fe': the FE nodal point receptance of this mesh: the reduced wave
          sum plus ``local_C`` (from local_compliance(model)) at x = 0.
    Returns {'G': (np, nx, nf, 2, 2) complex m/N in SPEC directions
    (index 0 = direction 2 lateral to the field side, 1 = direction 3
    vertical downward), 'y', 'z' (point positions), 'x', 'f'}.
    G[p, :, :, 0, 1] is G23 (lateral response to a vertical force)."""
    T = wave_table(model, freqs, points, local=local, k_local=k_local)
    x = np.asarray(distances, float)
    G = evaluate_table(T, x)
    if local == "fe":
        if local_C is None:
            raise ValueError("local='fe' needs local_C = local_compliance(model)")
        at0 = np.isclose(np.abs(x), 0.0)
        S = np.array([[1.0, -1.0], [-1.0, 1.0]])  # z up -> direction 3 down
        for ip, yp in enumerate(T["y"]):
            key = float(np.round(abs(yp), 10))
            C = 0.5 * (local_C[("sym", key)] + local_C[("anti", key)]) * S
            if yp < 0:  # mirror image: the cross terms change sign
                C = C * S
            for ix in np.where(at0)[0]:
                G[ip, ix] += C[None, :, :]
    return {"G": G, "y": T["y"], "z": T["z"], "x": x, "f": T["f"]}


def static_wavenumbers(model: RailModel) -> dict:
    """|k| (rad/m) of all waves at w = 0 per family, sorted: the beam waves
    (a few, |k| < ~5) and then the section's near field; ``k_local`` must
    fall in the gap."""
    return {f: np.sort(np.abs(waves(getattr(model, f), 0.0)[0])) for f in ("sym", "anti")}


def decay_rates(model: RailModel, freqs, y: float = 0.0, k_local: float = 20.0) -> dict:
    """Track decay rates (dB/m) of the vertical and lateral point receptance
    at head point y (default the head centre), EN 15461-style but from the
    exact wave sum: DR = 10 log10(e) |G(0)|^2 / int_0^inf |G(x)|^2 dx
    (structural receptance, local near field excluded).  Also returns,
    per family, the attenuation 8.686 |Im k| (dB/m) of the least-attenuated
    wave."""
    omegas = 2 * np.pi * np.asarray(freqs, float)
    out = {"f": np.asarray(freqs, float)}
    for fname, comp, key in (("sym", "z", "vertical"), ("anti", "y", "lateral")):
        rf = getattr(model, fname)
        pr = _pairs_for(rf, y)[0 if comp == "y" else 1]
        Kf, Af = wave_amplitudes(rf, omegas, [pr], k_local=k_local)
        g0 = Af[:, :, 0].sum(axis=1)
        integ = decay_integral(Kf, Af)[0]
        out[key] = 10 * np.log10(np.e) * np.abs(g0) ** 2 / integ
        out[f"min_wave_{fname}"] = DB_PER_NEPER * np.min(np.abs(Kf[:, :rf.size].imag), axis=1)
    return out


def beam_transfer(model: RailModel, freqs, y: float = 0.0) -> dict:
    """Receptances from a unit head load at |y| to the section-mean
    (beam) displacements: 'vertical' = mean u_z per vertical force at the
    head (SPEC sign: both downward), 'lateral' = mean u_y per lateral
    force, 'rotation' = section rotation per lateral force.  x = 0."""
    omegas = 2 * np.pi * np.asarray(freqs, float)
    out = {}
    for fname, resp, comp, key in (("sym", "mean_z", "z", "vertical"), ("anti", "mean_y", "y", "lateral"),
                                   ("anti", "rot_x", "y", "rotation")):
        rf = getattr(model, fname)
        io = rf.out_names.index(resp)
        ii = rf.in_names.index((float(y), comp))
        Kf, Af = wave_amplitudes(rf, omegas, [(io, ii)])
        # G_full = (G_sym + G_anti) / 2 and the other family does not contribute to these
        # responses; vertical: z up in both force and response, i.e. SPEC 33 unchanged
        out[key] = 0.5 * Af[:, :, 0].sum(axis=1)
    return out


# --------------------------------------------------------------------------- local (contact-zone) compliance
def reduced_H(rf: ReducedFamily, k: float, omega: float, io: list[int], ii: list[int]) -> np.ndarray:
    """Wavenumber-domain receptance of the reduced family at real k."""
    mW = rf.BW.shape[1]
    mY = rf.BY.shape[1]
    A = np.block([[rf.K0W + k * k * rf.K2W - omega**2 * np.eye(mW), k * rf.K1WY],
                  [k * rf.K1WY.T, rf.K0Y + k * k * rf.K2Y - omega**2 * np.eye(mY)]])
    rhs = np.vstack([np.zeros((mW, len(ii))), rf.inputs[ii].T])
    X = np.linalg.solve(A, rhs)
    return rf.outputs[io] @ X[mW:]


def local_compliance(model: RailModel, k_lo: float = 20.0, k_hi: float = 1e5, n: int = 90, points=None) -> dict:
    """The part of the FE point receptance that the reduced model leaves out:
    the static compliance of the contact zone (wavenumbers >> 1/section
    size), C = (1/pi) int_0^inf [H_full(k) - H_reduced(k)] dk at w = 0 (the
    integrand vanishes below ~k_lo; 1/k^2 tail added analytically).  It is
    frequency independent (checked in tests/rail/test_response.py), depends
    on the element size at the load node (a point load on a continuum has
    an infinite local compliance) and belongs to the contact model (SPEC
    3.5: g(0) = 0, the contact compliance takes its place), so it is NOT in
    the receptances unless asked for.  Returns {(family, |y|): 2x2 complex
    matrix [[yy, yz], [zy, zz]] in section axes (z up) for a unit load on
    the half model} for the head points |y| in ``points`` (default all)."""
    out = {}
    kk = np.geomspace(k_lo, k_hi, n)
    for fname in ("sym", "anti"):
        fam, rf = model.families[fname], getattr(model, fname)
        idx_in = {key: i for i, key in enumerate(rf.in_names)}
        idx_out = {key: i for i, key in enumerate(rf.out_names)}
        ys = model.point_y if points is None else np.unique(np.round(np.abs(points), 10))
        for y in ys:
            y = float(y)
            comps = [c for c in ("y", "z") if (float(y), c) in idx_in]
            ii = [idx_in[(float(y), c)] for c in comps]
            io = [idx_out[(float(y), c)] for c in comps]
            Fd = np.column_stack([list(rf_loads_vec(fam, model, y, c)) for c in comps])
            Hd = np.empty((len(kk), len(comps), len(comps)), complex)
            for j, k in enumerate(kk):
                X = splu(fam.K(k, complex_moduli=True).tocsc()).solve(Fd.astype(complex))
                Hd[j] = Fd.T @ X - reduced_H(rf, k, 0.0, io, ii)
            # int over log k: dk = k du
            integ = np.trapz(Hd * kk[:, None, None], np.log(kk), axis=0) + Hd[-1] * kk[-1]
            C = np.zeros((2, 2), complex)
            for a, ca in enumerate(comps):
                for b, cb in enumerate(comps):
                    C["yz".index(ca), "yz".index(cb)] = integ[a, b] / np.pi
            out[(fname, float(y))] = C
    return out


def rf_loads_vec(fam: wg.Family, model: RailModel, y: float, comp: str) -> np.ndarray:
    z = float(model.point_z[np.isclose(model.point_y, y)][0])
    nd = fam.node_at(y, z, tol=2e-6)
    e = np.zeros(fam.M.shape[0])
    e[fam.dof(nd, 1 if comp == "y" else 2)] = 1.0
    return e


# --------------------------------------------------------------------------- everything a pipeline stage saves
def stage_arrays(model: RailModel, freqs, distances, ks=None, fmax: float = 6500.0,
                 decay_freqs=None, head_y=None) -> dict:
    """All artifact arrays of a rail stage as a flat {name: ndarray} (SI):

    receptances    f_hz (nf,), x_m (nx,), point_y_m, point_z_m (np,),
                   G (np, nx, nf, 2, 2) complex m/N, SPEC directions
                   [2 lateral to field, 3 vertical down], structural;
    wave table     wave_k (nf, M) complex rad/m, wave_a (nf, M, np, 2, 2)
                   complex m/N: G(x) = sum_n wave_a exp(-i wave_k |x|) at any x;
    decay          decay_f_hz (nd,), decay_vertical_db_per_m, decay_lateral_db_per_m;
    dispersion     disp_k (nk,) rad/m and, for s in (free, supported),
                   fam in (sym, anti): disp_{s}_{fam}_f_hz (nk, nb) Hz (NaN
                   where a branch is absent), disp_{s}_{fam}_label (nb,),
                   disp_{s}_{fam}_point_label (nk, nb) (wave types);
    section        section_area_m2, section_mass_per_m, section_I_vertical_m4,
                   section_I_lateral_m4, section_J_m4, section_Gamma_m6,
                   section_z_centroid_m, section_z_shear_centre_m,
                   pad_E_pa, pad_k_vertical_n_per_m2, pad_k_lateral_n_per_m2,
                   pad_k_rocking_nm_per_rad_m;
    head profile   head_y_m (nh,), head_z_m (nh,) (z^R above the foot underside).
    """
    from geometry.rail import head_profile

    out = {}
    T = wave_table(model, freqs)
    x = np.asarray(distances, float)
    out.update(f_hz=T["f"], x_m=x, point_y_m=T["y"], point_z_m=T["z"], G=evaluate_table(T, x),
               wave_k=T["k"], wave_a=T["a"])
    fd = np.geomspace(25.0, float(np.max(freqs)), 200) if decay_freqs is None else np.asarray(decay_freqs, float)
    d = decay_rates(model, fd)
    out.update(decay_f_hz=fd, decay_vertical_db_per_m=d["vertical"], decay_lateral_db_per_m=d["lateral"])
    ks = np.linspace(0.0, 30.0, 31) if ks is None else np.asarray(ks, float)
    out["disp_k"] = ks
    zc = model.props["torsion"]["z_centroid"]
    for sup in (False, True):
        for fam_name in ("sym", "anti"):
            fam = model.families[fam_name] if sup else wg.family(model.asm, model.materials, fam_name, False)
            dd = wg.dispersion(fam, ks, fmax, model.rail, zc)
            key = f"disp_{'supported' if sup else 'free'}_{fam_name}"
            out[key + "_f_hz"] = dd["f"]
            out[key + "_label"] = dd["label"].astype(str)
            out[key + "_point_label"] = dd["point_label"].astype(str)
    t, pad = model.props["torsion"], model.props["pad"]
    out.update(section_area_m2=t["area"], section_mass_per_m=model.rail["material"]["rho"] * t["area"],
               section_I_vertical_m4=t["I_vertical"], section_I_lateral_m4=t["I_lateral"], section_J_m4=t["J"],
               section_Gamma_m6=t["Gamma"], section_z_centroid_m=t["z_centroid"],
               section_z_shear_centre_m=t["z_shear_centre"], pad_E_pa=pad["E"],
               pad_k_vertical_n_per_m2=pad["k_vertical"], pad_k_lateral_n_per_m2=pad["k_lateral"],
               pad_k_rocking_nm_per_rad_m=pad["k_rocking"])
    hy = np.linspace(-model.rail["head"]["width"] / 2, model.rail["head"]["width"] / 2, 281) if head_y is None \
        else np.asarray(head_y, float)
    out.update(head_y_m=hy, head_z_m=head_profile(model.rail, hy))
    return {k: np.asarray(v) for k, v in out.items()}
