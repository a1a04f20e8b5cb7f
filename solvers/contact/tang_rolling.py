"""The steady and transient TANG problem of one step on the contact's window (notes in
``solvers.contact.tang``): rigid slip, transport term, warm start and predictor, the Coulomb
solve, and the solution on the grid."""
from __future__ import annotations

import warnings

import numpy as np

from .tang_newton import solve_coulomb
from .tang_operator import tangential_operator
from .tang_state import Rolling, TangentialContact, TangOptions, next_history


PAD = 1                     # elements around the contact's bounding box in the working window


def _window(contact, pad=PAD):
    """Bounding box of the contact elements grown by `pad`, clipped to the grid: (i0, i1, j0, j1)
    inclusive, or None without contact."""
    rows = np.flatnonzero(contact.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(contact.any(axis=0))
    nx, ny = contact.shape
    return (max(int(rows[0]) - pad, 0), min(int(rows[-1]) + pad, nx - 1),
            max(int(cols[0]) - pad, 0), min(int(cols[-1]) + pad, ny - 1))


def _inside(w, v):
    """Window w inside window v."""
    return v is not None and w[0] >= v[0] and w[1] <= v[1] and w[2] >= v[2] and w[3] <= v[3]


def solve_rolling(p3, roll: Rolling, steady: bool, warm: TangentialContact | None,
                  opts: TangOptions) -> TangentialContact:
    """Common driver of tang_steady / tang_transient: the problem of pressures p3 (nx, ny) [Pa]
    rolling as ``roll`` (steady or one transient step from ``warm``) on the contact's window."""
    dx, dy, v, mu, gamma_x, gamma_y, spin = roll
    E, nu, tol, w_offset, full_output = opts
    p3 = np.asarray(p3, dtype=float)
    shape = p3.shape
    nx, ny = shape
    contact = p3 > 0.0
    dt = dx / v
    ix, iy = np.nonzero(contact)
    N = ix.size
    win = _window(contact)
    if win is not None and warm is not None and warm.p1.shape == shape and warm.history is not None:
        # keep the previous step's window while the contact fits in it (a stable window keeps the
        # predictor's history and the operator): time loops with a breathing contact area
        old = warm.history.window
        tight = _window(contact, 0)
        if _inside(tight, old) and (old[1] - old[0] + 1) * (old[3] - old[2] + 1) <= \
                2 * (win[1] - win[0] + 1) * (win[3] - win[2] + 1):
            win = old
    P1, P2, S1, S2 = (np.zeros(shape) for _ in range(4))
    st = np.zeros(shape, bool)
    # rigid slip at the contact elements, times dt (rigid_slip's formula at x_I + w_offset dx)
    xc = (ix - 0.5 * (nx - 1) + w_offset) * dx
    yc = (iy - 0.5 * (ny - 1)) * dy
    r = np.empty((N, 2))
    r[:, 0] = (gamma_x - spin * yc) * v * dt
    r[:, 1] = (gamma_y + spin * xc) * v * dt
    transient_prev = (not steady) and warm is not None and warm.p1.shape == shape
    if transient_prev:                         # transport term: -u(x + dx, t - dt)
        ahead = warm.u_ahead
        if ahead is None or not _inside(win, warm.window):
            full = tangential_operator(shape, dx, dy, E, nu)
            ahead = full.displacements(np.stack([warm.p1, warm.p2]))[:, 1:]
        r[:, 0] -= ahead[0][ix, iy]
        r[:, 1] -= ahead[1][ix, iy]
    if N == 0 or mu <= 0.0:                    # no contact or no friction: traction-free, all slip
        S1[ix, iy], S2[ix, iy] = r[:, 0] / dt, r[:, 1] / dt
        zero = np.zeros(shape)
        return TangentialContact(P1, P2, st, contact.copy(), S1, S2, zero, zero.copy(), 0.0, 0.0, 0, True, 0,
                                 np.zeros((2,) + shape), None, (0, nx - 1, 0, ny - 1))
    i0, i1, j0, j1 = win
    op = tangential_operator((i1 - i0 + 1, j1 - j0 + 1), dx, dy, E, nu)
    g = mu * p3[ix, iy]
    u_start = None
    if warm is not None and warm.p1.shape == shape:
        p0 = np.column_stack([warm.p1[ix, iy], warm.p2[ix, iy]])
        stick0 = ~warm.slip[ix, iy]
        new = ~(warm.stick | warm.slip)[ix, iy]       # elements entering the contact: start sliding
        if new.any():                                 # against the rigid slip (the set update corrects)
            rn = np.hypot(r[new, 0], r[new, 1])
            ok = rn > 0.0
            idx = np.flatnonzero(new)[ok]
            p0[idx] = -(g[idx] / rn[ok])[:, None] * r[idx]
            stick0[idx] = False
        h = warm.history
        if transient_prev and h is not None and h.order > 0 and h.window == win and _inside(win, warm.window):
            dp, du = (h.dp, h.du) if h.order == 1 else (h.dp + h.d2p, h.du + h.d2u)    # predictor
            p0 += np.column_stack([dp[0][ix, iy], dp[1][ix, iy]])
            u_start = np.stack([warm.u1[i0:i1 + 1, j0:j1 + 1], warm.u2[i0:i1 + 1, j0:j1 + 1]]) \
                + du[:, i0:i1 + 1, j0:j1 + 1]
    else:
        p0, stick0 = np.zeros((N, 2)), np.ones(N, bool)
    res = solve_coulomb(op, ix - i0, iy - j0, r, g, p0, stick0, steady=steady, tol=tol, warm=warm is not None,
                        u_start=u_start)
    if not res.converged:
        warnings.warn("TANG: stick/slip sets not converged", RuntimeWarning)
    p, s = res.p, res.s
    P1[ix, iy], P2[ix, iy] = p[:, 0], p[:, 1]
    S1[ix, iy], S2[ix, iy] = s[:, 0] / dt, s[:, 1] / dt
    st[ix, iy] = res.stick
    if full_output and win != (0, nx - 1, 0, ny - 1):
        u = tangential_operator(shape, dx, dy, E, nu).displacements(np.stack([P1, P2]))
        valid = (0, nx - 1, 0, ny - 1)
        U = u[:, :nx].copy()
        ahead = np.ascontiguousarray(u[:, 1:])
    else:
        valid = win
        U = np.zeros((2, nx, ny))
        ahead = np.zeros((2, nx, ny))
        U[:, i0:i1 + 1, j0:j1 + 1] = res.u[:, : i1 - i0 + 1]
        ahead[:, i0:i1 + 1, j0:j1 + 1] = res.u[:, 1:]
    history = None
    if transient_prev:
        history = next_history(warm.history, win, np.stack([P1 - warm.p1, P2 - warm.p2]),
                                U - np.stack([warm.u1, warm.u2]))
    dA = dx * dy
    return TangentialContact(P1, P2, st, contact & ~st, S1, S2, U[0], U[1], float(p[:, 0].sum() * dA),
                             float(p[:, 1].sum() * dA), res.newton, res.converged, res.krylov, ahead, history, valid)
