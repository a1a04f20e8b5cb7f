"""The time loop's driver (notes in ``solvers.timeloop.interaction``): a run's settings as one named
structure, the reference state, the structures' per-step objects, the choice between the numba
loop and the Python reference loop, and the result."""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from solvers.contact.compliance import table_compliance
from solvers.wheel.modal_filter import ModalFilter, modal_filter
from solvers.timeloop.partitioned import DEFAULT_BLOCK, PartitionedConvolver, partitioned_convolver
from solvers.timeloop.inputs import DEFAULT_KICK, EPS_SLIP, MAX_DURATION, ContactModel, LoopParams, WheelModes, per_step, point_tables, static_approach, steady_forces
from solvers.timeloop.kernel import run_point
from solvers.timeloop.result import InteractionResult, assemble, record
from solvers.timeloop.stop import StopRule, windows
from solvers.contact.norm import NormTable, table_pressure
from solvers.contact.spin import spin_lengths
from solvers.timeloop.reference import run_reference


@dataclass(frozen=True)
class RunSettings:
    """Settings of one run of ``simulate`` (SI units).

    dt [s], v [m/s] (dx = v dt must be the contact grid's dx for the reference drivers);
    gamma_y, gamma_x: creepages, a number or a per-step history (its last value is held);
    preload F_L3 [N]; duration [s] (at most 8 s, SPEC 6).  tangential 'point' | 'kalker';
    normal 'table' | 'norm' (per-step NORM); compliance 'table' | 'exact' (reference drivers only:
    [4.32]-[4.35] per step); start 'steady' | 'static'; kick [N s]: impulse on the structures
    (force kick/dt during the first step), lateral or (lateral, vertical) (default 0.01 N s
    lateral for 'steady', 0 for 'static'); slip_sign: +1 (physical) or -1 (the sign printed in
    [4.30]); final [s]: full-rate stretch; store_every: decimation of the history; stop: StopRule
    or None (run the full duration); xi3_static: static approach [m] (default: the table's
    approach at the preload); eps [m/s]: slip-direction regularisation (default 0 for a curve with
    mu_RF(0) = 0, else EPS_SLIP); driver: 'auto' (numba for table + point + table compliance,
    else the Python reference loop) or 'python' (force the reference loop, for testing);
    rail_block: head length of the rail's partitioned FFT convolution (exact,
    ``solvers.timeloop.partitioned``), None for the direct sum; spin [1/m]: a number or a per-step
    history like the creepages (the point contact: as equivalent creepages, ``timeloop.kernel``;
    Kalker's TANG: in the rigid slip)."""
    dt: float
    v: float
    gamma_y: object
    gamma_x: object = 0.0
    preload: float = 65e3
    duration: float = 8.0
    tangential: str = "point"
    normal: str = "table"
    compliance: str = "table"
    start: str = "steady"
    kick: object = None
    slip_sign: float = 1.0
    final: float = 0.5
    store_every: int = 1
    stop: StopRule | None = StopRule()
    xi3_static: float | None = None
    eps: float | None = None
    driver: str = "auto"
    rail_block: int | None = DEFAULT_BLOCK
    spin: object = 0.0

    def __post_init__(self):
        if self.duration > MAX_DURATION + 1e-12:
            raise ValueError(f"duration {self.duration} s exceeds the SPEC's maximum of {MAX_DURATION} s")
        if self.tangential not in ("point", "kalker") or self.normal not in ("table", "norm") or \
                self.compliance not in ("table", "exact") or self.start not in ("steady", "static"):
            raise ValueError("tangential 'point'|'kalker', normal 'table'|'norm', compliance 'table'|'exact', "
                             "start 'steady'|'static'")
        if self.driver not in ("auto", "python"):
            raise ValueError("driver 'auto' | 'python'")


def wheel_filter(wheel: WheelModes | None, dt: float) -> ModalFilter:
    """The wheel's recursive modal filters at rest (a rigid, fixed wheel for None or no modes)."""
    if wheel is None or len(np.atleast_1d(wheel.f_r)) == 0:
        return modal_filter(dt, np.zeros(0), np.zeros(0), np.zeros(0), np.zeros((0, 2)))
    return modal_filter(dt, wheel.f_r, wheel.modal_mass, wheel.zeta, wheel.phi)


def rail_convolver(rail_kernel: np.ndarray | None, block: int | None = DEFAULT_BLOCK) -> PartitionedConvolver:
    """The rail's convolver at rest (solvers.timeloop.partitioned): exact partitioned FFT convolution with a
    direct head of ``block`` lags, or the plain direct sum with block=None (the reference)."""
    g = np.zeros((1, 2, 2)) if rail_kernel is None else np.asarray(rail_kernel, float)
    if g.ndim != 3 or g.shape[1:] != (2, 2):
        raise ValueError(f"rail kernel must have shape (n_k, 2, 2), got {g.shape}")
    return partitioned_convolver(g, block)


