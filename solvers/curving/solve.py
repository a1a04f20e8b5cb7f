"""Solving the steady-curving equations (``model``) of a free wheelset or of the leading bogie,
with flange contact as a unilateral constraint (an active set).

Unknowns, scaled to order one: the lateral shift y in mm (or, for a wheelset whose flange is
in contact, the flange's normal force N_f in units of the static wheel load Q0, y being then
the flange shift), the yaw psi in mrad, eps in 1e-3, the tread normal forces in Q0, and for
the bogie the frame's y_b (mm) and psi_b (mrad).  Residuals: forces / Q0 and moments /
(Q0 * 1 m).  MINPACK's hybrid method (``scipy.optimize.root``, 'hybr') from a start in pure
rolling, then Newton steps with a finite-difference Jacobian until every residual is below
TOL (relative to the wheel load).  Flange contact: a wheelset whose shift passes the flange
shift y_f (``wheelrail.flange_shift``) is put in two-point contact (y = +-y_f, N_f unknown);
one whose flange force comes out negative is released; repeated until the set is stable.
When that stalls (the set cycling, or a worn pair's tread contact jumping between two points at
the equilibrium's shift: a two-point tread contact), ``semismooth`` solves the same equations
with the unilateral contacts as one continuous complementarity system, before the continuation.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import dataclasses

import numpy as np

from solvers.curving.creep import CreepLaw
from solvers.curving.model import Profiles, Track, Vehicle, box_loads, wheel_contacts, wheelset_residual
from solvers.curving.roots import TOL, newton, safe_residual
from solvers.curving.semismooth import semismooth
from solvers.curving.wheelrail import flange_shift

MAX_ACTIVE = 8       # active-set passes


class CurvingError(RuntimeError):
    """No equilibrium found (the message says where the iteration stopped)."""


@dataclass
class WheelsetState:
    """A solved wheelset: shift y (m, outward), yaw psi (rad), eps, flange side (0, +1 outer,
    -1 inner), its normal force N_f (N, 0 without), contacts (list of model.ContactResult, outer
    first), suspension force and moment on it (N, N m) and its five residuals (N, N m)."""

    x: float
    y: float
    psi: float
    eps: float
    flange: int
    flange_force: float
    contacts: list
    F_susp: float = 0.0
    M_susp: float = 0.0
    residual: tuple = ()


@dataclass
class CurvingSolution:
    """Wheelsets (leading first), frame shift and yaw (m, rad; NaN for a free wheelset), the
    flange shift y_f (m), the largest residual relative to Q0 (forces N / Q0, moments N m /
    (Q0 1 m)), the frame residuals and the number of active-set passes."""

    wheelsets: list
    frame_y: float
    frame_psi: float
    flange_shift: float
    max_residual: float
    frame_residual: tuple = ()
    passes: int = 0
    notes: list = field(default_factory=list)


def _unpack_wheelset(q, flange, y_f, Q0):
    """(y, psi, eps, loads outer, loads inner, N_f) of a wheelset's five scaled unknowns.  ``flange``:
    0 (free), +-1 (that flange in contact, q[0] = N_f / Q0) or a two-point tread contact
    ``(y_j, side, y^W before, y^W after)`` (``semismooth``): the wheelset at shift y_j, q[0] the share of
    that wheel's tread load on the second point."""
    if isinstance(flange, tuple):
        y_j, side, ya, yb = flange
        th = q[0]
        lo, li = {"tread": Q0 * q[3]}, {"tread": Q0 * q[4]}
        two = lo if side > 0 else li
        N = two.pop("tread")
        two[("tread", ya)], two[("tread", yb)] = (1.0 - th) * N, th * N
        return y_j, 1e-3 * q[1], 1e-3 * q[2], lo, li, 0.0
    y = flange * y_f if flange else 1e-3 * q[0]
    Nf = Q0 * q[0] if flange else 0.0
    lo, li = {"tread": Q0 * q[3]}, {"tread": Q0 * q[4]}
    if flange > 0:
        lo["flange"] = Nf
    elif flange < 0:
        li["flange"] = Nf
    return y, 1e-3 * q[1], 1e-3 * q[2], lo, li, Nf


