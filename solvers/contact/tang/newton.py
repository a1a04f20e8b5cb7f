"""Kalker's active-set Newton method for the Coulomb problem of TANG (notes in
``solvers.contact.tang``): the steady solve with its matrix-free restarted GMRES here, the
transient one compiled whole with its CG in ``tang.pcg``."""
from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from solvers.contact.tang.kernels import after_step, forcing_term, gather_slip, jacobian_rows, lift, newton_system, precondition_in, precondition_out, scatter, start_on_bounds, step_and_scatter
from solvers.contact.tang.operator import TangentialOperator
from solvers.contact.tang.pcg import FEW
from solvers.contact.tang.state import QUADRATIC, TOL


# ----------------------------------------------------------------------------------------------
# Krylov solvers (matrix-free, preconditioned)
# ----------------------------------------------------------------------------------------------

@numba.njit(cache=True)
def _givens(h, hnext, cs, sn, e, k):
    """GMRES: apply the previous Givens rotations to column h (k + 1), make the new one that
    zeroes hnext, and rotate the right-hand side e."""
    for j in range(k):
        a, b = h[j], h[j + 1]
        h[j] = cs[j] * a + sn[j] * b
        h[j + 1] = -sn[j] * a + cs[j] * b
    den = math.hypot(h[k], hnext)
    if den > 0.0:
        cs[k], sn[k] = h[k] / den, hnext / den
    else:
        cs[k], sn[k] = 1.0, 0.0
    h[k] = den
    e[k + 1] = -sn[k] * e[k]
    e[k] = cs[k] * e[k]


def _gmres(A, P, b, rtol, kmax, restarts=3):
    """Right-preconditioned restarted GMRES (classical Gram-Schmidt, repeated when it cancels;
    Givens rotations): x with |b - A x| <= rtol |b|.  Returns x, steps (operator applications)."""
    shape = b.shape
    n = b.size
    bflat = b.ravel()
    bn = float(np.linalg.norm(bflat))
    x = np.zeros(n)
    if bn == 0.0:
        return x.reshape(shape), 0
    steps = 0
    r = bflat.copy()
    V = np.empty((kmax + 1, n))
    Z = np.empty((kmax, n))
    H = np.zeros((kmax + 1, kmax))
    for _ in range(restarts + 1):
        beta = float(np.linalg.norm(r))
        if beta <= rtol * bn:
            break
        cs, sn = np.zeros(kmax), np.zeros(kmax)
        e = np.zeros(kmax + 1)
        e[0] = beta
        V[0] = r / beta
        k_used = 0
        for k in range(kmax):
            Z[k] = P(V[k].reshape(shape)).ravel()
            w = A(Z[k].reshape(shape)).ravel()
            steps += 1
            Vk = V[: k + 1]
            wn = float(np.linalg.norm(w))
            h = Vk @ w
            w -= h @ Vk
            hnext = float(np.linalg.norm(w))
            if hnext < 0.5 * wn:         # cancellation: re-orthogonalise (CGS2, Kahan-Parlett)
                h2 = Vk @ w
                w -= h2 @ Vk
                h += h2
                hnext = float(np.linalg.norm(w))
            _givens(h, hnext, cs, sn, e, k)
            H[: k + 1, k] = h
            k_used = k + 1
            if abs(e[k + 1]) <= rtol * bn or hnext == 0.0:
                break
            V[k + 1] = w / hnext
        y = np.zeros(k_used)
        for i in range(k_used - 1, -1, -1):
            y[i] = (e[i] - np.dot(H[i, i + 1:k_used], y[i + 1:k_used])) / H[i, i]
        x += y @ Z[:k_used]
        if abs(e[k_used]) > rtol * bn:   # not converged in this cycle: true residual, restart
            r = bflat - A(x.reshape(shape)).ravel()
            steps += 1
        else:
            break
    return x.reshape(shape), steps


# ----------------------------------------------------------------------------------------------
# the Coulomb solver
# ----------------------------------------------------------------------------------------------

class CoulombResult(NamedTuple):
    p: np.ndarray           # (N, 2) tractions
    s: np.ndarray           # (N, 2) slip [displacement per step], 0 on stick
    stick: np.ndarray       # (N,) bool
    u: np.ndarray           # (2, nx + 1, ny) displacements of the final tractions (grid + one row ahead)
    newton: int
    krylov: int
    converged: bool


