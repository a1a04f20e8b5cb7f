"""The two-point loop's and screen's reductions to one point, and the contact plane's projection (issue 26):
the runs whose numbers tests/interaction/test_two_point.py, tests/stability/test_two_point_screen.py and
tests/greens/test_contact_angle.py assert and the two-points writer reports.

* a second point carrying no load (its zone never reached): the first point's records and the screen's
  roots are the one-point loop's;
* two identical patches at the same place are one patch of twice the normal stiffness (``doubled``);
* the projected Kropp kernel of the C20 against the receptance of the modal sum with the shapes taken
  along the tilted directions e2', e3' (``tilted_directions``: each shape dotted with the unit vectors,
  not through ``solvers.contact.frame.rotation``)."""
from __future__ import annotations

import math

import numpy as np

from solvers.constants import F_MAX_HZ

from solvers.contact.frame import project_receptance
from solvers.greens.kernels import green_from_receptance
from solvers.stability.screen import characteristic, linearise, wheel_roots
from solvers.stability.two_point import linearise_two, wheel_roots as wheel_roots_two
from solvers.timeloop.interaction import simulate
from solvers.timeloop.two_point_driver import SecondPoint, simulate_two
from solvers.wheel.modal_filter import modal_filter
from solvers.wheel.receptance import wheel_receptance

from pipeline.validation.references.greens import kernel_spectrum
from pipeline.validation.references.interaction import DT, GAMMA_Y, PRELOAD, V, beam_kernel, c20_modes, hertz_contact

DURATION = 0.3
ANGLE = math.radians(-21.0)      # a gauge-corner-like contact angle (tread contacts: a few degrees)


def structures():
    """The C20 modes at y^W = -32 mm and the analytic beam rail's kernel (1024 lags)."""
    wheel, _ = c20_modes()
    return wheel, beam_kernel(DT, V, n_lags=1024, n_t=4096)


def doubled(c):
    """The contact of two identical coincident patches as one: F3 doubled (q = F3^(2/3) times
    2^(2/3)), A_tau halved."""
    return c._replace(q_nodes=c.q_nodes * 2.0 ** (2.0 / 3.0), A1_nodes=0.5 * c.A1_nodes, A2_nodes=0.5 * c.A2_nodes,
                      F3_nodes=None if c.F3_nodes is None else 2.0 * c.F3_nodes)


def rel(a, b):
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def _kw():
    return dict(dt=DT, v=V, gamma_y=GAMMA_Y, duration=DURATION, stop=None, preload=PRELOAD)


def loop_unloaded_second_point(wheel, g):
    """(one-point run, two-point run) with a second patch that is never reached (1 mm above the first,
    its own tables, shapes, creepage and rail blocks non-zero)."""
    ca = hertz_contact(0.35)
    cb = hertz_contact(0.3, F_L=40e3)
    phi_b = np.ascontiguousarray(wheel.phi[:, ::-1] * 1.3)
    one = simulate(wheel, g, ca, **_kw())
    two = simulate_two(wheel, (g, 0.6 * g, 0.6 * g, 1.2 * g), ca,
                       SecondPoint(cb, phi_b, separation=1e-3, gamma_x=-0.02), **_kw())
    return one, two


def loop_identical_patches(wheel, g):
    """(one-point run with the doubled contact, two-point run with two identical coincident patches)."""
    c = hertz_contact(0.35)
    one = simulate(wheel, g, doubled(c), **_kw())
    two = simulate_two(wheel, (g, g, g, g), c, SecondPoint(c, wheel.phi, separation=0.0), **_kw())
    return one, two


def by_mode(roots):
    return {r.mode: complex(r.sigma, 2 * np.pi * r.f_hz) for r in roots}


def _linearised(wheel, g, c):
    return linearise(wheel, g, c, dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD)