def _wheelset(q, flange, y_f, x_i, prof, veh, trk, law):
    y, psi, eps, lo, li, Nf = _unpack_wheelset(q, flange, y_f, veh.wheel_load)
    contacts = (wheel_contacts(prof, veh, trk, law, +1, y, psi, eps, lo)
                + wheel_contacts(prof, veh, trk, law, -1, y, psi, eps, li))
    return WheelsetState(x_i, y, psi, eps, flange if isinstance(flange, int) else 0, Nf, contacts)


def _suspension(ws: WheelsetState, veh: Vehicle, trk: Track, yb: float, pb: float):
    R, x = trk.radius, ws.x
    F = -2.0 * veh.ky * (ws.y - yb - x * pb - x * x / (2.0 * R))
    M = -2.0 * veh.kx * veh.box_half_spacing ** 2 * (ws.psi - pb - x / R)
    return F, M


def _scale(r, Q0):
    return np.array(r) / Q0


def bogie_residual(z, flanges, y_f, prof, veh, trk, law, keep=None):
    """The 12 scaled residuals of the bogie (two wheelsets, then the frame's force and moment)."""
    yb, pb = 1e-3 * z[10], 1e-3 * z[11]
    out, Ff, Mf, states = [], 0.0, 0.0, []
    for i, x_i in enumerate((veh.semi_wheelbase, -veh.semi_wheelbase)):
        ws = _wheelset(z[5 * i:5 * i + 5], flanges[i], y_f, x_i, prof, veh, trk, law)
        ws.F_susp, ws.M_susp = _suspension(ws, veh, trk, yb, pb)
        ws.residual = wheelset_residual(ws.contacts, veh, trk, ws.F_susp, ws.M_susp)
        out += list(ws.residual)
        Ff -= ws.F_susp
        Mf -= ws.M_susp + x_i * ws.F_susp
        states.append(ws)
    a_unc, _ = trk.unbalanced()
    m_s = 2.0 * veh.wheel_load / 9.81 - veh.wheelset_mass
    Ff += 2.0 * m_s * a_unc
    Mf -= veh.secondary_yaw * (pb - 0.5 * veh.bogie_spacing / trk.radius)
    out += [Ff, Mf]
    if keep is not None:
        keep[:] = [states, yb, pb, (Ff, Mf)]
    return _scale(out, veh.wheel_load)


def wheelset_only_residual(z, flanges, y_f, prof, veh, trk, law, keep=None):
    """The five scaled residuals of a free wheelset (no suspension forces)."""
    ws = _wheelset(z, flanges[0], y_f, 0.0, prof, veh, trk, law)
    ws.residual = wheelset_residual(ws.contacts, veh, trk, 0.0, 0.0)
    if keep is not None:
        keep[:] = [[ws], np.nan, np.nan, ()]
    return _scale(ws.residual, veh.wheel_load)


def _start(veh, trk, lam0, n_ws, y_f):
    y0 = 1e3 * min(veh.r0 * veh.rolling_circle / (lam0 * trk.radius), 0.8 * y_f, 0.02)
    per = [y0, 0.0, 0.0, 1.0, 1.0]
    return np.array(per * n_ws + ([y0, 0.0] if n_ws == 2 else []), float)


