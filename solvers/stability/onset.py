"""Squeal onset: the smallest friction level at which the linearised time loop has a growing wheel
mode, and the probability that a friction climate's level exceeds it.  Pure functions.

Onset.  ``growth(mu)`` is the largest growth rate (1/s) of the closed-loop poles continuing the
wheel modes (``solvers.stability.screen``) at friction level mu.  A coarse scan over [lo, hi]
finds the first grid interval where it changes sign from < 0 to > 0; Brent's method
(``scipy.optimize.brentq``; R. P. Brent, Algorithms for Minimization without Derivatives, 1973,
ch. 4) then finds the zero crossing inside it.  The largest growth rate is continuous in mu as
long as the pole tracking does not lose a pole; if it jumps, brentq still returns a point of the
bracket's sign change (to ``xtol``), which is the verdict's threshold.  A window of instability
narrower than the scan's step can be missed (the scan's step is reported).

Exceedance.  With the friction level a mixture of conditions c (share w_c, level distribution
F_c: uniform on [a, b] or a normal N(m, s^2) truncated to [a, b]),
P(mu > x) = sum_c w_c (1 - F_c(x)), exactly (no sampling).
"""
from __future__ import annotations

import math
from typing import Callable, NamedTuple

import numpy as np
from scipy.optimize import brentq
from scipy.special import ndtr


class Onset(NamedTuple):
    mu: float          # the onset level; NaN when none in [lo, hi]
    below: bool        # growing already at lo (onset <= lo)
    lo: float
    hi: float
    step: float        # the coarse scan's step
    evaluations: int   # growth(mu) calls

    def text(self) -> str:
        """'0.487', '>0.8' (quiet over the scanned range) or '<0.1' (squeals at its lower end)."""
        if self.below:
            return f"<{self.lo:g}"
        return f">{self.hi:g}" if not math.isfinite(self.mu) else f"{self.mu:.4g}"


def find_onset(growth: Callable[[float], float], lo: float = 0.1, hi: float = 0.8, n: int = 8,
               xtol: float = 1e-3, quiet: Callable[[float], bool] | None = None) -> Onset:
    """The smallest mu in [lo, hi] where ``growth`` (module notes) crosses zero upwards: coarse scan
    on ``n`` equal steps, then brentq to ``xtol`` in the first bracket.  ``quiet(mu)``: a cheaper
    test, true only where no pole grows (growth(mu) <= 0: the count of growing poles is zero); the scan
    then skips ``growth`` at that level (only its sign is read there; brentq evaluates its bracket's ends)."""
    if not 0.0 < lo < hi:
        raise ValueError(f"find_onset: need 0 < lo < hi, got lo = {lo}, hi = {hi}")
    grid = np.linspace(lo, hi, int(n) + 1)
    calls = [0]

    def g(mu):
        calls[0] += 1
        return float(growth(float(mu)))

    def level(mu):
        return -math.inf if quiet is not None and quiet(float(mu)) else g(mu)

    prev = level(grid[0])
    if prev > 0:
        return Onset(math.nan, True, lo, hi, grid[1] - grid[0], calls[0])
    for a, b in zip(grid[:-1], grid[1:]):
        gb = level(b)
        if gb > 0:
            mu = brentq(g, a, b, xtol=xtol) if prev < 0 else float(a)
            return Onset(float(mu), False, lo, hi, grid[1] - grid[0], calls[0])
        prev = gb
    return Onset(math.nan, False, lo, hi, grid[1] - grid[0], calls[0])


def unstable_windows(growth: Callable[[float], float], onset: Onset, top: float, n: int, xtol: float = 1e-3,
                     quiet: Callable[[float], bool] | None = None) -> tuple:
    """The friction levels from ``onset`` up to ``top`` where ``growth`` > 0, as intervals (a, b), b = inf
    when it still grows at the last level of the scan's grid at or below ``top``: the onset's grid
    (``n`` steps on [onset.lo, onset.hi]) continued upwards, brentq at each sign change, ``quiet`` as in
    ``find_onset``.  A curve can squeal in a window of friction only (stable again above it): the
    probability of squeal is then the climate's share of the windows, not of everything above the onset."""
    start = onset.lo if onset.below else onset.mu
    if not math.isfinite(start):
        return ()
    g = lambda mu: float(growth(float(mu)))                                     # noqa: E731
    level = lambda mu: -math.inf if quiet is not None and quiet(float(mu)) else g(mu)   # noqa: E731
    grid = np.linspace(onset.lo, onset.hi, int(n) + 1)
    out, a, growing = [], start, True
    prev_x, prev_v = start, g(start) if onset.below else math.inf      # growing just above the onset
    for x in grid[(grid > start) & (grid <= top + 1e-9)]:
        v = level(x)
        if growing and v <= 0:
            out.append((a, float(brentq(g, prev_x, x, xtol=xtol))))
            growing = False
        elif not growing and v > 0:
            a, growing = (float(brentq(g, prev_x, x, xtol=xtol)) if prev_v < 0 else float(prev_x)), True
        prev_x, prev_v = float(x), v
    if growing:
        out.append((a, math.inf))
    return tuple(out)


def exceedance(x: float, shares, lo, hi, mean=None, sd=None) -> float:
    """P(mu > x) for a mixture of conditions (module notes): ``shares`` (sum 1), each on [lo, hi];
    ``mean``/``sd`` NaN (or None) for a uniform condition, else its truncated normal's parameters."""
    w = np.asarray(shares, float)
    a, b = np.asarray(lo, float), np.asarray(hi, float)
    m = np.full(w.shape, np.nan) if mean is None else np.asarray(mean, float)
    s = np.full(w.shape, np.nan) if sd is None else np.asarray(sd, float)
    F = np.empty(w.shape)
    for i in range(len(w)):
        if not np.isfinite(m[i]):                    # uniform on [a, b]
            F[i] = np.clip((x - a[i]) / (b[i] - a[i]), 0.0, 1.0)
        else:                                        # truncated normal
            pa, pb = ndtr((a[i] - m[i]) / s[i]), ndtr((b[i] - m[i]) / s[i])
            F[i] = np.clip((ndtr((min(max(x, a[i]), b[i]) - m[i]) / s[i]) - pa) / (pb - pa), 0.0, 1.0)
    return float(np.clip(np.sum(w * (1.0 - F)), 0.0, 1.0))


def weighted_median(values, weights) -> float:
    """The median of a discrete distribution (values with weights >= 0); NaN when all weights are 0."""
    v, w = np.asarray(values, float), np.asarray(weights, float)
    if w.sum() <= 0:
        return math.nan
    i = np.argsort(v)
    c = np.cumsum(w[i]) / w.sum()
    return float(v[i][np.searchsorted(c, 0.5)])
