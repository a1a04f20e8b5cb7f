"""Wheel/rail interaction in the time domain: the squeal time stepper (SPEC 3.5,
4.1-4.4, 6; thesis [4.13]-[4.37]).

Per time step t_d = n dt the wheel and rail displacements follow from the PAST
contact forces (Green's functions without the instantaneous term g(0)), the
normal force from the normal contact model at the resulting approach, and the
two tangential forces from the tangential point-contact model (or, as the
reference, from Kalker's transient TANG).  The contact then moves one element
dx = v dt along the rail.

Conventions (SPEC 2, 3.5)
-------------------------
Contact frame: 1 longitudinal, 2 lateral (+ toward the field side), 3 vertical
(+ toward the ground).  F = (F1, F2, F3) act on the RAIL; the wheel receives -F.
Kernel layout [..., i, j], index 0 = direction 2, 1 = direction 3 (as in
``solvers.green``).  Structural displacements are deviations from the reference
(static) state and are convolved with the force DEVIATIONS dF = F - F_ref:

    wheel  xi^W[n] = - sum_{k>=1} g^W[k] dF[n-k]      [4.13]  (recursive modal filters)
    rail   xi^R[n] = + sum_{k>=1} g^R_mov[k] dF[n-k]  [4.15]  (partitioned FFT convolution, exact)
    xi[n]  = xi^R[n] - xi^W[n]   (displacement of the rail relative to the wheel)

Normal kinematics [4.16], [4.19]: d = xi3 + z^R - z^W + u3 with xi3 = xi3^R - xi3^W
grows when the rail moves away from the wheel (toward the ground) or the wheel
moves up.  The NORM table is parametrised by the approach (rigid penetration,
positive into contact, ``solvers.contact.norm``), so

    approach[n] = xi3_static - xi[n, 1]     (total = static + dynamic part)

and F3[n] = F3_table(approach[n]).  A rail moving down under +F3 lowers the
approach (restoring), the wheel pushed up by -F3 too: the normal contact is a
stiffening spring between the two structures.  approach <= first table node
(no pressure) is loss of contact: F = 0 exactly, the tangential deformation is
released (u = 0) and contact is found again when the approach turns positive.

Tangential kinematics [4.25]-[4.31]: slip of the rail relative to the wheel
(Kalker's convention, as in ``solvers.contact.tang``: u = u(rail) - u(wheel),
traction on the rail, F_tau = -mu F3 s_tau / s)

    s1 = (gamma_x + (u1[n] - u1[n-1]) / dx) v
    s2 = (gamma_y + (u2[n] - u2[n-1]) / dx + sign * (xi2[n] - xi2[n-1]) / dx) v
    u_tau = A_tau F_tau,   F_tau = -mu_RF(s) F3 s_tau / s,   s = |(s1, s2)|.

``sign`` (argument ``slip_sign``) is +1 by default.  The thesis prints [4.30]
with a MINUS sign in front of the structural term and the SPEC repeats it;
with xi2 = xi2^R - xi2^W (SPEC 4.2) and u = u(rail) - u(wheel) entering with
+ (as it must for the contact spring to relax: s = w + A dF/dt), consistency
demands the same sign for both, because the slip is the relative velocity of
the rail's and the wheel's surface particles, and the structural motion moves
those particles exactly as the contact deformation does.  The energy balance
decides it: the power the contact forces put into the structures is
F2 d(xi2)/dt (rail +F2, wheel -F2), and with s2 = w2 + ... + d(xi2)/dt the
friction work -F2 s2 >= 0 is dissipated, while with the printed minus sign a
RISING friction curve (the micro-slip branch of mu_RF, slope mu'(0) F3 ~
6e5 N s/m here) acts as a NEGATIVE damper on the lateral wheel/rail motion:
every lightly damped axial wheel mode is then unstable in micro-slip, i.e. at
the smallest creepages, contrary to the thesis' results (squeal needs larger
creepage).  slip_sign = -1 reproduces the printed equation
(docs/validation/60_interaction.md compares).

Tangential compliance (SPEC 4.3, [4.32]-[4.35]): A_tau(approach) from the
contact stage's table (unit-force limit of [4.32]-[4.35]: full-slip traction
shaped like the pressure, 2/3 of the peak half-space deformation; without the
cross influence A_12 the compliance depends on the pressure SHAPE only, i.e.
on the approach), updated every step.  The Python reference driver can
evaluate [4.32]-[4.35] literally instead (``compliance='exact'``: previous
step's forces, current pressure, with the cross term).

The tangential equations: with b_tau = gamma_tau v - u_tau[n-1]/dt (+ the
structural term for tau = 2) and c_tau = A_tau/dt, s_tau = b_tau + c_tau F_tau,
so with k_tau = c_tau F3 and m(sigma) = mu_RF(sigma)/sqrt(sigma^2 + eps^2)

    s_tau = b_tau / (1 + k_tau m(sigma)),   F_tau = -F3 m(sigma) s_tau,

and sigma = |s| is the root in (0, |b|] of the scalar equation

    H(sigma) = 1/sqrt(sum_tau b_tau^2 / D_tau(sigma)^2) - 1 = 0,
    D_tau(sigma) = sigma + k_tau mu_RF(sigma) sigma/sqrt(sigma^2 + eps^2).

D_tau is strictly increasing (mu_RF is non-decreasing), so H rises strictly
from -1 (sigma -> 0) to >= 0 (sigma = |b|): a unique root, bracketed, found by
Newton's method safeguarded by bisection (warm-started with the previous
step's sigma; 2-5 iterations).  For c_1 = c_2 H is (sigma + k mu_RF(sigma))/|b|
- 1, Newton on a monotone, nearly linear function.  The direction s_tau/s needs
no regularisation for the regularised friction curves: mu_RF(0) = 0 with a
finite slope, so F = -F3 (mu_RF(s)/s) s is smooth through s = 0 (eps = 0, the
default for such curves); for a curve with mu(0) > 0 (pure Coulomb) the
direction is s_tau/sqrt(s^2 + eps^2) with eps = 1e-9 m/s, a viscous
regularisation below eps.  |b| = 0 gives s = 0 and F = 0 exactly (no NaN).

Reference state and start (SPEC 3.5 "start from static equilibrium")
---------------------------------------------------------------------
``start='steady'`` (default): the reference state is the steady rolling
equilibrium under the preload: F_ref = (F1s, F2s, F_L3) with
F_tau,s = -mu_RF(|w|) F_L3 w_tau/|w|, w = (gamma_x, gamma_y) v at t = 0, the
static approach xi3_static (the table's approach for F_L3), u = A F_ref.  Its
structural deflection (including the quasi-static part of the rigid-body /
suspension modes, which are in the wheel's modal set) is the static deflection
the convolutions of the deviations leave out, so the state is an exact
equilibrium of the discrete model: nothing moves unless it is disturbed.  The
disturbance is ``kick``: an impulse (N s, default 0.01 N s lateral) given to
the structures as an extra force kick/dt during the first step (the same
impulse at any dt), from which an unstable mode grows.  ``start='static'``:
F_ref = (0, 0, F_L3), u = 0 (the wheel stands on the rail under its load, the
creep force appears at t = 0 as a step): the step excites everything, and the
quasi-static cross compliance of the half wheelset on its soft primary
suspension (roll mode, G32 ~ -1e-7 m/N at the tread) turns the creep force into
a vertical deflection, so F3 settles away from the preload (69 kN instead of
65 kN in the default case); an option, not the default.

Time discretisation: besides the explicit coupling (displacements from past
forces), the rule g(0) = 0 drops the first sample of the rail's kernel, which
holds a share of the rail's static compliance proportional to dt (2 % of the
vertical one at 36 us for BV50): modes dominated by the track stiffness (the
wheelset bouncing on the track, ~80 Hz) converge to first order in dt, wheel
modes in the kHz range much faster (validation doc).

Drivers
-------
``simulate(...)`` runs
* normal='table', tangential='point': the whole time loop inside numba
  (``_run_point``), O(modes + B + K / B) per step for a rail kernel of K lags and head B (benchmarks/interaction.py);
* normal='norm', compliance='exact' and/or tangential='kalker' (or
  driver='python'): the reference drivers, a Python loop over the steps with
  the same kinematics and the same njit building blocks: per-step NORM
  (warm-started active set, ``solvers.contact.norm``, ~0.7 ms per step; it
  agrees with the table to the table's interpolation error: exactly at the
  nodes, ~1e-5 over a run with the contact stage's 41 nodes, < 1e-6 with the
  table refined over the visited range by ``refine_table``), the literal
  compliance [4.32]-[4.35] per step, and Kalker's transient TANG per step
  (``tang_transient`` with the table's or NORM's pressures, the structural
  lateral velocity added to the rigid slip: gamma_y + sign (xi2[n] -
  xi2[n-1])/dx; FFT-based Newton-Krylov, warm-started and extrapolated from
  the last steps, tolerance KALKER_TOL, displacements on the contact's window
  only: about 1 ms per step on the default contact, docs/benchmarks.md).

Output: every ``store_every``-th step (decimated history) plus the last
``final`` seconds at full rate (for the spectra); early stop when a limit
cycle is reached or the motion has decayed (``StopRule``); never beyond
``duration`` (at most 8 s, SPEC 6).  Squeal measures [6.3]-[6.4] with
``squeal_measures`` / ``InteractionResult.measures``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import NamedTuple

import numba
import numpy as np

from .contact.compliance import table_compliance
from .contact.friction import mu_and_slope, mu_rf
from .contact.norm import table_force
from .green import ModalFilter, filter_step, modal_filter
from .partitioned import DEFAULT_BLOCK, partitioned_convolver, partitioned_step

MAX_DURATION = 8.0          # s, SPEC 6
EPS_SLIP = 1e-9             # m/s, regularisation of the slip direction (curves with mu(0) > 0)
DEFAULT_KICK = 0.01         # N s, lateral impulse that seeds the instability (start='steady')
FULL_SLIP = 0.99            # contact state 2 when mu_RF(s) >= FULL_SLIP * plateau
KALKER_TOL = 1e-6           # TANG's tolerance in the time loop (forces to ~1e-6, far below any squeal measure)
# columns of the stored histories
COLUMNS = ("F1", "F2", "F3", "s1", "s2", "xi2", "xi3", "state")
STOP_REASONS = {0: "duration", 1: "limit cycle", 2: "decayed"}


# ----------------------------------------------------------------------------------------------
# inputs
# ----------------------------------------------------------------------------------------------

class WheelModes(NamedTuple):
    """Modal data of the wheel at the contact point (SPEC 3.1): f_r (M,) Hz, modal_mass (M,) kg,
    zeta (M,), phi (M, 2) = (Phi_2, Phi_3).  Empty arrays: a rigid, fixed wheel."""
    f_r: np.ndarray
    modal_mass: np.ndarray
    zeta: np.ndarray
    phi: np.ndarray


class ContactModel(NamedTuple):
    """The contact of a case (SPEC 4.1-4.4) as arrays (keys of build/cases/<case>/contact.npz).

    xi3_nodes, q_nodes: NORM table (approach [m], q = F3^(2/3)); A1_nodes, A2_nodes: tangential
    compliances over the approach [m/N]; s_nodes, mu_nodes, slopes: the regularised friction
    curve mu_RF(s) (monotone Hermite, ``friction.mu_rf``); mu: its Coulomb coefficient.
    For the reference drivers: F3_nodes and pressure_nodes (the table's pressure fields, for
    Kalker's TANG), gap, dx, dy, E, nu (per-step NORM, TANG)."""
    xi3_nodes: np.ndarray
    q_nodes: np.ndarray
    A1_nodes: np.ndarray
    A2_nodes: np.ndarray
    s_nodes: np.ndarray
    mu_nodes: np.ndarray
    slopes: np.ndarray
    mu: float
    F3_nodes: np.ndarray | None = None
    pressure_nodes: np.ndarray | None = None
    gap: np.ndarray | None = None
    dx: float | None = None
    dy: float | None = None
    E: float = 210e9
    nu: float = 0.3


def contact_model(arrays, mu: float) -> ContactModel:
    """ContactModel from the contact stage's arrays (a dict or NpzFile with the keys of
    contact.npz) for the Coulomb coefficient ``mu`` (one of ``mu_values``)."""
    mus = np.asarray(arrays["mu_values"], float)
    i = int(np.argmin(np.abs(mus - mu)))
    if abs(mus[i] - mu) > 1e-9:
        raise ValueError(f"no friction curve for mu = {mu}; available: {mus.tolist()}")
    n = int(arrays["rf_n"][i])
    keys = set(arrays.files) if hasattr(arrays, "files") else set(arrays)
    f = lambda k: np.ascontiguousarray(np.asarray(arrays[k], float)) if k in keys else None   # noqa: E731
    return ContactModel(f("xi3_nodes"), f("q_nodes"), f("A1_nodes"), f("A2_nodes"),
                        f("rf_s")[i, :n].copy(), f("rf_mu")[i, :n].copy(), f("rf_slope")[i, :n].copy(),
                        float(mus[i]), f("F3_nodes"), f("pressure_nodes"), f("gap"),
                        float(arrays["dx"]) if "dx" in keys else None,
                        float(arrays["dy"]) if "dy" in keys else None)


def refine_table(contact: ContactModel, xi3_nodes) -> ContactModel:
    """The contact with its normal table (F3, q, pressures) and compliance table (A1, A2)
    recomputed by NORM and [4.32]-[4.35] at ``xi3_nodes`` inside [min, max] of the given nodes
    (the old nodes outside that range are kept).  The table's interpolation error (linear in
    q = F3^(2/3), ~5e-5 midway between the contact stage's 41 nodes at the working point)
    falls below 1e-6 for a node step of ~2e-3 of the static approach: use it to make the table
    mode reproduce per-step NORM to 1e-6 over the range a run visits."""
    from .contact.compliance import compliance_table
    from .contact.norm import norm_table

    if contact.gap is None or contact.dx is None or contact.dy is None:
        raise ValueError("refine_table needs the contact's gap, dx and dy")
    new = np.sort(np.asarray(xi3_nodes, float))
    old = contact.xi3_nodes
    keep = (old < new[0]) | (old > new[-1])
    xs = np.sort(np.concatenate([old[keep], new]))
    t = norm_table(contact.gap, xs, contact.dx, contact.dy, contact.E, contact.nu)
    A1, A2 = compliance_table(xs, t.p, contact.dx, contact.dy, contact.E, contact.nu)
    return contact._replace(xi3_nodes=t.xi3, q_nodes=t.q, F3_nodes=t.F3, pressure_nodes=t.p, A1_nodes=A1,
                            A2_nodes=A2)


@dataclass(frozen=True)
class StopRule:
    """Early stop (checked at the end of every window of ``window`` s):

    * 'decayed': the rms of the F2 and F3 deviations from their window means are both below
      ``decay_tol`` * preload and the rms of F2 has fallen from window to window over the last
      ones: the motion has died out to a constant force (a mode growing from far below that
      level, slower than the others decay, would be missed: the kick sets the start level);
    * 'limit cycle': over the last ceil(final / window) windows (at least ``min_windows``; they
      cover the full-rate final stretch) the rms of F2 (mean removed) and its zero-crossing
      frequency differ from the last window's by less than ``rms_tol`` and ``freq_tol``;
    * never before ``min_time`` (default: the final stretch plus one window)."""
    window: float = 0.25
    rms_tol: float = 0.03
    freq_tol: float = 0.03
    decay_tol: float = 1e-6
    min_windows: int = 3
    min_time: float | None = None


# ----------------------------------------------------------------------------------------------
# njit building blocks
# ----------------------------------------------------------------------------------------------



@numba.njit(cache=True)
def point_contact(b1, b2, c1, c2, F3, s_nodes, mu_nodes, slopes, eps, sigma0):
    """Tangential point-contact model [4.25]-[4.31] for one step (module notes):
    s_tau = b_tau + c_tau F_tau, F_tau = -mu_RF(s) F3 s_tau / sqrt(s^2 + eps^2).
    b (m/s): the known part of the slip; c_tau = A_tau / dt (m/s per N); F3 > 0; eps >= 0
    (0 needs mu_RF(0) = 0).
    sigma0: a start value for |s| (the previous step's), ignored unless in (0, |b|).
    Returns F1, F2, s1, s2, |s|, Newton iterations, bisection fallbacks."""
    bn = math.hypot(b1, b2)
    if bn == 0.0 or F3 <= 0.0:
        return 0.0, 0.0, b1, b2, bn, 0, 0
    k1 = c1 * F3
    k2 = c2 * F3
    e1 = b1 / bn
    e2 = b2 / bn
    # scaled unknown x = sigma / |b| in (0, 1]; H(x) = 1/sqrt(e1^2/d1^2 + e2^2/d2^2) - 1, d = D/|b|
    lo = 0.0
    hi = 1.0
    x = sigma0 / bn
    if not (0.0 < x < 1.0):
        x = 0.5
    it = 0
    nb = 0
    for it in range(1, 101):
        sig = x * bn
        m, dm = mu_and_slope(sig, s_nodes, mu_nodes, slopes)
        r = math.hypot(sig, eps)
        g = m * sig / r                                   # mu_RF(s) s / sqrt(s^2 + eps^2)
        dg = dm * sig / r                                 # d g / d sigma
        if eps > 0.0:
            dg += m * (eps / r) * (eps / r) / r
        d1 = x + k1 * g / bn
        d2 = x + k2 * g / bn
        dd1 = 1.0 + k1 * dg
        dd2 = 1.0 + k2 * dg
        N = (e1 / d1) ** 2 + (e2 / d2) ** 2
        H = 1.0 / math.sqrt(N) - 1.0
        if H == 0.0:
            break
        if H > 0.0:
            hi = x
        else:
            lo = x
        dN = -2.0 * (e1 * e1 * dd1 / (d1 * d1 * d1) + e2 * e2 * dd2 / (d2 * d2 * d2))
        dH = -0.5 * dN / (N * math.sqrt(N))
        xn = x - H / dH if dH > 0.0 else -1.0
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
            nb += 1
        if abs(xn - x) <= 1e-15 or hi - lo <= 1e-15:
            x = xn
            break
        x = xn
    sig = x * bn
    m = mu_rf(sig, s_nodes, mu_nodes, slopes)
    r = math.hypot(sig, eps)
    q = m / r if r > 0.0 else slopes[0]
    s1 = b1 / (1.0 + k1 * q)
    s2 = b2 / (1.0 + k2 * q)
    return -F3 * q * s1, -F3 * q * s2, s1, s2, math.hypot(s1, s2), it, nb


@numba.njit(cache=True)
def _store(n, row, hist, fin, store_every):
    """Record step n: every store_every-th step into hist, every step into the ring fin."""
    if n % store_every == 0:
        j = n // store_every
        if j < hist.shape[0]:
            for c in range(row.shape[0]):
                hist[j, c] = row[c]
    nf = fin.shape[0]
    if nf > 0:
        j = n % nf
        for c in range(row.shape[0]):
            fin[j, c] = row[c]


@numba.njit(cache=True)
def _end_window(iw, wbuf, nw, dt, t_end, win_stats):
    """Statistics of one window of nw steps: t_end, mean F2, rms F2, zero-crossing frequency of
    F2 - mean, rms F3 (means removed)."""
    m2 = 0.0
    m3 = 0.0
    for j in range(nw):
        m2 += wbuf[j, 0]
        m3 += wbuf[j, 1]
    m2 /= nw
    m3 /= nw
    v2 = 0.0
    v3 = 0.0
    cross = 0
    prev = wbuf[0, 0] - m2
    for j in range(nw):
        a = wbuf[j, 0] - m2
        v2 += a * a
        v3 += (wbuf[j, 1] - m3) ** 2
        if (a > 0.0) != (prev > 0.0):
            cross += 1
        prev = a
    win_stats[iw, 0] = t_end
    win_stats[iw, 1] = m2
    win_stats[iw, 2] = math.sqrt(v2 / nw)
    win_stats[iw, 3] = cross / (2.0 * nw * dt)
    win_stats[iw, 4] = math.sqrt(v3 / nw)


@numba.njit(cache=True)
def _stop_decision(iw, win_stats, need, rms_tol, f_tol, decay_abs):
    """0: go on, 1: limit cycle, 2: decayed (see StopRule)."""
    if iw + 1 < need:
        return 0
    if win_stats[iw, 2] <= decay_abs and win_stats[iw, 4] <= decay_abs:
        for j in range(iw - need + 2, iw + 1):         # and still falling: nothing growing underneath
            if win_stats[j, 2] >= win_stats[j - 1, 2] and win_stats[j, 2] > 1e-6 * decay_abs:
                return 0                                # (1e-6 decay_abs: the rounding floor)
        return 2
    r = win_stats[iw, 2]
    f = win_stats[iw, 3]
    if f <= 0.0:
        return 0
    for j in range(iw - need + 1, iw):
        if abs(win_stats[j, 2] - r) > rms_tol * r or abs(win_stats[j, 3] - f) > f_tol * f:
            return 0
    return 1


@numba.njit(cache=True)
def _record_window(F2, F3, done, wbuf, jw, iw, nw, dt, win_stats, min_steps, need, rms_tol, f_tol, decay_abs):
    """Store (F2, F3) in the window buffer; at a full window, close it and
    decide whether to stop.  Returns (jw, iw, reason), reason 0 = go on."""
    wbuf[jw, 0] = F2
    wbuf[jw, 1] = F3
    jw += 1
    reason = 0
    if jw == nw:
        jw = 0
        if iw < win_stats.shape[0]:
            _end_window(iw, wbuf, nw, dt, done * dt, win_stats)
            if done >= min_steps:
                reason = _stop_decision(iw, win_stats, need, rms_tol, f_tol, decay_abs)
            iw += 1
    return jw, iw, reason


@numba.njit(cache=True, inline="always")
def _advance(filt, rc, n, F2, F3, F_ref, kick, wbuf, jw, iw, nw, dt, win_stats, min_steps, need, rms_tol, f_tol,
             decay_abs):
    """End of step n, shared by both drivers: the structures' response to this step's force
    deviations (kick/dt added at n = 0) -> xi = xi^R - xi^W at step n + 1 (wheel: recursive modal
    filters, the wheel moving by minus their sum [4.13]; rail: moving kernel), then the stop rule's
    window.  Returns (xi2, xi3, jw, iw, reason)."""
    d2 = F2 - F_ref[1]
    d3 = F3 - F_ref[2]
    if n == 0:
        d2 += kick[0]
        d3 += kick[1]
    w2, w3 = filter_step(filt, d2, d3)
    r2, r3 = partitioned_step(rc, d2, d3)
    reason = 0
    if nw > 0:
        jw, iw, reason = _record_window(F2, F3, n + 1, wbuf, jw, iw, nw, dt, win_stats, min_steps, need, rms_tol,
                                        f_tol, decay_abs)
    return r2 + w2, r3 + w3, jw, iw, reason


@numba.njit(cache=True)
def _run_point(filt, rc, n_steps, dt, v, gx, gy, xi3_static, F_ref, u_ref, kick, slip_sign,
               xi3_nodes, q_nodes, A1_nodes, A2_nodes, s_nodes, mu_nodes, slopes, eps,
               store_every, hist, fin, nw, wbuf, win_stats, need, rms_tol, f_tol, decay_abs, min_steps,
               counters):
    """The time loop (table NORM, point-contact model), entirely in numba.  See the module
    notes; counters: [Newton iterations, max per step, bisections, steps without contact].
    Returns (steps done, stop reason)."""
    xi2 = 0.0
    xi3 = 0.0
    xi2_old = 0.0
    u1p = u_ref[0]
    u2p = u_ref[1]
    sig = 0.0
    mu_top = mu_nodes[mu_nodes.shape[0] - 1]
    row = np.zeros(8)
    ngx = gx.shape[0]
    ngy = gy.shape[0]
    iw = 0
    jw = 0
    reason = 0
    done = 0
    for n in range(n_steps):
        gxn = gx[n if n < ngx else ngx - 1]
        gyn = gy[n if n < ngy else ngy - 1]
        app = xi3_static - xi3
        F3 = table_force(app, xi3_nodes, q_nodes)
        b1 = gxn * v - u1p / dt
        b2 = gyn * v - u2p / dt + slip_sign * (xi2 - xi2_old) / dt
        if F3 > 0.0:
            A1 = table_compliance(app, xi3_nodes, A1_nodes)
            A2 = table_compliance(app, xi3_nodes, A2_nodes)
            F1, F2, s1, s2, sig, it, nb = point_contact(b1, b2, A1 / dt, A2 / dt, F3, s_nodes, mu_nodes,
                                                        slopes, eps, sig)
            u1p = A1 * F1
            u2p = A2 * F2
            counters[0] += it
            if it > counters[1]:
                counters[1] = it
            counters[2] += nb
            state = 2.0 if mu_rf(sig, s_nodes, mu_nodes, slopes) >= FULL_SLIP * mu_top else 1.0
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
        _store(n, row, hist, fin, store_every)
        xi2_old = xi2
        xi2, xi3, jw, iw, reason = _advance(filt, rc, n, F2, F3, F_ref, kick, wbuf, jw, iw, nw, dt, win_stats,
                                            min_steps, need, rms_tol, f_tol, decay_abs)
        done = n + 1
        if reason != 0:
            break
    return done, reason


# ----------------------------------------------------------------------------------------------
# result
# ----------------------------------------------------------------------------------------------

@dataclass
class InteractionResult:
    """Histories of a run (SI units).  Forces on the rail F (n, 3) = (F1, F2, F3) [N]; slip of the
    rail relative to the wheel (s1, s2) [m/s] (point model: the global slip of [4.29]-[4.30];
    Kalker: the mean over the contact elements, zero in stick); xi (n, 2) = xi^R - xi^W, the
    dynamic relative displacement (deviation from the reference state) in directions 2, 3 [m];
    state: 0 no contact, 1 partial slip (point model: mu_RF(s) < 0.99 of its plateau; Kalker:
    some elements stick), 2 full slip.
    ``t, F, slip, xi, state``: every ``store_every``-th step; ``*_final``: the last ``final`` s at
    full rate (all of the run if shorter)."""
    dt: float
    v: float
    t: np.ndarray
    F: np.ndarray
    slip: np.ndarray
    xi: np.ndarray
    state: np.ndarray
    t_final: np.ndarray
    F_final: np.ndarray
    slip_final: np.ndarray
    xi_final: np.ndarray
    state_final: np.ndarray
    n_steps: int
    stop_reason: str
    F_ref: np.ndarray
    xi3_static: float
    windows: np.ndarray           # per window: t_end, mean F2, rms F2, zero-crossing freq of F2, rms F3
    newton: dict
    lost_steps: int
    wall: float
    settings: dict = field(default_factory=dict)
    dt_final: float = 0.0         # sample interval of the *_final arrays (dt, or store_every dt without them)

    @property
    def duration(self) -> float:
        return self.n_steps * self.dt

    def measures(self, final: float | None = None, f_min: float = 20.0) -> dict:
        """Squeal measures [6.3]-[6.4] over the final stretch (the full-rate part, or its last
        ``final`` s): see ``squeal_measures``."""
        F = self.F_final
        h = self.dt_final or self.dt
        if final is not None:
            F = F[-max(1, int(round(final / h))):]
        out = squeal_measures(F[:, 1], h, f_min=f_min)
        out.update(F3_mean=float(F[:, 2].mean()), F3_rms=float(F[:, 2].std()),
                   contact_loss_share=float(np.mean(self.state_final == 0)),
                   stop_reason=self.stop_reason, t_end=self.duration)
        return out


def squeal_measures(F2, dt: float, f_min: float = 20.0) -> dict:
    """L_F2 = 20 log10(rms(F2 - mean) / 1 N) [6.3]-[6.4] and the dominant frequency of F2
    (largest peak above f_min of the Hann-windowed amplitude spectrum) of the given stretch,
    with postprocess.spectra.  L_F2 = -inf for a constant force."""
    from postprocess.spectra import amplitude_spectrum, dominant_frequency, force_level

    F2 = np.asarray(F2, float)
    L = force_level(F2)
    out = {"L_F2": L, "F2_mean": float(F2.mean()), "F2_rms": float(F2.std()), "F2_pp": float(np.ptp(F2)),
           "f_dominant": float("nan"), "F2_amplitude": 0.0}
    if np.isfinite(L) and F2.size > 8:
        f, X = amplitude_spectrum(F2, dt)
        fd, amp = dominant_frequency(f, X, f_min=f_min)
        out["f_dominant"], out["F2_amplitude"] = fd, amp
    return out


# ----------------------------------------------------------------------------------------------
# driver
# ----------------------------------------------------------------------------------------------

def _wheel_filter(wheel: WheelModes | None, dt: float) -> ModalFilter:
    if wheel is None or len(np.atleast_1d(wheel.f_r)) == 0:
        return modal_filter(dt, np.zeros(0), np.zeros(0), np.zeros(0), np.zeros((0, 2)))
    return modal_filter(dt, wheel.f_r, wheel.modal_mass, wheel.zeta, wheel.phi)


def _rail_ring(rail_kernel: np.ndarray | None, block: int | None = DEFAULT_BLOCK):
    """The rail's convolver (solvers.partitioned): exact partitioned FFT convolution with a direct
    head of ``block`` lags, or the plain direct sum with block=None (the reference)."""
    g = np.zeros((1, 2, 2)) if rail_kernel is None else np.asarray(rail_kernel, float)
    if g.ndim != 3 or g.shape[1:] != (2, 2):
        raise ValueError(f"rail kernel must have shape (n_k, 2, 2), got {g.shape}")
    return partitioned_convolver(g, block)


def static_approach(contact: ContactModel, preload: float) -> float:
    """The approach at which the NORM table gives F3 = preload (bisection on the monotone table)."""
    xs = contact.xi3_nodes
    lo, hi = float(xs[0]), float(xs[-1])
    while table_force(hi, xs, contact.q_nodes) < preload:
        hi = lo + 2.0 * (hi - lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if table_force(mid, xs, contact.q_nodes) < preload:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-16 * abs(hi):
            break
    return 0.5 * (lo + hi)


def _per_step(a, n_steps: int) -> np.ndarray:
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(a, float)))
    if a.size not in (1,) and a.size < n_steps:
        raise ValueError(f"a creepage history must have one value or >= {n_steps} values, got {a.size}")
    return a


