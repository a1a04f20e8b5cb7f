"""The numba time loop (table NORM, point-contact model; notes in ``solvers.timeloop.interaction``): the
tangential point-contact solve of one step [4.25]-[4.31], the end-of-step update of the
structures [4.13], [4.15] shared with the reference driver, and the loop itself.

Spin in the point contact: its effect on the forces enters as equivalent creepages, gamma_tau +
L_tau spin, with L = C^-1 dF/dspin from Kalker's linear theory on the contact's own grid
(``solvers.contact.spin``; for an elliptic patch L2 = sqrt(ab) C23/C22, L1 = 0: Shen, Hedrick and
Elkins, Vehicle System Dynamics 12 (1983)).  The structures have no longitudinal direction: the
loop's direction 1 is the contact's own compliance A1 only (the wheel's circumferential and
torsional motion and the rail's longitudinal receptance are not modelled), so F1 changes the
slip direction and the magnitude left for F2, never a structural displacement."""
from __future__ import annotations

import math

import numba
import numpy as np

from solvers.contact.compliance import table_compliance
from solvers.contact.friction import mu_and_slope
from solvers.contact.norm import table_force
from solvers.wheel.modal_filter import filter_step
from solvers.timeloop.partitioned import partitioned_step
from solvers.timeloop.inputs import FULL_SLIP
from solvers.timeloop.result import store
from solvers.timeloop.stop import record_window


@numba.njit(cache=True)
def point_contact(b1, b2, c1, c2, F3, s_nodes, mu_nodes, slopes, eps, sigma0):
    """Tangential point-contact model [4.25]-[4.31] for one step (module notes):
    s_tau = b_tau + c_tau F_tau, F_tau = -mu_RF(s) F3 s_tau / sqrt(s^2 + eps^2).
    b (m/s): the known part of the slip; c_tau = A_tau / dt (m/s per N); F3 > 0; eps >= 0
    (0 needs mu_RF(0) = 0).
    sigma0: a start value for |s| (the previous step's), ignored unless in (0, |b|).
    Returns F1, F2, s1, s2, |s|, Newton iterations, bisection fallbacks."""
    F1, F2, s1, s2, sig, it, nb, m = _point_contact(b1, b2, c1, c2, F3, s_nodes, mu_nodes, slopes, eps, sigma0)
    return F1, F2, s1, s2, sig, it, nb


@numba.njit(cache=True, inline="always")
def _point_contact(b1, b2, c1, c2, F3, s_nodes, mu_nodes, slopes, eps, sigma0):
    """``point_contact`` plus mu_RF(|s|) at the solution (the loop's contact state).  Each Newton
    step divides as little as it can (reciprocals reused: the step's latency is its divisions)."""
    bn = math.hypot(b1, b2)                              # (b^2 would underflow for |b| < 1e-154)
    if bn == 0.0 or F3 <= 0.0:
        return 0.0, 0.0, b1, b2, bn, 0, 0, mu_nodes[0]
    ib = 1.0 / bn
    k1 = c1 * F3
    k2 = c2 * F3
    e1 = b1 * ib
    e2 = b2 * ib
    q1 = e1 * e1                                          # e_tau^2, e = b / |b|
    q2 = e2 * e2
    kb1 = k1 * ib
    kb2 = k2 * ib
    ee = eps * eps
    # scaled unknown x = sigma / |b| in (0, 1]; H(x) = 1/sqrt(e1^2/d1^2 + e2^2/d2^2) - 1, d = D/|b|
    lo = 0.0
    hi = 1.0
    x = sigma0 * ib
    if not (0.0 < x < 1.0):
        x = 0.5
    it = 0
    nb = 0
    for it in range(1, 101):
        sig = x * bn
        m, dm = mu_and_slope(sig, s_nodes, mu_nodes, slopes)
        if eps > 0.0:                                     # g = mu_RF(s) s / sqrt(s^2 + eps^2), dg = dg / dsigma
            ir = 1.0 / math.sqrt(sig * sig + ee)
            sr = sig * ir
            g = m * sr
            dg = dm * sr + m * ee * ir * ir * ir
        else:                                             # sigma > 0: s / |s| = 1
            g = m
            dg = dm
        i1 = 1.0 / (x + kb1 * g)                          # 1 / d_tau
        i2 = 1.0 / (x + kb2 * g)
        u1 = q1 * i1 * i1                                 # e_tau^2 / d_tau^2
        u2 = q2 * i2 * i2
        N = u1 + u2
        rN = 1.0 / math.sqrt(N)
        H = rN - 1.0
        if H == 0.0:
            break
        if H > 0.0:
            hi = x
        else:
            lo = x
        # dH/dx = -dN/dx / (2 N^1.5), dN/dx = -2 sum e^2 dd / d^3, dd = 1 + k dg
        dH = (u1 * i1 * (1.0 + k1 * dg) + u2 * i2 * (1.0 + k2 * dg)) * rN / N
        xn = x - H / dH if dH > 0.0 else -1.0
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
            nb += 1
        if abs(xn - x) <= 1e-15 or hi - lo <= 1e-15:
            x = xn
            break
        x = xn
    sig = x * bn
    m, dm = mu_and_slope(sig, s_nodes, mu_nodes, slopes)
    if eps > 0.0:
        q = m / math.sqrt(sig * sig + ee)
    else:
        q = m / sig if sig > 0.0 else slopes[0]
    s1 = b1 / (1.0 + k1 * q)
    s2 = b2 / (1.0 + k2 * q)
    return -F3 * q * s1, -F3 * q * s2, s1, s2, math.hypot(s1, s2), it, nb, m