def _starts(veh, trk, lam0, n_ws, y_f):
    """Starting points: pure rolling without flange contact; for the bogie also the leading
    outer flange in contact with the frame at the chord position (a tight curve), and the
    diagonal position (the trailing wheelset's inner flange in contact too: a very tight one)."""
    yield _start(veh, trk, lam0, n_ws, y_f), [0] * n_ws
    if n_ws == 2 and np.isfinite(y_f):
        a = veh.semi_wheelbase
        pb = 0.25 * y_f / a
        yield np.array([0.3, 1e3 * (a / trk.radius + pb), 0.0, 1.0, 1.0, 500 * y_f, 1e3 * (pb - a / trk.radius),
                        0.0, 1.0, 1.0, 750 * y_f, 1e3 * pb]), [1, 0]
        pb = y_f / a  # very tight: the trailing wheelset against the inner rail
        yield np.array([0.3, 1e3 * (a / trk.radius + pb), 0.0, 1.0, 1.0, 0.3, 1e3 * (pb - a / trk.radius),
                        0.0, 1.0, 1.0, 0.0, 1e3 * pb]), [1, -1]


def _equilibrium(fun_of, z, flanges, y_f, prof, veh, trk, law):
    """Equilibrium for a given start: the flange's active set iterated to a stable set.
    Returns (z, residual, flanges, [states, y_b, psi_b, frame residual], passes)."""
    from scipy.optimize import root  # lazy: brings in scipy

    seen = {tuple(flanges)}
    for passes in range(1, MAX_ACTIVE + 1):
        fun = safe_residual(fun_of, flanges, y_f, prof, veh, trk, law)
        sol = root(fun, z, method="hybr", options={"xtol": 1e-13, "maxfev": 4000, "factor": 0.5})
        z, r = newton(fun, sol.x)
        keep = []
        try:
            fun_of(z, flanges, y_f, prof, veh, trk, law, keep)
        except ValueError:
            return z, np.full(len(z), np.inf), flanges, None, passes
        change = False
        for i, ws in enumerate(keep[0]):
            if ws.flange == 0 and abs(ws.y) > y_f:
                flanges[i], z[5 * i], change = (1 if ws.y > 0 else -1), 0.2, True
            elif ws.flange != 0 and ws.flange_force < 0.0:
                flanges[i], z[5 * i], change = 0, 1e3 * ws.y * 0.98, True
        if not change:
            return z, r, flanges, keep, passes
        if tuple(flanges) in seen:  # cycling between flange sets: no admissible equilibrium from here
            return z, np.full(len(z), np.inf), flanges, None, passes
        seen.add(tuple(flanges))
    return z, np.full(len(z), np.inf), flanges, None, MAX_ACTIVE


def _continuation(fun_of, y_f, prof, veh, trk, law, lam0, n_ws, steps):
    """Equilibrium continued in curvature from a ten times larger radius: steps of
    (1/R - 1/(10 R)) / steps, halved (down to 1/64 of that) when a step does not converge."""
    k0, k1 = 0.1 / trk.radius, 1.0 / trk.radius
    far = dataclasses.replace(trk, radius=1.0 / k0)
    z, r, flanges, keep, passes = _equilibrium(fun_of, _start(veh, far, lam0, n_ws, y_f), [0] * n_ws, y_f, prof,
                                               veh, far, law)
    if keep is None:
        return z, r, flanges, keep, passes
    k, dk = k0, (k1 - k0) / steps
    good = (z, r, list(flanges), keep, passes)
    while k < k1 * (1 - 1e-12):
        kn = min(k + dk, k1)
        z, r, flanges, keep, passes = _equilibrium(fun_of, good[0].copy(), list(good[2]), y_f, prof, veh,
                                                   dataclasses.replace(trk, radius=1.0 / kn), law)
        if keep is None or np.max(np.abs(r)) > 1e-8:
            dk *= 0.5
            if dk < (k1 - k0) / (64 * steps):
                return z, r, flanges, None, passes
            continue
        k, good = kn, (z, r, list(flanges), keep, passes)
        dk *= 1.5
    return good


