"""Frequency-domain stability screen: the time loop linearised about steady rolling.

The squeal time loop (``solvers.interaction``, SPEC 3.5, 4.1-4.4) is a discrete-time
system.  About its steady rolling state (preload F3, rigid slip w2 = gamma_y v,
gamma_x = 0, so F1 = 0 throughout) every part of it is linear in the deviations
but the friction curve and the NORM table, and those two are linearised:

* structures, [4.13]-[4.15]: xi[n] = sum_{k>=1} (g^R_mov[k] + g^W[k]) dF[n-k], with
  xi = xi^R - xi^W on directions (2, 3).  In the z domain xi = Y(z) dF with
  Y(z) = sum_k g[k] z^-k; the wheel part is the exact transform of the recursive
  modal filters (one pole pair per mode), the rail part the finite sum over the
  moving kernel's lags;
* normal contact [4.19]-[4.24]: dF3 = -k_c dxi3 (k_c = dF3/d approach of the NORM
  table at the static approach);
* tangential point contact [4.25]-[4.31] with s2 < 0 (gamma_y < 0, F2 > 0):
  F2 = mu_RF(|s2|) F3, s2 = gamma_y v + (A2 (F2[n] - F2[n-1]) + xi2[n] - xi2[n-1]) / dt, so
  dF2 = mu0 dF3 - q (A2 dF2 + dxi2) with q = F3 mu_RF'(s0) (1 - z^-1) / dt
  (mu0 = mu_RF(s0), s0 = |gamma_y| v; in full slip mu_RF' = 0 and dF2 = mu0 dF3).

So M(z) dF = 0 with

    M = [[1 + q A2 + q Y22,   -mu0 + q Y23],
         [k_c Y32,             1 + k_c Y33 ]]

and the closed-loop poles are the roots z = exp(s dt) of D(s) = det M.  In full
slip D = 1 + k_c (Y33 + mu0 Y32): the single-mode estimate of the interaction
validation (kappa_r = Phi3 (Phi3 + mu Phi2) < 0 destabilises) is its one-mode limit.
Roots near each wheel mode are found by Newton's method on D times the mode's
pole pair (a function regular at the open-loop pole), started at the open-loop
pole; the low-frequency roots of the wheelset on the track (20-400 Hz) by a grid
of starting points.  Growth rate sigma = Re s (1/s), frequency Im s / 2 pi.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .green import modal_filter


class LinearModel(NamedTuple):
    """The linearised time loop (module notes).  Units SI."""
    f_r: np.ndarray          # wheel modal frequencies (Hz), (M,)
    modal_mass: np.ndarray   # (M,) kg
    zeta: np.ndarray         # (M,)
    phi: np.ndarray          # (M, 2) = (Phi_2, Phi_3) at the contact point
    rail_kernel: np.ndarray  # moving Green's function (K, 2, 2) m/N, g[0] unused
    dt: float                # time step (s)
    kc: float                # normal contact stiffness dF3/d approach (N/m)
    mu0: float               # mu_RF at the operating slip
    dmu: float               # d mu_RF / d s at the operating slip (s/m)
    F3: float                # preload (N)
    A2: float                # lateral tangential compliance (m/N)


class Root(NamedTuple):
    f_hz: float              # frequency of the closed-loop pole (Hz)
    sigma: float             # growth rate (1/s), > 0 unstable
    mode: int                # index of the wheel mode it continues (-1: low-frequency track root)


def wheel_receptance_z(model: LinearModel, z: complex) -> np.ndarray:
    """Y^W(z) (2, 2): the z-transform of the modal filters' kernel (g[0] = 0)."""
    filt = modal_filter(model.dt, model.f_r, model.modal_mass, model.zeta, model.phi)
    return _wheel_z(filt, z)


def _wheel_z(filt, z: complex, skip: int = -1) -> np.ndarray:
    kind, zp, p2, w_in, w_out = filt.kind, filt.z, filt.p2, filt.w_in, filt.w_out
    # kind 0: y[k] = Im(zp^k) -> (zp/(z-zp) - conj(zp)/(z-conj zp)) / 2i; kind 1: (zp^k - p2^k) sums
    h = np.empty(len(kind), complex)
    k0 = kind == 0
    a, b = zp[k0], np.conj(zp[k0])
    h[k0] = (a / (z - a) - b / (z - b)) / 2j
    # kind 1 (zeta >= 1, two real poles a, b): y[k] = (a^k - b^k)/(a - b), k >= 1 (modal_filter's
    # two-state recursion); a = b (zeta = 1): y[k] = k a^(k-1), transform z/(z - a)^2
    a, b = zp[~k0].real, p2[~k0].real
    same = np.abs(a - b) <= 1e-12 * np.abs(a)
    with np.errstate(divide="ignore", invalid="ignore"):
        h1 = np.where(same, z / (z - a) ** 2, (a / (z - a) - b / (z - b)) / np.where(same, 1.0, a - b))
    h[~k0] = h1
    if skip >= 0:
        h = h.copy()
        h[skip] = 0.0
    return np.einsum("r,ri,rj->ij", h, w_out, w_in)