def steady_forces(contact: ContactModel, v: float, gamma_x: float, gamma_y: float, F3: float,
                  eps: float = 0.0) -> np.ndarray:
    """Steady rolling forces of the point-contact model at rigid slip w = (gamma_x, gamma_y) v:
    F_tau = -mu_RF(|w|) F3 w_tau / sqrt(|w|^2 + eps^2); returns (F1, F2, F3)."""
    w1, w2 = gamma_x * v, gamma_y * v
    s = math.hypot(w1, w2)
    r = math.sqrt(s * s + eps * eps)
    q = mu_rf(s, contact.s_nodes, contact.mu_nodes, contact.slopes) / r if r > 0 else 0.0
    return np.array([-F3 * q * w1, -F3 * q * w2, F3])


def simulate(wheel: WheelModes | None, rail_kernel: np.ndarray | None, contact: ContactModel, *,
             dt: float, v: float, gamma_y, gamma_x=0.0, preload: float = 65e3, duration: float = 8.0,
             tangential: str = "point", normal: str = "table", compliance: str = "table",
             start: str = "steady", kick=None, slip_sign: float = 1.0,
             final: float = 0.5, store_every: int = 1, stop: StopRule | None = StopRule(),
             xi3_static: float | None = None, eps: float | None = None, driver: str = "auto",
             rail_block: int | None = DEFAULT_BLOCK) -> InteractionResult:
    """Run the wheel/rail interaction (module notes).

    wheel: WheelModes (None: rigid fixed wheel); rail_kernel: the rail's moving Green's function
    g_mov (n_k, 2, 2) in m/N (None: rigid rail); contact: ContactModel.  dt [s], v [m/s] (dx = v dt
    must be the contact grid's dx for the reference drivers); gamma_y, gamma_x: creepages, a
    number or a per-step history (its last value is held); preload F_L3 [N]; duration [s] (at
    most 8 s).  tangential 'point' | 'kalker'; normal 'table' | 'norm' (per-step NORM);
    compliance 'table' | 'exact' (reference drivers only: [4.32]-[4.35] per step);
    start 'steady' | 'static'; kick [N s]: impulse on the structures (force kick/dt during the
    first step), lateral or (lateral, vertical) (default 0.01 N s lateral for 'steady', 0 for
    'static');
    slip_sign: +1 (physical) or -1 (the sign printed in [4.30]); final [s]: full-rate stretch;
    store_every: decimation of the history; stop: StopRule or None (run the full duration);
    xi3_static: static approach (default: the table's approach at the preload); eps: slip
    direction regularisation (default 0 for a curve with mu_RF(0) = 0, else EPS_SLIP); driver: 'auto'
    (numba for table + point + table compliance, else the Python reference loop) or 'python'
    (force the reference loop, for testing); rail_block: head length of the rail's partitioned
    FFT convolution (exact, ``solvers.partitioned``), None for the direct sum."""
    if duration > MAX_DURATION + 1e-12:
        raise ValueError(f"duration {duration} s exceeds the SPEC's maximum of {MAX_DURATION} s")
    if tangential not in ("point", "kalker") or normal not in ("table", "norm") or \
            compliance not in ("table", "exact") or start not in ("steady", "static"):
        raise ValueError("tangential 'point'|'kalker', normal 'table'|'norm', compliance 'table'|'exact', "
                         "start 'steady'|'static'")
    store_every = max(1, int(store_every))
    if eps is None:
        eps = 0.0 if contact.mu_nodes[0] == 0.0 else EPS_SLIP
    n_steps = int(round(duration / dt))
    gx = _per_step(gamma_x, n_steps)
    gy = _per_step(gamma_y, n_steps)
    if xi3_static is None:
        xi3_static = static_approach(contact, preload)
    A0 = np.array([table_compliance(xi3_static, contact.xi3_nodes, contact.A1_nodes),
                   table_compliance(xi3_static, contact.xi3_nodes, contact.A2_nodes)])
    if start == "steady":
        F_ref = steady_forces(contact, v, gx[0], gy[0], preload, eps)
        u_ref = A0 * F_ref[:2]
        kick = DEFAULT_KICK if kick is None else kick
    else:
        F_ref = np.array([0.0, 0.0, preload])
        u_ref = np.zeros(2)
        kick = 0.0 if kick is None else kick
    kick = np.array([kick, 0.0] if np.ndim(kick) == 0 else kick, float).reshape(2)
    kick_force = kick / dt
    n_final = min(n_steps, int(round(final / dt))) if final else 0
    hist = np.zeros(((n_steps + store_every - 1) // store_every, 8))
    fin = np.zeros((n_final, 8))
    rule = stop if stop is not None else StopRule()      # without a rule: window statistics only
    nw = max(1, int(round(rule.window / dt)))
    need = max(rule.min_windows, int(math.ceil(final / rule.window - 1e-9)) if final else 0)
    min_time = rule.min_time if rule.min_time is not None else final + rule.window
    min_steps = int(round(min_time / dt)) if stop is not None else n_steps + 1
    decay_abs = rule.decay_tol * preload
    rms_tol, f_tol = rule.rms_tol, rule.freq_tol
    win_stats = np.zeros((n_steps // nw if nw else 0, 5))
    wbuf = np.zeros((max(nw, 1), 2))
    counters = np.zeros(4, np.int64)
    filt = _wheel_filter(wheel, dt)
    rc = _rail_ring(rail_kernel, rail_block)
    settings = dict(dt=dt, v=v, preload=preload, duration=duration, tangential=tangential, normal=normal,
                    compliance=compliance, start=start, kick=kick.tolist(), slip_sign=slip_sign, final=final,
                    store_every=store_every, eps=eps)
    t0 = time.perf_counter()
    args = (filt, rc, n_steps, float(dt), float(v), gx, gy, float(xi3_static), F_ref, u_ref, kick_force,
            float(slip_sign), contact, eps, store_every, hist, fin, nw, wbuf, win_stats, need, rms_tol,
            f_tol, decay_abs, min_steps, counters)
    if driver not in ("auto", "python"):
        raise ValueError("driver 'auto' | 'python'")
    if tangential == "point" and normal == "table" and compliance == "table" and driver == "auto":
        c = contact
        done, reason = _run_point(filt, rc, n_steps, float(dt), float(v), gx, gy, float(xi3_static), F_ref,
                                  u_ref, kick_force, float(slip_sign), c.xi3_nodes, c.q_nodes, c.A1_nodes,
                                  c.A2_nodes, c.s_nodes, c.mu_nodes, c.slopes, float(eps), store_every, hist,
                                  fin, nw, wbuf, win_stats, need, rms_tol, f_tol, decay_abs, min_steps, counters)
    else:
        done, reason, F_ref = _run_reference(*args, tangential=tangential, normal=normal, compliance=compliance,
                                             start=start)
    wall = time.perf_counter() - t0
    return _assemble(hist, fin, win_stats, done, reason, counters, F_ref, xi3_static, dt, v, store_every, wall,
                     settings)


def _assemble(hist, fin, win_stats, done, reason, counters, F_ref, xi3_static, dt, v, store_every, wall,
              settings) -> InteractionResult:
    nh = (done + store_every - 1) // store_every
    h = hist[:nh]
    nf = fin.shape[0]
    if nf:
        m = min(done, nf)
        idx = (np.arange(done - m, done) % nf)
        f = fin[idx]
        tf = np.arange(done - m, done) * dt
    else:
        f = hist[:nh]
        tf = np.arange(nh) * store_every * dt
    nwin = int(np.count_nonzero(win_stats[:, 0])) if win_stats.size else 0
    steps = max(done - int(counters[3]), 1)
    return InteractionResult(
        dt=float(dt), v=float(v), t=np.arange(nh) * store_every * dt, F=h[:, 0:3].copy(), slip=h[:, 3:5].copy(),
        xi=h[:, 5:7].copy(), state=h[:, 7].astype(np.int8), t_final=tf, F_final=f[:, 0:3].copy(),
        slip_final=f[:, 3:5].copy(), xi_final=f[:, 5:7].copy(), state_final=f[:, 7].astype(np.int8),
        n_steps=int(done), stop_reason=STOP_REASONS[int(reason)], F_ref=np.asarray(F_ref, float),
        xi3_static=float(xi3_static), windows=win_stats[:nwin].copy(),
        newton={"iterations_mean": float(counters[0]) / steps, "iterations_max": int(counters[1]),
                "bisections": int(counters[2])},
        lost_steps=int(counters[3]), wall=wall, settings=settings,
        dt_final=float(dt if nf else store_every * dt))


# ----------------------------------------------------------------------------------------------
# reference drivers (Python loop): per-step NORM, Kalker's transient TANG
# ----------------------------------------------------------------------------------------------

def _run_reference(filt, rc, n_steps, dt, v, gx, gy, xi3_static, F_ref, u_ref, kick, slip_sign, c, eps,
                   store_every, hist, fin, nw, wbuf, win_stats, need, rms_tol, f_tol, decay_abs, min_steps,
                   counters, *, tangential, normal, compliance, start):
    """The same time loop as ``_run_point`` in Python, with per-step NORM (normal='norm'), the
    literal compliance [4.32]-[4.35] (compliance='exact') and/or Kalker's transient TANG
    (tangential='kalker').  Returns (steps done, reason, F_ref)."""
    from .contact.compliance import contact_compliance
    from .contact.norm import NormTable, norm, table_pressure
    from .contact.tang import tang_steady, tang_transient

    if normal == "norm" or tangential == "kalker" or compliance == "exact":
        if c.gap is None or c.dx is None or c.dy is None:
            raise ValueError("the reference drivers need the contact's gap, dx and dy")
        if abs(c.dx - v * dt) > 1e-9 * c.dx:
            raise ValueError(f"the contact grid's dx = {c.dx} must be v dt = {v * dt} (SPEC 4.1)")
    table = None
    if tangential == "kalker" or compliance == "exact":
        if c.pressure_nodes is None or c.F3_nodes is None:
            raise ValueError("Kalker's TANG and the exact compliance need the table's pressure fields")
        table = NormTable(c.xi3_nodes, c.F3_nodes, c.q_nodes, c.pressure_nodes, c.pressure_nodes > 0)
    E, nu = c.E, c.nu
    mu_top = c.mu_nodes[-1]
    tang_state = None
    if tangential == "kalker":
        if start == "steady":
            p0 = table_pressure(table, xi3_static) if normal == "table" else norm(c.gap, xi3_static, c.dx, c.dy,
                                                                                 E, nu).p
            tang_state = tang_steady(p0, c.dx, c.dy, v, c.mu, gamma_x=gx[0], gamma_y=gy[0], E=E, nu=nu,
                                     full_output=False, tol=KALKER_TOL)
            F_ref = np.array([tang_state.F1, tang_state.F2, F_ref[2]])
    xi2 = xi3 = xi2_old = 0.0
    u1p, u2p = float(u_ref[0]), float(u_ref[1])
    sig = 0.0
    F_prev = (float(F_ref[0]), float(F_ref[1]))
    nsol = None
    row = np.zeros(8)
    iw = jw = reason = done = 0
    for n in range(n_steps):
        gxn = gx[min(n, len(gx) - 1)]
        gyn = gy[min(n, len(gy) - 1)]
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
                b1 = gxn * v - u1p / dt
                b2 = gyn * v - u2p / dt + dxi2
                F1, F2, s1, s2, sig, it, nb = point_contact(b1, b2, A1 / dt, A2 / dt, F3, c.s_nodes, c.mu_nodes,
                                                            c.slopes, eps, sig)
                u1p, u2p = A1 * F1, A2 * F2
                counters[0] += it
                counters[1] = max(counters[1], it)
                counters[2] += nb
                state = 2.0 if mu_rf(sig, c.s_nodes, c.mu_nodes, c.slopes) >= FULL_SLIP * mu_top else 1.0
            else:
                if p3 is None:
                    p3 = table_pressure(table, app)
                tang_state = tang_transient(p3, c.dx, c.dy, v, c.mu, gamma_x=gxn, gamma_y=gyn + dxi2 / v,
                                            E=E, nu=nu, state=tang_state, full_output=False, tol=KALKER_TOL)
                F1, F2 = tang_state.F1, tang_state.F2
                inside = p3 > 0
                s1 = float(tang_state.s1[inside].mean())
                s2 = float(tang_state.s2[inside].mean())
                counters[0] += tang_state.iterations
                counters[1] = max(counters[1], tang_state.iterations)
                state = 1.0 if tang_state.stick.any() else 2.0
            F_prev = (F1, F2)
        else:
            F1 = F2 = F3 = 0.0
            s1, s2 = gxn * v - u1p / dt, gyn * v - u2p / dt + dxi2
            u1p = u2p = 0.0
            tang_state = None
            state = 0.0
            counters[3] += 1
        row[:] = (F1, F2, F3, s1, s2, xi2, xi3, state)
        _store(n, row, hist, fin, store_every)
        xi2_old = xi2
        xi2, xi3, jw, iw, reason = _advance(filt, rc, n, float(F2), float(F3), F_ref, kick, wbuf, jw, iw, nw, dt,
                                            win_stats, min_steps, need, rms_tol, f_tol, decay_abs)
        done = n + 1
        if reason != 0:
            break
    return done, reason, F_ref
