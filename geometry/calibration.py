"""Calibration of the worn wheel and rail profiles to the thesis' contact
points (thesis [4.1], SPEC 2), and the checks it was not fitted to.

The thesis' contact positions come from measured worn profiles that are not
available.  A worn C20 tread and a worn BV50 head are made from the new ones
by the parametric wear of ``geometry.wear`` (8 parameters: hollow band of
the wheel; top band and gauge-face wear of the rail) and fitted so that the
rigid contact search (``geometry.contact_point``) puts the wheel contact at
the tabulated y^W for the three offsets.

Convention (docs/validation/31_contact_positions.md, ``solvers.constants``):
y^W and y^R both + toward the field side (SPEC 2); a rigid wheelset moved by
dy_WR puts wheel point y^W over track point Y = y^W + c + dy_WR
(``contact_point.wheel_shift``).  The printed table satisfies this with one
c only when its y^W is negated (it is printed + toward the flange): targets
y^W = -5, +4, +32 mm at dy_WR = -5, -10, -15 mm, with the rail points as
printed (-16, -12, +12 mm).  c, the rolling circle's position over the rail
centre for the centred wheelset, follows from the table itself as the mean
of y^R - dy_WR - y^W = -6, -6, -5 mm: c = -17/3 mm.  c is therefore derived
from the data, not fitted; the wear parameters are fitted.

Objective: sum over the offsets of (y^W - target)^2 / (1 mm)^2 (each term
capped at 400, i.e. 20 mm, so a position on the wrong side of a jump does not
dominate) + LAMBDA * sum of the three wear depths^2 / (1 mm)^2 (the least
wear that reproduces the points) + a penalty ((|dy^W| - JUMP) / 1 mm)^2 when
the contact point moves by |dy^W| > JUMP for an offset change of +-STABLE:
the thesis' offsets are given to the millimetre, so a fitted position must
not sit at the brink of a jump (to another part of the tread or the flange);
a penalty ((MARGIN - m) / 0.02 mm)^2 when another contact zone
(``contact_point.second_zone``) is only m < MARGIN above the contact, so
that the static load (approach ~0.09 mm) gives one patch, as the thesis'
single contact point assumes;
and a penalty (kappa_max / 0.5 1/m)^2 when the worn head's curvature is
positive (a groove) anywhere on |y^R| < CONVEX_HALF_WIDTH: worn rail heads
flatten, they do not become concave (without it the least-wear fit grooves
the crown by 1.1 mm).
Differential evolution (seeded, reproducible), then Nelder-Mead.  The fit works on uniform grids with linear
interpolation (fast); ``verify`` repeats the search with the pipeline's
spline profiles.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solvers.constants import THESIS_CONTACT_POINTS_FIELD, thesis_rolling_circle_offset

from geometry.contact_point import second_zone, wheel_shift
from geometry.wear import RailWear, WheelWear, offset_inward, wheel_normals, worn_rail

# thesis [4.1] in the project's convention (y^W = -printed): dy_WR -> (y^W, y^R), m
THESIS_POSITIONS = THESIS_CONTACT_POINTS_FIELD
LAMBDA = 0.05
STABLE = 0.5e-3  # m: offset change the fitted positions must survive ...
JUMP = 3e-3  # m: ... without the contact point moving more than this
CONVEX_HALF_WIDTH = 0.022  # m: the worn head stays convex here (crown and shoulders)
MARGIN = 0.15e-3  # m: another contact zone must be this much further from the rail than the contact
NAMES = ("hollow_depth", "hollow_centre", "hollow_half_width", "top_depth", "top_centre", "top_half_width",
         "gauge_depth", "gauge_start")
BOUNDS = ((0.0, 3e-3), (-0.03, 0.045), (0.01, 0.06),     # wheel hollow band
          (0.0, 3e-3), (-0.025, 0.025), (0.01, 0.05),     # rail top band
          (0.0, 8e-3), (0.020, 0.035))                    # rail gauge-face wear: from the outer shoulder
GRID = 5e-5


def rolling_circle_offset() -> float:
    """c (m): mean over the table of y^R - dy_WR - y^W (field-positive y^W)."""
    return thesis_rolling_circle_offset()


def split(p) -> tuple[WheelWear, RailWear]:
    return WheelWear(*p[:3]), RailWear(*p[3:])


@dataclass
class FitProblem:
    """The fast forward model: new wheel on a uniform grid (y, z = r - r0),
    the new rail head curve (``rail_head_curve``), inclination (tan), c, and
    targets {dy_WR: y^W}."""

    wheel_y: np.ndarray
    wheel_z: np.ndarray
    rail_curve: dict
    inclination: float
    c: float
    targets: dict

    def __post_init__(self):
        self._n = wheel_normals(self.wheel_y, self.wheel_z)

    def profiles(self, p):
        """(worn wheel z on wheel_y, worn rail (Y, z) in the track frame);
        sets ``self.rail_kappa_max``, the worn head's largest curvature (1/m)
        on |y^R| < CONVEX_HALF_WIDTH."""
        ww, rw = split(p)
        y, z = offset_inward(self.wheel_y, self.wheel_z, self._n, ww.depth(self.wheel_y))
        if np.any(np.diff(y) <= 0):
            raise ValueError("worn wheel folds over")
        ry, rz = worn_rail(self.rail_curve, rw)
        run = np.abs(ry) < CONVEX_HALF_WIDTH
        self.rail_kappa_max = float(np.gradient(np.gradient(rz, ry), ry)[run].max())
        a = np.arctan(self.inclination)
        return np.interp(self.wheel_y, y, z), (ry * np.cos(a) - rz * np.sin(a), ry * np.sin(a) + rz * np.cos(a))

    def contact(self, zw, rail, dy: float, margin: bool = False):
        """y^W of the rigid contact at offset dy (grid minimum, parabola
        refined); with ``margin``, (y^W, extra separation of the nearest other
        contact zone, MARGIN if none within MARGIN)."""
        y = self.wheel_y
        sep = -zw - np.interp(y + wheel_shift(self.c, dy), rail[0], rail[1], left=np.nan, right=np.nan)
        sep = np.where(np.isnan(sep), np.inf, sep)
        i = int(np.argmin(sep))
        yc = float(y[i])
        if 0 < i < len(y) - 1 and np.isfinite(sep[i - 1:i + 2]).all():
            a, b, c = sep[i - 1:i + 2]
            if a - 2 * b + c > 0:
                yc = float(y[i] + 0.5 * (a - c) / (a - 2 * b + c) * (y[1] - y[0]))
        if not margin:
            return yc
        second = second_zone(y, sep, i, MARGIN)
        return yc, MARGIN if second is None else second[1]

    def objective(self, p) -> float:
        try:
            zw, rail = self.profiles(p)
        except ValueError:
            return 1e4
        err = 0.0
        for dy, t in self.targets.items():
            yc, m = self.contact(zw, rail, dy, margin=True)
            err += min(((yc - t) / 1e-3) ** 2, 400.0) + (max(0.0, MARGIN - m) / 2e-5) ** 2
            for d in (-STABLE, STABLE):
                move = abs(self.contact(zw, rail, dy + d) - yc)
                err += min((max(0.0, move - JUMP) / 1e-3) ** 2, 400.0)
        err += (max(0.0, self.rail_kappa_max) / 0.5) ** 2
        return err + LAMBDA * ((p[0] / 1e-3) ** 2 + (p[3] / 1e-3) ** 2 + (p[6] / 1e-3) ** 2)


def fit(problem: FitProblem, seed: int = 1, popsize: int = 20, maxiter: int = 300) -> dict:
    """Fitted wear parameters (dict by NAMES), objective and contact points."""
    from scipy.optimize import differential_evolution, minimize  # lazy: brings in scipy

    de = differential_evolution(problem.objective, BOUNDS, seed=seed, popsize=popsize, maxiter=maxiter,
                                tol=1e-10, polish=False)
    nm = minimize(problem.objective, de.x, method="Nelder-Mead",
                  options={"xatol": 1e-8, "fatol": 1e-8, "maxiter": 4000})
    p = nm.x if nm.fun <= de.fun else de.x
    p = np.clip(p, [b[0] for b in BOUNDS], [b[1] for b in BOUNDS])
    zw, rail = problem.profiles(p)
    found = {dy: problem.contact(zw, rail, dy) for dy in problem.targets}
    moves = {dy: max(abs(problem.contact(zw, rail, dy + d) - found[dy]) for d in (-STABLE, STABLE))
             for dy in problem.targets}
    margins = {dy: problem.contact(zw, rail, dy, margin=True)[1] for dy in problem.targets}
    return {"params": dict(zip(NAMES, map(float, p))), "x": p, "objective": float(problem.objective(p)),
            "evaluations": int(de.nfev + nm.nfev), "contacts": found, "moves": moves, "margins": margins,
            "rail_kappa_max": problem.rail_kappa_max}


def jump_offsets(contact_of_dy, lo: float, hi: float, step: float = 1e-4, jump: float = 2e-3) -> list:
    """Offsets in [lo, hi] (m) where the contact point jumps by more than
    ``jump`` between neighbouring offsets ``step`` apart: [(dy_before,
    y_before, dy_after, y_after)] (``contact_of_dy`` returns y^W or None)."""
    dys = np.arange(hi, lo - 1e-12, -step)
    ys = [contact_of_dy(d) for d in dys]
    out = []
    for k in range(1, len(dys)):
        a, b = ys[k - 1], ys[k]
        if a is None or b is None or abs(b - a) > jump:
            out.append((float(dys[k - 1]), a, float(dys[k]), b))
    return out
