"""The linearised time loop's characteristic function D(z) = det M(z) and its pieces (notes in
``solvers.stability.screen``): the linear model of an operating point, the wheel's modal transfer in z, the
rail kernel's transform, the determinant, and the secant step the root searches share.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from solvers.wheel.modal_filter import modal_filter


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
    dA2: float = 0.0         # d A2 / d approach at the static approach (1/N): the patch grows with F3
    A1: float = 0.0          # longitudinal tangential compliance (m/N)
    dA1: float = 0.0         # d A1 / d approach (1/N)
    e1: float = 0.0          # slip direction e = w / |w| at the operating point (e2 = -sqrt(1 - e1^2))
    sigma0: float = 0.0      # |w| (m/s), the operating slip velocity (used for e1 != 0)


class Root(NamedTuple):
    f_hz: float              # frequency of the closed-loop pole (Hz)
    sigma: float             # growth rate (1/s), > 0 unstable
    mode: int                # index of the wheel mode it continues (-1: low-frequency track root)


# ------------------------------------------------------------------------------ transforms

def _modal_terms(filt, z: np.ndarray) -> np.ndarray:
    """Per-mode scalar transforms h_r(z) (P, M): kind 0 (zeta < 1) y[k] = Im(p^k) ->
    (p/(z-p) - p*/(z-p*)) / 2i; kind 1 (two real poles a, b) y[k] = (a^k - b^k)/(a - b)
    (modal_filter's two-state recursion), a = b (zeta = 1): y[k] = k a^(k-1) -> z/(z-a)^2."""
    zz = np.asarray(z, complex).reshape(-1, 1)
    kind, zp, p2 = filt.kind, filt.z, filt.p2
    H = np.empty((zz.shape[0], len(kind)), complex)
    k0 = kind == 0
    a, b = zp[None, k0], np.conj(zp[None, k0])
    H[:, k0] = (a / (zz - a) - b / (zz - b)) / 2j
    if (~k0).any():
        a, b = zp[None, ~k0].real, p2[None, ~k0].real
        same = np.abs(a - b) <= 1e-12 * np.abs(a)
        with np.errstate(divide="ignore", invalid="ignore"):
            H[:, ~k0] = np.where(same, zz / (zz - a) ** 2, (a / (zz - a) - b / (zz - b)) / np.where(same, 1.0, a - b))
    return H


def _wheel_z(filt, z, skip: int = -1) -> np.ndarray:
    """Y^W at one point z (2, 2), optionally without mode ``skip``."""
    h = _modal_terms(filt, z)[0]
    if skip >= 0:
        h[skip] = 0.0
    return (h @ _outer(filt)).reshape(2, 2)


def _outer(filt) -> np.ndarray:
    """(M, 4): w_out[r] w_in[r]^T of every mode, flattened."""
    return np.einsum("ri,rj->rij", filt.w_out, filt.w_in).reshape(-1, 4)


def wheel_receptance_z(model: LinearModel, z: complex) -> np.ndarray:
    """Y^W(z) (2, 2): the z-transform of the modal filters' kernel (g[0] = 0)."""
    return _wheel_z(_filter(model), z)


def rail_receptance_z(kernel: np.ndarray, z: complex) -> np.ndarray:
    """Y^R(z) = sum_{k>=1} g[k] z^-k (2, 2) of the moving kernel."""
    w = np.exp(-np.log(complex(z)) * np.arange(1, kernel.shape[0]))
    K = kernel[1:].reshape(-1, 4)
    return (w.real @ K + 1j * (w.imag @ K)).reshape(2, 2)


def _filter(model: LinearModel):
    return modal_filter(model.dt, model.f_r, model.modal_mass, model.zeta, model.phi)


def _det(model, Y: np.ndarray, z, scale=1.0):
    """det M for Y (..., 2, 2) at z (...) (module notes); with ``scale`` c and Y = c Y_true,
    det(c M) = c^2 D."""
    if model.e1 != 0.0:
        return _det2(model, Y, z, scale)
    q = model.F3 * model.dmu * (1.0 - 1.0 / z) / model.dt
    M00 = scale * (1.0 + q * model.A2) + q * Y[..., 0, 0]
    M01 = (-model.mu0 + q * model.mu0 * model.F3 * model.dA2 / model.kc) * scale + q * Y[..., 0, 1]
    return M00 * (scale + model.kc * Y[..., 1, 1]) - M01 * model.kc * Y[..., 1, 0]


def _det2(model, Y, z, scale=1.0):
    """``_det`` with both tangential directions (module notes: dF1 eliminated)."""
    m = model
    e1 = m.e1
    e2 = -np.sqrt(1.0 - e1 * e1)
    D = (1.0 - 1.0 / z) / m.dt
    g = m.mu0 / m.sigma0
    K11 = m.F3 * (m.dmu * e1 * e1 + g * (1.0 - e1 * e1))
    K22 = m.F3 * (m.dmu * e2 * e2 + g * (1.0 - e2 * e2))
    K12 = m.F3 * (m.dmu - g) * e1 * e2
    F01, F02 = -m.F3 * m.mu0 * e1, -m.F3 * m.mu0 * e2
    rho = K12 * D * m.A1 / (1.0 + K11 * D * m.A1)
    c12 = K12 * D * (m.A2 * scale + Y[..., 0, 0])
    c13 = scale * (m.mu0 * e1 + D * (K11 * F01 * m.dA1 + K12 * F02 * m.dA2) / m.kc) + K12 * D * Y[..., 0, 1]
    c22 = scale + K22 * D * (m.A2 * scale + Y[..., 0, 0])
    c23 = scale * (m.mu0 * e2 + D * (K12 * F01 * m.dA1 + K22 * F02 * m.dA2) / m.kc) + K22 * D * Y[..., 0, 1]
    M00 = c22 - rho * c12
    M01 = c23 - rho * c13
    return M00 * (scale + m.kc * Y[..., 1, 1]) - M01 * m.kc * Y[..., 1, 0]


def characteristic(model: LinearModel, s: complex, filt=None) -> complex:
    """D(s) = det M(exp(s dt)) (module notes)."""
    filt = filt if filt is not None else _filter(model)
    z = np.exp(s * model.dt)
    return _det(model, _wheel_z(filt, z) + rail_receptance_z(model.rail_kernel, z), z)


# ------------------------------------------------------------------------------ root finding

def _secant(fun, s0: complex, tol: float = 1e-10, max_iter: int = 60) -> complex | None:
    """Secant iteration on a complex analytic function: a root (relative step below ``tol``, |fun|
    below 1e-6 of its value at the start and below 1e-2 of its values 1e-6 |s| away) or None.  The
    last test tells a zero from a point where a long jump out and back made the step small (the
    difference quotient taken across the jump): there |fun| is no smaller than around it (issue 34:
    r300/a2o's (6,0,a) 'root' at sigma = +28 1/s, |D| = 8.8; ``solvers.stability_nyquist``)."""
    s1 = s0 * (1 + 1e-6) + 1e-3
    with np.errstate(all="ignore"):
        f0, f1 = fun(s0), fun(s1)
        scale = max(abs(f0), abs(f1))
        for _ in range(max_iter):
            if f1 == f0:
                return None
            s2 = s1 - f1 * (s1 - s0) / (f1 - f0)      # s2 = s1 - f1 (s1 - s0) / (f1 - f0)
            if not np.isfinite(s2):
                return None
            s0, f0, s1, f1 = s1, f1, s2, fun(s2)
            if abs(s1 - s0) <= tol * max(abs(s1), 1.0):
                if abs(f1) > 1e-6 * scale:
                    return None
                h = 1e-6 * max(abs(s1), 1.0)
                return s1 if abs(f1) <= 1e-2 * min(abs(fun(s1 + h)), abs(fun(s1 + 1j * h))) else None
    return None
