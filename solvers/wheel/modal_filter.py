"""The wheel's modal Green's function (SPEC 3.3, [4.13]) and its exact recursive form, the modal
filters the time loop advances per step (notes in ``solvers.greens.kernels``)."""
from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from solvers.greens.convolution import at_rest, rest_in_place


def modal_impulse(t, f_r: float, zeta: float) -> np.ndarray:
    """h(t) = exp(-sigma t) sinh(mu t) / mu of one mode per unit modal mass
    (displacement impulse response of x'' + 2 zeta w x' + w^2 x = delta(t)),
    for any zeta >= 0: exp(-zeta w t) sin(w_d t)/w_d (zeta < 1), t exp(-w t)
    (zeta = 1), the over-damped pair (zeta > 1)."""
    t = np.asarray(t, float)
    w = 2 * np.pi * f_r
    sig = zeta * w
    if zeta < 1.0:
        wd = w * math.sqrt(1.0 - zeta * zeta)
        return np.exp(-sig * t) * np.sin(wd * t) / wd
    mu = w * math.sqrt(zeta * zeta - 1.0)
    x = mu * t
    small = x < 1e-3
    out = np.empty_like(t)
    xs = x[small]
    out[small] = t[small] * np.exp(-sig * t[small]) * (1.0 + xs * xs / 6.0 + xs ** 4 / 120.0)
    tb = t[~small]
    out[~small] = (np.exp((mu - sig) * tb) - np.exp(-(mu + sig) * tb)) / (2.0 * mu)
    return out


def modal_kernel(n_lags: int, dt: float, f_r, modal_mass, zeta, phi) -> np.ndarray:
    """The sampled modal impulse response g[k] = dt sum_r phi_r phi_r^T h_r(k dt)/m_r,
    k = 0..n_lags-1, (n_lags, 2, 2) in m/N; phi (M, 2) = (Phi_2, Phi_3) at the contact
    point.  This is the kernel ``ModalFilter`` reproduces exactly (g[0] = 0)."""
    return modal_kernel_at(np.arange(n_lags), dt, f_r, modal_mass, zeta, phi)


def modal_kernel_at(lags, dt: float, f_r, modal_mass, zeta, phi) -> np.ndarray:
    """``modal_kernel`` at the given lags k (any integers >= 0), (len(lags), 2, 2) in m/N."""
    f_r, modal_mass, zeta = (np.atleast_1d(np.asarray(a, float)) for a in (f_r, modal_mass, zeta))
    phi = np.asarray(phi, float).reshape(len(f_r), 2)
    t = np.asarray(lags) * dt
    g = np.zeros((len(t), 2, 2))
    for r in range(len(f_r)):
        h = dt * modal_impulse(t, f_r[r], zeta[r]) / modal_mass[r]
        g += h[:, None, None] * np.outer(phi[r], phi[r])[None]
    return g


def modal_kernel_dtft(f_hz, dt: float, f_r, modal_mass, zeta, phi) -> np.ndarray:
    """The spectrum sum_{k>=0} g[k] exp(-2 pi i f k dt) of the whole (untruncated) ``modal_kernel``,
    (nf, 2, 2) complex m/N, in closed form: per mode the geometric sums of
    h(k dt) = exp(-sigma k dt) sinh(mu k dt)/mu give, with x = exp(-sigma dt - 2 pi i f dt),
    x sinh(mu dt)/mu / (1 - 2 x cosh(mu dt) + x^2) (sinh(mu dt)/mu and cosh(mu dt) real for any
    zeta >= 0: mu^2 = w^2 (zeta^2 - 1)).  It is the aliased sum of the receptance over the images
    f + m/dt (module notes of ``solvers.greens.kernels``)."""
    f_r, modal_mass, zeta = (np.atleast_1d(np.asarray(a, float)) for a in (f_r, modal_mass, zeta))
    phi = np.asarray(phi, float).reshape(len(f_r), 2)
    w = 2 * np.pi * f_r
    mu = np.sqrt((w * w * (zeta * zeta - 1.0)).astype(complex))
    x_mu = mu * dt
    safe = np.where(np.abs(x_mu) < 1e-8, 1.0, x_mu)
    sinhc = np.where(np.abs(x_mu) < 1e-8, 1.0, np.sinh(safe) / safe).real * dt   # sinh(mu dt)/mu
    cosh = np.cosh(x_mu).real
    x = np.exp(-(zeta * w)[None, :] * dt - 2j * np.pi * np.atleast_1d(np.asarray(f_hz, float))[:, None] * dt)
    H = dt * x * sinhc / (modal_mass * (1.0 - 2.0 * x * cosh + x * x))              # (nf, M)
    P = (phi[:, :, None] * phi[:, None, :]).reshape(len(f_r), 4)
    return (H @ P).reshape(-1, 2, 2)


class FilterState(NamedTuple):
    """The modal filters' state, the only part ``filter_step`` changes (in place): q (M,) complex,
    a (M,) complex (kind-1 modes), u (2, M0) = Re q, Im q of the kind-0 modes."""
    q: np.ndarray
    a: np.ndarray
    u: np.ndarray


