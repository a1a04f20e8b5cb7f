"""Driver of the two-point time loop (``solvers.timeloop.two_point``): the second point's data,
the static state of two patches under one wheel load, and the run.

Static state.  A rigid vertical approach d of the wheel toward the rail gives patch k the normal
approach (d - e_k) cos(delta_k): e_k is the patch's extra rigid separation (vertical; e_a = 0 at
the first contact, e_b the contact stage's ``second_zone``), delta_k its contact angle (0 when the
forces are in the track's directions, ``[contact] angle = "none"``).  The vertical load Q is
carried by the normal forces, Q = sum_k N_k cos(delta_k) (frictionless static contact, as for one
point: ``solvers.contact.frame``); d by bisection.  When the second patch is not reached at the
one-point approach, the state is the one-point loop's exactly.

The patches are independent half-space contacts (each its own NORM table and compliance): the
elastic interaction of the two patches through the half-space is left out -- small when the
patches lie far apart against their size (tread and flange: 20-40 mm against a few mm), not
for two tread zones that nearly merge (docs/validation/34_two_points.md states the limits).
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from solvers.contact.norm import table_force
from solvers.timeloop.mimo_partitioned import mimo_convolver
from solvers.timeloop.partitioned import DEFAULT_BLOCK
from solvers.timeloop.driver import RunSettings, loop_params
from solvers.timeloop.inputs import ContactModel, WheelModes, point_tables, static_approach
from solvers.timeloop.result import InteractionResult, assemble, record, squeal_measures
from solvers.timeloop.stop import windows
from solvers.timeloop.two_point import two_point_filter, run_two_points


@dataclass(frozen=True)
class SecondPoint:
    """The second contact point of a run: contact (ContactModel: its own NORM table, compliance,
    friction curve); phi (M, 2): the wheel's modal shapes there (in its contact frame);
    separation [m]: extra rigid (vertical) separation of its zone; gamma_x, gamma_y: its creepages
    (None: the first point's); cos_a, cos_b: cosines of the first and second point's contact
    angles (1: forces in the track's directions)."""
    contact: ContactModel
    phi: np.ndarray
    separation: float
    gamma_x: object = None
    gamma_y: object = None
    cos_a: float = 1.0
    cos_b: float = 1.0


@dataclass
class TwoPointResult:
    """Records of both points (``a``: the first, as the one-point loop's; ``b``: the second) and
    the static state: normal forces N (2,) [N], approaches xi3 (2,) [m]; wall [s]."""
    a: InteractionResult
    b: InteractionResult
    N_static: np.ndarray
    xi3_static: np.ndarray
    wall: float

    def measures(self, final: float | None = None) -> dict:
        """Squeal measures of the summed lateral force F2a + F2b over the final stretch (SPEC 6;
        the sum of the two patches' forces on the rail, in the track's directions for angle
        "none"), and each point's share."""
        F2 = self.a.F_final[:, 1] + self.b.F_final[:, 1]
        h = self.a.dt_final or self.a.dt
        if final is not None:
            F2 = F2[-max(1, int(round(final / h))):]
        out = squeal_measures(F2, h)
        out.update(L_F2_a=self.a.measures(final)["L_F2"], L_F2_b=self.b.measures(final)["L_F2"],
                   F3b_mean=float(self.b.F_final[:, 2].mean()), stop_reason=self.a.stop_reason,
                   contact_loss_share_b=float(np.mean(self.b.state_final == 0)))
        return out


def static_state(ca: ContactModel, cb: ContactModel, preload: float, separation: float, cos_a: float = 1.0,
                 cos_b: float = 1.0) -> tuple[float, float, float, float]:
    """(xi3_a, xi3_b, N_a, N_b): static approaches [m] and normal forces [N] of the two patches under
    the vertical load ``preload`` (module notes)."""
    Na1 = preload / cos_a
    xa = static_approach(ca, Na1)
    d0 = xa / cos_a
    if table_force((d0 - separation) * cos_b, cb.xi3_nodes, cb.q_nodes) <= 0.0:
        return xa, (d0 - separation) * cos_b, Na1, 0.0         # the second patch is not reached

    def vertical_load(d):
        return (table_force(d * cos_a, ca.xi3_nodes, ca.q_nodes) * cos_a
                + table_force((d - separation) * cos_b, cb.xi3_nodes, cb.q_nodes) * cos_b)

    lo, hi = 0.0, d0                      # vertical_load(0) < preload <= vertical_load(d0): a alone carries it at d0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if vertical_load(mid) < preload:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-16 * abs(hi):
            break
    d = 0.5 * (lo + hi)
    xa, xb = d * cos_a, (d - separation) * cos_b
    return xa, xb, table_force(xa, ca.xi3_nodes, ca.q_nodes), table_force(xb, cb.xi3_nodes, cb.q_nodes)


def simulate_two(wheel: WheelModes | None, rail_blocks, contact: ContactModel, second: SecondPoint,
                 settings: RunSettings | None = None, **overrides) -> TwoPointResult:
    """Run the two-point wheel/rail interaction (``solvers.timeloop.two_point``).

    wheel: the modes with their shapes at the first point (None: rigid fixed wheel);
    rail_blocks: (g_aa, g_ab, g_ba, g_bb), each (n_k, 2, 2) m/N or None (rigid); the moving
    kernel's blocks, g_pq the response at p to a force at q; contact: the first point's
    ContactModel; second: SecondPoint; settings as ``simulate`` (point model, tables only; the
    preload is the vertical wheel load; the kick acts at the first point)."""
    s = RunSettings(**overrides) if settings is None else dataclasses.replace(settings, **overrides)
    if s.tangential != "point" or s.normal != "table" or s.compliance != "table":
        raise ValueError("the two-point loop has the point model with NORM and compliance tables only")
    cb = second.contact
    xa, xb, Na, Nb = static_state(contact, cb, s.preload, second.separation, second.cos_a, second.cos_b)
    pa, kick = loop_params(contact, dataclasses.replace(s, preload=Na, xi3_static=xa))
    gx_b = s.gamma_x if second.gamma_x is None else second.gamma_x
    gy_b = s.gamma_y if second.gamma_y is None else second.gamma_y
    pb, _ = loop_params(cb, dataclasses.replace(s, preload=Nb, xi3_static=xb, gamma_x=gx_b, gamma_y=gy_b,
                                                kick=0.0, eps=None))
    store_every = max(1, int(s.store_every))
    n_final = min(pa.n_steps, int(round(s.final / s.dt))) if s.final else 0
    rec_a = record(pa.n_steps, n_final, store_every)
    rec_b = record(pa.n_steps, n_final, store_every)
    win = windows(s.stop, pa.n_steps, s.dt, s.final, s.preload)
    if wheel is None or len(np.atleast_1d(wheel.f_r)) == 0:
        filt = two_point_filter(s.dt, np.zeros(0), np.zeros(0), np.zeros(0), np.zeros((0, 2)), np.zeros((0, 2)))
    else:
        filt = two_point_filter(s.dt, wheel.f_r, wheel.modal_mass, wheel.zeta, wheel.phi, second.phi)
    blocks = tuple(rail_blocks) if rail_blocks is not None else (None,) * 4
    block = s.rail_block if s.rail_block is not None else DEFAULT_BLOCK
    cross = [(o, i, g) for (o, i), g in zip(((0, 0), (0, 1), (1, 0), (1, 1)), blocks) if g is not None]
    if s.rail_block is None:                   # the direct sum: one head over the whole kernel
        block = 1 << max(1, int(np.ceil(np.log2(max([len(g) for _, _, g in cross], default=2)))))
    r_x = mimo_convolver(cross, block, gather=blocks[0] is not None)   # g_aa: the one-point loop's sums
    info = dict(dt=s.dt, v=s.v, preload=s.preload, duration=s.duration, start=s.start, kick=kick,
                slip_sign=s.slip_sign, final=s.final, store_every=store_every, eps=pa.eps, points=2)
    t0 = time.perf_counter()
    done, reason = run_two_points(filt, r_x, pa, pb, point_tables(contact), point_tables(cb), rec_a, rec_b, win)
    wall = time.perf_counter() - t0
    a = assemble(rec_a, win, done, reason, pa, wall, info)
    b = assemble(rec_b, win, done, reason, pb, wall, dict(info, eps=pb.eps))
    return TwoPointResult(a, b, np.array([Na, Nb]), np.array([xa, xb]), wall)
