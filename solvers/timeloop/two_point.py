"""The two-point time loop (issue 26): two contact patches between one wheel and one rail -- tread
and flange, or two tread zones -- each with its own normal table, tangential compliance and
friction curve, coupled through the structures (SPEC 3.5 per point, thesis ch. 7's multi-point
contact as future work).

Structures at two points.  The wheel's modal filters take the modal force of both patches,
P_r = phi_r(a) . dF_a + phi_r(b) . dF_b, and return the displacement at both (phi(a), phi(b):
the shapes at the two points, each in its own contact frame): the modal sum gives the point and
the cross receptances exactly.  The rail's moving kernel at two head points is a 4 x 4 kernel of
2 x 2 blocks g_pq (response at p to a force at q), convolved together by the exact frequency-domain
MIMO convolver (``solvers.timeloop.mimo_partitioned``: the one-point loop's overlap-save partitions, a
vectorised head, one FFT per point's forces and one per point's displacements, the second point's
forces skipped while they are zero).  xi_p = xi^R_p - xi^W_p as in the one-point loop.

Each point solves the one-point contact of [4.16]-[4.31] (``kernel._point_contact``) with its own
approach (static approach of the point minus its relative displacement along its own normal),
creepages and tables.  Point a is the one-point loop's point: when point b carries no load (its
approach never reaches its table), every force deviation of b is zero, its contributions to the
filters and convolutions are exact zeros and point a's records are the one-point loop's bit for
bit (the MIMO convolver gathers g_aa's head as ``solvers.timeloop.partitioned`` does until b's first force;
tests/interaction/test_two_point.py).
"""
from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np

from solvers.contact.compliance import table_compliance
from solvers.contact.norm import table_force
from solvers.wheel.modal_filter import FilterState, modal_filter
from solvers.timeloop.mimo_partitioned import mimo_step
from solvers.timeloop.inputs import FULL_SLIP
from solvers.timeloop.kernel import _point_contact
from solvers.timeloop.result import store
from solvers.timeloop.stop import record_window


class TwoPointFilter(NamedTuple):
    """The wheel's recursive modal filters (``solvers.wheel.modal_filter.ModalFilter``) with inputs and
    outputs at two points: w_in, w_out (M, 4) = (a2, a3, b2, b3); u_coef (10, M0) = Re z, Im z,
    w_in (4 rows), w_out (4 rows) of the kind-0 modes; state advanced IN PLACE."""
    kind: np.ndarray
    z: np.ndarray
    p2: np.ndarray
    w_in: np.ndarray
    w_out: np.ndarray
    u_coef: np.ndarray
    over: np.ndarray
    state: FilterState


def two_point_filter(dt: float, f_r, modal_mass, zeta, phi_a, phi_b) -> TwoPointFilter:
    """The modal filters of ``modal_filter(dt, f_r, modal_mass, zeta, phi)`` for the shapes
    phi_a, phi_b (M, 2) at the two points; at rest."""
    a = modal_filter(dt, f_r, modal_mass, zeta, phi_a)
    b = modal_filter(dt, f_r, modal_mass, zeta, phi_b)
    uc = np.ascontiguousarray(np.vstack([a.u_coef[0:4], b.u_coef[2:4], a.u_coef[4:6], b.u_coef[4:6]]))
    return TwoPointFilter(a.kind, a.z, a.p2, np.ascontiguousarray(np.hstack([a.w_in, b.w_in])),
                          np.ascontiguousarray(np.hstack([a.w_out, b.w_out])), uc, a.over, a.state)