def loop_params(contact: ContactModel, s: RunSettings) -> tuple[LoopParams, list]:
    """The loop's parameters for settings ``s``: the per-step creepages, the static approach, the
    reference state (steady rolling or static, module notes) and the kick.  Also returns the kick
    impulse (N s, lateral and vertical) as recorded in the result's settings."""
    eps = s.eps if s.eps is not None else (0.0 if contact.mu_nodes[0] == 0.0 else EPS_SLIP)
    n_steps = int(round(s.duration / s.dt))
    gx = per_step(s.gamma_x, n_steps)
    gy = per_step(s.gamma_y, n_steps)
    spin = per_step(s.spin, n_steps)
    xi3_static = s.xi3_static if s.xi3_static is not None else static_approach(contact, s.preload)
    L = spin_length(contact, xi3_static, s.v) if np.any(spin != 0.0) else np.zeros(2)
    A0 = np.array([table_compliance(xi3_static, contact.xi3_nodes, contact.A1_nodes),
                   table_compliance(xi3_static, contact.xi3_nodes, contact.A2_nodes)])
    if s.start == "steady":
        F_ref = steady_forces(contact, s.v, gx[0] + L[0] * spin[0], gy[0] + L[1] * spin[0], s.preload, eps)
        u_ref = A0 * F_ref[:2]
        kick = DEFAULT_KICK if s.kick is None else s.kick
    else:
        F_ref = np.array([0.0, 0.0, s.preload])
        u_ref = np.zeros(2)
        kick = 0.0 if s.kick is None else s.kick
    kick = np.array([kick, 0.0] if np.ndim(kick) == 0 else kick, float).reshape(2)
    p = LoopParams(n_steps, float(s.dt), float(s.v), float(xi3_static), float(s.slip_sign), float(eps), gx, gy,
                   F_ref, u_ref, kick / s.dt, spin, L)
    return p, kick.tolist()


def spin_length(contact: ContactModel, xi3_static: float, v: float) -> np.ndarray:
    """The contact's spin lengths L (2,) [m] (``solvers.contact.spin``): its own, or from Kalker's
    linear theory on the table's pressure at the static approach."""
    if contact.spin_length is not None:
        return np.asarray(contact.spin_length, float).reshape(2)
    if contact.pressure_nodes is None or contact.dx is None or contact.dy is None:
        raise ValueError("spin needs the contact's spin_length or its pressure table (pressure_nodes, dx, dy)")

    table = NormTable(contact.xi3_nodes, contact.F3_nodes, contact.q_nodes, contact.pressure_nodes,
                      contact.pressure_nodes > 0)
    return spin_lengths(table_pressure(table, xi3_static), contact.dx, contact.dy, v, contact.E, contact.nu)


def simulate(wheel: WheelModes | None, rail_kernel: np.ndarray | None, contact: ContactModel,
             settings: RunSettings | None = None, **overrides) -> InteractionResult:
    """Run the wheel/rail interaction (notes in ``solvers.timeloop.interaction``).

    wheel: WheelModes (None: rigid fixed wheel); rail_kernel: the rail's moving Green's function
    g_mov (n_k, 2, 2) in m/N (None: rigid rail); contact: ContactModel; settings: RunSettings,
    or its fields as keywords (``overrides``, applied on top of ``settings`` when both are given;
    dt, v and gamma_y are required)."""
    s = RunSettings(**overrides) if settings is None else dataclasses.replace(settings, **overrides)
    if s.tangential == "kalker" and contact.law is None and (np.isinf(contact.s_nodes[-1])
                                                             or np.any(np.diff(contact.mu_nodes) < 0)):
        raise ValueError("Kalker's TANG needs the friction law of a falling curve (ContactModel.law); without it "
                         "it would run Coulomb friction")
    store_every = max(1, int(s.store_every))
    p, kick = loop_params(contact, s)
    n_final = min(p.n_steps, int(round(s.final / s.dt))) if s.final else 0
    rec = record(p.n_steps, n_final, store_every)
    win = windows(s.stop, p.n_steps, s.dt, s.final, s.preload)
    filt = wheel_filter(wheel, s.dt)
    rc = rail_convolver(rail_kernel, s.rail_block)
    info = dict(dt=s.dt, v=s.v, preload=s.preload, duration=s.duration, tangential=s.tangential, normal=s.normal,
                compliance=s.compliance, start=s.start, kick=kick, slip_sign=s.slip_sign, final=s.final,
                store_every=store_every, eps=p.eps, spin_length=p.spin_length.tolist())
    t0 = time.perf_counter()
    if s.tangential == "point" and s.normal == "table" and s.compliance == "table" and s.driver == "auto":
        done, reason = run_point(filt, rc, p, point_tables(contact), rec, win)
    else:
        done, reason, F_ref = run_reference(filt, rc, p, contact, rec, win, tangential=s.tangential,
                                            normal=s.normal, compliance=s.compliance, start=s.start)
        p = p._replace(F_ref=F_ref)
    wall = time.perf_counter() - t0
    return assemble(rec, win, done, reason, p, wall, info)
