"""The reference driver's steps with Kalker's transient TANG on the NORM table, compiled (notes in
``solvers.timeloop.interaction``): the steps of ``reference.run_reference`` (normal='table',
tangential='kalker') while the contact keeps its working window, so that a step costs its
contact solve and not the Python around it.  A step that needs Python (the contact lost or
its window changed: a new operator) is left to the driver, which then resumes here.  Same
blocks, same order of operations, same results as the Python step."""
from __future__ import annotations

import numba

from solvers.contact.norm import _table_pressure, table_force
from solvers.contact.tang.pcg import transient_step
from solvers.contact.tang.rolling import MAX_ITER, PAD
from solvers.contact.tang.state import W_OFFSET
from solvers.contact.tang.steps import contact_elements, working_window
from solvers.timeloop.kernel import advance
from solvers.timeloop.result import store


@numba.njit(cache=True)
def slip_summary(p3, s1, s2, stick):
    """Kalker's solution as a row of the record: the mean slip velocities over the contact (p3 >
    0; s1, s2 are zero outside it) and the state, 1 with stick elements, 2 in full slip."""
    n = 0
    m1 = m2 = 0.0
    any_stick = False
    for i in range(p3.shape[0]):
        for j in range(p3.shape[1]):
            if p3[i, j] > 0.0:
                n += 1
                m1 += s1[i, j]
                m2 += s2[i, j]
                any_stick |= stick[i, j]
    return m1 / n, m2 / n, 1.0 if any_stick else 2.0


@numba.njit(cache=True)
def kalker_steps(n, filt, rc, p, rec, win, loop, table, contact, tang, op, row):
    """Steps n, n + 1, ... of the reference loop until the last, a stop, or a step that needs the
    Python driver.  loop = (xi2, xi3, xi2_old, jw, iw); table = (xi3, F3, q, p) of the NORM
    table; contact = (dx, dy, mu, tol); tang = the previous step's solution (P, S, stick, slip,
    U, ahead, window, d, n, order, pred: its fields and its predictor's history, valid on
    `window`); op = that window's operator arrays (buffers, hat, symbol, inv, a0, scale).
    Returns (next step, loop, stop reason, tang, (F1, F2, Newton steps, CG steps, converged) of the
    last step, steps not converged)."""
    n_steps, dt, v, xi3_static, slip_sign = p.n_steps, p.dt, p.v, p.xi3_static, p.slip_sign
    xs, F3s, qs, Ps = table
    dx, dy, mu, tol = contact
    bufs, hat, symbol, inv, a0, scale = op
    xi2, xi3, xi2_old, jw, iw = loop
    P, S, st, sl, U, ahead, window, d, hn, order, pred = tang
    counters = rec.counters
    no_prediction = pred[:, :, :0, :0]
    reason = bad = 0
    last = (0.0, 0.0, 0, 0, True)
    while n < n_steps and reason == 0:
        app = xi3_static - xi3
        F3 = table_force(app, xs, qs)
        if F3 <= 0.0:
            break
        p3 = _table_pressure(app, xs, Ps, F3s, qs)
        ix, iy, box = contact_elements(p3)
        if box[0] < 0 or working_window(box, p3.shape, window, PAD) != window:
            break
        gxn = p.gx[min(n, len(p.gx) - 1)]
        gyn = p.gy[min(n, len(p.gy) - 1)]
        dxi2 = slip_sign * (xi2 - xi2_old) / dt
        spn = p.spin[min(n, len(p.spin) - 1)]
        kin = (dx, dy, v, dx / v, gxn, gyn + dxi2 / v, spn, W_OFFSET)   # as tang_transient
        P, S, st, sl, U, ahead, f1, f2, newton, krylov, converged, d, hn, order, pred = transient_step(
            p3, ix, iy, window, kin, mu, ahead, P, st, sl, pred if order > 0 else no_prediction, U, d, hn, tol,
            MAX_ITER, bufs, hat, symbol, inv, a0, scale)
        bad += not converged
        F1, F2 = f1 * (dx * dy), f2 * (dx * dy)
        last = (F1, F2, newton, krylov, converged)
        s1, s2, state = slip_summary(p3, S[0], S[1], st)
        counters[0] += newton
        counters[1] = max(counters[1], newton)
        row[0], row[1], row[2], row[3], row[4], row[5], row[6], row[7] = F1, F2, F3, s1, s2, xi2, xi3, state
        store(n, row, rec)
        xi2_old = xi2
        xi2, xi3, jw, iw, reason = advance(filt, rc, n, F2, F3, p, win, jw, iw)
        n += 1
    return n, (xi2, xi3, xi2_old, jw, iw), reason, (P, S, st, sl, U, ahead, window, d, hn, order, pred), last, bad
