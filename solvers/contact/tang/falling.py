"""Slip-velocity dependent friction in TANG: the traction bound g = mu(|s|) p3 with the local
slip speed |s| of each element (a falling or rising law of ``solvers.contact.friction_laws``),
steady (``solve_falling``) and per transient step (``transient_falling``).

CONTACT's treatment (Vollebregt, User guide for CONTACT, sec. 'Slip velocity dependent
friction' and the iteration parameters INISLP, OMGSLP; source m_stang.f90; Vollebregt 2014,
Wear 314, for measured creep curves): an outer iteration on the slip speed around the
Coulomb solver.  Given the slip speeds of the previous iterate, each element's bound is
g = mu(|s|) p3 (stick elements: |s| = 0, the static coefficient mu(0)); the Coulomb problem
with these bounds is solved (here: Kalker's active-set Newton method of ``tang.newton``,
warm-started from the previous iterate); its slip speeds give the next bounds.  At the fixed
point every slip element carries |p| = mu(|s|) p3 opposite to its slip and every stick element
|p| <= mu(0) p3: Coulomb's law with the local coefficient of the local slip speed.  The start
follows CONTACT's INISLP = 0 (the previous case's slip, here a warm start's; without one the
slip is approximated from below, all elements at mu(0), INISLP > 0).  Where the fixed-point map
does not contract (a steep falling branch), the update of the bounds is relaxed (CONTACT's
OMGSLP; here halved whenever the change grows).  With the law's friction memory (memdst =
d_c > 0, CONTACT's MEMDST; user guide 'Friction memory', eq. dmu_dt) steady TANG uses CONTACT's
steady form of mu' = -max(|s|, s_0)/d_c (mu - mu_s(|s|)): along each grid line from the leading
edge (mu = mu(0) there), mu_I = theta mu_(I+dx) + (1 - theta) mu_s(|s_I|), theta = d_c / (d_c +
dt max(|s_I|, s_0)) (m_stang.f90).  Without it (d_c = 0) the coefficient jumps where an element
enters the slip area; for very steep laws (mu falling by much of itself within a slip speed
comparable to the rigid slip) the iteration may then not converge (RuntimeWarning, as CONTACT's
MAXIN stop; the discrete problem can have several solutions, Vollebregt and Schuttelaars, JSV 331,
2012), and the memory regularises it.  Transient TANG takes d_c = 0 only (the instantaneous law;
transient rolling at constant creepage settles on the steady solution, tests/contact/test_tang_law.py).

Stops when the largest change of the bounds is below ``TOL_MU`` times the largest bound (and the
last Coulomb solve had tolerance ``tol``; earlier ones are inexact, a tenth of the last change).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from solvers.contact.friction_laws import FrictionLaw
from solvers.contact.tang.newton import CoulombResult, solve_coulomb
from solvers.contact.tang.operator import TangentialOperator

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


def coefficients(law: FrictionLaw, speed, ix, iy, dt) -> np.ndarray:
    """mu per element (ix, iy) at slip speeds `speed` [m/s]: the law's mu_s(|s|), or with its
    friction memory (d_c > 0) the steady relaxation along x from the leading edge (module notes)."""
    mus = law.mu(speed)
    d_c, s_0 = law.memory
    if d_c <= 0.0:
        return mus
    nx, ny = int(ix.max()) + 1, int(iy.max()) + 1
    mu0 = law.mu_static
    MS, SV = np.full((nx, ny), mu0), np.zeros((nx, ny))
    MS[ix, iy], SV[ix, iy] = mus, speed
    theta = d_c / (d_c + dt * np.maximum(SV, s_0))
    M = np.empty((nx, ny))
    prev = np.full(ny, mu0)
    for i in range(nx - 1, -1, -1):          # the leading edge is at high x
        prev = theta[i] * prev + (1.0 - theta[i]) * MS[i]
        M[i] = prev
    return M[ix, iy]


def _relaxation(omega, change, last):
    """The update's relaxation (CONTACT's OMGSLP, reduced where elements alternate): halved when
    the bounds' change grew by half (an oscillation), grown back towards 1 while it contracts."""
    if change > 1.5 * last:
        return max(0.5 * omega, 1.0 / 64.0)
    if change < 0.5 * last:
        return min(1.0, 1.5 * omega)
    return omega


def solve_falling(op: TangentialOperator, ix, iy, r, p3, law: FrictionLaw, dt, p, stick, *, speed=None,
                  tol=1e-8, warm=False) -> FallingResult:
    """Steady TANG with the local coefficient mu(|s|) of `law` on the contact elements (ix,
    iy) of the operator's grid; r, p (N, 2), p3 (N,) [Pa], dt = dx / v [s]; `speed` (N,) the
    start's slip speeds [m/s] (None: zero, all at mu(0)); p, stick the start (as in
    ``solve_coulomb``)."""
    p3 = np.asarray(p3, dtype=float)
    sv = np.zeros(p3.shape) if speed is None else np.asarray(speed, dtype=float)
    g = coefficients(law, sv, ix, iy, dt) * p3
    omega, last, level = 1.0, np.inf, float(g.max(initial=0.0))
    total_newton = total_krylov = 0
    res = None
    converged = False
    for outer in range(1, MAX_OUTER + 1):
        # inexact inner solves while the bounds still move (a tenth of the last change), `tol` at the end
        tol_k = min(1e-3, max(tol, 0.1 * last / max(level, 1e-300)))
        res = solve_coulomb(op, ix, iy, r, g, p, stick, tol=tol_k, warm=warm or outer > 1)
        total_newton += res.newton
        total_krylov += res.krylov
        g_new = coefficients(law, slip_speed(res, dt), ix, iy, dt) * p3
        change = float(np.abs(g_new - g).max(initial=0.0))
        level = float(g.max(initial=0.0))
        if change <= TOL_MU * level and res.converged and tol_k <= tol:
            converged = True
            break
        omega = _relaxation(omega, change, last)
        last = change
        g = g + omega * (g_new - g)
        p, stick = res.p, res.stick
    res = res._replace(newton=total_newton, krylov=total_krylov, converged=converged)
    return FallingResult(res, g, outer, converged)


def transient_falling(step, law: FrictionLaw, p3, ix, iy, speed=None):
    """One transient step with the local coefficient mu(|s|) of `law`: the same outer iteration
    around ``step(mu_el)`` (``tang.pcg.transient_step_law`` with the problem bound, mu_el (N,) the
    elements' coefficients), starting from the previous step's slip speeds `speed` (N,) [m/s]
    (None: zero).  Returns transient_step's tuple with the Newton and CG steps of all outer
    iterations and ``converged`` of the last solve and the bounds."""
    p3 = np.asarray(p3, dtype=float)
    sv = np.zeros(p3.shape) if speed is None else np.asarray(speed, dtype=float)
    g = law.mu(sv) * p3
    omega, last = 1.0, np.inf
    newton = krylov = 0
    converged = False
    for _ in range(MAX_OUTER):
        out = step(g / p3)
        newton, krylov = newton + out[8], krylov + out[9]
        S, stick = out[1], out[2]
        sv = np.hypot(S[0][ix, iy], S[1][ix, iy])
        sv[stick[ix, iy]] = 0.0
        g_new = law.mu(sv) * p3
        change = float(np.abs(g_new - g).max(initial=0.0))
        if change <= TOL_MU * float(g.max(initial=0.0)):
            converged = bool(out[10])
            break
        omega = _relaxation(omega, change, last)
        last = change
        g = g + omega * (g_new - g)
    return out[:8] + (newton, krylov, converged) + out[11:]
