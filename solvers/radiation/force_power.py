"""Sound power of contact-force histories: the Thompson-Jones model (SPEC 5,
[4.38]-[4.57]) driven by the forces of a simulation's final stretch.

Pure functions on arrays (no file or configuration I/O); the pipeline's
``radiate`` stage loads the artifacts and calls these.

Fast form of [4.38] (the node averages of [4.54]-[4.57] as Gram matrices)
-------------------------------------------------------------------------
For harmonic n with modes r (participations q_r(f) = i W H_r(f) (Phi_r2 F2 +
Phi_r3 F3), H_r = 1 / (m_r (w_r^2 - W^2 + 2 i zeta_r w_r W)) [4.10],
``solvers.wheel.receptance.modal_frf``) the node
mean square of a surface is <v^2> = circ q^H (U^T U / N_nodes) q, circ = 1
(n = 0) or 1/2 (n > 0) [4.56].  The Gram matrices are summed with the areas
once per wheel, A_n = sum_q S_aq U_aq^T U_aq / N_aq (axial velocity U_z on the
annuli), B_n = S_r U_r^T U_r / N_r (radial velocity U_r), so

    W_n(f) = rho c0 circ [sigma_a(n, f) q^H A_n q + sigma_r(n, f) q^H B_n q]

costs (modes of n)^2 per frequency, independent of the number of nodes.

Force spectra: tones and residual
---------------------------------
The wheel's peaks are far narrower than an FFT bin (zeta = 1e-4: -3 dB band
2 zeta f_r = 0.09 Hz at 434 Hz, bins of 1/T = 2 Hz over a 0.5 s stretch), so
|G(f_k)|^2 |F_k|^2 on bins depends on where the bins fall relative to the
modes.  A squeal limit cycle is periodic: its force is a sum of tones, and the
wheel's steady response to a tone at f is G(f) F exactly.  So the stretch is
split (``decompose_forces``) into

* tones: the dominant peak of F2 (SPEC 6's dominant frequency), its frequency
  refined to ~1e-7 bin by maximising the Hann-windowed DTFT, the fundamental
  (the peak or its 1/2, 1/3 when those are spectral peaks too, within
  ``SUB_DB`` of it) and its
  harmonics k f0 that stand out of the local spectral floor (``PROMINENCE_DB``
  of F2 and F3 power combined) are fitted jointly to F2 and F3 by
  Hann-weighted least squares; up to ``MAX_SERIES`` such series (a second,
  incommensurate squeal tone); each tone gives complex RMS amplitudes of F2
  and F3 (their relative phase matters: v = G_2 F2 + G_3 F3), evaluated at
  its own frequency;
* residual: what the tones leave, as a Hann-windowed one-sided spectrum with
  power scaling (``spectra.amplitude_spectrum(..., scaling='power')``: the
  squared bins sum to the mean square), evaluated on the bins 0 < f <= f_max.

W is reported per entry (W per tone, W per bin), both in watts, so
L_W = 10 log10(sum W / 1e-12) is the total; the dominant sound frequency is
the entry with the largest W.  A stretch without tones (broadband, or a
constant force) is all residual.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Mapping

import numpy as np

from solvers.constants import F_MAX_HZ
from solvers.wheel.receptance import modal_frf

from solvers.radiation import thompson_jones as R
from solvers.radiation.surfaces import SurfaceNodes, Surfaces
from solvers.spectra import amplitude_spectrum, dominant_frequency, window_samples

PROMINENCE_DB = 20.0  # a tone's peak bin above the median of the bins 4..16 away (dB)
MAX_SERIES = 3        # harmonic series (fundamentals) fitted at most
MAX_TONES = 40        # tones fitted at most (all series)
FLOOR_BINS = (4, 16)  # the local floor: median of the bins this far from the peak
SUB_DB = 40.0         # a subharmonic fundamental is at most this far below the dominant peak (dB)


# --------------------------------------------------------------------------
# the wheel: per-harmonic modal data and area-weighted Gram matrices
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class RadiationModel:
    """Everything the sound power of a wheel driven at one contact point needs.

    ``f_r``, ``modal_mass``, ``zeta``, ``n``, ``m``, ``cls``: per mode (all
    modes of the wheel, rigid half-wheelset modes included, as in the
    simulation); ``phi`` (modes, 2) = (U_z, U_r) at the contact point
    (directions 2 lateral and 3 vertical); ``harmonics`` and ``groups`` (mode
    indices of each harmonic); ``A``/``B`` the Gram matrices above; ``r`` and
    ``gamma`` for the efficiencies; ``f_min`` the lowest tone searched,
    ``f_max`` the top of the band; ``meta`` free-form labels (case, wheel,
    contact point, surfaces)."""
    f_r: np.ndarray
    modal_mass: np.ndarray
    zeta: np.ndarray
    n: np.ndarray
    m: np.ndarray
    cls: np.ndarray
    phi: np.ndarray
    harmonics: np.ndarray
    groups: tuple
    A: tuple
    B: tuple
    r: float
    gamma: float
    rho: float = R.RHO_AIR
    c0: float = R.C0
    f_min: float = 20.0
    f_max: float = F_MAX_HZ
    meta: dict = field(default_factory=dict)

    def with_damping(self, zeta) -> "RadiationModel":
        """The same wheel with other modal damping ratios (e.g. the damping study's)."""
        z = np.asarray(zeta, float)
        if z.shape != self.f_r.shape or not np.all(z >= 0):
            raise ValueError(f"zeta: {self.f_r.size} non-negative ratios expected, got shape {z.shape}")
        return replace(self, zeta=z)

    def label(self, i: int) -> str:
        return f"({int(self.n[i])},{int(self.m[i])},{self.cls[i]})"


def build_model(modes: Mapping, surfaces: Surfaces, nodes: SurfaceNodes, phi, zeta, *,
                rho: float = R.RHO_AIR, c0: float = R.C0, f_min: float = 20.0, f_max: float = F_MAX_HZ,
                meta: dict | None = None) -> RadiationModel:
    """``modes``: f_hz, n, modal_mass, shapes (M, nodes, 3) = (U_r, U_z, U_phi)
    (and m, cls for labels; the wheel modal artifact works as is); ``phi`` (M, 2)
    = (U_z, U_r) at the contact point; ``zeta`` (M,) damping ratios."""
    f_r = np.asarray(modes["f_hz"], float)
    n = np.asarray(modes["n"], int)
    sh = np.asarray(modes["shapes"], float)
    M = f_r.size
    phi = np.asarray(phi, float)
    zeta = np.asarray(zeta, float)
    if phi.shape != (M, 2) or zeta.shape != (M,):
        raise ValueError(f"phi must be ({M}, 2) and zeta ({M},); got {phi.shape} and {zeta.shape}")
    harm = np.unique(n)
    groups, A, B = [], [], []
    for nn in harm:
        idx = np.flatnonzero(n == nn)
        a = np.zeros((idx.size, idx.size))
        for S, ax in zip(surfaces.S_a, nodes.axial):
            if len(ax):
                U = sh[idx][:, ax, 1]  # (k, nodes): axial velocity U_z on annulus q
                a += S * (U @ U.T) / len(ax)
        Ur = sh[idx][:, nodes.radial, 0]  # radial velocity U_r
        groups.append(idx)
        A.append(a)
        B.append(surfaces.S_r * (Ur @ Ur.T) / max(len(nodes.radial), 1))
    return RadiationModel(f_r=f_r, modal_mass=np.asarray(modes["modal_mass"], float), zeta=zeta, n=n,
                          m=np.asarray(modes["m"], int) if "m" in modes else np.zeros(M, int),
                          cls=np.asarray(modes["cls"]).astype(str) if "cls" in modes else np.full(M, "?"),
                          phi=phi, harmonics=harm, groups=tuple(groups), A=tuple(A), B=tuple(B),
                          r=float(surfaces.r), gamma=float(surfaces.gamma), rho=rho, c0=c0, f_min=f_min,
                          f_max=f_max, meta=dict(meta or {}))


def harmonic_power(model: RadiationModel, f, F2, F3) -> np.ndarray:
    """W_n(f) (harmonics, freqs) in W [4.38] for complex RMS force amplitudes
    F2(f), F3(f) on the wheel at the contact point (scalars or (freqs,))."""
    f = np.atleast_1d(np.asarray(f, float))
    F2 = np.broadcast_to(np.asarray(F2, complex), f.shape)
    F3 = np.broadcast_to(np.asarray(F3, complex), f.shape)
    W = 2 * np.pi * f
    out = np.zeros((model.harmonics.size, f.size))
    for h, (nn, idx) in enumerate(zip(model.harmonics, model.groups)):
        H = modal_frf(f, model.f_r[idx], model.modal_mass[idx], model.zeta[idx]).T  # [4.10]
        q = (1j * W) * H * (model.phi[idx, 0][:, None] * F2 + model.phi[idx, 1][:, None] * F3)  # [4.54]
        va = np.einsum("kf,kf->f", q.conj(), model.A[h] @ q).real  # sum_q S_aq <|v_aq|^2>
        vr = np.einsum("kf,kf->f", q.conj(), model.B[h] @ q).real  # S_r <|v_r|^2>
        circ = 1.0 if nn == 0 else 0.5  # [4.56]
        sa = R.sigma_axial(nn, f, model.r, model.c0)
        sr = R.sigma_radial(nn, f, model.r, model.gamma)
        out[h] = model.rho * model.c0 * circ * (sa * va + sr * vr)
    return out


# --------------------------------------------------------------------------
# force histories -> tones + residual spectrum
# --------------------------------------------------------------------------
@dataclass
class ForceDecomposition:
    """``tone_f`` (T,) Hz, ``tone_F2``/``tone_F3`` complex RMS amplitudes (N);
    ``series`` the fundamental of each tone's series; ``f``, ``R2``, ``R3`` the
    residual's power-scaled spectra on the bins 0 < f <= f_max; ``fundamentals``."""
    tone_f: np.ndarray
    tone_F2: np.ndarray
    tone_F3: np.ndarray
    series: np.ndarray
    f: np.ndarray
    R2: np.ndarray
    R3: np.ndarray
    fundamentals: list


def _prominent(P, k: int, ratio: float) -> bool:
    """Peak of the power spectrum P within one bin of k above ``ratio`` x the median of
    the bins FLOOR_BINS away."""
    lo, hi = FLOOR_BINS
    ring = np.r_[P[max(0, k - hi):max(0, k - lo + 1)], P[k + lo:k + hi + 1]]
    peak = P[max(0, k - 1):k + 2].max()
    return bool(peak > 0 and ring.size and peak > ratio * np.median(ring))


def refine_frequency(x, dt: float, f_est: float, half_width: float, steps: int = 5) -> float:
    """Frequency of the maximum of the Hann-windowed DTFT |sum w x exp(-2 pi i f t)| near
    f_est: parabolas through log|DTFT| at f - h, f, f + h (vertex clipped to +- h), h from
    half_width shrinking 4-fold per step (the main lobe is smooth and unimodal)."""
    x = np.asarray(x, float)
    wx = window_samples("hann", x.size) * (x - x.mean())
    # the DTFT as a two-level sum, n = a B + b: sum_a exp(-i th B a) sum_b wx[a B + b] exp(-i th b),
    # 2 sqrt(N) exponentials per frequency instead of N (the same sum to rounding)
    B = max(1, int(np.sqrt(x.size)))
    A = -(-x.size // B)
    wxb = np.zeros(A * B)
    wxb[:x.size] = wx
    wxb = wxb.reshape(A, B)
    a_idx, b_idx = np.arange(A) * B, np.arange(B)

    def g(f):
        th = -2j * np.pi * f * dt
        return np.log(max(abs(np.exp(th * a_idx) @ (wxb @ np.exp(th * b_idx))), np.finfo(float).tiny))

    f, h = float(f_est), float(half_width)
    b = g(f)
    for _ in range(steps):
        a, c = g(f - h), g(f + h)
        den = a - 2 * b + c
        if den < 0:
            f += h * float(np.clip(0.5 * (a - c) / den, -1.0, 1.0))
            b = g(f)
        elif c > b or a > b:
            f, b = (f + h, c) if c > a else (f - h, a)
        h /= 4
    return f


def _hann_sum(theta, N: int):
    """Z(theta) = sum_{n<N} w_n exp(i theta n) of the periodic Hann window w_n = 1/2 - 1/2 cos(2 pi n/N)
    (``window_samples``) in closed form: Dirichlet kernels D(theta) = sum_{n<N} exp(i theta n)
    = exp(i theta (N-1)/2) sin(N theta/2) / sin(theta/2) (N at theta = 0), Z = D(theta)/2 -
    (D(theta + 2 pi/N) + D(theta - 2 pi/N))/4.  For |theta| < 2 pi - 2 pi/N."""
    theta = np.asarray(theta, float)

    def dirichlet(a):
        s = np.sin(0.5 * a)
        zero = s == 0.0
        r = np.sin(0.5 * N * a) / np.where(zero, 1.0, s)
        return np.where(zero, float(N), r) * np.exp(0.5j * (N - 1) * a)

    phi = 2 * np.pi / N
    return 0.5 * dirichlet(theta) - 0.25 * (dirichlet(theta + phi) + dirichlet(theta - phi))


def _fit_tones(X, w, t, freqs):
    """Hann-weighted least squares of the columns of X (N, 2) on cos/sin at ``freqs``;
    returns (complex RMS amplitudes (T, 2), the fitted signal (N, 2)).  ``w``: the periodic Hann
    window (``window_samples('hann', N)``), ``t`` = n dt.  The normal equations' matrix
    D^T W D is summed in closed form (``_hann_sum`` of the sum and difference phases: products of
    cos/sin are cos/sin of sums and differences), not over the N samples."""
    if len(freqs) == 0:
        return np.zeros((0, 2), complex), np.zeros_like(X)
    N = len(t)
    T = len(freqs)
    dt = t[1] - t[0] if N > 1 else 1.0
    ph = 2 * np.pi * np.outer(t, freqs)
    D = np.empty((N, 2 * T))
    np.cos(ph, out=D[:, :T])
    np.sin(ph, out=D[:, T:])
    th = 2 * np.pi * dt * np.asarray(freqs, float)          # phase per sample of each tone
    Zd = _hann_sum(th[:, None] - th[None, :], N)
    Zs = _hann_sum(th[:, None] + th[None, :], N)
    G = np.empty((2 * T, 2 * T))
    G[:T, :T] = 0.5 * (Zd.real + Zs.real)                   # sum w cos_a cos_b
    G[T:, T:] = 0.5 * (Zd.real - Zs.real)                   # sum w sin_a sin_b
    G[:T, T:] = 0.5 * (Zs.imag - Zd.imag)                   # sum w cos_a sin_b
    G[T:, :T] = G[:T, T:].T
    # normal equations: tones >= 2 bins apart are nearly orthogonal under the Hann weight
    c = np.linalg.solve(G, D.T @ (X * w[:, None]))
    amp = (c[:T] - 1j * c[T:]) / np.sqrt(2)  # a cos + b sin = Re((a - i b) e^{i w t}); RMS = peak / sqrt 2
    return amp, D @ c


def decompose_forces(F2, F3, dt: float, *, f_min: float = 20.0, f_max: float = F_MAX_HZ,
                     prominence_db: float = PROMINENCE_DB) -> ForceDecomposition:
    """Split the (mean-removed) histories F2, F3 into tones and a residual (module docstring)."""
    X = np.column_stack([np.asarray(F2, float), np.asarray(F3, float)])
    X = X - X.mean(axis=0)
    N = X.shape[0]
    if N < 16:
        raise ValueError(f"need at least 16 samples of the forces, got {N}")
    w = window_samples("hann", N)
    t = np.arange(N) * dt
    df = 1.0 / (N * dt)
    top = min(f_max, 0.5 / dt - 2 * df)
    ratio = 10 ** (prominence_db / 10)
    freqs: list = []
    series: list = []
    fundamentals: list = []
    Y = X
    for _ in range(MAX_SERIES):
        f, S2 = amplitude_spectrum(Y[:, 0], dt)
        _, S3 = amplitude_spectrum(Y[:, 1], dt)
        P = np.abs(S2) ** 2 + np.abs(S3) ** 2
        band = (f >= f_min) & (f <= top)
        if not band.any() or not np.any(P[band] > 0):
            break
        # SPEC 6: the dominant frequency of F2 (of F3 when F2 has no oscillation left)
        S = S2 if np.any(np.abs(S2[band]) > 0) else S3
        try:
            f_est, _ = dominant_frequency(f, S, f_min=f_min, f_max=top)
        except ValueError:
            break
        k = int(round(f_est / df))
        if not _prominent(P, k, ratio) or any(abs(f_est - g) < 2 * df for g in freqs):
            break
        col = 0 if S is S2 else 1
        f_pk = refine_frequency(Y[:, col], dt, f_est, 0.5 * df)
        f0 = f_pk  # the fundamental: the peak, or f_pk/2, f_pk/3 when that is a spectral peak too
        for d in (3, 2):  # (prominent and within SUB_DB of the peak, so floor ripples do not count)
            j = int(round(f_pk / d / df))
            if f_pk / d >= f_min and _prominent(P, j, ratio) and P[j - 1:j + 2].max() >= 10 ** (-SUB_DB / 10) * P[k]:
                f0 = f_pk / d
                break
        new = [j * f0 for j in range(1, int(top / f0) + 1)
               if (abs(j * f0 - f_pk) < 0.5 * df or _prominent(P, int(round(j * f0 / df)), ratio))
               and all(abs(j * f0 - g) >= 2 * df for g in freqs)]
        new = new[:MAX_TONES - len(freqs)]
        if not new:
            break
        freqs += new
        series += [f0] * len(new)
        fundamentals.append(f0)
        amp, fit = _fit_tones(X, w, t, np.array(freqs))
        Y = X - fit
        if len(freqs) >= MAX_TONES:
            break
    if not freqs:
        amp = np.zeros((0, 2), complex)
    f, R2 = amplitude_spectrum(Y[:, 0], dt, scaling="power")
    _, R3 = amplitude_spectrum(Y[:, 1], dt, scaling="power")
    keep = (f > 0) & (f <= f_max)
    order = np.argsort(freqs) if freqs else np.zeros(0, int)
    return ForceDecomposition(tone_f=np.asarray(freqs, float)[order], tone_F2=amp[order, 0], tone_F3=amp[order, 1],
                              series=np.asarray(series, float)[order], f=f[keep], R2=R2[keep], R3=R3[keep],
                              fundamentals=fundamentals)


# --------------------------------------------------------------------------
# sound power of force histories
# --------------------------------------------------------------------------
def power_of_forces(model: RadiationModel, F2, F3, dt: float, decomposition: ForceDecomposition | None = None) -> dict:
    """Sound power of the wheel under the histories F2, F3 (N, on the rail; the wheel
    receives -F, which leaves mean squares unchanged) sampled at ``dt``.

    Returns 'f' (Hz: residual bins and tones, sorted), 'W' (W per entry), 'W_n'
    (harmonics, entries), 'harmonics', 'is_tone', 'L_W' (dB re 1e-12 W), 'f_sound'
    (frequency of the largest entry; NaN when W = 0), 'W_total', 'decomposition'."""
    d = decomposition or decompose_forces(F2, F3, dt, f_min=model.f_min, f_max=model.f_max)
    f = np.concatenate([d.f, d.tone_f])
    W_n = np.concatenate([harmonic_power(model, d.f, d.R2, d.R3),
                          harmonic_power(model, d.tone_f, d.tone_F2, d.tone_F3)], axis=1)
    is_tone = np.r_[np.zeros(d.f.size, bool), np.ones(d.tone_f.size, bool)]
    o = np.argsort(f, kind="stable")
    f, W_n, is_tone = f[o], W_n[:, o], is_tone[o]
    W = W_n.sum(axis=0)
    tot = float(W.sum())
    return {"f": f, "W": W, "W_n": W_n, "harmonics": model.harmonics, "is_tone": is_tone,
            "L_W": float(10 * np.log10(tot / R.W_REF)) if tot > 0 else -np.inf,
            "f_sound": float(f[np.argmax(W)]) if tot > 0 else float("nan"), "W_total": tot, "decomposition": d}


def unit_force_curve(model: RadiationModel, f, direction: str) -> np.ndarray:
    """W_n(f) (harmonics, freqs) for a unit RMS lateral (F2 = 1 N) or radial
    (F3 = 1 N) force at the contact point: W per N^2."""
    if direction not in ("lateral", "radial"):
        raise ValueError(f"direction: 'lateral' or 'radial', got {direction!r}")
    return harmonic_power(model, f, *((1.0, 0.0) if direction == "lateral" else (0.0, 1.0)))


def frequency_grid_for(model: RadiationModel, f_min: float, f_max: float) -> np.ndarray:
    """``radiation.frequency_grid`` over [f_min, f_max] resolving every mode's peak."""
    return R.frequency_grid(f_min, f_max, model.f_r, model.zeta)


def mode_at(model: RadiationModel, f: float, W_n_col) -> int:
    """The mode a sound peak at ``f`` belongs to: of the harmonic carrying most of the
    power there (``W_n_col``, (harmonics,)), the mode nearest in frequency."""
    h = int(np.argmax(W_n_col))
    idx = model.groups[h]
    return int(idx[np.argmin(np.abs(model.f_r[idx] - f))])
