"""Regularized friction curves mu_RF(s) (SPEC 4.4, thesis [4.36-4.37]).

For one Coulomb coefficient mu and one contact (its pressure field p3 on the
grid) the thesis runs TANG without structural dynamics through the slow ramp
gamma_y = -0.05 t / 2 s [4.36] and takes mu_RF = F2 / F3 at s = |gamma_y| v
[4.37].  The ramp is so slow that every step is a steady state, so the same
curve follows from steady-state TANG at chosen creepages.  The creepages are
placed with the full-slip creepage of the simplified (Johnson-Vermeulen /
Kalker) theory, gamma_sat = 3 mu F3 / k, where k = |dF2/dgamma_y| at zero
creepage is the no-slip creep stiffness (Kalker's c^2 G C22), computed here by
one TANG solve without slip on the same grid: 18 nodes in (0, 1.25 gamma_sat]
clustered towards zero creepage (where the curve bends most), 5 on the plateau
up to the ramp's end (|gamma_y| = 0.05).  Solved in order of increasing
creepage, each solve warm-started from the previous one (TANG's FFT-based Newton-Krylov
solver: a whole curve on the ~350-element wheel/rail contact takes ~0.1-0.2 s).

The curve is stored as arrays (s, mu_RF, slopes) of a shape-preserving piecewise-cubic
Hermite interpolant (Fritsch-Carlson: monotone between the nodes, flat at a node where the data
turn), evaluated by the njit function mu_rf().  A Coulomb curve is constant beyond its last
node (the full-slip plateau).

Any friction law (``solvers.contact.friction_laws``): with a slip-speed dependent law TANG
bounds each element's traction by mu(|s_local|) p3 (``tang.falling``), and the global curve
of a falling law rises to a peak and falls.  Its nodes: the same bend nodes placed with
the static coefficient mu(0) (the peak lies before full slip), then ``n_fall`` geometric
nodes up to the ramp's end, no monotone guard, and shape-preserving (Fritsch-Carlson)
slopes, with the falling branch's own slope at the last node.  A float or the 'coulomb'
law gives exactly the Coulomb curve above.

Beyond the last node a falling curve continues with the law's decay: the time loop's arrays of
such a curve (``solvers.contact.falling.with_law_tail``) end with a node at s = +inf holding the
asymptote mu_inf, and beyond the last finite node s_n ``mu_and_slope`` evaluates the exponential
tail mu_inf + (mu_n - mu_inf) exp(-(s - s_n) / s_c), s_c = (mu_n - mu_inf) / |mu'_n|: value and
slope continuous there.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from solvers.contact.friction_laws import FrictionLaw, as_law
from solvers.contact.tang import tang_steady

GAMMA_END = 0.05       # |gamma_y| at the end of the thesis' ramp [4.36]


class RFCurve(NamedTuple):
    s: np.ndarray           # slip velocity nodes [m/s], s[0] = 0
    mu_rf: np.ndarray       # F2 / F3 at the nodes [-], mu_rf[0] = 0
    slope: np.ndarray       # d mu_RF / ds at the nodes (monotone Hermite)
    gamma: np.ndarray       # |gamma_y| at the nodes
    F1_over_F3: np.ndarray  # residual longitudinal force (spin-free: ~0)
    stick_fraction: np.ndarray
    mu: float
    v: float
    gamma_sat: float        # full-slip creepage estimate 3 mu F3 / k
    creep_stiffness: float  # k = |dF2/dgamma_y| at zero creepage [N]
    law: FrictionLaw | None = None      # the friction law (None: Coulomb with mu)


def creep_stiffness(p3, dx, dy, v, E=210e9, nu=0.3) -> float:
    """|dF2/dgamma_y| at zero creepage (no slip: Kalker's linear theory c^2 G C22 on the
    grid), from one TANG solve with a friction bound too high to be reached."""
    gam = 1e-8
    sol = tang_steady(p3, dx, dy, v, 1e6, gamma_y=gam, E=E, nu=nu, full_output=False)
    return abs(sol.F2) / gam


def creepage_nodes(gamma_sat, n_bend=18, n_plateau=5, gamma_end=GAMMA_END):
    """|gamma_y| nodes: 0, n_bend in (0, 1.25 gamma_sat] (denser at small creepage),
    n_plateau geometric up to gamma_end."""
    k = np.arange(1, n_bend + 1) / n_bend
    bend = 1.25 * gamma_sat * k**1.5
    top = max(gamma_end, 3.0 * bend[-1])
    plateau = np.geomspace(bend[-1], top, n_plateau + 1)[1:]
    return np.concatenate([[0.0], bend, plateau])


def monotone_slopes(x, y, end_slope=0.0):
    """Fritsch-Carlson slopes of the shape-preserving cubic Hermite interpolant (PCHIP: monotone
    between the nodes, zero slope at a node that is a local extremum); ``end_slope`` at the last
    node (0: a plateau follows; None: the last interval's secant; a falling curve's own slope)."""
    h = np.diff(x)
    delta = np.diff(y) / h
    d = np.zeros_like(y)
    for k in range(1, len(x) - 1):
        if delta[k - 1] * delta[k] > 0.0:
            w1, w2 = 2 * h[k] + h[k - 1], h[k] + 2 * h[k - 1]
            d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k])
    d[0] = delta[0]             # one-sided at the ends (mu_RF rises linearly from 0)
    if len(x) > 2:
        d[-1] = delta[-1] if end_slope is None else end_slope
    else:
        d[-1] = delta[-1]
    return d


def rf_curve(p3, dx, dy, v, law_or_mu, E=210e9, nu=0.3, *, gammas=None, n_bend=18, n_plateau=5,
             n_fall=12) -> RFCurve:
    """Regularized friction curve mu_RF(s) = F2/F3 [4.37] for a Coulomb coefficient (float) or a
    ``FrictionLaw`` on the contact with pressures p3 (nx, ny) [Pa] (from NORM, any gap), grid
    dx x dy (dx = v dt), rolling speed v [m/s].  Negative lateral creepage as in the ramp
    [4.36], so F2 on the rail is positive.  A slip-speed dependent law: ``n_fall`` nodes on the
    falling branch up to the ramp's end (module notes)."""
    law = as_law(law_or_mu) if isinstance(law_or_mu, FrictionLaw) else None
    if law is not None and law.is_coulomb:
        law_or_mu = float(law.array[0])
    if law is None or law.is_coulomb:
        return _coulomb_curve(p3, dx, dy, v, float(law_or_mu), E, nu, gammas, n_bend, n_plateau, law)
    return _law_curve(p3, dx, dy, v, law, E, nu, gammas, n_bend, n_fall)


