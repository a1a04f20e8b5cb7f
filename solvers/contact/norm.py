"""Kalker's NORM: the discretised normal contact problem (SPEC 4.1, thesis [4.16-4.24]).

On the potential contact area (nx * ny rectangles dx * dy) find the pressures p_I
with
    d_I = h_I - xi3 + u_I >= 0,   p_I >= 0,   p_I d_I = 0           [4.19, 4.21-4.23]
    u_I = sum_J A_I3,J3 p_J                                          [4.18]
where h is the undeformed gap z^R - z^W (>= 0, zero at first contact for a
touching pair; any shape, non-Hertzian allowed) and xi3 the approach (rigid
penetration, positive into contact).  F3 = sum p dx dy               [4.24].

Algorithm: Kalker's active-set iteration (Kalker 1990, 'NORM'; thesis 4.3.1).
For the current contact set C the equations d_I = 0 (I in C) are solved with p
= 0 outside; elements of C with p < 0 leave the set, elements outside with
d < 0 join it; repeat until neither happens.  Each linear solve on C is a
conjugate-gradient solve with FFT matrix-vector products and a circulant
(Strang) preconditioner, warm-started from the previous set, so that one solve
on ~1000 elements takes a few ms (a dense Cholesky of the contact block would
cost ~10 ms per set with the reference BLAS of this machine).  The first set is
{h < h_min + delta/2}, delta = xi3 - h_min, exact for a Hertzian gap (the
contact ellipse is where the undeformed gap equals half the approach).
"""
from __future__ import annotations

import functools
import warnings
from typing import NamedTuple

import numba
import numpy as np
from scipy.fft import next_fast_len

from solvers.contact.influence import Convolver, normal_kernel, strang_inverse_symbol


class NormalContact(NamedTuple):
    p: np.ndarray           # pressures p3 [Pa], (nx, ny), >= 0
    contact: np.ndarray     # contact set C (bool)
    F3: float               # normal force [N] [4.24]
    d: np.ndarray           # deformed distance d [m] as computed (0 in C and >= 0 outside, to rtol)
    iterations: int         # active-set iterations
    cg_iterations: int      # conjugate-gradient steps in total
    converged: bool         # contact set converged (no p < 0 in C, no d < 0 outside)
    touches_edge: bool      # contact reaches the border of the potential area (grid too small)


class NormalOperator(NamedTuple):
    conv: Convolver         # u3 = A33 p3 by FFT
    prec: np.ndarray        # inverse Strang symbol (preconditioner), rfft2 layout
    torus: tuple            # FFT size of the preconditioner
    dx: float
    dy: float


@functools.lru_cache(maxsize=16)
def normal_operator(shape, dx, dy, E=210e9, nu=0.3) -> NormalOperator:
    """Boussinesq influence operator of the grid (cached per grid and material)."""
    K = normal_kernel(shape[0], shape[1], dx, dy, E, nu)
    torus = (next_fast_len(shape[0], real=True), next_fast_len(shape[1], real=True))
    return NormalOperator(Convolver(K), strang_inverse_symbol(K), torus, float(dx), float(dy))


def _precondition(op, r):
    return np.fft.irfft2(np.fft.rfft2(r, s=op.torus) * op.prec, s=op.torus)[: r.shape[0], : r.shape[1]]


def _pcg(op, C, b, p, rtol, maxit):
    """Preconditioned CG for (A p)_C = b_C with p = 0 outside C (A SPD).  Returns p, steps."""
    conv = op.conv
    p = np.where(C, p, 0.0)
    r = np.where(C, b - conv(p), 0.0)
    stop = rtol * np.sqrt(np.dot(b[C], b[C]))
    z = np.where(C, _precondition(op, r), 0.0)
    s = z.copy()
    rz = np.vdot(r, z)
    k = 0
    while k < maxit and np.sqrt(np.vdot(r, r)) > stop:
        q = np.where(C, conv(s), 0.0)
        alpha = rz / np.vdot(s, q)
        p += alpha * s
        r -= alpha * q
        z = np.where(C, _precondition(op, r), 0.0)
        rz, rz_old = np.vdot(r, z), rz
        s = z + (rz / rz_old) * s
        k += 1
    return p, k


