"""Kalker's TANG: the discretised tangential rolling contact problem with local
Coulomb friction (SPEC 4.5; Kalker 1990, ch. 2 and 5; thesis 4.3.4, footnote 3).

Grid, traction and displacement conventions as in influence.py: axis 0 is x,
the rolling direction (the contact travels towards +x, so material enters the
contact at the leading edge, high x, and leaves at the trailing edge), p is the
traction on the rail and u = u(rail) - u(wheel).  Per element I in the contact
area (p3 > 0) the slip of the rail relative to the wheel is

    s_I = w_I + (u_I(t) - u_{I+dx}(t - dt)) / dt,     dx = v dt      (SPEC 4.5)

(the particle at x_I at time t was at x_I + dx a step earlier), with the rigid
slip w1 = (gamma_x - spin y) v, w2 = (gamma_y + spin x) v (SPEC 2, [3.2]).  In
steady state u(t - dt) = u(t) and s_I = w_I - v (u_{I+dx} - u_I)/dx, the
discrete s = w - v du/dx.  Coulomb's law per element:

    stick  s_I = 0,            |p_I| <= mu p3_I
    slip   |p_I| = mu p3_I,    p_I = -mu p3_I s_I / |s_I|   (traction opposes slip)

so a positive creepage gives a negative force (F2 = -c^2 G C22 gamma_y in the
linear range; full slip F = -mu F3 w / |w|).

Solver (Kalker's active-set Newton method): with s = r + M p (in units of
displacement per step, s dt), M = A - A(x + dx) steady or M = A transient,
elements are split into a stick set H (unknowns p1, p2; equations s = 0) and a
slip set S (unknown: traction angle theta, |p| = mu p3; equation s x p = 0).
One Newton step on these equations, then elements of H exceeding the traction
bound move to S and elements of S whose slip points along the traction move to
H; repeat until the sets no longer change and the step is negligible.  The
Newton systems are solved by GMRES preconditioned with the LU of an earlier
Jacobian of the same M (kept across calls: in a time loop or along a creepage
ramp the sets and slip angles change little), and by a fresh dense LU when many
elements changed set or GMRES is slow.  Fine for the few hundred elements of a
wheel/rail contact at dx = 0.5 mm (timings: benchmarks/contact.py).
"""
from __future__ import annotations

import functools
import warnings
from typing import NamedTuple

import numpy as np
import scipy.linalg as sla

from .influence import Convolver, tangential_kernels


class TangentialContact(NamedTuple):
    p1: np.ndarray          # traction on the rail, longitudinal [Pa] (nx, ny)
    p2: np.ndarray          # traction on the rail, lateral [Pa]
    stick: np.ndarray       # stick elements (bool)
    slip: np.ndarray        # slip elements (bool); stick | slip = contact area
    s1: np.ndarray          # slip velocity of the rail relative to the wheel [m/s]
    s2: np.ndarray
    u1: np.ndarray          # tangential displacement difference at time t [m]
    u2: np.ndarray
    F1: float               # forces on the rail [N]
    F2: float
    iterations: int         # Newton steps in total
    converged: bool


class TangentialOperator(NamedTuple):
    ix: np.ndarray          # grid indices of the contact elements (N,)
    iy: np.ndarray
    M: np.ndarray           # (2N, 2N) dense, element-major: row 2I + a, column 2J + b
    steady: bool


@functools.lru_cache(maxsize=8)
def _kernels(shape, dx, dy, E, nu):
    """Cerruti kernels on the grid, at offsets X and X + dx (transport term), and
    FFT convolvers for displacements of whole traction fields."""
    nx, ny = shape
    A = tangential_kernels(nx, ny, dx, dy, E, nu)
    Ash = tangential_kernels(nx, ny, dx, dy, E, nu, shift_x=1)
    return A, Ash, Convolver(*A), Convolver(*Ash)


def _displacements(conv, p1, p2):
    """(u1, u2) = A (p1, p2) with the symmetric 2x2 kernel block (K11, K12, K22)."""
    h1, h2 = conv.transform(p1), conv.transform(p2)
    k11, k12, k22 = conv.hat
    return conv.back(k11 * h1 + k12 * h2), conv.back(k12 * h1 + k22 * h2)


