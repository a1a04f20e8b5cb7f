"""The steady and transient TANG problem of one step on the contact's window (notes in
``solvers.contact.tang``): rigid slip, transport term, warm start and predictor, the Coulomb
solve, and the solution on the grid."""
from __future__ import annotations

import warnings

import numpy as np

from solvers.contact.tang.falling import solve_falling, transient_falling
from solvers.contact.tang.newton import solve_coulomb
from solvers.contact.tang.operator import tangential_operator
from solvers.contact.tang.pcg import transient_step, transient_step_law
from solvers.contact.tang.state import ORDER, History, Rolling, TangentialContact, TangOptions
from solvers.contact.tang.steps import NO_WINDOW, contact_elements, inside, on_grid, rigid_and_transport, start_values, window_fields, working_window


_EMPTY = np.zeros((2, 0, 0))   # "no array" for the numba kernels
_NO_SET = np.zeros((0, 0), bool)
_NO_PREDICTION = np.zeros((2, 2, 0, 0))
_NEW_HISTORY = np.zeros((2, ORDER, 2, 1, 1))     # predictor differences: none valid yet
_NO_HISTORY = np.zeros((2, ORDER, 2, 0, 0))      # ... not kept (steady, or no previous step)
MAX_ITER = 200              # Newton steps at most (transient)
PAD = 1                     # elements around the contact's bounding box when it outgrew the window


def solve_rolling(p3, roll: Rolling, steady: bool, warm: TangentialContact | None,
                  opts: TangOptions, law=None) -> TangentialContact:
    """Common driver of tang_steady / tang_transient: the problem of pressures p3 (nx, ny) [Pa]
    rolling as ``roll`` (steady or one transient step from ``warm``) on the contact's window.
    `law`: a slip-speed dependent FrictionLaw (roll.mu is then its mu(0)), None: Coulomb with
    roll.mu."""
    dx, dy, v, mu, gamma_x, gamma_y, spin = roll
    E, nu, tol, w_offset, full_output = opts
    p3 = np.asarray(p3, dtype=float)
    shape = p3.shape
    nx, ny = shape
    dt = dx / v
    ix, iy, box = contact_elements(p3)
    N = ix.size
    old = NO_WINDOW
    if warm is not None and warm.p1.shape == shape and warm.history is not None:
        old = warm.history.window
    win = working_window(box, shape, old, PAD)
    transient_prev = (not steady) and warm is not None and warm.p1.shape == shape
    P_old = warm.P if warm is not None and warm.p1.shape == shape else None
    ahead = _EMPTY
    if transient_prev and N > 0:               # transport term: -u(x + dx, t - dt)
        ahead = warm.u_ahead
        if ahead is None or not inside(win, warm.window):
            ahead = tangential_operator(shape, dx, dy, E, nu).displacements(P_old)[:, 1:]
    kin = (dx, dy, v, dt, gamma_x, gamma_y, spin, w_offset)
    if N == 0 or mu <= 0.0:                    # no contact or no friction: traction-free, all slip
        r = np.empty((N, 2))
        rigid_and_transport(ix, iy, shape, kin, ahead, r)
        P, S, U = np.zeros((2,) + shape), np.zeros((2,) + shape), np.zeros((2,) + shape)
        S[0][ix, iy], S[1][ix, iy] = r[:, 0] / dt, r[:, 1] / dt
        return TangentialContact(P[0], P[1], np.zeros(shape, bool), p3 > 0.0, S[0], S[1], U[0], U[1],
                                 0.0, 0.0, 0, True, 0, np.zeros((2,) + shape), None, (0, nx - 1, 0, ny - 1), P, U)
    i0, i1, j0, j1 = win
    op = tangential_operator((i1 - i0 + 1, j1 - j0 + 1), dx, dy, E, nu)
    h = warm.history if P_old is not None else None
    predict = transient_prev and h is not None and h.order > 0 and h.window == win and inside(win, warm.window)
    if steady:
        P, S, st, sl, U, ahead, f1, f2, newton, krylov, converged = _steady(p3, ix, iy, win, kin, mu, op, P_old, warm,
                                                                        tol, law)
    else:                                      # compiled whole (tang.pcg)
        U_old = warm.U if transient_prev else _EMPTY
        if transient_prev and h is not None and h.pred.shape[1:] == P_old.shape and h.window == win:
            hist_d, hist_n = h.d, h.n
        elif transient_prev:                   # a new history (first step, or a new window)
            hist_d, hist_n = _NEW_HISTORY, 0
        else:
            hist_d, hist_n = _NO_HISTORY, 0
        rest = (ahead, _EMPTY if P_old is None else P_old,
                _NO_SET if P_old is None else warm.stick, _NO_SET if P_old is None else warm.slip,
                h.pred if predict else _NO_PREDICTION, U_old, hist_d, hist_n, tol, MAX_ITER, op.buffers.arrays, op.hat,
                op.symbol, op.inv, op.a0, op.scale)
        if law is None:
            out = transient_step(p3, ix, iy, win, kin, mu, *rest)
        else:                                  # the previous step's slip speeds start the iteration
            speed = None if P_old is None else np.hypot(warm.s1[ix, iy], warm.s2[ix, iy])
            out = transient_falling(lambda mu_el: transient_step_law(p3, ix, iy, win, kin, mu, mu_el, *rest), law,
                                    p3[ix, iy], ix, iy, speed)
        P, S, st, sl, U, ahead, f1, f2, newton, krylov, converged, d, n, order, pred = out
    if not converged:
        warnings.warn("TANG: stick/slip sets not converged", RuntimeWarning)
    valid = win
    if full_output and win != (0, nx - 1, 0, ny - 1):
        u = tangential_operator(shape, dx, dy, E, nu).displacements(P)
        valid = (0, nx - 1, 0, ny - 1)
        U = u[:, :nx].copy()
        ahead = np.ascontiguousarray(u[:, 1:])
    history = History(d, n, order, win, pred) if transient_prev else None
    dA = dx * dy
    return TangentialContact(P[0], P[1], st, sl, S[0], S[1], U[0], U[1], f1 * dA, f2 * dA, newton,
                             converged, krylov, ahead, history, valid, P, U)