def rail_receptance_z(kernel: np.ndarray, z: complex) -> np.ndarray:
    """Y^R(z) = sum_{k>=1} g[k] z^-k (2, 2) of the moving kernel."""
    k = np.arange(1, kernel.shape[0])
    return np.einsum("k,kij->ij", z ** (-k.astype(float)), kernel[1:])


def _det(model: LinearModel, Y: np.ndarray, z: complex) -> complex:
    q = model.F3 * model.dmu * (1.0 - 1.0 / z) / model.dt
    M = np.array([[1.0 + q * model.A2 + q * Y[0, 0], -model.mu0 + q * Y[0, 1]],
                  [model.kc * Y[1, 0], 1.0 + model.kc * Y[1, 1]]])
    return M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]


def characteristic(model: LinearModel, s: complex, filt=None) -> complex:
    """D(s) = det M(exp(s dt)) (module notes)."""
    filt = filt if filt is not None else modal_filter(model.dt, model.f_r, model.modal_mass, model.zeta, model.phi)
    z = np.exp(s * model.dt)
    Y = _wheel_z(filt, z) + rail_receptance_z(model.rail_kernel, z)
    return _det(model, Y, z)


def _newton(fun, s0: complex, tol: float = 1e-10, max_iter: int = 60) -> complex | None:
    """Secant iteration on a complex analytic function: a root (relative step below ``tol`` and
    |fun| below 1e-6 of its value at the start) or None."""
    s1 = s0 * (1 + 1e-6) + 1e-3
    f0, f1 = fun(s0), fun(s1)
    scale = max(abs(f0), abs(f1))
    with np.errstate(all="ignore"):
        return _secant(fun, s0, s1, f0, f1, scale, tol, max_iter)


def _secant(fun, s0, s1, f0, f1, scale, tol, max_iter):
    for _ in range(max_iter):
        if f1 == f0:
            break
        s2 = s1 - f1 * (s1 - s0) / (f1 - f0)
        if not np.isfinite(s2):
            return None
        s0, f0 = s1, f1
        s1, f1 = s2, fun(s2)
        if abs(s1 - s0) <= tol * max(abs(s1), 1.0):
            return s1 if abs(f1) <= 1e-6 * scale else None
    return None


def wheel_roots(model: LinearModel, modes=None) -> list[Root]:
    """The closed-loop pole continuing each lightly damped wheel mode (zeta < 0.5)."""
    filt = modal_filter(model.dt, model.f_r, model.modal_mass, model.zeta, model.phi)
    kern = model.rail_kernel
    idx = range(len(model.f_r)) if modes is None else modes
    out = []
    for r in idx:
        if model.zeta[r] >= 0.5:
            continue
        zr = filt.z[r]
        # D (z - zr)(z - conj zr): regular at the open-loop pole pair of mode r
        rest = lambda z, r=r: _wheel_z(filt, z, skip=r)                                   # noqa: E731

        def fun(s, r=r, zr=zr):
            z = np.exp(s * model.dt)
            pp = (z - zr) * (z - np.conj(zr))
            # mode r's term times its pole pair: (zr (z - conj zr) - conj zr (z - zr)) / 2i
            hr = (zr * (z - np.conj(zr)) - np.conj(zr) * (z - zr)) / 2j
            Yr = hr * np.outer(filt.w_out[r], filt.w_in[r])
            Y = rest(z) + rail_receptance_z(kern, z)
            q = model.F3 * model.dmu * (1.0 - 1.0 / z) / model.dt
            Yt = pp * Y + Yr
            M00 = pp * (1.0 + q * model.A2) + q * Yt[0, 0]
            M01 = -model.mu0 * pp + q * Yt[0, 1]
            M10 = model.kc * Yt[1, 0]
            M11 = pp + model.kc * Yt[1, 1]
            return (M00 * M11 - M01 * M10) / pp
        s0 = np.log(zr) / model.dt
        s = _newton(fun, complex(s0) + complex(1e-3, 1e-3))
        if s is not None and abs(s.imag - s0.imag) < 0.2 * abs(s0.imag) + 2 * np.pi * 5:
            out.append(Root(s.imag / (2 * np.pi), s.real, int(r)))
    return out


