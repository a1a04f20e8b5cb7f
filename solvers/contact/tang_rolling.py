"""The steady and transient TANG problem of one step on the contact's window (notes in
``solvers.contact.tang``): rigid slip, transport term, warm start and predictor, the Coulomb
solve, and the solution on the grid."""
from __future__ import annotations

import warnings

import numpy as np

from .tang_newton import solve_coulomb
from .tang_operator import tangential_operator
from .tang_state import Rolling, TangentialContact, TangOptions, next_history
from .tang_steps import (contact_elements, on_grid, predicted_start, rigid_and_transport, start_values,
                         window_fields)


_EMPTY = np.zeros((2, 0, 0))   # "no array" for the numba kernels
PAD = 1                     # elements around the contact's bounding box when it outgrew the window


def _grow(box, shape, pad):
    """Bounding box (i0, i1, j0, j1) grown by `pad`, clipped to the grid; None without contact."""
    if box[0] < 0:
        return None
    nx, ny = shape
    return (max(box[0] - pad, 0), min(box[1] + pad, nx - 1), max(box[2] - pad, 0), min(box[3] + pad, ny - 1))


def _inside(w, v):
    """Window w inside window v."""
    return v is not None and w[0] >= v[0] and w[1] <= v[1] and w[2] >= v[2] and w[3] <= v[3]


def _stacked(both, a, b):
    """A pair of a solution's fields as one (2, nx, ny) array: the stacked one it keeps (P, U), or
    its two rows stacked (a solution made elsewhere)."""
    return both if both is not None else np.stack([a, b])


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
    ix, iy, box = contact_elements(p3)
    N = ix.size
    win = _grow(box, shape, 0)
    if win is not None and warm is not None and warm.p1.shape == shape and warm.history is not None:
        # keep the previous step's window while the contact fits in it (a stable window keeps the
        # predictor's history and the operator); a contact that outgrew it gets PAD elements
        # around it (time loops with a breathing contact area)
        old = warm.history.window
        padded = _grow(box, shape, PAD)
        if _inside(win, old) and (old[1] - old[0] + 1) * (old[3] - old[2] + 1) <= \
                2 * (padded[1] - padded[0] + 1) * (padded[3] - padded[2] + 1):
            win = old
        else:
            win = padded
    P, S = np.zeros((2,) + shape), np.zeros((2,) + shape)
    st = np.zeros(shape, bool)
    transient_prev = (not steady) and warm is not None and warm.p1.shape == shape
    P_old = _stacked(warm.P, warm.p1, warm.p2) if warm is not None and warm.p1.shape == shape else None
    ahead = _EMPTY
    if transient_prev:                         # transport term: -u(x + dx, t - dt)
        ahead = warm.u_ahead
        if ahead is None or not _inside(win, warm.window):
            ahead = tangential_operator(shape, dx, dy, E, nu).displacements(P_old)[:, 1:]
    r = np.empty((N, 2))                       # rigid slip times dt at x_I + w_offset dx, transport
    rigid_and_transport(ix, iy, shape, (dx, dy, v, dt, gamma_x, gamma_y, spin, w_offset), ahead, r)
    if N == 0 or mu <= 0.0:                    # no contact or no friction: traction-free, all slip
        S[0][ix, iy], S[1][ix, iy] = r[:, 0] / dt, r[:, 1] / dt
        zero = np.zeros(shape)
        return TangentialContact(P[0], P[1], st, contact.copy(), S[0], S[1], zero, zero.copy(), 0.0, 0.0, 0, True,
                                 0, np.zeros((2,) + shape), None, (0, nx - 1, 0, ny - 1), P)
    i0, i1, j0, j1 = win
    op = tangential_operator((i1 - i0 + 1, j1 - j0 + 1), dx, dy, E, nu)
    g = mu * p3[ix, iy]
    u_start = None
    p0, stick0 = np.zeros((N, 2)), np.ones(N, bool)
    if P_old is not None:                      # warm start; entering elements start sliding
        h = warm.history
        predict = transient_prev and h is not None and h.order > 0 and h.window == win \
            and _inside(win, warm.window)
        start_values(ix, iy, r, g, P_old, warm.stick, warm.slip, h.pred[0] if predict else _EMPTY, p0, stick0)
        if predict:                            # predictor: polynomial extrapolation of the last steps
            u_start = predicted_start(_stacked(warm.U, warm.u1, warm.u2), h.pred, win)
    res = solve_coulomb(op, ix - i0, iy - j0, r, g, p0, stick0, steady=steady, tol=tol, warm=warm is not None,
                        u_start=u_start)
    if not res.converged:
        warnings.warn("TANG: stick/slip sets not converged", RuntimeWarning)
    f1, f2 = on_grid(ix, iy, res.p, res.s, res.stick, dt, P, S, st)
    if full_output and win != (0, nx - 1, 0, ny - 1):
        u = tangential_operator(shape, dx, dy, E, nu).displacements(P)
        valid = (0, nx - 1, 0, ny - 1)
        U = u[:, :nx].copy()
        ahead = np.ascontiguousarray(u[:, 1:])
    else:
        valid = win
        U, ahead = window_fields(res.u, win, shape)
    history = None
    if transient_prev:
        history = next_history(warm.history, win, P, P_old, U, _stacked(warm.U, warm.u1, warm.u2))
    dA = dx * dy
    return TangentialContact(P[0], P[1], st, contact & ~st, S[0], S[1], U[0], U[1], f1 * dA, f2 * dA, res.newton,
                             res.converged, res.krylov, ahead, history, valid, P, U)