@numba.njit(cache=True)
def filter_step2(filt, F2a, F3a, F2b, F3b):
    """njit: push the forces of step n at both points into the modal filters; return the
    displacements (xi2a, xi3a, xi2b, xi3b) at step n + 1 (``solvers.wheel.modal_filter.filter_step``
    with the second point's terms added after the first's)."""
    kind, z, p2, w_in, w_out, uc, over, state = filt
    q, a, us = state
    x2 = 0.0
    x3 = 0.0
    y2 = 0.0
    y3 = 0.0
    for j in range(uc.shape[1]):
        ur = us[0, j] + uc[2, j] * F2a + uc[3, j] * F3a + uc[4, j] * F2b + uc[5, j] * F3b
        ui = us[1, j]
        nr = uc[0, j] * ur - uc[1, j] * ui
        ni = uc[0, j] * ui + uc[1, j] * ur
        us[0, j] = nr
        us[1, j] = ni
        x2 += uc[6, j] * ni
        x3 += uc[7, j] * ni
        y2 += uc[8, j] * ni
        y3 += uc[9, j] * ni
    for i in range(over.shape[0]):
        r = over[i]
        P = w_in[r, 0] * F2a + w_in[r, 1] * F3a + w_in[r, 2] * F2b + w_in[r, 3] * F3b
        v = P + z[r] * q[r] + a[r]
        a[r] = p2[r] * (a[r] + P)
        q[r] = v
        y = v.real
        x2 += w_out[r, 0] * y
        x3 += w_out[r, 1] * y
        y2 += w_out[r, 2] * y
        y3 += w_out[r, 3] * y
    return x2, x3, y2, y3


@numba.njit(cache=True, inline="always")
def contact_step(gxn, gyn, v, dt, slip_sign, eps, app, db2, u1p, u2p, sig, sig_old, xi3_nodes, q_nodes, A1_nodes,
                 A2_nodes, s_nodes, mu_nodes, slopes, mu_top, counters):
    """One point's contact (the one-point loop's step, ``kernel.run_point``, same arithmetic) at
    approach ``app`` with the structural slip term db2 = slip_sign (xi2 - xi2_old) / dt.
    Returns (F1, F2, F3, s1, s2, state, u1p, u2p, sig, sig_old): the forces, slips and contact
    state of the step and the point's state for the next."""
    F3 = table_force(app, xi3_nodes, q_nodes)
    b1 = gxn * v - u1p / dt
    b2 = gyn * v - u2p / dt + db2
    if F3 > 0.0:
        A1 = table_compliance(app, xi3_nodes, A1_nodes)
        A2 = table_compliance(app, xi3_nodes, A2_nodes)
        guess = 2.0 * sig - sig_old
        sig_old = sig
        F1, F2, s1, s2, sig, it, nb, m = _point_contact(b1, b2, A1 / dt, A2 / dt, F3, s_nodes, mu_nodes,
                                                        slopes, eps, guess)
        u1p = A1 * F1
        u2p = A2 * F2
        counters[0] += it
        if it > counters[1]:
            counters[1] = it
        counters[2] += nb
        state = 2.0 if m >= FULL_SLIP * mu_top else 1.0
    else:
        F1 = 0.0
        F2 = 0.0
        F3 = 0.0
        s1 = b1
        s2 = b2
        u1p = 0.0
        u2p = 0.0
        state = 0.0
        counters[3] += 1
    return F1, F2, F3, s1, s2, state, u1p, u2p, sig, sig_old


@numba.njit(cache=True, inline="always")
def _row(row, F1, F2, F3, s1, s2, xi2, xi3, state):
    row[0] = F1
    row[1] = F2
    row[2] = F3
    row[3] = s1
    row[4] = s2
    row[5] = xi2
    row[6] = xi3
    row[7] = state