@numba.njit(cache=True, inline="always")
def advance(filt, rc, n, F2, F3, p, win, jw, iw):
    """End of step n, shared by both drivers: the structures' response to this step's force
    deviations from p.F_ref (p.kick added at n = 0) -> xi = xi^R - xi^W at step n + 1 (wheel:
    recursive modal filters ``filt``, the wheel moving by minus their sum [4.13]; rail: moving
    kernel ``rc`` [4.15]), then the stop rule's window ``win``.  Returns (xi2, xi3, jw, iw, reason)."""
    d2 = F2 - p.F_ref[1]
    d3 = F3 - p.F_ref[2]
    if n == 0:
        d2 += p.kick[0]
        d3 += p.kick[1]
    w2, w3 = filter_step(filt, d2, d3)
    r2, r3 = partitioned_step(rc, d2, d3)
    reason = 0
    if win.nw > 0:
        jw, iw, reason = record_window(F2, F3, n + 1, p.dt, win, jw, iw)
    return r2 + w2, r3 + w3, jw, iw, reason


@numba.njit(cache=True)
def run_point(filt, rc, p, tab, rec, win):
    """The time loop (table NORM, point-contact model), entirely in numba.  filt: the wheel's
    ModalFilter, rc: the rail's PartitionedConvolver (both advanced in place); p: LoopParams;
    tab: PointTables; rec: Record and win: Windows (written in place; rec.counters: Newton
    iterations, max per step, bisections, steps without contact).
    Returns (steps done, stop reason)."""
    dt = p.dt
    v = p.v
    slip_sign = p.slip_sign
    xi3_static = p.xi3_static
    gx = p.gx
    gy = p.gy
    eps = p.eps
    xi3_nodes = tab.xi3_nodes
    q_nodes = tab.q_nodes
    A1_nodes = tab.A1_nodes
    A2_nodes = tab.A2_nodes
    s_nodes = tab.s_nodes
    mu_nodes = tab.mu_nodes
    slopes = tab.slopes
    counters = rec.counters
    xi2 = 0.0
    xi3 = 0.0
    xi2_old = 0.0
    u1p = p.u_ref[0]
    u2p = p.u_ref[1]
    sig = 0.0
    sig_old = 0.0
    itop = np.argmax(mu_nodes)                      # full slip from the curve's peak on (a falling curve falls)
    mu_top = mu_nodes[itop]
    s_top = s_nodes[itop]
    row = np.zeros(8)
    ngx = gx.shape[0]
    ngy = gy.shape[0]
    spin = p.spin
    nsp = spin.shape[0]
    spin_l1 = p.spin_length[0]
    spin_l2 = p.spin_length[1]
    iw = 0
    jw = 0
    reason = 0
    done = 0
    for n in range(p.n_steps):
        spn = spin[n if n < nsp else nsp - 1]           # spin as equivalent creepages (module notes)
        gxn = gx[n if n < ngx else ngx - 1] + spin_l1 * spn
        gyn = gy[n if n < ngy else ngy - 1] + spin_l2 * spn
        app = xi3_static - xi3
        F3 = table_force(app, xi3_nodes, q_nodes)
        b1 = gxn * v - u1p / dt
        b2 = gyn * v - u2p / dt + slip_sign * (xi2 - xi2_old) / dt
        if F3 > 0.0:
            A1 = table_compliance(app, xi3_nodes, A1_nodes)
            A2 = table_compliance(app, xi3_nodes, A2_nodes)
            guess = 2.0 * sig - sig_old                 # |s| extrapolated from the last two steps
            sig_old = sig
            F1, F2, s1, s2, sig, it, nb, m = _point_contact(b1, b2, A1 / dt, A2 / dt, F3, s_nodes, mu_nodes,
                                                            slopes, eps, guess)
            u1p = A1 * F1
            u2p = A2 * F2
            counters[0] += it
            if it > counters[1]:
                counters[1] = it
            counters[2] += nb
            state = 2.0 if (m >= FULL_SLIP * mu_top or sig >= s_top) else 1.0
        else:                                   # loss of contact: no force, deformation released
            F1 = 0.0
            F2 = 0.0
            F3 = 0.0
            s1 = b1
            s2 = b2
            u1p = 0.0
            u2p = 0.0
            state = 0.0
            counters[3] += 1
        row[0] = F1
        row[1] = F2
        row[2] = F3
        row[3] = s1
        row[4] = s2
        row[5] = xi2
        row[6] = xi3
        row[7] = state
        store(n, row, rec)
        xi2_old = xi2
        xi2, xi3, jw, iw, reason = advance(filt, rc, n, F2, F3, p, win, jw, iw)
        done = n + 1
        if reason != 0:
            break
    return done, reason