def _branches(found):
    """Notes on equilibria of ``found`` other than the first (a wheelset's shift or yaw differing by
    more than 0.01 mm or 0.01 mrad): the steady curving is then not unique from these starts."""
    out = []
    ref = found[0][3][0]
    for z, r, fl, keep, _ in found[1:]:
        dy = max(abs(a.y - b.y) for a, b in zip(ref, keep[0]))
        dp = max(abs(a.psi - b.psi) for a, b in zip(ref, keep[0]))
        if dy > 1e-5 or dp > 1e-5:
            out.append(f"another equilibrium: flange set {fl}, shifts {[round(1e3 * w.y, 2) for w in keep[0]]} mm, "
                       f"yaws {[round(1e3 * w.psi, 2) for w in keep[0]]} mrad (kept the first)")
    return out


def solve(prof: Profiles, veh: Vehicle, trk: Track, law: CreepLaw, bogie: bool = True,
          lam0: float = 0.1, steps: int = 8) -> CurvingSolution:
    """Steady curving of the leading bogie (bogie=True) or of one free wheelset.  Started in
    pure rolling (conicity lam0), and for a bogie also in flange contact; when neither
    converges, the semismooth complementarity form from where they stalled (``semismooth``: notes
    say so, name a two-point tread contact and another equilibrium found), and last continued in
    curvature 1/R from a ten times larger radius (``_continuation``)."""

    y_f = flange_shift(prof.wheel, prof.rail, trk.c, prof.edge)
    fun_of = bogie_residual if bogie else wheelset_only_residual
    n_ws = 2 if bogie else 1
    stalled, tried = [], []
    for z0, fl0 in _starts(veh, trk, lam0, n_ws, y_f):
        tried.append((z0.copy(), list(fl0)))
        z, r, flanges, keep, passes = _equilibrium(fun_of, z0, fl0, y_f, prof, veh, trk, law)
        if keep is not None and np.max(np.abs(r)) <= 1e-8:
            break
        if np.all(np.isfinite(z)):
            stalled.append((float(np.max(np.abs(safe_residual(fun_of, flanges, y_f, prof, veh, trk, law)(z)))), z.copy(),
                            list(flanges)))
    notes = []
    if keep is None or np.max(np.abs(r)) > 1e-8:
        stalled.sort(key=lambda s: s[0])
        found = semismooth(fun_of, [s[1:] for s in stalled] + tried, y_f, prof, veh, trk, law, n_ws)
        if found:
            z, r, flanges, keep, passes = found[0]
            notes.append("found by the semismooth (complementarity) fallback")
            notes += [f"two-point tread contact: wheel a{i + 1}{'o' if f[1] > 0 else 'i'} at a shift of "
                      f"{1e3 * f[0]:+.3f} mm, {100 * z[5 * i]:.1f} % of its tread load on y^W = {1e3 * f[3]:+.2f} mm"
                      for i, f in enumerate(flanges) if isinstance(f, tuple)]
            notes += _branches(found)
    if keep is None or np.max(np.abs(r)) > 1e-8:
        z, r, flanges, keep, passes = _continuation(fun_of, y_f, prof, veh, trk, law, lam0, n_ws, steps)
    res = float(np.max(np.abs(r)))
    if keep is None or not np.isfinite(res) or res > 1e-8:
        raise CurvingError(f"steady curving did not converge (largest residual {res:.2e} of the wheel load; "
                           f"R = {trk.radius:g} m, flange set {flanges})")
    for k, ws in enumerate(keep[0], start=1):
        for c in ws.contacts:
            if c.N < 0.0:
                raise CurvingError(f"wheel a{k}{'o' if c.side > 0 else 'i'}: its {c.point.zone} contact would pull "
                                   f"({1e-3 * c.N:.1f} kN): the wheel lifts off it (flange climbing or wheel unloading), "
                                   f"beyond the steady model (R = {trk.radius:g} m)")
    return CurvingSolution(keep[0], keep[1], keep[2], y_f, res, keep[3], passes, notes)


__all__ = ["CurvingError", "CurvingSolution", "WheelsetState", "solve", "box_loads", "TOL"]