def solve_coulomb(op: TangentialOperator, ix, iy, r, g, p, stick, *, tol=TOL, max_iter=200,
                  warm=False) -> CoulombResult:
    """Kalker's active-set Newton solver for steady rolling, s = r + M p with M = A - A(x + dx),
    on the contact elements (ix, iy) of the operator's grid (r, p: (N, 2) [m per step, Pa]; g =
    mu p3 (N,)), per element: stick s = 0, |p| <= g, or slip |p| = g, p = -g s/|s|.  `p`,
    `stick`: start values (a previous solution, or zeros and all-stick).  Stops when no element
    changes set and the Newton step is below tol times the traction level (max(|p|)).  `warm`:
    the start is a previous solution (its sets are trusted for the first step).  Returns a
    CoulombResult.  (Transient rolling, M = A: ``tang.pcg.coulomb_transient``.)"""
    ix = np.ascontiguousarray(ix, dtype=np.int64)
    iy = np.ascontiguousarray(iy, dtype=np.int64)
    N = ix.shape[0]
    r = np.ascontiguousarray(r, dtype=float).reshape(N, 2)
    g = np.ascontiguousarray(g, dtype=float)
    p = np.array(p, dtype=float).reshape(N, 2)
    stick = np.array(stick, dtype=bool)
    bufs = op.buffers
    grid = bufs.conv_in                       # the FFT input arrays, filled in place
    convolve, precondition = bufs.convolve, bufs.precondition
    scale = op.scale
    mdiag_s = (op.a0 - op.a1) / scale
    theta = np.arctan2(p[:, 1], p[:, 0])
    t, s, R, b = np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2))
    D = np.zeros(N)
    sc = np.ones(N)
    q_lim = math.sqrt(tol / QUADRATIC)           # steps this small are final (quadratic convergence)
    p_level, _ = start_on_bounds(stick, theta, g, s, p, t, D, scale, p.copy())

    def slip_of(pp):
        scatter(ix, iy, pp, grid)
        u = convolve(grid)
        gather_slip(ix, iy, u, True, r, s)
        return u

    def J(x):
        lift(ix, iy, stick, t, x, grid)
        u = convolve(grid)
        y = np.empty_like(x)
        jacobian_rows(ix, iy, stick, t, D, u, True, scale, x, y)
        return y

    grid4 = bufs.prec_in
    inv = [op.inv]                                # the preconditioner's symbol on stick (None: no stick)

    def Pinv(x):                                  # GMRES's preconditioner (slip: diagonal)
        precondition_in(ix, iy, stick, t, sc, x, True, False, grid4)
        z = precondition(grid4, inv[0], None)
        y = np.empty_like(x)
        precondition_out(ix, iy, stick, t, sc, D, mdiag_s, z, False, x, y)
        return y

    u = slip_of(p)
    newton = krylov = 0
    converged = False
    sets_changed = not warm
    n_changed = N if not warm else 0
    ratio = 0.0
    eta_final = min(1e-3, 0.1 * tol / q_lim)
    for newton in range(1, max_iter + 1):
        r_max, n_stick, _ = newton_system(stick, theta, g, s, p, t, D, scale, R, b, mdiag_s, sc)
        inv[0] = op.inv if n_stick else None
        eta = forcing_term(n_changed > FEW or newton == 1, ratio, r_max, tol, p_level, eta_final)
        dz, k = _gmres(J, Pinv, b, eta, 40)
        err = eta * float(np.abs(dz).max(initial=0.0))
        krylov += k
        change = step_and_scatter(ix, iy, stick, theta, g, dz, p, 0.5, grid)
        ratio = change / max(r_max, 1e-300)
        u = convolve(grid)
        to_slip, n_changed, p_level, converged = after_step(ix, iy, u, True, r, s, stick, theta, g, p, change, err,
                                                            tol, q_lim, sets_changed)
        sets_changed = n_changed > 0
        if converged:
            break
        if to_slip:                   # projected tractions: the slip follows
            u = slip_of(p)
    s_out = s.copy()
    s_out[stick] = 0.0
    return CoulombResult(p, s_out, stick, u.copy(), newton, krylov, converged)
