"""Data structures of Kalker's TANG (notes in ``solvers.contact.tang``): the solution of one
step, the problem's kinematics and options, and the transient predictor's history."""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

W_OFFSET = 1.0 / 6.0        # rigid slip evaluated at x_I + W_OFFSET dx (see the module notes)
QUADRATIC = 10.0            # bound of the Newton steps' quadratic constant (relative), for stopping
TOL = 1e-8                  # default: Newton step <= TOL * traction level, no set change


class TangentialContact(NamedTuple):
    p1: np.ndarray          # traction on the rail, longitudinal [Pa] (nx, ny)
    p2: np.ndarray          # traction on the rail, lateral [Pa]
    stick: np.ndarray       # stick elements (bool)
    slip: np.ndarray        # slip elements (bool); stick | slip = contact area
    s1: np.ndarray          # slip velocity of the rail relative to the wheel [m/s]
    s2: np.ndarray
    u1: np.ndarray          # tangential displacement difference at time t [m]
    u2: np.ndarray
    F1: float               # forces on the rail [N]
    F2: float
    iterations: int         # Newton steps in total
    converged: bool
    krylov: int = 0         # Krylov (CG / GMRES) steps in total
    u_ahead: np.ndarray | None = None    # (2, nx, ny): u(x + dx, t), the next step's transport term
    history: "History | None" = None    # transient: the last steps' changes (the next step's predictor)
    window: tuple | None = None          # (i0, i1, j0, j1): rows/columns where u1, u2, u_ahead are valid
    P: np.ndarray | None = None          # (2, nx, ny): p1, p2 are its rows (the next step reads it whole)
    U: np.ndarray | None = None          # (2, nx, ny): u1, u2 are its rows (every solution has P and U)


class History(NamedTuple):
    """The last transient steps' backward differences on the window (``tang.steps.differences``):
    d (2, ORDER, 2, wx, wy), row 0 tractions, row 1 displacements (d[:, 0] = the last change,
    d[:, 1] its change, ...), n of them valid; the order (0 .. ORDER) of the polynomial
    extrapolation that would have predicted the last step best, and its prediction of the next
    change on the grid, pred (2, 2, nx, ny) (tractions, displacements; zero off the window)."""
    d: np.ndarray
    n: int
    order: int
    window: tuple           # the working window of the step (the differences are valid there)
    pred: np.ndarray


ORDER = 3                   # highest order of the predictor (cubic)


class Rolling(NamedTuple):
    """The rolling problem of one step: grid dx (rolling direction) x dy [m], speed v [m/s],
    Coulomb coefficient mu, creepages gamma_x, gamma_y [-], spin [1/m]."""
    dx: float
    dy: float
    v: float
    mu: float
    gamma_x: float
    gamma_y: float
    spin: float


class TangOptions(NamedTuple):
    """Material and solver options of ``tang_steady`` / ``tang_transient``: E [Pa], nu (the
    bodies' common elastic constants); tol: the Newton iteration stops when no element changes set
    and the last step is below tol times the largest traction (or its remaining error is, by
    quadratic convergence); w_offset: where the rigid slip is evaluated, x_I + w_offset dx
    (module notes of ``solvers.contact.tang``); full_output: u1, u2 on the whole grid (one more FFT
    product), False: only on the window around the contact (``window``), zero elsewhere."""
    E: float = 210e9
    nu: float = 0.3
    tol: float = TOL
    w_offset: float = W_OFFSET
    full_output: bool = True