@functools.lru_cache(maxsize=8)
def _operator(key, shape, dx, dy, E, nu, steady):
    contact = np.frombuffer(key, dtype=bool).reshape(shape)
    ix, iy = np.nonzero(contact)
    nx, ny = shape
    A, Ash, _, _ = _kernels(shape, dx, dy, E, nu)
    K = [a - b for a, b in zip(A, Ash)] if steady else list(A)
    k = ix[:, None] - ix[None, :] + nx - 1
    l = iy[:, None] - iy[None, :] + ny - 1
    N = len(ix)
    M = np.empty((N, 2, N, 2))
    M[:, 0, :, 0] = K[0][k, l]
    M[:, 0, :, 1] = K[1][k, l]
    M[:, 1, :, 0] = K[1][k, l]
    M[:, 1, :, 1] = K[2][k, l]
    return TangentialOperator(ix, iy, M.reshape(2 * N, 2 * N), steady)


def tangential_operator(contact, dx, dy, E=210e9, nu=0.3, steady=True) -> TangentialOperator:
    """Influence matrix of s dt on p over the contact elements (cached per contact set):
    steady M_IJ = A(x_I - x_J) - A(x_I + dx - x_J); transient M_IJ = A(x_I - x_J)."""
    c = np.ascontiguousarray(contact, dtype=bool)
    return _operator(c.tobytes(), c.shape, float(dx), float(dy), float(E), float(nu), bool(steady))


def rigid_slip(shape, dx, dy, v, gamma_x=0.0, gamma_y=0.0, spin=0.0, origin=(0.0, 0.0)):
    """Rigid slip w1, w2 [m/s] at the element centres (SPEC 2, [3.2]); x, y measured
    from `origin` relative to the grid centre."""
    nx, ny = shape
    x = (np.arange(nx) - 0.5 * (nx - 1)) * dx - origin[0]
    y = (np.arange(ny) - 0.5 * (ny - 1)) * dy - origin[1]
    w1 = (gamma_x - spin * y[None, :]) * v + 0.0 * x[:, None]
    w2 = (gamma_y + spin * x[:, None]) * v + 0.0 * y[None, :]
    return w1, w2


_REFERENCE_LU: dict = {}      # id(M) -> (M.shape, LU of a recent Jacobian): preconditioner across calls
_GMRES_MAX = 15               # GMRES steps before a fresh LU is cheaper


def _block_apply(B, v):
    """Apply per-element 2x2 blocks B (N, 2, 2) to v (2N,)."""
    v2 = v.reshape(-1, 2)
    return (B[:, :, 0] * v2[:, :1] + B[:, :, 1] * v2[:, 1:]).ravel()


def _gmres(A, P, b, rtol, kmax):
    """Right-preconditioned GMRES (modified Gram-Schmidt): x with |b - A x| <= rtol |b|
    (true residual), or None after kmax steps."""
    beta = np.linalg.norm(b)
    if beta == 0.0:
        return np.zeros_like(b)
    V = np.zeros((kmax + 1, len(b)))
    Z = np.zeros((kmax, len(b)))
    Hm = np.zeros((kmax + 1, kmax))
    V[0] = b / beta
    e1 = np.zeros(kmax + 1)
    e1[0] = beta
    for k in range(kmax):
        Z[k] = P(V[k])
        w = A(Z[k])
        for j in range(k + 1):
            Hm[j, k] = np.dot(V[j], w)
            w -= Hm[j, k] * V[j]
        Hm[k + 1, k] = np.linalg.norm(w)
        y, *_ = np.linalg.lstsq(Hm[:k + 2, :k + 1], e1[:k + 2], rcond=None)
        res = np.linalg.norm(Hm[:k + 2, :k + 1] @ y - e1[:k + 2])
        if res <= rtol * beta or Hm[k + 1, k] <= 1e-300:
            return y @ Z[:k + 1]
        V[k + 1] = w / Hm[k + 1, k]
    return None