def norm(gap, xi3, dx, dy, E=210e9, nu=0.3, *, warm: NormalContact | None = None,
         rtol=1e-9, max_iter=60, op: NormalOperator | None = None) -> NormalContact:
    """Solve the normal contact problem [4.16-4.24] for the gap h (nx, ny) [m] and the
    approach xi3 [m].  `warm`: a previous solution (its contact set and pressures
    start the iteration; useful in a time loop or along a table)."""
    h = np.asarray(gap, dtype=float)
    if not np.all(np.isfinite(h)) or not np.isfinite(xi3):
        raise ValueError("gap and xi3 must be finite")
    if op is None:
        op = normal_operator(h.shape, float(dx), float(dy), float(E), float(nu))
    h_min = h.min()
    delta = xi3 - h_min
    if delta <= 0.0:   # loss of contact: exactly no load
        zero = np.zeros_like(h)
        return NormalContact(zero, np.zeros(h.shape, bool), 0.0, h - xi3, 0, 0, True, False)
    b = xi3 - h                                   # required u where d = 0 [4.20]
    if warm is not None and warm.contact.any():
        C, p = warm.contact.copy(), warm.p.copy()
    else:
        C, p = h - h_min < 0.5 * delta, np.zeros_like(h)
    d_tol = 1e-9 * delta
    steps, converged = 0, False
    for it in range(1, max_iter + 1):
        p, k = _pcg(op, C, b, p, rtol, 10 * C.sum() + 50)
        steps += k
        d = h - xi3 + op.conv(p)
        leave = C & (p < 0.0)                     # adhesion not allowed [4.22]
        join = ~C & (d < -d_tol)                  # penetration not allowed [4.21]
        if not leave.any() and not join.any():
            converged = True
            break
        C = (C & ~leave) | join
        p[leave] = 0.0
    if not converged:
        warnings.warn(f"NORM: contact set not converged after {max_iter} iterations", RuntimeWarning)
    p = np.where(C, p, 0.0)
    edge = bool(C[0].any() or C[-1].any() or C[:, 0].any() or C[:, -1].any())
    return NormalContact(p, C, float(p.sum() * dx * dy), d, it, steps, converged, edge)


def approach_for_load(F3, gap, dx, dy, E=210e9, nu=0.3, *, rtol=1e-10, max_iter=50) -> tuple[float, NormalContact]:
    """Approach xi3 giving the normal force F3 [N]: monotone root find of
    q(xi3) = F3(xi3)^(2/3), which is linear in xi3 for a Hertzian gap (secant steps
    kept inside a bracket, bisection as fallback; warm-started NORM solves)."""
    h = np.asarray(gap, dtype=float)
    h_min = float(h.min())
    if F3 <= 0.0:
        return h_min, norm(h, h_min, dx, dy, E, nu)
    target = F3 ** (2.0 / 3.0)
    sol = None

    def q(xi3):
        nonlocal sol
        sol = norm(h, xi3, dx, dy, E, nu, warm=sol if (sol is not None and sol.F3 > 0) else None)
        return sol.F3 ** (2.0 / 3.0) - target

    lo, q_lo = h_min, -target                  # q(h_min) = -target (no contact)
    x = h_min + 1e-5
    qx = q(x)
    while qx < 0.0:                            # extrapolate linearly in q until bracketed
        lo, q_lo = x, qx
        x = h_min + max(2.0 * (x - h_min), (x - h_min) * target / max(qx + target, 1e-300) * 1.05)
        if x - h_min > 1.0:
            raise ValueError("no approach found for this load")
        qx = q(x)
    hi, q_hi = x, qx
    for _ in range(max_iter):
        if q_hi - q_lo <= 0.0:
            break
        x = hi - q_hi * (hi - lo) / (q_hi - q_lo)              # secant (regula falsi point)
        if not lo < x < hi:
            x = 0.5 * (lo + hi)
        qx = q(x)
        if abs(qx) <= rtol * target or hi - lo <= 1e-15:
            break
        if qx < 0.0:
            lo, q_lo = x, qx
        else:
            hi, q_hi = x, qx
        # Illinois-style guard: keep the bracket shrinking from both sides
        if qx < 0.0 and abs(q_hi) > 4 * abs(qx):
            q_hi *= 0.5
        elif qx > 0.0 and abs(q_lo) > 4 * abs(qx):
            q_lo *= 0.5
    return float(x), sol


class NormTable(NamedTuple):
    """F3(xi3) and the pressure fields tabulated with NORM (for a fixed gap the normal
    solution depends on xi3 alone, SPEC 4.1).  q = F3^(2/3) is stored for
    interpolation: it is linear in xi3 for a Hertzian contact."""
    xi3: np.ndarray         # (n,) increasing [m]
    F3: np.ndarray          # (n,) [N]
    q: np.ndarray           # (n,) F3^(2/3)
    p: np.ndarray           # (n, nx, ny) pressures [Pa]
    contact: np.ndarray     # (n, nx, ny) contact sets


