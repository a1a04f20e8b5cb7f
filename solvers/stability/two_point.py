"""Stability screen of the two-point time loop (issue 26): ``solvers.stability.screen`` for two contact
patches, the loop of ``solvers.timeloop.two_point`` linearised about steady rolling.

Structures: xi = Y(z) dF with the 4 x 4 receptance of both points (directions 2, 3 at a, then at
b): the wheel's modal filters with inputs and outputs at both points (exact transform of the
recursive filters, one pole pair per mode) plus the z-transform of the rail's four kernel blocks.

Contact, per loaded point k (``kernel._point_contact`` about the rigid slip w = (gamma_x, gamma_y) v,
sigma0 = |w|, e = w / sigma0, F_tau = -F3 mu_RF(sigma) s_tau / sigma):

    dF_tau = -m0 e_tau dF3 - F3 C ds,   C = m' e e^T + (m0 / sigma0) (I - e e^T)
    ds1 = c (A1 dF1 + F1 A1' dF3 / k_c),   ds2 = c (A2 dF2 + F2 A2' dF3 / k_c + dxi2),  c = (1 - z^-1) / dt
    dF3 = -k_c dxi3

(m0, m' = mu_RF and its slope at sigma0; A' = dA/d approach; the compliance follows the
approach as in the loop).  With gamma_x = 0 the longitudinal rows decouple and each point's
2 x 2 block is ``solvers.stability.screen``'s M; an unloaded point contributes identity rows, so the
screen of a two-point model whose second point carries no load is the one-point screen
(tests/stability/test_two_point_screen.py).  D(z) = det M (6 x 6: dF1, dF2, dF3 per point).

Roots: the closed-loop pole continuing each lightly damped wheel mode (zeta < 0.5), by the secant
method on the exact pp(z) D(z) (pp: the mode's pole pair, which makes it regular there: the
mode's term in Y has rank one), started at the open-loop pole.  The low-frequency roots of the
wheelset on the track are not sought here (``solvers.stability.screen.track_roots`` for one point).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from solvers.stability.screen import Root, _modal_terms, _secant


class PointLinear(NamedTuple):
    """One contact point's linearisation: normal stiffness kc (N/m), normal force F3 (N), friction
    m0 = mu_RF(sigma0), dm = its slope (s/m), sigma0 (m/s), e (2,) slip direction, compliances A1, A2
    (m/N) and their approach derivatives dA1, dA2 (1/N); steady F1, F2 (N)."""
    kc: float
    F3: float
    m0: float
    dm: float
    sigma0: float
    e: np.ndarray
    A1: float
    A2: float
    dA1: float
    dA2: float
    F1: float
    F2: float


class TwoPointLinear(NamedTuple):
    """The linearised two-point loop: filt (TwoPointFilter), blocks (g_aa, g_ab, g_ba, g_bb),
    dt (s), points (PointLinear of a and b), zeta (M,) of the wheel modes."""
    filt: object
    blocks: tuple
    dt: float
    points: tuple
    zeta: np.ndarray


def linearise_two(wheel, rail_blocks, contact, second, *, dt: float, v: float, gamma_y: float,
                  gamma_x: float = 0.0, preload: float) -> TwoPointLinear:
    """The TwoPointLinear of ``simulate_two``'s steady rolling state (same arguments: wheel
    WheelModes at the first point, rail_blocks (g_aa, g_ab, g_ba, g_bb), contact the first
    point's ContactModel, second a ``two_point_driver.SecondPoint``; preload the vertical load)."""
    from solvers.timeloop.two_point import two_point_filter  # lazy: brings in rocket_fft, scipy
    from solvers.timeloop.two_point_driver import static_state  # lazy: brings in rocket_fft, scipy

    xa, xb, Na, Nb = static_state(contact, second.contact, preload, second.separation, second.cos_a, second.cos_b)
    gxb = gamma_x if second.gamma_x is None else float(second.gamma_x)
    gyb = gamma_y if second.gamma_y is None else float(second.gamma_y)
    pa = point_linear(contact, xa, Na, gamma_x, gamma_y, v)
    pb = point_linear(second.contact, xb, Nb, gxb, gyb, v)
    filt = two_point_filter(dt, wheel.f_r, wheel.modal_mass, wheel.zeta, wheel.phi, second.phi)
    blocks = tuple(np.zeros((2, 2, 2)) if g is None else np.asarray(g, float) for g in rail_blocks)
    return TwoPointLinear(filt, blocks, float(dt), (pa, pb), np.asarray(wheel.zeta, float))


