"""The curving equilibrium's fallback when the active-set iteration of ``solve`` stalls: the
unilateral contacts written as one continuous, piecewise smooth system and solved by MINPACK.

Two things make the plain iteration fail in tight or wet curves (the example line's C05, C11-C13,
C17, C22, C25, C26): (1) the flange's active set cycles between passes (the wheelset's shift wants
to pass the flange shift y_f, the flange's force then comes out negative); (2) on worn profiles the
tread contact of one wheel *jumps* between two local minima of the separation at a shift y_j
(``wheelrail.tread_jumps``): there the single-point model's residuals are discontinuous in y and
the equilibrium sits on the jump -- a two-point tread contact, its load shared by both points.

Both are complementarity conditions (shift at its bound, or the extra contact's load zero) and
are written here without an active set: each wheelset's first unknown w (mm) walks through
its states in order of increasing shift.  Away from the events w = 1e3 y (offset by the
plateaus passed); at each tread jump y_j a plateau of width ``PLATEAU`` in w holds the shift at
y_j while the load moves from the point before to the point after (share theta = 0 .. 1); past
+-1e3 y_f the wheelset sits at the flange shift with N_f / Q0 = the excess of |w|.  At every
switch both sides give the same residuals (the extra load being zero there), so the system is
continuous, and MINPACK's hybrid method (then Levenberg-Marquardt) crosses the switches within
one iteration.  The root is then polished by Newton steps and accepted on the same residuals
(< 1e-8 of the wheel load) as every other solution (``solve``).
"""
from __future__ import annotations

import numpy as np

from solvers.curving.roots import newton, safe_residual
from solvers.curving.wheelrail import tread_jumps

PLATEAU = 1.0   # width (in w, mm) of a two-point tread contact's load transfer


def _events(prof, trk, y_f):
    """The tread jumps of both wheels within the flange shifts: [(y_j, side, y^W before, y^W after)]."""
    ev = [(y, s, a, b) for s in (1, -1) for y, a, b in
          tread_jumps(prof.wheel, prof.rail, trk.c, prof.edge, s, min(y_f, 0.04))]
    return sorted(ev)


class Complementarity:
    """The map between w (one scaled unknown vector, 5 per wheelset + the frame's 2) and the
    active-set form (z, flanges) of ``solve.bogie_residual``, and the residual of w."""

    def __init__(self, fun_of, n_ws, y_f, prof, veh, trk, law):
        self.fun_of, self.n_ws, self.y_f = fun_of, n_ws, y_f
        self.args = (prof, veh, trk, law)
        self.ev = _events(prof, trk, y_f) if np.isfinite(y_f) else []
        self.n0 = sum(1 for e in self.ev if e[0] < 0.0)

    def _one(self, w):
        """(first unknown, state) of one wheelset's w[0]."""
        u = w + PLATEAU * self.n0
        for k, ev in enumerate(self.ev):
            a = 1e3 * ev[0] + PLATEAU * k
            if u < a:
                break
            if u <= a + PLATEAU:
                return (u - a) / PLATEAU, ev
        else:
            k = len(self.ev)
        y = 1e-3 * (u - PLATEAU * k)
        if abs(y) > self.y_f:
            return 1e3 * (abs(y) - self.y_f), (1 if y > 0 else -1)
        return 1e3 * y, 0

    def split(self, w):
        z, states = np.array(w, float), []
        for i in range(self.n_ws):
            z[5 * i], st = self._one(w[5 * i])
            states.append(st)
        return z, states

    def join(self, z, states):
        w = np.array(z, float)
        for i, st in enumerate(states):
            if isinstance(st, tuple):
                k = self.ev.index(st)
                w[5 * i] = 1e3 * st[0] + PLATEAU * (k + z[5 * i]) - PLATEAU * self.n0
                continue
            y = st * (self.y_f + 1e-3 * max(z[5 * i], 0.0)) if st else 1e-3 * z[5 * i]
            k = sum(1 for e in self.ev if e[0] < y)
            w[5 * i] = 1e3 * y + PLATEAU * (k - self.n0)
        return w

    def residual(self, w):
        z, states = self.split(w)
        return safe_residual(self.fun_of, states, self.y_f, *self.args)(z)


def semismooth(fun_of, starts, y_f, prof, veh, trk, law, n_ws):
    """Equilibria from ``starts`` ((z, flanges) pairs of the active-set form: where it stalled, its
    starting points): [(z, r, flanges, keep, 0), ...], each accepted (residual <= 1e-8 of Q0); after the
    first, one more start is tried, so that a second equilibrium (another branch) can be reported."""
    from scipy.optimize import root  # lazy: brings in scipy

    cp = Complementarity(fun_of, n_ws, y_f, prof, veh, trk, law)
    fun = cp.residual
    found, tries = [], 0
    for z0, fl0 in starts:
        if found and tries >= 1:
            break  # one more start after the first equilibrium: a check for another branch, not a search
        tries += bool(found)
        best = cp.join(z0, fl0)
        for method, opts in (("hybr", {"xtol": 1e-13, "maxfev": 3000, "factor": 0.5}),
                             ("lm", {"xtol": 1e-13, "ftol": 1e-14, "maxiter": 3000})):
            sol = root(fun, best, method=method, options=opts)
            if np.max(np.abs(fun(sol.x))) < np.max(np.abs(fun(best))):
                best = sol.x
            if np.max(np.abs(fun(best))) < 1e-6:
                break
        w, r = newton(fun, best)
        if not np.max(np.abs(r)) <= 1e-8:
            continue
        z, fl = cp.split(w)
        keep = []
        r = fun_of(z, fl, y_f, prof, veh, trk, law, keep)
        if np.max(np.abs(r)) <= 1e-8:
            found.append((z, r, fl, keep, 0))
    return found