def _wheel_z_many(filt, z: np.ndarray) -> np.ndarray:
    """Y^W at many points z (P,) -> (P, 2, 2)."""
    kind, zp, p2 = filt.kind, filt.z, filt.p2
    zz = z[:, None]
    k0 = kind == 0
    a, b = zp[None, k0], np.conj(zp[None, k0])
    H = np.empty((len(z), len(kind)), complex)
    H[:, k0] = (a / (zz - a) - b / (zz - b)) / 2j
    if (~k0).any():
        a, b = zp[None, ~k0].real, p2[None, ~k0].real
        same = np.abs(a - b) <= 1e-12 * np.abs(a)
        with np.errstate(divide="ignore", invalid="ignore"):
            H[:, ~k0] = np.where(same, zz / (zz - a) ** 2, (a / (zz - a) - b / (zz - b)) / np.where(same, 1.0, a - b))
    return np.einsum("pr,ri,rj->pij", H, filt.w_out, filt.w_in)


def track_roots(model: LinearModel, f_lo: float = 20.0, f_hi: float = 400.0, sigma_lo: float = -20.0,
                sigma_hi: float = 400.0) -> list[Root]:
    """Closed-loop poles of the wheelset on the track with f_lo <= f <= f_hi (Hz) and growth rate
    sigma_lo <= sigma <= sigma_hi (1/s): local minima of |D| on a grid (FFT bins of ~1.7 Hz x
    10/s; the rail's transform on a row of constant sigma is one FFT of g[k] exp(-sigma k dt))
    refined by the secant method.  Below sigma ~ -30/s the finite moving kernel's transform
    amplifies its truncated tail, so strongly damped roots are not sought."""
    filt = modal_filter(model.dt, model.f_r, model.modal_mass, model.zeta, model.phi)
    g = model.rail_kernel.copy()
    g[0] = 0.0
    n_fft = 1 << int(np.ceil(np.log2(max(len(g), 1.0 / (2.0 * model.dt)))))
    fb = np.fft.fftfreq(n_fft, model.dt)
    cols = np.flatnonzero((fb >= f_lo) & (fb <= f_hi))
    fs = fb[cols]
    sg = np.arange(sigma_lo, sigma_hi + 1e-9, 10.0)
    k = np.arange(len(g))
    S = sg[:, None] + 2j * np.pi * fs[None, :]
    Z = np.exp(S * model.dt)
    Yr = np.stack([np.fft.fft(g * np.exp(-s * k * model.dt)[:, None, None], n=n_fft, axis=0)[cols] for s in sg])
    Y = Yr + _wheel_z_many(filt, Z.ravel()).reshape(*Z.shape, 2, 2)
    q = model.F3 * model.dmu * (1.0 - 1.0 / Z) / model.dt
    M00 = 1.0 + q * model.A2 + q * Y[..., 0, 0]
    M01 = -model.mu0 + q * Y[..., 0, 1]
    L = np.log(np.abs(M00 * (1.0 + model.kc * Y[..., 1, 1]) - M01 * model.kc * Y[..., 1, 0]))
    fun = lambda s: characteristic(model, s, filt)                                         # noqa: E731
    found = []
    for i in range(len(sg)):
        for j in range(1, len(fs) - 1):
            if L[i, j] > L[max(i - 1, 0):i + 2, j - 1:j + 2].min():
                continue
            s = _newton(fun, complex(S[i, j]))
            if s is None or not (f_lo <= s.imag / (2 * np.pi) <= f_hi and sigma_lo - 5 <= s.real <= sigma_hi):
                continue
            if all(abs(s - t) > 1e-4 * abs(s) for t in found):
                found.append(s)
    return [Root(s.imag / (2 * np.pi), s.real, -1) for s in sorted(found, key=lambda s: s.imag)]


def linearise(wheel, rail_kernel: np.ndarray, contact, *, dt: float, v: float, gamma_y: float,
              preload: float) -> LinearModel:
    """The LinearModel of the time loop's steady rolling state.

    wheel: ``interaction.WheelModes``; rail_kernel: the moving Green's function (K, 2, 2);
    contact: ``interaction.ContactModel``; dt (s), v (m/s), gamma_y (< 0), preload F3 (N)."""
    from .contact.compliance import table_compliance
    from .contact.friction import mu_and_slope
    from .contact.norm import table_force
    from .interaction import static_approach

    if gamma_y >= 0:
        raise ValueError(f"linearise: gamma_y = {gamma_y} must be negative (F2 > 0 on the rail)")
    app = static_approach(contact, preload)
    h = 1e-6 * app
    kc = (table_force(app + h, contact.xi3_nodes, contact.q_nodes)
          - table_force(app - h, contact.xi3_nodes, contact.q_nodes)) / (2 * h)
    mu0, dmu = mu_and_slope(abs(gamma_y) * v, contact.s_nodes, contact.mu_nodes, contact.slopes)
    A2 = table_compliance(app, contact.xi3_nodes, contact.A2_nodes)
    return LinearModel(np.asarray(wheel.f_r, float), np.asarray(wheel.modal_mass, float),
                       np.asarray(wheel.zeta, float), np.asarray(wheel.phi, float),
                       np.asarray(rail_kernel, float), float(dt), float(kc), float(mu0), float(dmu),
                       float(preload), float(A2))
