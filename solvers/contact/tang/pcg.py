"""The transient step of TANG compiled whole (notes in ``solvers.contact.tang``): Kalker's
active-set Newton method with its preconditioned CG inner solver and the FFT products
(``tang.operator.fft_convolve`` / ``fft_precondition``) in one numba function, and the step
around it (``transient_step``: the bookkeeping of ``tang.steps``), so that a time step of a
small contact is not spent in Python between the transforms.  Same Newton steps and stopping
rules as the steady solve in ``tang.newton``."""
from __future__ import annotations

import math

import numba
import numpy as np

from solvers.contact.tang.kernels import after_step, forcing_term, gather_slip, newton_system, pcg_direction, pcg_update, precondition_in, scatter, slip_geometry, start_on_bounds, step_and_scatter, update_sets
from solvers.contact.tang.operator import _shifted_inverse, fft_convolve, fft_precondition
from solvers.contact.tang.state import QUADRATIC
from solvers.contact.tang.steps import differences, on_grid, predicted_start, rigid_and_transport, start_values, window_fields

CG_ABS = 0.1        # CG also stops when its error estimate is below CG_ABS tol x traction level
RHO_MIN = 0.25      # ... the contraction per CG step assumed at least (the preconditioned CG's is ~1/4)
LINEAR = 0.1        # a Newton step whose non-linear part is below LINEAR tol x traction level: its
                    # displacements are the sum of its CG products (error well inside CG_ABS's budget)
FEW = 2             # set changes after which the next Newton step may be final (steady solve too)


@numba.njit(cache=True)
def _pcg(ix, iy, stick, t, sc, D, mdiag, scale, b, rtol, atol, kmax, bufs, hat, ny, inv_a, inv_b, use_a,
         use_b, x, rv, q, z, d, Ax):
    """J x = b by preconditioned CG (transient: J symmetric positive definite), fused kernels.
    Stops at |r| <= rtol |b|, or when the error left, estimated from the last update max |alpha d|
    and its ratio rho to the one before (rho >= RHO_MIN) as |alpha d| rho / (1 - rho), is below
    atol.  x is overwritten, and Ax with the displacements of lift(x) on the window and one row
    ahead (the sum of the products).  Returns (steps, error estimate: rtol max |x| or that
    estimate)."""
    nx = bufs[0].shape[1]
    conv_in = bufs[0][:, :, :ny]
    prec_in = bufs[5][:, :nx, :ny]
    x[:] = 0.0
    Ax[:] = 0.0
    rv[:] = b
    bn2 = 0.0
    for k in range(b.shape[0]):
        bn2 += b[k, 0] * b[k, 0] + b[k, 1] * b[k, 1]
    if bn2 == 0.0:
        return 0, 0.0
    step_old = math.inf
    precondition_in(ix, iy, stick, t, sc, rv, False, use_b, prec_in)
    Z = fft_precondition(bufs, inv_a, inv_b, use_a, use_b, nx, ny)
    rz = pcg_direction(ix, iy, stick, t, sc, D, mdiag, Z, use_b, rv, z, 0.0, d, conv_in)
    for k in range(1, kmax + 1):
        U = fft_convolve(bufs, hat, ny)
        rr, dq, step, xmax = pcg_update(ix, iy, stick, t, D, U, False, scale, d, q, rz, x, rv, sc, use_b, prec_in)
        if dq <= 0.0:
            return k, 0.0
        _axpy(rz / dq, U, Ax)
        if rr <= rtol * rtol * bn2:
            return k, rtol * xmax
        rho = min(max(step / step_old, RHO_MIN), 1.0)     # contraction of the last step
        est = step * rho / (1.0 - rho) if rho < 1.0 else math.inf
        if est <= atol:
            return k, est
        step_old = step
        Z = fft_precondition(bufs, inv_a, inv_b, use_a, use_b, nx, ny)
        rz = pcg_direction(ix, iy, stick, t, sc, D, mdiag, Z, use_b, rv, z, rz, d, conv_in)
    return kmax, math.inf


@numba.njit(cache=True)
def _axpy(a, X, Y):
    """Y += a X (3-d arrays)."""
    for i in range(X.shape[0]):
        for j in range(X.shape[1]):
            for k in range(X.shape[2]):
                Y[i, j, k] += a * X[i, j, k]


