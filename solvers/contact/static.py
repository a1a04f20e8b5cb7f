"""The static contact of a case's profiles: the potential area, the undeformed gap on the grid and
the static NORM solution at the preload (SPEC 4.1; thesis [4.16]-[4.24]).

The potential area starts from the gap's own extent at a Hertzian approach estimate and grows within
the profiles until the patch at twice the static approach (the NORM table's last node) stays inside it.
"""
from __future__ import annotations

import numpy as np

from solvers.contact.norm import approach_for_load, norm
from solvers.contact.surfaces import contact_gap, curvatures, potential_area

DY = 0.5e-3  # lateral element size (m)
GROW, MAX_TRIES = 1.4, 5  # potential area: growth per retry, retries


class ConformalContact(RuntimeError):
    """The static patch outgrows the potential area the profiles allow (too conformal a contact)."""


def static_contact(geo, E: float, nu: float, F_L: float, dx: float):
    """Potential area, gap and static NORM solution at the preload F_L:
    (x, y, gap, A, B, xi_static, static).  The area starts from the gap's own
    extent at an approach estimate (Hertz with the lateral curvature kept >=
    A/30, an overestimate for conformal gaps), with a 15 % margin, and grows
    (within the profiles) until the patch at twice the static approach (the
    NORM table's last node) does not reach its edge; it is then trimmed to
    that patch plus two elements on every side."""
    yw, Y = geo.contact.y_wheel, geo.contact.y_track
    A, B = curvatures(geo.r_wheel, geo.z_rail, yw, Y)
    Be = max(B, A / 30.0)
    Estar = E / (2 * (1 - nu**2))
    c_eq = (3 * F_L * 0.5 / np.sqrt(A * Be) / (4 * Estar)) ** (1 / 3)
    delta = c_eq**2 * 2 * np.sqrt(A * Be)  # Hertz approach (Johnson 4.2x, equivalent radius)
    a_half, lo, hi, lo_max, hi_max = potential_area(geo.r_wheel, geo.z_rail, yw, Y, delta, A, DY)
    lo, hi = max(1.15 * lo, lo_max), min(1.15 * hi, hi_max)

    def grid(a_half, lo, hi):
        nx = int(np.ceil(a_half / dx - 1e-9))
        ny0, ny1 = int(np.floor(lo / DY + 1e-9)), int(np.ceil(hi / DY - 1e-9))
        return np.arange(-nx, nx + 1) * dx, np.arange(ny0, ny1 + 1) * DY

    for _ in range(MAX_TRIES):
        x, y = grid(a_half, lo, hi)
        gap = contact_gap(geo.r_wheel, geo.z_rail, yw, Y, x, y)
        xi_static, static = approach_for_load(F_L, gap, dx, DY, E, nu)
        top = norm(gap, 2.0 * xi_static, dx, DY, E, nu, warm=static)  # the NORM table's last node
        if not top.touches_edge:
            # trim to the top node's patch plus two elements, then solve the static load again
            ix, iy = np.flatnonzero(top.contact.any(axis=1)), np.flatnonzero(top.contact.any(axis=0))
            a_half = max(-x[ix[0]], x[ix[-1]]) + 2 * dx
            x, y = grid(a_half, max(y[iy[0]] - 2 * DY, lo_max), min(y[iy[-1]] + 2 * DY, hi_max))
            gap = contact_gap(geo.r_wheel, geo.z_rail, yw, Y, x, y)
            xi_static, static = approach_for_load(F_L, gap, dx, DY, E, nu)
            return x, y, gap, A, B, xi_static, static
        C = top.contact
        if (C[:, 0].any() and lo <= lo_max + DY) or (C[:, -1].any() and hi >= hi_max - DY):
            break
        a_half, lo, hi = GROW * a_half, max(GROW * lo, lo_max), min(GROW * hi, hi_max)
    raise ConformalContact(f"at twice the static approach the contact patch reaches the edge of the potential area "
                       f"({1e3 * lo:+.1f} .. {1e3 * hi:+.1f} mm laterally: the wheel or rail profile ends there, or "
                       f"it is {MAX_TRIES} times enlarged); the profiles are too conformal here for this contact model")
