"""Inputs of the time loop (SPEC 3.1, 4.1-4.4): the wheel's modal data, the contact model of a
case, the reference (steady rolling) state, and the loop's parameters as one named structure.

Pure numerics; the physics of the loop is in the notes of ``solvers.timeloop.interaction``.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from solvers.contact.friction import mu_rf
from solvers.contact.norm import table_force, norm_table
from solvers.contact.compliance import compliance_table

MAX_DURATION = 8.0          # s, SPEC 6
EPS_SLIP = 1e-9             # m/s, regularisation of the slip direction (curves with mu(0) > 0)
DEFAULT_KICK = 0.01         # N s, lateral impulse that seeds the instability (start='steady')
FULL_SLIP = 0.99            # contact state 2 when mu_RF(s) >= FULL_SLIP * plateau
KALKER_TOL = 1e-5           # TANG's tolerance in the time loop: the eps of CONTACT's own examples; 8 s of the default
                            # case give L_F2 and f as at 1e-6 to 0.001 dB and 0.01 Hz (docs/benchmarks.md)


class WheelModes(NamedTuple):
    """Modal data of the wheel at the contact point (SPEC 3.1): f_r (M,) Hz, modal_mass (M,) kg,
    zeta (M,), phi (M, 2) = (Phi_2, Phi_3).  Empty arrays: a rigid, fixed wheel."""
    f_r: np.ndarray
    modal_mass: np.ndarray
    zeta: np.ndarray
    phi: np.ndarray


class ContactModel(NamedTuple):
    """The contact of a case (SPEC 4.1-4.4) as arrays (keys of build/cases/<case>/contact.npz).

    xi3_nodes, q_nodes: NORM table (approach [m], q = F3^(2/3)); A1_nodes, A2_nodes: tangential
    compliances over the approach [m/N]; s_nodes, mu_nodes, slopes: the regularised friction
    curve mu_RF(s) (monotone Hermite, ``friction.mu_rf``); mu: its Coulomb coefficient.
    For the reference drivers: F3_nodes and pressure_nodes (the table's pressure fields, for
    Kalker's TANG), gap, dx, dy, E, nu (per-step NORM, TANG).  spin_length (2,) [m]: spin's
    equivalent creepages per 1/m (``solvers.contact.spin``; None: computed from the pressure at
    the static approach when a run has spin); law: the friction law of a non-Coulomb curve, for
    Kalker's TANG in the reference loop (None: Coulomb with mu)."""
    xi3_nodes: np.ndarray
    q_nodes: np.ndarray
    A1_nodes: np.ndarray
    A2_nodes: np.ndarray
    s_nodes: np.ndarray
    mu_nodes: np.ndarray
    slopes: np.ndarray
    mu: float
    F3_nodes: np.ndarray | None = None
    pressure_nodes: np.ndarray | None = None
    gap: np.ndarray | None = None
    dx: float | None = None
    dy: float | None = None
    E: float = 210e9
    nu: float = 0.3
    spin_length: np.ndarray | None = None
    law: object | None = None      # the friction law for Kalker's TANG (a FrictionLaw; None: Coulomb mu)


def curve_label(law) -> str:
    """The name of a friction curve: ``coulomb(mu=0.35)`` for a float (the Coulomb coefficient),
    else ``<name>(<param>=<value>, ...)`` of anything with ``.name`` and ``.params`` (a
    ``FrictionLaw``, the pipeline's resolved friction), parameters sorted, values to 10 digits."""
    if isinstance(law, (int, float, np.floating, np.integer)):
        name, params = "coulomb", {"mu": float(law)}
    else:
        name, params = str(law.name), dict(law.params)
    return name + "(" + ", ".join(f"{k}={float(v):.10g}" for k, v in sorted(params.items())) + ")"


def curve_labels(arrays) -> list[str]:
    """The labels of the friction curves in a contact artifact's arrays (``rf_label``; artifacts
    without it hold Coulomb curves named by ``mu_values``)."""
    keys = set(arrays.files) if hasattr(arrays, "files") else set(arrays)
    if "rf_label" in keys:
        return [str(x) for x in np.asarray(arrays["rf_label"])]
    return [curve_label(float(m)) for m in np.asarray(arrays["mu_values"], float)]


def contact_model(arrays, law) -> ContactModel:
    """ContactModel from the contact stage's arrays (a dict or NpzFile with the keys of
    contact.npz) with the friction curve of ``law``: a float (the Coulomb coefficient) or a
    friction law (``.name``, ``.params``), selected by its ``curve_label`` among the curves held.
    The curve is taken as stored (a falling law's curve rises to a peak and falls: nothing
    here makes it monotone)."""
    labels = curve_labels(arrays)
    want = curve_label(law)
    if want not in labels:
        raise ValueError(f"no friction curve for {want}; available: {labels}")
    i = labels.index(want)
    mus = np.asarray(arrays["mu_values"], float)
    n = int(arrays["rf_n"][i])
    keys = set(arrays.files) if hasattr(arrays, "files") else set(arrays)
    f = lambda k: np.ascontiguousarray(np.asarray(arrays[k], float)) if k in keys else None   # noqa: E731
    curve = f("rf_s")[i, :n].copy(), f("rf_mu")[i, :n].copy(), f("rf_slope")[i, :n].copy()
    solver_law = _solver_law(law)
    if solver_law is not None:                 # issue 26: a falling law's decay beyond the last node
        from solvers.contact.falling import with_law_tail  # here: Make's DEPS of the module's other entry points stay without it

        curve = with_law_tail(*curve, solver_law)
    return ContactModel(f("xi3_nodes"), f("q_nodes"), f("A1_nodes"), f("A2_nodes"), *curve,
                        float(mus[i]), f("F3_nodes"), f("pressure_nodes"), f("gap"),
                        float(arrays["dx"]) if "dx" in keys else None,
                        float(arrays["dy"]) if "dy" in keys else None, law=solver_law)


def _solver_law(law):
    """The solver's law object (.mu, .dmu) of ``law`` when it is not Coulomb (a ``FrictionLaw``, or
    anything with ``solver_law()`` giving one), else None."""
    if hasattr(law, "solver_law"):
        law = law.solver_law()
    if isinstance(law, (int, float, np.floating, np.integer)) or getattr(law, "is_coulomb", True):
        return None
    return law if hasattr(law, "mu") and hasattr(law, "dmu") else None


def refine_table(contact: ContactModel, xi3_nodes) -> ContactModel:
    """The contact with its normal table (F3, q, pressures) and compliance table (A1, A2)
    recomputed by NORM and [4.32]-[4.35] at ``xi3_nodes`` inside [min, max] of the given nodes
    (the old nodes outside that range are kept).  The table's interpolation error (linear in
    q = F3^(2/3), ~5e-5 midway between the contact stage's 41 nodes at the working point)
    falls below 1e-6 for a node step of ~5e-4 of the static approach (coarser steps leave ~1e-6
    where a grid element enters the patch and F3(xi3) has a kink): use it to make the table mode
    reproduce per-step NORM to 1e-6 over the range a run visits."""
    if contact.gap is None or contact.dx is None or contact.dy is None:
        raise ValueError("refine_table needs the contact's gap, dx and dy")
    new = np.sort(np.asarray(xi3_nodes, float))
    old = contact.xi3_nodes
    keep = (old < new[0]) | (old > new[-1])
    xs = np.sort(np.concatenate([old[keep], new]))
    t = norm_table(contact.gap, xs, contact.dx, contact.dy, contact.E, contact.nu)
    A1, A2 = compliance_table(xs, t.p, contact.dx, contact.dy, contact.E, contact.nu)
    return contact._replace(xi3_nodes=t.xi3, q_nodes=t.q, F3_nodes=t.F3, pressure_nodes=t.p, A1_nodes=A1,
                            A2_nodes=A2)


class PointTables(NamedTuple):
    """The contact tables the numba loop reads (SPEC 4.1, 4.3, 4.4): NORM table (xi3_nodes [m],
    q_nodes = F3^(2/3)), tangential compliances A1_nodes, A2_nodes [m/N] over the approach, and the
    friction curve mu_RF (s_nodes [m/s], mu_nodes, slopes).  Read only."""
    xi3_nodes: np.ndarray
    q_nodes: np.ndarray
    A1_nodes: np.ndarray
    A2_nodes: np.ndarray
    s_nodes: np.ndarray
    mu_nodes: np.ndarray
    slopes: np.ndarray


def point_tables(c: ContactModel) -> PointTables:
    """The arrays of ``c`` the numba loop needs."""
    return PointTables(c.xi3_nodes, c.q_nodes, c.A1_nodes, c.A2_nodes, c.s_nodes, c.mu_nodes, c.slopes)


class LoopParams(NamedTuple):
    """What stays fixed during one run (SI units; read only in the loop).

    n_steps: steps to run at most; dt [s]; v [m/s]; xi3_static: static approach [m]; slip_sign:
    +1 or -1 (sign of the structural term of [4.30]); eps [m/s]: slip-direction regularisation;
    gx, gy: creepage per step (one value, or a history whose last value is held); F_ref (3,) [N]
    and u_ref (2,) [m]: the reference state; kick (2,) [N]: force added to the deviations during
    the first step; spin (per step, like gx) [1/m] and spin_length (2,) [m]: the point contact
    adds spin_length * spin to (gx, gy) (equivalent creepages), Kalker's TANG takes the spin."""
    n_steps: int
    dt: float
    v: float
    xi3_static: float
    slip_sign: float
    eps: float
    gx: np.ndarray
    gy: np.ndarray
    F_ref: np.ndarray
    u_ref: np.ndarray
    kick: np.ndarray
    spin: np.ndarray = np.zeros(1)
    spin_length: np.ndarray = np.zeros(2)


def static_approach(contact: ContactModel, preload: float) -> float:
    """The approach at which the NORM table gives F3 = preload (bisection on the monotone table)."""
    xs = contact.xi3_nodes
    lo, hi = float(xs[0]), float(xs[-1])
    while table_force(hi, xs, contact.q_nodes) < preload:
        hi = lo + 2.0 * (hi - lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if table_force(mid, xs, contact.q_nodes) < preload:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-16 * abs(hi):
            break
    return 0.5 * (lo + hi)


def steady_forces(contact: ContactModel, v: float, gamma_x: float, gamma_y: float, F3: float,
                  eps: float = 0.0) -> np.ndarray:
    """Steady rolling forces of the point-contact model at rigid slip w = (gamma_x, gamma_y) v:
    F_tau = -mu_RF(|w|) F3 w_tau / sqrt(|w|^2 + eps^2); returns (F1, F2, F3)."""
    w1, w2 = gamma_x * v, gamma_y * v
    s = math.hypot(w1, w2)
    r = math.sqrt(s * s + eps * eps)
    q = mu_rf(s, contact.s_nodes, contact.mu_nodes, contact.slopes) / r if r > 0 else 0.0
    return np.array([-F3 * q * w1, -F3 * q * w2, F3])


def per_step(a, n_steps: int) -> np.ndarray:
    """A creepage as a contiguous per-step array (one value, or >= n_steps values)."""
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(a, float)))
    if a.size not in (1,) and a.size < n_steps:
        raise ValueError(f"a creepage history must have one value or >= {n_steps} values, got {a.size}")
    return a