class ModalFilter(NamedTuple):
    """Exact recursive form of the wheel's modal kernel (see the module notes).
    Coefficients (per mode r, read only): kind 0 (zeta < 1, complex one-pole) or 1 (zeta >= 1,
    real poles); z = pole / first pole, p2 = second pole; w_in (M, 2): modal force
    P_r = w_in[r] . (F2, F3); w_out (M, 2): xi_i += w_out[r, i] * y_r.
    The time loop runs the kind-0 modes from real, mode-contiguous copies (a loop without
    branches or complex types, which the compiler vectorises): u_coef (6, M0) = Re z, Im z,
    w_in[:, 0], w_in[:, 1], w_out[:, 0], w_out[:, 1]; ``over`` (M1,) the indices of the kind-1
    modes.  ``state`` (FilterState): the part advanced IN PLACE by ``filter_step`` /
    ``filter_history`` / ``step``; ``fresh()`` gives a filter at rest sharing the coefficients.
    Pass the whole tuple to the njit functions from inside a numba time loop."""
    kind: np.ndarray
    z: np.ndarray
    p2: np.ndarray
    w_in: np.ndarray
    w_out: np.ndarray
    u_coef: np.ndarray
    over: np.ndarray
    state: FilterState

    def step(self, F2: float, F3: float) -> tuple[float, float]:
        """Record the force at the current step (advancing ``state``); return (xi2, xi3) at the
        next step."""
        return filter_step(self, F2, F3)

    def reset(self) -> None:
        """Back to rest, in place."""
        rest_in_place(self.state)

    def fresh(self) -> "ModalFilter":
        """The same filter with a state of its own, at rest."""
        return self._replace(state=at_rest(self.state))

    def copy(self) -> "ModalFilter":
        """The same filter with a copy of the current state."""
        return self._replace(state=FilterState(*(x.copy() for x in self.state)))

    def response(self, F: np.ndarray) -> np.ndarray:
        """Whole history from rest (this filter's state is not touched): xi (nt, 2)."""
        return filter_history(self.fresh(), np.ascontiguousarray(F, dtype=float))

    def copy_reset(self) -> "ModalFilter":
        return self.fresh()


def modal_filter(dt: float, f_r, modal_mass, zeta, phi) -> ModalFilter:
    """Build the recursive modal filters of the kernel ``modal_kernel(.., dt, f_r,
    modal_mass, zeta, phi)``: f_r (M,) Hz, modal_mass (M,) kg, zeta (M,) (any
    value >= 0; zeta >= 1 gives the critically / over-damped forms), phi (M, 2) =
    (Phi_2, Phi_3) at the contact point.  State at rest."""
    f_r, modal_mass, zeta = (np.atleast_1d(np.asarray(a, float)) for a in (f_r, modal_mass, zeta))
    phi = np.asarray(phi, float).reshape(len(f_r), 2)
    M = len(f_r)
    if np.any(zeta < 0) or np.any(f_r <= 0) or np.any(modal_mass <= 0):
        raise ValueError("modal_filter needs f_r > 0, modal_mass > 0, zeta >= 0")
    kind = np.zeros(M, np.int64)
    z = np.zeros(M, complex)
    p2 = np.zeros(M, complex)
    gain = np.zeros(M)
    for r in range(M):
        w = 2 * np.pi * f_r[r]
        sig = zeta[r] * w
        if zeta[r] < 1.0:
            wd = w * math.sqrt(1.0 - zeta[r] ** 2)
            z[r] = math.exp(-sig * dt) * complex(math.cos(wd * dt), math.sin(wd * dt))
            gain[r] = dt / wd
        else:
            kind[r] = 1
            mu = w * math.sqrt(zeta[r] ** 2 - 1.0)
            z[r] = math.exp((mu - sig) * dt)
            p2[r] = math.exp(-(mu + sig) * dt)
            x = mu * dt
            shc = 1.0 + x * x / 6.0 + x ** 4 / 120.0 if x < 1e-3 else math.sinh(x) / x
            gain[r] = dt * dt * math.exp(-sig * dt) * shc
    w_in = np.ascontiguousarray(phi)
    w_out = np.ascontiguousarray(phi * (gain / modal_mass)[:, None])
    under = kind == 0
    u_coef = np.ascontiguousarray(np.vstack([z.real, z.imag, w_in.T, w_out.T])[:, under])
    return ModalFilter(kind, z, p2, w_in, w_out, u_coef, np.flatnonzero(~under).astype(np.int64),
                       FilterState(np.zeros(M, complex), np.zeros(M, complex), np.zeros((2, int(under.sum())))))


@numba.njit(cache=True)
def filter_step(filt, F2, F3):
    """njit: push the force (F2, F3) of step n into the modal filters, return the
    displacement (xi2, xi3) at step n + 1 (forces up to step n only, g[0] excluded)."""
    kind, z, p2, w_in, w_out, uc, over, state = filt
    q, a, us = state
    x2 = 0.0
    x3 = 0.0
    for j in range(uc.shape[1]):                    # zeta < 1: q <- z (q + P), y = Im q
        ur = us[0, j] + uc[2, j] * F2 + uc[3, j] * F3
        ui = us[1, j]
        nr = uc[0, j] * ur - uc[1, j] * ui
        ni = uc[0, j] * ui + uc[1, j] * ur
        us[0, j] = nr
        us[1, j] = ni
        x2 += uc[4, j] * ni
        x3 += uc[5, j] * ni
    for i in range(over.shape[0]):                  # zeta >= 1: divided-difference states
        r = over[i]
        P = w_in[r, 0] * F2 + w_in[r, 1] * F3
        v = P + z[r] * q[r] + a[r]
        a[r] = p2[r] * (a[r] + P)
        q[r] = v
        y = v.real
        x2 += w_out[r, 0] * y
        x3 += w_out[r, 1] * y
    return x2, x3


@numba.njit(cache=True)
def filter_history(filt, F):
    """njit: xi[n] = sum_{k>=1} g[k] F[n-k] for a whole force history F (nt, 2),
    starting from the filter's current state (at rest: xi[0] = 0)."""
    nt = F.shape[0]
    xi = np.zeros((nt, 2))
    for n in range(nt - 1):
        x2, x3 = filter_step(filt, F[n, 0], F[n, 1])
        xi[n + 1, 0] = x2
        xi[n + 1, 1] = x3
    return xi
