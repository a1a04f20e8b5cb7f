"""Tangential contact compliances A_tau of the point-contact model (SPEC 4.3,
thesis [4.31-4.35]): u_tau = A_tau F_tau.

Per time step, from the previous step's tangential forces and the current
normal solution (the thesis' assumptions: full slip, traction shaped like the
pressure, ellipsoidal deformation):

    p_tau^fs  = p3 F_tau(t - dt) / F3(t)                              [4.32]
    u_tau^fs  = A_tau1 p_1^fs + A_tau2 p_2^fs   (half-space, Cerruti)  [4.33]
    mean u    = (2/3) max(u_tau^fs)      (half-ellipsoid volume / area) [4.35]
    A_tau     = mean u / F_tau(t - dt)                                  [4.34]

'max' is taken in the direction of F_tau, so A_tau > 0 for either sign.  If a
force is zero (first step) the unit-force limit is used.  Without the cross
influence (A_12 p_2 in u_1) A_tau depends on the pressure SHAPE only, i.e. on
xi3 alone for a fixed gap, so it can be tabulated along a NormTable.
"""
from __future__ import annotations

import functools

import numba
import numpy as np

from solvers.contact.influence import Convolver, tangential_kernels


@functools.lru_cache(maxsize=8)
def _convolver(shape: tuple, dx: float, dy: float, E: float, nu: float) -> Convolver:
    """The tangential influence convolver of a grid (cached by value: shape, dx, dy, E, nu)."""
    return Convolver(*tangential_kernels(shape[0], shape[1], dx, dy, E, nu))


def _conv(shape, dx, dy, E, nu):
    return _convolver(tuple(int(n) for n in shape), float(dx), float(dy), float(E), float(nu))


def contact_compliance(p3, F_prev, dx, dy, E=210e9, nu=0.3):
    """(A1, A2) [m/N] from the pressures p3 (nx, ny) [Pa] of the current step and the
    previous step's forces F_prev = (F1, F2) [N] on the rail [4.32-4.35]."""
    p3 = np.asarray(p3, dtype=float)
    F3 = p3.sum() * dx * dy
    if F3 <= 0.0:
        return 0.0, 0.0
    conv = _conv(p3.shape, dx, dy, E, nu)
    k11, k12, k22 = conv.hat
    shape_hat = conv.transform(p3 / F3)            # traction per unit force [1/m^2]
    F1, F2 = float(F_prev[0]), float(F_prev[1])
    small = 1e-12 * F3
    out = []
    for tau, (Ft, Fo, k_own, k_cross) in enumerate(((F1, F2, k11, k12), (F2, F1, k22, k12))):
        if abs(Ft) <= small:                       # unit-force limit, no cross term
            Ft, Fo = 1.0, 0.0
        u = conv.back(shape_hat * (k_own * Ft + k_cross * Fo))     # [4.33]
        u_max = np.max(u * np.sign(Ft)) * np.sign(Ft)              # extreme in the direction of F
        out.append((2.0 / 3.0) * u_max / Ft)                       # [4.35], [4.34]
    return out[0], out[1]


def compliance_table(xi3, pressures, dx, dy, E=210e9, nu=0.3):
    """A1(xi3), A2(xi3) for the pressure fields of a NormTable (unit forces, no cross
    terms): arrays for table_compliance()."""
    A = np.zeros((len(xi3), 2))
    for k, p in enumerate(pressures):
        if p.sum() > 0.0:
            A[k] = contact_compliance(p, (0.0, 0.0), dx, dy, E, nu)
    if (A[:, 0] == 0.0).any() and (A[:, 0] > 0.0).any():      # no contact: hold the first value
        first = np.argmax(A[:, 0] > 0.0)
        A[:first] = A[first]
    return A[:, 0].copy(), A[:, 1].copy()


@numba.njit(cache=True)
def table_compliance(xi3, xi3_nodes, A_nodes):
    """A_tau at xi3, linear between the nodes, held constant outside."""
    n = xi3_nodes.shape[0]
    if xi3 <= xi3_nodes[0]:
        return A_nodes[0]
    if xi3 >= xi3_nodes[n - 1]:
        return A_nodes[n - 1]
    k = np.searchsorted(xi3_nodes, xi3) - 1
    t = (xi3 - xi3_nodes[k]) / (xi3_nodes[k + 1] - xi3_nodes[k])
    return (1.0 - t) * A_nodes[k] + t * A_nodes[k + 1]