def norm_table(gap, xi3_values, dx, dy, E=210e9, nu=0.3) -> NormTable:
    """Tabulate NORM at increasing approaches xi3_values (each solve warm-started)."""
    h = np.asarray(gap, dtype=float)
    xs = np.sort(np.asarray(xi3_values, dtype=float))
    P = np.zeros((len(xs),) + h.shape)
    Cs = np.zeros((len(xs),) + h.shape, bool)
    F = np.zeros(len(xs))
    warm = None
    for k, x in enumerate(xs):
        warm = norm(h, x, dx, dy, E, nu, warm=warm if (warm is not None and warm.F3 > 0) else None)
        P[k], Cs[k], F[k] = warm.p, warm.contact, warm.F3
    return NormTable(xs, F, F ** (2.0 / 3.0), P, Cs)


@numba.njit(cache=True)
def table_force(xi3, xi3_nodes, q_nodes):
    """F3(xi3) from a NormTable (arrays xi3, q): linear in q = F3^(2/3), zero below the
    first node with q = 0, extrapolated linearly in q beyond the last node."""
    n = xi3_nodes.shape[0]
    if xi3 <= xi3_nodes[0]:
        if q_nodes[0] > 0.0:    # below the table: continue the first interval (q >= 0)
            s = (q_nodes[1] - q_nodes[0]) / (xi3_nodes[1] - xi3_nodes[0])
            q = q_nodes[0] + s * (xi3 - xi3_nodes[0])
            return q ** 1.5 if q > 0.0 else 0.0
        return 0.0
    k = np.searchsorted(xi3_nodes, xi3) - 1
    if k > n - 2:
        k = n - 2
    t = (xi3 - xi3_nodes[k]) / (xi3_nodes[k + 1] - xi3_nodes[k])
    q = (1.0 - t) * q_nodes[k] + t * q_nodes[k + 1]
    return q ** 1.5 if q > 0.0 else 0.0


def table_pressure(table: NormTable, xi3):
    """Pressure field at xi3 interpolated linearly between the tabulated fields and
    scaled to the interpolated force table_force(xi3)."""
    return _table_pressure(float(xi3), table.xi3, table.p, table.F3, table.q)


@numba.njit(cache=True)
def _table_pressure(xi3, xs, P, F3, q):
    k = min(max(np.searchsorted(xs, xi3) - 1, 0), len(xs) - 2)
    t = (xi3 - xs[k]) / (xs[k + 1] - xs[k])
    F_lin = (1.0 - t) * F3[k] + t * F3[k + 1]     # force of p
    p = (1.0 - t) * P[k] + t * P[k + 1]
    return p * (table_force(xi3, xs, q) / F_lin) if F_lin > 0.0 else p


def table_midpoint_error(table: NormTable, gap, dx, dy, E=210e9, nu=0.3) -> dict:
    """Interpolation error of the table at the midpoints between nodes, against NORM.
    Arrays per interval (NaN where the midpoint has no contact): 'xi3', relative force
    error 'force', pressure error relative to the peak pressure as maximum 'pressure'
    and root mean square over the contact area 'pressure_rms'.  Each midpoint's NORM solve starts
    from the node above it (its contact set and pressures; the solution is the same to NORM's
    tolerances, in about half the iterations)."""
    h = np.asarray(gap, dtype=float)
    xm = 0.5 * (table.xi3[1:] + table.xi3[:-1])
    out = {k: np.full(len(xm), np.nan) for k in ("force", "pressure", "pressure_rms")}
    for k, x in enumerate(xm):
        above = NormalContact(table.p[k + 1], table.contact[k + 1], float(table.F3[k + 1]), h, 0, 0, True, False)
        sol = norm(h, x, dx, dy, E, nu, warm=above if table.F3[k + 1] > 0 else None)
        if sol.F3 <= 0.0:
            continue
        dp = (table_pressure(table, x) - sol.p) / sol.p.max()
        out["force"][k] = abs(table_force(x, table.xi3, table.q) - sol.F3) / sol.F3
        out["pressure"][k] = np.abs(dp).max()
        out["pressure_rms"][k] = np.sqrt(np.mean(dp[sol.contact] ** 2))
    out["xi3"] = xm
    return out
