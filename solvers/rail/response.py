"""Forced response of the continuously supported rail: point and transfer
receptances by the wave expansion (residues of the wavenumber integral).

SPEC 3.2 / 3.4.  For a harmonic load F exp(i w t) at x = 0 the response of
the waveguide (``solvers.rail.waveguide``) at distance x is the wavenumber
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

import numpy as np
from scipy.sparse.linalg import splu

from solvers.rail import waveguide as wg
from solvers.rail.model import RailModel, contact_points
from solvers.rail.reduced import ReducedFamily, decay_integral, evaluate, reduced_H, wave_amplitudes, waves  # noqa: F401

DB_PER_NEPER = 20.0 / np.log(10.0)  # 8.686 dB per neper


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
        points = contact_points(model.rail)
    points = np.asarray(points, float)
    missing = [y for y in points if not np.any(np.isclose(abs(y), model.point_y, atol=1e-9))]
    if missing:
        raise ValueError(f"head points {missing} are not loaded in this model (available |y^R|: "
                         f"{model.point_y.tolist()}); rebuild it with contact_y=...")
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
    a2 = a.reshape(nf, M, npt * 4).transpose(0, 2, 1)               # (nf, np*4, M)
    for s in range(0, nf, block):
        e = np.exp(-1j * K[s:s + block, :, None] * x[None, None, :])  # (b, M, nx)
        r = np.matmul(a2[s:s + block], e)                             # (b, np*4, nx): one product per f
        G[:, :, s:s + block] = r.reshape(-1, npt, 2, 2, len(x)).transpose(1, 4, 0, 2, 3)
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
        out[key] = wave_sum_decay_rate(Kf, Af[:, :, 0])
        out[f"min_wave_{fname}"] = DB_PER_NEPER * np.min(np.abs(Kf[:, :rf.size].imag), axis=1)
    return out


def wave_sum_decay_rate(K: np.ndarray, a: np.ndarray) -> np.ndarray:
    """The decay rate (dB/m) of the receptance G(x) = sum_n a[f, n] exp(-i K[f, n] |x|) at each
    frequency: 10 log10(e) |G(0)|^2 / int_0^inf |G(x)|^2 dx (``decay_rates``; waves of zero
    amplitude, e.g. the other family's in a wave table, add nothing)."""
    return 10 * np.log10(np.e) * np.abs(a.sum(axis=1)) ** 2 / decay_integral(K, a[:, :, None])[0]


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
