"""Per-step bookkeeping of TANG on the grid in numba (notes in ``solvers.contact.tang``): the
rigid slip and transport term of the contact elements, the start values from a previous
solution (warm start, entering elements, predictor), the solution back on the grid, and the
transient predictor's differences.  One pass each, so that a time step's own work is not lost
in array calls."""
from __future__ import annotations

import math

import numba
import numpy as np


@numba.njit(cache=True)
def rigid_and_transport(ix, iy, shape, kin, ahead, r):
    """r (N, 2) <- rigid slip times dt at x_I + w_offset dx (``tang.rigid_slip``'s formula),
    minus the transport term ahead (2, nx, ny) = u(x + dx, t - dt) when it has rows (transient).
    kin = (dx, dy, v, dt, gamma_x, gamma_y, spin, w_offset)."""
    dx, dy, v, dt, gx, gy, spin, w_off = kin
    nx, ny = shape
    transport = ahead.shape[1] > 0
    for k in range(ix.shape[0]):
        xc = (ix[k] - 0.5 * (nx - 1) + w_off) * dx
        yc = (iy[k] - 0.5 * (ny - 1)) * dy
        r[k, 0] = (gx - spin * yc) * v * dt
        r[k, 1] = (gy + spin * xc) * v * dt
        if transport:
            r[k, 0] -= ahead[0, ix[k], iy[k]]
            r[k, 1] -= ahead[1, ix[k], iy[k]]


@numba.njit(cache=True)
def start_values(ix, iy, r, g, P, stick, slip, pred, p0, stick0):
    """Start of a warm-started solve: p0 (N, 2), stick0 (N,) from the previous solution P (2,
    nx, ny) and its sets; elements entering the contact start sliding against the rigid slip
    (the set update corrects); then the predicted change pred (2, nx, ny) is added when it has
    rows."""
    predict = pred.shape[1] > 0
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        p0[k, 0], p0[k, 1] = P[0, i, j], P[1, i, j]
        stick0[k] = not slip[i, j]
        if not (stick[i, j] or slip[i, j]):
            rn = math.hypot(r[k, 0], r[k, 1])
            if rn > 0.0:
                p0[k, 0] = -g[k] / rn * r[k, 0]
                p0[k, 1] = -g[k] / rn * r[k, 1]
                stick0[k] = False
        if predict:
            p0[k, 0] += pred[0, i, j]
            p0[k, 1] += pred[1, i, j]


@numba.njit(cache=True)
def on_grid(ix, iy, p, s, stick, dt, shape):
    """The solution on the grid (zero outside the contact): tractions P, slip velocities S = s /
    dt (2, nx, ny), stick and slip sets.  Returns (P, S, stick, slip, sum p1, sum p2 [Pa])."""
    P, S = np.zeros((2,) + shape), np.zeros((2,) + shape)
    st, sl = np.zeros(shape, np.bool_), np.zeros(shape, np.bool_)
    f1 = f2 = 0.0
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        P[0, i, j], P[1, i, j] = p[k, 0], p[k, 1]
        S[0, i, j], S[1, i, j] = s[k, 0] / dt, s[k, 1] / dt
        st[i, j] = stick[k]
        sl[i, j] = not stick[k]
        f1 += p[k, 0]
        f2 += p[k, 1]
    return P, S, st, sl, f1, f2


@numba.njit(cache=True)
def differences(P, P_old, U, U_old, window, prev, n_prev):
    """Backward differences of the tractions P and displacements U (2, nx, ny) after a step, on
    the step's window (i0, i1, j0, j1): d[:, 0] = this step's change, d[:, m] = d[:, m - 1] -
    prev[:, m - 1] (prev: the previous step's differences (2, K, 2, wx, wy) on the same window,
    n_prev of them valid; row 0 tractions, 1 displacements).  The extrapolation of order m
    would have predicted this step with error d[0, m]: the order with the smallest max |d[0, m]|
    is chosen.  Returns (d (2, K, 2, wx, wy), n valid, order, prediction (2, 2, nx, ny) of the
    next change on the grid (zero outside the window): the sum of the first `order` d)."""
    i0, i1, j0, j1 = window
    wx, wy = i1 - i0 + 1, j1 - j0 + 1
    K = prev.shape[1]
    n = min(n_prev, K) + 1
    d = np.empty((2, K, 2, wx, wy))
    err = np.zeros(n)        # max |d[0, m]| over the window: the error of order m's prediction
    for c in range(2):
        for i in range(wx):
            for j in range(wy):
                dp = P[c, i0 + i, j0 + j] - P_old[c, i0 + i, j0 + j]
                du = U[c, i0 + i, j0 + j] - U_old[c, i0 + i, j0 + j]
                for m in range(n):
                    if m > 0:
                        dp -= prev[0, m - 1, c, i, j]
                        du -= prev[1, m - 1, c, i, j]
                    err[m] = max(err[m], abs(dp))
                    if m < K:
                        d[0, m, c, i, j] = dp
                        d[1, m, c, i, j] = du
    best, order = math.inf, 0
    for m in range(n):
        if err[m] < best:
            best, order = err[m], m
    if n == 1:              # no history yet: linear
        order = 1
    pred = np.zeros((2,) + P.shape)
    for a in range(2):
        for c in range(2):
            for i in range(wx):
                for j in range(wy):
                    v = 0.0
                    for m in range(order):
                        v += d[a, m, c, i, j]
                    pred[a, c, i0 + i, j0 + j] = v
    return d, min(n, K), order, pred