def _steady_ramp(p3, dx, dy, v, law_or_mu, E, nu, gam, F3):
    """Steady TANG at the creepages ``gam`` in increasing order, each warm-started from the one
    before (the slow ramp [4.36] as steady states): (F2/F3, F1/F3, stick fraction) per node."""
    mu_rf, f1, stick = np.zeros(len(gam)), np.zeros(len(gam)), np.zeros(len(gam))
    stick[0] = 1.0
    warm = None
    for i, g in enumerate(gam):
        if g == 0.0:
            continue
        sol = tang_steady(p3, dx, dy, v, law_or_mu, gamma_y=-g, E=E, nu=nu, warm=warm, full_output=False)
        warm = sol
        mu_rf[i], f1[i] = sol.F2 / F3, sol.F1 / F3
        stick[i] = sol.stick.sum() / max((p3 > 0).sum(), 1)
    return mu_rf, f1, stick


def _law_curve(p3, dx, dy, v, law, E, nu, gammas, n_bend, n_fall) -> RFCurve:
    """rf_curve of a slip-speed dependent law: nodes to the peak and along the falling branch."""
    p3 = np.asarray(p3, dtype=float)
    F3 = p3.sum() * dx * dy
    k = creep_stiffness(p3, dx, dy, v, E, nu)
    mu0 = law.mu_static
    g_sat = 3.0 * mu0 * F3 / k
    gam = creepage_nodes(g_sat, n_bend, n_fall) if gammas is None else np.sort(np.abs(gammas))
    mu_rf, f1, stick = _steady_ramp(p3, dx, dy, v, law, E, nu, gam, F3)
    s = gam * v
    return RFCurve(s, mu_rf, monotone_slopes(s, mu_rf, end_slope=None), gam, f1, stick, float(mu0), float(v),
                   float(g_sat), float(k), law)


def _coulomb_curve(p3, dx, dy, v, mu, E, nu, gammas, n_bend, n_plateau, law) -> RFCurve:
    """rf_curve for Coulomb friction mu (the thesis' curve)."""
    p3 = np.asarray(p3, dtype=float)
    F3 = p3.sum() * dx * dy
    k = creep_stiffness(p3, dx, dy, v, E, nu)
    g_sat = 3.0 * mu * F3 / k
    gam = creepage_nodes(g_sat, n_bend, n_plateau) if gammas is None else np.sort(np.abs(gammas))
    mu_rf, f1, stick = _steady_ramp(p3, dx, dy, v, mu, E, nu, gam, F3)
    mu_rf = np.maximum.accumulate(mu_rf)        # guard: rounding must not break monotonicity
    s = gam * v
    return RFCurve(s, mu_rf, monotone_slopes(s, mu_rf), gam, f1, stick, float(mu), float(v), float(g_sat), float(k),
                   law)


@numba.njit(cache=True)
def mu_and_slope(s, s_nodes, mu_nodes, slopes):
    """mu_RF(|s|) and its derivative d mu_RF / d|s|: shape-preserving cubic Hermite between the
    nodes; beyond the last node constant (derivative 0: the full slip plateau), or, for a curve
    whose last node is at s = +inf (a falling law, module notes), the exponential tail from the
    last finite node down to mu_nodes[-1]."""
    s = abs(s)
    n = s_nodes.shape[0]
    if s >= s_nodes[n - 1]:
        return mu_nodes[n - 1], 0.0
    k = np.searchsorted(s_nodes, s, side="right") - 1
    if k < 0:
        k = 0
    if k == n - 2 and s_nodes[n - 1] == np.inf:       # falling tail beyond the last finite node
        a = mu_nodes[k] - mu_nodes[n - 1]
        d = slopes[k]
        if a <= 0.0 or d >= 0.0:
            return mu_nodes[k], 0.0
        e = math.exp(d * (s - s_nodes[k]) / a)
        return mu_nodes[n - 1] + a * e, d * e
    h = s_nodes[k + 1] - s_nodes[k]
    t = (s - s_nodes[k]) / h
    t2, t3 = t * t, t * t * t
    val = ((2 * t3 - 3 * t2 + 1) * mu_nodes[k] + (t3 - 2 * t2 + t) * h * slopes[k]
           + (-2 * t3 + 3 * t2) * mu_nodes[k + 1] + (t3 - t2) * h * slopes[k + 1])
    der = ((6 * t2 - 6 * t) * (mu_nodes[k] - mu_nodes[k + 1]) / h + (3 * t2 - 4 * t + 1) * slopes[k]
           + (3 * t2 - 2 * t) * slopes[k + 1])
    return val, der


@numba.njit(cache=True)
def mu_rf(s, s_nodes, mu_nodes, slopes):
    """mu_RF at slip velocity |s| [m/s] (see ``mu_and_slope``)."""
    return mu_and_slope(s, s_nodes, mu_nodes, slopes)[0]