def point_linear(contact, app: float, F3: float, gx: float, gy: float, v: float) -> PointLinear:
    """PointLinear of a ContactModel at approach ``app`` with normal force F3 and creepages."""
    from solvers.contact.compliance import table_compliance  # lazy: brings in scipy
    from solvers.contact.friction import mu_and_slope  # lazy: brings in rocket_fft, scipy
    from solvers.contact.norm import table_force  # lazy: brings in scipy

    if F3 <= 0.0:
        return PointLinear(0.0, 0.0, 0.0, 0.0, 1.0, np.zeros(2), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    h = 1e-6 * app
    xs = contact.xi3_nodes
    kc = (table_force(app + h, xs, contact.q_nodes) - table_force(app - h, xs, contact.q_nodes)) / (2 * h)
    A = [table_compliance(app, xs, n) for n in (contact.A1_nodes, contact.A2_nodes)]
    dA = [(table_compliance(app + h, xs, n) - table_compliance(app - h, xs, n)) / (2 * h)
          for n in (contact.A1_nodes, contact.A2_nodes)]
    w = np.array([gx * v, gy * v])
    sig = float(np.hypot(*w))
    if sig == 0.0:
        raise ValueError("the screen linearises about a rolling state with slip (gamma != 0)")
    m0, dm = mu_and_slope(sig, contact.s_nodes, contact.mu_nodes, contact.slopes)
    e = w / sig
    F = -F3 * m0 * e
    return PointLinear(float(kc), float(F3), float(m0), float(dm), sig, e, float(A[0]), float(A[1]), float(dA[0]),
                       float(dA[1]), float(F[0]), float(F[1]))


def structure_z(model: TwoPointLinear, z: complex) -> np.ndarray:
    """Y(z) (4, 4): wheel (modal filters at both points) + rail (the four blocks)."""
    f = model.filt
    h = _modal_terms(f, z)[0]
    Y = np.einsum("r,ri,rj->ij", h, f.w_out, f.w_in)
    for n, (p, q) in enumerate(((0, 0), (0, 1), (1, 0), (1, 1))):
        g = model.blocks[n]
        w = np.exp(-np.log(complex(z)) * np.arange(1, g.shape[0]))
        Y[2 * p:2 * p + 2, 2 * q:2 * q + 2] += (w @ g[1:].reshape(-1, 4)).reshape(2, 2)
    return Y


def system_matrix(model: TwoPointLinear, z: complex, Y: np.ndarray) -> np.ndarray:
    """M(z) (6, 6) on (dF1, dF2, dF3) of a then b (module notes)."""
    c = (1.0 - 1.0 / z) / model.dt
    Yx = np.zeros((4, 6), complex)                     # xi (2a, 3a, 2b, 3b) from X
    for q in range(2):
        Yx[:, 3 * q + 1] = Y[:, 2 * q]
        Yx[:, 3 * q + 2] = Y[:, 2 * q + 1]
    M = np.eye(6, dtype=complex)
    for k, p in enumerate(model.points):
        o = 3 * k
        if p.F3 <= 0.0:
            continue                                   # unloaded: dF = 0 (identity rows)
        ds1 = np.zeros(6, complex)
        ds1[o] = c * p.A1
        ds1[o + 2] = c * p.F1 * p.dA1 / p.kc
        ds2 = c * Yx[2 * k]
        ds2[o + 1] += c * p.A2
        ds2[o + 2] += c * p.F2 * p.dA2 / p.kc
        ee = np.outer(p.e, p.e)
        C = p.dm * ee + (p.m0 / p.sigma0) * (np.eye(2) - ee)
        for t in range(2):
            M[o + t] += p.F3 * (C[t, 0] * ds1 + C[t, 1] * ds2)
            M[o + t, o + 2] += p.m0 * p.e[t]
        M[o + 2] += p.kc * Yx[2 * k + 1]
    return M


def characteristic(model: TwoPointLinear, s: complex) -> complex:
    z = np.exp(s * model.dt)
    return complex(np.linalg.det(system_matrix(model, z, structure_z(model, z))))


def wheel_roots(model: TwoPointLinear, zeta_max: float = 0.5) -> list[Root]:
    """The closed-loop pole continuing each lightly damped wheel mode, fastest growing first."""
    f = model.filt
    out = []
    dt = model.dt
    for r in np.flatnonzero(model.zeta < zeta_max):
        zr = f.z[r]
        s0 = np.log(zr) / dt

        def fun(s, zr=zr):
            z = np.exp(s * dt)
            pp = (z - zr) * (z - np.conj(zr))
            return pp * complex(np.linalg.det(system_matrix(model, z, structure_z(model, z))))
        s = _secant(fun, complex(s0) + complex(1e-3, 1e-3))
        if s is not None and abs(s.imag - s0.imag) < 0.2 * abs(s0.imag) + 2 * np.pi * 5:
            out.append(Root(s.imag / (2 * np.pi), s.real, int(r)))
    return sorted(out, key=lambda q: -q.sigma)