@numba.njit(cache=True)
def _remainder(stick, p, p_old, x, t):
    """Largest |p - p_old - lift(x)|: the part of a Newton step that is not its linearisation
    (slip elements: the traction circle's curvature, or a clipped angle)."""
    e = 0.0
    for k in range(stick.shape[0]):
        if not stick[k]:
            e = max(e, abs(p[k, 0] - p_old[k, 0] - x[k, 0] * t[k, 0]), abs(p[k, 1] - p_old[k, 1] - x[k, 0] * t[k, 1]))
    return e


@numba.njit(cache=True)
def _slip_of(ix, iy, p, r, s, bufs, hat, ny):
    """s <- r + A p; returns the displacements (a view into the FFT buffers)."""
    scatter(ix, iy, p, bufs[0][:, :, :ny])
    u = fft_convolve(bufs, hat, ny)
    gather_slip(ix, iy, u, False, r, s)
    return u


@numba.njit(cache=True)
def coulomb_transient(ix, iy, r, g, p, stick, u_start, warm, tol, max_iter, bufs, hat, ny, symbol, inv, a0,
                      scale):
    """``tang.newton.solve_coulomb`` for transient rolling (M = A), compiled: p (N, 2), stick (N,)
    are the start and are overwritten by the solution; u_start (2, nx, ny) the predicted
    displacements of the start, or an array without rows.  Returns (slip s (N, 2), displacements
    u (2, nx + 1, ny) of the solution, Newton steps, CG steps, converged)."""
    N = ix.shape[0]
    mdiag = a0 / scale
    theta = np.empty(N)
    for k in range(N):
        theta[k] = math.atan2(p[k, 1], p[k, 0])
    t, s, R, b = np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2))
    x, rv, q, z, d = np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2))
    D = np.zeros(N)
    sc = np.ones(N)
    inv_slip = np.empty_like(symbol)
    q_lim = math.sqrt(tol / QUADRATIC)           # steps this small are final (quadratic convergence) ...
    eta_final = min(1e-3, 0.1 * tol / q_lim)      # ... if solved this accurately
    # start: slip elements on their circle, stick elements inside their bound; the predicted
    # displacements hold for the start only if it was kept
    p_old = p.copy()                             # the start as given; then the tractions before each step
    p_level, moved = start_on_bounds(stick, theta, g, s, p, t, D, scale, p_old)
    use_start = u_start.shape[1] > 0 and moved <= 1e-3 * q_lim * p_level
    u = u_start
    if use_start:
        gather_slip(ix, iy, u_start, False, r, s)
    else:
        u = _slip_of(ix, iy, p, r, s, bufs, hat, ny)
    if warm:                    # the sets the (predicted) start implies, as after a step
        slip_geometry(stick, theta, g, s, p, t, D, scale)
        to_slip, to_stick = update_sets(stick, theta, g, p, s, 1e-9)
        if to_slip:
            u = _slip_of(ix, iy, p, r, s, bufs, hat, ny)
    # the displacements of the current tractions (u_cur; valid on all rows unless the predicted
    # start's), and of the last Krylov solution (Ax: summed from the CG products)
    u_cur = np.empty((2, bufs[4].shape[1], ny))
    exact = u.shape[1] == u_cur.shape[1]
    if exact:
        u_cur[:] = u
    Ax = np.empty_like(u_cur)
    newton = krylov = 0
    converged = False
    sets_changed = not warm
    n_changed = N if not warm else 0
    ratio = 0.0
    for newton in range(1, max_iter + 1):
        r_max, n_stick, dbar = newton_system(stick, theta, g, s, p, t, D, scale, R, b, mdiag, sc)
        if n_stick < N:
            _shifted_inverse(symbol, dbar, inv_slip)
        eta = forcing_term(n_changed > FEW, ratio, r_max, tol, p_level, eta_final)
        # absolute stop only where the step may be final (its error budget: 0.1 tol level)
        atol = CG_ABS * tol * p_level if n_changed <= FEW else 0.0
        k, err = _pcg(ix, iy, stick, t, sc, D, mdiag, scale, b, eta, atol, 200, bufs, hat, ny, inv, inv_slip,
                      n_stick > 0, n_stick < N, x, rv, q, z, d, Ax)
        krylov += k
        p_old[:] = p
        change = step_and_scatter(ix, iy, stick, theta, g, x, p, 0.5, bufs[0][:, :, :ny])
        ratio = change / max(r_max, 1e-300)
        if exact and _remainder(stick, p, p_old, x, t) <= LINEAR * tol * p_level:
            _axpy(1.0, Ax, u_cur)         # u(p + lift(x)) = u(p) + A lift(x): no product
        else:
            u_cur[:] = fft_convolve(bufs, hat, ny)
            exact = True
        to_slip, n_changed, p_level, converged = after_step(ix, iy, u_cur, False, r, s, stick, theta, g, p, change,
                                                            err, tol, q_lim, sets_changed)
        sets_changed = n_changed > 0
        if converged:
            break
        if to_slip:                   # projected tractions: the slip follows
            u_cur[:] = _slip_of(ix, iy, p, r, s, bufs, hat, ny)
    for k in range(N):
        if stick[k]:
            s[k, 0] = s[k, 1] = 0.0
    return s, u_cur, newton, krylov, converged