def _newton_step(M, Rb, Cb, D, R, active, key, fresh):
    """Solve J dz = -R, J = Rb M Cb + D (Rb, Cb, D per-element 2x2 blocks; the dummy
    unknowns of slip elements, outside `active`, have identity rows and columns).
    GMRES preconditioned with the LU of an earlier Jacobian of the same M (sets and
    slip angles change little between Newton steps, creepages and time steps); a
    fresh LU of the active block when asked (`fresh`) or when GMRES is slow."""
    n = len(R)
    ref = _REFERENCE_LU.get(key)
    if not fresh and ref is not None and ref[0] == M.shape:
        _, lu, act = ref

        def precondition(v):
            x = v.copy()
            x[act] = sla.lu_solve(lu, v[act], check_finite=False)
            return x

        dz = _gmres(lambda v: _block_apply(Rb, M @ _block_apply(Cb, v)) + _block_apply(D, v),
                    precondition, -R, 1e-9, _GMRES_MAX)
        if dz is not None:
            return dz, "gmres"
        how = "lu after gmres"
    else:
        how = "lu"
    e, k = np.divmod(active, 2)                  # element and local index of each active unknown
    Cf, Rf = Cb.reshape(-1, 2, 2), Rb.reshape(-1, 2, 2)
    MC = M[:, 2 * e] * Cf[e, 0, k] + M[:, 2 * e + 1] * Cf[e, 1, k]          # columns M Cb
    J = MC[2 * e] * Rf[e, k, 0][:, None] + MC[2 * e + 1] * Rf[e, k, 1][:, None]   # rows Rb M Cb
    J[np.arange(len(active)), np.arange(len(active))] += D[e, k, k]
    lu = sla.lu_factor(J, check_finite=False)
    if len(_REFERENCE_LU) > 3:
        _REFERENCE_LU.clear()
    _REFERENCE_LU[key] = (M.shape, lu, active)
    dz = -R.copy()                    # dummy unknowns: identity rows (their residual is 0)
    dz[active] = sla.lu_solve(lu, -R[active], check_finite=False)
    return dz, how


def solve_coulomb(M, r, g, p, stick, *, tol=1e-10, max_iter=200, reuse_lu=True):
    """Kalker's active-set Newton solver for  s = r + M p  (r, p: (N, 2); M: (2N, 2N))
    with per element: stick s = 0, |p| <= g, or slip |p| = g, p = -g s/|s|.
    `p`, `stick`: start values (a previous solution, or zeros and all-stick).
    Unknowns per element: stick (p1, p2), equations s = 0; slip (theta, -) with
    p = g (cos theta, sin theta), equations s x p = 0 and a dummy, so the Newton
    system keeps its size 2N when elements change set.  Each step: one Newton step,
    then the set update; stop when no element changes set and the step is below
    tol * max g.  `reuse_lu`: precondition with the last LU of this M from the start
    (a warm start); otherwise factor first.  Returns p, s, stick, Newton steps, converged."""
    N = len(g)
    p = np.array(p, dtype=float).reshape(N, 2)
    stick = np.array(stick, dtype=bool)
    gmax = max(float(g.max()), 1e-300)
    theta = np.arctan2(p[:, 1], p[:, 0])
    key = id(M)
    converged = False
    changed = 0                     # set changes since the last LU
    gmres_failed = False
    I2 = np.eye(2)
    for step in range(1, max_iter + 1):
        slip = ~stick
        c, sn = np.cos(theta), np.sin(theta)
        p[slip] = (g * np.array([c, sn])).T[slip]
        s = r + (M @ p.ravel()).reshape(N, 2)
        R = s.copy()
        R[slip, 0] = s[slip, 0] * sn[slip] - s[slip, 1] * c[slip]       # s x t = 0
        R[slip, 1] = 0.0
        Cb = np.broadcast_to(I2, (N, 2, 2)).copy()
        Rb = Cb.copy()
        D = np.zeros((N, 2, 2))
        Cb[slip] = 0.0
        Cb[slip, 0, 0], Cb[slip, 1, 0] = -g[slip] * sn[slip], g[slip] * c[slip]     # dp/dtheta
        Rb[slip] = 0.0
        Rb[slip, 0, 0], Rb[slip, 0, 1] = sn[slip], -c[slip]
        D[slip, 0, 0] = s[slip, 0] * c[slip] + s[slip, 1] * sn[slip]                # s . t
        D[slip, 1, 1] = 1.0
        active = np.flatnonzero(np.column_stack([np.ones(N, bool), stick]).ravel())
        dz, how = _newton_step(M, Rb, Cb, D, R.ravel(), active, key,
                               fresh=(not reuse_lu) or changed > 3 or (gmres_failed and changed > 0))
        reuse_lu = True
        gmres_failed |= how == "lu after gmres"
        dz = dz.reshape(N, 2)
        changed = changed if how == "gmres" else 0
        dth = np.clip(dz[slip, 0], -0.5, 0.5)
        p[stick] += dz[stick]
        theta[slip] += dth
        change = max(np.abs(dz[stick]).max(initial=0.0), (g[slip] * np.abs(dth)).max(initial=0.0))
        c, sn = np.cos(theta), np.sin(theta)
        p[slip] = (g * np.array([c, sn])).T[slip]
        s = r + (M @ p.ravel()).reshape(N, 2)
        s_scale = max(np.abs(s).max(), np.abs(r).max(), 1e-300)
        to_slip = stick & (np.hypot(*p.T) > g * (1.0 + 1e-9))
        to_stick = slip & ((s * p).sum(axis=1) > 1e-9 * s_scale * g)
        if not to_slip.any() and not to_stick.any() and change <= tol * gmax:
            converged = True
            break
        changed += int(to_slip.sum() + to_stick.sum())
        stick[to_slip] = False
        stick[to_stick] = True
        theta[to_slip] = np.arctan2(p[to_slip, 1], p[to_slip, 0])
    s[stick] = 0.0
    return p, s, stick, step, converged