def screen_unloaded_second_point(wheel, g):
    """(one-point linear model, its roots by mode, the two-point screen's roots by mode)."""
    ca, cb = hertz_contact(0.35), hertz_contact(0.3, F_L=40e3)
    lm1 = _linearised(wheel, g, ca)
    lm2 = linearise_two(wheel, (g, 0.6 * g, 0.6 * g, 1.2 * g), ca,
                        SecondPoint(cb, np.ascontiguousarray(wheel.phi[:, ::-1]), separation=1e-3),
                        dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD)
    return lm1, by_mode(wheel_roots(lm1)), by_mode(wheel_roots_two(lm2))


def screen_identical_patches(wheel, g):
    """(the doubled contact's linear model, its roots, the two identical patches' roots)."""
    c = hertz_contact(0.35)
    lm1 = _linearised(wheel, g, doubled(c))
    lm2 = linearise_two(wheel, (g, g, g, g), c, SecondPoint(c, wheel.phi, separation=0.0), dt=DT, v=V,
                        gamma_y=GAMMA_Y, preload=PRELOAD)
    return lm1, by_mode(wheel_roots(lm1)), by_mode(wheel_roots_two(lm2))


def compare_roots(one_model, one, two):
    """(roots continuing the same mode, their max relative difference, the other two-point roots that are
    neither a root of the one-point characteristic -- |D(s)| < 1e-6 |D| 0.1 % away -- nor the open-loop pole of
    a mode the contact does not move: should be empty)."""
    common = [r for r in sorted(set(one) & set(two)) if abs(two[r] - one[r]) <= 1e-6 * abs(one[r])]
    err = max(abs(two[r] - one[r]) / abs(one[r]) for r in common)
    poles = np.log(modal_filter(one_model.dt, one_model.f_r, one_model.modal_mass, one_model.zeta, one_model.phi).z)
    poles /= one_model.dt
    stray = []
    for r, s in two.items():
        if abs(s - poles[r]) <= 1e-9 * abs(s):
            continue                                  # a mode the contact does not move (shape ~0 there)
        d0 = abs(characteristic(one_model, s))
        d1 = abs(characteristic(one_model, s + 1e-3 * abs(s)))
        if not d0 < 1e-6 * d1:
            stray.append((r, s, d0, d1))
    return common, err, stray


def tilted_directions(angle):
    """e2' (lateral tangent) and e3' (normal) in SPEC directions (2, 3-down), from the geometry of
    a surface rising toward the field side with slope tan(angle): upward normal (-sin, -cos) in
    (2, 3-down), so the normal into the rail is (sin, cos); the tangent toward the field side is
    (cos, -sin) (up is -3)."""
    return np.array([math.cos(angle), -math.sin(angle)]), np.array([math.sin(angle), math.cos(angle)])


def projected_kernel(w, n_t, f, angle=ANGLE):
    """The C20 (``w``: references.greens.wheel_case) band-limited kernel projected on the plane tilted by
    ``angle``, against the receptance along the tilted directions: dict of G (untilted), Gt (tilted
    reference), Gd (the projected kernel's DFT), phi_t (the tilted shapes), band (5 Hz - 6.5 kHz), err (the
    Frobenius-norm error per frequency in the band) and err0 (the unprojected kernel's)."""
    G = wheel_receptance(f, w["f_hz"], w["modal_mass"], w["n"], w["phi"], w["zeta"])
    g = green_from_receptance(G, DT, n_t, band_limit=F_MAX_HZ)
    e2, e3 = tilted_directions(angle)
    phi_t = np.column_stack([w["phi"] @ e2, w["phi"] @ e3])         # shapes along the tilted directions
    Gt = wheel_receptance(f, w["f_hz"], w["modal_mass"], w["n"], phi_t, w["zeta"])
    Gd = kernel_spectrum(project_receptance(g, angle), n_t)
    band = (f >= 5.0) & (f <= F_MAX_HZ)
    err = np.linalg.norm(Gd[band] - Gt[band], axis=(1, 2)) / np.linalg.norm(Gt[band], axis=(1, 2))
    err0 = (np.linalg.norm(kernel_spectrum(g, n_t)[band] - G[band], axis=(1, 2))
            / np.linalg.norm(G[band], axis=(1, 2)))
    return dict(G=G, Gt=Gt, Gd=Gd, phi_t=phi_t, band=band, err=err, err0=err0)
