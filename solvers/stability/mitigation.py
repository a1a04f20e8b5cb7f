"""Mitigation what-ifs of a squealing wheel: the friction coefficient below which it stops
squealing and the modal damping its squealing modes would need.  Pure functions on arrays.

Friction at any coefficient.  With Coulomb's law the steady tangential problem of Kalker's
theory (TANG, [3.8]-[3.13]) is homogeneous of degree one in (mu, creepage, tangential
traction): the traction bound mu p3 and the slip both scale with c when mu and the creepage
do, the elastic displacement is linear in the traction, so the stick/slip partition is the
same and F2 scales with c.  Hence the regularized curve [4.37] at mu follows exactly from the
one at mu_ref: mu_RF(s; mu) = (mu / mu_ref) mu_RF(s mu_ref / mu; mu_ref), with unchanged slopes
d mu_RF / d s (``coulomb_curve_at``; checked against a direct TANG run in the tests).

Threshold.  ``threshold`` bisects a monotone yes/no verdict (e.g. "the stability screen
finds a growing wheel mode") over a bracket [lo, hi] with verdict(lo) False and verdict(hi)
True, to an absolute tolerance.

Damping.  ``screen_outcome`` turns the screen's closed-loop poles into the outcome the
damping procedure (``solvers.study.damping_procedure``, SPEC 7) asks of a simulation, so that
procedure can run on the screen (a growing pole at a wheel mode = squeal at its frequency).
"""
from __future__ import annotations

import math
from typing import Callable, NamedTuple

import numpy as np
from solvers.study import Outcome


def coulomb_curve_at(s_nodes, mu_nodes, slopes, mu_ref: float, mu: float):
    """(s, mu_RF, slope) of the regularized Coulomb friction curve at ``mu`` from the one at
    ``mu_ref`` (module notes: exact for Kalker's theory with Coulomb friction)."""
    if not (mu > 0 and mu_ref > 0):
        raise ValueError(f"friction coefficients must be > 0 (mu = {mu}, mu_ref = {mu_ref})")
    c = mu / mu_ref
    return (np.asarray(s_nodes, float) * c, np.asarray(mu_nodes, float) * c, np.asarray(slopes, float).copy())


class Bracket(NamedTuple):
    """The threshold lies in (quiet, squeal]: verdict(quiet) is False, verdict(squeal) True."""
    quiet: float
    squeal: float
    evaluations: int

    @property
    def value(self) -> float:
        return 0.5 * (self.quiet + self.squeal)


def threshold(verdict: Callable[[float], bool], lo: float, hi: float, tol: float = 1e-3,
              max_iter: int = 60) -> Bracket:
    """Bisection of a monotone verdict (False at ``lo``, True at ``hi``) to ``hi - lo <= tol``.
    Raises ValueError when the bracket does not hold (the caller reports "squeals at the lowest
    value tried" or "quiet at the highest")."""
    n = 0
    if verdict(hi) is not True:
        raise ValueError(f"no threshold in [{lo}, {hi}]: quiet at the upper end")
    n += 1
    if verdict(lo) is not False:
        raise ValueError(f"no threshold in [{lo}, {hi}]: squeals at the lower end")
    n += 1
    for _ in range(max_iter):
        if hi - lo <= tol:
            break
        mid = 0.5 * (lo + hi)
        n += 1
        if verdict(mid):
            hi = mid
        else:
            lo = mid
    return Bracket(lo, hi, n)


def first_squeal(verdict: Callable[[float], bool], values) -> float:
    """The first value of an ascending scan at which the verdict is True (NaN if none): the
    direct scan a bisection is checked against."""
    for v in values:
        if verdict(float(v)):
            return float(v)
    return math.nan


def growing_wheel_root(roots, keep=None):
    """The fastest growing closed-loop pole at a wheel mode (``Root`` with mode >= 0 and
    sigma > 0; only modes in ``keep`` when given), or None."""
    keep = None if keep is None else set(int(k) for k in keep)
    for r in roots:                       # sorted fastest growing first (solvers.stability.screen)
        if r.mode >= 0 and r.sigma > 0 and (keep is None or r.mode in keep):
            return r
    return None


def screen_outcome(roots, level: float, keep=None):
    """The damping procedure's ``Outcome`` from the screen's poles: a growing pole at a wheel
    mode squeals (L_F2 reported as ``level``, the squeal criterion's threshold, and its
    frequency as the dominant one); none: quiet (L_F2 = -inf, frequency NaN)."""
    r = growing_wheel_root(roots, keep)
    return Outcome(float(level), float(r.f_hz)) if r is not None else Outcome(-math.inf, math.nan)
