"""Falling friction in the regularized point contact: the global curve mu_RF(s) of a falling
local law, with its tail beyond the last node (``friction.mu_and_slope``, module notes there).

A falling law's global curve rises through micro-slip to a peak and falls with the law in full
slip.  Its nodes are stored as for a Coulomb curve (s, mu_RF, shape-preserving Hermite slopes)
plus a last node at s = +inf holding the curve's asymptote; the slope at the last finite node is
the law's own (the tail continues it with value and slope continuous).

``tang_curve`` computes it: TANG with the local law (``friction.rf_curve(..., law)``, the peer of
CONTACT's falling laws) plus the tail (``with_law_tail``).  ``scaled_curve`` approximates it from
a Coulomb curve of the same contact: mu_RF(s) =
mu_RF^C(s) mu_law(s) / mu, the Coulomb curve's saturation times the law at the rigid slip
velocity.  This is exact in full slip (every element slips at |w|: F = mu_law(|w|) F3) and in the
linear range (both vanish with the same creep stiffness); in between it is an approximation in
the spirit of the point-contact squeal models with a falling creep curve (Heckl and Abrahams,
JSV 229, 2000; Meehan and Liu, JSV 413, 2018, an experimentally tuned creep curve that rises and
falls); on the default contact it is within 0.002 of TANG's curve, its slope within 3 % on the
falling branch (tests/interaction/test_falling.py).  Laws: ``friction_laws.get_friction_law``
(anything with .mu(s), .dmu(s)).
"""
from __future__ import annotations

import math
import numpy as np

from solvers.contact.friction import monotone_slopes, mu_rf, rf_curve

S_INF = 1e3          # m/s: where a law's asymptote is read (``law.mu(S_INF)``)


def is_falling(s_nodes) -> bool:
    """Whether a curve's arrays carry a falling tail (last node at s = +inf)."""
    return bool(np.isinf(np.asarray(s_nodes)[-1]))


def with_tail(s, mu, end_slope: float, mu_inf: float):
    """The arrays (s, mu, slopes) of a falling global curve from its finite nodes (s[0] = 0,
    mu[0] = 0), the slope at the last finite node (< 0) and the asymptote mu_inf < mu[-1]: the
    shape-preserving Hermite slopes and the node at +inf."""
    s, mu = np.asarray(s, float), np.asarray(mu, float)
    if not (end_slope < 0.0 and mu_inf < mu[-1]):
        raise ValueError(f"a falling tail needs end_slope < 0 and mu_inf < mu[-1]: {end_slope}, {mu_inf}, {mu[-1]}")
    d = monotone_slopes(s, mu, end_slope)
    return np.append(s, np.inf), np.append(mu, mu_inf), np.append(d, 0.0)


def with_law_tail(s, mu, slopes, law):
    """The arrays of a global curve of ``law`` (.mu, .dmu; finite nodes from full slip at the
    last node on, as ``friction.rf_curve(..., law)`` gives them) with the law's own decay beyond
    the last node: there mu_RF = mu_n mu_law(s) / mu_law(s_n) (full slip), so the slope at the
    last node is mu_n mu_law'(s_n) / mu_law(s_n) and the asymptote mu_n mu_law(inf) / mu_law(s_n)
    (the tail's exponential matches both; exact for an exponential law).  A law that does not
    fall at the last node, or a curve that already has its tail, is returned unchanged."""
    s, mu, slopes = (np.asarray(a, float) for a in (s, mu, slopes))
    if is_falling(s):
        return s, mu, slopes
    r = float(law.mu(s[-1]))
    d_end = mu[-1] * float(law.dmu(s[-1])) / r
    mu_inf = mu[-1] * float(law.mu(S_INF)) / r
    if not (d_end < 0.0 and mu_inf < mu[-1]):
        return s, mu, slopes
    return with_tail(s, mu, d_end, mu_inf)


def tang_curve(p3, dx, dy, v, law, E=210e9, nu=0.3):
    """The global curve (s, mu_RF, slopes) of ``law`` on the contact with pressures p3: TANG's
    (``friction.rf_curve``) with the law's tail beyond the last node."""
    cur = rf_curve(p3, dx, dy, v, law, E, nu)
    return with_law_tail(cur.s, cur.mu_rf, cur.slope, law)


def scaled_curve(s_nodes, mu_nodes, slopes, mu: float, law, *, n_fall: int = 24, s_end: float | None = None):
    """The global curve of the falling ``law`` (.mu(s), .dmu(s)) on the contact whose Coulomb
    curve (coefficient ``mu``) is (s_nodes, mu_nodes, slopes): mu_RF^C(s) mu_law(s) / mu (module
    notes), on the Coulomb nodes plus ``n_fall`` geometric nodes up to ``s_end`` (default: the
    Coulomb curve's last node), then the tail.  Returns (s, mu_RF, slopes) with s[-1] = inf."""
    s_nodes = np.asarray(s_nodes, float)
    top = float(s_nodes[-1]) if s_end is None else float(s_end)
    extra = np.geomspace(s_nodes[1], top, n_fall)
    s = np.unique(np.concatenate([s_nodes[s_nodes <= top], extra]))
    base = np.array([mu_rf(x, s_nodes, mu_nodes, slopes) for x in s])
    m = base * np.asarray(law.mu(s), float) / mu
    c_end = base[-1] / mu
    return with_tail(s, m, c_end * float(law.dmu(top)), c_end * float(law.mu(S_INF)))


def tail_decay(s_nodes, mu_nodes, slopes) -> float:
    """The tail's decay velocity s_c [m/s] of a falling curve (inf for a plateau)."""
    a, d = mu_nodes[-2] - mu_nodes[-1], slopes[-2]
    return a / -d if (is_falling(s_nodes) and a > 0 and d < 0) else math.inf