@numba.njit(cache=True)
def contact_elements(p3):
    """Indices (ix, iy) of the elements with p3 > 0 and their bounding box (i0, i1, j0, j1)
    (i0 = -1 without contact)."""
    nx, ny = p3.shape
    n = 0
    i0, i1, j0, j1 = nx, -1, ny, -1
    for i in range(nx):
        for j in range(ny):
            if p3[i, j] > 0.0:
                n += 1
                i0, i1, j0, j1 = min(i0, i), max(i1, i), min(j0, j), max(j1, j)
    ix, iy = np.empty(n, np.int64), np.empty(n, np.int64)
    k = 0
    for i in range(nx):
        for j in range(ny):
            if p3[i, j] > 0.0:
                ix[k], iy[k] = i, j
                k += 1
    if n == 0:
        i0 = -1
    return ix, iy, (i0, i1, j0, j1)


@numba.njit(cache=True)
def predicted_start(U, pred, window):
    """The predicted displacements of a warm start on the window (i0, i1, j0, j1): U + pred[1] there
    (U (2, nx, ny): the previous step's; pred: History.pred)."""
    i0, i1, j0, j1 = window
    out = np.empty((2, i1 - i0 + 1, j1 - j0 + 1))
    for a in range(2):
        for i in range(i0, i1 + 1):
            for j in range(j0, j1 + 1):
                out[a, i - i0, j - j0] = U[a, i, j] + pred[1, a, i, j]
    return out


@numba.njit(cache=True)
def window_fields(u, window, shape):
    """The displacements of a solve on the window (u (2, wx + 1, wy): grid rows and one ahead) on the
    whole grid, zero outside the window: U (2, nx, ny) and the next step's transport term ahead =
    u(x + dx) (2, nx, ny)."""
    i0, i1, j0, j1 = window
    U = np.zeros((2,) + shape)
    ahead = np.zeros((2,) + shape)
    for a in range(2):
        for i in range(i0, i1 + 1):
            for j in range(j0, j1 + 1):
                U[a, i, j] = u[a, i - i0, j - j0]
                ahead[a, i, j] = u[a, i - i0 + 1, j - j0]
    return U, ahead


NO_WINDOW = (-1, -1, -1, -1)    # "no previous window" for working_window


@numba.njit(cache=True)
def inside(w, v):
    """Window w (i0, i1, j0, j1) inside window v."""
    return w[0] >= v[0] and w[1] <= v[1] and w[2] >= v[2] and w[3] <= v[3]


@numba.njit(cache=True)
def working_window(box, shape, old, pad):
    """The window of a step's solve for the contact's bounding box (i0, i1, j0, j1; i0 >= 0): the
    previous step's window `old` while the contact fits in it and it is at most twice the box
    grown by `pad` elements (a stable window keeps the predictor's history and the operator);
    otherwise the box grown by `pad`, clipped to the grid (a breathing contact outgrew it); the
    box itself without a previous window (old = NO_WINDOW)."""
    nx, ny = shape
    if old[0] < 0:
        return box
    padded = (max(box[0] - pad, 0), min(box[1] + pad, nx - 1), max(box[2] - pad, 0), min(box[3] + pad, ny - 1))
    if inside(box, old) and (old[1] - old[0] + 1) * (old[3] - old[2] + 1) <= \
            2 * (padded[1] - padded[0] + 1) * (padded[3] - padded[2] + 1):
        return old
    return padded
