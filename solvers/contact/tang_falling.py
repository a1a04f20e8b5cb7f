"""Slip-velocity dependent friction in steady TANG: the traction bound g = mu(|s|) p3 with
the local slip speed |s| of each element (a falling or rising law of
``solvers.contact.friction_laws``).

CONTACT's treatment (Vollebregt, User guide for CONTACT, sec. 'Slip velocity dependent
friction' and the iteration parameters INISLP, OMGSLP; source m_stang.f90; Vollebregt 2014,
Wear 314, for measured creep curves): an outer iteration on the slip speed around the
Coulomb solver.  Given the slip speeds of the previous iterate, each element's bound is
g = mu(|s|) p3 (stick elements: |s| = 0, the static coefficient mu(0)); the Coulomb problem
with these bounds is solved (here: Kalker's active-set Newton method of ``tang_newton``,
warm-started from the previous iterate); its slip speeds give the next bounds.  At the fixed
point every slip element carries |p| = mu(|s|) p3 opposite to its slip and every stick element
|p| <= mu(0) p3: Coulomb's law with the local coefficient of the local slip speed.  The start
follows CONTACT's INISLP = 0 (the previous case's slip, here a warm start's; without one the
slip is approximated from below, all elements at mu(0), INISLP > 0).  Where the fixed-point map
does not contract (a steep falling branch), the update of the bounds is relaxed (CONTACT's
OMGSLP; here halved whenever the change grows).  The friction memory of CONTACT (MEMDST) is
not modelled: MEMDST = 0, the instantaneous law.

Stops when the largest change of the bounds is below ``tol_mu`` times the largest bound.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .friction_laws import FrictionLaw
from .tang_newton import CoulombResult, solve_coulomb
from .tang_operator import TangentialOperator

TOL_MU = 1e-7               # bound change (relative to the largest bound) at the fixed point
MAX_OUTER = 400


class FallingResult(NamedTuple):
    result: CoulombResult   # the last Coulomb solve (its bounds are the converged ones)
    g: np.ndarray           # (N,) the bounds mu(|s|) p3 [Pa]
    outer: int              # outer iterations
    converged: bool


def slip_speed(res: CoulombResult, dt: float) -> np.ndarray:
    """|s| [m/s] per element (0 on stick) from a Coulomb solve's slip per step."""
    v = np.hypot(res.s[:, 0], res.s[:, 1]) / dt
    v[res.stick] = 0.0
    return v


def solve_falling(op: TangentialOperator, ix, iy, r, p3, law: FrictionLaw, dt, p, stick, *, speed=None,
                  tol=1e-8, tol_mu=TOL_MU, warm=False, max_outer=MAX_OUTER) -> FallingResult:
    """Steady TANG with the local coefficient mu(|s|) of `law` on the contact elements (ix,
    iy) of the operator's grid; r, p (N, 2), p3 (N,) [Pa], dt = dx / v [s]; `speed` (N,) the
    start's slip speeds [m/s] (None: zero, all at mu(0)); p, stick the start (as in
    ``solve_coulomb``)."""
    p3 = np.asarray(p3, dtype=float)
    sv = np.zeros(p3.shape) if speed is None else np.asarray(speed, dtype=float)
    g = law.mu(sv) * p3
    omega, last = 1.0, np.inf
    total_newton = total_krylov = 0
    res = None
    converged = False
    for outer in range(1, max_outer + 1):
        res = solve_coulomb(op, ix, iy, r, g, p, stick, tol=tol, warm=warm or outer > 1)
        total_newton += res.newton
        total_krylov += res.krylov
        g_new = law.mu(slip_speed(res, dt)) * p3
        change = float(np.abs(g_new - g).max(initial=0.0))
        level = float(g.max(initial=0.0))
        if change <= tol_mu * level and res.converged:
            converged = True
            break
        if change > last:           # not contracting: relax the bounds' update (CONTACT's OMGSLP)
            omega = max(0.5 * omega, 1.0 / 64.0)
        last = change
        g = g + omega * (g_new - g)
        p, stick = res.p, res.stick
    res = res._replace(newton=total_newton, krylov=total_krylov, converged=converged)
    return FallingResult(res, g, outer, converged)