@numba.njit(cache=True)
def transient_step(p3, ix, iy, win, kin, mu, ahead, P_old, stick_old, slip_old, pred, U_old, hist_d, hist_n,
                   tol, max_iter, bufs, hat, symbol, inv, a0, scale):
    """One transient step with Coulomb friction mu (``transient_step_law`` without coefficients)."""
    return transient_step_law(p3, ix, iy, win, kin, mu, np.empty(0), ahead, P_old, stick_old, slip_old, pred, U_old,
                              hist_d, hist_n, tol, max_iter, bufs, hat, symbol, inv, a0, scale)


@numba.njit(cache=True)
def transient_step_law(p3, ix, iy, win, kin, mu, mu_el, ahead, P_old, stick_old, slip_old, pred, U_old, hist_d,
                       hist_n, tol, max_iter, bufs, hat, symbol, inv, a0, scale):
    """One transient step of ``tang.rolling.solve_rolling`` after its window is chosen, compiled:
    the rigid slip and transport term (ahead (2, nx, ny), or no rows: first step), the start from
    the previous solution P_old (no rows: traction-free) with its sets and the predicted change
    pred (2, 2, nx, ny) (no rows: none), the Coulomb solve on the window win = (i0, i1, j0, j1)
    with the operator's arrays, the solution on the grid and the predictor's differences after
    the step (hist_d with rows: the previous step's, hist_n valid; ``tang.steps.differences``).
    kin = (dx, dy, v, dt, gamma_x, gamma_y, spin, w_offset).  mu_el (N,): the elements' coefficients
    of a slip-speed dependent law (``tang.falling``; no elements: Coulomb with mu).  Returns (P, S (2, nx, ny), stick,
    slip, U, ahead, f1, f2, Newton steps, CG steps, converged, d, n, order, prediction)."""
    nx, ny = p3.shape
    i0, i1, j0, j1 = win
    N = ix.shape[0]
    r = np.empty((N, 2))
    rigid_and_transport(ix, iy, (nx, ny), kin, ahead, r)
    g = np.empty(N)
    if mu_el.shape[0] == N and N > 0:
        for k in range(N):
            g[k] = mu_el[k] * p3[ix[k], iy[k]]
    else:
        for k in range(N):
            g[k] = mu * p3[ix[k], iy[k]]
    p = np.zeros((N, 2))
    stick = np.ones(N, np.bool_)
    warm = P_old.shape[1] > 0
    u_start = pred[0, :, :0, :0]
    if warm:                                   # warm start; entering elements start sliding
        start_values(ix, iy, r, g, P_old, stick_old, slip_old, pred[0], p, stick)
        if pred.shape[2] > 0:                  # predictor: polynomial extrapolation of the last steps
            u_start = predicted_start(U_old, pred, win)
    s, u, newton, krylov, converged = coulomb_transient(ix - i0, iy - j0, r, g, p, stick, u_start, warm, tol,
                                                        max_iter, bufs, hat, j1 - j0 + 1, symbol, inv, a0, scale)
    P, S, st, sl, f1, f2 = on_grid(ix, iy, p, s, stick, kin[3], (nx, ny))
    U, ahead_new = window_fields(u, win, (nx, ny))
    d, n, order, pred_new = hist_d, 0, 0, pred[:, :, :0, :0]
    if hist_d.shape[3] > 0:
        d, n, order, pred_new = differences(P, P_old, U, U_old, win, hist_d, hist_n)
    return P, S, st, sl, U, ahead_new, f1, f2, newton, krylov, converged, d, n, order, pred_new
