"""Spin in the regularized point contact: equivalent creepages from Kalker's linear theory.

The point contact (``solvers.timeloop.kernel``) knows a creepage vector, not a slip field.  Spin
phi [1/m] (rigid slip w = (gamma_x - phi y, gamma_y + phi x) v, TANG's convention) enters it as
the equivalent creepages gamma_tau + L_tau phi, with L chosen so that the linear theory's forces
are exact: F = -C gamma - c_phi phi  =>  L = C^-1 c_phi, where C (2x2) is the creep stiffness
matrix dF/d(gamma_x, gamma_y) and c_phi = dF/dphi, both from steady TANG without slip on the
contact's own grid (three solves; Kalker's linear theory on a non-elliptic patch).  For an
elliptic patch with semi-axes a, b: L = (0, sqrt(ab) C23 / C22) with Kalker's coefficients, the
equivalent lateral creepage of Shen, Hedrick and Elkins ("A comparison of alternative creep
force models for rail vehicle dynamic analysis", Vehicle System Dynamics 12, 1983); the
resultant then saturates through the friction curve like a creepage.  Beyond the linear range
this is an approximation (spin saturates earlier than the creepage it is equivalent to):
tests/interaction/test_spin.py measures it against steady TANG with spin.
"""
from __future__ import annotations

import numpy as np

from solvers.contact.tang import tang_steady

_LINEAR = 1e-8       # creepage [-] / spin x patch size of the no-slip solves
_MU_NO_SLIP = 1e6    # a friction bound too high to be reached


def linear_creep_matrix(p3, dx, dy, v, E=210e9, nu=0.3):
    """(C, c_phi): the creep stiffness matrix C [N] (2x2: dF_i/d gamma_j, i, j = 1, 2) and the
    spin stiffness c_phi = dF/dphi [N m] at zero creepage, from TANG without slip."""
    p3 = np.asarray(p3, float)
    C = np.empty((2, 2))
    for j, kw in enumerate(({"gamma_x": _LINEAR}, {"gamma_y": _LINEAR})):
        sol = tang_steady(p3, dx, dy, v, _MU_NO_SLIP, E=E, nu=nu, full_output=False, **kw)
        C[:, j] = np.array([sol.F1, sol.F2]) / _LINEAR
    phi = _LINEAR / max(p3.shape[0] * dx, p3.shape[1] * dy)
    sol = tang_steady(p3, dx, dy, v, _MU_NO_SLIP, spin=phi, E=E, nu=nu, full_output=False)
    return C, np.array([sol.F1, sol.F2]) / phi


def spin_lengths(p3, dx, dy, v, E=210e9, nu=0.3) -> np.ndarray:
    """L = C^-1 c_phi [m] (2,): spin phi acts as the creepages L phi (module notes)."""
    C, c_phi = linear_creep_matrix(p3, dx, dy, v, E, nu)
    return np.linalg.solve(C, c_phi)