@numba.njit(cache=True)
def run_two_points(filt, r_x, pa, pb, tab_a, tab_b, rec_a, rec_b, win):
    """The two-point time loop (module notes), entirely in numba.  filt: TwoPointFilter; r_x:
    MimoConvolver of the rail's blocks g_pq (response at p to a force at q; outputs and inputs
    0 = a, 1 = b); pa, pb:
    LoopParams of the points (n_steps, dt, v of pa rule; the kick of each point is its own);
    tab_a, tab_b: PointTables; rec_a, rec_b: Records (written in place); win: Windows of the
    stop rule on the summed forces F2a + F2b, F3a + F3b.  Returns (steps done, stop reason)."""
    dt = pa.dt
    v = pa.v
    ss_a = pa.slip_sign
    ss_b = pb.slip_sign
    eps_a = pa.eps
    eps_b = pb.eps
    xs_a = pa.xi3_static
    xs_b = pb.xi3_static
    gxa = pa.gx
    gya = pa.gy
    gxb = pb.gx
    gyb = pb.gy
    xa_n, qa_n, A1a, A2a, sa_n, mua, sla = tab_a
    xb_n, qb_n, A1b, A2b, sb_n, mub, slb = tab_b
    top_a = mua[mua.shape[0] - 1]
    top_b = mub[mub.shape[0] - 1]
    ca = rec_a.counters
    cb = rec_b.counters
    xi2a = 0.0
    xi3a = 0.0
    xi2a_old = 0.0
    u1a = pa.u_ref[0]
    u2a = pa.u_ref[1]
    sga = 0.0
    sga_old = 0.0
    xi2b = 0.0
    xi3b = 0.0
    xi2b_old = 0.0
    u1b = pb.u_ref[0]
    u2b = pb.u_ref[1]
    sgb = 0.0
    sgb_old = 0.0
    row_a = np.zeros(8)
    row_b = np.zeros(8)
    nga = gxa.shape[0]
    nya = gya.shape[0]
    ngb = gxb.shape[0]
    nyb = gyb.shape[0]
    iw = 0
    jw = 0
    reason = 0
    done = 0
    for n in range(pa.n_steps):
        F1a, F2a, F3a, s1a, s2a, sta, u1a, u2a, sga, sga_old = contact_step(
            gxa[n if n < nga else nga - 1], gya[n if n < nya else nya - 1], v, dt, ss_a, eps_a, xs_a - xi3a,
            ss_a * (xi2a - xi2a_old) / dt, u1a, u2a, sga, sga_old, xa_n, qa_n, A1a, A2a, sa_n, mua, sla, top_a, ca)
        F1b, F2b, F3b, s1b, s2b, stb, u1b, u2b, sgb, sgb_old = contact_step(
            gxb[n if n < ngb else ngb - 1], gyb[n if n < nyb else nyb - 1], v, dt, ss_b, eps_b, xs_b - xi3b,
            ss_b * (xi2b - xi2b_old) / dt, u1b, u2b, sgb, sgb_old, xb_n, qb_n, A1b, A2b, sb_n, mub, slb, top_b, cb)
        _row(row_a, F1a, F2a, F3a, s1a, s2a, xi2a, xi3a, sta)
        _row(row_b, F1b, F2b, F3b, s1b, s2b, xi2b, xi3b, stb)
        store(n, row_a, rec_a)
        store(n, row_b, rec_b)
        xi2a_old = xi2a
        xi2b_old = xi2b
        d2a = F2a - pa.F_ref[1]
        d3a = F3a - pa.F_ref[2]
        d2b = F2b - pb.F_ref[1]
        d3b = F3b - pb.F_ref[2]
        if n == 0:
            d2a += pa.kick[0]
            d3a += pa.kick[1]
            d2b += pb.kick[0]
            d3b += pb.kick[1]
        w2a, w3a, w2b, w3b = filter_step2(filt, d2a, d3a, d2b, d3b)
        qa2, qa3, qb2, qb3 = mimo_step(r_x, d2a, d3a, d2b, d3b)
        xi2a = qa2 + w2a
        xi3a = qa3 + w3a
        xi2b = qb2 + w2b
        xi3b = qb3 + w3b
        if win.nw > 0:
            jw, iw, reason = record_window(F2a + F2b, F3a + F3b, n + 1, dt, win, jw, iw)
        done = n + 1
        if reason != 0:
            break
    return done, reason