def _steady(p3, ix, iy, win, kin, mu, op, P_old, warm, tol, law=None):
    """The steady solve on the window (GMRES in Python, ``tang.newton``; with a slip-speed
    dependent `law` the outer iteration of ``tang.falling``), returning the fields of
    ``tang.pcg.transient_step`` up to ``converged``."""
    nx, ny = p3.shape
    i0, _, j0, _ = win
    N = ix.size
    r = np.empty((N, 2))
    rigid_and_transport(ix, iy, (nx, ny), kin, _EMPTY, r)
    g = mu * p3[ix, iy]
    p0, stick0 = np.zeros((N, 2)), np.ones(N, bool)
    if P_old is not None:                      # warm start; entering elements start sliding
        start_values(ix, iy, r, g, P_old, warm.stick, warm.slip, _EMPTY, p0, stick0)
    if law is None:
        res = solve_coulomb(op, ix - i0, iy - j0, r, g, p0, stick0, tol=tol, warm=warm is not None)
    else:                                      # INISLP = 0: the warm start's slip speeds
        speed = None if P_old is None else np.hypot(warm.s1[ix, iy], warm.s2[ix, iy])
        res = solve_falling(op, ix - i0, iy - j0, r, p3[ix, iy], law, kin[3], p0, stick0, speed=speed, tol=tol,
                            warm=warm is not None).result
    P, S, st, sl, f1, f2 = on_grid(ix, iy, res.p, res.s, res.stick, kin[3], (nx, ny))
    U, ahead = window_fields(res.u, win, (nx, ny))
    return P, S, st, sl, U, ahead, f1, f2, res.newton, res.krylov, res.converged
