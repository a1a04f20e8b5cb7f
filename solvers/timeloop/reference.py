"""The reference driver of the time loop (notes in ``solvers.timeloop.interaction``): the same loop as
``kernel.run_point`` in Python, with per-step NORM, the literal compliance [4.32]-[4.35] and/or
Kalker's transient TANG, built from the same njit blocks."""
from __future__ import annotations

import warnings

import numpy as np

from solvers.contact.compliance import contact_compliance, table_compliance
from solvers.contact.friction import mu_rf
from solvers.contact.norm import NormTable, norm, table_force, table_pressure
from solvers.contact.tang import tang_steady, tang_transient
from solvers.contact.tang.operator import tangential_operator
from solvers.contact.tang.state import History, TangentialContact
from solvers.timeloop.kalker import kalker_steps, slip_summary
from solvers.timeloop.inputs import FULL_SLIP, KALKER_TOL, ContactModel, LoopParams
from solvers.timeloop.kernel import advance, point_contact
from solvers.timeloop.result import Record, store
from solvers.timeloop.stop import Windows


def _check(c: ContactModel, p: LoopParams, tangential: str, normal: str, compliance: str):
    """The NORM table with pressures (None if not needed); errors if c lacks what the models need."""
    if normal == "norm" or tangential == "kalker" or compliance == "exact":
        if c.gap is None or c.dx is None or c.dy is None:
            raise ValueError("the reference drivers need the contact's gap, dx and dy")
        if abs(c.dx - p.v * p.dt) > 1e-9 * c.dx:
            raise ValueError(f"the contact grid's dx = {c.dx} must be v dt = {p.v * p.dt} (SPEC 4.1)")
    if tangential == "kalker" or compliance == "exact":
        if c.pressure_nodes is None or c.F3_nodes is None:
            raise ValueError("Kalker's TANG and the exact compliance need the table's pressure fields")
        return NormTable(c.xi3_nodes, c.F3_nodes, c.q_nodes, c.pressure_nodes, c.pressure_nodes > 0)
    return None