def _solve(p3, dx, dy, v, mu, w1, w2, r_extra, steady, E, nu, warm, tol):
    p3 = np.asarray(p3, dtype=float)
    shape = p3.shape
    contact = p3 > 0.0
    dt = dx / v
    op = tangential_operator(contact, dx, dy, E, nu, steady)
    ix, iy = op.ix, op.iy
    g = mu * p3[ix, iy]
    r = np.column_stack([w1[ix, iy], w2[ix, iy]]) * dt + r_extra + np.zeros((len(ix), 2))
    if warm is not None:
        p0 = np.column_stack([warm.p1[ix, iy], warm.p2[ix, iy]])
        stick0 = ~warm.slip[ix, iy]
    else:
        p0, stick0 = np.zeros((len(ix), 2)), np.ones(len(ix), bool)
    if len(ix) == 0 or mu <= 0.0:        # no contact or no friction: traction-free, all slip
        p, s, stick, steps, ok = np.zeros((len(ix), 2)), r.reshape(len(ix), 2), np.zeros(len(ix), bool), 0, True
    else:
        p, s, stick, steps, ok = solve_coulomb(op.M, r, g, p0, stick0, tol=tol, reuse_lu=warm is not None)
    if not ok:
        warnings.warn("TANG: stick/slip sets not converged", RuntimeWarning)
    P1, P2, S1, S2 = (np.zeros(shape) for _ in range(4))
    P1[ix, iy], P2[ix, iy] = p[:, 0], p[:, 1]
    S1[ix, iy], S2[ix, iy] = s[:, 0] / dt, s[:, 1] / dt
    st = np.zeros(shape, bool)
    st[ix, iy] = stick
    _, _, conv, _ = _kernels(shape, float(dx), float(dy), float(E), float(nu))
    u1, u2 = _displacements(conv, P1, P2)
    dA = dx * dy
    return TangentialContact(P1, P2, st, contact & ~st, S1, S2, u1, u2,
                             float(P1.sum() * dA), float(P2.sum() * dA), steps, ok)


def tang_steady(p3, dx, dy, v, mu, gamma_x=0.0, gamma_y=0.0, spin=0.0, E=210e9, nu=0.3, *,
                warm: TangentialContact | None = None, tol=1e-10) -> TangentialContact:
    """Steady-state rolling (du/dt = 0) with normal pressures p3 (nx, ny) [Pa] on the grid
    dx (rolling direction) x dy, rolling speed v [m/s], Coulomb coefficient mu and
    creepages gamma_x, gamma_y [-], spin [1/m].  `warm`: a previous solution as start."""
    w1, w2 = rigid_slip(np.shape(p3), dx, dy, v, gamma_x, gamma_y, spin)
    return _solve(p3, dx, dy, v, mu, w1, w2, 0.0, True, E, nu, warm, tol)


def tang_transient(p3, dx, dy, v, mu, gamma_x=0.0, gamma_y=0.0, spin=0.0, E=210e9, nu=0.3, *,
                   state: TangentialContact | None = None, tol=1e-10) -> TangentialContact:
    """One time step dt = dx / v of transient rolling.  `state` is the previous step's
    solution (None: traction-free start); its tractions give the previous displacement
    one element ahead, u(x + dx, t - dt), and start the iteration.  Call once per step."""
    p3 = np.asarray(p3, dtype=float)
    w1, w2 = rigid_slip(p3.shape, dx, dy, v, gamma_x, gamma_y, spin)
    contact = p3 > 0.0
    ix, iy = np.nonzero(contact)
    if state is None:
        r_extra = 0.0
    else:
        _, _, _, conv_ahead = _kernels(p3.shape, float(dx), float(dy), float(E), float(nu))
        a1, a2 = _displacements(conv_ahead, state.p1, state.p2)     # u(x + dx, t - dt)
        r_extra = -np.column_stack([a1[ix, iy], a2[ix, iy]])
    return _solve(p3, dx, dy, v, mu, w1, w2, r_extra, False, E, nu, state, tol)
