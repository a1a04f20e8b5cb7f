"""The transient Coulomb solve of TANG compiled whole (notes in ``solvers.contact.tang``): Kalker's
active-set Newton method with its preconditioned CG inner solver and the FFT products
(``tang_operator.fft_convolve`` / ``fft_precondition``) in one numba function, so that a time
step of a small contact is not spent in Python between the transforms.  Same Newton steps and
stopping rules as the steady solve in ``tang_newton``."""
from __future__ import annotations

import math

import numba
import numpy as np

from .tang_kernels import (after_step, forcing_term, gather_slip, newton_system, pcg_direction, pcg_update,
                           precondition_in, scatter, slip_geometry, start_on_bounds, step_and_scatter, update_sets)
from .tang_operator import _shifted_inverse, fft_convolve, fft_precondition
from .tang_state import QUADRATIC

CG_ABS = 0.1        # CG also stops when its error estimate is below CG_ABS tol x traction level
RHO_MIN = 0.25      # ... the contraction per CG step assumed at least (the preconditioned CG's is ~1/4)
FEW = 2             # set changes after which the next Newton step may be final (steady solve too)


@numba.njit(cache=True)
def _pcg(ix, iy, stick, t, sc, D, mdiag, scale, b, rtol, atol, kmax, bufs, hat, ny, inv_a, inv_b, use_a,
         use_b, x, rv, q, z, d):
    """J x = b by preconditioned CG (transient: J symmetric positive definite), fused kernels.
    Stops at |r| <= rtol |b|, or when the error left, estimated from the last update max |alpha d|
    and its ratio rho to the one before (rho >= RHO_MIN) as |alpha d| rho / (1 - rho), is below
    atol.  x is overwritten.  Returns (steps, error estimate: rtol max |x| or that estimate)."""
    nx = bufs[0].shape[1]
    conv_in = bufs[0][:, :, :ny]
    prec_in = bufs[5][:, :nx, :ny]
    x[:] = 0.0
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
def _slip_of(ix, iy, p, r, s, bufs, hat, ny):
    """s <- r + A p; returns the displacements (a view into the FFT buffers)."""
    scatter(ix, iy, p, bufs[0][:, :, :ny])
    u = fft_convolve(bufs, hat, ny)
    gather_slip(ix, iy, u, False, r, s)
    return u


@numba.njit(cache=True)
def coulomb_transient(ix, iy, r, g, p, stick, u_start, warm, tol, max_iter, bufs, hat, ny, symbol, inv, a0,
                      scale):
    """``tang_newton.solve_coulomb`` for transient rolling (M = A), compiled: p (N, 2), stick (N,)
    are the start and are overwritten by the solution; u_start (2, nx + 1, ny) the predicted
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
    p_level, moved = start_on_bounds(stick, theta, g, s, p, t, D, scale, p.copy())
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
                      n_stick > 0, n_stick < N, x, rv, q, z, d)
        krylov += k
        change = step_and_scatter(ix, iy, stick, theta, g, x, p, 0.5, bufs[0][:, :, :ny])
        ratio = change / max(r_max, 1e-300)
        u = fft_convolve(bufs, hat, ny)
        to_slip, n_changed, p_level, converged = after_step(ix, iy, u, False, r, s, stick, theta, g, p, change, err,
                                                            tol, q_lim, sets_changed)
        sets_changed = n_changed > 0
        if converged:
            break
        if to_slip:                   # projected tractions: the slip follows
            u = _slip_of(ix, iy, p, r, s, bufs, hat, ny)
    for k in range(N):
        if stick[k]:
            s[k, 0] = s[k, 1] = 0.0
    return s, u.copy(), newton, krylov, converged