def run_reference(filt, rc, p: LoopParams, c: ContactModel, rec: Record, win: Windows, *, tangential: str,
                  normal: str, compliance: str, start: str):
    """The time loop in Python (normal 'table' | 'norm', compliance 'table' | 'exact', tangential
    'point' | 'kalker'; start 'steady' | 'static'), writing into ``rec`` and ``win`` like
    ``run_point``.  Returns (steps done, reason, F_ref): with Kalker's TANG and start='steady' the
    reference forces are TANG's steady ones instead of p.F_ref."""
    table = _check(c, p, tangential, normal, compliance)
    n_steps, dt, v, xi3_static, slip_sign, eps, gx, gy, F_ref, u_ref, _, spin, L = p
    counters = rec.counters
    E, nu = c.E, c.nu
    itop = int(np.argmax(c.mu_nodes))                     # full slip from the curve's peak on
    mu_top, s_top = c.mu_nodes[itop], c.s_nodes[itop]
    tang_state = None
    friction = c.mu if c.law is None else c.law          # Kalker's TANG: Coulomb mu or the local law
    if tangential == "kalker" and start == "steady":
        p0 = table_pressure(table, xi3_static) if normal == "table" else norm(c.gap, xi3_static, c.dx, c.dy, E, nu).p
        tang_state = tang_steady(p0, c.dx, c.dy, v, friction, gamma_x=gx[0], gamma_y=gy[0], spin=spin[0], E=E, nu=nu,
                                 full_output=False, tol=KALKER_TOL)
        F_ref = np.array([tang_state.F1, tang_state.F2, F_ref[2]])
        p = p._replace(F_ref=F_ref)
    xi2 = xi3 = xi2_old = 0.0
    u1p, u2p = float(u_ref[0]), float(u_ref[1])
    sig = 0.0
    F_prev = (float(F_ref[0]), float(F_ref[1]))
    nsol = None
    row = np.zeros(8)
    iw = jw = reason = done = 0
    compiled = tangential == "kalker" and normal == "table" and c.law is None   # (a law: TANG's Python step)
    n = 0
    while n < n_steps:
        if compiled and tang_state is not None and tang_state.history is not None \
                and tang_state.window == tang_state.history.window:       # steps in numba while they can
            n_new, loop, reason, tang, last, bad = kalker_steps(
                n, filt, rc, p, rec, win, (xi2, xi3, xi2_old, jw, iw), table[:4], (c.dx, c.dy, c.mu, KALKER_TOL),
                _fields(tang_state), _operator(tang_state, c), row)
            if bad:
                warnings.warn(f"TANG: stick/slip sets not converged in {bad} steps", RuntimeWarning)
            if n_new > n:
                xi2, xi3, xi2_old, jw, iw = loop
                tang_state = _solution(tang, last)
                n = done = n_new
                if reason != 0 or n == n_steps:
                    break
        gxn = gx[min(n, len(gx) - 1)]
        gyn = gy[min(n, len(gy) - 1)]
        spn = spin[min(n, len(spin) - 1)]
        app = xi3_static - xi3
        p3 = None
        if normal == "table":
            F3 = table_force(app, c.xi3_nodes, c.q_nodes)
        else:
            nsol = norm(c.gap, app, c.dx, c.dy, E, nu, warm=nsol if (nsol is not None and nsol.F3 > 0) else None)
            F3, p3 = nsol.F3, nsol.p
        dxi2 = slip_sign * (xi2 - xi2_old) / dt
        if F3 > 0.0:
            if tangential == "point":
                if compliance == "table":
                    A1 = table_compliance(app, c.xi3_nodes, c.A1_nodes)
                    A2 = table_compliance(app, c.xi3_nodes, c.A2_nodes)
                else:
                    if p3 is None:
                        p3 = table_pressure(table, app)
                    A1, A2 = contact_compliance(p3, F_prev, c.dx, c.dy, E, nu)
                b1 = (gxn + L[0] * spn) * v - u1p / dt              # spin as equivalent creepages
                b2 = (gyn + L[1] * spn) * v - u2p / dt + dxi2
                F1, F2, s1, s2, sig, it, nb = point_contact(b1, b2, A1 / dt, A2 / dt, F3, c.s_nodes, c.mu_nodes,
                                                            c.slopes, eps, sig)
                u1p, u2p = A1 * F1, A2 * F2
                counters[0] += it
                counters[1] = max(counters[1], it)
                counters[2] += nb
                m = mu_rf(sig, c.s_nodes, c.mu_nodes, c.slopes)
                state = 2.0 if (m >= FULL_SLIP * mu_top or sig >= s_top) else 1.0
            else:
                if p3 is None:
                    p3 = table_pressure(table, app)
                tang_state = tang_transient(p3, c.dx, c.dy, v, friction, gamma_x=gxn, gamma_y=gyn + dxi2 / v,
                                            spin=spn, E=E, nu=nu, state=tang_state, full_output=False, tol=KALKER_TOL)
                F1, F2 = tang_state.F1, tang_state.F2
                s1, s2, state = slip_summary(p3, tang_state.s1, tang_state.s2, tang_state.stick)
                counters[0] += tang_state.iterations
                counters[1] = max(counters[1], tang_state.iterations)
            F_prev = (F1, F2)
        else:
            F1 = F2 = F3 = 0.0
            s1, s2 = (gxn + L[0] * spn) * v - u1p / dt, (gyn + L[1] * spn) * v - u2p / dt + dxi2
            u1p = u2p = 0.0
            tang_state = None
            state = 0.0
            counters[3] += 1
        row[:] = (F1, F2, F3, s1, s2, xi2, xi3, state)
        store(n, row, rec)
        xi2_old = xi2
        xi2, xi3, jw, iw, reason = advance(filt, rc, n, float(F2), float(F3), p, win, jw, iw)
        n = done = n + 1
        if reason != 0:
            break
    return done, reason, F_ref


def _fields(t: TangentialContact):
    """A transient solution as ``kalker_steps`` takes it."""
    h = t.history
    return (t.P, np.stack([t.s1, t.s2]), t.stick, t.slip, t.U, t.u_ahead, h.window, h.d, h.n, h.order, h.pred)


def _solution(f, last) -> TangentialContact:
    """``kalker_steps``' last solution as a TangentialContact."""
    P, S, st, sl, U, ahead, window, d, n, order, pred = f
    F1, F2, newton, krylov, converged = last
    return TangentialContact(P[0], P[1], st, sl, S[0], S[1], U[0], U[1], F1, F2, newton, converged, krylov, ahead,
                             History(d, n, order, window, pred), window, P, U)


def _operator(t: TangentialContact, c: ContactModel):
    """The arrays of the operator of a transient solution's window."""
    i0, i1, j0, j1 = t.history.window
    op = tangential_operator((i1 - i0 + 1, j1 - j0 + 1), c.dx, c.dy, c.E, c.nu)
    return op.buffers.arrays, op.hat, op.symbol, op.inv, op.a0, op.scale
